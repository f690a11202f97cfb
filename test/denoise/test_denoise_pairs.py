"""denoise.denoise_pairs (analyze: all onset windows of a batch in one transform) gives every window
bit for bit what denoise.denoise_pair (the denoise node, window by window) gives it."""
import numpy as np
import pytest

from backlash_monitor.denoise import denoise_pair, denoise_pairs


def windows(rng, count, n=2048):
    for i in range(count):
        scale = 10.0 ** rng.uniform(-3, 2)
        yield (scale * np.cumsum(rng.standard_normal(n)),
               np.sin(np.arange(n) * 0.01 * (i + 1)) + 0.1 * rng.standard_normal(n))


@pytest.mark.parametrize("count", [1, 2, 7, 40, 64])
def test_batch_equals_window_by_window(count):
    rng = np.random.default_rng(count)
    pairs = list(windows(rng, count))
    got = denoise_pairs(pairs)
    assert len(got) == count
    for (a1, a2), (b1, b2) in zip(pairs, got):
        r1, r2 = denoise_pair(a1, a2)
        assert b1.tobytes() == r1.tobytes() and b2.tobytes() == r2.tobytes()
        assert b1.dtype == r1.dtype == np.float64 and b1.shape == r1.shape


def test_unequal_lengths_and_options():
    rng = np.random.default_rng(0)
    pairs = [next(windows(rng, 1, 2048)), next(windows(rng, 1, 1500))]
    for (a1, a2), (b1, b2) in zip(pairs, denoise_pairs(pairs)):
        r1, r2 = denoise_pair(a1, a2)
        assert np.array_equal(b1, r1) and np.array_equal(b2, r2)
    pairs = list(windows(rng, 3))
    for (a1, a2), (b1, b2) in zip(pairs, denoise_pairs(pairs, details_removed=(1, 2))):
        r1, r2 = denoise_pair(a1, a2, details_removed=(1, 2))
        assert np.array_equal(b1, r1) and np.array_equal(b2, r2)
    assert denoise_pairs([]) == []
