"""diagnose's memory: the parameter sets are simulated in batches (fitting.Problem.evaluate) whose whole records are
reduced to events before the next batch; the batches must not change what is fitted. Common random numbers hold
across batches (every batch runs the same seeds), so the model's ensemble of a set is the same however the sets
are batched, and a diagnosis with one set per batch gives the verdict and fitted values of one whole batch."""
import numpy as np
import pytest

from backlash_monitor.workbench import analysis, fitting
from backlash_monitor.workbench.diagnose import diagnose
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.synthetic import hidden_effect_recording

# fitted values: the same simulations in other batches; the tolerance allows only floating-point reassociation
VALUE_RTOL = 1e-9


@pytest.fixture(scope="module")
def drive():
    model = load_model(None)
    meas = hidden_effect_recording(model, 2.0, seed=51, config_overrides={
        "effects.load_mass_drift": True, "load_mass_drift.relative_change": 0.3})
    return model, meas


def test_batched_ensemble_is_the_whole_batch(drive, monkeypatch):
    model, meas = drive
    comp = analysis.build_comparison(meas, model, [0, 1, 2])
    p = fitting.Problem(model, comp.events, comp.seeds, meas.n_samples, meas.sample_period_s, comp.conditions,
                        comp.weights, comp.spec_weights, comp.dc_weights, comp.segment_noise, comp.dc_names)
    sets = [{}, {"load_mass_drift.relative_change": 0.2}, {"load_mass_drift.relative_change": -0.1}]
    monkeypatch.setattr(fitting, "BATCH_BYTES", 1e18)
    assert p.sets_per_batch() >= len(sets)
    whole = p.evaluate(sets)
    monkeypatch.setattr(fitting, "BATCH_BYTES", 1.0)
    assert p.sets_per_batch() == 1
    batched = p.evaluate(sets)
    assert batched.seed_means.shape == whole.seed_means.shape == (3, 3, 2, whole.seed_means.shape[-1])
    np.testing.assert_array_equal(batched.n_events, whole.n_events)
    np.testing.assert_allclose(batched.seed_means, whole.seed_means, rtol=0, atol=1e-12)
    for i in range(len(sets)):
        np.testing.assert_allclose(p.pred_of(batched, i), p.pred_of(whole, i), rtol=1e-12, atol=1e-12)
    # the sets differ: the batches keep each set's own runs
    assert not np.allclose(whole.seed_means[1], whole.seed_means[0])
    assert p.n_sets_simulated == 2 * len(sets)


@pytest.mark.slow
def test_one_set_per_batch_same_verdict_and_values(drive, monkeypatch):
    model, meas = drive
    kwargs = dict(seeds=[0, 1, 2], effects=["load_mass_drift", "wheel_inertia_drift"], propose=False)
    monkeypatch.setattr(fitting, "BATCH_BYTES", 1e18)
    whole = diagnose(meas, model, **kwargs).to_json()
    monkeypatch.setattr(fitting, "BATCH_BYTES", 1.0)
    batched = diagnose(meas, model, **kwargs).to_json()
    assert batched["verdict"] == whole["verdict"]
    assert batched["discovery"] == whole["discovery"]
    assert [r["effect"] for r in batched["ranked"]] == [r["effect"] for r in whole["ranked"]]
    for a, b in zip(batched["ranked"], whole["ranked"]):
        for k, v in b["parameters"].items():
            assert a["parameters"][k] == pytest.approx(v, rel=VALUE_RTOL, abs=1e-12), (b["effect"], k)
    assert batched["measured_width"]["width_m"] == pytest.approx(whole["measured_width"]["width_m"], rel=VALUE_RTOL)
