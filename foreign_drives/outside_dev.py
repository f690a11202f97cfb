"""Outside mechanisms, DEVELOPMENT half (issue 31 part 4): seven mechanisms outside the catalogue, of kinds the
generator had not, with their laws in the open (docs/foreign_drives.md "Outside mechanisms"). The proposal is
developed on these; the sealed half (:mod:`outside_sealed`) is for the final, once-only test.

Angles: alpha1, alpha2 are the simulator's shaft angles; a recording holds only their difference and the speeds, so
a law locked to an angle is stated with the angle's value at sample 0 in the manifest (``made.angles_at_sample0_rad``):
the phase a user fits on the recording's own angle theta(t) = integral of omega from sample 0 is phi + alpha(0).
"""
from __future__ import annotations

import math

import numpy as np

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (relative to the simulator's angle)")
G_M_S2 = 9.80665


class WheelCamFollower(OutsideForm):
    name = "wheel_cam_follower"
    half = "dev"
    balance = "wheel_torque"
    depends_on = ("wheel_angle",)
    description = ("a cam on the load wheel's shaft lifting a spring-loaded follower (an ejector, a valve): the "
                   "follower's force times the cam's slope, a torque locked to the WHEEL angle, "
                   "-A*sin(th)*(1 + q*(1 - cos(th))), th = alpha2 + phi; conservative (zero work per revolution)")
    parameters = (Param("amplitude_Nm", "N*m", (0.0, 50.0), "A = preload force x eccentricity"),
                  Param("lift_ratio", "-", (0.0, 5.0), "q = follower spring x eccentricity / preload force"),
                  _PHASE)
    note = "two harmonics of the wheel angle in a fixed ratio: -A(1+q) sin(th) + (A q/2) sin(2 th)"

    def apply(self, b, p):
        a, q, ph = p["amplitude_Nm"], p["lift_ratio"], p["phase_rad"]
        add_term(b, "wheel_torque", -a * (1.0 + q), (K.XS_ALPHA2, K.XF_SIN, 1.0, ph, 0.0), nonperiodic=True)
        if q != 0.0:
            add_term(b, "wheel_torque", 0.5 * a * q, (K.XS_ALPHA2, K.XF_SIN, 2.0, 2.0 * ph, 0.0), nonperiodic=True)

    @staticmethod
    def torque(alpha2, p):
        th = alpha2 + p["phase_rad"]
        return -p["amplitude_Nm"] * np.sin(th) * (1.0 + p["lift_ratio"] * (1.0 - np.cos(th)))

    def law(self, p):
        return (f"wheel torque += -{p['amplitude_Nm']:.6g} N*m * sin(alpha2 + {p['phase_rad']:.6g}) * "
                f"(1 + {p['lift_ratio']:.6g} * (1 - cos(alpha2 + {p['phase_rad']:.6g})))")

    def plugin(self, p):
        return _plugin("WheelCamFollower", self.name, "wheel_torque_Nm", self.description, [
            ("amplitude_Nm", "N*m", (0.0, 50.0), "A"), ("lift_ratio", "-", (0.0, 5.0), "q"),
            ("phase_rad", "rad", (-math.pi, math.pi), "phi")],
            "alpha2, amplitude_Nm, lift_ratio, phase_rad",
            "-amplitude_Nm * sin(alpha2 + phase_rad) * (1.0 + lift_ratio * (1.0 - cos(alpha2 + phase_rad)))",
            "sin, cos")


class MotorCrankPump(OutsideForm):
    name = "motor_crank_pump"
    half = "dev"
    balance = "motor_load_moment"
    depends_on = ("motor_angle",)
    description = ("a single-acting pump (a lubrication or coolant pump) on the MOTOR shaft's crank: it loads the "
                   "motor only on its pressure stroke, A*max(0, sin(alpha1 + phi)) on the load moment [p.u.]")
    parameters = (Param("amplitude_pu", "p.u.", (0.0, 2.0), "A (peak, x T_b = 20 N*m)"), _PHASE)
    note = "a half-wave rectified sine of the motor angle: a mean A/pi and harmonics 1, 2, 4, 6, ... at once"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["amplitude_pu"] * C.BASE_TORQUE_NM,
                 (K.XS_ALPHA1, K.XF_SIN_POSITIVE, 1.0, p["phase_rad"], 1.0), nonperiodic=True)

    @staticmethod
    def load_pu(alpha1, p):
        return p["amplitude_pu"] * np.maximum(0.0, np.sin(alpha1 + p["phase_rad"]))

    def law(self, p):
        return f"motor load moment += {p['amplitude_pu']:.6g} p.u. * max(0, sin(alpha1 + {p['phase_rad']:.6g}))"

    def plugin(self, p):
        return _plugin("MotorCrankPump", self.name, "motor_load_moment_pu", self.description, [
            ("amplitude_pu", "p.u.", (0.0, 2.0), "A"), ("phase_rad", "rad", (-math.pi, math.pi), "phi")],
            "alpha1, amplitude_pu, phase_rad", "amplitude_pu * fmax(0.0, sin(alpha1 + phase_rad))", "fmax, sin")


class MassCreepingResistance(OutsideForm):
    name = "mass_creeping_resistance"
    half = "dev"
    balance = "mass_force"
    depends_on = ("time",)
    description = ("a resistance on the mass that creeps up during the recording (material piling up on the "
                   "carriage, a brake pad warming): -dF*min(1, t/T) from sample 0 (t = 0)")
    parameters = (Param("force_N", "N", (0.0, 1000.0), "dF reached at t = T"),
                  Param("creep_time_s", "s", (0.1, 1000.0), "T"))

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_N"], (K.XS_TIME, K.XF_RAMP, p["creep_time_s"], 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def force(t, p):
        return -p["force_N"] * np.clip(np.asarray(t) / p["creep_time_s"], 0.0, 1.0)

    def law(self, p):
        return f"mass force += -{p['force_N']:.6g} N * min(1, t / {p['creep_time_s']:.6g} s), t from sample 0"


class WheelProcessBrake(OutsideForm):
    name = "wheel_process_brake"
    half = "dev"
    balance = "wheel_torque"
    depends_on = ("load_pulse",)
    description = ("a brake on the load wheel applied with every press stroke (the load pulse) and building up "
                   "with its actuator's lag: -T*(1 - exp(-(t - t_pulse)/tau)) while the pulse is on, 0 otherwise")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("build_up_s", "s", (1e-4, 1.0), "tau"))

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_PULSE_AGE, K.XF_RISE, p["build_up_s"], 0.0, 0.0))

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * (1 - exp(-(t - t_pulse) / {p['build_up_s']:.6g} s)) "
                "while the load pulse is on (t_pulse: its start), else 0")


class ClutchGapDrag(OutsideForm):
    name = "clutch_gap_drag"
    half = "dev"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an oil film (or a magnetic drag) between the jaw halves: a torque c*(Omega1 - Omega2) from "
                   "the motor to the wheel at ALL times, inside the backlash gap too, where the catalogue's "
                   "clutch torque is zero")
    parameters = (Param("damping_Nms_per_rad", "N*m*s/rad", (0.0, 10.0), "c"),)
    note = "dissipative: its power c*(Omega1 - Omega2)^2 >= 0; in the gap the only coupling of the two shafts"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["damping_Nms_per_rad"], (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += {p['damping_Nms_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2), in and out of "
                "contact")


class MotorCarriageCoupling(OutsideForm):
    name = "motor_carriage_coupling"
    half = "dev"
    balance = "motor_load_moment"
    depends_on = ("motor_speed", "mass_speed")
    description = ("a fluid coupling from the motor shaft to a roller running on the carriage: a load on the "
                   "motor c*(r*Omega1 - v) [N*m], v the mass speed (the roller's reaction is taken by its guide)")
    parameters = (Param("coefficient_Nms_per_m", "N*m*s/m", (0.0, 200.0), "c"),)
    note = "zero on average (the mass follows the rim); it couples the motor to the mass's oscillation"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["coefficient_Nms_per_m"],
                 (K.XS_MOTOR_RIM_MINUS_MASS, K.XF_X, 0.0, 0.0, 0.0))

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nms_per_m']:.6g} N*m*s/m * (r*Omega1 - v) / T_b "
                "[p.u.], v the mass speed")

    def plugin(self, p):
        return _plugin("MotorCarriageCoupling", self.name, "motor_load_moment_pu", self.description, [
            ("coefficient_Nms_per_m", "N*m*s/m", (0.0, 200.0), "c")],
            "omega1, xdot, wheel_radius_m, base_torque_Nm, coefficient_Nms_per_m",
            "coefficient_Nms_per_m * (wheel_radius_m * omega1 - xdot) / base_torque_Nm", "")


class A1RotatingGravity(OutsideForm):
    name = "a1_rotating_gravity"
    half = "dev"
    stage = "sensor"
    order = 0                      # the sensing element (before the anti-alias filter)
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_angle",)
    description = ("the a1 accelerometer sits on the motor's rim and turns with it: its sensing axis sweeps "
                   "through gravity once per revolution, a1 += g_t*sin(alpha1 + phi) (g_t = g on a horizontal "
                   "shaft)")
    parameters = (Param("amplitude_m_s2", "m/s^2", (0.0, 20.0), "g_t"), _PHASE)

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = sig["a1"] + p["amplitude_m_s2"] * np.sin(states["alpha1"] + p["phase_rad"])

    def law(self, p):
        return f"a1 sensor += {p['amplitude_m_s2']:.6g} m/s^2 * sin(alpha1 + {p['phase_rad']:.6g})"


def _plugin(cls, name, balance, description, params, args, expr, helpers) -> str:
    """A plug-in file's text (docs/effects.md, "Writing an effect") with the exact law. Every default 0 where its
    bounds hold 0 (the amplitude's 0 makes the term neutral), else its lower bound (a speed, a time: the project
    refuses a default outside its bounds, and the law divides by some of them)."""
    imp = ("from backlash_monitor.plant.effects import Effect, Parameter\n"
           + (f"from backlash_monitor.plant.mathlib import {helpers}\n" if helpers else ""))
    ps = "".join(f"        Parameter({n!r}, {u!r}, {0.0 if lo <= 0.0 <= hi else float(lo)!r}, ({lo!r}, {hi!r}), {d!r}),\n"
                 for n, u, (lo, hi), d in params)
    return (f"{imp}\n\nclass {cls}(Effect):\n    name = {name!r}\n    balance = {balance!r}\n"
            f"    description = {description!r}\n    parameters = (\n{ps}    )\n\n    @staticmethod\n"
            f"    def term({args}):\n        return {expr}\n")


FORM_CLASSES = (WheelCamFollower, MotorCrankPump, MassCreepingResistance, WheelProcessBrake, ClutchGapDrag,
                MotorCarriageCoupling, A1RotatingGravity)
