"""Joining a drive's signals: the per-signal chunks of one sample range into one range.

A drive's signals arrive on separate topics, a chunk of each per sample range; the windowing node
and ``analyze`` hand every chunk to a :class:`ChunkJoiner`, which returns a :class:`JoinedRange`
once the range is complete and gives up on ranges that stay incomplete. The constants say how long
it waits (MAX_PENDING_RANGES, :func:`pending_ranges_for`) and when a range is a restart of the
stream rather than a late chunk (RESYNC_SAMPLES).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from backlash_monitor.windowing.faults import MAX_INDEX, FaultLog, is_index

MAX_PENDING_RANGES = 16
# A node that joins chunks from queues deeper than that waits for a range as long as its missing
# chunk can still be waiting in one (pending_ranges_for): on a reliable topic a chunk comes late,
# never not at all, and under load the signals' topics run seconds apart (docs/graph.md, "While a
# consumer is away").


def pending_ranges_for(queue_depth: int) -> int:
    """Ranges a joiner keeps waiting for their missing chunks when each signal's chunks come
    through a queue of ``queue_depth``: that many (a chunk still in its queue can be that far
    behind the other signals'), at least MAX_PENDING_RANGES (best effort's 5-deep queue: a lost
    chunk never comes, a late one is a few ranges behind)."""
    return max(MAX_PENDING_RANGES, int(queue_depth))
# A range that starts this far (or more) behind the expected index is a restart of the stream (a
# drive restarted, its index counts from 0 again), not a late chunk: 1 s at 50 kHz, far more than
# any reordering of best-effort chunks (MAX_PENDING_RANGES ranges of 1000 samples at most).
RESYNC_SAMPLES = 50_000


@dataclass
class JoinedRange:
    first_sample_index: int
    sample_period_s: float
    arrays: dict
    stamp: object = None     # the first signal's header stamp, when the caller has one
    frame_id: str = ""
    period_mismatch: bool = False   # the signals came with different sample periods


class ChunkJoiner:
    """Collects one chunk of each of ``signals`` per first_sample_index; returns complete ranges.

    A range still incomplete while more than ``max_pending`` ranges wait is dropped (counted in
    ``dropped_ranges`` and in ``faults`` as ``incomplete_range``); the window capture then sees the
    gap and discards the windows spanning it. A chunk whose index is not an integer in
    0..2**53 is dropped at once (``bad_index``): it cannot be placed in the stream. Everything
    else about the samples (period, lengths, values) is checked by :class:`WindowingStage`,
    which knows the range's place in the stream. A chunk at index 0 (or RESYNC_SAMPLES behind)
    after complete ranges is a restarted stream: the incomplete ranges still waiting are dropped
    first (counted), so that no old chunk is joined with a new one.
    """

    def __init__(self, signals, max_pending: int = MAX_PENDING_RANGES, faults: FaultLog | None = None):
        self.signals = tuple(signals)
        self.max_pending = max_pending
        self.pending: dict[int, dict] = {}
        self.meta: dict[int, tuple] = {}
        self.dropped_ranges = 0
        self.faults = faults if faults is not None else FaultLog()
        self._end: int | None = None    # end of the last complete range (restart detection)
        self._dropped_up_to: int | None = None  # the last range dropped incomplete (late chunks)
        self.pending_max = 0            # most ranges that waited at once (how far the topics ran apart)

    def add(self, name: str, first_sample_index: int, sample_period_s: float, samples,
            stamp=None, frame_id: str = "") -> JoinedRange | None:
        if name not in self.signals:
            return None
        if not is_index(first_sample_index):
            self.faults.add("bad_index", f"{name} chunk at index {first_sample_index!r}")
            return None
        first_sample_index = int(first_sample_index)
        if self._end is not None and first_sample_index < self._end and (
                first_sample_index == 0 or self._end - first_sample_index >= RESYNC_SAMPLES):
            # the stream restarted: an old incomplete range must not be completed by new chunks
            self._drop_pending("stream restart")
            self._end = None
            self._dropped_up_to = None
        if (self._dropped_up_to is not None and first_sample_index not in self.pending
                and first_sample_index <= self._dropped_up_to
                and (first_sample_index > 0 or self._end is None)
                and self._dropped_up_to - first_sample_index < RESYNC_SAMPLES):
            self.faults.add("out_of_order", f"{name} chunk at sample {first_sample_index}: its "
                            "range was dropped incomplete before it came")
            return None
        try:
            array = np.asarray(samples, dtype=np.float64)
        except (TypeError, ValueError):
            array = np.full(1, np.nan)   # not numbers: the stage drops the range as non-finite
        group = self.pending.setdefault(first_sample_index, {})
        group[name] = array
        if name == self.signals[0] or first_sample_index not in self.meta:
            self.meta[first_sample_index] = (sample_period_s, stamp, frame_id)
        if name != self.signals[0]:
            group.setdefault("__periods__", {})[name] = sample_period_s
        if len(group) - ("__periods__" in group) < len(self.signals):
            self.pending_max = max(self.pending_max, len(self.pending))
            if len(self.pending) > self.max_pending:
                oldest = min(self.pending)
                del self.pending[oldest]
                self.meta.pop(oldest, None)
                self.dropped_ranges += 1
                self._dropped_up_to = max(oldest, self._dropped_up_to or 0)
                self.faults.add("incomplete_range", f"range at sample {oldest}")
            return None
        del self.pending[first_sample_index]
        self._end = first_sample_index + int(array.size)
        periods = group.pop("__periods__", {})
        period, stamp, frame_id = self.meta.pop(first_sample_index)
        joined = JoinedRange(first_sample_index, period, group, stamp, frame_id)
        if any(p != period and not (_isnan(p) and _isnan(period)) for p in periods.values()):
            joined.sample_period_s = math.nan      # the stage drops it: sample_period_mismatch
            joined.period_mismatch = True
        return joined

    def add_rows(self, signal, first_sample_index, sample_period_s, samples,
                 meta) -> list[JoinedRange] | None:
        """What :meth:`add` returns, chunk by chunk, for chunks that come as whole ranges one after
        the other -- each signal's chunk of a range, in any order, then the next range's, at an
        index at or past the end of the one before (the way a recorder writes a drive's topics):
        the complete ranges, the joiner left as those adds leave it. None when they do not come
        that way (the first range behind the end of the last one completed before, too), or a
        chunk is irregular (an index that is not usable, a range whose chunks' periods or
        lengths differ, no samples), or ranges are waiting already: then nothing is done (add
        them one by one, which counts what is wrong). Called again for the next chunks, it goes
        on where the adds or the call before ended.

        ``signal``: each chunk's signal, as its index in ``signals`` (an int array);
        ``first_sample_index`` and ``sample_period_s``: numpy arrays of theirs (unsigned ints,
        floats); ``samples``: their float64 arrays; ``meta(i)``: (stamp, frame_id) of chunk i,
        asked for each range's first signal (``signals[0]``), whose stamp a range keeps as with
        ``add``."""
        width = len(self.signals)
        codes = np.asarray(signal)
        n = codes.size
        if (self.pending or n == 0 or n % width or len(samples) != n
                or codes.dtype.kind not in "ui"):
            return None
        codes = codes.reshape(-1, width)
        firsts = np.asarray(first_sample_index)
        periods = np.asarray(sample_period_s, dtype=np.float64).reshape(-1, width)
        sizes = np.array([a.size for a in samples]).reshape(-1, width)
        if firsts.dtype.kind not in "ui":
            return None
        firsts = firsts.reshape(-1, width)
        starts = firsts[:, 0]
        if not ((np.sort(codes, axis=1) == np.arange(width)).all()
                and (firsts == starts[:, None]).all() and (starts >= 0).all()
                and (starts < MAX_INDEX).all() and (periods == periods[:, :1]).all()
                and (sizes == sizes[:, :1]).all() and (sizes > 0).all()):
            return None
        starts = starts.astype(np.int64)
        if (starts[1:] < starts[:-1] + sizes[:-1, 0]).any() or (
                self._end is not None and starts[0] < self._end):
            return None       # a range behind the end of the one before: a restart or a repeat
        signals = self.signals
        firsts, period_list = starts.tolist(), periods[:, 0].tolist()
        if (codes == codes[0]).all():    # every range's signals come in one order (a recorder's)
            row = codes[0].tolist()
            order, head = [signals[k] for k in row], row.index(0)
            ranges = [JoinedRange(first, period, dict(zip(order, samples[at:at + width])),
                                  *meta(at + head))
                      for first, period, at in zip(firsts, period_list, range(0, n, width))]
        else:
            ranges = []
            for r, (first, row, period) in enumerate(zip(firsts, codes.tolist(), period_list)):
                at = r * width
                # the signals as they came (the dict's order, as add's)
                group = dict(zip([signals[k] for k in row], samples[at:at + width]))
                ranges.append(JoinedRange(first, period, group, *meta(at + row.index(0))))
        self._end = int(starts[-1]) + int(sizes[-1, 0])
        return ranges

    def flush(self) -> int:
        """End of the stream: the ranges still incomplete are dropped and counted
        (``incomplete_range``); returns how many."""
        return self._drop_pending("end of stream")

    def _drop_pending(self, why: str) -> int:
        n = len(self.pending)
        for first in sorted(self.pending):
            self.faults.add("incomplete_range", f"range at sample {first} ({why})")
        self.dropped_ranges += n
        self.pending.clear()
        self.meta.clear()
        return n


def _isnan(value) -> bool:
    try:
        return math.isnan(value)
    except TypeError:
        return False

