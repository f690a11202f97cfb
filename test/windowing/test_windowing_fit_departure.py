"""fit_departure keeps its y-independent least-squares terms per length (computed once): the
departure index equals the inline computation's (the code before the cache, kept here as the
reference), for contact-loss-like data, noise, constants and many lengths."""
import numpy as np
import pytest

from backlash_monitor.windowing.detector import fit_departure


def reference_fit_departure(y, direction, min_pre=16, min_post=16):
    y = np.asarray(y, dtype=np.float64)
    n = y.size
    if n < min_pre + min_post + 3:
        return 0
    y = y - y[0]
    k = np.arange(n, dtype=np.float64)
    rc = lambda v: np.cumsum(v[::-1])[::-1]  # noqa: E731
    a0, a1, a2 = rc(y), rc(y * k), rc(y * k * k)
    t = k
    m = n - t - 1.0
    s2 = m * (m + 1) * (2 * m + 1) / 6.0
    s3 = (m * (m + 1) / 2.0) ** 2
    s4 = m * (m + 1) * (2 * m + 1) * (3 * m * m + 3 * m - 1) / 30.0
    sk, skk = k.sum(), (k * k).sum()
    ginv = np.linalg.inv(np.array([[n, sk], [sk, skk]]))
    xq0, xq1 = s2, s3 + t * s2
    xy = np.array([y.sum(), np.dot(k, y)])
    gy = ginv @ xy
    r_qq = s4 - (ginv[0, 0] * xq0 * xq0 + 2 * ginv[0, 1] * xq0 * xq1 + ginv[1, 1] * xq1 * xq1)
    r_yq = (a2 - 2.0 * t * a1 + t * t * a0) - (xq0 * gy[0] + xq1 * gy[1])
    lo, hi = min_pre, n - min_post
    with np.errstate(all="ignore"):
        acc = r_yq / r_qq
        gain = r_yq * acc
    valid = np.zeros(n, dtype=bool)
    valid[lo:hi] = True
    valid &= np.isfinite(gain) & (acc * direction > 0) & (r_qq > 0)
    if not valid.any():
        return 0
    return int(np.argmax(np.where(valid, gain, -np.inf)))


def departures(rng, n):
    """Contact-loss-like traces: a slow ramp with noise, then a parabola from a random t0."""
    k = np.arange(n, dtype=float)
    for _ in range(20):
        t0 = rng.integers(n // 4, n - 20)
        direction = int(rng.choice((-1, 1)))
        y = (0.01 + 1e-7 * rng.standard_normal() * k + direction * 2e-7 * np.maximum(0, k - t0) ** 2
             + 3e-4 * rng.standard_normal(n))
        yield y, direction


@pytest.mark.parametrize("n", [35, 64, 200, 1000, 2047, 2048])
def test_departure_equals_inline_computation(n):
    rng = np.random.default_rng(n)
    for y, direction in departures(rng, n):
        for d in (direction, -direction):
            assert fit_departure(y, d) == reference_fit_departure(y, d)
    noise = rng.standard_normal(n)
    for d in (1, -1):
        assert fit_departure(noise, d) == reference_fit_departure(noise, d)
        assert fit_departure(np.full(n, 0.3), d) == reference_fit_departure(np.full(n, 0.3), d) == 0


def test_short_input_and_repeated_lengths():
    assert fit_departure(np.arange(10.0), 1) == 0
    rng = np.random.default_rng(0)
    for n in rng.integers(40, 3000, size=80):   # more lengths than the cache keeps
        y = np.cumsum(rng.standard_normal(int(n)))
        assert fit_departure(y, 1) == reference_fit_departure(y, 1)
