"""Offline (``analyze``): contiguous joined ranges fed to a windowing stage in blocks, with the
same windows as the live node's range-by-range feed.
"""
from __future__ import annotations

import bisect

import numpy as np

from backlash_monitor.chain.joiner import JoinedRange
from backlash_monitor.chain.stage import WindowingStage

class BlockFeeder:
    """Offline (``analyze``): feeds a :class:`WindowingStage` contiguous joined ranges merged into
    blocks of up to ``block_samples`` samples, giving the same windows, in the same order, as
    feeding the ranges one by one (the live node's way) -- with far fewer Python calls.

    Exact because the detector and the capture are chunk-invariant for measured angles (every
    decision is a search over the stream, the contact tracker's state carries over exactly;
    test_analyze_chunk_invariance.py checks it on plant data). Integrated angles (a running sum,
    whose rounding depends on the chunking) and irregular ranges (a gap, an out-of-order or
    repeated range, another sample period, unequal lengths) are fed one by one, after the block
    before them, and so are the ranges while the stage is unsure which stream to follow
    (:meth:`WindowingStage.takes_block`).

    ``add(joined)`` / ``flush()`` -> (list of (window, range), discarded): ``range`` is the
    joined range whose feed completes the window when fed one by one (its stamp/frame_id).
    """

    def __init__(self, stage: WindowingStage, block_samples: int = 65536):
        self.stage = stage
        self.block_samples = (int(block_samples) if stage.detector.angle_source == "measured"
                              else 0)
        self._pending: list[JoinedRange] = []
        self._n = 0

    def add(self, joined: JoinedRange):
        """(list of (window, range), discarded) completed by ``joined``. The sample values of a
        block are tested once, when the block is fed (:meth:`WindowingStage.samples_good`); a block
        that fails it is added again range by range with the full check, as if its bad range had
        been seen when it came: the same windows, discards and faults."""
        return self._add(joined, exact=False)

    def _add(self, joined: JoinedRange, exact: bool):
        windows, discarded = [], []
        reason, n = self.stage.check(joined, samples=exact)
        period = joined.sample_period_s
        regular = self.block_samples > 0 and reason is None
        if self._pending:
            last = self._pending[-1]
            if not (regular and joined.first_sample_index == last.first_sample_index + self._last_n
                    and period == last.sample_period_s
                    and joined.arrays.keys() == last.arrays.keys()):
                windows, discarded = self._flush(exact, whole=True)
        if regular and not self._pending and not self._accepts(joined):
            regular = False     # dropped, switching or unsure: one by one, followers must not merge
        if not regular:
            # its values are known good only after the full check (exact)
            w, d = self._feed([joined], checked=exact and reason is None)
            return windows + w, discarded + d
        self._pending.append(joined)
        self._last_n = n
        self._n += n
        if self._n >= self.block_samples:
            w, d = self._flush(exact, whole=False)
            windows += w
            discarded += d
        return windows, discarded

    def _accepts(self, joined: JoinedRange) -> bool:
        """The range may head a block (WindowingStage.takes_block); else it is fed alone."""
        return self.stage.takes_block(joined.first_sample_index)

    def flush(self):
        return self._flush(exact=False, whole=True)

    def _flush(self, exact: bool, whole: bool):
        """Feed the pending block. Not ``exact``: its values are tested first; when they fail,
        its ranges are added again with the full check (range by range, as they came), and the
        ranges left pending after that are fed too when ``whole``."""
        ranges, self._pending, self._n = self._pending, [], 0
        if not ranges:
            return [], []
        block = self._join(ranges)
        if exact or self.stage.samples_good(block.arrays):
            return self._feed(ranges, checked=True, block=block)
        windows, discarded = [], []
        for r in ranges:
            w, d = self._add(r, exact=True)
            windows += w
            discarded += d
        if whole:
            w, d = self._flush(exact=True, whole=True)
            windows += w
            discarded += d
        return windows, discarded

    @staticmethod
    def _join(ranges: list[JoinedRange]) -> JoinedRange:
        if len(ranges) == 1:
            return ranges[0]
        first = ranges[0]
        return JoinedRange(first.first_sample_index, first.sample_period_s,
                           {k: np.concatenate([r.arrays[k] for r in ranges]) for k in first.arrays},
                           first.stamp, first.frame_id)

    def _feed(self, ranges: list[JoinedRange], checked: bool, block: JoinedRange | None = None):
        if block is None:
            block = self._join(ranges)
        windows, discarded = self.stage.feed(block, checked=checked)
        if len(ranges) == 1:
            return [(w, block) for w in windows], discarded
        # one by one, a window comes out of the feed of the range holding both its confirmation
        # (when the detector reports the entry) and its last sample; stable: same order then
        starts = [r.first_sample_index for r in ranges]
        length = self.stage.capture.window_length
        done = [max(w.start_sample_index + length - 1, w.confirm_sample_index
                    if w.confirm_sample_index is not None else w.entry_sample_index)
                for w in windows]
        at = [max(0, bisect.bisect_right(starts, d) - 1) for d in done]
        order = sorted(range(len(windows)), key=lambda i: at[i])
        return [(windows[i], ranges[at[i]]) for i in order], discarded
