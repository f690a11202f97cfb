"""The coupling balance (``coupling_torque_Nm``, docs/effects.md "Kinds and balances"): a torque from the motor's shaft
to the wheel's beside the jaw, in the gap and in contact. By Newton's third law it is the same torque put on the wheel
(``wheel_torque_Nm``) and taken from the motor (``motor_load_moment_pu``, by the base torque) -- written here as that
pair of terms, an independent form -- on every backend; unlike the clutch's own balance it acts in the gap and may
pull (a spring across the jaw, a slip coupling)."""
import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.effects import Effect, Parameter, validate_effect

N = 6000        # 120 ms from the settled start: the first pulse's onset, the gap crossed, contact again


class CouplingSpring(Effect):
    name = "test_coupling_spring"
    balance = "coupling_torque_Nm"
    description = "a torsion spring and damper across the jaw, in parallel with it"
    parameters = (Parameter("stiffness_Nm_per_rad", "N*m/rad", 0.0, (-1e3, 1e3), "spring across the jaw"),
                  Parameter("damping_Nms_per_rad", "N*m*s/rad", 0.0, (-10.0, 10.0), "damper across the jaw"))

    @staticmethod
    def term(delta, rel_speed, stiffness_Nm_per_rad, damping_Nms_per_rad):
        return stiffness_Nm_per_rad * delta + damping_Nms_per_rad * rel_speed


class WheelSide(CouplingSpring):
    """The same law as a wheel torque (its term inherited)."""
    name = "test_wheel_side"
    balance = "wheel_torque_Nm"
    description = "the spring's torque on the wheel"


class MotorSide(Effect):
    name = "test_motor_side"
    balance = "motor_load_moment_pu"
    description = "the spring's reaction on the motor"
    parameters = CouplingSpring.parameters

    @staticmethod
    def term(delta, rel_speed, base_torque_Nm, stiffness_Nm_per_rad, damping_Nms_per_rad):
        return (stiffness_Nm_per_rad * delta + damping_Nms_per_rad * rel_speed) / base_torque_Nm


K_NM_PER_RAD, D_NMS_PER_RAD = 150.0, 0.4     # 7.5 N*m at the gap's face (beta 0.05 rad): a third of the working torque


def _run(effects, backend):
    cat = builtin_catalogue().copy()
    for e in (CouplingSpring, WheelSide, MotorSide):
        cat.register(e)
    over = {"simulation.run_in_s": 0.0} | {f"effects.{e.name}": True for e in effects}
    cfg = load_plant_config(overrides=over, catalogue=cat)
    params = {f"{e.name}.{p}": np.array([v]) for e in effects
              for p, v in (("stiffness_Nm_per_rad", K_NM_PER_RAD), ("damping_Nms_per_rad", D_NMS_PER_RAD))}
    sim = PlantSimulator([Scenario(0.005, 0.025, 0.89)], config=cfg, noise=False, backend=backend, parameters=params)
    return sim.run(N)


@pytest.mark.parametrize("backend", ["numba", "numba-scalar", "numpy"])
def test_coupling_is_the_wheel_torque_and_the_motor_reaction(backend):
    """The pair of plain terms acts everywhere, in the gap too (neither is gated): so does the coupling term."""
    coupled = _run((CouplingSpring,), backend)
    pair = _run((WheelSide, MotorSide), backend)
    nominal = _run((), backend)
    for sig in ("a1", "a2", "omega1", "omega2"):
        c, p, n = (np.asarray(getattr(r, sig), dtype=float) for r in (coupled, pair, nominal))
        scale = float(np.max(np.abs(p - n)))
        assert scale > 0.0, sig          # the spring moves the drive
        np.testing.assert_allclose(c, p, rtol=0, atol=1e-6 * max(scale, 1.0), err_msg=sig)


def test_a_coupling_term_may_name_the_contact_torque_and_pull():
    class Pulling(Effect):
        name = "test_coupling_contact_share"
        balance = "coupling_torque_Nm"
        description = "a share of the contact torque carried beside the jaw"
        parameters = (Parameter("gain", "-", 0.0, (-1.0, 1.0), "share"),)

        @staticmethod
        def term(contact_torque_Nm, gain):
            return gain * contact_torque_Nm
    validate_effect(Pulling)          # the clutch's own balance refuses contact_torque_Nm; this one takes it
