"""The recorded outputs (plant/outputs.py, one definition for every backend) against their physics:
a1 is the time derivative of r*Omega1 and a2 that of the mass speed x' (exact derivatives at the
sample, docs/model.md "Outputs"), so a central difference of the recorded speeds must match them to
O(h^2) away from the clutch's torque jumps (measured: 99th percentile of the difference 8e-7 of the
peak on every backend; a wrong factor or a wrong state would give an error of the order of the peak)."""
import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.outputs import OUTPUT_NAMES, render
from backlash_monitor.plant.simulate import SimulationChunk


@pytest.mark.parametrize("backend", ["numba", "numba-scalar", pytest.param("numpy", marks=pytest.mark.slow)])
def test_accelerations_are_the_derivatives_of_the_recorded_speeds(backend):
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.1})
    sim = PlantSimulator([Scenario(0.005, 0.025, 0.89, seed=1)], config=cfg, noise=False, backend=backend,
                         record_states=True)
    ch = sim.run(10_000)                                   # across the load pulse: contact, impacts
    h, r = sim.sample_period_s, cfg.load.wheel_radius_m
    for a, speed in ((ch.a1[0], r * ch.omega1[0]), (ch.a2[0], ch.states["xdot"][0])):
        central = (speed[2:] - speed[:-2]) / (2 * h)
        err = np.abs(central - a[1:-1])
        assert np.quantile(err, 0.99) <= 1e-4 * np.max(np.abs(a))
    assert np.array_equal(ch.omega2[0], ch.states["omega2"][0])
    assert np.array_equal(ch.angle_difference[0], ch.states["delta"][0])


def test_every_output_is_a_chunk_field_and_unknown_names_are_refused():
    fields = SimulationChunk.__dataclass_fields__
    assert all(name in fields for name in OUTPUT_NAMES)
    with pytest.raises(ValueError, match="names 'omega3'"):
        render("omega3 * g_r", "y[{i}]", "d[{i}]", "tc")
