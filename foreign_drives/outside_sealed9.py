"""Outside mechanisms, ninth SEALED half (issue 31 part 4, set 9).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed9``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first eight sets
nor the ninth development half (:mod:`outside_dev9`) has, and the suite's rows (seeds 9100+). The split rule is in
:mod:`outside_dev9` (written as one list of fourteen; the even numbers are here; 4, 10, 14 with a memory, 2, 6, 8, 12
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed9")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed TIMES the spring extension: a magnetic-particle brake on the motor's shaft end
   is a tension control: its excitation comes from a potentiometer on the spring's bracket, so it brakes with
   c*z*Omega1 (a viscous load whose coefficient is the spring's extension: a bilinear law of two states);
4. wheel torque x a ONE-SHOT fired by the wheel angle: a cam switch at the wheel angle phi fires a timer that applies
   a solenoid brake for a fixed time W after each pass: -T while less than W seconds since the latest pass of phi
   (scanned every 0.2 ms; a brake window fixed in time, so its angular extent grows with the speed);
6. clutch torque x the jaw's angle difference beyond an INNER DEAD ZONE: rubber bumpers inside the jaw's gap touch at
   |D| = d0 < beta, before the metal faces: k_r*sign(D)*max(0, |D| - d0) from the motor to the wheel, in the gap and
   in contact (a soft stop that engages before the contact: a second, earlier, softer contact);
8. mass force x the WHEEL SPEED squared: a blower on the wheel shaft blows on a sail on the carriage: F = c*Omega2^2
   along x (a cross-balance power law: the mass pushed by the other shaft's speed);
10. a1 sensor x a1's own past through a MOUNTING RESONANCE: a1 is glued on a plastic bracket that rings: y is a
    second-order low-pass of a with natural frequency f_n and damping ratio zeta ~ 0.05 (a peak of gain ~1/(2*zeta)
    at f_n: not a well-damped anti-alias filter);
12. motor load moment x the motor angle through a RECTANGULAR WINDOW: a rotary distributor valve on the motor's shaft
    end feeds a cylinder during n windows of each turn: +T while (alpha1 - phi) mod (2*pi/n) < d*2*pi/n, else 0 (a
    square wave of the motor angle, all odd and even harmonics at once);
14. wheel torque x the wheel speed through a PEAK DETECTOR with decay: a drag-cup overspeed governor on the wheel shaft
    whose flyweights are held out by a ratchet that a dashpot lets go slowly: it brakes with -K*max(0, m - Omega_0),
    m the wheel speed's peak, decaying with time constant tau (a brake set by the recent maximum speed).

Visibility, measured as for the development half (4 s, same spec without the mechanism, same seed; criterion a2 >=
0.05 m/s^2, a1 >= 0.25): 2 a2 0.0086, scaled once x8.72 -> 0.0943; 4 a2 0.0915; 6 a2 0.101; 8 a2 0.163; 10 a1 20.2;
12 a2 0.0054, scaled once x13.9 -> 0.0644; 14 a2 0.144.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import bilinear, lfilter, lfilter_zi

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory
from .outside_dev9 import _PHASE


# 2. motor load moment x the motor speed times the spring extension
class MotorTensionParticleBrake(OutsideForm):
    name = "motor_tension_particle_brake"
    half = "sealed9"
    balance = "motor_load_moment"
    depends_on = ("motor_speed", "spring_extension")
    description = ("a magnetic-particle brake on the motor's shaft end excited from a potentiometer on the spring's "
                   "bracket (a tension control): a load c*z*Omega1, z the spring's extension")
    parameters = (Param("coefficient_Nm_s_per_rad_m", "N*m*s/(rad*m)", (0.0, 10.0), "c"),)
    note = "a viscous load whose coefficient is the spring's extension: a bilinear law of two states"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["coefficient_Nm_s_per_rad_m"],
                 (K.XS_OMEGA1, K.XF_X, 0.0, 0.0, 0.0), (K.XS_SPRING_EXTENSION, K.XF_X, 0.0, 0.0, 0.0))

    @staticmethod
    def torque(omega1, z, p):
        return p["coefficient_Nm_s_per_rad_m"] * np.asarray(z) * np.asarray(omega1)

    def law(self, p):
        return f"motor load moment += {p['coefficient_Nm_s_per_rad_m']:.6g} N*m*s/(rad*m) * z * Omega1"


# 4. wheel torque x a one-shot fired by the wheel angle
class WheelCamTimedBrake(OutsideForm):
    name = "wheel_cam_timed_brake"
    half = "sealed9"
    balance = "wheel_torque"
    depends_on = ("wheel_angle",)
    description = ("a cam switch at the wheel angle phi fires a timer that applies a solenoid brake for W seconds after "
                   "each pass: -T while less than W since the latest pass of phi (the wheel angle in [0, 2*pi) rising "
                   "through phi; scanned every 0.2 ms)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("hold_s", "s", (2e-4, 1.0), "W"),
                  Param("trigger_angle_rad", "rad", (0.01, 6.27), "phi"))
    note = "a brake window fixed in time after an angle event: its angular extent grows with the speed"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_ONESHOT, K.XS_ALPHA2, p["trigger_angle_rad"], p["hold_s"])
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m for {p['hold_s']:.6g} s after each pass of the wheel angle "
                f"{p['trigger_angle_rad']:.6g} rad (scanned every 0.2 ms)")


# 6. clutch torque x the jaw's angle difference beyond an inner dead zone
class ClutchGapBumpers(OutsideForm):
    name = "clutch_gap_bumpers"
    half = "sealed9"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("rubber bumpers inside the jaw's gap touch at |D| = d0, before the metal faces: k_r*sign(D)*max(0, "
                   "|D| - d0) from the motor to the wheel, D the jaw's angle difference, in the gap and in contact")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 3000.0), "k_r"),
                  Param("touch_angle_rad", "rad", (0.0, 0.1), "d0"))
    note = "a soft stop that engages before the contact: a second, earlier, softer contact"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["stiffness_Nm_per_rad"],
                 (K.XS_JAW_ANGLE, K.XF_DEADZONE, p["touch_angle_rad"], 0.0, 0.0))

    @staticmethod
    def torque(d, p):
        d = np.asarray(d, dtype=np.float64)
        return p["stiffness_Nm_per_rad"] * np.sign(d) * np.maximum(0.0, np.abs(d) - p["touch_angle_rad"])

    def law(self, p):
        return (f"clutch torque += {p['stiffness_Nm_per_rad']:.6g} N*m/rad * sign(D)*max(0, |D| - "
                f"{p['touch_angle_rad']:.6g} rad)")


# 8. mass force x the wheel speed squared
class MassWheelBlowerSail(OutsideForm):
    name = "mass_wheel_blower_sail"
    half = "sealed9"
    balance = "mass_force"
    depends_on = ("wheel_speed",)
    description = "a blower on the wheel shaft blows on a sail on the carriage: a force c*Omega2^2 along x"
    parameters = (Param("coefficient_N_s2_per_rad2", "N*s^2/rad^2", (0.0, 0.1), "c"),)
    note = "a cross-balance power law: the mass pushed by the other shaft's speed"

    def apply(self, b, p):
        add_term(b, "mass_force", p["coefficient_N_s2_per_rad2"], (K.XS_OMEGA2, K.XF_POWER, 2.0, 0.0, 0.0))

    def law(self, p):
        return f"mass force += {p['coefficient_N_s2_per_rad2']:.6g} N*s^2/rad^2 * Omega2^2"


# 10. a1 sensor x a1's own past through a mounting resonance
class A1BracketResonance(OutsideForm):
    name = "a1_bracket_resonance"
    half = "sealed9"
    stage = "sensor"
    order = 0                      # the sensing element's mount
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1 is glued on a plastic bracket that rings: y = a second-order low-pass of a, w_n^2/(s^2 + "
                   "2*zeta*w_n*s + w_n^2), w_n = 2*pi*f_n (bilinear, at rest at the pre-roll's first value)")
    parameters = (Param("natural_frequency_hz", "Hz", (10.0, 20_000.0), "f_n"),
                  Param("damping_ratio", "-", (0.005, 1.0), "zeta"))
    note = "a lightly damped resonance: a peak of gain ~1/(2*zeta) at f_n, not a well-damped anti-alias filter"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p, fs)

    @staticmethod
    def read(a, p, fs):
        wn = 2.0 * math.pi * p["natural_frequency_hz"]
        bz, az = bilinear([wn * wn], [1.0, 2.0 * p["damping_ratio"] * wn, wn * wn], fs=fs)
        a = np.asarray(a, dtype=np.float64)
        y, _ = lfilter(bz, az, a, zi=lfilter_zi(bz, az) * a[0])
        return y

    def law(self, p):
        return (f"a1 sensor = a second-order low-pass of a1 at {p['natural_frequency_hz']:.6g} Hz, damping ratio "
                f"{p['damping_ratio']:.6g}")


# 12. motor load moment x the motor angle through a rectangular window
class MotorRotaryDistributorValve(OutsideForm):
    name = "motor_rotary_distributor_valve"
    half = "sealed9"
    balance = "motor_load_moment"
    depends_on = ("motor_angle",)
    description = ("a rotary distributor valve on the motor's shaft end feeds a cylinder during n windows of each turn: "
                   "+T while (alpha1 - phi) mod (2*pi/n) < d*2*pi/n, else 0")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("ports", "per revolution", (1, 8), "n", "int"),
                  Param("duty", "-", (0.01, 0.99), "d"), _PHASE)
    note = "a square wave of the motor angle: odd and even harmonics at once"

    def apply(self, b, p):
        period = 2.0 * math.pi / p["ports"]
        add_term(b, "motor_load_moment", p["torque_Nm"],
                 (K.XS_ALPHA1, K.XF_PERIODIC_GATE, period, p["phase_rad"], p["duty"] * period), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m while (alpha1 - {p['phase_rad']:.6g} rad) mod "
                f"(2*pi/{p['ports']:g}) < {p['duty']:.6g}*2*pi/{p['ports']:g}, else 0")


# 14. wheel torque x the wheel speed through a peak detector with decay
class WheelDragCupGovernor(OutsideForm):
    name = "wheel_drag_cup_governor"
    half = "sealed9"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a drag-cup overspeed governor whose flyweights a ratchet holds out and a dashpot lets go: it brakes "
                   "with -K*max(0, m - Omega_0), m -> max(Omega2, m*exp(-dt/tau)) every 0.2 ms (m = Omega2 at the "
                   "run-in's start)")
    parameters = (Param("gain_Nm_s_per_rad", "N*m*s/rad", (0.0, 50.0), "K"),
                  Param("set_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_0"),
                  Param("release_time_s", "s", (1e-3, 100.0), "tau"))
    note = "a brake set by the recent maximum of the speed (a peak detector with decay)"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PEAK, K.XS_OMEGA2, p["release_time_s"])
        add_term(b, "wheel_torque", -p["gain_Nm_s_per_rad"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["set_speed_rad_s"], 1.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['gain_Nm_s_per_rad']:.6g} N*m*s/rad * max(0, m - {p['set_speed_rad_s']:.6g} rad/s),"
                f" m -> max(Omega2, m*exp(-0.2 ms/{p['release_time_s']:.6g} s)) every 0.2 ms")


FORM_CLASSES = (MotorTensionParticleBrake, WheelCamTimedBrake, ClutchGapBumpers, MassWheelBlowerSail,
                A1BracketResonance, MotorRotaryDistributorValve, WheelDragCupGovernor)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 9100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 0.05 N*m per rad/s per m of extension a priori, a2 0.0086: scaled once x8.72
        ("os9_motor_tension_particle_brake", "outside", 0.0071, 0.0295, 0.92,
         [E("motor_tension_particle_brake", {"coefficient_Nm_s_per_rad_m": 0.436})]),
        # 4 N*m for 20 ms after each pass of 1 rad (a turn takes ~42 ms)
        ("os9_wheel_cam_timed_brake", "outside", 0.0054, 0.0235, 0.95,
         [E("wheel_cam_timed_brake", {"torque_Nm": 4.0, "hold_s": 0.02, "trigger_angle_rad": 1.0})]),
        # bumpers of 200 N*m/rad touching at 20 mrad
        ("os9_clutch_gap_bumpers", "outside", 0.0086, 0.0185, 0.90,
         [E("clutch_gap_bumpers", {"stiffness_Nm_per_rad": 200.0, "touch_angle_rad": 0.02})]),
        # 1e-3 N*s^2/rad^2: ~22 N at 150 rad/s
        ("os9_mass_wheel_blower_sail", "outside", 0.0048, 0.0385, 0.93,
         [E("mass_wheel_blower_sail", {"coefficient_N_s2_per_rad2": 1e-3})]),
        ("os9_clean_w6.3_eta0.0215_n0.91", "clean", 0.0063, 0.0215, 0.91, []),
        # a 1.5 kHz ring, damping ratio 0.05
        ("os9_a1_bracket_resonance", "outside", 0.0091, 0.0275, 0.96,
         [E("a1_bracket_resonance", {"natural_frequency_hz": 1500.0, "damping_ratio": 0.05})]),
        # over 30 % of each half turn; 3 N*m a priori, a2 0.0054: scaled once x13.9
        ("os9_motor_rotary_distributor_valve", "outside", 0.0059, 0.0225, 0.89,
         [E("motor_rotary_distributor_valve", {"torque_Nm": 41.6, "ports": 2, "duty": 0.3, "phase_rad": 0.4})]),
        # 2 N*m per rad/s of the speed's recent peak above 151 rad/s, released over 0.5 s
        ("os9_wheel_drag_cup_governor", "outside", 0.0076, 0.0345, 0.94,
         [E("wheel_drag_cup_governor", {"gain_Nm_s_per_rad": 2.0, "set_speed_rad_s": 151.0,
                                        "release_time_s": 0.5})]),
    ]
