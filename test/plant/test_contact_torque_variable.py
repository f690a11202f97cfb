"""The clutch's contact torque as a model variable (``contact_torque_Nm``, docs/effects.md): a term that names it
in the motor's or the wheel's balance runs the same on every backend, and matches solve_ivp on the nominal model
plus that term written here from the clutch law itself (drivetrain.clutch_torque, an independent form); a term of
the clutch's own balance may not name it (its terms make it)."""
import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.codegen import kernel_for
from backlash_monitor.plant.drivetrain import clutch_torque
from backlash_monitor.plant.effects import NOMINAL, Effect, Parameter
from backlash_monitor.plant.reference import reference_run

N = 4000        # 80 ms from the settled start: the first pulse's onset entry, far-side impact and contact


class WheelByContact(Effect):
    name = "test_wheel_by_contact"
    balance = "wheel_torque_Nm"
    description = "a wheel torque in proportion to the clutch's contact torque"
    parameters = (Parameter("gain", "-", 0.0, (-1.0, 1.0), "share of T_c"),)

    @staticmethod
    def term(contact_torque_Nm, gain):
        return gain * contact_torque_Nm


class MotorByContact(Effect):
    name = "test_motor_by_contact"
    balance = "motor_load_moment_pu"
    description = "a motor load in proportion to the contact torque's magnitude"
    parameters = (Parameter("gain", "-", 0.0, (-1.0, 1.0), "share of |T_c|/T_b"),)

    @staticmethod
    def term(contact_torque_Nm, base_torque_Nm, gain):
        return gain * fabs(contact_torque_Nm) / base_torque_Nm   # noqa: F821 (mathlib's, in the kernel)


GAINS = {"test_wheel_by_contact.gain": (0.3, 0.0), "test_motor_by_contact.gain": (0.0, 0.4)}


@pytest.fixture(scope="module")
def runs():
    cat = builtin_catalogue().copy()
    cat.register(WheelByContact)
    cat.register(MotorByContact)
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0, "effects.test_wheel_by_contact": True,
                                       "effects.test_motor_by_contact": True}, catalogue=cat)
    scen = [Scenario(0.005, 0.025, 0.89)] * 2
    params = {k: np.array(v) for k, v in GAINS.items()}
    out = {}
    for backend in ("numba", "numba-scalar", "numpy"):
        sim = PlantSimulator(scen, config=cfg, noise=False, backend=backend, parameters=params)
        x0 = sim.state.copy()
        load = sim.motor_load_pu(0, N)
        out[backend] = sim.run(N)
    base = PlantSimulator(scen[:1], config=load_plant_config(overrides={"simulation.run_in_s": 0.0}),
                          noise=False).run(N)
    return {"sim": sim, "x0": x0, "load": load, "out": out, "base": base, "cfg": cfg}


def _independent(i, sim, cfg):
    """The term's contribution to the 11 derivatives, from the clutch law (not from the generated kernel)."""
    T_b, T_m = cfg.motor.base_torque_Nm, cfg.motor.mechanical_time_constant_s
    omb, J2 = cfg.motor.base_mechanical_speed_rad_s, cfg.load.wheel_inertia_kgm2
    kc, dc = cfg.clutch.contact_stiffness_Nm_per_rad, cfg.clutch.contact_damping_Nms_per_rad
    gw, gm = GAINS["test_wheel_by_contact.gain"][i], GAINS["test_motor_by_contact.gain"][i]
    beta = sim.beta[i]

    def extra(t, y, der):
        tc = clutch_torque(y[5], y[4] * omb - y[8], beta, kc, dc)
        d = np.zeros(11)
        d[8] = gw * tc / J2
        d[4] = -gm * abs(tc) / T_b / T_m
        return d
    return extra


@pytest.mark.parametrize("i", [0, 1], ids=["wheel", "motor"])
def test_contact_torque_variable_is_the_clutch_torque_on_every_backend(runs, i):
    out, sim, cfg = runs["out"], runs["sim"], runs["cfg"]
    floors = (("a1", 1.0), ("a2", 0.1), ("omega2", 1.0), ("angle_difference", 1e-3))
    for backend in ("numba-scalar", "numpy"):
        for sig, floor in floors:
            a, b = getattr(out["numba"], sig)[i], getattr(out[backend], sig)[i]
            assert np.max(np.abs(a - b)) <= 1e-9 * max(np.max(np.abs(b)), floor), (backend, sig)
    nominal = kernel_for(tuple(c for c in NOMINAL if c.kind == "term"))
    ref = reference_run(sim, i, runs["load"][i], method="DOP853", rtol=1e-10, atol=1e-12, state0=runs["x0"][i],
                        rhs=nominal, extra=_independent(i, sim, cfg))
    base = runs["base"]
    for sig in ("a1", "omega2"):
        size = np.max(np.abs(getattr(base, sig)[0] - ref[sig]))
        assert size > 1e-6, sig                                   # the term does something
        assert np.max(np.abs(getattr(out["numba"], sig)[i] - ref[sig])) <= 0.02 * size, sig


def test_a_clutch_term_may_not_name_the_contact_torque():
    class Circular(Effect):
        name = "test_circular_clutch"
        balance = "clutch_torque_Nm"
        description = "a contact law of its own result"
        parameters = (Parameter("gain", "-", 0.0, (-1.0, 1.0)),)

        @staticmethod
        def term(contact_torque_Nm, gain):
            return gain * contact_torque_Nm

    with pytest.raises(ValueError, match="contact_torque_Nm.*clutch torque its own balance makes"):
        builtin_catalogue().copy().register(Circular)
