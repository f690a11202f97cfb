"""The detector's numpy filters against their definitions (and scipy's filters they replaced)."""
import numpy as np
import pytest
from scipy.ndimage import maximum_filter1d, minimum_filter1d
from scipy.signal import lfilter

from backlash_monitor.windowing.filters import exponential_average, first_excursion, window_range


def _walk(n, seed=1):
    return np.cumsum(np.random.default_rng(seed).normal(size=n)) * 1e-3 + 0.3


@pytest.mark.parametrize("n", [1, 5, 1023, 1024, 1025, 30000])
@pytest.mark.parametrize("lam", [1e-3, 0.05, 0.5, 0.95, 1.0])
def test_exponential_average_is_the_recurrence(n, lam):
    x = _walk(n)
    y = exponential_average(x, lam, 0.29)
    # the recurrence in long double, sample by sample: y[n] = lam x[n] + (1 - lam) y[n-1]
    ref = np.empty(n, dtype=np.longdouble)
    prev, lam_l = np.longdouble(0.29), np.longdouble(lam)
    for i, v in enumerate(x.astype(np.longdouble)):
        prev = lam_l * v + (1 - lam_l) * prev
        ref[i] = prev
    assert np.max(np.abs(y - ref)) < 1e-14 * np.max(np.abs(x))
    scipy_y = lfilter([lam], [1.0, lam - 1.0], x, zi=[(1.0 - lam) * 0.29])[0]
    assert np.max(np.abs(y - scipy_y)) < 1e-14 * np.max(np.abs(x))


def test_exponential_average_step_response():
    """A step from the start value: 1 - (1 - lam)^(n+1) of the way after n + 1 samples."""
    lam = 1e-3
    y = exponential_average(np.ones(5000), lam, 0.0)
    n = np.arange(5000)
    np.testing.assert_allclose(y, 1.0 - (1.0 - lam) ** (n + 1), rtol=0, atol=1e-14)
    with pytest.raises(ValueError, match="allowed: 0 <= lam <= 1"):
        exponential_average(np.ones(3), -0.1, 0.0)


@pytest.mark.parametrize("lam", [0.0, 1e-300])
def test_exponential_average_of_a_vanishing_weight_holds_its_start(lam):
    """lam = 0 (or below 1's float resolution: a sample period ~0 against the time constant):
    the average stays at its start value, as the recurrence (and scipy's lfilter) gives."""
    x = _walk(3000)
    y = exponential_average(x, lam, 0.29)
    assert np.array_equal(y, np.full(3000, 0.29))
    assert np.allclose(lfilter([lam], [1.0, lam - 1.0], x, zi=[(1.0 - lam) * 0.29])[0], y,
                       rtol=0, atol=1e-15)


@pytest.mark.parametrize("n", [1, 99, 100, 101, 257, 5000])
@pytest.mark.parametrize("w", [1, 2, 100, 400])
def test_window_range_is_max_minus_min_of_each_full_window(n, w):
    x = _walk(n, seed=n + w)
    out = window_range(x, w)
    expected = np.array([x[i:i + w].max() - x[i:i + w].min() for i in range(n - w + 1)])
    assert np.array_equal(out, expected)
    if n >= w:   # what the detector used before: scipy's filters over the last w samples
        org = (w - 1) // 2
        rng = maximum_filter1d(x, w, origin=org) - minimum_filter1d(x, w, origin=org)
        assert np.array_equal(out, rng[w - 1:])


def _first_excursion_by_definition(x, lam, y_before, limit):
    """The first n with |x[n] - y[n-1]| > limit over exponential_average's y (y[-1] = y_before)."""
    y = exponential_average(x, lam, y_before)
    dev = x - np.concatenate(([y_before], y[:-1]))
    big = np.flatnonzero(np.abs(dev) > limit)
    if big.size:
        return int(big[0]), int(np.sign(dev[big[0]]))
    return -1, float(y[-1])


@pytest.mark.parametrize("lam", [1.0 - np.exp(-2e-5 / 0.02), 1.0 - np.exp(-2e-5 / 0.005), 0.05, 1e-5, 0.5, 1.0])
@pytest.mark.parametrize("n", [1, 63, 1000, 1024, 2047, 4096, 5000])
def test_first_excursion_is_the_first_sample_beyond_the_limit(lam, n):
    """Its block-wise search (quiet blocks: zero-start sums only) gives the definition's answer, and
    with no excursion the average's last value to the bit: a contact with noise and slow drift,
    then a parabolic departure starting in any block, either way."""
    rng = np.random.default_rng(n)
    for start in [None, 0, n // 3, n - 1, 1500, 3100]:
        for sign in (1, -1):
            x = 0.04 + 1e-4 * rng.standard_normal(n) + 2e-7 * np.arange(n)
            if start is not None and start < n:
                x[start:] += sign * 3e-6 * np.arange(n - start) ** 2
            y0 = 0.04 + 1e-3 * rng.standard_normal()
            k, direction, last = first_excursion(x, lam, y0, 0.015)
            want = _first_excursion_by_definition(x, lam, y0, 0.015)
            if want[0] >= 0:
                assert (k, direction) == want and np.isnan(last)
            else:
                assert k == -1 and direction == 0 and last == want[1]    # bit for bit
