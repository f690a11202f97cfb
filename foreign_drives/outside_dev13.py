"""Outside mechanisms, thirteenth DEVELOPMENT half (issue 31 part 4, set 13): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first twelve sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev12`, :mod:`outside_sealed12`) have, with their laws in
the open. The thirteenth sealed half is :mod:`outside_sealed13`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (motor
load moment, sensor, clutch torque, mass force); in that order, the odd ones (1st, 3rd, ...) are this development
half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers
are in :mod:`outside_sealed13` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass
force, 10 sensor, 12 sensor, 14 mass force). About half of the fourteen are plain memoryless laws of new kinds, half
have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory). Written before any
diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation
against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the motor speed through a LOGARITHMIC (Eyring) law: a paste mixer (an agitator in a
   shear-thinning, yield-stress paste) on the motor's shaft end: c*ln(Omega1/Omega_0) above Omega_0, 0 below (a load
   that grows with the logarithm of the speed: the earlier motor loads are polynomial, power, constant-power, choked or
   resonant in the speed; the eleventh set's logarithm is a rate-and-state friction of the mass with a memory);
3. wheel torque x the wheel speed through a RELIEF VALVE: a gear pump on the wheel's shaft pumps through a throttle
   and a relief valve that cracks at Omega_r's pressure: -c*clip(Omega2, -Omega_r, Omega_r) (a viscous load that
   saturates at a speed: a kink from linear to constant; the earlier wheel laws of the speed are stairs, a PWM, a PI,
   thresholds with a memory, a tank or products);
5. clutch torque x the slip speed through a HYSTERESIS COUPLING: a permanent-magnet hysteresis coupling beside the
   jaw, whose torque is nearly independent of the slip speed once it slips: T_h*tanh((Omega1 - Omega2)/w), in the gap
   and in contact (a Coulomb-like law of the slip, not of the faces' pressure: the second set's dry friction acts in
   contact only and scales with the contact's force; the earlier couplings beside the jaw are viscous);
7. mass force x the WHEEL speed MINUS the mass speed: a powered roller conveyor under the carriage whose speed follows
   a tacho on the wheel's shaft (an electronic line shaft, no mechanical reaction on the wheel), its rollers dragging the
   carriage towards the belt speed: c*(r_b*Omega2 - v) (a viscous coupling of the mass to the other shaft's speed:
   the first set's roller coupling runs from the motor and loads both; the ninth set's sail reads Omega2 squared);
9. a2 sensor x the motor ANGLE TIMES the motor speed: the motor rotor's magnets induce a voltage in a2's unshielded
   cable that runs past the motor: y = x + A*(Omega1/Omega_n)*sin(p*alpha1 + phi), Omega_n = 150 rad/s (Faraday: an
   interference locked to the motor's angle whose amplitude grows with its speed; the first set's rotating gravity and
   the third set's slip ring are on a1, the second set's hum is locked to the time);
11. motor load moment x the motor speed through a ONE-SHOT: an overspeed switch on the motor's shaft fires a timed
    brake: when Omega1 rises through Omega_t (from at or below it) and the brake is off, -T for a fixed time T_h, then
    off until the next rising crossing (the one-shot reads the motor speed every 0.2 ms, off at the run-in's start; the
    fourth set's one-shot reads the spring's extension for the mass, the ninth set's the wheel angle);
13. clutch torque x the slip speed through a SLIP-PUMPED PLATE CLUTCH (a Haldex-type coupling): a reversible gerotor
    between the two halves pumps oil into a plate clutch's piston chamber when the motor overruns the wheel and out
    again when the wheel overruns, the chamber leaking through an orifice: m -> max(0, m + dt*(a*(Omega1 - Omega2) -
    b*sqrt(m))) every 0.2 ms (m = 0 at the run-in's start), the plates passing c*m*tanh((Omega1 - Omega2)/w) (a
    friction whose clamping pressure the slip's own history builds; the eleventh set's fill ramps with the pulse).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed;
no diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2
0.0125 at its a-priori strength, scaled once x6.00 (c 10 -> 60.05 N*m; a2 0.0743 after); 3 a2 0.125; 5 a2 0.104; 7 a2
0.0467, scaled once x1.61 (c 2 -> 3.211 N*s/m; a2 0.0749 after); 9 a2 0.0714; 11 a2 0.0278, scaled once x2.69 (T 3 ->
8.082 N*m; a2 0.130 after); 13 a2 0.000948, scaled once x79.1 (c 1 -> 79.12 N*m/cm^3; a2 0.0709 after) -- the others as
written (docs/foreign_drives.md "The thirteenth set"). Before it, a 0.4 s run of each row only checked that it
simulates.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth to twelfth sets; the memory starts afresh at the run-in's first scan, 2 s before sample 0.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import oneshot_reference, segments, set_memory

OMEGA_N_RAD_S = 150.0              # the speed the cable pickup's amplitude is stated at (9)


# 1. motor load moment x the motor speed through a logarithmic (Eyring) law
class MotorPasteMixer(OutsideForm):
    name = "motor_paste_mixer"
    half = "dev13"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a paste mixer (an agitator in a shear-thinning, yield-stress paste) on the motor's shaft end: "
                   "c*ln(Omega1/Omega_0) on the motor's load above Omega_0, 0 below")
    parameters = (Param("coefficient_Nm", "N*m", (0.0, 100.0), "c"),
                  Param("reference_speed_rad_s", "rad/s", (1.0, 300.0), "Omega_0"))
    note = "a load growing with the logarithm of the speed (an Eyring fluid)"

    def apply(self, b, p):
        w0 = p["reference_speed_rad_s"]
        add_term(b, "motor_load_moment", p["coefficient_Nm"], (K.XS_OMEGA1, K.XF_LOG, w0, 0.0, 0.0),
                 (K.XS_OMEGA1, K.XF_EXCESS_POWER, w0, 0.0, 0.0))

    @staticmethod
    def torque(omega1, p):
        w = np.asarray(omega1, dtype=np.float64)
        w0 = p["reference_speed_rad_s"]
        return np.where(w > w0, p["coefficient_Nm"] * np.log(np.maximum(w, w0) / w0), 0.0)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm']:.6g} N*m * ln(Omega1/{p['reference_speed_rad_s']:.6g} "
                "rad/s) above that speed, 0 below")

    def plugin(self, p):
        return _plugin("MotorPasteMixer", self.name, "motor_load_moment_pu", self.description, [
            ("coefficient_pu", "p.u.", (0.0, 5.0), "c / T_b (T_b = 20 N*m)"),
            ("reference_speed_rad_s", "rad/s", (1.0, 300.0), "Omega_0")],
            "omega1, coefficient_pu, reference_speed_rad_s",
            "coefficient_pu * log(fmax(omega1, reference_speed_rad_s) / reference_speed_rad_s)", "log, fmax")


# 3. wheel torque x the wheel speed through a relief valve
class WheelReliefValvePump(OutsideForm):
    name = "wheel_relief_valve_pump"
    half = "dev13"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a gear pump on the wheel's shaft pumping through a throttle and a relief valve that cracks at "
                   "Omega_r's pressure: -c*clip(Omega2, -Omega_r, Omega_r) on the wheel")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c"),
                  Param("relief_speed_rad_s", "rad/s", (1.0, 300.0), "Omega_r"))
    note = "a viscous load that saturates at a speed (linear -> constant)"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["coefficient_Nm_s_per_rad"],
                 (K.XS_OMEGA2, K.XF_CLIP, p["relief_speed_rad_s"], 0.0, 0.0))

    @staticmethod
    def torque(omega2, p):
        wr = p["relief_speed_rad_s"]
        return -p["coefficient_Nm_s_per_rad"] * np.clip(np.asarray(omega2, dtype=np.float64), -wr, wr)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * clip(Omega2, "
                f"+-{p['relief_speed_rad_s']:.6g} rad/s)")

    def plugin(self, p):
        return _plugin("WheelReliefValvePump", self.name, "wheel_torque_Nm", self.description, [
            ("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c"),
            ("relief_speed_rad_s", "rad/s", (1.0, 300.0), "Omega_r")],
            "omega2, coefficient_Nm_s_per_rad, relief_speed_rad_s",
            "-coefficient_Nm_s_per_rad * fmin(fmax(omega2, -relief_speed_rad_s), relief_speed_rad_s)", "fmin, fmax")


# 5. clutch torque x the slip speed through a hysteresis coupling
class ClutchHysteresisCoupling(OutsideForm):
    name = "clutch_hysteresis_coupling"
    half = "dev13"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a permanent-magnet hysteresis coupling beside the jaw: T_h*tanh((Omega1 - Omega2)/w) from the "
                   "motor to the wheel, in the gap and in contact")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T_h"),
                  Param("smoothing_speed_rad_s", "rad/s", (0.01, 10.0), "w"))
    note = "a Coulomb-like law of the slip speed, not of the faces' pressure"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["torque_Nm"], (K.XS_JAW_SPEED, K.XF_TANH, p["smoothing_speed_rad_s"], 0.0, 0.0))

    @staticmethod
    def torque(omega1, omega2, p):
        slip = np.asarray(omega1, dtype=np.float64) - np.asarray(omega2, dtype=np.float64)
        return p["torque_Nm"] * np.tanh(slip / p["smoothing_speed_rad_s"])

    def law(self, p):
        return (f"clutch torque += {p['torque_Nm']:.6g} N*m * tanh((Omega1 - Omega2)/{p['smoothing_speed_rad_s']:.6g} "
                "rad/s), in the gap and in contact")


# 7. mass force x the wheel speed minus the mass speed
class MassWheelTrackingConveyor(OutsideForm):
    name = "mass_wheel_tracking_conveyor"
    half = "dev13"
    balance = "mass_force"
    depends_on = ("wheel_speed", "mass_speed")
    description = ("a powered roller conveyor under the carriage whose speed follows a tacho on the wheel's shaft (no "
                   "mechanical reaction on the wheel): its rollers drag the carriage with c*(r_b*Omega2 - v)")
    parameters = (Param("coefficient_N_s_per_m", "N*s/m", (0.0, 100.0), "c"),
                  Param("belt_radius_m", "m", (0.0, 1.0), "r_b: the belt's speed per rad/s of the wheel"))
    note = "a viscous coupling of the mass to the other shaft's speed"

    def apply(self, b, p):
        c = p["coefficient_N_s_per_m"]
        add_term(b, "mass_force", c * p["belt_radius_m"], (K.XS_OMEGA2, K.XF_X, 0.0, 0.0, 0.0))
        add_term(b, "mass_force", -c, (K.XS_MASS_SPEED, K.XF_X, 0.0, 0.0, 0.0))

    @staticmethod
    def force(omega2, v, p):
        return p["coefficient_N_s_per_m"] * (p["belt_radius_m"] * np.asarray(omega2, dtype=np.float64)
                                             - np.asarray(v, dtype=np.float64))

    def law(self, p):
        return (f"mass force += {p['coefficient_N_s_per_m']:.6g} N*s/m * ({p['belt_radius_m']:.6g} m * Omega2 - v), v "
                "the mass speed")

    def plugin(self, p):
        return _plugin("MassWheelTrackingConveyor", self.name, "mass_force_N", self.description, [
            ("coefficient_N_s_per_m", "N*s/m", (0.0, 100.0), "c"),
            ("belt_radius_m", "m", (0.0, 1.0), "r_b")],
            "omega2, xdot, coefficient_N_s_per_m, belt_radius_m",
            "coefficient_N_s_per_m * (belt_radius_m * omega2 - xdot)", "")


# 9. a2 sensor x the motor angle times the motor speed
class A2MotorMagnetPickup(OutsideForm):
    name = "a2_motor_magnet_pickup"
    half = "dev13"
    stage = "sensor"
    order = 1                      # the cable, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "motor_angle", "motor_speed")
    description = ("the motor rotor's magnets induce a voltage in a2's unshielded cable: y = x + A*(Omega1/Omega_n)*"
                   "sin(p*alpha1 + phi), Omega_n = 150 rad/s, alpha1 the motor's angle")
    parameters = (Param("amplitude_m_s2", "m/s^2", (0.0, 5.0), "A (at 150 rad/s)"),
                  Param("pole_pairs", "-", (1, 20), "p", "int"),
                  Param("phase_rad", "rad", (-3.1416, 3.1416), "phi"))
    note = "an interference locked to the motor's angle whose amplitude grows with its speed"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], states["alpha1"], states["omega1"], p)

    @staticmethod
    def read(a, alpha1, omega1, p):
        return (np.asarray(a, dtype=np.float64) + p["amplitude_m_s2"] * np.asarray(omega1) / OMEGA_N_RAD_S
                * np.sin(int(p["pole_pairs"]) * np.asarray(alpha1) + p["phase_rad"]))

    def law(self, p):
        return (f"a2 sensor += {p['amplitude_m_s2']:.6g} m/s^2 * (Omega1/150 rad/s) * sin({int(p['pole_pairs'])}*"
                f"alpha1 + {p['phase_rad']:.6g} rad)")


# 11. motor load moment x the motor speed through a one-shot
class MotorOverspeedTimedBrake(OutsideForm):
    name = "motor_overspeed_timed_brake"
    half = "dev13"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("an overspeed switch on the motor's shaft fires a timed brake: when Omega1 rises through Omega_t "
                   "(from at or below it at the previous 0.2 ms scan) while the brake is off, T on the motor's load for "
                   "T_h, then off until the next rising crossing (off at the run-in's start)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("trip_speed_rad_s", "rad/s", (1.0, 300.0), "Omega_t"),
                  Param("hold_s", "s", (2e-4, 0.5), "T_h (a multiple of 0.2 ms)"))
    note = "a one-shot timer: a fixed brake pulse at each overspeed, however long it lasts"

    def apply(self, b, p):
        segments(p["hold_s"], f"{self.name}: hold_s")
        set_memory(b, self.name, K.MK_ONESHOT, K.XS_OMEGA1, p["trip_speed_rad_s"], p["hold_s"])
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def on(omega1_at_scans, p, dt):
        """The brake's state after each scan from Omega1 at the scans' starts (the first scan: the run-in's start)."""
        return oneshot_reference(omega1_at_scans, p["trip_speed_rad_s"], round(p["hold_s"] / dt))

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m for {p['hold_s']:.6g} s from each rise of Omega1 "
                f"through {p['trip_speed_rad_s']:.6g} rad/s while off (a one-shot scanned every 0.2 ms)")


# 13. clutch torque x the slip speed through a slip-pumped plate clutch
class ClutchSlipPumpedPlateClutch(OutsideForm):
    name = "clutch_slip_pumped_plate_clutch"
    half = "dev13"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a Haldex-type coupling beside the jaw: a reversible gerotor driven by the slip fills a plate "
                   "clutch's piston chamber that leaks through an orifice, m -> max(0, m + dt*(a*(Omega1 - Omega2) - "
                   "b*sqrt(m))) every 0.2 ms (m = 0 at the run-in's start); the plates pass c*m*tanh((Omega1 - Omega2)/"
                   "w), w = 0.1 rad/s")
    parameters = (Param("torque_Nm_per_cm3", "N*m/cm^3", (0.0, 100.0), "c"),
                  Param("inflow_cm3_per_rad", "cm^3/rad", (0.0, 10.0), "a"),
                  Param("drain_cm3_s_per_sqrt_cm3", "cm^3/s/sqrt(cm^3)", (1e-3, 1000.0), "b"))
    note = "a friction whose clamping pressure the slip's own history builds"

    SMOOTHING_RAD_S = 0.1

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_TANK, K.XS_JAW_SPEED, p["inflow_cm3_per_rad"], p["drain_cm3_s_per_sqrt_cm3"])
        add_term(b, "clutch_torque", p["torque_Nm_per_cm3"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_TANH, self.SMOOTHING_RAD_S, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def fill(slip_at_scans, p, dt, m0=0.0):
        """The chamber's fill after each scan from the slip at the scans' starts (m0 before the first)."""
        m, out = m0, []
        for s in np.asarray(slip_at_scans, dtype=np.float64).tolist():
            m = max(0.0, m + dt * (p["inflow_cm3_per_rad"] * s - p["drain_cm3_s_per_sqrt_cm3"] * np.sqrt(m)))
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"clutch torque += {p['torque_Nm_per_cm3']:.6g} N*m/cm^3 * m * tanh((Omega1 - Omega2)/0.1 rad/s), "
                f"m -> max(0, m + 0.2 ms*({p['inflow_cm3_per_rad']:.6g} cm^3/rad*(Omega1 - Omega2) - "
                f"{p['drain_cm3_s_per_sqrt_cm3']:.6g} cm^3/s/sqrt(cm^3)*sqrt(m))) every 0.2 ms, m = 0 at the run-in's "
                "start")


FORM_CLASSES = (MotorPasteMixer, WheelReliefValvePump, ClutchHysteresisCoupling, MassWheelTrackingConveyor,
                A2MotorMagnetPickup, MotorOverspeedTimedBrake, ClutchSlipPumpedPlateClutch)
