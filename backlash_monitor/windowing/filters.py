"""The detector's two filters in plain numpy (no scipy): the contact reference's exponential average
and the settle test's peak-to-peak over a sliding window.

They replaced ``scipy.signal.lfilter`` and ``scipy.ndimage.maximum/minimum_filter1d``, which the
detector used once each: importing scipy.signal and scipy.ndimage cost about 0.7 s of CPU and
40 MB per process, paid by every chain process of a fleet and by every `analyze` run before its
first bag (docs/fleet.md). ``window_range`` gives exactly the values of the scipy filters (a
maximum and a minimum are exact); ``exponential_average`` computes the same recurrence in blocks
and agrees with ``lfilter`` to rounding (a few 1e-16 relative; test/windowing/test_windowing_filters.py).
"""
from __future__ import annotations

import math

import numpy as np

EMA_BLOCK = 1024        # samples per block of the blocked recurrence (bounded by the growth below)
EMA_MAX_GROWTH = 4.0    # largest (1 - lam)^-k inside a block: keeps the block sums well scaled


def exponential_average(x: np.ndarray, lam: float, y_before: float) -> np.ndarray:
    """y[n] = lam * x[n] + (1 - lam) * y[n-1] with y[-1] = ``y_before``, 0 <= lam <= 1.

    What ``lfilter([lam], [1, lam - 1], x, zi=[(1 - lam) * y_before])[0]`` computes. In blocks of B
    samples with the block's start value s: y[k] = r^(k+1) s + lam r^k cumsum(r^-j x[j])[k] (r = 1 -
    lam, r^-j <= EMA_MAX_GROWTH inside a block); the block start values follow s_b = r^B s_(b-1) +
    (the previous block's zero-start response at its end): one Python step per block.
    """
    x = np.asarray(x, dtype=np.float64)
    n = x.size
    if not 0.0 <= lam <= 1.0:
        raise ValueError(f"exponential_average: lam = {lam!r}; allowed: 0 <= lam <= 1")
    if n == 0:
        return np.empty(0)
    r = 1.0 - lam
    if r == 0.0:
        return x.copy()
    if r == 1.0:     # lam below the float resolution of 1 (a time constant ~1e16 samples long)
        return np.full(n, float(y_before))
    block = max(1, min(EMA_BLOCK, n, int(math.log(EMA_MAX_GROWTH) / -math.log(r))))
    n_blocks = -(-n // block)
    padded = np.zeros(n_blocks * block)
    padded[:n] = x
    k = np.arange(block, dtype=np.float64)
    down = r ** k
    zero_start = np.cumsum(padded.reshape(n_blocks, block) / down, axis=1)
    zero_start *= lam * down
    starts = np.empty(n_blocks)
    starts[0] = y_before
    r_block = r ** block
    ends = zero_start[:, -1]
    for b in range(1, n_blocks):
        starts[b] = ends[b - 1] + r_block * starts[b - 1]
    zero_start += (r * down) * starts[:, None]
    return zero_start.reshape(-1)[:n]


def window_range(x: np.ndarray, width: int) -> np.ndarray:
    """max - min of every full window of ``width`` consecutive samples: out[i] over x[i : i + width],
    i = 0 .. len(x) - width (empty when x is shorter). van Herk / Gil-Werman: running maxima and
    minima from the start and from the end of blocks of ``width`` samples, O(len(x))."""
    x = np.asarray(x, dtype=np.float64)
    n = x.size
    if width < 1:
        raise ValueError(f"window_range: width = {width!r}; allowed: 1 or more")
    if n < width:
        return np.empty(0)
    if width == 1:
        return np.zeros(n)
    m = -(-n // width) * width
    padded = np.empty(m)
    padded[:n] = x
    padded[n:] = x[-1]          # never inside a full window (each lies in one or two blocks)
    blocks = padded.reshape(-1, width)
    out = []
    for acc in (np.maximum, np.minimum):
        from_start = acc.accumulate(blocks, axis=1).reshape(-1)
        from_end = acc.accumulate(blocks[:, ::-1], axis=1)[:, ::-1].reshape(-1)
        out.append(acc(from_end[:n - width + 1], from_start[width - 1:n]))
    return out[0] - out[1]
