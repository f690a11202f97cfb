"""Outside mechanisms, eighteenth DEVELOPMENT half (issue 31 part 4, set 18): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first seventeen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev17`, :mod:`outside_sealed17`) have, with their laws in
the open. The eighteenth sealed half is :mod:`outside_sealed18`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (clutch
torque, motor load moment, mass force, wheel torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed18` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 motor load moment, 14 wheel torque). About half of the fourteen are plain
memoryless laws of new kinds, half have a memory or a limit of their own (here: 1, 5, 9, 13 memoryless; 3, 7, 11 with
a memory). Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each
strength is set by one simulation against the clean drive of the same seed, for visibility, and not changed after.
Checked before the list was committed: no row is a constant on this drive (each reads a quantity that moves with the
strokes, the jaw's crossings of the gap or the carriage's travel), and none is an earlier kind moved to another
balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the CARRIAGE's POSITION through a WINDOW, times the motor speed: a dynamo on the motor's free
   shaft end feeds the carriage's heaters through a sectioned conductor rail; its collector shoe is on a live section
   for a length l of every section pitch L, and only then does the dynamo carry a load (a generator, proportional to
   its speed): c*Omega1 while (x - x_0) mod L < l, else 0, x the carriage's position unwrapped from the run-in's start
   (a motor load switched by the carriage's travel: the earlier motor windows are of the motor's own angle (the ninth
   sealed half's rotary distributor valve), of the pulse count (the nth-stroke pierce) and of the time; the fifth
   sealed half's rail joints are windows of the position on the carriage itself; the earlier motor loads of the
   carriage read its speed against the motor rim's (the first set's roller coupling));
3. wheel torque x the CARRIAGE's SPEED through a PEAK HELD SINCE EACH STROKE BEGAN: a stroke-by-stroke overspeed
   limiter: a drag pointer on the carriage's tacho, reset by the press's valve at each stroke's start, holds the
   highest carriage speed since, and a proportional brake on the wheel acts on its excess over v_r: -c*max(0, m - v_r),
   m -> v at each load pulse's first 0.2 ms scan, else max(m, v) (m = v at the run-in's start) (the fifteenth set's
   peak held since the stroke is of the extension, on the wheel's cable tensioner, the sixteenth set's on the motor;
   the fifteenth set's carriage-runaway brake on the wheel reads the carriage's speed without a memory; the earlier
   memories of the carriage's speed are a delay, a lag, an on-delay, a resonator, a run-to-run, an impact sample, a
   since-stroke integral, a slip hub, a rattle, a rate-state, all on the carriage);
5. clutch torque x the slip through an INDUCTION (KLOSS) CURVE: an eddy-current slip coupling beside the jaw (a drum
   on one shaft, an excited pole wheel on the other): its torque rises with the slip up to a pull-out torque T_k at the
   slip s_k and falls beyond: 2*T_k*(s/s_k)/(1 + (s/s_k)^2), s = Omega1 - Omega2, from the motor to the wheel, in the gap
   and in contact (a slip coupling whose torque peaks and falls again: the earlier slip couplings are linear from zero,
   one-way, hydrodynamic (the slip times the motor speed), a hysteresis coupling (tanh), of the second power, with a
   dead zone, gated, or with a memory; the eighth sealed half's eddy rail brake has the same characteristic of the
   carriage's own speed, braking the carriage against the ground, not coupling two shafts by their slip);
7. mass force x the CARRIAGE's SPEED through a LATCH RE-ARMED AT EACH STROKE: an overspeed catch on the carriage's rail
   wheel (a centrifugal pawl) drops a drag shoe onto the rail once the carriage's speed passes v_t and holds it down
   until the press's valve lifts it at the next stroke's start: -F*m, m -> 0 at each load pulse's first 0.2 ms scan,
   then m -> 1 at a scan with v > v_t (m = 1 at the run-in's start if v > v_t) (the seventh set's debounced overspeed
   brake is an on-delay of the carriage's speed, released as soon as the speed falls; the first sealed half's overspeed
   brake is memoryless; the earlier latches are of the wheel's speed and of the extension, both on the wheel);
9. a2 sensor x a2 TIMES a1 (a multiplicative crosstalk): a1's and a2's conditioners share one reference; a1's signal
   current loads it, so a2's gain follows a1's signal: y = x*(1 + g*a1), a1 the acceleration at a1's sensing element
   (a gain modulated by the other channel: the first sealed half's channel crosstalk adds a part of a1 to a2; the
   earlier gain modulations follow the load pulse (the supply sag), the time (the reference ripple), the motor's angle
   (the slip ring), the extension (the seventeenth set's strain gain), a2's own level (the bilinear gain, the
   auto-ranging, the AGC));
11. clutch torque x the jaw's ANGLE DIFFERENCE through a RATE LIMITER (a spring anchored on a creeping cylinder): a
    torsion bar bridging the jaw halves is anchored on the drive half through a small hydraulic rotary actuator whose
    pressure-compensated flow-control valve lets it creep at most R rad/s whatever the torque: -k*(D - m), m moving
    towards D by at most R*dt each 0.2 ms (m = D at the run-in's start), D the jaw's angle difference (a centring torque
    about an anchor that follows the angle at a limited speed: the fourteenth set's friction slider re-anchors when the
    torque passes its slip torque (a play), the seventeenth set's torsion bar at each stroke's start, the sixth sealed
    half's Dahl ring with the angle's changes, the tenth set's viscoelastic coupling is a lag of the slip; the sixth
    sealed half's rate limiter is of the extension, on the carriage, the twelfth sealed half's of the motor speed's
    follower, on the motor);
13. mass force x the CARRIAGE's POSITION through a RANDOM STEP PATTERN: the carriage's rail is laid in sections of
    length L, each with a small slope of its own; the carriage's weight along each section gives a force constant over
    the section and random from section to section: F*h(floor((x - x_0)/L)), h a fixed pseudo-random pattern in [-1, 1)
    (seed s), x the carriage's position unwrapped from the run-in's start (a random pattern of the carriage's travel:
    the tenth sealed half's worn chain is a random pattern of the wheel's angle, link by link, on the wheel, the
    eleventh set's upstream tension steps a random pattern of the time, on the wheel, the sixth sealed half's blank
    thickness of the stroke count, on the motor; the fifth sealed half's rail joints knock once per joint, all alike).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2 0.0181
at its a-priori strength, scaled once x4.14 (c 0.01 -> 0.04142 N*m*s/rad; a2 0.0715 after); 3 a2 0.0899; 5 a2 0.0899;
7 a2 0.117; 9 a2 0.293; 11 a2 0.0866; 13 a2 0.167 -- the others as written (docs/foreign_drives.md "The eighteenth
set"). Before it, a 0.4 s run of each row only checked that it simulates.

Memory elements (one per recording) are advanced once per 0.2 ms input segment from the state at the segment's start
(kernel.py "memory"), as in the fourth to seventeenth sets; the memory starts afresh at the run-in's first scan, 2 s
before sample 0. The peak held since the stroke (3) is the fifteenth set's MK_STROKE_PEAK on the carriage's speed, the
re-armed catch (7) the seventh set's MK_LATCH, the creeping anchor (11) the sixth set's MK_RATE_LIMIT on the jaw's angle
difference (its term on XS_MEMORY_EXCESS, D - m); the carriage's position (1, 13) is the fifth set's XS_MASS_POSITION
(windowed by XF_PERIODIC_GATE, patterned by the tenth set's XF_HASH_STEP), the induction curve (5) x times the eighth
set's XF_LORENTZ, the shared reference (9) a sensor form in numpy. No kernel change for this set.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import set_memory


def hash_step(x, seed: float, step: float, offset: float) -> np.ndarray:
    """kernel XF_HASH_STEP in numpy: a pseudo-random number in [-1, 1) from the whole number floor((x - offset)/step)
    and the seed (the same exact integer arithmetic in float64)."""
    k = np.floor((np.asarray(x, dtype=np.float64) - offset) / step)
    q = k * k * 7919.0 + k * 40503.0 + seed * 104729.0
    return 2.0 * (q - 65521.0 * np.floor(q / 65521.0)) / 65521.0 - 1.0


# 1. motor load moment x the carriage's position through a window, times the motor speed
class MotorRailSectionDynamo(OutsideForm):
    name = "motor_rail_section_dynamo"
    half = "dev18"
    balance = "motor_load_moment"
    depends_on = ("wheel_angle", "spring_extension", "motor_speed")    # x = r*alpha2 - z
    description = ("a dynamo on the motor's free shaft end feeds the carriage's heaters through a sectioned conductor "
                   "rail; it carries a load only while the carriage's collector shoe is on a live section: c*Omega1 "
                   "while (x - x_0) mod L < l, else 0, x the carriage's position unwrapped from the run-in's start")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c"),
                  Param("pitch_m", "m", (0.01, 100.0), "L (the sections' pitch)"),
                  Param("live_m", "m", (0.0, 100.0), "l (the live length of each section, below L)"),
                  Param("offset_m", "m", (-100.0, 100.0), "x_0"))
    note = "a generator load on the motor switched by the carriage's travel"

    def apply(self, b, p):
        if p["live_m"] > p["pitch_m"]:
            raise ValueError(f"{self.name}: live_m {p['live_m']} is above pitch_m {p['pitch_m']}; allowed: live_m <= "
                             "pitch_m")
        add_term(b, "motor_load_moment", p["coefficient_Nm_s_per_rad"],
                 (K.XS_MASS_POSITION, K.XF_PERIODIC_GATE, p["pitch_m"], p["offset_m"], p["live_m"]),
                 (K.XS_OMEGA1, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def torque(omega1, x, p):
        q = np.mod(np.asarray(x, dtype=np.float64) - p["offset_m"], p["pitch_m"])
        return np.where(q < p["live_m"], p["coefficient_Nm_s_per_rad"] * np.asarray(omega1, dtype=np.float64), 0.0)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * Omega1 while (x - "
                f"{p['offset_m']:.6g} m) mod {p['pitch_m']:.6g} m < {p['live_m']:.6g} m, else 0, x the carriage's "
                "position unwrapped from the run-in's start")


# 3. wheel torque x the carriage's speed through a peak held since each stroke began
class WheelStrokePeakCarriageSpeedBrake(OutsideForm):
    name = "wheel_stroke_peak_carriage_speed_brake"
    half = "dev18"
    balance = "wheel_torque"
    depends_on = ("mass_speed", "load_pulse")
    description = ("a stroke-by-stroke overspeed limiter: a drag pointer on the carriage's tacho, reset by the press's "
                   "valve at each stroke's start, holds the highest carriage speed since; a proportional brake on the "
                   "wheel acts on its excess over v_r: -c*max(0, m - v_r), m -> v at each load pulse's first 0.2 ms "
                   "scan, else max(m, v) (m = v at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_m", "N*m*s/m", (0.0, 1000.0), "c"),
                  Param("reference_speed_m_s", "m/s", (0.0, 100.0), "v_r"))
    note = "a wheel brake on the carriage's peak speed held since the stroke began"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_STROKE_PEAK, K.XS_MASS_SPEED, 0.0)
        add_term(b, "wheel_torque", -p["coefficient_Nm_s_per_m"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["reference_speed_m_s"], 1.0, 0.0), nonperiodic=True)

    @staticmethod
    def peaks(v_at_scans, pulse_count_at_scans, m0=None, count0=None):
        """The held peak m after each scan from v and the pulse count at the scans' starts (m0, count0 before the
        first; None: the first scan is the run-in's start)."""
        out, m, c = [], m0, count0
        for v, k in zip(np.asarray(v_at_scans, dtype=np.float64).tolist(), np.asarray(pulse_count_at_scans).tolist()):
            if m is None or k != c:
                m = v
            elif v > m:
                m = v
            c = k
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_s_per_m']:.6g} N*m*s/m * max(0, m - "
                f"{p['reference_speed_m_s']:.6g} m/s), m the highest mass speed since the load pulse began (scanned "
                "every 0.2 ms)")


# 5. clutch torque x the slip through an induction (Kloss) curve
class ClutchInductionSlipCoupling(OutsideForm):
    name = "clutch_induction_slip_coupling"
    half = "dev18"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an eddy-current slip coupling beside the jaw (a drum on one shaft, an excited pole wheel on the "
                   "other): 2*T_k*(s/s_k)/(1 + (s/s_k)^2), s = Omega1 - Omega2, rising to its pull-out torque T_k at "
                   "the slip s_k and falling beyond, from the motor to the wheel, in the gap and in contact")
    parameters = (Param("pullout_torque_Nm", "N*m", (0.0, 50.0), "T_k"),
                  Param("pullout_slip_rad_s", "rad/s", (0.1, 50.0), "s_k"))
    note = "a slip coupling whose torque peaks at a slip and falls beyond (an induction curve)"

    def apply(self, b, p):
        sk = p["pullout_slip_rad_s"]
        add_term(b, "clutch_torque", 2.0 * p["pullout_torque_Nm"] / sk, (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_LORENTZ, sk, 0.0, 0.0))

    @staticmethod
    def torque(slip, p):
        q = np.asarray(slip, dtype=np.float64) / p["pullout_slip_rad_s"]
        return 2.0 * p["pullout_torque_Nm"] * q / (1.0 + q * q)

    def law(self, p):
        return (f"clutch torque += 2*{p['pullout_torque_Nm']:.6g} N*m * q/(1 + q^2), q = (Omega1 - Omega2)/"
                f"{p['pullout_slip_rad_s']:.6g} rad/s, in the gap and in contact")

    def plugin(self, p):
        return _plugin("ClutchInductionSlipCoupling", self.name, "coupling_torque_Nm", self.description, [
            ("pullout_torque_Nm", "N*m", (0.0, 50.0), "T_k"),
            ("pullout_slip_rad_s", "rad/s", (0.1, 50.0), "s_k")],
            "rel_speed, pullout_torque_Nm, pullout_slip_rad_s",
            "2.0 * pullout_torque_Nm * (rel_speed / pullout_slip_rad_s) / (1.0 + (rel_speed / pullout_slip_rad_s) ** 2)",
            "")


# 7. mass force x the carriage's speed through a latch re-armed at each stroke
class MassStrokeRearmedOverspeedCatch(OutsideForm):
    name = "mass_stroke_rearmed_overspeed_catch"
    half = "dev18"
    balance = "mass_force"
    depends_on = ("mass_speed", "load_pulse")
    description = ("an overspeed catch on the carriage's rail wheel (a centrifugal pawl) drops a drag shoe onto the "
                   "rail once the carriage's speed passes v_t and holds it down until the press's valve lifts it at "
                   "the next stroke's start: -F*m, m -> 0 at each load pulse's first 0.2 ms scan, then m -> 1 at a "
                   "scan with v > v_t (m = 1 at the run-in's start if v > v_t)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("trip_speed_m_s", "m/s", (0.0, 100.0), "v_t"))
    note = "a drag on the carriage latched by its overspeed, re-armed at each stroke"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_LATCH, K.XS_MASS_SPEED, p["trip_speed_m_s"])
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def latches(v_at_scans, pulse_count_at_scans, trip, m0=None, count0=None):
        """The latch m after each scan from v and the pulse count at the scans' starts (m0, count0 before the first;
        None: the first scan is the run-in's start)."""
        out, m, c = [], m0, count0
        for v, k in zip(np.asarray(v_at_scans, dtype=np.float64).tolist(), np.asarray(pulse_count_at_scans).tolist()):
            if m is None:
                m = 0.0
            elif k != c:
                m = 0.0
            if v > trip:
                m = 1.0
            c = k
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * m, m set when the mass speed passes {p['trip_speed_m_s']:.6g} "
                "m/s and reset at each load pulse's first 0.2 ms scan (scanned every 0.2 ms)")


# 9. a2 sensor x a2 times a1
class A2ReferenceSharedWithA1(OutsideForm):
    name = "a2_reference_shared_with_a1"
    half = "dev18"
    stage = "sensor"
    order = 0                      # the conditioner, at the sensing element's signal
    uses_states = True
    balance = "sensor"
    channel = "a2"                 # the signal it changes (it reads a1 too)
    depends_on = ("mass_acceleration", "motor_acceleration")
    description = ("a1's and a2's conditioners share one reference, which a1's signal current loads, so a2's gain "
                   "follows a1's signal: y = x*(1 + g*a1), a1 the acceleration at a1's sensing element")
    parameters = (Param("gain_per_m_s2", "s^2/m", (-1.0, 1.0), "g"),)
    note = "a2's gain modulated by a1's signal (a multiplicative crosstalk)"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], states["a1_physical"], p)

    @staticmethod
    def read(a2, a1, p):
        return np.asarray(a2, dtype=np.float64) * (1.0 + p["gain_per_m_s2"] * np.asarray(a1, dtype=np.float64))

    def law(self, p):
        return f"a2 sensor = a2 * (1 + {p['gain_per_m_s2']:.6g} s^2/m * a1), a1 at a1's sensing element"


# 11. clutch torque x the jaw's angle difference through a rate limiter
class ClutchCreepingAnchorTorsionBar(OutsideForm):
    name = "clutch_creeping_anchor_torsion_bar"
    half = "dev18"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("a torsion bar bridging the jaw halves is anchored on the drive half through a small hydraulic "
                   "rotary actuator whose pressure-compensated flow-control valve lets it creep at most R rad/s: "
                   "-k*(D - m), m moving towards D by at most R*dt each 0.2 ms (m = D at the run-in's start), D the "
                   "jaw's angle difference")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 1000.0), "k"),
                  Param("creep_rad_s", "rad/s", (1e-4, 100.0), "R"))
    note = "a centring torque across the jaw about an anchor that follows its angle at a limited speed"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RATE_LIMIT, K.XS_JAW_ANGLE, p["creep_rad_s"])
        add_term(b, "clutch_torque", -p["stiffness_Nm_per_rad"], (K.XS_MEMORY_EXCESS, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def anchors(d_at_scans, creep_rad_s, dt, m0=None):
        """The anchor m after each scan from D at the scans' starts (m0 before the first; None: the first scan is the
        run-in's start)."""
        out, m, lim = [], m0, creep_rad_s * dt
        for d in np.asarray(d_at_scans, dtype=np.float64).tolist():
            if m is None:
                m = d
            else:
                step = d - m
                m += -lim if step < -lim else (lim if step > lim else step)
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"clutch torque += -{p['stiffness_Nm_per_rad']:.6g} N*m/rad * (D - m), m moving towards D by at most "
                f"{p['creep_rad_s']:.6g} rad/s * 0.2 ms each 0.2 ms; D the jaw's angle difference, in the gap and in "
                "contact")


# 13. mass force x the carriage's position through a random step pattern
class MassRailSectionSlopes(OutsideForm):
    name = "mass_rail_section_slopes"
    half = "dev18"
    balance = "mass_force"
    depends_on = ("wheel_angle", "spring_extension")     # x = r*alpha2 - z
    description = ("the carriage's rail is laid in sections of length L, each with a small slope of its own: the "
                   "carriage's weight along each gives a force constant over the section and random from section to "
                   "section: F*h(floor((x - x_0)/L)), h a fixed pseudo-random pattern in [-1, 1) (seed s), x the "
                   "carriage's position unwrapped from the run-in's start")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("section_m", "m", (0.01, 100.0), "L"),
                  Param("offset_m", "m", (-100.0, 100.0), "x_0"),
                  Param("seed", "-", (0.0, 1000.0), "s (a whole number)"))
    note = "a random force pattern of the carriage's travel, section by section"

    def apply(self, b, p):
        add_term(b, "mass_force", p["force_N"],
                 (K.XS_MASS_POSITION, K.XF_HASH_STEP, float(int(p["seed"])), p["section_m"], p["offset_m"]),
                 nonperiodic=True)

    @staticmethod
    def force(x, p):
        return p["force_N"] * hash_step(x, float(int(p["seed"])), p["section_m"], p["offset_m"])

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * h(floor((x - {p['offset_m']:.6g} m)/{p['section_m']:.6g} m)), h "
                f"the pseudo-random pattern of seed {int(p['seed'])} in [-1, 1), x the carriage's position unwrapped "
                "from the run-in's start")


FORM_CLASSES = (MotorRailSectionDynamo, WheelStrokePeakCarriageSpeedBrake, ClutchInductionSlipCoupling,
                MassStrokeRearmedOverspeedCatch, A2ReferenceSharedWithA1, ClutchCreepingAnchorTorsionBar,
                MassRailSectionSlopes)
