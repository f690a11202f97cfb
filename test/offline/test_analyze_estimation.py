"""`analyze` estimates its onset windows in batches (DriveEstimator.estimate_many); the live classifier
node one window at a time (estimate = a batch of one). Both must equal ShapeModel.b on single
windows (minus their sensor offset estimates) bit for bit, and the batched features must equal the
single-window ones row for row."""
import numpy as np
import pytest

plant = pytest.importorskip("backlash_monitor.plant")

from backlash_monitor.chain.joiner import JoinedRange  # noqa: E402

from backlash_monitor.chain.stage import WindowingStage  # noqa: E402

from backlash_monitor.denoise import denoise_pair  # noqa: E402
from backlash_monitor.classifier.cpn import b_margin  # noqa: E402
from backlash_monitor.classifier.patterns import default_library_path, load_library  # noqa: E402
from backlash_monitor.classifier.shape import a1_features, a2_features  # noqa: E402
from backlash_monitor.estimation import DriveEstimator  # noqa: E402

WIDTHS = (0.0025, 0.0075, 0.0125)


@pytest.fixture(scope="module")
def windows():
    scen = [plant.Scenario(width_m=w, eta_k=0.025, n1=0.89, seed=7) for w in WIDTHS]
    sim = plant.PlantSimulator(scen, config=plant.load_plant_config(), noise=True)
    stages = [WindowingStage() for _ in WIDTHS]
    out = []
    for _ in range(round(4.0 / 2e-5) // 5000):
        c = sim.run(5000)
        for i, stage in enumerate(stages):
            joined = JoinedRange(c.first_sample_index, c.sample_period_s,
                                 {s: getattr(c, s)[i] for s in ("a1", "a2", "angle_difference")})
            for w in stage.feed(joined)[0]:
                a1, a2 = denoise_pair(w.signals["a1"], w.signals["a2"])
                out.append((a1, a2, w.kind, w.sample_period_s, w.sensor_offsets))
    assert sum(w[2] == "onset" for w in out) >= 30
    return out


@pytest.fixture(scope="module")
def library():
    return load_library(default_library_path("contact_loss"), trigger="contact_loss")


def test_batched_features_equal_single_window_features_row_for_row(windows):
    A1 = np.stack([w[0] for w in windows])
    A2 = np.stack([w[1] for w in windows])
    for f, A in ((a1_features, A1), (a2_features, A2)):
        for rows in (slice(None), slice(3, 4), slice(1, None, 3)):
            batch = f(np.ascontiguousarray(A[rows]), 2e-5)
            single = np.concatenate([f(a[None, :], 2e-5) for a in A[rows]])
            assert np.array_equal(batch, single)
            assert batch.tobytes() == single.tobytes()


def flat(estimates):
    return [(e.signal_name, e.b_vector.tobytes(), e.width_index, e.width_m, e.b_margin,
             e.continuous_width_m, e.fused_width_m, e.fused_events)
            for per_window in estimates for e in per_window]


def test_estimate_many_equals_window_by_window_and_shape_model(windows, library):
    single = DriveEstimator(library)
    one_by_one = [single.estimate(*w) for w in windows]
    for batch in (1, 7, 64, len(windows)):
        est = DriveEstimator(library)
        got = []
        for lo in range(0, len(windows), batch):
            got += est.estimate_many(windows[lo:lo + batch])
        assert flat(got) == flat(one_by_one), batch
    # against the classifier's own ShapeModel.b, one window at a time
    for (a1, a2, kind, _, offsets), estimates in zip(windows, one_by_one):
        # every onset but each stream's first (no whole load period behind it: no offset estimate)
        assert bool(estimates) == (kind == "onset" and np.isfinite(offsets["a1"]))
        for e in estimates:
            b, w = single.models[e.signal_name].b(a1=(a1 - offsets["a1"])[None, :],
                                                  a2=(a2 - offsets["a2"])[None, :])
            assert b[0].tobytes() == e.b_vector.tobytes()
            assert float(w[0]) == e.continuous_width_m
            # winner and margin (taken for all rows at once) as of the window's own B vector
            assert e.width_index == int(np.argmin(b[0]))
            assert e.b_margin == float(b_margin(b[0]))


def test_windows_of_different_lengths_are_estimated_one_by_one(windows, library):
    onsets = [w for w in windows if w[2] == "onset" and np.isfinite(w[4]["a1"])][:4]
    mixed = [onsets[0], (onsets[1][0][:1800], onsets[1][1][:1800], "onset", None, onsets[1][4]), onsets[2]]
    ref = DriveEstimator(library)
    expected = [ref.estimate(*w) for w in mixed]
    assert flat(DriveEstimator(library).estimate_many(mixed)) == flat(expected)
