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
    (the previous block's zero-start response at its end): one Python step per block. The powers of
    r of a block length are computed once per (lam, B) (``_ema_weights``).
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
    down, lam_down, r_down, r_block = _ema_weights(lam, r, block)
    n_blocks = -(-n // block)
    full = n // block
    y = np.empty((n_blocks, block))
    if full:
        np.divide(x[:full * block].reshape(full, block), down, out=y[:full])
    if full < n_blocks:          # the last block's tail (beyond n) is 0, as if x were padded with zeros
        rest = n - full * block
        np.divide(x[full * block:], down[:rest], out=y[full, :rest])
        y[full, rest:] = 0.0
    np.cumsum(y, axis=1, out=y)
    y *= lam_down                # the zero-start responses
    if n_blocks == 1:
        y += r_down * y_before
        return y.reshape(-1)[:n]
    starts = np.empty(n_blocks)
    starts[0] = y_before
    ends = y[:, -1]
    for b in range(1, n_blocks):
        starts[b] = ends[b - 1] + r_block * starts[b - 1]
    y += r_down * starts[:, None]
    return y.reshape(-1)[:n]


_EMA_WEIGHTS: dict[tuple[float, int], tuple] = {}


def _ema_weights(lam: float, r: float, block: int) -> tuple:
    """(r^k, lam r^k, r^(k+1) for k = 0..block-1, r^block) of one block length, computed once."""
    key = (lam, block)
    w = _EMA_WEIGHTS.get(key)
    if w is None:
        down = r ** np.arange(block, dtype=np.float64)
        w = (down, lam * down, r * down, r ** block)
        for a in w[:3]:
            a.flags.writeable = False
        if len(_EMA_WEIGHTS) >= 256:
            _EMA_WEIGHTS.clear()
        _EMA_WEIGHTS[key] = w
    return w


def window_range(x: np.ndarray, width: int) -> np.ndarray:
    """max - min of every full window of ``width`` consecutive samples: out[i] over x[i : i + width],
    i = 0 .. len(x) - width (empty when x is shorter). By doubling: the maxima and minima over
    windows of 2, 4, .. p samples (p the largest power of two <= width), each from two of the
    previous level; a window of ``width`` is the union of the two windows of p at its start and at
    its end. O(len(x) log2(width)) in whole-array operations (a maximum and a minimum are exact:
    the values are those of any other way of taking them)."""
    x = np.asarray(x, dtype=np.float64)
    n = x.size
    if width < 1:
        raise ValueError(f"window_range: width = {width!r}; allowed: 1 or more")
    if n < width:
        return np.empty(0)
    if width == 1:
        return np.zeros(n)
    hi = lo = x
    p = 1
    while 2 * p <= width:        # windows of 2p samples: n - 2p + 1 of them
        m = n - 2 * p + 1
        hi = np.maximum(hi[:m], hi[p:p + m])
        lo = np.minimum(lo[:m], lo[p:p + m])
        p *= 2
    m = n - width + 1
    d = width - p
    if d == 0:
        return hi - lo
    out = np.maximum(hi[:m], hi[d:d + m])
    out -= np.minimum(lo[:m], lo[d:d + m])
    return out
