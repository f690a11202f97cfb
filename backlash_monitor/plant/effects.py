"""Every physical effect of the plant, defined once, as a small class (docs/effects.md).

An effect names the *balance* it acts on and its parameters (unit, default, bounds), carries a
one-line physical description, and, depending on its kind:

- ``kind = "term"``: a math-only ``term`` function (a staticmethod) whose arguments are model
  variables (``MODEL_VARIABLES``) and the effect's own parameters, by name. The compiled kernels and
  the numpy form are generated from the enabled terms (:mod:`backlash_monitor.plant.codegen`);
  balances: ``motor_load_moment_pu``, ``clutch_torque_Nm`` (the contact law, gated by the
  backlash_clutch), ``rim_mass_force_N``, ``wheel_torque_Nm``, ``mass_force_N``,
  ``coupling_torque_Nm`` (a torque from the motor's shaft to the wheel's beside the jaw, in and out of
  contact: a flexible element in parallel with it, a slip coupling);
- ``kind = "held_input"``: an input held over each sample step, on the motor's load moment
  (pulse load, the two disturbance generators, a constant load), produced in
  :mod:`backlash_monitor.plant.disturbances`;
- ``kind = "drift"``: a change of one model parameter from its nominal value (``target``), relative
  (``value*(1 + change)``) or absolute (``value + change``);
- ``kind = "sensor"``: a stage on the published a1/a2 (``apply``), the same in batch and live
  (both go through :meth:`PlantSimulator.run`).

Which effects a config may switch on is an :class:`~backlash_monitor.plant.catalogue.EffectCatalogue`,
passed as an object: the built-in one (``NOMINAL`` + ``CATALOGUE`` + installed entry points of the
group ``backlash_monitor.effects``) or a copy with a user's plug-in files (``--effects-file
my_effects.py``), see :mod:`backlash_monitor.plant.catalogue`.
"""
from __future__ import annotations

import ast
import difflib
import inspect
import math
import textwrap
from dataclasses import dataclass

import numpy as np

from . import lags as _lags
from .mathlib import cos, exp, fabs, fmax, fmin, log, power, sign, sin, smooth_sign, sqrt, where  # noqa: F401 (terms run in Python too)

# the balances of the terms (docs/effects.md "Kinds and balances"); coupling_torque_Nm last: the gated terms'
# accumulator rows are in this order, the earlier ones keep their rows
BALANCES = ("motor_load_moment_pu", "clutch_torque_Nm", "rim_mass_force_N", "wheel_torque_Nm", "mass_force_N",
            "coupling_torque_Nm")
SENSOR_BALANCE = "sensor_a1_a2"
DRIFT_BALANCE = "parameter_drift"
KINDS = ("term", "held_input", "drift", "sensor")
ENTRY_POINT_GROUP = "backlash_monitor.effects"

# variables a term may name (besides its own parameters), with their meaning; codegen binds them
MODEL_VARIABLES = {
    "psi_sa": "stator flux alpha [p.u.]", "psi_sb": "stator flux beta [p.u.]",
    "psi_ra": "rotor flux alpha [p.u.]", "psi_rb": "rotor flux beta [p.u.]",
    "w1": "motor speed [p.u.]", "omega1": "motor speed Omega1 [rad/s]", "omega2": "wheel speed Omega2 [rad/s]",
    "delta": "angle difference Delta = alpha1 - alpha2 [rad]", "alpha1": "motor shaft angle [rad]",
    "alpha2": "wheel angle [rad]", "z": "spring/absorber extension r*alpha2 - x [m]", "xdot": "mass speed [m/s]",
    "v": "rim-mass relative speed r*Omega2 - xdot [m/s]", "rel_speed": "Omega1 - Omega2 [rad/s]",
    "te": "electromagnetic torque [p.u.]",
    "load_moment_pu": "the motor's load moment input [p.u.]: the load pulses (the press strokes) and any constant load",
    "pulse_time_s": "the time since the latest load pulse began, its rising edge [s] (0 <= t < the pulse period; held "
                    "over each sample step like load_moment_pu; the recording's pulse train in the workbench)",
    "pulse_off_time_s": "the time since the latest load pulse ended, its falling edge [s] (0 <= t < the pulse period; "
                        "held like pulse_time_s)",
    "penetration": "|Delta| - beta [rad] (>= 0 in contact)",
    "approach_speed": "sign(Delta)*(Omega1 - Omega2) [rad/s] (> 0: contact closing)",
    "beta": "half gap width/r [rad]", "wheel_radius_m": "r [m]", "wheel_inertia_kgm2": "J2 [kg*m^2]",
    "mass_kg": "m [kg]", "base_torque_Nm": "T_b [N*m]", "base_mechanical_speed_rad_s": "Omega_mb [rad/s]",
    "contact_stiffness_Nm_per_rad": "the clutch's k_c [N*m/rad]",
    "contact_damping_Nms_per_rad": "the clutch's d_c [N*m*s/rad]",
    "contact_torque_Nm": "T_c, the clutch's contact torque on the wheel [N*m] (signed as Delta; 0 in the gap); "
                         "not in the clutch_torque_Nm balance, whose terms make it",
}
MODEL_VARIABLES.update(_lags.MODEL_VARIABLES)     # the first-order lags of the drive's states (plant/lags.py)
CLUTCH_MADE = ("contact_torque_Nm",)     # variables the clutch balance's own terms make: not arguments of them


@dataclass(frozen=True)
class Parameter:
    """One parameter of an effect. ``config_key``: for the nominal model's effects, the existing config
    key its default is read from (``clutch.contact_stiffness_Nm_per_rad``); ``source="scenario"``: the
    default comes from each Scenario (absorber coefficient and flow index)."""
    name: str
    unit: str
    default: float
    bounds: tuple
    description: str = ""
    config_key: str | None = None
    source: str = "config"

    def check(self, effect: str, value) -> None:
        lo, hi = self.bounds
        arr = np.asarray(value, dtype=np.float64)
        if not np.all(np.isfinite(arr)) or np.any(arr < lo) or np.any(arr > hi):
            bad = arr[~(np.isfinite(arr) & (arr >= lo) & (arr <= hi))].ravel()[0] if arr.ndim else float(arr)
            raise ValueError(f"effect parameter {effect}.{self.name} = {bad!r} is out of range; "
                             f"allowed: {lo} <= value <= {hi} [{self.unit}]")


class Effect:
    """Base class of every effect (see the module docstring); subclass and set the class attributes."""
    name: str = ""
    balance: str = ""
    description: str = ""
    parameters: tuple = ()
    kind: str = "term"
    nominal: bool = False          # part of the nominal model (on by default)
    target: str = ""               # drift: the model value it changes
    relative: bool = True          # drift: relative (value*(1+change)) or absolute (value + change)
    term = None

    @classmethod
    def parameter(cls, name: str) -> Parameter:
        for p in cls.parameters:
            if p.name == name:
                return p
        raise KeyError(name)

    @classmethod
    def parameter_names(cls) -> tuple:
        return tuple(p.name for p in cls.parameters)


# ------------------------------------------------------------------ the nominal model's effects
class BacklashClutch(Effect):
    name = "backlash_clutch"
    balance = "clutch_torque_Nm"
    nominal = True
    description = ("stiff, never-pulling contact across the backlash gap (beta = width/r): "
                   "T_c = s*max(0, k_c*(|D|-beta) + d_c*s*(W1-W2)) outside the zone, exactly 0 inside")
    parameters = (
        Parameter("contact_stiffness_Nm_per_rad", "N*m/rad", 3000.0, (1e-6, 1e7), "contact stiffness k_c",
                  config_key="clutch.contact_stiffness_Nm_per_rad"),
        Parameter("contact_damping_Nms_per_rad", "N*m*s/rad", 20.0, (0.0, 1e5), "contact damping d_c",
                  config_key="clutch.contact_damping_Nms_per_rad"),
    )

    @staticmethod
    def term(penetration, approach_speed, contact_stiffness_Nm_per_rad, contact_damping_Nms_per_rad):
        return contact_stiffness_Nm_per_rad * penetration + contact_damping_Nms_per_rad * approach_speed


class Spring(Effect):
    name = "spring"
    balance = "rim_mass_force_N"
    nominal = True
    description = "linear spring between rim and mass, F_s = k*z"
    parameters = (Parameter("stiffness_N_per_m", "N/m", 100.0, (0.0, 1e7), "spring stiffness k",
                            config_key="load.spring_stiffness_N_per_m"),)

    @staticmethod
    def term(z, stiffness_N_per_m):
        return stiffness_N_per_m * z


class AbsorberPowerLaw(Effect):
    name = "absorber_power_law"
    balance = "rim_mass_force_N"
    nominal = True
    description = ("Ostwald-de Waele (power-law fluid) absorber between rim and mass, F_a = c*|v|^n1*sign(v), "
                   "c = eta_k*S1/h^n1")
    parameters = (
        Parameter("coefficient", "N*(s/m)^n1", 17.0, (0.0, 1e12), "c = eta_k*S1/h^n1 (default: from the Scenario)",
                  source="scenario"),
        Parameter("flow_index", "-", 0.89, (0.01, 3.0), "n1 (default: from the Scenario)", source="scenario"),
    )

    @staticmethod
    def term(v, coefficient, flow_index):
        return coefficient * power(fabs(v), flow_index) * sign(v)


class WorkingResistance(Effect):
    name = "working_resistance"
    balance = "mass_force_N"
    nominal = True
    description = "constant working resistance on the mass, F_w = -F0"
    parameters = (Parameter("force_N", "N", 30.0, (0.0, 1e5), "F0", config_key="load.working_resistance_N"),)

    @staticmethod
    def term(force_N):
        return -force_N


class PulseLoad(Effect):
    name = "pulse_load"
    balance = "motor_load_moment_pu"
    kind = "held_input"
    nominal = True
    description = "the system load: rectangular pulses of constant amplitude at equal intervals on the motor"
    parameters = (
        Parameter("amplitude_pu", "p.u.", 1.6, (-10.0, 10.0), "pulse amplitude", config_key="pulse_load.amplitude_pu"),
    )


class GaussianDisturbance(Effect):
    name = "gaussian_disturbance"
    balance = "motor_load_moment_pu"
    kind = "held_input"
    nominal = True
    description = "generator of normally distributed values N(mean, variance), a new value every hold_s, held"
    parameters = ()    # config section disturbances (global, not per scenario)


class PulseDisturbance(Effect):
    name = "pulse_disturbance"
    balance = "motor_load_moment_pu"
    kind = "held_input"
    nominal = True
    description = "generator of rectangular impulses: mean +- sqrt(variance) with a random sign every hold_s"
    parameters = ()


class ConstantMotorLoad(Effect):
    name = "constant_motor_load"
    balance = "motor_load_moment_pu"
    kind = "held_input"
    description = "constant extra load moment on the motor (held input; see also motor_load_offset)"
    parameters = (Parameter("load_pu", "p.u.", 0.0, (-10.0, 10.0), "the load moment",
                            config_key="constant_motor_load_pu"),)


# ------------------------------------------------------------------ the catalogue of candidate effects
_FRICTION_EPS = "1e-3 rad/s"


class WheelCoulombFriction(Effect):
    name = "wheel_coulomb_friction"
    balance = "wheel_torque_Nm"
    description = ("dry (Coulomb) friction on the wheel bearing, -T*sign(Omega2); sign smoothed as "
                   "x/sqrt(x^2+eps^2), eps = 1e-3 rad/s")
    parameters = (Parameter("torque_Nm", "N*m", 0.0, (0.0, 50.0), "friction torque T"),)

    @staticmethod
    def term(omega2, torque_Nm):
        return -torque_Nm * smooth_sign(omega2, 1e-3)


class WheelViscousFriction(Effect):
    name = "wheel_viscous_friction"
    balance = "wheel_torque_Nm"
    description = "viscous friction on the wheel bearing, -b*Omega2"
    parameters = (Parameter("damping_Nms_per_rad", "N*m*s/rad", 0.0, (0.0, 1.0), "viscous coefficient b"),)

    @staticmethod
    def term(omega2, damping_Nms_per_rad):
        return -damping_Nms_per_rad * omega2


class WheelStribeckFriction(Effect):
    name = "wheel_stribeck_friction"
    balance = "wheel_torque_Nm"
    description = ("Stribeck excess of static over dry friction on the wheel, "
                   "-T_s*exp(-(Omega2/w_s)^2)*sign(Omega2) (add wheel_coulomb_friction for the dry part)")
    parameters = (Parameter("excess_torque_Nm", "N*m", 0.0, (0.0, 50.0), "static minus Coulomb torque T_s"),
                  Parameter("stribeck_speed_rad_s", "rad/s", 10.0, (0.01, 1000.0), "Stribeck speed w_s"))

    @staticmethod
    def term(omega2, excess_torque_Nm, stribeck_speed_rad_s):
        x = omega2 / stribeck_speed_rad_s
        return -excess_torque_Nm * exp(-x * x) * smooth_sign(omega2, 1e-3)


class MotorCoulombFriction(Effect):
    name = "motor_coulomb_friction"
    balance = "motor_load_moment_pu"
    description = "dry friction in the motor bearings, T/T_b*sign(Omega1) on the load moment (sign smoothed, eps 1e-3 rad/s)"
    parameters = (Parameter("torque_Nm", "N*m", 0.0, (0.0, 20.0), "friction torque T"),)

    @staticmethod
    def term(omega1, base_torque_Nm, torque_Nm):
        return torque_Nm / base_torque_Nm * smooth_sign(omega1, 1e-3)


class ClutchContactStiffness(Effect):
    name = "clutch_contact_stiffness"
    balance = "clutch_torque_Nm"
    description = "contact stiffness differing from nominal: adds e*k_c*(|D|-beta) to the contact law"
    parameters = (Parameter("relative_change", "-", 0.0, (-0.9, 10.0), "e: k_c -> k_c*(1+e)"),)

    @staticmethod
    def term(penetration, contact_stiffness_Nm_per_rad, relative_change):
        return relative_change * contact_stiffness_Nm_per_rad * penetration


class ClutchContactDamping(Effect):
    name = "clutch_contact_damping"
    balance = "clutch_torque_Nm"
    description = "contact damping differing from nominal: adds e*d_c*s*(W1-W2) to the contact law"
    parameters = (Parameter("relative_change", "-", 0.0, (-1.0, 10.0), "e: d_c -> d_c*(1+e)"),)

    @staticmethod
    def term(approach_speed, contact_damping_Nms_per_rad, relative_change):
        return relative_change * contact_damping_Nms_per_rad * approach_speed


class ShaftCompliance(Effect):
    name = "shaft_compliance"
    balance = "clutch_torque_Nm"
    description = ("a massless torsional shaft of compliance C in series with the jaw contact: "
                   "k_c -> k_c/(1 + k_c*C) (quasi-static; the damper stays at the contact)")
    parameters = (Parameter("compliance_rad_per_Nm", "rad/(N*m)", 0.0, (0.0, 1e-2), "shaft compliance C = 1/k_s"),)

    @staticmethod
    def term(penetration, contact_stiffness_Nm_per_rad, compliance_rad_per_Nm):
        kc = contact_stiffness_Nm_per_rad
        return -kc * kc * compliance_rad_per_Nm / (1.0 + kc * compliance_rad_per_Nm) * penetration


class MassForceOffset(Effect):
    name = "mass_force_offset"
    balance = "mass_force_N"
    description = "a constant force on the mass (gravity on an incline, a preload), +F along x"
    parameters = (Parameter("force_N", "N", 0.0, (-1e4, 1e4), "force F"),)

    @staticmethod
    def term(force_N):
        return force_N


class MotorLoadOffset(Effect):
    name = "motor_load_offset"
    balance = "motor_load_moment_pu"
    description = "a constant extra load moment on the motor shaft (compiled term; a fit parameter)"
    parameters = (Parameter("load_pu", "p.u.", 0.0, (-2.0, 2.0), "load moment"),)

    @staticmethod
    def term(load_pu):
        return load_pu


class TorqueRipple(Effect):
    name = "torque_ripple"
    balance = "motor_load_moment_pu"
    description = "a load-moment ripple locked to the motor angle, A*sin(order*alpha1 + phase) (cogging, gear mesh)"
    parameters = (Parameter("amplitude_pu", "p.u.", 0.0, (0.0, 2.0), "amplitude A"),
                  Parameter("order", "per revolution", 1.0, (0.0, 50.0), "harmonic order"),
                  Parameter("phase_rad", "rad", 0.0, (-math.pi, math.pi), "phase"))

    @staticmethod
    def term(alpha1, amplitude_pu, order, phase_rad):
        return amplitude_pu * sin(order * alpha1 + phase_rad)


class AccelerometerBias(Effect):
    name = "accelerometer_bias"
    balance = SENSOR_BALANCE
    kind = "sensor"
    description = "a constant offset on the published accelerations: a -> a + b (applied last)"
    parameters = (Parameter("a1_m_s2", "m/s^2", 0.0, (-1000.0, 1000.0), "bias of a1"),
                  Parameter("a2_m_s2", "m/s^2", 0.0, (-1000.0, 1000.0), "bias of a2"))
    order = 2


class AccelerometerGain(Effect):
    name = "accelerometer_gain"
    balance = SENSOR_BALANCE
    kind = "sensor"
    description = "a scale error of the accelerometers: a -> a*(1 + g) (after the low-pass, before the bias)"
    parameters = (Parameter("a1_relative_change", "-", 0.0, (-0.99, 10.0), "g of a1"),
                  Parameter("a2_relative_change", "-", 0.0, (-0.99, 10.0), "g of a2"))
    order = 1


class AccelerometerLowpass(Effect):
    name = "accelerometer_lowpass"
    balance = SENSOR_BALANCE
    kind = "sensor"
    description = ("sensor low-pass of n identical first-order sections tau*y' = a - y (n = 1: first order; a sensor's "
                   "anti-alias filter rolls off at n x 20 dB/decade), each exact for a held over each sample: "
                   "y_k = y_{k-1} + (1 - exp(-h/tau))*(a_k - y_{k-1}); tau = 0: no filter")
    parameters = (Parameter("a1_time_constant_s", "s", 0.0, (0.0, 1.0), "tau of a1"),
                  Parameter("a2_time_constant_s", "s", 0.0, (0.0, 1.0), "tau of a2"),
                  Parameter("a1_sections", "-", 1.0, (1.0, 4.0), "number n of a1's first-order sections (rounded)"),
                  Parameter("a2_sections", "-", 1.0, (1.0, 4.0), "number n of a2's first-order sections (rounded)"))
    order = 0


def _drift(name_, target_, relative_, unit_, bounds_, what):
    attrs = dict(name=name_, balance=DRIFT_BALANCE, kind="drift", target=target_, relative=relative_,
                 description=(f"drift of {what} from nominal: "
                              + ("value*(1 + change)" if relative_ else "value + change")),
                 parameters=(Parameter("relative_change" if relative_ else "change", unit_, 0.0, bounds_,
                                       f"change of {what}"),))
    return type("".join(w.title() for w in name_.split("_")), (Effect,), attrs)


DRIFTS = (
    _drift("backlash_width_drift", "width_m", False, "m", (-0.01, 0.01), "the backlash width (stays > 0)"),
    _drift("absorber_consistency_drift", "eta_k", True, "-", (-0.9, 10.0), "the absorber consistency eta_k"),
    _drift("absorber_flow_index_drift", "n1", False, "-", (-0.5, 0.5), "the absorber flow index n1"),
    _drift("spring_stiffness_drift", "spring.stiffness_N_per_m", True, "-", (-0.9, 10.0), "the spring stiffness k"),
    _drift("load_mass_drift", "mass_kg", True, "-", (-0.9, 10.0), "the mass m"),
    _drift("wheel_inertia_drift", "wheel_inertia_kgm2", True, "-", (-0.9, 10.0), "the wheel inertia J2"),
    _drift("working_resistance_drift", "working_resistance.force_N", True, "-", (-1.0, 10.0),
           "the working resistance F0"),
    _drift("pulse_amplitude_drift", "pulse_load.amplitude_pu", True, "-", (-1.0, 10.0), "the pulse load amplitude"),
    # a weaker (or stronger) motor: the rotor's resistance follows its temperature (copper/aluminium +0.4 %/K),
    # the supply voltage the grid; both move the slip at a given torque as a load on the motor shaft does
    _drift("rotor_resistance_drift", "rotor_resistance_pu", True, "-", (-0.9, 10.0),
           "the motor's rotor resistance r_r (its temperature; broken bars)"),
    _drift("supply_voltage_drift", "supply_voltage_scale", True, "-", (-0.9, 1.0), "the motor's supply voltage"),
)

NOMINAL = (BacklashClutch, Spring, AbsorberPowerLaw, WorkingResistance, PulseLoad, GaussianDisturbance,
           PulseDisturbance, ConstantMotorLoad)
CATALOGUE = (WheelCoulombFriction, WheelViscousFriction, WheelStribeckFriction, MotorCoulombFriction,
             ClutchContactStiffness, ClutchContactDamping, ShaftCompliance, MassForceOffset, MotorLoadOffset,
             TorqueRipple, AccelerometerBias, AccelerometerGain, AccelerometerLowpass) + DRIFTS

def term_source(cls) -> str:
    """The source of an effect's term function, renamed ``_t_<name>``, decorators dropped (the text the
    generated kernels inline, and part of their cache key)."""
    func = cls.__dict__.get("term")
    if func is None:
        for base in cls.__mro__:
            if "term" in base.__dict__:
                func = base.__dict__["term"]
                break
    func = func.__func__ if isinstance(func, staticmethod) else func
    src = getattr(func, "__effect_source__", None) or textwrap.dedent(inspect.getsource(func))
    tree = ast.parse(src)
    fn = tree.body[0]
    if not isinstance(fn, ast.FunctionDef):
        raise ValueError(f"effect {cls.name}: term must be a plain function (def term(...): ...)")
    fn.name = f"_t_{cls.name}"
    fn.decorator_list = []
    return ast.unparse(fn)


def term_arguments(cls) -> tuple:
    fn = ast.parse(term_source(cls)).body[0]
    return tuple(a.arg for a in fn.args.args)


def validate_effect(cls) -> None:
    """ValueError naming the problem and the allowed values when ``cls`` is not a valid effect class."""
    name = getattr(cls, "name", "")
    if not isinstance(name, str) or not name.isidentifier() or name.startswith("_"):
        raise ValueError(f"effect class {cls.__name__}: name = {name!r}; allowed: a Python identifier "
                         "not starting with '_'")
    if cls.kind not in KINDS:
        raise ValueError(f"effect {name}: kind = {cls.kind!r}; allowed: {', '.join(KINDS)}")
    allowed_bal = BALANCES + (SENSOR_BALANCE, DRIFT_BALANCE)
    if cls.balance not in allowed_bal:
        raise ValueError(f"effect {name}: balance = {cls.balance!r}; allowed: {', '.join(allowed_bal)}")
    if not cls.description:
        raise ValueError(f"effect {name}: no description; allowed: one line of physics")
    seen = set()
    for p in cls.parameters:
        if not isinstance(p, Parameter) or not p.name.isidentifier() or p.name in seen:
            raise ValueError(f"effect {name}: parameter {p!r} is not a Parameter with a unique identifier name")
        seen.add(p.name)
        lo, hi = p.bounds
        if not (lo <= p.default <= hi):
            raise ValueError(f"effect {name}: parameter {p.name} default {p.default} is outside its bounds {p.bounds}")
    if cls.kind == "term":
        if cls.balance not in BALANCES:
            raise ValueError(f"effect {name}: a term acts on one of {', '.join(BALANCES)}, not {cls.balance!r}")
        args = term_arguments(cls)
        made = [a for a in args if a in CLUTCH_MADE and a not in seen]
        if cls.balance == "clutch_torque_Nm" and made:
            raise ValueError(f"effect {name}: term argument {made[0]!r} is the clutch torque its own balance makes; "
                             "allowed in a clutch_torque_Nm term: its parameters and the model variables but "
                             + ", ".join(CLUTCH_MADE))
        for a in args:
            if a not in seen and a not in MODEL_VARIABLES:
                near = difflib.get_close_matches(a, list(seen) + list(MODEL_VARIABLES), n=1)
                raise ValueError(f"effect {name}: term argument {a!r} is neither a parameter of the effect nor a "
                                 f"model variable" + (f" (nearest: {near[0]!r})" if near else "")
                                 + "; allowed: its parameters and backlash_monitor.plant.effects.MODEL_VARIABLES")


def term_source_or_none(cls):
    try:
        return term_source(cls) if cls.kind == "term" else None
    except (OSError, TypeError):
        return None


CATALOGUE_NAMES = tuple(c.name for c in CATALOGUE)
