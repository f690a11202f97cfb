"""Event-locked views of a drive: onset entries (the project's contact_loss trigger), entry-aligned
segments, their event average (raw and sym5-denoised), and the model's noise ensemble of the same.

A *segment* is ``PRE_SAMPLES`` before the onset entry to ``POST_SAMPLES`` after it, of a1 and a2.
The same detector runs on the measurement and on every simulated run, so the alignment is the same.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from backlash_monitor.denoise import denoise_sym5
from backlash_monitor.windowing import BacklashEntryDetector

from . import spectral

PRE_SAMPLES = 250          # 5 ms before the entry: the "before entry" phase
POST_SAMPLES = 2048        # the paper's window after the entry
SEGMENT_SIGNALS = ("a1", "a2")
IMPACT_SETTLE_S = 0.004    # the "impact" phase: first 4 ms after the far-side impact; then "settling"


def onset_entries(signals: dict, sample_period_s: float) -> np.ndarray:
    """Sample indices of the onset entries (contact_loss trigger, measured or integrated angle)."""
    if "angle_difference" in signals:
        det = BacklashEntryDetector(trigger="contact_loss", sample_period_s=sample_period_s)
        sig = {"angle_difference": signals["angle_difference"]}
    else:
        det = BacklashEntryDetector(trigger="contact_loss", sample_period_s=sample_period_s,
                                    angle_source="integrated")
        sig = {"omega1": signals["omega1"], "omega2": signals["omega2"]}
    entries = det.feed(0, sig, sample_period_s)
    return np.array([e.sample_index for e in entries if e.kind == "onset"], dtype=np.int64)


def segments(signals: dict, entries: np.ndarray) -> np.ndarray:
    """(n_events, 2, PRE+POST) raw segments of a1, a2 around each complete onset entry."""
    n = len(signals["a1"])
    keep = [int(k) for k in entries if k - PRE_SAMPLES >= 0 and k + POST_SAMPLES <= n]
    out = np.empty((len(keep), len(SEGMENT_SIGNALS), PRE_SAMPLES + POST_SAMPLES))
    for i, k in enumerate(keep):
        for j, s in enumerate(SEGMENT_SIGNALS):
            out[i, j] = signals[s][k - PRE_SAMPLES:k + POST_SAMPLES]
    return out


def denoise(x: np.ndarray) -> np.ndarray:
    """The project's sym5 denoising (level 6, details 1-6 removed) along the last axis (linear)."""
    return denoise_sym5(x)


@dataclass
class EventSet:
    """The onset segments of one record: raw (n_events, 2, L); ``entries`` their entry indices; ``dc``
    (n_events, 2) each event's *period mean* of a1, a2 (period_means: the record-mean view's units)."""
    raw: np.ndarray
    entries: np.ndarray
    dc: np.ndarray | None = None

    @property
    def n_events(self) -> int:
        return int(self.raw.shape[0])

    def mean_raw(self) -> np.ndarray:
        return self.raw.mean(axis=0)

    def mean_denoised(self) -> np.ndarray:
        return denoise(self.mean_raw())


DC_SIGNALS = ("a1", "a2", "omega1")   # the record-mean view's signals (omega1 when the recording has it)


DC_BLOCKS = 4     # the record-mean view's noise: the spread of the means of this many consecutive blocks of events


def dc_block_deviations(per_event_dc: np.ndarray, blocks: int = DC_BLOCKS) -> np.ndarray:
    """(n_events, n_dc): each event's period means replaced by its block's mean minus the record's mean, times
    sqrt(n_events / blocks): events as the units, but with the covariance of the record mean's noise x n_events.
    A record's period means are not independent -- the motor speed wanders over several pulse periods (its mechanical
    time constant is 0.86 s), and an acceleration's period means telescope -- so the event-to-event spread misstates
    the noise of their mean (measured: the mean motor speed of a 4 s recording scattered ~0.1 rad/s between noise
    seeds, 3x what 16 independent periods would give); the means of blocks of consecutive events are ~independent."""
    x = np.asarray(per_event_dc, dtype=float)
    e = x.shape[0]
    if e < 2 * blocks:
        return (x - x.mean(axis=0)) * 1.0
    idx = np.array_split(np.arange(e), blocks)
    out = np.empty_like(x)
    mean = x.mean(axis=0)
    for sel in idx:
        out[sel] = x[sel].mean(axis=0) - mean
    return out * np.sqrt(e / blocks)


def dc_signals(signals: dict) -> tuple:
    """The record-mean view's signals a recording has: a1, a2, and the motor speed omega1 when recorded."""
    return tuple(s for s in DC_SIGNALS if s in signals)


def period_means(signals: dict, entries: np.ndarray, all_entries: np.ndarray, names=None) -> np.ndarray:
    """(n_events, len(names)): per onset event, the mean of each signal (default dc_signals: a1, a2 and omega1)
    over one pulse period starting PRE_SAMPLES before its entry (the period: the median spacing of the record's
    onset entries; clipped to the record -- the model's runs have the measurement's length and pulse phase, so a
    clipped last period is clipped alike there).
    An acceleration averages to zero over a stretch whose speed returns to its value: over a period of the
    periodic steady state the physics' mean is ~0, a sensor's constant offset is not. The motor's mean speed is
    its load: an induction motor slips in proportion to its load torque (0.1 p.u. more load: ~0.9 rad/s slower),
    which the accelerations alone do not show (docs/workbench.md "Views")."""
    names = dc_signals(signals) if names is None else tuple(names)
    n = len(signals["a1"])
    period = int(np.median(np.diff(all_entries))) if len(all_entries) > 1 else n
    out = np.empty((len(entries), len(names)))
    for i, k in enumerate(entries):
        lo = max(int(k) - PRE_SAMPLES, 0)
        hi = min(lo + period, n)
        for j, s in enumerate(names):
            out[i, j] = float(np.mean(signals[s][lo:hi]))
    return out


def event_set(signals: dict, sample_period_s: float, dc_names=None) -> EventSet:
    entries = onset_entries(signals, sample_period_s)
    seg = segments(signals, entries)
    n = len(signals["a1"])
    kept = np.array([k for k in entries if k - PRE_SAMPLES >= 0 and k + POST_SAMPLES <= n], dtype=np.int64)
    return EventSet(seg, kept, period_means(signals, kept, entries, dc_names))


@dataclass
class Ensemble:
    """A model's ensemble: per run (set, seed) the event-averaged raw segment; (n_sets, n_seeds, 2, L).

    ``per_event`` keeps every event's raw segment of set 0 (for the per-event statistics)."""
    seed_means: np.ndarray
    n_events: np.ndarray          # (n_sets, n_seeds)
    per_event: list               # per seed of set 0: (n_events, 2, L)
    raw_records: dict | None = None
    per_event_entries: list | None = None   # per seed of set 0: the entry indices of per_event
    seed_bands: list | None = None          # [set][seed]: (n_events, 2, n_bands) raw band powers (spectral.py)
    seed_dc: np.ndarray | None = None       # (n_sets, n_seeds, 2) event-mean period means of a1, a2
    per_event_dc: list | None = None        # per seed of set 0: (n_events, 2)

    def mean_raw(self, s: int = 0) -> np.ndarray:
        w = self.n_events[s].astype(float)
        return np.tensordot(w / w.sum(), self.seed_means[s], axes=(0, 0))

    def mean_denoised(self, s: int = 0) -> np.ndarray:
        return denoise(self.mean_raw(s))

    def spec_mean(self, s: int = 0, noise=None) -> np.ndarray:
        """The spectral-shape features averaged over all events of set s (every seed's events); ``noise``: a
        sensor noise floor per signal added to the band powers first (spectral.features_from_bands)."""
        return spectral.features_from_bands(np.concatenate(self.seed_bands[s], axis=0), noise).mean(axis=0)

    def event_bands(self, k: int) -> np.ndarray:
        """Band powers of seed k's events of set 0: (n_events, 2, n_bands)."""
        return self.seed_bands[0][k]

    def dc_mean(self, s: int = 0) -> np.ndarray:
        """The period means of a1, a2 averaged over all events of set s (every seed's events)."""
        w = self.n_events[s].astype(float)
        return np.tensordot(w / w.sum(), self.seed_dc[s], axes=(0, 0))

    def dc_samples(self, k: int) -> np.ndarray:
        """The period means of seed k's events of set 0: (n_events, 2)."""
        return self.per_event_dc[k]

    def seed_denoised(self, s: int = 0) -> np.ndarray:
        return denoise(self.seed_means[s])

    def loo_deviation(self, s: int = 0, denoised: bool = True) -> np.ndarray:
        """(n_seeds, 2, L): each seed's average minus the average of the others (the noise floor's
        samples: what a correct model's own records look like against the model's mean)."""
        x = self.seed_denoised(s) if denoised else self.seed_means[s]
        k = x.shape[0]
        total = x.sum(axis=0)
        return x - (total - x) / (k - 1)


class NoOnsetWindow(ValueError):
    """A simulated run gave no complete onset window: the model does not cross its backlash there. ``sets``: the
    indices (in the batch given) of the parameter sets with a seed that gave none; ``message``: what says where (None:
    the general words)."""

    def __init__(self, sets=(), message: str | None = None):
        self.sets = tuple(int(i) for i in sets)
        super().__init__(message or "a simulated run of the model gave no complete onset window; the model does not "
                                    "cross its backlash under these conditions")


def ensemble_from_runs(runs: dict, sample_period_s: float, keep_records: bool = False, dc_names=None,
                       empty_ok: bool = False) -> Ensemble:
    """``runs``: {signal: (n_sets, n_seeds, n)} from plant_adapter.simulate_sets; ``dc_names``: the record-mean
    view's signals (the measurement's: dc_signals). A set with a seed that gave no onset window raises
    NoOnsetWindow, or with ``empty_ok`` stays in the ensemble with ``n_events`` 0 there (the caller reads it: its
    means are zeros and its band powers None)."""
    dc_names = tuple(dc_names) if dc_names is not None else dc_signals(runs)
    n_sets, n_seeds, n = runs["a1"].shape
    L = PRE_SAMPLES + POST_SAMPLES
    means = np.zeros((n_sets, n_seeds, len(SEGMENT_SIGNALS), L))
    counts = np.zeros((n_sets, n_seeds), dtype=np.int64)
    bands = [[None] * n_seeds for _ in range(n_sets)]
    dc = np.zeros((n_sets, n_seeds, len(dc_names)))
    per_event, per_entries, per_dc = [], [], []
    for i in range(n_sets):
        for j in range(n_seeds):
            sig = {s: runs[s][i, j] for s in runs}
            ev = event_set(sig, sample_period_s, dc_names)
            counts[i, j] = ev.n_events
            if ev.n_events:
                means[i, j] = ev.mean_raw()
                bands[i][j] = spectral.band_powers(ev.raw, sample_period_s)
                dc[i, j] = ev.dc.mean(axis=0)
            if i == 0:
                per_event.append(ev.raw)
                per_entries.append(ev.entries)
                per_dc.append(ev.dc)
    if (counts == 0).any() and not empty_ok:
        raise NoOnsetWindow(np.flatnonzero((counts == 0).any(axis=1)))
    records = {s: runs[s][0] for s in runs} if keep_records else None
    return Ensemble(means, counts, per_event, records, per_entries, bands, dc, per_dc)


def concat_ensembles(parts: list) -> Ensemble:
    """One ensemble of the sets of ``parts`` (ensembles of the same seeds from ensemble_from_runs, in order): the
    per-event fields of set 0 from the first part."""
    if len(parts) == 1:
        return parts[0]
    first = parts[0]
    return Ensemble(np.concatenate([p.seed_means for p in parts], axis=0),
                    np.concatenate([p.n_events for p in parts], axis=0), first.per_event, first.raw_records,
                    first.per_event_entries, [b for p in parts for b in p.seed_bands],
                    np.concatenate([p.seed_dc for p in parts], axis=0), first.per_event_dc)
