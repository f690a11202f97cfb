"""The signal chain's stages as plain objects (no rclpy), shared by the nodes and ``analyze``.

The windowing, denoise and classifier nodes are thin shells over these; ``python -m
backlash_monitor analyze`` runs the same stages over a bag's messages in the order they were
received, so the offline estimates equal the live ones exactly.

- :class:`ChunkJoiner` joins the per-signal chunks of one sample range (a drive's signals arrive on
  separate topics) and gives up on ranges that stay incomplete.
- :class:`WindowingStage` feeds joined ranges to the entry detector and the window capture.
- :func:`denoise_pair` denoises a window's a1 and a2 together (one call, as the node does).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from backlash_monitor.denoise import DEFAULT_MODE, denoise_sym5
from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture

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
                 signals=("a1", "a2")):
        self.detector = BacklashEntryDetector(trigger=trigger, width_m=width_m,
                                              angle_source=angle_source)
        self.capture = WindowCapture(window_length=window_length, signals=tuple(signals))
        angle = ("angle_difference",) if angle_source == "measured" else ("omega1", "omega2")
        self.input_signals = tuple(signals) + angle

    def feed(self, joined: JoinedRange):
        """(windows, discarded) completed by this range."""
        entries = self.detector.feed(joined.first_sample_index, joined.arrays,
                                     joined.sample_period_s)
        return self.capture.feed(joined.first_sample_index, joined.arrays, entries=entries,
                                 sample_period_s=joined.sample_period_s)


def denoise_pair(a1, a2, **options):
    """sym5 denoising of a window's a1 and a2 in one call; returns (a1, a2)."""
    clean = denoise_sym5(np.stack([np.asarray(a1, dtype=np.float64),
                                   np.asarray(a2, dtype=np.float64)]),
                         **{**DENOISE_DEFAULTS, **options})
    return clean[0], clean[1]


def denoising_label(level: int, details_removed, mode: str) -> str:
    return (f"sym5 level {level}, details {','.join(map(str, details_removed))} removed, "
            f"mode {mode}")
