"""Outside mechanisms, seventeenth SEALED half (issue 31 part 4, set 17): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev17`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the spring extension through an OFF-DELAY: a tension switch on the spring's cable guide with a
   run-on timer: while the extension is above z_t, and for T_off after the last 0.2 ms scan at which it was, a
   holding brake on the motor's free shaft end pulls T: T*m, m -> 1 at a scan with z > z_t, -> 0 once T_off has passed
   since the last such scan (m = 1 at the run-in's start if z > z_t, else 0) (the eleventh set's off-delay is of the
   wheel speed, on the wheel, the fourteenth sealed half's of the jaw's penetration, on the clutch; the earlier motor
   loads of the extension are a linear excess, the extension times the motor speed and a peak held since the stroke
   began);
4. wheel torque x the slip through a PEAK DETECTOR with a decay: a slip-reading drag pointer: a tacho on each shaft
   feeds a peak detector (a diode into a capacitor bled by a resistor, time constant tau) whose output excites an
   eddy-current brake on the wheel: -c*max(0, m), m -> max(s, m*exp(-dt/tau)) every 0.2 ms, s = Omega1 - Omega2 (m = s
   at the run-in's start) (the earlier peak detectors hold the wheel speed on the wheel, the motor speed on the motor,
   the penetration on the clutch and the extension since each stroke; the fifteenth set's slip monitor is memoryless,
   on the motor);
6. clutch torque x the slip through a RATE LIMITER: a magnetorheological coupling beside the jaw whose coil current a
   controller sets from the slip, through a current source that slews at most R: c*m, m moves towards s = Omega1 -
   Omega2 by at most R*dt each 0.2 ms (m = s at the run-in's start) (a slew-limited copy of the slip: the earlier
   memories of the slip are a lag, a dead time, an on-delay, a heat, a pumped plate; the earlier rate limiters are of
   the extension, on the carriage, and of the motor speed's follower, on the motor);
8. mass force x the spring extension through a RELAY WITH HYSTERESIS: a two-point tension switch with a switching
   differential clamps a drag shoe on the carriage: -F*s, s switched to 1 when z rises above z_on and to 0 when it falls
   below z_off < z_on (scanned every 0.2 ms; s = 0 at the run-in's start) (the third set's relay is of the motor speed,
   on the motor; the earlier switches of the extension on the carriage are a one-shot timer and an impulse relay (a
   toggle), memoryless ones the festoon and the gas spring);
10. a2 sensor x the LOAD PULSE through a TRACK-AND-HOLD: a2's module has a blanking input: the PLC holds a2's
    track-and-hold while the press's valve is energised (to blank its switching noise), so a2 reads its value at the
    stroke's first sample throughout each stroke: y = x(t_p) while the pulse is on, t_p its start, else x (a hold gated
    by the press: the fourth set's telemetry hold is gated by the motor's angle, on a1; the supply sag's gain, the
    solenoid pickup and the stroke ringing follow the pulse without holding anything);
12. mass force x the carriage's POSITION through a SMOOTH SINE: the carriage's rail sags between its supports (a span
    L): the carriage's weight along the cambered rail gives F*sin(2*pi*x/L + phi), x its position unwrapped from the
    run-in's start (a smooth force of the travel, locked to neither shaft nor the time: the fifth sealed half's rail
    joints knock once per joint, the floor vibration is locked to the time, the eccentric roller to the wheel's angle);
14. motor load moment x the TIME through a SAWTOOTH: a pump on the motor's shaft end charges a lubrication accumulator
    that a timer dumps every T_f (its own period, locked to nothing of the press): the pump's load rises with the
    accumulator's pressure and drops at each dump: T*((t - t_0) mod T_f)/T_f (a ramp restarting at a fixed period:
    the first sealed half's clogging load rises once over the recording, the timed brush is a window of its own period
    on the wheel, the neighbour press's strikes are decays of its own period on the carriage, the catalogue's
    structural vibration is a sine).

Visibility, measured as for the development half (4 s, against the same spec without the mechanism, same seed;
criterion a2 >= 0.05, a1 >= 0.25 for an a1 row): 2 a2 0.0950; 4 a2 0.0990; 6 a2 0.103; 8 a2 0.0155 at its a-priori
strength, scaled once x4.83 (a2 0.0702 after); 10 a2 0.767; 12 a2 0.141; 14 a2 0.100 -- the others as written.

Thin (read off the laws and the documented clean drive, no diagnose): the accumulator pump's sawtooth (14) has a mean of
half its amplitude, a constant motor load beside its ramp (the ramp's rms about the mean is 0.29 of the amplitude); the
cambered rail (12) reads the carriage's position, as the fifth sealed half's rail joints do, with a smooth shape instead
of a knock per joint, and at the carriage's near-constant speed it is close to a fixed 10.3 Hz line.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term, set_relay
from .outside_dev4 import segments, set_memory


# 2. motor load moment x the spring extension through an off-delay
class MotorTensionRunOnBrake(OutsideForm):
    name = "motor_tension_run_on_brake"
    half = "sealed17"
    balance = "motor_load_moment"
    depends_on = ("spring_extension",)
    description = ("a tension switch on the spring's cable guide with a run-on timer: while the extension is above "
                   "z_t, and for T_off after the last 0.2 ms scan at which it was, a holding brake on the motor's free "
                   "shaft end pulls T: T*m, m -> 1 at a scan with z > z_t, -> 0 once T_off has passed since the last "
                   "such scan (m = 1 at the run-in's start if z > z_t, else 0)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("trip_extension_m", "m", (0.0, 1.0), "z_t"),
                  Param("run_on_s", "s", (2e-4, 0.5), "T_off (a multiple of 0.2 ms)"))
    note = "a motor brake switched by the extension with a run-on time"

    def apply(self, b, p):
        segments(p["run_on_s"], f"{self.name}: run_on_s")
        set_memory(b, self.name, K.MK_OFF_DELAY, K.XS_SPRING_EXTENSION, p["trip_extension_m"], p["run_on_s"])
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m while z > {p['trip_extension_m']:.6g} m and for "
                f"{p['run_on_s']:.6g} s after the last 0.2 ms scan at which it was, z the spring's extension")


# 4. wheel torque x the slip through a peak detector with a decay
class WheelSlipPeakEddyBrake(OutsideForm):
    name = "wheel_slip_peak_eddy_brake"
    half = "sealed17"
    balance = "wheel_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a slip-reading drag pointer: a tacho on each shaft feeds a peak detector (bled with time constant "
                   "tau) whose output excites an eddy-current brake on the wheel: -c*max(0, m), m -> max(s, "
                   "m*exp(-dt/tau)) every 0.2 ms, s = Omega1 - Omega2 (m = s at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "c"),
                  Param("decay_s", "s", (1e-3, 10.0), "tau"))
    note = "a wheel brake set by the slip's recent peak"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PEAK, K.XS_JAW_SPEED, p["decay_s"])
        add_term(b, "wheel_torque", -p["coefficient_Nm_s_per_rad"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, 0.0, 1.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * max(0, m), m -> max(Omega1 - "
                f"Omega2, m*exp(-dt/{p['decay_s']:.6g} s)) every 0.2 ms")


# 6. clutch torque x the slip through a rate limiter
class ClutchSlewLimitedMrCoupling(OutsideForm):
    name = "clutch_slew_limited_mr_coupling"
    half = "sealed17"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a magnetorheological coupling beside the jaw whose coil current a controller sets from the slip "
                   "through a current source that slews at most R: c*m, m moves towards s = Omega1 - Omega2 by at most "
                   "R*dt each 0.2 ms (m = s at the run-in's start), from the motor to the wheel, in the gap and in "
                   "contact")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "c"),
                  Param("slew_rad_s2", "rad/s^2", (1.0, 1e5), "R"))
    note = "a slip coupling following a slew-limited copy of the slip"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RATE_LIMIT, K.XS_JAW_SPEED, p["slew_rad_s2"])
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * m, m moving towards Omega1 - Omega2 "
                f"by at most {p['slew_rad_s2']:.6g} rad/s^2 * 0.2 ms each 0.2 ms, in the gap and in contact")


# 8. mass force x the spring extension through a relay with hysteresis
class MassTensionSwitchDragShoe(OutsideForm):
    name = "mass_tension_switch_drag_shoe"
    half = "sealed17"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("a two-point tension switch with a switching differential clamps a drag shoe on the carriage: -F*s, "
                   "s switched to 1 when z rises above z_on and to 0 when it falls below z_off < z_on (scanned every "
                   "0.2 ms; s = 0 at the run-in's start), z the spring's extension")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("on_above_m", "m", (0.0, 1.0), "z_on"),
                  Param("off_below_m", "m", (0.0, 1.0), "z_off (below z_on)"))
    note = "a drag shoe on the carriage switched by the extension with hysteresis"

    def apply(self, b, p):
        set_relay(b, self.name, K.XS_SPRING_EXTENSION, p["on_above_m"], p["off_below_m"], "on_above_m", "off_below_m")
        add_term(b, "mass_force", -p["force_N"], (K.XS_RELAY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * s, s switched to 1 when z rises above {p['on_above_m']:.6g} m "
                f"and to 0 when it falls below {p['off_below_m']:.6g} m (checked every 0.2 ms)")


# 10. a2 sensor x the load pulse through a track-and-hold
class A2StrokeBlankingHold(OutsideForm):
    name = "a2_stroke_blanking_hold"
    half = "sealed17"
    stage = "sensor"
    order = 1                      # the module, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "load_pulse")
    description = ("a2's module has a blanking input: the PLC holds a2's track-and-hold while the press's valve is "
                   "energised, so a2 reads its value at the stroke's first sample throughout each stroke: y = x(t_p) "
                   "while the load pulse is on, t_p its start, else x")
    parameters = (Param("enabled", "-", (0.0, 1.0), "1: the hold acts, 0: off"),)
    note = "a2 held through each stroke"

    def apply_signal(self, sig, p, t, fs, states=None):
        if p["enabled"] >= 0.5:
            sig["a2"] = self.read(sig["a2"], states["pulse"])

    @staticmethod
    def read(a, pulse):
        a = np.asarray(a, dtype=np.float64)
        on = np.asarray(pulse) > 0
        start = on & ~np.concatenate(([False], on[:-1]))
        idx = np.maximum.accumulate(np.where(start, np.arange(a.size), 0))
        return np.where(on, a[idx], a)

    def law(self, p):
        return ("a2 sensor = a2 at the load pulse's first sample while the pulse is on, else a2 (a track-and-hold "
                "held through each stroke)" if p["enabled"] >= 0.5 else "off")


# 12. mass force x the carriage's position through a smooth sine
class MassCamberedRail(OutsideForm):
    name = "mass_cambered_rail"
    half = "sealed17"
    balance = "mass_force"
    depends_on = ("wheel_angle", "spring_extension")     # x = r*alpha2 - z (the fifth sealed half's rail joints)
    description = ("the carriage's rail sags between its supports (a span L): the carriage's weight along the "
                   "cambered rail gives F*sin(2*pi*x/L + phi) along x, x its position unwrapped from the run-in's start")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("span_m", "m", (0.1, 100.0), "L"),
                  Param("phase_rad", "rad", (-np.pi, np.pi), "phi"))
    note = "a smooth force of the carriage's travel, locked to neither shaft nor the time"

    def apply(self, b, p):
        add_term(b, "mass_force", p["force_N"],
                 (K.XS_MASS_POSITION, K.XF_SIN, 2.0 * np.pi / p["span_m"], p["phase_rad"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * sin(2*pi*x/{p['span_m']:.6g} m + {p['phase_rad']:.6g}), x the "
                "carriage's position unwrapped from the run-in's start")


# 14. motor load moment x the time through a sawtooth
class MotorTimerDumpedAccumulatorPump(OutsideForm):
    name = "motor_timer_dumped_accumulator_pump"
    half = "sealed17"
    balance = "motor_load_moment"
    depends_on = ("time",)
    description = ("a pump on the motor's shaft end charges a lubrication accumulator that a timer dumps every T_f: "
                   "the pump's load rises with the accumulator's pressure and drops at each dump: "
                   "T*((t - t_0) mod T_f)/T_f on the motor's load")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T (just before a dump)"),
                  Param("period_s", "s", (0.01, 10.0), "T_f"),
                  Param("first_dump_s", "s", (-10.0, 10.0), "t_0"))
    note = "a ramp of the time restarting at a period of its own"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"] / p["period_s"],
                 (K.XS_TIME, K.XF_MOD, p["period_s"], p["first_dump_s"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * ((t - {p['first_dump_s']:.6g} s) mod "
                f"{p['period_s']:.6g} s)/{p['period_s']:.6g} s")


FORM_CLASSES = (MotorTensionRunOnBrake, WheelSlipPeakEddyBrake, ClutchSlewLimitedMrCoupling, MassTensionSwitchDragShoe,
                A2StrokeBlankingHold, MassCamberedRail, MotorTimerDumpedAccumulatorPump)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 17100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 2 N*m above 0.31 m and for 40 ms after
        ("os17_motor_tension_run_on_brake", "outside", 0.0071, 0.0260, 0.95,
         [E("motor_tension_run_on_brake", {"torque_Nm": 2.0, "trip_extension_m": 0.31, "run_on_s": 0.04})]),
        # 1 N*m*s/rad of the slip's peak, bled over 50 ms
        ("os17_wheel_slip_peak_eddy_brake", "outside", 0.0063, 0.0305, 0.92,
         [E("wheel_slip_peak_eddy_brake", {"coefficient_Nm_s_per_rad": 1.0, "decay_s": 0.05})]),
        # 1 N*m*s/rad of the slip, slewing at most 200 rad/s^2
        ("os17_clutch_slew_limited_mr_coupling", "outside", 0.0085, 0.0240, 0.94,
         [E("clutch_slew_limited_mr_coupling", {"coefficient_Nm_s_per_rad": 1.0, "slew_rad_s2": 200.0})]),
        # 3 N, on above 0.31 m, off below 0.29 m a priori, a2 0.0155: scaled once x4.83
        ("os17_mass_tension_switch_drag_shoe", "outside", 0.0066, 0.0285, 0.90,
         [E("mass_tension_switch_drag_shoe", {"force_N": 14.48, "on_above_m": 0.31, "off_below_m": 0.29})]),
        ("os17_clean_w7.5_eta0.0250_n0.96", "clean", 0.0075, 0.0250, 0.96, []),
        # held through each stroke
        ("os17_a2_stroke_blanking_hold", "outside", 0.0080, 0.0330, 0.93,
         [E("a2_stroke_blanking_hold", {"enabled": 1.0})]),
        # 2 N over a 2.2 m span (about 10.3 Hz at the carriage's speed), phase 0.3
        ("os17_mass_cambered_rail", "outside", 0.0068, 0.0225, 0.97,
         [E("mass_cambered_rail", {"force_N": 2.0, "span_m": 2.2, "phase_rad": 0.3})]),
        # 3 N*m just before each dump, every 0.7 s from 0.1 s
        ("os17_motor_timer_dumped_accumulator_pump", "outside", 0.0086, 0.0280, 0.91,
         [E("motor_timer_dumped_accumulator_pump", {"torque_Nm": 3.0, "period_s": 0.7, "first_dump_s": 0.1})]),
    ]
