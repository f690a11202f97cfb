"""A user's plug-in locked to the load wheel's angle (docs/effects.md, docs/workbench.md "Terms locked to a shaft's
angle"): a torque -A*sin(alpha2 + phi) on the wheel, once per revolution (an unbalanced or eccentric wheel, a cam).

    python -m backlash_monitor diagnose BAG --effects-file docs/examples/wheel_angle_torque.py

The workbench fits such a term as a sine/cosine pair: its phase has no derivative at A = 0, and the model's wheel
angle lines up with the recording's only up to a constant, which phi takes up."""
from backlash_monitor.plant.effects import Effect, Parameter
from backlash_monitor.plant.mathlib import sin


class WheelAngleTorque(Effect):
    name = "wheel_angle_torque"
    balance = "wheel_torque_Nm"
    description = "a torque locked to the wheel angle, -A*sin(alpha2 + phi)"
    parameters = (Parameter("amplitude_Nm", "N*m", 0.0, (0.0, 20.0), "amplitude A"),
                  Parameter("phase_rad", "rad", 0.0, (-3.141592653589793, 3.141592653589793), "phase phi"))

    @staticmethod
    def term(alpha2, amplitude_Nm, phase_rad):
        return -amplitude_Nm * sin(alpha2 + phase_rad)
