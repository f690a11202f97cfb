"""Outside mechanisms, nineteenth DEVELOPMENT half (issue 31 part 4, set 19): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first eighteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev18`, :mod:`outside_sealed18`) have, with their laws in
the open. The nineteenth sealed half is :mod:`outside_sealed19`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, mass force, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed19` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 mass force, 14 clutch torque). About half of the fourteen are plain memoryless
laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set
by one simulation against the clean drive of the same seed, for visibility, and not changed after. Checked before the
list was committed: no row is a constant on this drive (each reads a quantity that moves with the strokes, the jaw's
crossings of the gap, the wheel's turns or the carriage's travel), and none is an earlier kind moved to another
balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the TIME SINCE THE LATEST STROKE BEGAN through a RAMP held at its top: a pump on the motor's
   free shaft end charges the press's hydraulic accumulator, which the press empties at each stroke's start; a
   constant-flow pump into a spring accumulator sees a pressure rising linearly with the time since, until the relief
   valve opens at full charge: T*min(1, (t - t_s)/T_c), t_s the latest load pulse's start, on or off (a motor load
   that ramps up after each stroke and holds: the earlier motor loads timed by the stroke are a decay after the
   pulse's falling edge (the third set), a decaying oscillation (the tenth set) and a peak at a set delay (the
   sixteenth set); the first set's process brake on the wheel rises with its actuator's lag only while the pulse is
   on; the seventeenth sealed half's ramp restarts at a period of its own, locked to no stroke; the first set's
   creeping resistance ramps once over the recording, on the carriage);
3. wheel torque x the CARRIAGE's POSITION through a HALF-WAVE RECTIFIED SINE: the tow cable runs from the drum along
   the track over spring-loaded guide rollers at a pitch L; where the cable's clamp rides over a roller it presses it
   down and drags on the cable, hence on the drum: -T*max(0, sin(2*pi*(x - x_0)/L))^2, x the carriage's position
   unwrapped from the run-in's start (a wheel torque of the carriage's travel: the earlier laws of the carriage's
   position act on the carriage (the fifth sealed half's rail joints, a window times its speed; the seventeenth sealed
   half's smooth force, a sine; the eighteenth set's rail sections, a random pattern) or on the motor (the eighteenth
   set's rail-section dynamo, a window times the motor speed); the earlier half-wave sines are of the motor's angle
   (the first set's crank pump), of the wheel's angle (the second sealed half's tooth, the fourteenth set's timing
   linkage) and of the unwrapped wheel angle (the third sealed half's non-integer order));
5. clutch torque x the jaw's ANGLE DIFFERENCE TIMES the SPRING EXTENSION: a pneumatic torsion bellows (an air spring)
   bridges the jaw halves; it is fed from the cable's tension cylinder, so its pressure, hence its centring stiffness,
   follows the cable's extension: -k*(z - z_0)*D, D the jaw's angle difference, in the gap and in contact (a centring
   stiffness across the jaw scheduled by the load's cable: the earlier stiffnesses across the jaw are constant (the
   first sealed half), switched by the pulse (the tenth set), scheduled by the motor speed's square (the fourteenth
   set), cubic (the fifteenth set), or re-anchored (the fourteenth, seventeenth and eighteenth sets); the sixteenth
   set's friction plate pressed by the cable is a dry friction of the slip, not a stiffness of the angle);
7. mass force x the WHEEL's ANGLE through a ONCE-PER-TURN WINDOW: the drum's rope grooving has a crossover (a
   counter-grooved drum): once per turn, over an arc w of the wheel's angle, the rope climbs the crossover and jerks
   the tow cable back: -F while (alpha2 - alpha_0) mod 2*pi < w, else 0 (a rectangular window of the wheel's angle on
   the carriage: the earlier forces of the wheel's angle on the carriage are smooth (the second set's unbalance, a
   cosine; the seventh sealed half's stroke-gated sine); the earlier windows of the wheel's angle are on the wheel
   (the ninth set's Geneva drive, once every N turns); the ninth sealed half's square wave is of the motor's angle, on
   the motor);
9. a2 sensor x the CARRIAGE's POSITION through a COSINE (a tilt into gravity): the carriage's rail undulates with a
   wavelength L (a wavy track); the carriage pitches with the rail's slope, tilting a2's axis into gravity: y = x +
   A*cos(2*pi*(x_c - x_0)/L), x_c the carriage's position unwrapped from the run-in's start (an additive error locked
   to the carriage's travel: the earlier additive sensor errors are of the motor's angle (the first set's rotating
   gravity, the thirteenth set's interference), of the time, of the carriage's or the motor's speed (the fourteenth
   set, the fifteenth sealed half), of the contact state (the fifteenth set); the eighteenth set's rail slopes are a
   force on the carriage, not a reading);
11. wheel torque x the SLIP through a MOVING AVERAGE (a boxcar): an anti-clatter controller averages a slip monitor's
    reading over the last n 0.2 ms scans and drives a hydraulic torque motor on the wheel towards the motor's speed:
    +c*m, m the mean of s = Omega1 - Omega2 over the last n scans (all n = s at the run-in's start) (the earlier
    memories of the slip are a lag, a fill, a delay, a tank, an on-delay, an off-delay, a heat integrator, an impact
    sample, a decaying peak and a rate limiter, none an average over a window; the tenth sealed half's
    boxcar is of the motor's speed, on the motor; the seventeenth set's anti-clatter actuator on the wheel samples the
    slip at the jaw's impacts);
13. motor load moment x the jaw's CONTACT POWER through a DECAYING PEAK: an impact-severity meter on the coupling's
    guard (a peak hold with a bleed of the power the jaw's contact dissipates) sets the motor's eddy-current brake, so
    that the drive half closes on the jaw more softly after hard impacts: c*m, m -> max(P, m*exp(-dt/tau)) every 0.2
    ms, P = |T_c*D'| the contact law's power (0 in the gap; m = P at the run-in's start) (the fifth set's impact
    softening is a lag of the contact's power, on the clutch; the earlier decaying peaks are of the wheel's speed (the
    ninth sealed half), the penetration (the seventh sealed half), the motor's speed (the fourteenth set) and the slip
    (the seventeenth sealed half); no earlier motor load reads the contact's power).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2 0.0498
at its a-priori strength, scaled once x1.51 (T 2 -> 3.011 N*m; a2 0.0744 after); 3 a2 0.0415, scaled once x1.81 (T 2
-> 3.619 N*m; a2 0.0738 after); 5 a2 0.0672; 7 a2 0.0880; 9 a2 0.0707; 11 a2 0.0493, scaled once x1.52 (c 1 -> 1.520
N*m*s/rad; a2 0.0748 after); 13 a2 0.412 -- the others as written (docs/foreign_drives.md "The nineteenth set").
Before it, a 0.4 s run of each row only checked that it simulates.

Memory elements (one per recording) are advanced once per 0.2 ms input segment from the state at the segment's start
(kernel.py "memory"), as in the fourth to eighteenth sets; the memory starts afresh at the run-in's first scan, 2 s
before sample 0. The boxcar (11) is the tenth set's MK_MOVING_MEAN on the slip, the decaying peak (13) the seventh
set's MK_PEAK on the fifth set's XS_CONTACT_POWER; the pump (1) is XF_RAMP of the third set's XS_PULSE_PHASE (periodic
with the pulse train, so in the settled start's period map), the rollers (3) XF_SIN_POSITIVE of the fifth set's
XS_MASS_POSITION, the bellows (5) XS_JAW_ANGLE times XF_CLIP of the extension (z - z_0, the clip never reached), the
crossover (7) XF_PERIODIC_GATE of alpha2 (re-referenced by whole turns, so its residue mod 2*pi is the wheel's angle),
the tilt (9) a sensor form in numpy on the carriage's position (the sensor chain's states gain it: drive.mass_position,
the kernel's XS_MASS_POSITION at each sample). No kernel change for this set.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import set_memory


# 1. motor load moment x the time since the latest stroke began through a ramp held at its top
class MotorAccumulatorChargingPump(OutsideForm):
    name = "motor_accumulator_charging_pump"
    half = "dev19"
    balance = "motor_load_moment"
    depends_on = ("load_pulse",)
    description = ("a pump on the motor's free shaft end charges the press's hydraulic accumulator, which the press "
                   "empties at each stroke's start; its pressure, hence the pump's torque, rises linearly with the time "
                   "since until the relief valve opens at full charge: T*min(1, (t - t_s)/T_c), t_s the latest load "
                   "pulse's start (the pulse on or off)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T (at full charge)"),
                  Param("charge_time_s", "s", (1e-3, 10.0), "T_c"))
    note = "a motor load that ramps up after each stroke's start and holds"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_PULSE_PHASE, K.XF_RAMP, p["charge_time_s"], 0.0, 0.0))

    @staticmethod
    def torque(since_stroke_s, p):
        q = np.asarray(since_stroke_s, dtype=np.float64) / p["charge_time_s"]
        return p["torque_Nm"] * np.clip(q, 0.0, 1.0)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * min(1, (t - t_s)/{p['charge_time_s']:.6g} s), t_s the "
                "latest load pulse's start (on or off)")

    def plugin(self, p):
        return _plugin("MotorAccumulatorChargingPump", self.name, "motor_load_moment_pu", self.description, [
            ("amplitude_pu", "p.u.", (0.0, 2.0), "T / T_b (T_b = 20 N*m)"),
            ("charge_time_s", "s", (1e-3, 10.0), "T_c")],
            "pulse_time_s, amplitude_pu, charge_time_s",
            "amplitude_pu * fmin(1.0, pulse_time_s / charge_time_s)", "fmin")


# 3. wheel torque x the carriage's position through a half-wave rectified sine
class WheelCableGuideRollers(OutsideForm):
    name = "wheel_cable_guide_rollers"
    half = "dev19"
    balance = "wheel_torque"
    depends_on = ("wheel_angle", "spring_extension")     # x = r*alpha2 - z
    description = ("the tow cable runs from the drum along the track over spring-loaded guide rollers at a pitch L; "
                   "where the cable's clamp rides over a roller it presses it down and drags on the cable, hence on the "
                   "drum: -T*max(0, sin(2*pi*(x - x_0)/L))^2, x the carriage's position unwrapped from the run-in's "
                   "start")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("pitch_m", "m", (0.01, 100.0), "L"),
                  Param("offset_m", "m", (-100.0, 100.0), "x_0"))
    note = "a wheel torque of the carriage's travel (a half-wave rectified sine)"

    def apply(self, b, p):
        k = 2.0 * np.pi / p["pitch_m"]
        add_term(b, "wheel_torque", -p["torque_Nm"],
                 (K.XS_MASS_POSITION, K.XF_SIN_POSITIVE, k, -k * p["offset_m"], 2.0), nonperiodic=True)

    @staticmethod
    def torque(x, p):
        k = 2.0 * np.pi / p["pitch_m"]
        s = np.sin(k * np.asarray(x, dtype=np.float64) - k * p["offset_m"])
        return -p["torque_Nm"] * np.where(s > 0.0, s, 0.0) ** 2

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * max(0, sin(2*pi*(x - {p['offset_m']:.6g} m)/"
                f"{p['pitch_m']:.6g} m))^2, x the carriage's position unwrapped from the run-in's start")


# 5. clutch torque x the jaw's angle difference times the spring extension
class ClutchTensionFedTorsionBellows(OutsideForm):
    name = "clutch_tension_fed_torsion_bellows"
    half = "dev19"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration", "spring_extension")
    description = ("a pneumatic torsion bellows bridges the jaw halves, fed from the cable's tension cylinder: its "
                   "pressure, hence its centring stiffness, follows the cable's extension: -k*(z - z_0)*D, D the jaw's "
                   "angle difference, in the gap and in contact")
    parameters = (Param("stiffness_Nm_per_rad_m", "N*m/(rad*m)", (0.0, 1e5), "k (per m of extension)"),
                  Param("reference_m", "m", (0.0, 1.0), "z_0"))
    note = "a centring stiffness across the jaw scheduled by the load's cable"

    def apply(self, b, p):
        add_term(b, "clutch_torque", -p["stiffness_Nm_per_rad_m"], (K.XS_JAW_ANGLE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_SPRING_EXTENSION, K.XF_CLIP, 10.0, -p["reference_m"], 0.0))   # z - z_0 (|z - z_0| < 10 m)

    @staticmethod
    def torque(d, z, p):
        return -p["stiffness_Nm_per_rad_m"] * (np.asarray(z, dtype=np.float64) - p["reference_m"]) * np.asarray(
            d, dtype=np.float64)

    def law(self, p):
        return (f"clutch torque += -{p['stiffness_Nm_per_rad_m']:.6g} N*m/(rad*m) * (z - {p['reference_m']:.6g} m) * D, "
                "D the jaw's angle difference, in the gap and in contact")

    def plugin(self, p):
        return _plugin("ClutchTensionFedTorsionBellows", self.name, "coupling_torque_Nm", self.description, [
            ("stiffness_Nm_per_rad_m", "N*m/(rad*m)", (0.0, 1e5), "k"),
            ("reference_m", "m", (0.0, 1.0), "z_0")],
            "delta, z, stiffness_Nm_per_rad_m, reference_m",
            "-stiffness_Nm_per_rad_m * (z - reference_m) * delta", "")


# 7. mass force x the wheel's angle through a once-per-turn window
class MassDrumGroovingCrossover(OutsideForm):
    name = "mass_drum_grooving_crossover"
    half = "dev19"
    balance = "mass_force"
    depends_on = ("wheel_angle",)
    description = ("the drum's rope grooving has a crossover: once per turn, over an arc w of the wheel's angle, the "
                   "rope climbs it and jerks the tow cable back: -F while (alpha2 - alpha_0) mod 2*pi < w, else 0")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("arc_rad", "rad", (0.0, 2.0 * np.pi), "w"),
                  Param("angle_rad", "rad", (-np.pi, np.pi), "alpha_0"))
    note = "a rectangular window of the wheel's angle on the carriage, once per turn"

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_N"],
                 (K.XS_ALPHA2, K.XF_PERIODIC_GATE, 2.0 * np.pi, p["angle_rad"], p["arc_rad"]), nonperiodic=True)

    @staticmethod
    def force(alpha2, p):
        q = np.mod(np.asarray(alpha2, dtype=np.float64) - p["angle_rad"], 2.0 * np.pi)
        return np.where(q < p["arc_rad"], -p["force_N"], 0.0)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N while (alpha2 - {p['angle_rad']:.6g}) mod 2*pi < "
                f"{p['arc_rad']:.6g} rad, else 0")


# 9. a2 sensor x the carriage's position through a cosine (a tilt into gravity)
class A2WavyTrackTilt(OutsideForm):
    name = "a2_wavy_track_tilt"
    half = "dev19"
    stage = "sensor"
    order = 0                      # the sensing element's axis
    uses_states = True
    balance = "sensor"
    channel = "a2"
    depends_on = ("mass_acceleration", "wheel_angle", "spring_extension")     # x_c = r*alpha2 - z
    description = ("the carriage's rail undulates with a wavelength L; the carriage pitches with the rail's slope, "
                   "tilting a2's axis into gravity: y = x + A*cos(2*pi*(x_c - x_0)/L), x_c the carriage's position "
                   "unwrapped from the run-in's start")
    parameters = (Param("amplitude_m_s2", "m/s^2", (0.0, 10.0), "A (g times the slope's amplitude)"),
                  Param("wavelength_m", "m", (0.01, 100.0), "L"),
                  Param("offset_m", "m", (-100.0, 100.0), "x_0"))
    note = "an additive a2 error locked to the carriage's travel (its tilt into gravity on a wavy rail)"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], states["mass_position"], p)

    @staticmethod
    def read(a2, x, p):
        q = 2.0 * np.pi * (np.asarray(x, dtype=np.float64) - p["offset_m"]) / p["wavelength_m"]
        return np.asarray(a2, dtype=np.float64) + p["amplitude_m_s2"] * np.cos(q)

    def law(self, p):
        return (f"a2 sensor = a2 + {p['amplitude_m_s2']:.6g} m/s^2 * cos(2*pi*(x - {p['offset_m']:.6g} m)/"
                f"{p['wavelength_m']:.6g} m), x the carriage's position unwrapped from the run-in's start")


# 11. wheel torque x the slip through a moving average
class WheelSlipAveragingAntiClatter(OutsideForm):
    name = "wheel_slip_averaging_anti_clatter"
    half = "dev19"
    balance = "wheel_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an anti-clatter controller averages a slip monitor's reading over the last n 0.2 ms scans and "
                   "drives a hydraulic torque motor on the wheel towards the motor's speed: +c*m, m the mean of "
                   "s = Omega1 - Omega2 over the last n scans (all n = s at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "c"),
                  Param("window_scans", "-", (1.0, float(K.MEMORY_RING)), "n (a whole number of 0.2 ms scans)"))
    note = "a wheel torque of the slip averaged over a window (a boxcar)"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_MOVING_MEAN, K.XS_JAW_SPEED, float(int(p["window_scans"])))
        add_term(b, "wheel_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def means(s_at_scans, n):
        """The boxcar's output after each scan from the n-th on (the mean of the slip at the starts of that scan and the
        n - 1 before it), from the slip at the scans' starts."""
        s = np.asarray(s_at_scans, dtype=np.float64)
        c = np.concatenate([[0.0], np.cumsum(s)])
        return (c[int(n):] - c[:-int(n)]) / int(n)

    def law(self, p):
        return (f"wheel torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * m, m the mean of Omega1 - Omega2 "
                f"over the last {int(p['window_scans'])} 0.2 ms scans")


# 13. motor load moment x the jaw's contact power through a decaying peak
class MotorImpactSeverityBrake(OutsideForm):
    name = "motor_impact_severity_brake"
    half = "dev19"
    balance = "motor_load_moment"
    depends_on = ("clutch_penetration", "motor_speed", "wheel_speed")    # |T_c*D'|, D' = Omega1 - Omega2
    description = ("an impact-severity meter on the coupling's guard, a peak hold with a bleed of the power the jaw's "
                   "contact dissipates, sets the motor's eddy-current brake: c*m, m -> max(P, m*exp(-dt/tau)) every "
                   "0.2 ms, P = |T_c*D'| the contact law's power (0 in the gap; m = P at the run-in's start)")
    parameters = (Param("coefficient_Nm_per_W", "N*m/W", (0.0, 10.0), "c"),
                  Param("decay_s", "s", (1e-4, 100.0), "tau"))
    note = "a motor brake set by the jaw's recent peak contact power"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PEAK, K.XS_CONTACT_POWER, p["decay_s"])
        add_term(b, "motor_load_moment", p["coefficient_Nm_per_W"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def peaks(power_at_scans, decay_s, dt, m0=None):
        """The held peak m after each scan from the contact power at the scans' starts (m0 before the first; None: the
        first scan is the run-in's start)."""
        out, m, f = [], m0, float(np.exp(-dt / decay_s))
        for x in np.asarray(power_at_scans, dtype=np.float64).tolist():
            if m is None:
                m = x
            else:
                m = max(x, m * f)
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_per_W']:.6g} N*m/W * m, m -> max(P, m*exp(-0.2 ms/"
                f"{p['decay_s']:.6g} s)) every 0.2 ms, P = |T_c*D'| the power the jaw's contact law dissipates (0 in "
                "the gap)")


FORM_CLASSES = (MotorAccumulatorChargingPump, WheelCableGuideRollers, ClutchTensionFedTorsionBellows,
                MassDrumGroovingCrossover, A2WavyTrackTilt, WheelSlipAveragingAntiClatter, MotorImpactSeverityBrake)
