"""The signal chain's stages as plain objects (no rclpy), shared by the nodes and ``analyze``.

The windowing, denoise and classifier nodes are thin shells over these; ``python -m
backlash_monitor analyze`` runs the same stages over a bag's messages in the order they were
received, so the offline estimates equal the live ones exactly.

- :class:`ChunkJoiner` joins the per-signal chunks of one sample range (a drive's signals arrive on
  separate topics) and gives up on ranges that stay incomplete.
- :class:`WindowingStage` feeds joined ranges to the entry detector and the window capture.
- :class:`BlockFeeder` (offline) feeds contiguous ranges to a WindowingStage in blocks, with
  the same windows as one by one.
- :func:`denoise_pair` denoises a window's a1 and a2 together (one call, as the node does);
  :func:`denoise_pairs` (offline) many windows in one batch, with the same results.
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass

import numpy as np

from backlash_monitor.denoise import DEFAULT_MODE, denoise_sym5
from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture, default_window_offset

MAX_PENDING_RANGES = 16
DENOISE_DEFAULTS = dict(level=6, details_removed=(1, 2, 3, 4, 5, 6), mode=DEFAULT_MODE)


@dataclass
class JoinedRange:
    first_sample_index: int
    sample_period_s: float
    arrays: dict
    stamp: object = None     # the first signal's header stamp, when the caller has one
    frame_id: str = ""


class ChunkJoiner:
    """Collects one chunk of each of ``signals`` per first_sample_index; returns complete ranges.

    A range still incomplete while more than ``max_pending`` ranges wait is dropped (counted in
    ``dropped_ranges``); the window capture then sees the gap and discards the windows spanning it.
    """

    def __init__(self, signals, max_pending: int = MAX_PENDING_RANGES):
        self.signals = tuple(signals)
        self.max_pending = max_pending
        self.pending: dict[int, dict] = {}
        self.meta: dict[int, tuple] = {}
        self.dropped_ranges = 0

    def add(self, name: str, first_sample_index: int, sample_period_s: float, samples,
            stamp=None, frame_id: str = "") -> JoinedRange | None:
        if name not in self.signals:
            return None
        group = self.pending.setdefault(first_sample_index, {})
        group[name] = np.asarray(samples, dtype=np.float64)
        if name == self.signals[0] or first_sample_index not in self.meta:
            self.meta[first_sample_index] = (sample_period_s, stamp, frame_id)
        if len(group) < len(self.signals):
            if len(self.pending) > self.max_pending:
                oldest = min(self.pending)
                del self.pending[oldest]
                self.meta.pop(oldest, None)
                self.dropped_ranges += 1
            return None
        del self.pending[first_sample_index]
        period, stamp, frame_id = self.meta.pop(first_sample_index)
        return JoinedRange(first_sample_index, period, group, stamp, frame_id)


class WindowingStage:
    """Entry detection + window capture of one drive (backlash_monitor.windowing)."""

    def __init__(self, trigger: str = "contact_loss", width_m: float | None = None,
                 angle_source: str = "measured", window_length: int = 2048,
                 signals=("a1", "a2"), window_offset_samples: int | None = None):
        """``window_offset_samples``: window start after the entry; None = the trigger's configured
        value (config/windowing.yaml capture.window_offset_samples)."""
        if window_offset_samples is None:
            window_offset_samples = default_window_offset(trigger)
        self.detector = BacklashEntryDetector(trigger=trigger, width_m=width_m,
                                              angle_source=angle_source)
        self.capture = WindowCapture(window_length=window_length, signals=tuple(signals),
                                     window_offset_samples=window_offset_samples)
        self.window_offset_samples = self.capture.window_offset_samples
        angle = ("angle_difference",) if angle_source == "measured" else ("omega1", "omega2")
        self.input_signals = tuple(signals) + angle

    def feed(self, joined: JoinedRange):
        """(windows, discarded) completed by this range."""
        entries = self.detector.feed(joined.first_sample_index, joined.arrays,
                                     joined.sample_period_s)
        return self.capture.feed(joined.first_sample_index, joined.arrays, entries=entries,
                                 sample_period_s=joined.sample_period_s)


class BlockFeeder:
    """Offline (``analyze``): feeds a :class:`WindowingStage` contiguous joined ranges merged into
    blocks of up to ``block_samples`` samples, giving the same windows, in the same order, as
    feeding the ranges one by one (the live node's way) -- with far fewer Python calls.

    Exact because the detector and the capture are chunk-invariant for measured angles (every
    decision is a search over the stream, the contact tracker's state carries over exactly;
    test_analyze_chunk_invariance.py checks it on plant data). Integrated angles (a running sum,
    whose rounding depends on the chunking) and irregular ranges (a gap, an out-of-order or
    repeated range, another sample period, unequal lengths) are fed one by one, after the block
    before them.

    ``add(joined)`` / ``flush()`` -> (list of (window, range), discarded): ``range`` is the
    joined range whose feed completes the window when fed one by one (its stamp/frame_id).
    """

    def __init__(self, stage: WindowingStage, block_samples: int = 65536):
        self.stage = stage
        self.block_samples = (int(block_samples) if stage.detector.angle_source == "measured"
                              else 0)
        self._pending: list[JoinedRange] = []
        self._n = 0

    @staticmethod
    def _length(joined: JoinedRange) -> int:
        """Common length of the range's 1-D arrays; -1 when they differ (or are not 1-D)."""
        n = -1
        for a in joined.arrays.values():
            if a.ndim != 1 or (n >= 0 and a.size != n):
                return -1
            n = a.size
        return n

    def add(self, joined: JoinedRange):
        windows, discarded = [], []
        n = self._length(joined)
        period = joined.sample_period_s
        regular = (self.block_samples > 0 and n > 0 and isinstance(period, float)
                   and 0.0 < period < float("inf"))
        if self._pending:
            last = self._pending[-1]
            if not (regular and joined.first_sample_index == last.first_sample_index + self._last_n
                    and period == last.sample_period_s
                    and joined.arrays.keys() == last.arrays.keys()):
                windows, discarded = self.flush()
        if regular and not self._pending and not self._accepts(joined):
            regular = False     # ignored one by one (out of order): followers must not merge
        if not regular:
            w, d = self._feed([joined])
            return windows + w, discarded + d
        self._pending.append(joined)
        self._last_n = n
        self._n += n
        if self._n >= self.block_samples:
            w, d = self.flush()
            windows += w
            discarded += d
        return windows, discarded

    def _accepts(self, joined: JoinedRange) -> bool:
        """The stage takes the range in (not ignored as out of order): it may head a block."""
        first = joined.first_sample_index
        return all(nxt is None or first >= nxt
                   for nxt in (self.stage.detector._next_index, self.stage.capture._next))

    def flush(self):
        ranges, self._pending, self._n = self._pending, [], 0
        return self._feed(ranges) if ranges else ([], [])

    def _feed(self, ranges: list[JoinedRange]):
        if len(ranges) == 1:
            block = ranges[0]
        else:
            first = ranges[0]
            block = JoinedRange(first.first_sample_index, first.sample_period_s,
                                {k: np.concatenate([r.arrays[k] for r in ranges])
                                 for k in first.arrays}, first.stamp, first.frame_id)
        windows, discarded = self.stage.feed(block)
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


def denoise_pair(a1, a2, **options):
    """sym5 denoising of a window's a1 and a2 in one call; returns (a1, a2)."""
    clean = denoise_sym5(np.stack([np.asarray(a1, dtype=np.float64),
                                   np.asarray(a2, dtype=np.float64)]),
                         **{**DENOISE_DEFAULTS, **options})
    return clean[0], clean[1]


def denoise_pairs(pairs, **options) -> list[tuple[np.ndarray, np.ndarray]]:
    """:func:`denoise_pair` of many windows' (a1, a2) in one batched transform (offline).

    pywt transforms every row of a 2-D batch with the same 1-D routine, so each result is bit for
    bit the window's own ``denoise_pair`` (test_chain_denoise_pairs.py); windows of unequal
    lengths are denoised pair by pair."""
    pairs = [(np.asarray(a1, dtype=np.float64), np.asarray(a2, dtype=np.float64))
             for a1, a2 in pairs]
    shapes = {a.shape for pair in pairs for a in pair}
    if len(pairs) < 2 or len(shapes) != 1 or len(next(iter(shapes))) != 1:
        return [denoise_pair(a1, a2, **options) for a1, a2 in pairs]
    rows = np.stack([a for pair in pairs for a in pair])          # a1, a2, a1, a2, ...
    clean = denoise_sym5(rows, **{**DENOISE_DEFAULTS, **options})
    return [(clean[2 * i], clean[2 * i + 1]) for i in range(len(pairs))]


def denoising_label(level: int, details_removed, mode: str) -> str:
    return (f"sym5 level {level}, details {','.join(map(str, details_removed))} removed, "
            f"mode {mode}")
