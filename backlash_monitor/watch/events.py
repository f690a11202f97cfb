"""The live onset events of a drive's stream, as the workbench takes them from a recording (workbench/events.py).

The project's contact_loss detector (the one ``diagnose`` runs) finds the onset entries in the angle difference;
an event is complete once its pulse period has streamed past: then it has its raw segment (PRE_SAMPLES before the
entry to POST_SAMPLES after it, a1 and a2), its period mean of a1, a2 and the motor speed omega1 when it is
streamed (events.period_means: one pulse period from PRE_SAMPLES before the entry; the period is the median
spacing of the drive's recent onset entries; omega1's mean is the motor's load, which the accelerations do not
show), its
raw spectral-shape features (spectral.event_features) and the Welch spectrum of that period (the sensor noise
floor is read off it, as analysis.sensor_noise_floor reads the whole record's). Plain numpy, no rclpy.

A gap in the stream (a lost chunk, a restart) drops the events it cuts and starts the detector again after it,
as the windowing does; the events completed before it are kept.
"""
from __future__ import annotations

from collections import deque
from dataclasses import dataclass

import numpy as np

from backlash_monitor.windowing import BacklashEntryDetector
from backlash_monitor.workbench import analysis, spectral
from backlash_monitor.workbench.events import DC_SIGNALS, POST_SAMPLES, PRE_SAMPLES, SEGMENT_SIGNALS, denoise

ENTRY_SPACINGS = 16          # onset spacings the period is the median of
PSD_EVERY = 4                # the Welch spectrum of every 4th event's period (a sensor's noise floor is a slow
                             # property; scipy's welch costs ~1.7 ms, a third of an event's work): 4 of a
                             # 16-event window, 8 Welch segments of 8192 samples


@dataclass
class LiveEvent:
    entry_sample_index: int
    raw: np.ndarray              # (2, PRE + POST) a1, a2 [m/s^2]
    dc: np.ndarray               # (D,) period means of LiveEvents.dc_names [m/s^2, rad/s]
    spec: np.ndarray             # (n_features,) spectral-shape features (spectral.event_features)
    psd: np.ndarray | None       # (2, F) Welch PSD of the event's period [(m/s^2)^2/Hz] (analysis.welch_psd);
                                 # every PSD_EVERY-th event
    denoised: np.ndarray | None = None   # (2, PRE + POST) the raw segment sym5-denoised (events.denoise) [m/s^2]:
                                         # once per event, not once per window it is in


class SampleRing:
    """The last ``capacity`` samples of some signals, addressed by their stream index."""

    def __init__(self, names, capacity: int):
        self.capacity = int(capacity)
        self.data = {n: np.zeros(self.capacity) for n in names}
        self.end = 0              # stream index one past the newest sample
        self.count = 0            # samples held

    def clear(self, at: int) -> None:
        self.end, self.count = int(at), 0

    def append(self, first_index: int, arrays: dict) -> None:
        n = len(next(iter(arrays.values())))
        if first_index != self.end:
            self.clear(first_index)
        for name, x in arrays.items():
            buf = self.data[name]
            x = np.asarray(x, dtype=np.float64)[-self.capacity:]
            start = (first_index + n - len(x)) % self.capacity
            k = min(len(x), self.capacity - start)
            buf[start:start + k] = x[:k]
            buf[:len(x) - k] = x[k:]
        self.end = first_index + n
        self.count = min(self.count + n, self.capacity)

    @property
    def start(self) -> int:
        return self.end - self.count

    def get(self, name: str, lo: int, hi: int) -> np.ndarray:
        """Samples lo..hi-1 (stream indices; must be held)."""
        if lo < self.start or hi > self.end or hi < lo:
            raise IndexError(f"samples {lo}..{hi} not held ({self.start}..{self.end})")
        buf = self.data[name]
        a, b = lo % self.capacity, hi % self.capacity
        if hi - lo == 0:
            return buf[:0].copy()
        if a < b or b == 0:
            return buf[a:b or self.capacity].copy()
        return np.concatenate([buf[a:], buf[:b]])


class LiveEvents:
    """Streams a drive's a1, a2, angle difference (and omega1) in; gives its completed onset events out.
    ``dc_names``: the record-mean view's signals, a1 and a2 and optionally omega1 (events.DC_SIGNALS' order);
    with omega1 every feed brings it."""

    def __init__(self, sample_period_s: float, pulse_period_samples: int, psd_every: int = PSD_EVERY,
                 dc_names=SEGMENT_SIGNALS):
        self.dc_names = tuple(dc_names)
        if self.dc_names not in (SEGMENT_SIGNALS, DC_SIGNALS):
            raise ValueError(f"record-mean signals {self.dc_names}; allowed: {SEGMENT_SIGNALS} or {DC_SIGNALS}")
        self.dt = float(sample_period_s)
        self.psd_every = int(psd_every)
        self.completed = 0
        self.default_period = int(pulse_period_samples)
        self.detector = BacklashEntryDetector(trigger="contact_loss", sample_period_s=self.dt)
        # the detector confirms an entry a few ms late; an event needs PRE before it and a period after it
        self.ring = SampleRing(self.dc_names, PRE_SAMPLES + 3 * self.default_period)
        self.pending: deque = deque()
        self.spacings: deque = deque(maxlen=ENTRY_SPACINGS)
        self.last_entry: int | None = None
        self.period = self.default_period    # the median spacing of the recent onset entries [samples]
        self.next_index: int | None = None
        self.dropped_events = 0          # cut by a gap in the stream
        self.gaps = 0

    def feed(self, first_sample_index: int, a1, a2, angle_difference, omega1=None) -> list[LiveEvent]:
        """The next samples of the stream (from ``first_sample_index``; omega1 [rad/s] when dc_names has it); the
        onset events they complete."""
        first = int(first_sample_index)
        streams = {"a1": a1, "a2": a2}
        if "omega1" in self.dc_names:
            if omega1 is None or len(omega1) != len(a1):
                raise ValueError("this watch's record mean has omega1: each feed brings omega1's samples of the "
                                 "same range")
            streams["omega1"] = omega1
        if self.next_index is not None and first != self.next_index:
            self.gaps += 1
            self.dropped_events += len(self.pending)
            self.pending.clear()
            self.last_entry = None
        self.ring.append(first, streams)
        self.next_index = first + len(a1)
        for e in self.detector.feed(first, {"angle_difference": np.asarray(angle_difference, dtype=np.float64)},
                                    self.dt):
            if e.kind != "onset":
                continue
            if self.last_entry is not None:
                self.spacings.append(e.sample_index - self.last_entry)
                if len(self.spacings) >= 2:      # one spacing may be a restart's: the model's period until two
                    self.period = int(np.median(self.spacings))
            self.last_entry = e.sample_index
            self.pending.append(e.sample_index)
        out = []
        while self.pending:
            k = self.pending[0]
            lo = k - PRE_SAMPLES
            hi = lo + max(self.period, PRE_SAMPLES + POST_SAMPLES)
            if hi > self.ring.end:
                break
            self.pending.popleft()
            if lo < self.ring.start:
                self.dropped_events += 1         # its samples came before a gap or before the stream
                continue
            out.append(self._event(k, lo, hi))
        return out

    def _event(self, k: int, lo: int, hi: int) -> LiveEvent:
        seg_hi = k + POST_SAMPLES
        raw = np.stack([self.ring.get(s, lo, seg_hi) for s in SEGMENT_SIGNALS])
        period = np.stack([self.ring.get(s, lo, lo + self.period) for s in self.dc_names])
        accel = period[:len(SEGMENT_SIGNALS)]
        psd = analysis.welch_psd(accel, 1.0 / self.dt)[1] if self.completed % self.psd_every == 0 else None
        self.completed += 1
        return LiveEvent(int(k), raw, period.mean(axis=1), spectral.event_features(raw[None], self.dt)[0], psd,
                         denoise(raw))
