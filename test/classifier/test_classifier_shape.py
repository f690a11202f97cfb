"""Shape mode on synthetic windows: impact detection, the width regression, the B vector, continuous width."""
import numpy as np
import pytest

from backlash_monitor.classifier.cpn import continuous_width_from_b
from backlash_monitor.classifier.shape import ShapeModel, a1_features, a2_features, window_features

DT = 2e-5
WIDTHS = np.array([0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01])
IMPACT_MS = np.array([14.7, 19.1, 22.9, 29.5, 33.1, 35.4])


def _synthetic(width_index, jitter_ms, rng, n=2048):
    """a1: -35 m/s^2 until the impact, then a jump of 100 decaying; a2: a line that drops after it."""
    t = np.arange(n) * DT
    ti = (IMPACT_MS[width_index] + jitter_ms) * 1e-3
    after = np.clip(t - ti, 0, None)
    a1 = -35.0 + np.where(t >= ti, 100.0 * np.exp(-after / 0.004), 0.0) + rng.normal(0, 0.5, n)
    a2 = 0.3 - 2.0 * t - np.where(t >= ti, 1.0 - np.exp(-after / 0.003), 0.0)
    return a1, a2, ti


def test_impact_time_found_from_a1_jump_and_a2_kink():
    rng = np.random.default_rng(0)
    for i in range(6):
        a1, a2, ti = _synthetic(i, 0.3, rng)
        assert a1_features(a1[None], DT)[0, 0] == pytest.approx(ti, abs=2 * DT)
        assert a2_features(a2[None], DT)[0, 0] == pytest.approx(ti, abs=0.5e-3)


def test_no_impact_in_window_gives_the_window_end():
    a1 = np.full((1, 2048), -35.0)
    assert a1_features(a1, DT)[0, 0] == pytest.approx(2047 * DT)


def test_regression_learns_width_from_impact_time_and_b_is_a_distance():
    rng = np.random.default_rng(1)
    a1s, a2s, ys = [], [], []
    for _ in range(40):
        for i in range(6):
            a1, a2, _ = _synthetic(i, rng.normal(0, 0.3), rng)
            a1s.append(a1), a2s.append(a2), ys.append(WIDTHS[i])
    a1s, a2s, ys = np.array(a1s), np.array(a2s), np.array(ys)
    for signal in ("a1", "a2", "a1+a2"):
        m = ShapeModel.fit(signal, WIDTHS, ys, a1s, a2s, DT)
        b, w = m.b(a1s, a2s)
        assert b.shape == (len(ys), 6)
        assert np.mean(np.argmin(b, axis=1) == np.searchsorted(WIDTHS, ys)) > 0.95
        np.testing.assert_allclose(b, ((w[:, None] - WIDTHS[None]) / m.sigma_m) ** 2)


def test_window_features_need_the_signals_they_use():
    with pytest.raises(ValueError, match="needs the a2 window"):
        window_features("a2", a1=np.zeros((1, 2048)))
    with pytest.raises(ValueError, match="allowed: a1, a2, a1\\+a2"):
        window_features("a3", a1=np.zeros((1, 2048)))


def test_continuous_width_from_b_by_hand():
    # winner index 2 (B 1), better neighbour index 3 (B 3): w = 0.005 + 0.0025 * 1/4
    b = np.array([9.0, 5.0, 1.0, 3.0, 7.0, 9.0])
    assert continuous_width_from_b(b, WIDTHS)[0] == pytest.approx(0.005 + 0.0025 * 0.25)
    # exact match -> the candidate itself; edges use their only neighbour
    assert continuous_width_from_b(np.array([0.0, 1, 2, 3, 4, 5]), WIDTHS)[0] == pytest.approx(0.0025)
    assert continuous_width_from_b(np.array([5.0, 4, 3, 2, 1, 1]), WIDTHS)[0] == pytest.approx(0.0095)
