"""The workbench's width check (workbench/width.py): what the monitor publishes per onset window of a
recording -- the continuous width (shape a1+a2) and the fused candidate width -- and the errors of one drive
against its true width."""
import numpy as np
import pytest

from backlash_monitor.estimation import DEFAULT_FUSION_EVENTS
from backlash_monitor.plant import K2_WIDTHS_M
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.synthetic import hidden_effect_recording
from backlash_monitor.workbench.width import WidthTrace, continuous_widths, monitor_widths, width_errors

DURATION_S = 3.0            # 12 onset events: the fusion (8 events) fills
PER_WINDOW_BOUND_MM = 0.3   # per-window mean |error| at a candidate width on the default model (measured ~0.1)


@pytest.fixture(scope="module")
def clean_drive():
    width = 0.005
    model = load_model(None, width_m=width)
    return width, hidden_effect_recording(model, DURATION_S, seed=61)


def test_monitor_widths_on_a_clean_drive_give_the_true_width(clean_drive):
    width, meas = clean_drive
    trace = monitor_widths(meas)
    assert trace.continuous_m.size >= 10
    # the fused width fills up to the fusion length, one more event per onset window
    assert list(trace.fused_events[:DEFAULT_FUSION_EVENTS]) == list(range(1, DEFAULT_FUSION_EVENTS + 1))
    assert set(np.round(trace.fused_m, 6)) <= set(np.round(K2_WIDTHS_M, 6))
    err = width_errors(trace, width)
    assert err["per_window_mean_abs_mm"] < PER_WINDOW_BOUND_MM
    assert err["fused_final_abs_mm"] == 0.0 and err["fused_mean_abs_mm"] == 0.0
    assert err["onset_windows"] == trace.continuous_m.size
    np.testing.assert_array_equal(continuous_widths(meas), trace.continuous_m)


def test_width_errors_definitions():
    trace = WidthTrace(continuous_m=np.array([0.0074, 0.0077, 0.0075, 0.0072]),
                       fused_m=np.array([0.005, 0.0075, 0.0075, 0.009]), fused_events=np.array([1, 2, 2, 2]),
                       fused_continuous_m=np.array([0.0074, 0.00755, 0.0076, 0.00735]))
    err = width_errors(trace, 0.0075, fusion_events=2)
    assert err["per_window_mean_abs_mm"] == pytest.approx((0.1 + 0.2 + 0.0 + 0.3) / 4)
    assert err["bias_mm"] == pytest.approx((-0.1 + 0.2 + 0.0 - 0.3) / 4)
    assert err["fused_final_abs_mm"] == pytest.approx(1.5)              # the last published fused width
    assert err["fused_mean_abs_mm"] == pytest.approx(1.5 / 3)           # over the full fusions only
    assert err["fused_continuous_mean_abs_mm"] == pytest.approx((0.05 + 0.1 + 0.15) / 3)
    with pytest.raises(ValueError, match="no onset window"):
        width_errors(WidthTrace(np.zeros(0), np.zeros(0), np.zeros(0, dtype=int), np.zeros(0)), 0.0075)


def test_training_on_several_model_versions_deals_the_seeds_out(tmp_path):
    """build_library with a list of plant configs (train --model A --model B): seed k simulates config k mod n,
    the windows are pooled (the same windows as each config trained alone on its seeds)."""
    from backlash_monitor.classifier.dataset import collect_windows
    from backlash_monitor.classifier.training import build_library
    from backlash_monitor.workbench.versions import EffectValues, add_effects
    model = load_model(None)
    heavy = add_effects(model, [EffectValues("load_mass_drift", {"relative_change": 0.3})])
    configs = [model.plant_config(), heavy.plant_config()]
    lib = build_library("contact_loss", (1000, 1001), duration_s=0.5, config=configs)
    alone = [collect_windows((s,), "contact_loss", duration_s=0.5, config=c) for s, c in zip((1000, 1001), configs)]
    assert lib.training["seeds_per_config"] == [[1000], [1001]]
    assert lib.training["n_onset_windows"] == sum(len(w) for w in alone)
    assert lib.settings["plant_config_hash"] == "+".join(w.info["plant_config_hash"] for w in alone)
    assert alone[0].info["plant_config_hash"] != alone[1].info["plant_config_hash"]
    with pytest.raises(ValueError, match="at least 2 training seeds"):
        build_library("contact_loss", (1000,), duration_s=0.5, config=configs)


def test_versions_that_differ_only_in_an_effect_value_do_not_share_training_windows(tmp_path, monkeypatch):
    """The window cache is keyed by the plant config's hash: it must cover the effects' values (held beside
    the config's dataclass fields). Before, load_mass_drift +0.30 and +0.45 hashed alike and the second
    training silently reused the first one's windows."""
    from backlash_monitor.classifier import dataset
    from backlash_monitor.classifier.patterns import config_hash
    from backlash_monitor.workbench.versions import EffectValues, add_effects
    monkeypatch.setattr(dataset, "CACHE_DIR", tmp_path / "cache")
    model = load_model(None)
    a, b = (add_effects(model, [EffectValues("load_mass_drift", {"relative_change": v})]).plant_config()
            for v in (0.30, 0.45))
    assert config_hash(a) != config_hash(b)
    assert config_hash(model.plant_config()) == config_hash(dataset.load_plant_config())   # nominal: as before
    # the six widths at one eta_k and n1 (one SIMD vector of drives, not the 120 of the whole grid): the cache's
    # key is under test, and the grid is part of the key alike for both versions
    grid = dict(eta_k_values=(0.025,), n1_values=(0.89,), duration_s=0.5)
    wa = dataset.collect_windows((1000,), "contact_loss", config=a, **grid)         # cached
    wb = dataset.collect_windows((1000,), "contact_loss", config=b, **grid)
    fresh = dataset.collect_windows((1000,), "contact_loss", config=b, cache=False, **grid)
    assert wb.a1.shape == fresh.a1.shape and np.array_equal(wb.a1, fresh.a1)
    assert not (wa.a1.shape == wb.a1.shape and np.array_equal(wa.a1, wb.a1))


def test_train_several_models_needs_as_many_seeds(tmp_path, capsys):
    from backlash_monitor.__main__ import main
    model = load_model(None)
    model.save(tmp_path / "a.yaml")
    model.save(tmp_path / "b.yaml")
    assert main(["train", "--model", str(tmp_path / "a.yaml"), "--model", str(tmp_path / "b.yaml"),
                 "--seeds", "1000", "--output", str(tmp_path / "x.npz"), "--no-progress"]) == 2
    assert "2 --model files need at least 2 --seeds" in capsys.readouterr().err


def _width_fit(change_m: float, uncertainty_m: float):
    from backlash_monitor.workbench.fitting import FitResult
    return FitResult("backlash_width_drift", ["change"], ["m"], np.array([change_m]), np.array([uncertainty_m]),
                     np.zeros(1), (np.array([-0.003]), np.array([0.003])), 0.9, -30.0, 0.0, np.zeros((2, 3)), 0.9, 1)


def test_a_width_within_two_of_its_uncertainties_of_the_nominal_is_not_measured_as_another_width():
    """The width has no nominal tolerance (it is the measurand), so its own fit uncertainty decides: 8.44 +- 0.11 mm
    on an 8.30 mm model (a clean foreign drive just outside the event average's band) is no other width."""
    from backlash_monitor.workbench import plant_adapter
    from backlash_monitor.workbench.decisions import qualifies
    width = next(c for c in plant_adapter.catalogue(load_model(None)) if c.name == "backlash_width_drift")
    assert not qualifies(_width_fit(0.14e-3, 0.11e-3), width)
    assert qualifies(_width_fit(0.5e-3, 0.11e-3), width)
    assert not qualifies(_width_fit(-0.2e-3, 0.11e-3), width)
    assert qualifies(_width_fit(-0.3e-3, 0.11e-3), width)


def test_a_weakly_evidenced_effect_within_two_of_its_uncertainties_does_not_qualify():
    """Below decisive evidence (delta_ic -10) a single effect must also stand out from its own uncertainty: a clean
    foreign drive took a shaft compliance of 2.3e-5 +- 2.3e-5 rad/(N*m) at delta_ic -3.9; with decisive evidence the IC
    alone decides (a nonlinear parameter's jackknife can be far off)."""
    from backlash_monitor.workbench import plant_adapter
    from backlash_monitor.workbench.decisions import qualifies
    from backlash_monitor.workbench.fitting import FitResult
    shaft = next(c for c in plant_adapter.catalogue(load_model(None)) if c.name == "shaft_compliance")

    def fit(value, unc, delta_ic):
        return FitResult("shaft_compliance", ["compliance_rad_per_Nm"], ["rad/(N*m)"], np.array([value]),
                         np.array([unc]), np.zeros(1), (np.zeros(1), np.array([1e-3])), 0.9, delta_ic, 0.0,
                         np.zeros((2, 3)), 0.9, 1)
    assert not qualifies(fit(2.3e-5, 2.3e-5, -3.9), shaft)
    assert qualifies(fit(2.3e-5, 0.5e-5, -3.9), shaft)
    assert qualifies(fit(2.3e-5, 2.3e-5, -40.0), shaft)


def test_the_measurand_form_tolerance_is_how_far_the_width_moves_with_the_nominal_values():
    """A nominal value off by its sigma moves a width fitted alone by the projection of its prediction change on the
    width's direction; independent nominal values add in quadrature, and a direction orthogonal to the width's moves
    it not at all (linear algebra on a toy prediction space, identity metric)."""
    from types import SimpleNamespace

    from backlash_monitor.workbench import tolerance

    class Toy:
        target_vec = np.zeros(4)
        spectral_slice = slice(4, 4)
        ws = np.zeros(0)

        @staticmethod
        def project(r):
            return r

    width_col = np.array([1.0, 0.0, 0.0, 0.0])         # the width's prediction change per metre
    mass = SimpleNamespace(parameters=[SimpleNamespace(key="load_mass_drift.relative_change")])      # sigma 0.02
    spring = SimpleNamespace(parameters=[SimpleNamespace(key="spring_stiffness_drift.relative_change")])  # 0.05
    gain = SimpleNamespace(parameters=[SimpleNamespace(key="accelerometer_gain.a1_relative_change")])     # 0.02
    jacobians = {"m": np.array([[3.0], [1.0], [0.0], [0.0]]),      # partly along the width: 3 per unit
                 "k": np.array([[-2.0], [0.0], [5.0], [0.0]]),
                 "g": np.array([[0.0], [0.0], [0.0], [7.0]])}      # orthogonal to it
    by_name = {"m": mass, "k": spring, "g": gain}
    sigma = tolerance.measurand_form_sigma(Toy(), jacobians, by_name, width_col)
    assert sigma == pytest.approx(np.hypot(3.0 * 0.02, -2.0 * 0.05))
    assert tolerance.measurand_form_sigma(Toy(), {"g": jacobians["g"]}, by_name, width_col) == 0.0
