"""Outside mechanisms, twentieth SEALED half (issue 31 part 4, set 20): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev20`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the SPRING EXTENSION through a PWM ACTUATOR: a tension controller pulses a motor-side eddy
   brake through an on/off valve: at the start of each period of n 0.2 ms scans it takes the duty clip((z - z_0)/w,
   0, 1) from the extension and keeps the valve open for the first round(duty*n) scans of the period: T*m, m = 1
   while open, else 0 (the period starts at the run-in's first scan) (the sixth set's PWM brake reads the wheel's
   speed, on the wheel; the earlier memories of the extension on the motor are a peak held since the stroke began
   (the sixteenth set), an off-delay (the seventeenth sealed half) and a boxcar (the eighteenth sealed half));
4. wheel torque x the CARRIAGE's SPEED through a THREE-POINT STEP CONTROLLER: a line-speed controller trims the drum's
   brake through a motorised valve: one step up each T_s the carriage's speed stays above v_r + d, one step down each
   T_s it stays below v_r - d, between 0 and N steps: -T*m, m the steps (m = 0 at the run-in's start; the scans
   counted every 0.2 ms) (the eighth sealed half's step controller reads the motor's speed, on the motor; the earlier
   memory of the carriage's speed on the wheel is the eighteenth set's peak held since the stroke began);
6. clutch torque x the SLIP through a SELF-EXCITED OSCILLATOR: the felt dust seal between the jaw halves squeals when
   the drive half overruns the wheel: a van der Pol oscillator of its own frequency f whose negative damping grows with
   the slip's excess over s_c: T*X/2, X'' = w*g*(s - s_c)*(1 - X^2)*X' - w^2*X, w = 2*pi*f, s = Omega1 - Omega2 (X =
   1e-3, X' = 0 at the run-in's start; a floor keeps a seed amplitude), in the gap and in contact (the earlier squeals
   are of the wheel's speed, on the wheel (the eighth set), and of the extension, on the carriage (the nineteenth
   sealed half); the earlier memories of the slip across the jaw are a lag, a tank, a delay, an on-delay, an off-delay,
   a heat integrator, a one-shot, a rate limiter and a thermal cut-out);
8. mass force x the SPRING EXTENSION through a TANK: the cable's tension cylinder is a piston pump the cable's pull
   works: it fills the carriage's hold-back cylinder at a flow a*z, which drains through an orifice, b*sqrt(h): -F*h,
   h' = a*z - b*sqrt(h), h >= 0 (h = 0 at the run-in's start) (the earlier tanks are filled by the wheel's speed (the
   twelfth set, on the wheel), the slip (the thirteenth set, across the jaw) and the pulse (the eighth sealed half, on
   the carriage); the earlier memories of the extension on the carriage are a toggle, a play, a stroke sample, a
   rate limiter, a delay, a Dahl element, a one-shot and a squeal);
10. a2 sensor x a BASELINE RESTORER (a one-sided envelope follower): a2's module has a DC restorer, a clamp as in
    pulse electronics: its baseline b follows the signal's lower envelope, taking any sample below it at once and
    creeping up at R otherwise, and is subtracted: b[n] = min(x[n], b[n-1] + R/fs), y = x - b (b = x at the
    pre-roll's first sample) (the earlier zero-setting memories of a sensor are a periodic tare of the mean (the fifth
    set's autozero), a first-order high-pass (the third and sixteenth sealed halves) and a play (the ninth set's loose
    seismic mass, two-sided and not subtracted));
12. mass force x the TIME SINCE THE LATEST STROKE BEGAN through a WINDOW at a set delay: the press's strip gripper
    grips the strip from d to d + w after each stroke began; the strip, threaded through the carriage's guide, holds
    the carriage back while it is gripped: -F while d <= t - t_s < d + w, else 0, t_s the latest load pulse's start,
    on or off (the third set's pneumatic hold-back on the carriage rises after a delay and holds to the next stroke;
    the sixteenth set's flying shear is a smooth peak while the pulse is on, on the motor; the nineteenth set's pump
    is a ramp held at its top, on the motor);
14. clutch torque x the jaw's ANGLE DIFFERENCE through a SIGN (a preload): a pre-compressed centring spring cartridge
    across the jaw pushes back by its preload T_0 as soon as the jaw leaves its centre, whichever way: -T_0*tanh(D/w),
    w a small smoothing angle, D the jaw's angle difference, in the gap and in contact (the earlier laws of the jaw's
    angle alone are linear, a power, a sine (the eighth set's ball detent), a face pull (the seventh set), a dead zone
    (the ninth sealed half's bumpers) and a snap-through of the overlap (the ninth set), none a constant torque).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 2 a2 0.0455
at its a-priori strength, scaled once x1.65 (T 2 -> 3.295 N*m; a2 0.0750 after); 4 a2 0.0663; 6 a2 0.00046, BELOW;
8 a2 0.0242, BELOW; 10 a2 1.12; 12 a2 0.108; 14 a2 0.0644 -- 4, 10, 12 and 14 as written.

Two rows are left below the criterion, as written, and said so here rather than made visible by force:
- the seal's squeal (6): its a-priori growth (2 s/rad) made a 0.4 s smoke run not finish in 500 s (the oscillator's
  eight Euler steps a scan are unstable at that negative damping and the jaw's contact then chatters), so it was set to
  0.2 s/rad before the visibility run; at that, the oscillator grows only in the gap traversals' slip peaks and rarely
  reaches its limit cycle (|T| > 0.04 N*m over 18 % of the recording, at most 0.69 N*m), and a 120 Hz torque across
  the jaw hardly reaches the carriage: a2 0.00046. One scaling would be x163 (326 N*m, beyond the torque's bound of
  50 N*m). After the visibility run three other conditions were tried, once each, to see whether any would act (no
  diagnose; none taken): 120 Hz at 0.4 s/rad and at 0.2 s/rad, both from a slip of 0, did not finish in 90 s and 60 s
  (the same chatter), 60 Hz at 0.3 s/rad and 30 Hz at 0.5 s/rad from 0.5 rad/s gave a2 0.00085 and 0.0013, 10 Hz at
  2 s/rad from 0.5 rad/s gave a2 0.0080 (15 Hz at 1 s/rad from 0 did not finish in 45 s). The row stays as committed
  before the visibility run; it is the set's test of a mechanism the recording barely shows.
- the tension-pumped hold-back (8): a tank of the extension is mostly a steady hold-back (the extension never nears 0:
  the fill follows z^2 within about +-4 %), a2 0.0242. Scaled once (x3.09, F 9.282 N) the drive ran away: the
  hold-back's rise with the extension outgrew the spring's (k z = 30 N + F*(a*z/b)^2 has no root), the hold-back
  reaching 925 N and a2 9.4: not a drive. Left as written, below the criterion.

A check that each memory moves (no figure used for a strength; the visibility run's recordings and the same specs
without noise): the PWM brake (2) is open 45 % of the recording, switching about twice a period (799 switches in 4 s);
the step trim (4) climbed in bursts to its top (6 steps) with the suite's noise, above 0 over 13 % of the recording, and
noise-free steps to 1 in four bursts, 6 % of it; the tank's fill (8) stays within 1.21-1.33 (the hold-back moves the
extension up to 0.325-0.353 m); the restorer (10) moves a2's mean by 0.93 m/s^2 with a spread of 0.61 m/s^2.

Thin (read off the laws and the clean drive, no diagnose; recorded here only): the PWM brake (2) is a 100 Hz pulse train
whose width follows the extension; the step trim (4) acts in bursts and rests at 0 most of the time; the restorer (10)
shifts a2 by a slowly varying offset (a2's mean moves by about 0.9 m/s^2), far above the criterion; the gripper (12) is a
window at a fixed delay in each stroke (periodic with the pulse train); the cartridge (14) is a torque of fixed size
whose sign follows the jaw's side, so in contact it is a steady torque against the drive side, switching in the gap.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory
from .outside_dev6 import set_extra


# 2. motor load moment x the spring extension through a PWM actuator
class MotorTensionPwmEddyBrake(OutsideForm):
    name = "motor_tension_pwm_eddy_brake"
    half = "sealed20"
    balance = "motor_load_moment"
    depends_on = ("spring_extension",)
    description = ("a tension controller pulses a motor-side eddy brake through an on/off valve: at the start of each "
                   "period of n 0.2 ms scans it takes the duty clip((z - z_0)/w, 0, 1) from the extension and keeps "
                   "the valve open for the first round(duty*n) scans of the period: T*m, m = 1 while open, else 0 (the "
                   "periods counted from the run-in's first scan)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("zero_duty_m", "m", (0.0, 1.0), "z_0"),
                  Param("full_duty_span_m", "m", (1e-4, 1.0), "w"),
                  Param("period_s", "s", (4e-4, 1.0), "n*0.2 ms (a whole number of scans)"))
    note = "a motor brake pulsed by a PWM valve whose duty the extension sets"

    def apply(self, b, p):
        n = segments(p["period_s"], f"{self.name}: period_s")
        set_memory(b, self.name, K.MK_PWM, K.XS_SPRING_EXTENSION, float(n), p["zero_duty_m"], p["full_duty_span_m"])
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * m, m = 1 for the first round(d*n) of each period of "
                f"n = {p['period_s']:.6g} s/0.2 ms scans, d = clip((z - {p['zero_duty_m']:.6g} m)/"
                f"{p['full_duty_span_m']:.6g} m, 0, 1) taken at the period's start, else 0")


# 4. wheel torque x the carriage's speed through a three-point step controller
class WheelLineSpeedStepTrim(OutsideForm):
    name = "wheel_line_speed_step_trim"
    half = "sealed20"
    balance = "wheel_torque"
    depends_on = ("mass_speed",)
    description = ("a line-speed controller trims the drum's brake through a motorised valve: one step up each T_s the "
                   "carriage's speed stays above v_r + d, one step down each T_s it stays below v_r - d, between 0 and "
                   "N steps: -T*m, m the steps (m = 0 at the run-in's start; the scans counted every 0.2 ms)")
    parameters = (Param("torque_per_step_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("reference_m_s", "m/s", (0.0, 100.0), "v_r"),
                  Param("dead_band_m_s", "m/s", (0.0, 10.0), "d"),
                  Param("step_time_s", "s", (2e-4, 10.0), "T_s"),
                  Param("steps", "-", (1.0, 1000.0), "N"))
    note = "a wheel brake stepped by a three-point controller of the carriage's speed"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_STEP, K.XS_MASS_SPEED, p["reference_m_s"], p["dead_band_m_s"],
                   p["step_time_s"])
        set_extra(b, float(int(p["steps"])))
        add_term(b, "wheel_torque", -p["torque_per_step_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_per_step_Nm']:.6g} N*m * m, m stepped up each {p['step_time_s']:.6g} s "
                f"the carriage's speed stays above {p['reference_m_s']:.6g} + {p['dead_band_m_s']:.6g} m/s, down each "
                f"{p['step_time_s']:.6g} s it stays below {p['reference_m_s']:.6g} - {p['dead_band_m_s']:.6g} m/s, "
                f"within 0..{int(p['steps'])} (scanned every 0.2 ms)")


# 6. clutch torque x the slip through a self-excited oscillator
class ClutchDustSealSqueal(OutsideForm):
    name = "clutch_dust_seal_squeal"
    half = "sealed20"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("the felt dust seal between the jaw halves squeals when the drive half overruns the wheel: a van der "
                   "Pol oscillator X'' = w*g*(s - s_c)*(1 - X^2)*X' - w^2*X, w = 2*pi*f, s = Omega1 - Omega2, advanced "
                   "every 0.2 ms from X = 1e-3 at the run-in's start, its amplitude kept at least 1e-3; the seal's "
                   "torque across the jaw T*X/2, in the gap and in contact")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T: the torque at the limit cycle's amplitude (X ~ 2)"),
                  Param("frequency_hz", "Hz", (10.0, 500.0), "f"),
                  Param("growth_per_rad_s", "s/rad", (0.0, 1000.0), "g: the negative damping per rad/s of slip above "
                        "s_c"),
                  Param("onset_rad_s", "rad/s", (-50.0, 50.0), "s_c"))
    note = "a self-excited oscillator across the jaw whose negative damping the slip sets"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_SQUEAL, K.XS_JAW_SPEED, 2.0 * np.pi * p["frequency_hz"],
                   p["growth_per_rad_s"], p["onset_rad_s"])
        add_term(b, "clutch_torque", 0.5 * p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        w = 2.0 * np.pi * p["frequency_hz"]
        return (f"clutch torque += {p['torque_Nm']:.6g} N*m * X/2, X'' = {w:.6g}*{p['growth_per_rad_s']:.6g}*(Omega1 - "
                f"Omega2 - {p['onset_rad_s']:.6g} rad/s)*(1 - X^2)*X' - {w:.6g}^2*X (advanced every 0.2 ms, amplitude "
                "at least 1e-3), in the gap and in contact")


# 8. mass force x the spring extension through a tank
class MassTensionPumpedHoldback(OutsideForm):
    name = "mass_tension_pumped_holdback"
    half = "sealed20"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("the cable's tension cylinder, a piston pump the cable's pull works, fills the carriage's hold-back "
                   "cylinder at a flow a*z, which drains through an orifice, b*sqrt(h): -F*h, h' = a*z - b*sqrt(h), "
                   "h >= 0, advanced every 0.2 ms (h = 0 at the run-in's start)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F (per unit of fill)"),
                  Param("inflow_per_m_s", "1/(m*s)", (0.0, 1e5), "a"),
                  Param("outflow_per_s", "1/s", (0.0, 1e5), "b"))
    note = "a hold-back on the carriage from a tank the cable's extension fills"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_TANK, K.XS_SPRING_EXTENSION, p["inflow_per_m_s"], p["outflow_per_s"])
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * h, h -> max(0, h + dt*({p['inflow_per_m_s']:.6g}/(m*s) * z - "
                f"{p['outflow_per_s']:.6g}/s * sqrt(h))) every 0.2 ms")


# 10. a2 sensor x a baseline restorer
class A2BaselineRestorer(OutsideForm):
    name = "a2_baseline_restorer"
    half = "sealed20"
    stage = "sensor"
    order = 1                      # the module, after the sensing element
    balance = "sensor"
    channel = "a2"
    depends_on = ("mass_acceleration",)
    description = ("a2's module has a DC restorer (a clamp): its baseline b follows the signal's lower envelope, taking "
                   "any sample below it at once and creeping up at R otherwise, and k of it is subtracted: b[n] = "
                   "min(x[n], b[n-1] + R/fs), y = x - k*b (b = x at the pre-roll's first sample)")
    parameters = (Param("creep_m_s3", "m/s^3", (0.0, 1e5), "R"),
                  Param("clamp_gain", "-", (0.0, 1.0), "k (1: the whole baseline)"))
    note = "a2 less its lower envelope (a one-sided baseline follower)"

    def apply_signal(self, sig, p, t, fs):
        sig["a2"] = self.read(sig["a2"], fs, p)

    @staticmethod
    def baseline(x, fs, p):
        """b[n] = min(x[n], b[n-1] + R/fs), b[0] = x[0]: the running minimum of x less a ramp, plus the ramp."""
        x = np.asarray(x, dtype=np.float64)
        ramp = np.arange(x.size) * (p["creep_m_s3"] / fs)
        return np.minimum.accumulate(x - ramp) + ramp

    @classmethod
    def read(cls, x, fs, p):
        x = np.asarray(x, dtype=np.float64)
        if p["clamp_gain"] == 0.0:
            return x
        return x - p["clamp_gain"] * cls.baseline(x, fs, p)

    def law(self, p):
        return (f"a2 sensor = a2 - {p['clamp_gain']:.6g}*b, b[n] = min(a2[n], b[n-1] + {p['creep_m_s3']:.6g} m/s^3/fs) "
                "(b = a2 at the pre-roll's first sample)")


# 12. mass force x the time since the latest stroke began through a window at a set delay
class MassStripGripperHoldback(OutsideForm):
    name = "mass_strip_gripper_holdback"
    half = "sealed20"
    balance = "mass_force"
    depends_on = ("load_pulse",)
    description = ("the press's strip gripper grips the strip from d to d + w after each stroke began; the strip, "
                   "threaded through the carriage's guide, holds the carriage back while gripped: -F while d <= t - "
                   "t_s < d + w, else 0, t_s the latest load pulse's start (on or off)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("delay_s", "s", (0.0, 10.0), "d"),
                  Param("width_s", "s", (0.0, 10.0), "w"))
    note = "a hold-back on the carriage in a window at a set delay after each stroke's start"

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_N"],
                 (K.XS_PULSE_PHASE, K.XF_PERIODIC_GATE, 1000.0, p["delay_s"], p["width_s"]),
                 nonperiodic=True)   # out of the settled start's period map: its Newton fails on the window's edges

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N while {p['delay_s']:.6g} s <= t - t_s < "
                f"{p['delay_s'] + p['width_s']:.6g} s, else 0, t_s the latest load pulse's start (on or off)")


# 14. clutch torque x the jaw's angle difference through a sign (a preload)
class ClutchPreloadedCentringCartridge(OutsideForm):
    name = "clutch_preloaded_centring_cartridge"
    half = "sealed20"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("a pre-compressed centring spring cartridge across the jaw pushes back by its preload as soon as the "
                   "jaw leaves its centre, whichever way: -T_0*tanh(D/w), w a small smoothing angle, D the jaw's angle "
                   "difference, in the gap and in contact")
    parameters = (Param("preload_Nm", "N*m", (0.0, 50.0), "T_0"),
                  Param("smoothing_rad", "rad", (1e-5, 1.0), "w"))
    note = "a constant centring torque across the jaw (a preloaded spring's sign)"

    def apply(self, b, p):
        add_term(b, "clutch_torque", -p["preload_Nm"], (K.XS_JAW_ANGLE, K.XF_TANH, p["smoothing_rad"], 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += -{p['preload_Nm']:.6g} N*m * tanh(D/{p['smoothing_rad']:.6g} rad), D the jaw's angle "
                "difference, in the gap and in contact")


FORM_CLASSES = (MotorTensionPwmEddyBrake, WheelLineSpeedStepTrim, ClutchDustSealSqueal, MassTensionPumpedHoldback,
                A2BaselineRestorer, MassStripGripperHoldback, ClutchPreloadedCentringCartridge)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 20100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 2 N*m, the duty from 0 at 0.28 m to 1 at 0.32 m, a 10 ms period a priori, a2 0.0455: scaled once x1.65
        ("os20_motor_tension_pwm_eddy_brake", "outside", 0.0078, 0.0255, 0.95,
         [E("motor_tension_pwm_eddy_brake", {"torque_Nm": 3.295, "zero_duty_m": 0.28, "full_duty_span_m": 0.04,
                                             "period_s": 0.01})]),
        # 0.5 N*m a step, up to 6 steps, around 22.73 m/s +- 0.03 m/s, a step each 10 ms
        ("os20_wheel_line_speed_step_trim", "outside", 0.0070, 0.0290, 0.92,
         [E("wheel_line_speed_step_trim", {"torque_per_step_Nm": 0.5, "reference_m_s": 22.73, "dead_band_m_s": 0.03,
                                           "step_time_s": 0.01, "steps": 6.0})]),
        # 2 N*m at 120 Hz, growing above a slip of 1 rad/s by 0.2 s/rad (written 2 s/rad first: its 0.4 s smoke run did
        # not finish in 500 s, the oscillator's eight Euler steps a scan unstable at that negative damping; set to 0.2
        # before any visibility run); a2 0.00046 in the visibility run: left as written, BELOW the criterion (one scaling
        # would be x163, 326 N*m, beyond its bounds; other conditions tried after, see the module's docstring)
        ("os20_clutch_dust_seal_squeal", "outside", 0.0084, 0.0230, 0.97,
         [E("clutch_dust_seal_squeal", {"torque_Nm": 2.0, "frequency_hz": 120.0, "growth_per_rad_s": 0.2,
                                        "onset_rad_s": 1.0})]),
        # 3 N per unit of fill; the fill about 1 at 0.3 m, following the extension over about 50 ms; a2 0.0242 in the
        # visibility run: left as written, BELOW the criterion (scaled once, x3.09, the drive ran away: see the
        # module's docstring)
        ("os20_mass_tension_pumped_holdback", "outside", 0.0065, 0.0310, 0.90,
         [E("mass_tension_pumped_holdback", {"force_N": 3.0, "inflow_per_m_s": 133.3, "outflow_per_s": 40.0})]),
        ("os20_clean_w7.5_eta0.0250_n0.92", "clean", 0.0075, 0.0250, 0.92, []),
        # creeping up at 10 m/s^3, the whole baseline subtracted
        ("os20_a2_baseline_restorer", "outside", 0.0069, 0.0275, 0.94,
         [E("a2_baseline_restorer", {"creep_m_s3": 10.0, "clamp_gain": 1.0})]),
        # 3 N from 0.1 s to 0.14 s after each stroke's start
        ("os20_mass_strip_gripper_holdback", "outside", 0.0082, 0.0240, 0.96,
         [E("mass_strip_gripper_holdback", {"force_N": 3.0, "delay_s": 0.1, "width_s": 0.04})]),
        # 1.5 N*m, smoothed over 5 mrad
        ("os20_clutch_preloaded_centring_cartridge", "outside", 0.0072, 0.0260, 0.93,
         [E("clutch_preloaded_centring_cartridge", {"preload_Nm": 1.5, "smoothing_rad": 0.005})]),
    ]
