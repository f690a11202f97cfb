"""Outside mechanisms, nineteenth SEALED half (issue 31 part 4, set 19): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev19`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the SLIP through a LATCH RE-ARMED AT EACH STROKE: a closing-speed guard: a slip monitor trips
   a motor-side brake once the slip rises past s_t (the drive half closing on the jaw fast) and the press's valve
   releases it at the next stroke's start: T*m, m -> 0 at each load pulse's first 0.2 ms scan, then m -> 1 at a scan
   with s > s_t (m = 1 at the run-in's start if s > s_t), s = Omega1 - Omega2 (the earlier latches are of the wheel's
   speed (the seventh set), of the extension (the fourteenth sealed half) and of the carriage's speed (the eighteenth
   set); the fifteenth set's motor load of the slip is memoryless (|s|); the earlier memories of the slip include a
   lag, a fill, a delay, a tank, an on-delay, an off-delay, a heat integrator, an impact sample, a decaying peak and a
   rate limiter, none a latch);
4. wheel torque x the spring extension through an ON-DELAY (a debounced switch): a tension switch on the cable's guide
   sheave applies a wheel brake through a PLC timer once the extension has stayed above z_t for T_d: -T*m, m = 1 while
   z > z_t has held for at least T_d (counted in 0.2 ms scans), else 0 (the earlier on-delays are of the carriage's
   speed (the seventh set) and of the slip (the thirteenth sealed half); the earlier memories of the extension on the
   wheel include a latch, a stroke sample, a play and a peak held since the stroke began; the seventeenth sealed half's
   motor brake of the extension is an off-delay, on at once and held after);
6. clutch torque x the slip through a THERMAL CUT-OUT: an eddy-current drag coupling beside the jaw whose drum carries
   a bimetal cut-out: its heat h, fed by the coupling's own power while it is on and cooling with a time constant,
   switches its excitation off above h_hi and on again below h_lo: c*s*m, h' = m*c*s^2 - h/tau, m -> 0 when h > h_hi,
   -> 1 when h < h_lo (m = 1, h = 0 at the run-in's start), s = Omega1 - Omega2, in the gap and in contact (the tenth
   set's thermal cut-out is of the wheel's speed, on the wheel; the earlier slip couplings switched by a memory of the
   slip include an on-delay (the thirteenth sealed half); the fifteenth sealed half's coupling thinned by its
   heat fades smoothly, without a switch);
8. mass force x the spring extension through a SELF-EXCITED OSCILLATOR: the carriage's guide shoe squeals (a
   friction-induced vibration) when the cable's pull presses it hard: a van der Pol oscillator of its own frequency f
   whose negative damping grows with the extension's excess over z_c: F*X, X'' = w*g*(z - z_c)*(1 - X^2)*X' - w^2*X,
   w = 2*pi*f (X = 1e-3, X' = 0 at the run-in's start; a floor keeps a seed amplitude) (the eighth set's squeal is of
   the wheel's speed, on the wheel; the thirteenth sealed half's and the fifth set's resonators are driven, not
   self-excited; the earlier laws of the extension on the carriage are memoryless or a rate limiter, a delay, a toggle,
   a play, a stroke sample, a one-shot and a Dahl element);
10. a1 sensor x the TIME BASE through a CLOCK SKEW (a sample clock of its own): a1 is digitised by the motor drive's own
    converter, whose crystal runs fast by a fraction e against the recorder's clock; the recording is a1 read at the
    converter's instants: y(t) = x(t_0 + (1 + e)*(t - t_0)), t_0 the recording's first sample (the pre-roll's) (a delay
    that grows over the recording: the fifteenth sealed half's delay of one channel is constant; the earlier sensor
    timing errors are a hold, a decimation and the pulse-synchronous holds, none a drift of the time base);
12. mass force x the STROKE COUNT through a SINE: the strip is drawn from an eccentric coil, each stroke drawing the
    same length; the coil turns once every N strokes and its eccentricity swings the strip's back-tension on the
    carriage stroke by stroke: F*sin(2*pi*k/N + phi), k the current load pulse's number (a force on the carriage that
    steps once per stroke along a slow sine: the sixth set's staircase of the stroke count resets every N strokes; the
    sixth sealed half's blank thickness is a random pattern of the count, on the motor; the fourth set's sub-harmonic
    is a window of the count, on the motor);
14. clutch torque x the slip times the MOTOR SPEED's EXCESS: a centrifugal shoe clutch in parallel with the jaw: its
    shoes, on the drive half's hub, press on a drum on the wheel's half with the centrifugal force less their springs'
    pull, so the friction's capacity grows with the motor speed's excess over its engagement speed: mu*max(0, Omega1 -
    Omega_e)*tanh(s/w), s = Omega1 - Omega2, in the gap and in contact (the earlier dry frictions across the jaw are
    pressed by the cable (the sixteenth set) or by the slip's own fill (the thirteenth set), or constant (the
    thirteenth set's hysteresis coupling); the twelfth set's hydrodynamic coupling is the slip times the motor's speed,
    viscous).

Visibility, measured as for the development half (4 s, against the same spec without the mechanism, same seed;
criterion a2 >= 0.05, a1 >= 0.25 for an a1 row): 2 a2 0.0726; 4 a2 0.0700; 6 a2 0.0940; 8 a2 0.137 at its first
conditions, 0.0605 as re-written (below); 10 a1 12.8; 12 a2 0.160; 14 a2 0.0737 -- all as written, none scaled.

The guide-shoe squeal's CONDITIONS (8) were re-written before any diagnose, as the fourteenth set's festoon loop's were:
at z_c 0.29 m and g 20 /m it squealed through 97 % of the recording (|F| > 0.1 N), a steady 60 Hz tone that never
died (the second set's fixed frequency on the carriage, in effect), because the extension (0.283-0.318 m on the clean
drive, median 0.297 m) stays above 0.29 m most of the time and fell below it too little to damp the tone; now z_c
0.306 m (about the clean drive's upper quartile) and g 200 /m: it squeals in bursts, 24 % of the recording. Its
strength (F 2 N) is as written. A check that each memory switches (no figure used for a strength) found the latch (2)
on 71 % of the recording, the on-delay (4) 34 %, the cut-out (6) switching 31 times in 4 s.

Thin (read off the laws and the clean drive, no diagnose; recorded here only): the slip guard (2) trips at each stroke's
gap traversal and holds to the next stroke's start, so 71 % of the recording it is on: mostly a constant brake with a
stroke-locked gap; the debounced tension brake (4) and the squeal (8) read the extension through thresholds inside its
range (0.30 m, 0.306 m), so each acts as a stroke-locked window; the clock skew (10) is far above the criterion (a1
12.8, 200 ppm: a1's impacts are sharp, so 0.8 ms of drift by the end moves them a good deal), and its effect grows
linearly over the recording; the coil's back-tension (12) steps once a stroke along a sine of five strokes (1.25 s), a
slow pattern; the centrifugal clutch (14) acts mostly in the gap (in contact the slip is about 0, so tanh(s/w) is
small), its pressing varying about twofold with the motor's speed (147-154 rad/s against 140 rad/s).
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 2. motor load moment x the slip through a latch re-armed at each stroke
class MotorSlipLatchedGuardBrake(OutsideForm):
    name = "motor_slip_latched_guard_brake"
    half = "sealed19"
    balance = "motor_load_moment"
    depends_on = ("motor_speed", "wheel_speed", "load_pulse")
    description = ("a closing-speed guard: a slip monitor trips a motor-side brake once the slip rises past s_t and "
                   "the press's valve releases it at the next stroke's start: T*m, m -> 0 at each load pulse's first "
                   "0.2 ms scan, then m -> 1 at a scan with s > s_t (m = 1 at the run-in's start if s > s_t), "
                   "s = Omega1 - Omega2")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("trip_slip_rad_s", "rad/s", (-50.0, 50.0), "s_t"))
    note = "a motor brake latched by the slip, re-armed at each stroke"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_LATCH, K.XS_JAW_SPEED, p["trip_slip_rad_s"])
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * m, m set when Omega1 - Omega2 passes "
                f"{p['trip_slip_rad_s']:.6g} rad/s and reset at each load pulse's first 0.2 ms scan (scanned every "
                "0.2 ms)")


# 4. wheel torque x the spring extension through an on-delay
class WheelDebouncedTensionBrake(OutsideForm):
    name = "wheel_debounced_tension_brake"
    half = "sealed19"
    balance = "wheel_torque"
    depends_on = ("spring_extension",)
    description = ("a tension switch on the cable's guide sheave applies a wheel brake through a PLC timer once the "
                   "extension has stayed above z_t for T_d: -T*m, m = 1 while z > z_t has held for at least T_d "
                   "(counted in 0.2 ms scans), else 0")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("threshold_m", "m", (0.0, 1.0), "z_t"),
                  Param("delay_s", "s", (0.0, 10.0), "T_d"))
    note = "a wheel brake of the extension through a debounce timer"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_ON_DELAY, K.XS_SPRING_EXTENSION, p["threshold_m"], p["delay_s"])
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * m, m = 1 once the spring's extension has stayed above "
                f"{p['threshold_m']:.6g} m for {p['delay_s']:.6g} s (scanned every 0.2 ms), else 0")


# 6. clutch torque x the slip through a thermal cut-out
class ClutchThermalCutoutDragCoupling(OutsideForm):
    name = "clutch_thermal_cutout_drag_coupling"
    half = "sealed19"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an eddy-current drag coupling beside the jaw whose drum carries a bimetal cut-out: its heat h, fed "
                   "by the coupling's own power while it is on and cooling with tau, switches its excitation off above "
                   "h_hi and on below h_lo: c*s*m, h += dt*(m*c*s^2 - h/tau), m -> 0 when h > h_hi, -> 1 when h < h_lo "
                   "(m = 1, h = 0 at the run-in's start), s = Omega1 - Omega2, in the gap and in contact")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "c"),
                  Param("cooling_time_s", "s", (1e-3, 100.0), "tau"),
                  Param("off_above_J", "J", (1e-6, 1e5), "h_hi"),
                  Param("on_below_J", "J", (0.0, 1e5), "h_lo (< h_hi)"))
    note = "a slip coupling behind a thermal cut-out its own heat drives"

    def apply(self, b, p):
        c = p["coefficient_Nm_s_per_rad"]
        if p["on_below_J"] >= p["off_above_J"]:
            raise ValueError(f"{self.name}: on_below_J {p['on_below_J']} is not below off_above_J "
                             f"{p['off_above_J']}; allowed: on_below_J < off_above_J")
        set_memory(b, self.name, K.MK_THERMOSTAT, K.XS_JAW_SPEED, c, p["cooling_time_s"], p["off_above_J"])
        set_extra(b, p["on_below_J"])
        add_term(b, "clutch_torque", c, (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0), (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) * m, h += dt*(m*"
                f"{p['coefficient_Nm_s_per_rad']:.6g}*(Omega1 - Omega2)^2 - h/{p['cooling_time_s']:.6g} s), m off above "
                f"{p['off_above_J']:.6g} J and on below {p['on_below_J']:.6g} J (scanned every 0.2 ms), in the gap and "
                "in contact")


# 8. mass force x the spring extension through a self-excited oscillator
class MassGuideShoeSqueal(OutsideForm):
    name = "mass_guide_shoe_squeal"
    half = "sealed19"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("the carriage's guide shoe squeals when the cable's pull presses it hard: a van der Pol oscillator "
                   "X'' = w*g*(z - z_c)*(1 - X^2)*X' - w^2*X, w = 2*pi*f, advanced every 0.2 ms from X = 1e-3 at the "
                   "run-in's start, its amplitude kept at least 1e-3; the shoe's force on the carriage F*X/2")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F: the force at the limit cycle's amplitude (X ~ 2)"),
                  Param("frequency_hz", "Hz", (10.0, 500.0), "f"),
                  Param("growth_per_m", "1/m", (0.0, 1000.0), "g: the negative damping per m of extension above z_c"),
                  Param("onset_m", "m", (0.0, 1.0), "z_c"))
    note = "a self-excited oscillator on the carriage whose negative damping the cable's extension sets"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_SQUEAL, K.XS_SPRING_EXTENSION, 2.0 * np.pi * p["frequency_hz"],
                   p["growth_per_m"], p["onset_m"])
        add_term(b, "mass_force", 0.5 * p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        w = 2.0 * np.pi * p["frequency_hz"]
        return (f"mass force += {p['force_N']:.6g} N * X/2, X'' = {w:.6g}*{p['growth_per_m']:.6g}*(z - "
                f"{p['onset_m']:.6g} m)*(1 - X^2)*X' - {w:.6g}^2*X (advanced every 0.2 ms, amplitude at least 1e-3)")


# 10. a1 sensor x the time base through a clock skew
class A1OwnClockSkew(OutsideForm):
    name = "a1_own_clock_skew"
    half = "sealed19"
    stage = "sensor"
    order = 1                      # the converter, after the sensing element
    balance = "sensor"
    channel = "a1"
    depends_on = ("motor_acceleration", "time")
    description = ("a1 is digitised by the motor drive's own converter, whose clock runs fast by a fraction e against "
                   "the recorder's: y(t) = x(t_0 + (1 + e)*(t - t_0)), t_0 the recording's first sample (the "
                   "pre-roll's), linear between samples, held at the last sample beyond the recording's end")
    parameters = (Param("skew", "-", (-0.01, 0.01), "e"),)
    note = "a1 read on a time base drifting against the recorder's (a delay growing over the recording)"

    def apply_signal(self, sig, p, t, fs):
        sig["a1"] = self.read(sig["a1"], t, p)

    @staticmethod
    def read(a, t, p):
        if p["skew"] == 0.0:
            return np.asarray(a, dtype=np.float64)
        t = np.asarray(t, dtype=np.float64)
        return np.interp(t[0] + (1.0 + p["skew"]) * (t - t[0]), t, np.asarray(a, dtype=np.float64))

    def law(self, p):
        return (f"a1 sensor = a1 read at t_0 + (1 + {p['skew']:.6g})*(t - t_0), t_0 the recording's first sample (the "
                "pre-roll's), linear between samples")


# 12. mass force x the stroke count through a sine
class MassEccentricCoilBackTension(OutsideForm):
    name = "mass_eccentric_coil_back_tension"
    half = "sealed19"
    balance = "mass_force"
    depends_on = ("load_pulse",)
    description = ("the strip is drawn from an eccentric coil, each stroke drawing the same length; the coil turns "
                   "once every N strokes and its eccentricity swings the strip's back-tension on the carriage stroke by "
                   "stroke: F*sin(2*pi*k/N + phi), k the current load pulse's number")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("strokes_per_turn", "-", (2.0, 1000.0), "N"),
                  Param("phase_rad", "rad", (-np.pi, np.pi), "phi"))
    note = "a force on the carriage stepping once per stroke along a slow sine of the stroke count"

    def apply(self, b, p):
        add_term(b, "mass_force", p["force_N"],
                 (K.XS_PULSE_COUNT, K.XF_SIN, 2.0 * np.pi / p["strokes_per_turn"], p["phase_rad"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * sin(2*pi*k/{p['strokes_per_turn']:.6g} + "
                f"{p['phase_rad']:.6g}), k the current load pulse's number (0: the first at or after sample 0)")


# 14. clutch torque x the slip times the motor speed's excess
class ClutchCentrifugalShoeClutch(OutsideForm):
    name = "clutch_centrifugal_shoe_clutch"
    half = "sealed19"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a centrifugal shoe clutch in parallel with the jaw: its shoes on the drive half's hub press on a "
                   "drum on the wheel's half with the centrifugal force less their springs' pull: mu*max(0, Omega1 - "
                   "Omega_e)*tanh(s/w), s = Omega1 - Omega2, in the gap and in contact")
    parameters = (Param("capacity_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "mu (per rad/s above Omega_e)"),
                  Param("engage_speed_rad_s", "rad/s", (0.0, 300.0), "Omega_e"),
                  Param("slip_width_rad_s", "rad/s", (1e-3, 50.0), "w"))
    note = "a dry friction across the jaw pressed by the motor speed's excess (a centrifugal clutch)"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["capacity_Nm_s_per_rad"],
                 (K.XS_JAW_SPEED, K.XF_TANH, p["slip_width_rad_s"], 0.0, 0.0),
                 (K.XS_OMEGA1, K.XF_EXCESS_POWER, p["engage_speed_rad_s"], 1.0, 0.0))

    def law(self, p):
        return (f"clutch torque += {p['capacity_Nm_s_per_rad']:.6g} N*m*s/rad * max(0, Omega1 - "
                f"{p['engage_speed_rad_s']:.6g} rad/s) * tanh((Omega1 - Omega2)/{p['slip_width_rad_s']:.6g} rad/s), in "
                "the gap and in contact")


FORM_CLASSES = (MotorSlipLatchedGuardBrake, WheelDebouncedTensionBrake, ClutchThermalCutoutDragCoupling,
                MassGuideShoeSqueal, A1OwnClockSkew, MassEccentricCoilBackTension, ClutchCentrifugalShoeClutch)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 19100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 2 N*m from a slip above 2 rad/s to the next stroke
        ("os19_motor_slip_latched_guard_brake", "outside", 0.0071, 0.0265, 0.94,
         [E("motor_slip_latched_guard_brake", {"torque_Nm": 2.0, "trip_slip_rad_s": 2.0})]),
        # 2 N*m once the extension has stayed above 0.30 m for 20 ms
        ("os19_wheel_debounced_tension_brake", "outside", 0.0083, 0.0235, 0.92,
         [E("wheel_debounced_tension_brake", {"torque_Nm": 2.0, "threshold_m": 0.30, "delay_s": 0.02})]),
        # 1 N*m*s/rad of the slip, cooling over 0.2 s, off above 0.2 J, on below 0.1 J
        ("os19_clutch_thermal_cutout_drag_coupling", "outside", 0.0064, 0.0295, 0.96,
         [E("clutch_thermal_cutout_drag_coupling", {"coefficient_Nm_s_per_rad": 1.0, "cooling_time_s": 0.2,
                                                     "off_above_J": 0.2, "on_below_J": 0.1})]),
        # 2 N at 60 Hz, growing above 0.306 m by 200 /m (conditions re-written before any diagnose: at 0.29 m and
        # 20 /m it squealed through 97 % of the recording, a steady tone that never died)
        ("os19_mass_guide_shoe_squeal", "outside", 0.0077, 0.0250, 0.90,
         [E("mass_guide_shoe_squeal", {"force_N": 2.0, "frequency_hz": 60.0, "growth_per_m": 200.0,
                                       "onset_m": 0.306})]),
        ("os19_clean_w6.9_eta0.0280_n0.95", "clean", 0.0069, 0.0280, 0.95, []),
        # 200 ppm fast
        ("os19_a1_own_clock_skew", "outside", 0.0086, 0.0215, 0.93,
         [E("a1_own_clock_skew", {"skew": 2e-4})]),
        # 3 N, one coil turn every 5 strokes
        ("os19_mass_eccentric_coil_back_tension", "outside", 0.0068, 0.0320, 0.97,
         [E("mass_eccentric_coil_back_tension", {"force_N": 3.0, "strokes_per_turn": 5.0, "phase_rad": 0.5})]),
        # 0.2 N*m*s/rad above 140 rad/s (1.4-2.8 N*m over the motor's speed range), w 0.5 rad/s
        ("os19_clutch_centrifugal_shoe_clutch", "outside", 0.0080, 0.0245, 0.91,
         [E("clutch_centrifugal_shoe_clutch", {"capacity_Nm_s_per_rad": 0.2, "engage_speed_rad_s": 140.0,
                                               "slip_width_rad_s": 0.5})]),
    ]
