"""Window capture: the ``window_length`` samples that follow each entry, across chunk boundaries."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Iterable, Mapping, Sequence

import numpy as np

from .config import DEFAULTS, KIND_ONSET
from .detector import BacklashEntry, BacklashEntryDetector, _check_positive
from .offset import SensorOffsetEstimator

__all__ = ["BacklashWindow", "DiscardedWindow", "WindowCapture", "BacklashWindower", "extract_windows",
           "extract_windows_batch", "DISCARD_REASONS"]

DISCARD_REASONS = (
    "dropped_chunk",          # first_sample_index jumped: samples of the window are missing
    "out_of_order_chunk",     # a chunk older than the expected one arrived while the window was open
    "sample_period_change",   # the chunk's sample period differs from the window's
    "entry_before_history",   # the (back-dated) entry is older than the kept history
    "end_of_stream",          # flush() with the window still incomplete
    "non_finite_samples",     # a chunk with NaN/inf samples (the window would contain them)
    "length_mismatch",        # the captured signals of a chunk differ in length
    "bad_sample_period",      # a chunk whose sample period is not a finite number > 0
    "bad_index",              # a range whose first_sample_index is unusable (WindowingStage)
    "bad_shape",              # a range whose samples are not 1-D or empty (WindowingStage)
    "incomplete_range",       # a range missing a signal (WindowingStage)
    "sample_period_mismatch", # the signals of a range came with different periods (WindowingStage)
    "stream_restart",         # the sample index went back: re-synchronised (WindowingStage)
)


@dataclass
class BacklashWindow:
    """A captured window: ``signals[name]`` has ``window_length`` samples starting at the entry."""

    entry_sample_index: int
    kind: str
    trigger: str
    sample_period_s: float
    signals: dict = field(default_factory=dict)
    confirm_sample_index: int | None = None
    window_offset_samples: int = 0      # the signals start at entry_sample_index + this
    # each captured signal's constant sensor offset [its unit] as estimated at the window's end
    # (mean over the last whole load periods, offset.py); NaN before the first whole period
    sensor_offsets: dict = field(default_factory=dict)
    offset_periods: int = 0             # whole load periods behind sensor_offsets (0: none yet)
    # each captured signal's samples at a rail of the stream or stuck (saturation.SignalSaturation);
    # empty: not checked (WindowingStage checks every window it returns)
    input_saturation: dict = field(default_factory=dict)
    # a1 against the recorded motor speed up to the window's end (a1_chain.A1ChainResult); None: not checked (the
    # stage was not given the motor speed)
    a1_chain: object = None

    @property
    def saturated_samples(self) -> int:
        """Samples of the window's signals at a rail or stuck (0: clean or not checked)."""
        return sum(r.at_rail + r.stuck for r in self.input_saturation.values())

    @property
    def start_sample_index(self) -> int:
        return self.entry_sample_index + self.window_offset_samples

    @property
    def end_sample_index(self) -> int:
        """One past the window's last sample."""
        return self.start_sample_index + self.window_length

    @property
    def window_length(self) -> int:
        return int(next(iter(self.signals.values())).shape[-1]) if self.signals else 0


@dataclass(frozen=True)
class DiscardedWindow:
    entry_sample_index: int
    reason: str
    kind: str | None = None


def _all_finite(a: np.ndarray) -> bool:
    """Every sample finite: a finite sum says so at once (NaN and inf propagate into it); a sum
    that is not finite (those, or finite samples overflowing it) is decided sample by sample."""
    return math.isfinite(np.add.reduce(a)) or bool(np.isfinite(a).all())


class WindowCapture:
    """Collects windows for entries given to ``feed`` (entries may be back-dated into the history).

    ``feed(first_sample_index, signals, entries=(), sample_period_s=None)
        -> (list[BacklashWindow], list[DiscardedWindow])``
    ``signals``: mapping name -> 1-D chunk array; every name in ``self.signals`` must be present.
    Windows are returned in the call that completes them.  A dropped chunk (index jump), an
    out-of-order chunk or a sample-period change discards every open window with that reason (and
    the history: the stream restarts at the new chunk); an out-of-order chunk is otherwise ignored.

    Every window carries each captured signal's constant sensor offset as estimated at its end
    (``sensor_offsets``, ``offset_periods``): the mean over the last ``offset_periods`` whole load
    periods, each from the end of one onset window to the end of the next (offset.py).
    """

    def __init__(self, window_length: int = DEFAULTS["capture"]["window_length"],
                 signals: Sequence[str] = tuple(DEFAULTS["capture"]["signals"]),
                 history_samples: int = DEFAULTS["capture"]["history_samples"],
                 sample_period_s: float = DEFAULTS["detector"]["sample_period_s"],
                 window_offset_samples: int = 0,
                 offset_periods: int = DEFAULTS["sensor_offset"]["periods"]):
        self.window_length = _check_positive("window_length", window_length, integer=True)
        if (isinstance(window_offset_samples, bool) or not float(window_offset_samples).is_integer()
                or not 0 <= int(window_offset_samples) <= 65536):
            raise ValueError(f"window_offset_samples={window_offset_samples!r}: must be an integer, "
                             "0 <= offset <= 65536 (samples from the entry to the window start)")
        self.window_offset_samples = int(window_offset_samples)
        if isinstance(signals, str) or not len(signals):
            raise ValueError(f"signals={signals!r}: must be a non-empty sequence of signal names")
        self.signals = tuple(signals)
        self.history_samples = _check_positive("history_samples", history_samples, integer=True)
        self.sample_period_s = _check_positive("sample_period_s", sample_period_s)
        self._buf: dict[str, np.ndarray] = {s: np.zeros(0) for s in self.signals}
        self._base = 0                  # absolute index of the first buffered sample
        self._next: int | None = None   # expected first_sample_index of the next chunk
        self._pending: list[BacklashEntry] = []
        self.offsets = SensorOffsetEstimator(self.signals, periods=offset_periods)

    def _discard_all(self, reason: str) -> list[DiscardedWindow]:
        d = [DiscardedWindow(e.sample_index, reason, e.kind) for e in self._pending]
        self._pending = []
        return d

    def _restart(self, first: int) -> None:
        self._buf = {s: np.zeros(0) for s in self.signals}
        self._base = first
        self.offsets.restart(first)

    def feed(self, first_sample_index: int, signals: Mapping[str, np.ndarray],
             entries: Iterable[BacklashEntry] = (), sample_period_s: float | None = None,
             finite: bool = False):
        """(windows, discarded) this chunk completes. ``finite``: the caller has checked that
        every sample in ``signals`` is finite (WindowingStage does): not tested again."""
        first = int(first_sample_index)
        discarded: list[DiscardedWindow] = []
        if sample_period_s is not None:
            try:
                sp = _check_positive("sample_period_s", sample_period_s)
            except ValueError:
                discarded += self._discard_all("bad_sample_period")
                discarded += [DiscardedWindow(e.sample_index, "bad_sample_period", e.kind) for e in entries]
                self._next = None
                return [], discarded
            if abs(sp - self.sample_period_s) > 1e-9 * self.sample_period_s:
                discarded += self._discard_all("sample_period_change")
                self.sample_period_s = sp
                self._next = None
        if self._next is not None and first < self._next:
            discarded += self._discard_all("out_of_order_chunk")
            discarded += [DiscardedWindow(e.sample_index, "out_of_order_chunk", e.kind) for e in entries]
            return [], discarded
        if self._next is not None and first > self._next:
            discarded += self._discard_all("dropped_chunk")
        if self._next is None or first != self._next:
            self._restart(first)
        missing = [s for s in self.signals if s not in signals]
        if missing:
            raise ValueError(f"signals: missing {missing} (capture signals={self.signals})")
        arrays = [np.asarray(signals[s], dtype=np.float64) for s in self.signals]
        n = arrays[0].size
        if any(a.ndim != 1 for a in arrays):
            raise ValueError("signals: every captured signal must be a 1-D array of the same length")
        bad = ("length_mismatch" if any(a.size != n for a in arrays) else
               "non_finite_samples" if not finite and not all(map(_all_finite, arrays)) else None)
        if bad is not None:
            # the windows open across this chunk would hold it: discard them, start again after it
            discarded += self._discard_all(bad)
            discarded += [DiscardedWindow(e.sample_index, bad, e.kind) for e in entries]
            end = first + max(a.size for a in arrays)
            self._restart(end)
            self._next = end
            return [], discarded
        for s, a in zip(self.signals, arrays):
            self._buf[s] = np.concatenate((self._buf[s], a))
        self.offsets.feed(first, dict(zip(self.signals, arrays)))
        self._next = first + n
        for e in entries:
            if e.sample_index < self._base:
                discarded.append(DiscardedWindow(e.sample_index, "entry_before_history", e.kind))
            else:
                self._pending.append(e)
        end = self._next
        windows: list[BacklashWindow] = []
        still = []
        for e in self._pending:
            if e.sample_index + self.window_offset_samples + self.window_length <= end:
                lo = e.sample_index + self.window_offset_samples - self._base
                window = BacklashWindow(
                    entry_sample_index=e.sample_index, kind=e.kind, trigger=e.trigger,
                    sample_period_s=self.sample_period_s,
                    signals={s: self._buf[s][lo:lo + self.window_length].copy() for s in self.signals},
                    confirm_sample_index=e.confirm_sample_index,
                    window_offset_samples=self.window_offset_samples)
                if e.kind == KIND_ONSET:   # a whole load period ends with each onset window
                    self.offsets.close_period(window.end_sample_index,
                                              self._heads(window.end_sample_index))
                window.sensor_offsets, window.offset_periods = self.offsets.estimate()
                windows.append(window)
            else:
                still.append(e)
        self._pending = still
        keep_from = end - self.history_samples
        if still:
            keep_from = min(keep_from, min(e.sample_index for e in still))
        cut = keep_from - self._base
        if cut > 0:
            for s in self.signals:
                self._buf[s] = self._buf[s][cut:]
            self._base += cut
        return windows, discarded

    def _heads(self, index: int) -> dict | None:
        """Each signal's sum over [block start of ``index``, ``index``) from the kept history (one
        contiguous slice: the same sum however the stream came in), or None when not all there."""
        lo = self.offsets.block_start(index) - self._base
        hi = index - self._base
        if lo < 0 or hi > self._buf[self.signals[0]].size:
            return None
        return {s: float(np.sum(self._buf[s][lo:hi])) for s in self.signals}

    def flush(self) -> list[DiscardedWindow]:
        """End of stream: every open window is discarded ("end_of_stream")."""
        return self._discard_all("end_of_stream")


class BacklashWindower:
    """Detector + capture in one: ``feed(first_sample_index, signals, sample_period_s=None)
    -> (windows, discarded)``.  The capture history is sized from the detector's back-dating."""

    def __init__(self, detector: BacklashEntryDetector | None = None, capture: WindowCapture | None = None,
                 **detector_kwargs):
        self.detector = detector if detector is not None else BacklashEntryDetector(**detector_kwargs)
        if capture is None:
            capture = WindowCapture(history_samples=max(DEFAULTS["capture"]["history_samples"],
                                                        self.detector.latency_samples + 1),
                                    sample_period_s=self.detector.sample_period_s)
        if capture.history_samples <= self.detector.latency_samples:
            raise ValueError(f"capture.history_samples={capture.history_samples}: must exceed the detector's "
                             f"back-dating latency ({self.detector.latency_samples} samples)")
        self.capture = capture
        self.entries: list[BacklashEntry] = []

    def feed(self, first_sample_index: int, signals: Mapping[str, np.ndarray], sample_period_s: float | None = None):
        ent = self.detector.feed(first_sample_index, signals, sample_period_s)
        self.entries += ent
        return self.capture.feed(first_sample_index, signals, ent, sample_period_s)

    def flush(self) -> list[DiscardedWindow]:
        return self.capture.flush()


def extract_windows(signals: Mapping[str, np.ndarray], trigger: str = DEFAULTS["detector"]["trigger"],
                    width_m: float | None = None, first_sample_index: int = 0,
                    sample_period_s: float = DEFAULTS["detector"]["sample_period_s"],
                    window_length: int = DEFAULTS["capture"]["window_length"],
                    window_signals: Sequence[str] = tuple(DEFAULTS["capture"]["signals"]),
                    chunk_samples: int | None = None, return_discarded: bool = False,
                    window_offset_samples: int = 0, **detector_kwargs):
    """Offline convenience for one drive: 1-D arrays of a whole record -> list[BacklashWindow].

    ``chunk_samples`` feeds the record in chunks of that size (the streaming path; default: one
    chunk).  ``window_offset_samples``: the window starts that many samples after the entry.
    Windows still open at the end of the record are dropped (or returned as
    ``end_of_stream`` discards with ``return_discarded=True``, which returns (windows, discarded)).
    """
    arrs = {k: np.asarray(v) for k, v in signals.items()}
    shapes = {v.shape for v in arrs.values()}
    if len(shapes) != 1 or next(iter(shapes)).__len__() != 1:
        raise ValueError(f"signals: need 1-D arrays of one length (got shapes {sorted(shapes)}); "
                         "use extract_windows_batch for (n_scenarios, n) arrays")
    n = next(iter(shapes))[0]
    det = BacklashEntryDetector(trigger=trigger, width_m=width_m, sample_period_s=sample_period_s, **detector_kwargs)
    cap = WindowCapture(window_length=window_length, signals=window_signals,
                        history_samples=max(DEFAULTS["capture"]["history_samples"], det.latency_samples + 1),
                        sample_period_s=sample_period_s, window_offset_samples=window_offset_samples)
    w = BacklashWindower(det, cap)
    step = n if chunk_samples is None else _check_positive("chunk_samples", chunk_samples, integer=True)
    windows, discarded = [], []
    for lo in range(0, n, max(step, 1)):
        ww, dd = w.feed(first_sample_index + lo, {k: v[lo:lo + step] for k, v in arrs.items()})
        windows += ww
        discarded += dd
    discarded += w.flush()
    return (windows, discarded) if return_discarded else windows


def extract_windows_batch(signals: Mapping[str, np.ndarray], width_m=None, **kwargs) -> list[list[BacklashWindow]]:
    """``extract_windows`` for every row of (n_scenarios, n) arrays; ``width_m`` scalar or per row."""
    arrs = {k: np.atleast_2d(np.asarray(v)) for k, v in signals.items()}
    rows = {v.shape[0] for v in arrs.values()}
    if len(rows) != 1:
        raise ValueError(f"signals: all arrays need the same number of rows (got {sorted(rows)})")
    nrow = rows.pop()
    widths = np.broadcast_to(np.asarray(width_m if width_m is not None else np.nan, dtype=float), (nrow,))
    return [extract_windows({k: v[i] for k, v in arrs.items()},
                            width_m=None if np.isnan(widths[i]) else float(widths[i]), **kwargs)
            for i in range(nrow)]
