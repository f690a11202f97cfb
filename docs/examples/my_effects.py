"""A user's own effects (docs/effects.md, "Writing an effect"): loaded with

    python -m backlash_monitor simulate --effects-file docs/examples/my_effects.py \
        --set effects.wheel_drag=true --set wheel_drag.coefficient_Nms2_per_rad2=1e-4

Each class is one physical effect: its balance, parameters (unit, default, bounds), a one-line
description and a math-only term whose arguments are model variables (effects.MODEL_VARIABLES)
and its own parameters, by name.
"""
from backlash_monitor.plant.effects import Effect, Parameter
from backlash_monitor.plant.mathlib import fabs


class WheelDrag(Effect):
    """Quadratic (aerodynamic) drag on the wheel."""
    name = "wheel_drag"
    balance = "wheel_torque_Nm"
    description = "aerodynamic drag on the wheel, -c*Omega2*|Omega2|"
    parameters = (Parameter("coefficient_Nms2_per_rad2", "N*m*s^2/rad^2", 0.0, (0.0, 1.0), "drag coefficient c"),)

    @staticmethod
    def term(omega2, coefficient_Nms2_per_rad2):
        return -coefficient_Nms2_per_rad2 * omega2 * fabs(omega2)


class MyViscousWheel(Effect):
    """The catalogue's wheel_viscous_friction written as a plug-in (the benchmark compares their speed)."""
    name = "my_viscous_wheel"
    balance = "wheel_torque_Nm"
    description = "viscous friction on the wheel bearing, -b*Omega2 (a plug-in copy of wheel_viscous_friction)"
    parameters = (Parameter("damping_Nms_per_rad", "N*m*s/rad", 0.0, (0.0, 1.0), "viscous coefficient b"),)

    @staticmethod
    def term(omega2, damping_Nms_per_rad):
        return -damping_Nms_per_rad * omega2
