"""Registry of the plant's named, switchable physical terms (SPEC sections 3 and 5).

Each term contributes to one named *balance* of the model:

- ``motor_load_moment_pu``: added to the motor's load moment, T_m dw1/dt = t_e - T_c/T_b - sum(terms)
- ``clutch_torque_Nm``: the torque T_c the clutch transmits (acts +T_c on the wheel, -T_c on the motor)
- ``rim_mass_force_N``: the force F between the wheel rim and the mass (+F on the mass, -r*F on the wheel)
- ``mass_force_N``: an external force on the mass only, m*x'' = F + sum(terms)
- ``wheel_torque_Nm``: an external torque on the wheel only (none built in yet)

The switch of every term is ``effects.<name>`` in ``config/plant.yaml``. How to add a term:
register it here, add its field to :class:`~backlash_monitor.plant.config.EffectsConfig`, and add
its contribution to its balance in the three forms of the right-hand side:
:func:`drivetrain.plant_derivatives` (numpy; solve_ivp reference), :func:`drivetrain.plant_derivatives_scalar`
(numba-scalar backend, zone-crossing step) and :func:`integrator._stage_simd` (default kernel);
the tests check that the three agree. Inputs held over a step (loads, disturbances) go into
:mod:`backlash_monitor.plant.disturbances` only.
"""
from __future__ import annotations

from dataclasses import dataclass

BALANCES = ("motor_load_moment_pu", "clutch_torque_Nm", "rim_mass_force_N", "mass_force_N", "wheel_torque_Nm")


@dataclass(frozen=True)
class EffectTerm:
    name: str
    balance: str
    equation: str
    parameters: tuple[str, ...]
    description: str


TERMS: dict[str, EffectTerm] = {t.name: t for t in (
    EffectTerm("backlash_clutch", "clutch_torque_Nm",
               "T_c = 0 if |D| < beta else s*max(0, k_c(|D|-beta) + s*d_c*(W1-W2)), s = sign D",
               ("clutch.contact_stiffness_Nm_per_rad", "clutch.contact_damping_Nms_per_rad"),
               "stiff, never-pulling contact across the backlash gap (beta = width/r)"),
    EffectTerm("spring", "rim_mass_force_N", "F_s = k*z",
               ("load.spring_stiffness_N_per_m",), "linear spring between rim and mass"),
    EffectTerm("absorber_power_law", "rim_mass_force_N", "F_a = c*|v|^n1*sign(v), c = eta_k*S1/h^n1",
               ("load.absorber_area_m2", "load.absorber_gap_m"),
               "Ostwald-de Waele (power-law fluid) absorber between rim and mass"),
    EffectTerm("working_resistance", "mass_force_N", "F_w = -F0",
               ("load.working_resistance_N",), "constant working resistance on the mass"),
    EffectTerm("pulse_load", "motor_load_moment_pu", "t_pulse = A while (t - t0) mod P < D, t >= t0",
               ("pulse_load.amplitude_pu", "pulse_load.duration_s", "pulse_load.period_s", "pulse_load.first_s"),
               "the system load: rectangular pulses of constant amplitude at equal intervals"),
    EffectTerm("gaussian_disturbance", "motor_load_moment_pu", "N(mean, variance), new value every hold_s, held",
               ("disturbances.gaussian_mean_pu", "disturbances.gaussian_variance_pu2", "disturbances.gaussian_hold_s"),
               "generator of normally distributed values"),
    EffectTerm("pulse_disturbance", "motor_load_moment_pu", "mean +- sqrt(variance), random sign every hold_s",
               ("disturbances.pulse_mean_pu", "disturbances.pulse_variance_pu2", "disturbances.pulse_hold_s"),
               "generator of rectangular impulses (random-sign telegraph)"),
    EffectTerm("constant_motor_load", "motor_load_moment_pu", "t_const = constant_motor_load_pu",
               ("constant_motor_load_pu",), "constant extra load moment"),
)}


def enabled_terms(effects_config) -> list[str]:
    """Names of the switched-on terms of an :class:`EffectsConfig`."""
    return [name for name in TERMS if getattr(effects_config, name)]
