"""Workbench model files, overrides, versions, history and measurement loading (fast, no simulation)."""

import numpy as np
import pytest

from backlash_monitor.workbench.measurement import (Measurement, MeasurementError, check_against_model,
                                                    load_measurement)
from backlash_monitor.workbench.model import ModelError, load_model, read_history, append_history
from backlash_monitor.workbench.versions import EffectValues, add_effects


def test_default_model_and_overrides():
    m = load_model(None, ["load.mass_kg=12.5"], width_m=0.005, n1=0.93)
    cfg = m.plant_config()
    assert cfg.load.mass_kg == 12.5
    assert m.nominal["width_m"] == 0.005 and m.nominal["n1"] == 0.93


def test_bad_override_and_nominal_are_refused():
    with pytest.raises(ModelError, match="load.mass_kg"):
        load_model(None, ["load.mass_kg=-1"])
    with pytest.raises(ModelError, match="width_m"):
        load_model(None, width_m=0.2)
    with pytest.raises(ModelError, match="SECTION.KEY=VALUE"):
        load_model(None, ["load.mass_kg"])


def test_version_roundtrip_and_history(tmp_path):
    m = load_model(None)
    m.name = "drive"
    m.save(tmp_path / "v1.yaml")
    m1 = load_model(tmp_path / "v1.yaml")
    m2 = add_effects(m1, [EffectValues("wheel_coulomb_friction", {"torque_Nm": 1.5}, {"torque_Nm": 0.2}, "test")])
    assert m2.version == 2 and m2.parent == "v1.yaml"
    m2.save(tmp_path / "v2.yaml")
    again = load_model(tmp_path / "v2.yaml")
    cfg = again.plant_config()
    assert cfg.effects["wheel_coulomb_friction"] and cfg.effect_parameter("wheel_coulomb_friction", "torque_Nm") == 1.5
    assert again.effects_added[0]["effect"] == "wheel_coulomb_friction"
    with pytest.raises(ValueError, match="range"):
        add_effects(m1, [EffectValues("wheel_coulomb_friction", {"torque_Nm": 1000.0})])
    with pytest.raises(ValueError, match="not in the catalogue"):
        add_effects(m1, [EffectValues("no_such_effect", {})])
    append_history(tmp_path / "v2.yaml", {"type": "version", "model": "v2.yaml", "version": 2})
    assert read_history(tmp_path)[0]["version"] == 2


def _table(n=60000, dt=2e-5):
    t = np.arange(n) * dt
    return t, {"a1": np.sin(t), "a2": np.cos(t), "angle_difference": 0.01 * np.ones(n)}


def test_csv_and_npz_measurements(tmp_path):
    t, sig = _table()
    p = tmp_path / "m.csv"
    cols = ["time_s", "a1", "a2", "angle_difference"]
    np.savetxt(p, np.column_stack([t] + [sig[c] for c in cols[1:]]), delimiter=",", header=",".join(cols),
               comments="")
    m = load_measurement(p)
    assert abs(m.sample_period_s - 2e-5) < 1e-12 and np.allclose(m.signals["a2"], sig["a2"])
    np.savez(tmp_path / "m.npz", sample_period_s=2e-5, **sig)
    assert load_measurement(tmp_path / "m.npz").n_samples == len(t)
    np.savez(tmp_path / "bad.npz", sample_period_s=2e-5, a1=sig["a1"])
    with pytest.raises(MeasurementError, match="needs a1, a2 and angle_difference"):
        load_measurement(tmp_path / "bad.npz")


def test_sample_rate_and_length_mismatch_refused():
    model = load_model(None)
    n = 200000
    m = Measurement("x", 1e-4, {"a1": np.zeros(n), "a2": np.zeros(n), "angle_difference": np.zeros(n)})
    with pytest.raises(MeasurementError, match="sample rate 10000 Hz differs"):
        check_against_model(m, model)
    short = Measurement("x", 2e-5, {"a1": np.zeros(1000), "a2": np.zeros(1000), "angle_difference": np.zeros(1000)})
    with pytest.raises(MeasurementError, match="too short"):
        check_against_model(short, model)


def test_cli_refuses_bad_input_without_traceback(tmp_path, capsys):
    from backlash_monitor.__main__ import main
    assert main(["diagnose", str(tmp_path / "missing.npz")]) == 2
    err = capsys.readouterr().err
    assert "does not exist" in err and "Traceback" not in err


def test_candidate_sets_share_noise_and_seeds_do_not():
    """Common random numbers: a tiny parameter change on the same seed moves the output by a tiny amount;
    another seed moves it by the noise."""
    from backlash_monitor.workbench import plant_adapter
    m = load_model(None, ["simulation.run_in_s=0.2"])
    out = plant_adapter.simulate_sets(m, [{}, {"load_mass_drift.relative_change": 1e-6}], [0, 1], 5000,
                                      signals=("a1",))["a1"]
    same_seed = np.abs(out[1, 0] - out[0, 0]).max()
    other_seed = np.abs(out[0, 1] - out[0, 0]).max()
    assert other_seed > 1.0
    assert same_seed < 1e-3 * other_seed


def test_catalogue_has_the_issue_names_with_ranges_inside_bounds():
    from backlash_monitor.workbench import plant_adapter
    model = load_model(None)
    cands = plant_adapter.catalogue(model)
    names = {c.effect for c in cands}
    assert {"wheel_coulomb_friction", "accelerometer_lowpass", "load_mass_drift"} <= names
    reg = model.catalogue
    for c in cands:
        for p in c.parameters:
            lo, hi = reg[c.effect].parameter(p.name).bounds
            assert lo <= p.lower <= p.default <= p.upper <= hi


def test_train_model_needs_out_and_a_valid_model(tmp_path, capsys):
    from backlash_monitor.__main__ import main
    assert main(["train", "--model", str(tmp_path / "m.yaml")]) == 2
    assert "--model needs -o/--output" in capsys.readouterr().err
    assert main(["train", "--model", str(tmp_path / "m.yaml"), "--output", str(tmp_path / "x.npz")]) == 2
    assert "does not exist" in capsys.readouterr().err


def test_mcap_measurement_any_namespace(tmp_path):
    """A bag with the project's topics under a namespace (and a true width, ignored) loads without
    --namespace, and with the right one; a wrong namespace is refused naming what the bag has."""
    from backlash_monitor.bag.simulated import SimulationBagWriter
    n, dt = 3000, 2e-5
    rng = np.random.default_rng(0)
    sig = {k: rng.normal(size=n) for k in ("a1", "a2", "omega1", "omega2", "angle_difference")}
    with SimulationBagWriter(tmp_path / "one.mcap", true_width_m=0.005, namespace="line1/drive7") as bag:
        for k in range(0, n, 1000):
            bag.write_chunk(k, dt, {s: v[k:k + 1000] for s, v in sig.items()})
    m = load_measurement(tmp_path / "one.mcap")
    assert m.sample_period_s == dt and np.array_equal(m.signals["a2"], sig["a2"])
    assert load_measurement(tmp_path / "one.mcap", namespace="/line1/drive7").n_samples == n
    with pytest.raises(MeasurementError, match="no plant/a1"):
        load_measurement(tmp_path / "one.mcap", namespace="/other")
