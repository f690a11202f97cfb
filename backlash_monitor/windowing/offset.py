"""The accelerometers' constant offsets, estimated online over whole load periods.

Physics: an acceleration is the derivative of a speed, so its mean over a stretch [t0, t1) is

    mean(a) = (v(t1) - v(t0)) / (t1 - t0) + b

with b the sensor's constant offset. Over a stretch whose speed returns to its value the first term
vanishes. The drive's load pulses come at equal intervals, and every onset window starts at the
same phase of that cycle (the contact loss at a load step), so the stretch from the end of one onset
window to the end of the next is one whole load period: its mean is b, up to the speed's
period-to-period difference over the stretch's length (docs/windowing.md "Sensor offsets" has the
measured error: falls as 1/periods). The estimate of each onset window is the mean of the signal over
the last ``periods`` whole periods that end at that window's end.

The estimate is LINEAR in the samples with weights that sum to one, so ``window - estimate`` does
not change at all when a constant is added to the signal -- whatever the estimate's own error. That
is what the classifier reads (:func:`remove_offset`), in training as in use: its width cannot move
with a constant sensor offset. Before the first whole period (the first onset window of a stream)
there is no estimate (NaN): that window is not classified.

Exactly the same numbers however the stream is cut into chunks (the live nodes and ``analyze``
must agree bit for bit): the sums are taken per block of ``block_samples`` samples on a fixed grid
of absolute sample indices (each block summed once, from one contiguous copy), the part of a block
before a period boundary from the capture's contiguous history, and the blocks of a period are added
with ``math.fsum`` (correctly rounded, independent of the order).

A break in the stream (lost chunks, a bad range, a restart) drops the period under way; the closed
periods are kept -- the offset belongs to the sensor, not to the stream.
"""
from __future__ import annotations

import math
from collections import deque
from typing import Mapping, Sequence

import numpy as np

from .config import DEFAULTS

__all__ = ["SensorOffsetEstimator", "remove_offset", "implausible_offsets", "offset_removal_label",
           "BLOCK_SAMPLES", "MAX_PERIOD_SAMPLES"]

BLOCK_SAMPLES = 64            # samples per block sum (<= the shortest window the nodes allow: 64)
MAX_PERIOD_SAMPLES = 3_000_000   # 60 s at 50 kHz: a longer stretch between two onsets is no load period
_RETAIN_SAMPLES = 1 << 17     # block sums kept behind the previous range's end (2.6 s at 50 kHz): a
                              # window ends at most ~fit_samples before the range completing it starts


class SensorOffsetEstimator:
    """Constant offset of each of ``signals``: the mean over the last ``periods`` whole load periods.

    ``feed(first_sample_index, arrays)``: contiguous samples (a jump restarts); ``close_period(index,
    heads)``: an onset window ends at ``index`` (exclusive), ``heads[s]`` = sum of signal s over
    [block start of index, index); ``estimate()`` -> ({signal: offset or NaN}, periods averaged).
    """

    def __init__(self, signals: Sequence[str], periods: int = DEFAULTS["sensor_offset"]["periods"],
                 block_samples: int = BLOCK_SAMPLES, max_period_samples: int = MAX_PERIOD_SAMPLES):
        if isinstance(periods, bool) or not isinstance(periods, (int, np.integer)) or periods < 1:
            raise ValueError(f"sensor offset periods={periods!r}: must be an integer >= 1 (whole load "
                             "periods averaged)")
        self.signals = tuple(signals)
        self.periods = int(periods)
        self.block_samples = int(block_samples)
        self.max_period_samples = int(max_period_samples)
        self._closed: deque = deque(maxlen=self.periods)   # (samples, {signal: sum}) per period
        self.restart(0)

    # ------------------------------------------------------------------ stream
    def restart(self, first: int) -> None:
        """A break before sample ``first``: the period under way is dropped (the closed ones stay)."""
        b = self.block_samples
        self._next = int(first)
        self._tail_start = -(-int(first) // b) * b     # block sums start at the next block boundary
        self._tail = {s: np.zeros(0) for s in self.signals}
        self._blocks = {s: [] for s in self.signals}
        self._blocks_first = self._tail_start           # absolute index of _blocks[s][0]
        self._open: tuple[int, dict] | None = None      # (index, heads) of the last boundary

    def feed(self, first_sample_index: int, arrays: Mapping[str, np.ndarray]) -> None:
        first = int(first_sample_index)
        if first != self._next:
            self.restart(first)
        # what the boundaries still to come can need: the open period, and a margin behind the end
        # of the data fed so far (a window never ends further behind the range that completes it)
        keep_from = self._next - _RETAIN_SAMPLES
        if self._open is not None:
            if self._next - self._open[0] > self.max_period_samples + _RETAIN_SAMPLES:
                self._open = None        # no load period is that long: nothing to close
            else:
                keep_from = min(keep_from, self._open[0])
        self._drop_blocks_before(keep_from)
        n = int(np.asarray(arrays[self.signals[0]]).size)
        b = self.block_samples
        held = self._tail[self.signals[0]].size
        skip = max(0, self._tail_start + held - first)
        need = b - held if held else 0       # samples that complete the block under way
        whole = 0
        for s in self.signals:
            x = np.asarray(arrays[s], dtype=np.float64)[skip:]
            blocks = self._blocks[s]
            if x.size < need:                 # the block under way is still not complete
                self._tail[s] = np.concatenate((self._tail[s], x))
                continue
            if need:                          # each block is summed once, from one contiguous copy
                blocks.append(float(np.concatenate((self._tail[s], x[:need])).sum()))
            rest = x[need:]
            whole = rest.size // b
            if whole:
                blocks.extend(rest[:whole * b].reshape(whole, b).sum(axis=1).tolist())
            self._tail[s] = rest[whole * b:].copy()
        if x.size >= need:
            self._tail_start += (b if need else 0) + whole * b
        self._next = first + n

    def block_start(self, index: int) -> int:
        """The first sample of the block holding ``index`` (the grid of absolute indices)."""
        return int(index) // self.block_samples * self.block_samples

    def close_period(self, index: int, heads: Mapping[str, float] | None) -> bool:
        """An onset window ends at ``index``: close the period from the last boundary to it (if one
        is open, no longer than ``max_period_samples``) and open the next. ``heads`` None: the
        samples before ``index`` in its block are not at hand; the boundary is skipped (the next
        period then spans two load periods -- still whole periods). True if a period was closed."""
        index = int(index)
        first_block = self.block_start(index)
        if heads is None or first_block < self._blocks_first or index > self._next:
            return False
        closed = False
        if self._open is not None:
            start, start_heads = self._open
            if 0 < index - start <= self.max_period_samples:
                i0 = (self.block_start(start) - self._blocks_first) // self.block_samples
                i1 = (first_block - self._blocks_first) // self.block_samples
                sums = {s: math.fsum(self._blocks[s][i0:i1] + [-start_heads[s], heads[s]])
                        for s in self.signals}
                self._closed.append((index - start, sums))
                closed = True
        self._open = (index, {s: float(heads[s]) for s in self.signals})
        self._drop_blocks_before(first_block)
        return closed

    def _drop_blocks_before(self, index: int) -> None:
        cut = (self.block_start(index) - self._blocks_first) // self.block_samples
        if cut > 0:
            for s in self.signals:
                del self._blocks[s][:cut]
            self._blocks_first += cut * self.block_samples

    # ------------------------------------------------------------------ result
    def estimate(self) -> tuple[dict, int]:
        """({signal: mean over the closed periods, NaN when none}, number of periods averaged)."""
        if not self._closed:
            return {s: math.nan for s in self.signals}, 0
        samples = sum(n for n, _ in self._closed)
        return ({s: math.fsum(sums[s] for _, sums in self._closed) / samples for s in self.signals},
                len(self._closed))


def remove_offset(window: np.ndarray, offset: float) -> np.ndarray:
    """What every classifier mode reads: the (denoised) window minus the drive's offset estimate.
    Denoising keeps a constant (sym5's approximation holds constants), so subtracting after it
    equals subtracting before it, to rounding."""
    return np.asarray(window, dtype=np.float64) - float(offset)


def offset_removal_label(periods: int = DEFAULTS["sensor_offset"]["periods"]) -> str:
    """How the classifier's input is made, as a pattern library records it (setting
    ``sensor_offset``): a library is only used on windows preprocessed the way it was trained."""
    return f"mean over the last {int(periods)} whole load periods removed"


def implausible_offsets(offsets: Mapping[str, float], plausible_abs: float) -> dict:
    """The signals whose estimated offset lies beyond +-``plausible_abs`` (NaN: not judged)."""
    return {s: float(v) for s, v in offsets.items() if math.isfinite(v) and abs(v) > plausible_abs}
