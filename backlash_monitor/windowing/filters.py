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
    block = min(n, _ema_block(lam))
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
    y = y.cumsum(axis=1)         # (the methods: np.cumsum/np.argmax add a Python wrapper's ~2 us)
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


def first_excursion(x: np.ndarray, lam: float, y_before: float, limit: float) -> tuple[int, int, float]:
    """The first n with |x[n] - y[n-1]| > ``limit``, y = ``exponential_average(x, lam, y_before)``
    (y[-1] = ``y_before``): (n, sign of x[n] - y[n-1], nan), or (-1, 0, y[-1]) if there is none.

    The same values as exponential_average computes, bit for bit (its blocks, in the same
    operations), taken block by block and only as far as needed: a block none of whose samples can
    be the first excursion is passed with its zero-start sums alone (its start value and end need
    them), the blocks after the excursion are not computed. A block cannot hold one when the span
    of its samples, its start value and the average before it is <= limit: y[n-1] is a weighted
    mean (weights >= 0 summing to 1) of those, so |x[n] - y[n-1]| <= that span. The margin
    (1e-9 relative to the values' size) is far above the average's rounding (~1e-12 of it).
    Scalars are Python floats (the same IEEE double arithmetic as numpy's, with less overhead).
    """
    x = np.asarray(x, dtype=np.float64)
    n = x.size
    if n == 0:
        return -1, 0, float(y_before)
    r = 1.0 - lam
    block = min(n, _ema_block(lam)) if 0.0 < lam < 1.0 and r != 1.0 else 0
    if block < min(n, 64):           # short blocks (a time constant of a few samples): all at once
        y = exponential_average(x, lam, y_before)
        k, sign = _beyond(x, y_before, y, limit)
        return (k, sign, float("nan")) if k >= 0 else (-1, 0, float(y[-1]))
    down, lam_down, r_down, r_block = _ema_weights(lam, r, block)
    start = float(y_before)           # the block's start value (exponential_average's starts[b])
    prev = start                      # y just before the block
    first = 0
    full = n // block
    if full >= 2:
        # the leading blocks no excursion can be in, found at once: y up to block b is a weighted
        # mean of y_before and the samples up to it, so the span of those bounds |x[n] - y[n-1]|
        rows = x[:full * block].reshape(full, block)
        tops, bottoms = rows.max(axis=1).tolist(), rows.min(axis=1).tolist()
        hi_v = lo_v = start
        quiet = 0
        for top, bottom in zip(tops, bottoms):
            hi_v, lo_v = max(hi_v, top), min(lo_v, bottom)
            if not _within(hi_v, lo_v, limit):
                break
            quiet += 1
        if quiet:
            lam_last, r_last = lam_down.item(-1), r_down.item(-1)
            for total in _block_sums(rows[:quiet], down).tolist():
                end = total * lam_last
                prev = end + r_last * start
                start = end + r_block * start
            first = quiet * block
    for lo in range(first, n, block):
        xs = x[lo:lo + block]
        m = xs.size
        q = (xs / down if m == block else xs / down[:m]).cumsum()    # the zero-start sums
        hi_v = max(_MAX(xs), start, prev)
        lo_v = min(_MIN(xs), start, prev)
        if _within(hi_v, lo_v, limit):
            total = q.item(m - 1)
            last = total * lam_down.item(m - 1) + r_down.item(m - 1) * start
            if m == block:
                start = total * lam_down.item(m - 1) + r_block * start
            prev = last
            continue
        q *= lam_down[:m]
        end = q.item(m - 1)           # the block's end before its start value is added
        q += r_down[:m] * start
        k, sign = _beyond(xs, prev, q, limit)
        if k >= 0:
            return lo + k, sign, float("nan")
        start = end + r_block * start
        prev = q.item(m - 1)
    return -1, 0, prev


def _beyond(x: np.ndarray, y_before: float, y: np.ndarray, limit: float) -> tuple[int, int]:
    """The first n with |x[n] - y[n-1]| > ``limit`` (y[-1] = ``y_before``) and the sign of that
    difference, or (-1, 0)."""
    dev = np.empty(x.size)
    dev[0] = x[0] - y_before
    np.subtract(x[1:], y[:-1], out=dev[1:])
    big = np.abs(dev) > limit
    k = int(big.argmax())
    if big[k]:
        return k, (1 if dev[k] > 0 else -1)
    return -1, 0


def _within(hi: float, lo: float, limit: float) -> bool:
    """No sample can depart from an average of values in [lo, hi] by more than ``limit`` (with a
    margin of 1e-9 of their size, far above the average's rounding)."""
    return hi - lo <= limit - 1e-9 * (1.0 + max(abs(hi), abs(lo)))


_MAX, _MIN = np.maximum.reduce, np.minimum.reduce
_EMA_BLOCKS: dict[float, int] = {}


def _ema_block(lam: float) -> int:
    """exponential_average's block length before the min with n: min(EMA_BLOCK, log(growth)/-log r)."""
    b = _EMA_BLOCKS.get(lam)
    if b is None:
        b = max(1, min(EMA_BLOCK, int(math.log(EMA_MAX_GROWTH) / -math.log(1.0 - lam))))
        if len(_EMA_BLOCKS) >= 256:
            _EMA_BLOCKS.clear()
        _EMA_BLOCKS[lam] = b
    return b


def _block_sums(rows: np.ndarray, down: np.ndarray) -> np.ndarray:
    """cumsum(rows[b] / down)[-1] for every row b: two rows at a time, as the real and imaginary
    parts of one complex running sum (complex addition adds the parts separately: the same sums)."""
    k = rows.shape[0]
    if k == 1:
        return (rows[0] / down).cumsum()[-1:]
    pairs = (k + 1) // 2
    w = np.empty((pairs, rows.shape[1]), dtype=np.complex128)
    np.divide(rows[0::2], down, out=w.real)
    if k % 2:
        np.divide(rows[1::2], down, out=w.imag[:-1])
        w.imag[-1] = 0.0
    else:
        np.divide(rows[1::2], down, out=w.imag)
    w = w.cumsum(axis=1)
    sums = np.empty(k)
    sums[0::2] = w.real[:, -1]
    sums[1::2] = w.imag[:k // 2, -1]
    return sums


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
    if n == width:               # one window
        return np.array([x.max() - x.min()])
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
