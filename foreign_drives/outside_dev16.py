"""Outside mechanisms, sixteenth DEVELOPMENT half (issue 31 part 4, set 16): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first fifteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev15`, :mod:`outside_sealed15`) have, with their laws in
the open. The sixteenth sealed half is :mod:`outside_sealed16`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, wheel torque, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed16` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 wheel torque, 14 clutch torque). About half of the fourteen are plain memoryless
laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set
by one simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the LOAD PULSE's AGE through a RESONANCE-SHAPED PEAK: a flying shear on the motor's free shaft
   end cuts the strip once per stroke, at t_c into it; its cutting load rises and falls about that instant:
   A/(1 + ((tau - t_c)/w)^2) on the motor's load while the pulse is on, tau the time since the pulse began (a load
   peak inside each stroke at a set delay: the earlier motor loads of the pulse are the accumulator's recharge, the
   n-th stroke's pierce, the stroke's torsional ringing, the metered roll feed (with the motor angle), the strain-rate
   forming load (the pulse times the speed) and the batch's random strokes; the eighth set's Lorentzian is a
   resonance of the mass speed on the carriage);
3. wheel torque x the MOTOR SPEED SQUARED: a hydrostatic booster: a gear pump on the motor's shaft end feeds a
   hydraulic motor on the wheel's shaft through a fixed orifice; the orifice's pressure drop, ~ flow^2 ~ Omega1^2,
   drives the wheel: +c*Omega1*|Omega1| on the wheel (a wheel law of the MOTOR's speed: the earlier wheel laws read the
   wheel's speed or angle, the extension, the pulse, the time, the jaw, the contact torque or the carriage's speed;
   the motor-side laws of the wheel's speed are the runaway governor and the hydraulic lag brake, on the motor);
5. clutch torque x the SLIP's direction TIMES the SPRING EXTENSION beyond a reference: a friction plate beside the
   jaw pressed through a lever by the spring's cable (the further it is stretched, the harder the plate is pressed):
   mu_k*max(0, z - z_0)*tanh((Omega1 - Omega2)/w) (a dry friction across the jaw whose normal force is the load's
   cable: the earlier slip couplings are viscous, overrunning, hydrodynamic, hysteresis, plate (pumped by the slip),
   thermally thinned or gated by the motor speed or the pulse (the stroke leaf spring); no clutch law reads the
   spring's extension);
7. mass force x the MOTOR ANGLE TIMES THE MOTOR SPEED SQUARED: the motor's rotor unbalance (e*m_r) shakes the common
   base frame, and the carriage on its rail feels the frame's motion: A*Omega1^2*sin(alpha1 + phi) along x (a force on
   the carriage locked to the motor's angle AND scaled by the motor speed squared: the nearest earlier kind is the
   third sealed half's lobe cam on the motor shaft, F*sin(n*alpha1 + phi) on the carriage, a fixed amplitude -- this
   one is its order 1 with an unbalance's centrifugal amplitude, so at the drive's near-constant speed the two differ
   only by that amplitude's +-5 % swing with Omega1 (a near repeat, found after the list was written: see
   docs/foreign_drives.md "The sixteenth set"); the eccentric roller is locked to the wheel's angle, the hold-down
   roller (sealed 7) to the pulse times the wheel's angle, the rail's waviness to the carriage's position; the first
   set's rotating gravity is a1's, of the motor angle alone);
9. a2 sensor x the CARRIAGE SPEED's DIRECTION: a2's cable rolls in the carriage's drag chain; the cable's
   triboelectric charge flips with the chain's direction of travel and shifts a2's zero: y = x + o*tanh(v/v_s) (a
   saturating, odd zero shift of the speed: the fourteenth set's velocity sensitivity is linear in v, the ground loop
   switches with the jaw's contact, the tacho's drop follows the motor speed);
11. mass force x the WHEEL SPEED through a ONE-SHOT: an overspeed switch on the wheel's shaft fires the carriage's rail
    brake for T_h each time the wheel's speed rises through Omega_t (scanned every 0.2 ms; not retriggered while it
    runs): -F while on (a timed brake on the carriage fired by the wheel: the earlier one-shots are fired by the
    extension (the impulse relay brake is a toggle), the motor speed (the overspeed timed brake, on the motor), the
    wheel's angle (the cam switch, on the wheel) or the jaw's impacts (the knock-triggered rail brake); the seventh
    set's debounced overspeed brake on the carriage reads the carriage's own speed; the earlier carriage forces of the
    wheel's speed are memoryless: the ninth sealed half's blower sail, the thirteenth set's tracking conveyor);
13. motor load moment x the spring extension through a PEAK-HOLD RESET AT EACH STROKE: a peak-reading load cell on the
    spring's cable sets a regenerative brake on the motor from the largest extension since the stroke began (the PLC
    clears the peak at each stroke's start): c*max(0, m - z_0), m -> z at each load pulse's first 0.2 ms scan, else
    m -> max(m, z) every 0.2 ms (m = z at the run-in's start) (the fifteenth set's ratchet is this memory on the
    WHEEL; the earlier motor loads of the extension are memoryless (the overload band brake, the magnetic-particle
    brake times the speed)).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2 0.0203 at
its a-priori strength, scaled once x3.70 (A 3 -> 11.09 N*m; a2 0.0738 after); 3 a2 0.0737; 5 a2 0.126; 7 a2 0.144; 9 a2
0.100; 11 a2 0.107; 13 a2 0.0278, scaled once x2.70 (c 50 -> 134.7 N*m/m; a2 0.0541 after) -- the others as written
(docs/foreign_drives.md "The sixteenth set"). Before it, a 0.4 s run of each row only checked that it simulates.

Memory elements (one per recording) are advanced once per 0.2 ms input segment from the state at the segment's start
(kernel.py "memory"), as in the fourth to fifteenth sets; the memory starts afresh at the run-in's first scan, 2 s
before sample 0. The overspeed rail brake (11) is the one-shot MK_ONESHOT on the wheel speed; the peak-reading load
cell (13) is the fifteenth set's MK_STROKE_PEAK on the extension. No kernel change for this set.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import oneshot_reference, segments, set_memory


# 1. motor load moment x the load pulse's age through a resonance-shaped peak
class MotorFlyingShearCut(OutsideForm):
    name = "motor_flying_shear_cut"
    half = "dev16"
    balance = "motor_load_moment"
    depends_on = ("load_pulse",)
    description = ("a flying shear on the motor's free shaft end cuts the strip once per stroke, at t_c into it: "
                   "A/(1 + ((tau - t_c)/w)^2) on the motor's load while the load pulse is on, tau the time since the "
                   "pulse began; 0 between pulses")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "A (at the peak)"),
                  Param("cut_delay_s", "s", (0.0, 0.06), "t_c"),
                  Param("half_width_s", "s", (1e-4, 0.1), "w"))
    note = "a load peak inside each stroke at a set delay"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"],
                 (K.XS_PULSE_AGE, K.XF_LORENTZ, p["half_width_s"], p["cut_delay_s"], 0.0),
                 (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0))

    @staticmethod
    def torque(pulse_age, pulse, p):
        q = (np.asarray(pulse_age, dtype=np.float64) - p["cut_delay_s"]) / p["half_width_s"]
        return p["torque_Nm"] * np.asarray(pulse, dtype=np.float64) / (1.0 + q * q)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m / (1 + ((tau - {p['cut_delay_s']:.6g} s)/"
                f"{p['half_width_s']:.6g} s)^2) while the load pulse is on, tau the time since it began; else 0")

    def plugin(self, p):
        return _plugin("MotorFlyingShearCut", self.name, "motor_load_moment_pu", self.description, [
            ("amplitude_pu", "p.u.", (0.0, 2.0), "A / T_b (T_b = 20 N*m)"),
            ("cut_delay_s", "s", (0.0, 0.06), "t_c"),
            ("half_width_s", "s", (1e-4, 0.1), "w")],
            "pulse_time_s, pulse_off_time_s, amplitude_pu, cut_delay_s, half_width_s",
            "amplitude_pu / (1.0 + ((pulse_time_s - cut_delay_s) / half_width_s) ** 2) * 0.5 * (1.0 + "
            "sign(pulse_off_time_s - pulse_time_s))", "sign")


# 3. wheel torque x the motor speed squared
class WheelHydrostaticBooster(OutsideForm):
    name = "wheel_hydrostatic_booster"
    half = "dev16"
    balance = "wheel_torque"
    depends_on = ("motor_speed",)
    description = ("a hydrostatic booster: a gear pump on the motor's shaft end feeds a hydraulic motor on the wheel's "
                   "shaft through a fixed orifice; the orifice's pressure drop (~ flow^2 ~ Omega1^2) drives the wheel: "
                   "+c*Omega1*|Omega1| on the wheel")
    parameters = (Param("coefficient_Nm_s2_per_rad2", "N*m*s^2/rad^2", (0.0, 0.01), "c"),)
    note = "a wheel torque of the motor's speed (a cross-shaft law)"

    def apply(self, b, p):
        add_term(b, "wheel_torque", p["coefficient_Nm_s2_per_rad2"], (K.XS_OMEGA1, K.XF_POWER, 2.0, 0.0, 0.0))

    @staticmethod
    def torque(omega1, p):
        w = np.asarray(omega1, dtype=np.float64)
        return p["coefficient_Nm_s2_per_rad2"] * w * np.abs(w)

    def law(self, p):
        return f"wheel torque += {p['coefficient_Nm_s2_per_rad2']:.6g} N*m*s^2/rad^2 * Omega1*|Omega1|"

    def plugin(self, p):
        return _plugin("WheelHydrostaticBooster", self.name, "wheel_torque_Nm", self.description, [
            ("coefficient_Nm_s2_per_rad2", "N*m*s^2/rad^2", (0.0, 0.01), "c")],
            "omega1, coefficient_Nm_s2_per_rad2", "coefficient_Nm_s2_per_rad2 * omega1 * fabs(omega1)", "fabs")


# 5. clutch torque x the slip's direction times the spring extension beyond a reference
class ClutchCableLoadedFrictionPlate(OutsideForm):
    name = "clutch_cable_loaded_friction_plate"
    half = "dev16"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed", "spring_extension")
    description = ("a friction plate beside the jaw pressed through a lever by the spring's cable: "
                   "mu_k*max(0, z - z_0)*tanh((Omega1 - Omega2)/w) from the motor to the wheel, in the gap and in "
                   "contact, z the spring's extension")
    parameters = (Param("coefficient_Nm_per_m", "N*m/m", (0.0, 5000.0), "mu_k"),
                  Param("reference_m", "m", (0.0, 1.0), "z_0"),
                  Param("slip_scale_rad_s", "rad/s", (1e-3, 10.0), "w"))
    note = "a dry friction across the jaw pressed by the load's cable"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["coefficient_Nm_per_m"],
                 (K.XS_JAW_SPEED, K.XF_TANH, p["slip_scale_rad_s"], 0.0, 0.0),
                 (K.XS_SPRING_EXTENSION, K.XF_EXCESS_POWER, p["reference_m"], 1.0, 0.0))

    @staticmethod
    def torque(slip, z, p):
        return (p["coefficient_Nm_per_m"] * np.maximum(0.0, np.asarray(z, dtype=np.float64) - p["reference_m"])
                * np.tanh(np.asarray(slip, dtype=np.float64) / p["slip_scale_rad_s"]))

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_per_m']:.6g} N*m/m * max(0, z - {p['reference_m']:.6g} m) * "
                f"tanh((Omega1 - Omega2)/{p['slip_scale_rad_s']:.6g} rad/s), in the gap and in contact")


# 7. mass force x the motor angle times the motor speed squared
class MassMotorUnbalanceFrameShake(OutsideForm):
    name = "mass_motor_unbalance_frame_shake"
    half = "dev16"
    balance = "mass_force"
    depends_on = ("motor_speed", "motor_angle")
    description = ("the motor's rotor unbalance shakes the common base frame, and the carriage on its rail feels the "
                   "frame's motion: A*Omega1^2*sin(alpha1 + phi) along x")
    parameters = (Param("coefficient_N_s2_per_rad2", "N*s^2/rad^2", (0.0, 0.01), "A"),
                  Param("phase_rad", "rad", (-np.pi, np.pi), "phi"))
    note = "a force on the carriage locked to the motor's angle"

    def apply(self, b, p):
        add_term(b, "mass_force", p["coefficient_N_s2_per_rad2"], (K.XS_OMEGA1, K.XF_POWER, 2.0, 0.0, 0.0),
                 (K.XS_ALPHA1, K.XF_SIN, 1.0, p["phase_rad"], 0.0), nonperiodic=True)

    @staticmethod
    def force(omega1, alpha1, p):
        w = np.asarray(omega1, dtype=np.float64)
        return p["coefficient_N_s2_per_rad2"] * w * np.abs(w) * np.sin(np.asarray(alpha1, dtype=np.float64)
                                                                         + p["phase_rad"])

    def law(self, p):
        return (f"mass force += {p['coefficient_N_s2_per_rad2']:.6g} N*s^2/rad^2 * Omega1*|Omega1| * sin(alpha1 + "
                f"{p['phase_rad']:.6g})")

    def plugin(self, p):
        return _plugin("MassMotorUnbalanceFrameShake", self.name, "mass_force_N", self.description, [
            ("coefficient_N_s2_per_rad2", "N*s^2/rad^2", (0.0, 0.01), "A"),
            ("phase_rad", "rad", (-np.pi, np.pi), "phi")],
            "omega1, alpha1, coefficient_N_s2_per_rad2, phase_rad",
            "coefficient_N_s2_per_rad2 * omega1 * fabs(omega1) * sin(alpha1 + phase_rad)", "fabs, sin")


# 9. a2 sensor x the carriage speed's direction
class A2DragChainTriboelectric(OutsideForm):
    name = "a2_drag_chain_triboelectric"
    half = "dev16"
    stage = "sensor"
    order = 1                      # the cable, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "mass_speed")
    description = ("a2's cable rolls in the carriage's drag chain; its triboelectric charge flips with the chain's "
                   "direction of travel and shifts a2's zero: y = x + o*tanh(v/v_s), v the carriage's speed")
    parameters = (Param("offset_m_s2", "m/s^2", (-5.0, 5.0), "o"),
                  Param("speed_scale_m_s", "m/s", (1e-3, 100.0), "v_s"))
    note = "a saturating, odd zero shift of a2 with the carriage's speed"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], states["mass_speed"], p)

    @staticmethod
    def read(a, v, p):
        return (np.asarray(a, dtype=np.float64)
                + p["offset_m_s2"] * np.tanh(np.asarray(v, dtype=np.float64) / p["speed_scale_m_s"]))

    def law(self, p):
        return f"a2 sensor += {p['offset_m_s2']:.6g} m/s^2 * tanh(v/{p['speed_scale_m_s']:.6g} m/s), v the mass speed"


# 11. mass force x the wheel speed through a one-shot
class MassWheelOverspeedTimedRailBrake(OutsideForm):
    name = "mass_wheel_overspeed_timed_rail_brake"
    half = "dev16"
    balance = "mass_force"
    depends_on = ("wheel_speed",)
    description = ("an overspeed switch on the wheel's shaft fires the carriage's rail brake for T_h each time the "
                   "wheel's speed rises through Omega_t (from at or below it at the previous 0.2 ms scan) while the "
                   "brake is off: -F along x while on (off at the run-in's start)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("trip_speed_rad_s", "rad/s", (0.0, 300.0), "Omega_t"),
                  Param("hold_s", "s", (2e-4, 0.5), "T_h (a multiple of 0.2 ms)"))
    note = "a timed brake on the carriage fired by the wheel's speed"

    def apply(self, b, p):
        segments(p["hold_s"], f"{self.name}: hold_s")
        set_memory(b, self.name, K.MK_ONESHOT, K.XS_OMEGA2, p["trip_speed_rad_s"], p["hold_s"])
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def on(omega2_at_scans, p, dt, state0=None):
        """The brake's state after each scan from the wheel speed at the scans' starts. ``state0`` = (on, scans since
        it fired, the speed at the scan before the first) before the first; None: the first scan is the run-in's start
        (off, no previous speed)."""
        return oneshot_reference(omega2_at_scans, p["trip_speed_rad_s"], round(p["hold_s"] / dt), state0)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N for {p['hold_s']:.6g} s from each rise of the wheel speed through "
                f"{p['trip_speed_rad_s']:.6g} rad/s while off (a one-shot scanned every 0.2 ms)")


# 13. motor load moment x the spring extension through a peak-hold reset at each stroke
class MotorPeakTensionRegenBrake(OutsideForm):
    name = "motor_peak_tension_regen_brake"
    half = "dev16"
    balance = "motor_load_moment"
    depends_on = ("spring_extension", "load_pulse")
    description = ("a peak-reading load cell on the spring's cable sets a regenerative brake on the motor from the "
                   "largest extension since the stroke began: c*max(0, m - z_0), m -> z at each load pulse's first "
                   "0.2 ms scan, else m -> max(m, z) every 0.2 ms (m = z at the run-in's start)")
    parameters = (Param("coefficient_Nm_per_m", "N*m/m", (0.0, 5000.0), "c"),
                  Param("reference_m", "m", (0.0, 1.0), "z_0"))
    note = "a motor brake set by the largest extension since the stroke began"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_STROKE_PEAK, K.XS_SPRING_EXTENSION, 0.0)
        add_term(b, "motor_load_moment", p["coefficient_Nm_per_m"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["reference_m"], 1.0, 0.0), nonperiodic=True)

    @staticmethod
    def held(z_at_scans, pulse_count_at_scans, m0=None, count0=None):
        """The peak m after each scan from z and the pulse count at the scans' starts (m0, count0 before the first;
        None: the first scan is the run-in's start)."""
        out, m, c = [], m0, count0
        for z, k in zip(np.asarray(z_at_scans, dtype=np.float64).tolist(), np.asarray(pulse_count_at_scans).tolist()):
            m = z if (m is None or k != c) else max(m, z)
            c = k
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_per_m']:.6g} N*m/m * max(0, m - {p['reference_m']:.6g} m), m "
                "-> z at each load pulse's first 0.2 ms scan, else max(m, z), every 0.2 ms, z the spring's extension")


FORM_CLASSES = (MotorFlyingShearCut, WheelHydrostaticBooster, ClutchCableLoadedFrictionPlate,
                MassMotorUnbalanceFrameShake, A2DragChainTriboelectric, MassWheelOverspeedTimedRailBrake,
                MotorPeakTensionRegenBrake)
