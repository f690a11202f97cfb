"""denoise_sym5: perfect reconstruction, linearity, batch = per window, shapes."""
import numpy as np
import pytest

from backlash_monitor.denoise import ALLOWED_MODES, denoise_sym5


@pytest.mark.parametrize("mode", ["symmetric", "periodization", "smooth", "zero", "reflect"])
@pytest.mark.parametrize("n", [2048, 2000, 1500])
def test_removing_nothing_reconstructs(mode, n):
    x = np.random.default_rng(0).standard_normal(n)
    np.testing.assert_allclose(denoise_sym5(x, details_removed=(), mode=mode), x, atol=1e-10)


def test_linearity():
    rng = np.random.default_rng(1)
    x, y = rng.standard_normal((2, 2048))
    np.testing.assert_allclose(denoise_sym5(2.5 * x - 0.7 * y), 2.5 * denoise_sym5(x) - 0.7 * denoise_sym5(y),
                               atol=1e-12)


def test_batch_equals_per_window_and_axis():
    x = np.random.default_rng(2).standard_normal((3, 4, 2048))
    b = denoise_sym5(x)
    assert b.shape == x.shape
    for i in range(3):
        for j in range(4):
            np.testing.assert_allclose(b[i, j], denoise_sym5(x[i, j]), atol=1e-12)
    np.testing.assert_allclose(denoise_sym5(np.moveaxis(x, -1, 0), axis=0), np.moveaxis(b, -1, 0), atol=1e-12)


def test_output_length_matches_odd_input():
    assert denoise_sym5(np.ones(2047)).shape == (2047,)


def test_constant_passes():
    np.testing.assert_allclose(denoise_sym5(np.full(2048, 3.0)), 3.0, atol=1e-9)


def test_window_object():
    from backlash_monitor.denoise import denoise_sym5_window

    class W:
        signals = {"a1": np.ones(2048), "a2": np.zeros(2048)}

    out = denoise_sym5_window(W())
    assert set(out) == {"a1", "a2"}
    assert "symmetric" in ALLOWED_MODES
