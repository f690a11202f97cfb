"""Outside mechanisms, fifth DEVELOPMENT half (issue 31 part 4, set 5): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first four sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2`, :mod:`outside_sealed2`, :mod:`outside_dev3`, :mod:`outside_sealed3`,
:mod:`outside_dev4`, :mod:`outside_sealed4`) have, with their laws in the open. The fifth sealed half is
:mod:`outside_sealed5`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed5` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 motor load moment, 14 wheel
torque). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength
is set by one quick simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a PLAY (a rate-independent hysteresis, a backlash operator): a
   flyball governor on the motor shaft sets a brake band through a linkage with play; the linkage's position m
   follows Omega1 only once Omega1 has moved more than h away from it, m = min(max(m, Omega1 - h), Omega1 + h), and the
   band loads the motor with K*max(0, m - Omega_0);
3. wheel torque x a PRODUCT of the unwrapped wheel angle and the spring extension: the spring's cable winds onto the
   wheel's drum in layers, so its lever arm grows by dr per turn; the spring's force k*z acts on the growing arm,
   -k*z*dr*theta2/(2*pi) beside the nominal r*k*z (theta2 unwrapped from the run-in's start);
5. clutch torque x the contact law TIMES the wheel angle (an amplitude modulation of the contact): the jaw coupling's
   hub runs out on the wheel shaft, so the contact's lever arm and with it the torque a given penetration passes vary
   once per revolution, T_c*g*sin(alpha2 + phi);
7. mass force x a HIDDEN RESONATOR driven by the mass speed: a tuned vibration absorber (an auxiliary mass on a spring
   and damper) bolted to the carriage; its relative displacement d and speed obey d'' = -w_a^2*d - 2*zeta*w_a*d' -
   dv/dt, and it pushes the carriage with m_a*(w_a^2*d + 2*zeta*w_a*d') (advanced once per 0.2 ms);
9. a2 sensor x TIME and a2's own PAST (a tare): a2's data-acquisition module auto-zeroes every T_z seconds: at each
   tare it takes the mean of its input over the W seconds before as its new zero, and subtracts it until the next;
11. clutch torque x a THERMAL MEMORY of the power the contact dissipates: the jaw's elastomer insert heats with the
   power P = |T_c*D'| its impacts dissipate and cools with tau; it softens as it heats, the contact torque times
   (1 - g*theta), theta' = P - theta/tau (theta the heat held, J; advanced once per 0.2 ms);
13. a2 sensor x a2's own value through a STUCK ADC BIT: a2's I/O module digitises it with an ADC of N bits over +-R
   whose bit b is stuck at 1 (a failed line): every code has that bit set, a non-monotone, periodic error in the
   signal's amplitude.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle; the manifest has its
value at sample 0). Memory elements (the play, the resonator, the insert's heat; one per recording) are advanced once
per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"), as in the fourth set.
"""
from __future__ import annotations

import math

import numpy as np

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (on the simulator's angle)")


# 1. motor load moment x the motor speed through a play
class MotorGovernorLinkagePlay(OutsideForm):
    name = "motor_governor_linkage_play"
    half = "dev5"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a flyball governor on the motor shaft sets a brake band through a linkage with play h: the "
                   "linkage's position m (in rad/s of the speed) follows Omega1 only once Omega1 is more than h away, "
                   "m = min(max(m, Omega1 - h), Omega1 + h) (scanned every 0.2 ms), and the band loads the motor with "
                   "K*max(0, m - Omega_0)")
    parameters = (Param("gain_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "K"),
                  Param("play_rad_s", "rad/s", (0.0, 20.0), "h: the linkage's play, in speed"),
                  Param("set_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_0: where the band starts to bite"))
    note = "a rate-independent hysteresis: the load depends on the path the speed took, not on how fast it took it"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PLAY, K.XS_OMEGA1, p["play_rad_s"])
        add_term(b, "motor_load_moment", p["gain_Nms_per_rad"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["set_speed_rad_s"], 1.0, 0.0), nonperiodic=True)

    @staticmethod
    def linkage(omega1_at_segments, p):
        """m at each segment's start from Omega1 at the segments' starts (the first: m = Omega1)."""
        x = np.asarray(omega1_at_segments, dtype=np.float64).tolist()
        h, out, m = p["play_rad_s"], np.empty(len(x)), x[0]
        for i, v in enumerate(x):
            m = min(max(m, v - h), v + h)
            out[i] = m
        return out

    def law(self, p):
        return (f"motor load moment += {p['gain_Nms_per_rad']:.6g} N*m*s/rad * max(0, m - "
                f"{p['set_speed_rad_s']:.6g} rad/s), m = min(max(m, Omega1 - {p['play_rad_s']:.6g}), Omega1 + "
                f"{p['play_rad_s']:.6g}) rad/s every 0.2 ms (a play)")


# 3. wheel torque x the unwrapped wheel angle times the spring extension
class WheelRopeDrumLayers(OutsideForm):
    name = "wheel_rope_drum_layers"
    half = "dev5"
    balance = "wheel_torque"
    depends_on = ("wheel_angle", "spring_extension")
    description = ("the spring's cable winds onto the wheel's drum in layers, so its lever arm grows by dr per turn: "
                   "the spring's force k*z on the extra arm, -k*z*dr*theta2/(2*pi) beside the nominal r*k*z, theta2 "
                   "the wheel angle unwrapped from the run-in's start (2 s before sample 0; the rim's kinematics kept "
                   "at r: dr*theta2/(2*pi) << r)")
    parameters = (Param("growth_m_per_turn", "m/turn", (0.0, 0.01), "dr: the cable's thickness per layer and turn"),)
    note = "a slowly growing torque: proportional to the spring's force and to the turns since the run-in began"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -C.SPRING_STIFFNESS_N_PER_M * p["growth_m_per_turn"] / (2.0 * math.pi),
                 (K.XS_ALPHA2_UNWRAPPED, K.XF_X, 0.0, 0.0, 0.0), (K.XS_SPRING_EXTENSION, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{C.SPRING_STIFFNESS_N_PER_M:g} N/m * z * {p['growth_m_per_turn']:.6g} m * "
                "theta2/(2*pi), z the spring extension, theta2 the wheel angle unwrapped from the run-in's start "
                "(t = -2 s)")


# 5. clutch torque x the contact law times the wheel angle
class ClutchHubRunout(OutsideForm):
    name = "clutch_hub_runout"
    half = "dev5"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration", "wheel_angle")
    description = ("the jaw coupling's hub runs out on the wheel shaft: the contact's lever arm, and with it the torque "
                   "a given penetration passes, varies once per revolution: the contact law's torque T_c times "
                   "1 + g*sin(alpha2 + phi); 0 in the gap")
    parameters = (Param("gain", "-", (0.0, 0.9), "g: the run-out over the contact radius"), _PHASE)
    note = "an amplitude modulation of the contact law by the wheel angle (the sign kept: g < 1)"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["gain"], (K.XS_CONTACT_TORQUE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_ALPHA2, K.XF_SIN, 1.0, p["phase_rad"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['gain']:.6g} * T_c * sin(alpha2 + {p['phase_rad']:.6g}), T_c the contact law's "
                "torque (0 in the gap)")


# 7. mass force x a hidden resonator driven by the mass speed
class MassTunedAbsorber(OutsideForm):
    name = "mass_tuned_absorber"
    half = "dev5"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("a tuned vibration absorber (an auxiliary mass m_a on a spring and damper) bolted to the carriage: "
                   "its displacement d relative to the carriage obeys d'' = -w_a^2*d - 2*zeta*w_a*d' - dv/dt and it "
                   "pushes the carriage with m_a*(w_a^2*d + 2*zeta*w_a*d') (advanced once per 0.2 ms: dv/dt the mass "
                   "speed's change over the last 0.2 ms, four semi-implicit Euler steps; at rest at the run-in's start)")
    parameters = (Param("mass_kg", "kg", (0.0, 50.0), "m_a"),
                  Param("frequency_hz", "Hz", (1.0, 500.0), "w_a/(2*pi)"),
                  Param("damping_ratio", "-", (0.001, 1.0), "zeta"))
    note = "a hidden degree of freedom: a resonance of its own on the mass, excited by the carriage's motion"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RESONATOR, K.XS_MASS_SPEED, 2.0 * math.pi * p["frequency_hz"],
                   p["damping_ratio"])
        add_term(b, "mass_force", p["mass_kg"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['mass_kg']:.6g} kg * (w^2*d + 2*{p['damping_ratio']:.6g}*w*d'), d'' = -w^2*d - "
                f"2*{p['damping_ratio']:.6g}*w*d' - dv/dt, w = 2*pi*{p['frequency_hz']:.6g} Hz (every 0.2 ms)")


# 9. a2 sensor x time and a2's own past (a tare)
class A2DaqAutozero(OutsideForm):
    name = "a2_daq_autozero"
    half = "dev5"
    stage = "sensor"
    order = 1                      # the acquisition module, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "time")
    description = ("a2's data-acquisition module auto-zeroes every T_z seconds from t_0: at each tare t_j = t_0 + "
                   "j*T_z it takes the mean of its input over [t_j - W, t_j) as its zero and subtracts it until the "
                   "next tare (zero before the first, t in s from sample 0)")
    parameters = (Param("period_s", "s", (0.01, 100.0), "T_z"),
                  Param("window_s", "s", (1e-4, 1.0), "W"),
                  Param("first_s", "s", (0.0, 100.0), "t_0: the first tare, from sample 0"))
    note = "a piecewise-constant offset made of the signal's own past, changing at the tares only"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.tared(sig["a2"], t, p)

    @staticmethod
    def offsets(a, t, p):
        a, t = np.asarray(a, dtype=np.float64), np.asarray(t, dtype=np.float64)
        out = np.zeros(a.size)
        tj = p["first_s"]
        while tj <= t[-1]:
            win = (t >= tj - p["window_s"] - 1e-12) & (t < tj - 1e-12)
            if win.any():
                out[t >= tj - 1e-12] = a[win].mean()
            tj += p["period_s"]
        return out

    @classmethod
    def tared(cls, a, t, p):
        return np.asarray(a, dtype=np.float64) - cls.offsets(a, t, p)

    def law(self, p):
        return (f"a2 sensor -= the mean of a2 over [t_j - {p['window_s']:.6g} s, t_j) from each tare t_j = "
                f"{p['first_s']:.6g} + j*{p['period_s']:.6g} s on (0 before the first)")


# 11. clutch torque x a thermal memory of the contact's power
class ClutchInsertHeating(OutsideForm):
    name = "clutch_insert_heating"
    half = "dev5"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("the jaw's elastomer insert heats with the power P = |T_c*D'| its contact dissipates and cools with "
                   "tau; it softens as it heats: the contact law's torque T_c times 1 - g*theta, theta' = P - "
                   "theta/tau (theta the heat held [J]; P from the state at each 0.2 ms scan, theta advanced exactly "
                   "over the scan; theta = tau*P at the run-in's first scan)")
    parameters = (Param("softening_per_J", "1/J", (0.0, 0.2),
                        "g (g*theta < 1: at 0.1/J on a nominal drive g*theta <= 0.15; at 0.4/J the softening ran away)"),
                  Param("cooling_time_s", "s", (1e-3, 100.0), "tau"))
    note = "a rate-dependent memory of the impacts: the same penetration passes less torque after hard impacts"

    def apply(self, b, p):
        tau = p["cooling_time_s"]
        set_memory(b, self.name, K.MK_LAG, K.XS_CONTACT_POWER, tau, tau, 0.0)
        add_term(b, "clutch_torque", -p["softening_per_J"] * tau, (K.XS_CONTACT_TORQUE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += -{p['softening_per_J']:.6g}/J * theta * T_c, theta' = |T_c*D'| - theta / "
                f"{p['cooling_time_s']:.6g} s (T_c the contact law's torque, D' the jaw's speed difference)")


# 13. a2 sensor x a2's own value through a stuck ADC bit
class A2StuckAdcBit(OutsideForm):
    name = "a2_stuck_adc_bit"
    half = "dev5"
    stage = "sensor"
    order = 1                      # the I/O module's ADC, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's I/O module digitises it with an ADC over +-R whose bit of weight w is stuck at 1: wherever "
                   "that bit would be 0 the reading is w too high, a2 += w*(1 - (floor((a + R)/w) mod 2)) (its finer "
                   "bits below the recorder's)")
    parameters = (Param("bit_weight_m_s2", "m/s^2", (1e-6, 100.0), "w: the stuck bit's weight"),
                  Param("range_m_s2", "m/s^2", (1.0, 10000.0), "R: the ADC's half range"))
    note = "a non-monotone error periodic in the signal's amplitude (period 2*w): not a gain, an offset or a filter"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        w = p["bit_weight_m_s2"]
        return a + w * (1.0 - np.mod(np.floor((a + p["range_m_s2"]) / w), 2.0))

    def law(self, p):
        w = p["bit_weight_m_s2"]
        return f"a2 sensor += {w:.6g} * (1 - (floor((a + {p['range_m_s2']:.6g})/{w:.6g}) mod 2)) m/s^2"


FORM_CLASSES = (MotorGovernorLinkagePlay, WheelRopeDrumLayers, ClutchHubRunout, MassTunedAbsorber, A2DaqAutozero,
                ClutchInsertHeating, A2StuckAdcBit)
