"""An effect that appears mid-run (PlantSimulator.set_config / set_parameters, the plant node's plant_set_at): the
stream goes on from the plant's state with the new values; only run-time values may change."""
import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.simulate import check_runtime_change

SCEN = [Scenario(width_m=0.005, seed=4)]
OUT = ("a1", "a2", "omega2", "angle_difference")


def _run(sim, chunks, n=2500):
    return [sim.run(n) for _ in range(chunks)]


def test_a_switch_mid_run_continues_the_run_and_then_acts():
    """Friction switched on at its neutral default from the start is the nominal plant to rounding (the two term sets
    are two kernels compiled with fastmath: LLVM may contract them differently; in one process they agree to the last
    bit, but after other kernels were compiled in the same test session they differed by ~1e-13); set to
    2 N*m after 0.1 s it leaves every sample before the switch as it was, and from the switch on the load wheel
    decelerates by T / J more than the nominal plant's (the dry torque acts at once; over the first millisecond
    the spring to the mass has not yet passed on a change: the wheel's own inertia J)."""
    nominal = _run(PlantSimulator(SCEN, outputs=OUT), 4)
    cfg_off = load_plant_config(overrides={"effects.wheel_coulomb_friction": True})
    sim = PlantSimulator(SCEN, config=cfg_off, outputs=OUT)
    before = _run(sim, 2)
    sim.set_config(load_plant_config(overrides={"effects.wheel_coulomb_friction": True,
                                                "wheel_coulomb_friction.torque_Nm": 2.0}))
    after = _run(sim, 2)
    for a, b in zip(before, nominal[:2]):
        for s in OUT:
            x, y = getattr(a, s), getattr(b, s)
            assert np.max(np.abs(x - y)) <= 1e-12 * np.max(np.abs(y)), s
    assert after[0].first_sample_index == 5000             # the stream goes on where it was
    assert after[0].omega2[0, 0] == pytest.approx(nominal[2].omega2[0, 0], abs=1e-3)     # no jump at the switch
    k, dt = 50, sim.sample_period_s
    extra = ((after[0].omega2[0, k] - after[0].omega2[0, 0]) - (nominal[2].omega2[0, k] - nominal[2].omega2[0, 0]))
    inertia = load_plant_config().load.wheel_inertia_kgm2
    assert extra / (k * dt) == pytest.approx(-2.0 / inertia, rel=0.25)


def test_set_parameters_changes_one_scenario_of_a_batch():
    cfg = load_plant_config(overrides={"effects.load_mass_drift": True})
    scen = [Scenario(width_m=0.005, seed=4), Scenario(width_m=0.005, seed=5)]
    sim = PlantSimulator(scen, config=cfg, outputs=OUT)
    ref = PlantSimulator(scen, config=cfg, outputs=OUT)
    sim.run(2500), ref.run(2500)
    sim.set_parameters({"load_mass_drift.relative_change": np.array([0.0, 0.3])})
    a, b = sim.run(5000), ref.run(5000)
    assert np.array_equal(a.a2[0], b.a2[0])                  # the unchanged scenario is unchanged
    assert not np.allclose(a.a2[1], b.a2[1])
    assert sim.parameter_values("mass_kg")[1] == pytest.approx(1.3 * sim.parameter_values("mass_kg")[0])
    with pytest.raises(ValueError, match="switched off"):
        sim.set_parameters({"wheel_coulomb_friction.torque_Nm": 1.0})
    assert sim.parameter_values("load_mass_drift.relative_change")[1] == 0.3      # a refused change changes nothing


@pytest.mark.parametrize("new,match", [
    ({"effects.wheel_coulomb_friction": True}, "would switch on wheel_coulomb_friction"),
    ({"simulation.sample_rate_hz": 40000}, "simulation"),
    ({"pulse_load.period_s": 0.2}, "pulse_load"),
])
def test_what_cannot_change_at_run_time_is_refused_naming_it(new, match):
    with pytest.raises(ValueError, match=match):
        check_runtime_change(load_plant_config(), load_plant_config(overrides=new))


@pytest.mark.ros
def test_the_plant_nodes_set_at_entries_are_checked_at_start():
    from backlash_monitor.nodes.plant_simulator import parse_set_at
    assert parse_set_at(["30:effects.wheel_coulomb_friction=true;wheel_coulomb_friction.torque_Nm=1.5", "",
                         "5s:load_mass_drift.relative_change=0.1"]) == [
        (5.0, {"load_mass_drift.relative_change": 0.1}),
        (30.0, {"effects.wheel_coulomb_friction": True, "wheel_coulomb_friction.torque_Nm": 1.5})]
    for bad in ("effects.x=true", "-1:effects.x=true", "abc:a.b=1", "3:"):
        with pytest.raises(ValueError, match="plant_set_at"):
            parse_set_at([bad])
