"""Outside mechanisms, sixth DEVELOPMENT half (issue 31 part 4, set 6): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first five sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev5`, :mod:`outside_sealed5`) have, with their laws in
the open. The sixth sealed half is :mod:`outside_sealed6`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed6` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 motor load moment, 14 mass
force). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength
is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a STICK-SLIP coupling to a hidden inertia: a brake disc (or a fan)
   on the motor's free shaft end sits on a friction (slip) hub that has loosened; it turns with the shaft as long as
   the torque to accelerate it, J_f*dOmega1/dt, stays below the hub's slip torque T_s, and slips beyond (at the jaw's
   impacts), passing +-T_s until it has caught up: a hidden degree of freedom through a dry-friction coupling;
3. wheel torque x the wheel speed through a hidden body in a GAP (gear rattle): an unloaded idler gear (the drive of a
   tacho-generator, an encoder's pinion) meshes with a gear on the wheel shaft with backlash +-g; a bearing drag keeps
   it on the driving flank while the wheel runs steadily, and whenever the wheel decelerates faster than the drag can
   slow the idler, it crosses the gap and strikes the other flank: an intermittent contact elsewhere in the train;
5. clutch torque x the contact law through a SATURATION: a ball-detent torque limiter in the jaw's hub; above T_lim
   the balls ride up their ramps and the coupling passes T_lim whatever the penetration, springing back as the torque
   falls: the contact torque capped, sign(T_c)*min(|T_c|, T_lim);
7. mass force x the STROKE COUNT accumulated and reset: each stroke drops a finished part onto a tray on the carriage
   and a sweeper empties the tray every N strokes; the parts' weight loads the carriage's rail with friction, a force
   against the motion growing by F_p with each part, -F_p*((k - k_0) mod N)*sign(v), k the stroke's number (a staircase
   with a periodic reset, a discrete event count);
9. a2 sensor x the SIGN of a2 (a bilinear gain): a2's accelerometer has a cracked suspension spring on one side of its
   proof mass, so its gain differs for the two directions, a2 = a*(1 + g) for a > 0 and a*(1 - g) for a < 0, i.e.
   a2 = a + g*|a|: an even-order, memoryless distortion with a kink at zero;
11. a2 sensor x its own OVERLOADS through a dead time: a2's sigma-delta module detects an overload when |a| exceeds its
    range A and resets its digital filter: its output is 0 while the input is over range and for T_r after it
    returns (a recovery time, retriggered by every overload sample);
13. wheel torque x the wheel speed through a PWM actuator: a chopper drives the wheel's eddy-current brake at a fixed
    carrier period T_p; at each carrier period's start the PLC samples the wheel speed and sets the duty
    d = clip((Omega2_s - Omega_0)/dOmega, 0, 1); the brake is then fully on (-T) for d*T_p of the period and off for
    the rest (a quantised, time-gated actuator, not a proportional one).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed;
no diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2
0.078; 3 a2 0.0147 at 0.005 kg*m^2, scaled once x5.12 -> 0.0747; 5 a2 0.136; 7 a2 0.188; 9 a2 0.123; 11 a2 0.605;
13 a2 0.0346 at 3 N*m, scaled once x2.17 -> 0.0645 (docs/foreign_drives.md "The sixth set").

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth and fifth sets.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory


def set_extra(b, *values) -> None:
    """The memory element's extra parameters (kernel.MEM_EXTRA on in its ring)."""
    for i, v in enumerate(values):
        b.P[K.P_MEMR0 + K.MEM_EXTRA + i] = v


# 1. motor load moment x the motor speed through a stick-slip coupling to a hidden inertia
class MotorSlipHubFlywheel(OutsideForm):
    name = "motor_slip_hub_flywheel"
    half = "dev6"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a brake disc on the motor's free shaft end sits on a loosened friction (slip) hub: every 0.2 ms the "
                   "hub passes the torque J_f*(Omega1 - w_f)/dt that brings the disc to the shaft's speed when it is "
                   "within +-T_s (the disc sticks, w_f = Omega1), else +-T_s (it slips, w_f moving by +-T_s/J_f*dt); that "
                   "torque loads the motor over the next 0.2 ms")
    parameters = (Param("inertia_kgm2", "kg*m^2", (1e-4, 0.05), "J_f: the disc's inertia"),
                  Param("slip_torque_Nm", "N*m", (0.0, 50.0), "T_s: the hub's slip torque"))
    note = "a hidden inertia through a dry-friction coupling: stuck it adds J_f to the motor, slipping it passes +-T_s"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_SLIP_HUB, K.XS_OMEGA1, p["inertia_kgm2"], p["slip_torque_Nm"])
        add_term(b, "motor_load_moment", 1.0, (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def hub_torque(omega1_at_segments, p, dt):
        """The hub's torque at each segment's start from Omega1 at the segments' starts (the first: 0, w_f = Omega1)."""
        x = np.asarray(omega1_at_segments, dtype=np.float64).tolist()
        jf, ts = p["inertia_kgm2"], p["slip_torque_Nm"]
        out, wf = np.zeros(len(x)), x[0]
        for i in range(1, len(x)):
            need = jf * (x[i] - wf) / dt
            if abs(need) <= ts:
                wf, out[i] = x[i], need
            else:
                out[i] = ts if need > 0 else -ts
                wf += out[i] / jf * dt
        return out

    def law(self, p):
        return (f"motor load moment += T_hub, T_hub = {p['inertia_kgm2']:.6g} kg*m^2 * (Omega1 - w_f)/0.2 ms while within "
                f"+-{p['slip_torque_Nm']:.6g} N*m (w_f = Omega1), else +-{p['slip_torque_Nm']:.6g} N*m (w_f += T_hub/"
                f"{p['inertia_kgm2']:.6g} * 0.2 ms), every 0.2 ms (a stick-slip hub)")


# 3. wheel torque x the wheel speed through a hidden body in a gap (gear rattle)
class WheelIdlerGearRattle(OutsideForm):
    name = "wheel_idler_gear_rattle"
    half = "dev6"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("an unloaded idler gear (of inertia J_i, referred to the wheel) meshes with a gear on the wheel "
                   "shaft with backlash +-g: its angle d relative to the wheel obeys d'' = c_a - lambda*(Omega2 + d') - "
                   "dOmega2/dt, the flanks' contact c_a = -w_c^2*(d -+ g) - 2*zeta*w_c*d' beyond +-g (never pulling), "
                   "and the wheel feels -J_i*c_a (advanced once per 0.2 ms in eight steps, dOmega2/dt the wheel speed's "
                   "change over the last 0.2 ms; the torque the mean over the scan; from rest on the driving flank)")
    parameters = (Param("inertia_kgm2", "kg*m^2", (0.0, 0.05), "J_i"),
                  Param("backlash_rad", "rad", (1e-5, 0.1), "g: half the mesh's backlash, at the wheel"),
                  Param("contact_frequency_hz", "Hz", (10.0, 1000.0), "w_c/(2*pi): the mesh's stiffness on J_i"),
                  Param("contact_damping_ratio", "-", (0.0, 1.0), "zeta"),
                  Param("drag_per_s", "1/s", (0.0, 10.0), "lambda: the idler's bearing drag over J_i"))
    note = "a hidden degree of freedom through an intermittent contact: quiet on the flank, impacts when it flies across"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RATTLE, K.XS_OMEGA2, p["backlash_rad"],
                   2.0 * np.pi * p["contact_frequency_hz"], p["drag_per_s"])
        set_extra(b, p["contact_damping_ratio"], 0.0)
        add_term(b, "wheel_torque", p["inertia_kgm2"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['inertia_kgm2']:.6g} kg*m^2 * c_a, c_a = -w^2*(d -+ {p['backlash_rad']:.6g}) - "
                f"2*{p['contact_damping_ratio']:.6g}*w*d' beyond +-{p['backlash_rad']:.6g} rad (never pulling), d'' = c_a "
                f"- {p['drag_per_s']:.6g}/s*(Omega2 + d') - dOmega2/dt, w = 2*pi*{p['contact_frequency_hz']:.6g} Hz "
                "(every 0.2 ms)")


# 5. clutch torque x the contact law through a saturation
class ClutchTorqueLimiter(OutsideForm):
    name = "clutch_torque_limiter"
    half = "dev6"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("a ball-detent torque limiter in the jaw's hub: above T_lim its balls ride up their ramps and the "
                   "coupling passes T_lim whatever the penetration, springing back as the torque falls: the contact "
                   "law's torque T_c capped, sign(T_c)*min(|T_c|, T_lim); 0 in the gap")
    parameters = (Param("limit_Nm", "N*m", (1.0, 500.0), "T_lim"),)
    note = "a saturation of the contact torque (memoryless): the impacts' peaks cut off, the contact sign kept"

    def apply(self, b, p):
        add_term(b, "clutch_torque", -1.0, (K.XS_CONTACT_TORQUE, K.XF_DEADZONE, p["limit_Nm"], 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += -sign(T_c)*max(0, |T_c| - {p['limit_Nm']:.6g} N*m), T_c the contact law's torque "
                f"(the total capped at +-{p['limit_Nm']:.6g} N*m)")


# 7. mass force x the stroke count accumulated and reset
class MassTrayParts(OutsideForm):
    name = "mass_tray_parts"
    half = "dev6"
    balance = "mass_force"
    depends_on = ("load_pulse", "mass_speed")
    description = ("each stroke drops a part onto a tray on the carriage, and a sweeper empties the tray every N "
                   "strokes: the parts' weight loads the rail with friction, -F_p*((k - k_0) mod N)*tanh(v/0.01 m/s), k "
                   "the current stroke's number (0: the first pulse at or after sample 0; it counts from each pulse's "
                   "start)")
    parameters = (Param("force_per_part_N", "N", (0.0, 20.0), "F_p: one part's rail friction"),
                  Param("every_n", "strokes", (2, 12), "N", "int"),
                  Param("first_empty", "-", (0, 11), "k_0 (below N): a stroke at which the tray is empty", "int"))
    note = "a staircase in the stroke count with a periodic reset: a discrete event count, period N*0.25 s"

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_per_part_N"],
                 (K.XS_PULSE_COUNT, K.XF_MOD, float(p["every_n"]), float(p["first_empty"]), 0.0),
                 (K.XS_MASS_SPEED, K.XF_TANH, 0.01, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['force_per_part_N']:.6g} N * ((k - {int(p['first_empty'])}) mod "
                f"{int(p['every_n'])}) * tanh(v/0.01 m/s), k the stroke's number")


# 9. a2 sensor x the sign of a2
class A2BilinearGain(OutsideForm):
    name = "a2_bilinear_gain"
    half = "dev6"
    stage = "sensor"
    order = 0                      # the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's accelerometer has a cracked suspension spring on one side of its proof mass: its gain differs "
                   "for the two directions, a*(1 + g) for a > 0 and a*(1 - g) for a < 0: a2 = a + g*|a|")
    parameters = (Param("asymmetry", "-", (-0.5, 0.5), "g"),)
    note = "an even-order, memoryless distortion with a kink at zero (not a gain, not an offset)"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        return a + p["asymmetry"] * np.abs(a)

    def law(self, p):
        return f"a2 sensor += {p['asymmetry']:.6g} * |a2|"


# 11. a2 sensor x its own overloads through a dead time
class A2OverloadRecovery(OutsideForm):
    name = "a2_overload_recovery"
    half = "dev6"
    stage = "sensor"
    order = 1                      # the module's ADC, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's sigma-delta module resets its digital filter when its input exceeds its range A: its output "
                   "is 0 at every sample with |a| > A and for T_r after the last such sample (recovery, retriggered)")
    parameters = (Param("range_m_s2", "m/s^2", (0.1, 1000.0), "A"),
                  Param("recovery_s", "s", (0.0, 0.1), "T_r"))
    note = "a dead time triggered by the signal's own overloads: the recording is 0 where the signal is largest"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], t, p)

    @staticmethod
    def muted(a, t, p):
        a, t = np.asarray(a, dtype=np.float64), np.asarray(t, dtype=np.float64)
        over = np.abs(a) > p["range_m_s2"]
        last = np.where(over, t, -np.inf)
        last = np.maximum.accumulate(last)
        return t - last <= p["recovery_s"] + 1e-12

    @classmethod
    def read(cls, a, t, p):
        return np.where(cls.muted(a, t, p), 0.0, np.asarray(a, dtype=np.float64))

    def law(self, p):
        return (f"a2 sensor = 0 where |a2| > {p['range_m_s2']:.6g} m/s^2 and for {p['recovery_s']:.6g} s after the last "
                "such sample, else a2")


# 13. wheel torque x the wheel speed through a PWM actuator
class WheelPwmBrake(OutsideForm):
    name = "wheel_pwm_brake"
    half = "dev6"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a chopper drives the wheel's eddy-current brake at a carrier period T_p: at each period's start "
                   "(the 0.2 ms scans from the run-in's start) the PLC samples Omega2 and sets the duty d = clip((Omega2_s "
                   "- Omega_0)/dOmega, 0, 1); the brake is fully on, -T, for the first round(d*T_p/0.2 ms) scans of the "
                   "period and off for the rest")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("carrier_period_s", "s", (4e-4, 0.05), "T_p (a multiple of 0.2 ms)"),
                  Param("zero_duty_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_0"),
                  Param("full_duty_span_rad_s", "rad/s", (0.1, 50.0), "dOmega"))
    note = "a quantised, time-gated actuator: full torque or none, its mean following the sampled speed"

    def apply(self, b, p):
        per = segments(p["carrier_period_s"], f"{self.name}: carrier_period_s")
        set_memory(b, self.name, K.MK_PWM, K.XS_OMEGA2, float(per), p["zero_duty_speed_rad_s"],
                   p["full_duty_span_rad_s"])
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m while the scan is within the first d*{p['carrier_period_s']:.6g} "
                f"s of each carrier period, d = clip((Omega2_s - {p['zero_duty_speed_rad_s']:.6g})/"
                f"{p['full_duty_span_rad_s']:.6g}, 0, 1), Omega2_s sampled at the period's start")


FORM_CLASSES = (MotorSlipHubFlywheel, WheelIdlerGearRattle, ClutchTorqueLimiter, MassTrayParts, A2BilinearGain,
                A2OverloadRecovery, WheelPwmBrake)
