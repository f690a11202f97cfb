"""Outside mechanisms, fifteenth DEVELOPMENT half (issue 31 part 4, set 15): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first fourteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev14`, :mod:`outside_sealed14`) have, with their laws in
the open. The fifteenth sealed half is :mod:`outside_sealed15`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, sensor, mass force, motor load moment); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed15` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 sensor, 14 motor load moment). About half of the fourteen are plain memoryless laws of new kinds,
half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory). Written before any
diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation
against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the SLIP's MAGNITUDE: an anti-clatter slip monitor (a tacho on each shaft) excites an
   eddy-current brake on the motor's shaft in proportion to how fast the jaw's halves move against each other, either
   way: c*|Omega1 - Omega2| on the motor's load (an even law of the slip on ONE shaft: the earlier laws of the slip
   are clutch torques, odd in it or half-wave, acting on both shafts; the earlier motor loads read Omega1, Omega2,
   r*Omega1 - v, the extension, the angles, the contact torque, the pulse or the time);
3. wheel torque x the CARRIAGE's speed beyond a limit: a runaway guard on the carriage (a centrifugal governor on its
   guide roller) pulls, through a Bowden cable, a band brake on the wheel's shaft when the carriage overruns:
   -K*max(0, v - v_0) (a cross-domain law: the earlier wheel laws read the wheel's speed or angle, the extension, the
   pulse, the time or the jaw; the eleventh set's runaway governor brakes the motor from the wheel's speed);
5. clutch torque x the CUBE of the jaw's angle difference: an elastomer spider (a progressively hardening rubber
   element) bridging the jaw halves, in the gap and in contact: k3*(alpha1 - alpha2)^3 (a hardening spring across the
   backlash: the earlier springs across the jaw are linear -- the first sealed half's anti-backlash spring, the tenth
   set's stroke-switched leaf spring, the fourteenth's centrifugally stiffened one --, piecewise linear (the bumpers),
   periodic (the detent), non-monotone (the snap-through), an over-centre toggle or a Jenkin element);
7. mass force x the spring extension TIMES the load pulse: a gas spring hooked beside the spring between the carriage
   and the cable's clamp, pressurised by the press's valve during each stroke only: k_p*pulse*(z - z_0) along x (a
   stiffness on the carriage switched by the process: the tenth set's switched stiffness is across the jaw; the
   earlier stroke-related springs on the carriage are re-referenced at each stroke's start (the trapped air cushion)
   or stretched by the distance travelled since it (the hooked return spring), both acting between strokes too);
9. a2 sensor x the jaw's DRIVE-FACE CONTACT: a2's cable shield is grounded at both ends; the loop closes through the
   frame, the motor's shaft, the jaw's drive faces (their insulating coating worn through) and the wheel while the
   drive faces touch, and the loop's current shifts a2's zero: y = x + o*[drive faces in contact] (a sensor law of
   the clutch's contact state: the earlier sensor laws read the accelerations, the angles, the speeds, the spring's
   extension, the pulse or the time; none the jaw);
11. wheel torque x the spring extension through a PEAK-HOLD RESET AT EACH STROKE: a ratchet cable tensioner: a pawl on
    the cable guide follows the extension one way (it ratchets along while the extension grows and holds at its
    largest) and pulls a band brake on the wheel the tighter the further it has gone past z_0; the press's cam knocks
    the pawl out at each stroke's start and it picks up the extension there: -c*max(0, m - z_0), m -> z at each load
    pulse's first 0.2 ms scan, else m -> max(m, z) every 0.2 ms (m = z at the run-in's start) (a running maximum
    reset by the process: the drag pointers' peaks bleed off with a time constant and are never reset, the seventh and
    fourteenth sets' stroke-reset latches hold one bit, the stroke samples hold the value at the stroke's start);
13. mass force x the jaw's PENETRATION through a ONE-SHOT: a knock sensor on the coupling's housing: each time the
    jaw strikes (its penetration depth rising through p_t at a 0.2 ms scan) the PLC fires a rail brake on the carriage
    for T_h, not retriggered while it runs: -F while on (a timed brake triggered by the jaw's impacts: the earlier
    one-shots are triggered by the extension, the motor speed or the wheel's angle; the tenth sealed half's knock
    sensor samples the carriage's speed at each contact and holds a brake set from it until the next).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2 0.0694; 3
a2 0.0386 at its a-priori strength, scaled once x1.94 (K 40 -> 77.78 N*m*s/m; a2 0.0551 after); 5 a2 0.0563; 7 a2
0.0336, scaled once x2.23 (k_p 60 -> 133.9 N/m; a2 0.0662 after); 9 a2 0.0795; 11 a2 0.159; 13 a2 0.146 -- the others as
written (docs/foreign_drives.md "The fifteenth set"). Before it, a 0.4 s run of each row only checked that it
simulates.

Memory elements (one per recording) are advanced once per 0.2 ms input segment from the state at the segment's start
(kernel.py "memory"), as in the fourth to fourteenth sets; the memory starts afresh at the run-in's first scan, 2 s
before sample 0. The ratchet (11) is the kernel's one new memory kind for this set, MK_STROKE_PEAK (a running maximum
reset at each load pulse's first scan); the knock sensor (13) is the one-shot MK_ONESHOT on the penetration depth. The
ground loop (9) reads the contact mode the sensor chain is now passed beside the run's other states.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import oneshot_reference, segments, set_memory


# 1. motor load moment x the slip's magnitude
class MotorSlipMonitorBrake(OutsideForm):
    name = "motor_slip_monitor_brake"
    half = "dev15"
    balance = "motor_load_moment"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an anti-clatter slip monitor (a tacho on each shaft) excites an eddy-current brake on the motor's "
                   "shaft in proportion to the slip's magnitude: c*|Omega1 - Omega2| on the motor's load")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),)
    note = "an even law of the slip on one shaft (a load on the motor whichever half runs ahead)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["coefficient_Nm_s_per_rad"], (K.XS_JAW_SPEED, K.XF_ABS, 0.0, 0.0, 0.0))

    @staticmethod
    def torque(omega1, omega2, p):
        return p["coefficient_Nm_s_per_rad"] * np.abs(np.asarray(omega1, dtype=np.float64)
                                                       - np.asarray(omega2, dtype=np.float64))

    def law(self, p):
        return f"motor load moment += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * |Omega1 - Omega2|"

    def plugin(self, p):
        return _plugin("MotorSlipMonitorBrake", self.name, "motor_load_moment_pu", self.description, [
            ("coefficient_pu_s_per_rad", "p.u.*s/rad", (0.0, 1.0), "c / T_b (T_b = 20 N*m)")],
            "rel_speed, coefficient_pu_s_per_rad", "coefficient_pu_s_per_rad * fabs(rel_speed)", "fabs")


# 3. wheel torque x the carriage's speed beyond a limit
class WheelCarriageRunawayBrake(OutsideForm):
    name = "wheel_carriage_runaway_brake"
    half = "dev15"
    balance = "wheel_torque"
    depends_on = ("mass_speed",)
    description = ("a runaway guard on the carriage (a centrifugal governor on its guide roller) pulls, through a "
                   "Bowden cable, a band brake on the wheel's shaft when the carriage overruns: -K*max(0, v - v_0) on "
                   "the wheel, v the carriage's speed")
    parameters = (Param("coefficient_Nm_s_per_m", "N*m*s/m", (0.0, 1000.0), "K"),
                  Param("trip_speed_m_s", "m/s", (0.0, 100.0), "v_0"))
    note = "the wheel braked by the carriage's speed (a cross-domain law)"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["coefficient_Nm_s_per_m"],
                 (K.XS_MASS_SPEED, K.XF_EXCESS_POWER, p["trip_speed_m_s"], 1.0, 0.0))

    @staticmethod
    def torque(v, p):
        return -p["coefficient_Nm_s_per_m"] * np.maximum(0.0, np.asarray(v, dtype=np.float64) - p["trip_speed_m_s"])

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_s_per_m']:.6g} N*m*s/m * max(0, v - {p['trip_speed_m_s']:.6g} "
                "m/s), v the mass speed")

    def plugin(self, p):
        return _plugin("WheelCarriageRunawayBrake", self.name, "wheel_torque_Nm", self.description, [
            ("coefficient_Nm_s_per_m", "N*m*s/m", (0.0, 1000.0), "K"),
            ("trip_speed_m_s", "m/s", (0.0, 100.0), "v_0")],
            "xdot, coefficient_Nm_s_per_m, trip_speed_m_s",
            "-coefficient_Nm_s_per_m * fmax(0.0, xdot - trip_speed_m_s)", "fmax")


# 5. clutch torque x the cube of the jaw's angle difference
class ClutchHardeningElastomerSpider(OutsideForm):
    name = "clutch_hardening_elastomer_spider"
    half = "dev15"
    balance = "clutch_torque"
    depends_on = ("motor_angle", "wheel_angle")
    description = ("an elastomer spider (a progressively hardening rubber element) bridging the jaw halves, in the gap "
                   "and in contact: k3*(alpha1 - alpha2)^3 from the motor to the wheel")
    parameters = (Param("stiffness_Nm_per_rad3", "N*m/rad^3", (0.0, 1.0e7), "k3"),)
    note = "a hardening (cubic) spring across the backlash"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["stiffness_Nm_per_rad3"], (K.XS_JAW_ANGLE, K.XF_POWER, 3.0, 0.0, 0.0))

    @staticmethod
    def torque(jaw_angle, p):
        return p["stiffness_Nm_per_rad3"] * np.asarray(jaw_angle, dtype=np.float64) ** 3

    def law(self, p):
        return (f"clutch torque += {p['stiffness_Nm_per_rad3']:.6g} N*m/rad^3 * (alpha1 - alpha2)^3, in the gap and in "
                "contact")


# 7. mass force x the spring extension times the load pulse
class MassStrokeGasSpring(OutsideForm):
    name = "mass_stroke_gas_spring"
    half = "dev15"
    balance = "mass_force"
    depends_on = ("spring_extension", "load_pulse")
    description = ("a gas spring hooked beside the spring between the carriage and the cable's clamp, pressurised by "
                   "the press's valve during each stroke only: k_p*pulse*(z - z_0) along x, z the spring's extension, "
                   "pulse = 1 while the load pulse is on, else 0")
    parameters = (Param("stiffness_N_per_m", "N/m", (0.0, 5000.0), "k_p"),
                  Param("reference_m", "m", (0.0, 1.0), "z_0"))
    note = "a stiffness on the carriage switched by the process"

    def apply(self, b, p):
        k = p["stiffness_N_per_m"]
        add_term(b, "mass_force", k, (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0), (K.XS_SPRING_EXTENSION, K.XF_X, 0.0, 0.0, 0.0))
        add_term(b, "mass_force", -k * p["reference_m"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0))

    @staticmethod
    def force(z, pulse, p):
        return (p["stiffness_N_per_m"] * np.asarray(pulse, dtype=np.float64)
                * (np.asarray(z, dtype=np.float64) - p["reference_m"]))

    def law(self, p):
        return (f"mass force += {p['stiffness_N_per_m']:.6g} N/m * pulse * (z - {p['reference_m']:.6g} m), z the "
                "spring's extension, pulse = 1 while the load pulse is on")

    def plugin(self, p):
        return _plugin("MassStrokeGasSpring", self.name, "mass_force_N", self.description, [
            ("stiffness_N_per_m", "N/m", (0.0, 5000.0), "k_p"),
            ("reference_m", "m", (0.0, 1.0), "z_0")],
            "z, pulse_time_s, pulse_off_time_s, stiffness_N_per_m, reference_m",
            "stiffness_N_per_m * (z - reference_m) * 0.5 * (1.0 + sign(pulse_off_time_s - pulse_time_s))", "sign")


# 9. a2 sensor x the jaw's drive-face contact
class A2DriveFaceGroundLoop(OutsideForm):
    name = "a2_drive_face_ground_loop"
    half = "dev15"
    stage = "sensor"
    order = 1                      # the cable, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "clutch_penetration")
    description = ("a2's cable shield is grounded at both ends; the loop closes through the frame, the motor's shaft, "
                   "the jaw's drive faces (their coating worn through) and the wheel while the drive faces touch: y = "
                   "x + o while the jaw is in contact on its drive side, else y = x")
    parameters = (Param("offset_m_s2", "m/s^2", (-5.0, 5.0), "o"),)
    note = "a zero shift of a2 switched by the clutch's contact state"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], states["mode"], p)

    @staticmethod
    def read(a, mode, p):
        return np.asarray(a, dtype=np.float64) + p["offset_m_s2"] * (np.asarray(mode) == 1)

    def law(self, p):
        return (f"a2 sensor += {p['offset_m_s2']:.6g} m/s^2 while the jaw's drive faces are in contact (contact mode "
                "+1), else 0")


# 11. wheel torque x the spring extension through a peak-hold reset at each stroke
class WheelRatchetCableTensioner(OutsideForm):
    name = "wheel_ratchet_cable_tensioner"
    half = "dev15"
    balance = "wheel_torque"
    depends_on = ("spring_extension", "load_pulse")
    description = ("a ratchet cable tensioner: a pawl on the cable guide follows the spring's extension one way, m -> "
                   "max(m, z) every 0.2 ms, and is knocked out by the press's cam at each load pulse's first scan, m -> "
                   "z (m = z at the run-in's start); it pulls a band brake on the wheel: -c*max(0, m - z_0)")
    parameters = (Param("coefficient_Nm_per_m", "N*m/m", (0.0, 5000.0), "c"),
                  Param("reference_m", "m", (0.0, 1.0), "z_0"))
    note = "a brake set by the largest extension since the stroke began"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_STROKE_PEAK, K.XS_SPRING_EXTENSION, 0.0)
        add_term(b, "wheel_torque", -p["coefficient_Nm_per_m"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["reference_m"], 1.0, 0.0), nonperiodic=True)

    @staticmethod
    def held(z_at_scans, pulse_count_at_scans, m0=None, count0=None):
        """The pawl's position m after each scan from z and the pulse count at the scans' starts (m0, count0 before the
        first; None: the first scan is the run-in's start)."""
        out, m, c = [], m0, count0
        for z, k in zip(np.asarray(z_at_scans, dtype=np.float64).tolist(), np.asarray(pulse_count_at_scans).tolist()):
            if m is None or k != c:
                m = z
            else:
                m = max(m, z)
            c = k
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_per_m']:.6g} N*m/m * max(0, m - {p['reference_m']:.6g} m), m -> "
                "z at each load pulse's first 0.2 ms scan, else max(m, z), every 0.2 ms, z the spring's extension")


# 13. mass force x the jaw's penetration through a one-shot
class MassKnockTriggeredRailBrake(OutsideForm):
    name = "mass_knock_triggered_rail_brake"
    half = "dev15"
    balance = "mass_force"
    depends_on = ("clutch_penetration",)
    description = ("a knock sensor on the coupling's housing: each time the jaw strikes (its penetration depth rising "
                   "through p_t, from at or below it at the previous 0.2 ms scan) while the brake is off, the PLC fires "
                   "a rail brake on the carriage for T_h: -F along x while on (off at the run-in's start)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("trigger_penetration_rad", "rad", (0.0, 0.1), "p_t"),
                  Param("hold_s", "s", (2e-4, 0.5), "T_h (a multiple of 0.2 ms)"))
    note = "a timed brake on the carriage fired by the jaw's impacts"

    def apply(self, b, p):
        segments(p["hold_s"], f"{self.name}: hold_s")
        set_memory(b, self.name, K.MK_ONESHOT, K.XS_PENETRATION_DEPTH, p["trigger_penetration_rad"], p["hold_s"])
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def on(depth_at_scans, p, dt, state0=None):
        """The brake's state after each scan from the penetration depth at the scans' starts. ``state0`` = (on, scans
        since it fired, the depth at the scan before the first) before the first; None: the first scan is the run-in's
        start (off, no previous depth)."""
        return oneshot_reference(depth_at_scans, p["trigger_penetration_rad"], round(p["hold_s"] / dt), state0)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N for {p['hold_s']:.6g} s from each rise of the jaw's penetration "
                f"depth through {p['trigger_penetration_rad']:.6g} rad while off (a one-shot scanned every 0.2 ms)")


FORM_CLASSES = (MotorSlipMonitorBrake, WheelCarriageRunawayBrake, ClutchHardeningElastomerSpider, MassStrokeGasSpring,
                A2DriveFaceGroundLoop, WheelRatchetCableTensioner, MassKnockTriggeredRailBrake)
