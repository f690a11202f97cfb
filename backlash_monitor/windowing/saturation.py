"""Sensor saturation (a signal at its rail) and a stuck sensor, found from the data alone.

A clipped sensor reports exactly its rail value whenever the true signal lies beyond it: the rail is
the signal's extreme value, it comes in runs of identical samples, and it holds far more samples than
the thin band of values just inside it (the signal would have gone on, so it crosses that band fast).
A clean signal's extreme is one sample (noise), or -- behind an undithered ADC -- one quantisation
level that a slow peak sits on for a while; but then the levels just below it hold as many samples
as it does. So an extreme value is a **rail** when (config/windowing.yaml ``saturation``, docs/windowing.md
"Input faults"):

- it comes in runs of at least ``rail_min_run_samples`` identical samples, and
- it holds at least ``rail_overpopulation_ratio`` times the samples of the band just inside it, of
  width max(``rail_band_fraction`` * |extreme - median|, ``rail_band_quanta`` * the signal's
  quantisation step near the extreme) -- the step read from the occupied values there (``_step_at``), since a
  codec whose step grows with |x| (float16, a block floating-point codec, a mu-law ADC) is coarse at the top
  though fine elsewhere.

Behind a **coarse ADC** -- where the band just inside is set by its steps (``rail_band_quanta`` steps wider than
``rail_band_fraction`` of the excursion) -- one excursion held on the top level cannot be told from a clip that
removed a few steps (a high-g accelerometer behind 12 bits: 1 m/s^2 steps on a 124 m/s^2 impact): there the
extreme is a rail only when two runs or more reach it (a clip is hit by every excursion beyond it).

A **stuck** sensor repeats one value for ``stuck_min_run_samples`` samples or more, not at a rail (a
dead sensor, a broken wire, a frozen driver): a signal of one value throughout is stuck, not saturated.
A quantised signal's **quiet stretch** is not: behind a coarse ADC (10-12 bits over +-4 g) a2 between the
load events moves less than one step and sits on one level for tens of ms. Such a run is entered and left
by a change of at most ``stuck_quiet_steps`` quantisation steps (the signal drifts to the next level),
and it is no longer than ``stuck_quiet_max_run_samples``; a dead sensor's hold ends where the signal has
gone meanwhile (a load event moves a2 by many steps), or runs on past any quiet stretch.

``assess_signal(x, name)`` -> :class:`SignalSaturation` (one array: a window, a recording);
``assess(signals)`` for several; :class:`SaturationCounter` counts a stream in blocks of
``block_samples`` (the live node and ``analyze`` count a recording alike). Plain numpy, no rclpy.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Mapping, Sequence

import numpy as np

__all__ = ["SaturationSettings", "SignalSaturation", "assess_signal", "assess", "SaturationCounter",
           "sensor_of", "unit_of"]


@dataclass(frozen=True)
class SaturationSettings:
    """The thresholds (config/windowing.yaml ``saturation`` has each one's unit and reason)."""
    rail_min_run_samples: int = 3
    rail_band_fraction: float = 0.0025
    rail_band_quanta: int = 4
    rail_overpopulation_ratio: float = 3.0
    stuck_min_run_samples: int = 1000
    stuck_quiet_steps: int = 1
    stuck_quiet_max_run_samples: int = 9500
    local_step_levels: int = 8
    local_step_tolerance: float = 0.1
    rail_noise_band_sd: float = 2.0
    rail_noise_shape_z: float = 4.0
    rail_noise_event_gap_samples: int = 2048
    rail_noise_min_visit_samples: int = 8
    block_samples: int = 50_000

    def __post_init__(self):
        for name, lo, hi, integer in (("rail_min_run_samples", 2, 10_000, True),
                                      ("rail_band_fraction", 1e-6, 0.5, False),
                                      ("rail_band_quanta", 1, 10_000, True),
                                      ("rail_overpopulation_ratio", 1.0, 1e6, False),
                                      ("stuck_min_run_samples", 2, 10_000_000, True),
                                      ("stuck_quiet_steps", 0, 1000, True),
                                      ("stuck_quiet_max_run_samples", 0, 100_000_000, True),
                                      ("local_step_levels", 2, 1000, True),
                                      ("local_step_tolerance", 0.0, 0.49, False),
                                      ("rail_noise_band_sd", 0.0, 100.0, False),
                                      ("rail_noise_shape_z", 0.0, 1e6, False),
                                      ("rail_noise_event_gap_samples", 0, 10_000_000, True),
                                      ("rail_noise_min_visit_samples", 2, 10_000_000, True),
                                      ("block_samples", 2, 100_000_000, True)):
            value = getattr(self, name)
            ok = (not isinstance(value, bool) and isinstance(value, (int, float)) and math.isfinite(value)
                  and lo <= value <= hi and (not integer or float(value).is_integer()))
            if not ok:
                raise ValueError(f"saturation.{name} = {value!r}; allowed: "
                                 f"{'an integer' if integer else 'a number'} in [{lo:g}, {hi:g}]")

    @classmethod
    def from_config(cls, section: Mapping | None) -> "SaturationSettings":
        """From ``load_windowing_config()["saturation"]`` (unknown keys are the loader's error)."""
        known = {f.name for f in fields(cls)}
        return cls(**{k: v for k, v in (section or {}).items() if k in known})


def sensor_of(signal: str) -> str:
    """The sensor behind a signal, as a user names it."""
    if signal.startswith("a"):
        return "accelerometer"
    if signal.startswith("omega"):
        return "speed sensor"
    if "angle" in signal or signal.startswith("alpha"):
        return "encoder"
    return "sensor"


def unit_of(signal: str) -> str:
    if signal.startswith("a") and not signal.startswith("angle") and not signal.startswith("alpha"):
        return "m/s²"
    if signal.startswith("omega"):
        return "rad/s"
    if "angle" in signal or signal.startswith("alpha"):
        return "rad"
    return ""


def _share_text(count: int, samples: int) -> str:
    """'4.1 % of samples'; a share that one decimal would print as 0.0 % as the count ('12 of 200000 samples'): a
    fault found is never said to be in 0.0 % of the samples."""
    share = 100.0 * count / samples if samples else 0.0
    return f"{share:.1f} % of samples" if share >= 0.05 else f"{count} of {samples} samples"


@dataclass(frozen=True)
class SignalSaturation:
    """One signal's count: ``samples`` looked at, ``at_rail`` of them at a rail (in ``runs`` runs of
    at least ``rail_min_run_samples``), the rails (None: none), ``stuck`` samples in runs of one
    value of at least ``stuck_min_run_samples`` (the longest at ``stuck_value``)."""
    signal: str
    samples: int = 0
    at_rail: int = 0
    runs: int = 0
    upper_rail: float | None = None
    lower_rail: float | None = None
    stuck: int = 0
    stuck_value: float | None = None
    rail_band: float = 0.0       # a rail with noise on it: samples within this of it are at it (0: the value itself)

    @property
    def rail_fraction(self) -> float:
        return self.at_rail / self.samples if self.samples else 0.0

    @property
    def stuck_fraction(self) -> float:
        return self.stuck / self.samples if self.samples else 0.0

    @property
    def faulty(self) -> bool:
        return bool(self.at_rail or self.stuck)

    def rails_text(self) -> str:
        unit = unit_of(self.signal)
        up, lo = self.upper_rail, self.lower_rail
        if up is not None and lo is not None and math.isclose(abs(up), abs(lo), rel_tol=0.01):
            text = f"±{abs(up):.3g}"
        else:
            text = " and ".join(f"{v:+.3g}" for v in (up, lo) if v is not None)
        return f"{text} {unit}".strip()

    def message(self) -> str:
        """One line per fault ('' when clean): the rail first, then a stuck stretch."""
        parts = []
        if self.at_rail:
            parts.append(f"{self.signal} at its rail ({self.rails_text()}) in {_share_text(self.at_rail, self.samples)}: "
                         f"the {sensor_of(self.signal)}'s range is too small")
        if self.stuck:
            value = "" if self.stuck_value is None else f" at {self.stuck_value:.4g} {unit_of(self.signal)}".rstrip()
            parts.append(f"{self.signal} stuck{value} in {_share_text(self.stuck, self.samples)} (one value "
                         f"repeated): a dead {sensor_of(self.signal)} or a broken wire")
        return "; ".join(parts)

    def merged(self, other: "SignalSaturation") -> "SignalSaturation":
        """This count and ``other``'s (another stretch of the same signal) together."""
        def extreme(a, b, pick):
            return b if a is None else a if b is None else pick(a, b)
        return replace(self, samples=self.samples + other.samples, at_rail=self.at_rail + other.at_rail,
                       runs=self.runs + other.runs,
                       upper_rail=extreme(self.upper_rail, other.upper_rail, max),
                       lower_rail=extreme(self.lower_rail, other.lower_rail, min),
                       stuck=self.stuck + other.stuck,
                       stuck_value=self.stuck_value if other.stuck <= self.stuck else other.stuck_value,
                       rail_band=max(self.rail_band, other.rail_band))

    def as_dict(self) -> dict:
        """For JSON: counts, shares [%] and the rails [the signal's unit]."""
        return {"samples": self.samples, "at_rail": self.at_rail, "rail_percent": round(100 * self.rail_fraction, 3),
                "upper_rail": self.upper_rail, "lower_rail": self.lower_rail, "stuck": self.stuck,
                "stuck_percent": round(100 * self.stuck_fraction, 3), "stuck_value": self.stuck_value,
                "message": self.message()}


def _runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Starts and lengths of the runs of True in a boolean array."""
    edges = np.diff(np.concatenate(([0], mask.view(np.int8), [0])))
    starts = np.flatnonzero(edges == 1)
    return starts, np.flatnonzero(edges == -1) - starts


def _rail(x: np.ndarray, side: int, median: float, step: float, runs: tuple,
          s: SaturationSettings, quantised: bool, levels) -> tuple[float | None, int, int, np.ndarray]:
    """The rail on one side (+1 upper, -1 lower): (value or None, samples in runs, runs, mask of them).
    ``step``: the signal's quantisation step (its smallest change between two samples; ~0 unquantised);
    ``runs``: (starts, lengths) of its runs of one value; ``quantised``: _quantised's answer for the signal;
    ``levels()``: the signal's distinct values, sorted, and their runs' counts."""
    value = float(x.max() if side > 0 else x.min())
    starts, lengths = runs
    on = np.flatnonzero(x[starts] == value)          # the runs at the extreme
    # a run counts when it is rail_min_run_samples times as long as the runs next to it: a sensor whose
    # output the recorder holds for several samples (a slower output rate) holds its top as long as
    # any other value, and a clipped signal arrives at and leaves its rail in short runs
    before = lengths[np.maximum(on - 1, 0)]
    after = lengths[np.minimum(on + 1, lengths.size - 1)]
    hold = np.maximum(1, np.minimum(before, after))
    good = on[lengths[on] >= s.rail_min_run_samples * hold]
    if not good.size:
        return None, 0, 0, x[:0].astype(bool)
    # the step near this extreme: a codec whose step grows with |x| is coarse here though fine elsewhere
    values = levels()
    near = _step_at(values, values[0].size - 1 if side > 0 else 0, s)
    if near > step:
        step, quantised = near, True
    # behind a coarse ADC (the band set by its steps) one excursion held on the top level is no rail
    coarse = quantised and s.rail_band_quanta * step > s.rail_band_fraction * abs(value - median)
    if coarse and good.size < 2:
        return None, 0, 0, x[:0].astype(bool)
    band = max(s.rail_band_fraction * abs(value - median), s.rail_band_quanta * step)
    inner = side * (value - x)                       # >= 0: how far inside the extreme
    n_band = int(np.count_nonzero((inner > 0) & (inner <= band)))
    if band <= 0 or int(np.count_nonzero(inner == 0)) < s.rail_overpopulation_ratio * n_band:
        return None, 0, 0, x[:0].astype(bool)
    mask = np.zeros(x.size, dtype=bool)
    for start, length in zip(starts[good], lengths[good]):
        mask[start:start + length] = True
    return value, int(lengths[good].sum()), int(good.size), mask


def _step_at(levels: tuple[np.ndarray, np.ndarray], index: int, s: SaturationSettings) -> float:
    """The quantisation step at the occupied value ``levels[0][index]``, 0 when the values there are not on one.
    ``levels``: a signal's distinct values, sorted, and how many runs of one value each has.

    The gaps between the ``local_step_levels`` + 1 occupied values around it (at an extreme, the ones inside it)
    are whole multiples of the smallest, to within ``local_step_tolerance`` of it (a companding ADC's levels widen
    slowly with |x|); and either exactly so (a uniform quantiser: an ADC, a block floating-point codec, float16
    within a power of two) or the signal comes back to one of those values in another run (a quantiser's level is
    met again; an unquantised signal never repeats a value, and a smooth ramp's samples, nearly evenly spaced,
    are met once each). A codec whose step grows with |x| -- float16 storage, a block floating-point codec, a
    mu-law or A-law ADC -- is coarse at an impact's top though the signal's smallest change, far from it, is
    fine."""
    values, run_counts = levels
    k = s.local_step_levels + 1
    lo = max(0, min(index - k // 2, values.size - k))
    gaps = np.diff(values[lo:lo + k])
    if gaps.size < 2 or gaps.min() <= 0:
        return 0.0
    ratio = gaps / gaps.min()
    off = np.abs(ratio - np.rint(ratio))
    if not np.all(off <= s.local_step_tolerance * np.rint(ratio)):
        return 0.0
    exact = bool(np.all(off <= 1e-6 * np.rint(ratio)))
    met_again = bool(np.any(np.delete(run_counts[lo:lo + k], index - lo) >= 2)) if lo <= index < lo + k else False
    return float(gaps.min()) if exact or met_again else 0.0


def _quantised(x: np.ndarray, diff: np.ndarray, step: float) -> bool:
    """Every change between two samples a whole number of ``step`` (an ADC's output, maybe scaled and offset),
    to within the values' own representation (float32 holds 2^-24 of |x|: a float32 recording of an ADC's levels
    is still quantised). An unquantised signal's smallest change is far below that: not quantised."""
    changes = diff[diff > 0]
    if step <= 0 or not changes.size:
        return False
    representation = 2.0 ** -22 * float(np.max(np.abs(x))) / step     # in steps: a few float32 ulps of |x|
    if representation > 0.05:
        return False
    ratio = changes / step
    return bool(np.all(np.abs(ratio - np.rint(ratio)) <= 1e-6 * np.maximum(ratio, 1.0) + 2 * representation))


def _quiet_quantised_runs(x, step, starts, lengths, candidates, s: SaturationSettings, quantised: bool,
                          levels) -> np.ndarray:
    """The candidate runs that are a quantised signal's quiet stretch, not a hold: entered and left by at most
    ``stuck_quiet_steps`` steps (a border the stretch does not have -- the block's first or last sample --
    does not count against it) and no longer than ``stuck_quiet_max_run_samples``. ``quantised``: _quantised's
    answer for the signal, whose steps are ``step``; where it is not on one step (a codec whose step grows with
    |x|), the step at the run's value (_step_at; none is quiet where the values are on no step). ``levels()``: the
    signal's distinct values, sorted, and their runs' counts."""
    if s.stuck_quiet_steps < 1 or not candidates.size:
        return candidates[:0]
    begin, end = starts[candidates], starts[candidates] + lengths[candidates]
    here = np.full(candidates.size, step if quantised else 0.0)
    values = levels()
    for j, b in enumerate(begin):
        here[j] = max(here[j], _step_at(values, int(np.searchsorted(values[0], x[b])), s))
    limit = (s.stuck_quiet_steps + 0.5) * here          # whole steps: half a step apart
    entered = np.where(begin > 0, np.abs(x[begin] - x[np.maximum(begin - 1, 0)]), 0.0)
    left = np.where(end < x.size, np.abs(x[np.minimum(end, x.size - 1)] - x[end - 1]), 0.0)
    quiet = ((here > 0) & (entered <= limit) & (left <= limit)
             & (lengths[candidates] <= s.stuck_quiet_max_run_samples))
    return candidates[quiet]


def _noise_sd(diff: np.ndarray) -> float:
    """The signal's noise [its unit], from its sample-to-sample changes (robust: their median, the quiet stretches';
    a recorder's held samples, no change, left out): 0 where it does not change."""
    changes = diff[diff > 0]
    return float(np.median(changes)) * 1.4826 / math.sqrt(2.0) if changes.size else 0.0


def _flat(y: np.ndarray, starts: np.ndarray, lengths: np.ndarray, sigma: float, z_max: float,
          min_samples: int) -> bool:
    """One visit to a level, its runs near it (``starts``, ``lengths``): from its first sample near the level to its
    last (at least ``min_samples``), a line and a parabola fitted; flat when neither the slope nor the curvature is
    ``z_max`` standard errors (of white noise ``sigma``) from 0."""
    first, last = int(starts[0]), int(starts[-1] + lengths[-1])
    n = last - first
    if n < min_samples:       # too short to show a slope: a ramp of 1 sd a sample is 4 standard errors in 6 samples
        return False
    t = (np.arange(n) - (n - 1) / 2.0) / n
    design = np.stack([np.ones(n), t, t * t - np.mean(t * t)], axis=1)
    gram_inv = np.linalg.inv(design.T @ design)
    coef = gram_inv @ (design.T @ y[first:last])
    z = np.abs(coef[1:]) / (sigma * np.sqrt(np.diag(gram_inv)[1:]))
    return bool(np.all(z <= z_max))


def _noisy_rail(x: np.ndarray, side: int, median: float, sigma: float,
                s: SaturationSettings) -> tuple[float | None, int, int, np.ndarray]:
    """A rail with noise on it (+1 upper, -1 lower): a sensor that saturates in its analog stage, read with noise
    ``sigma`` after it, holds a level +-noise, not one value. Its level: the median of the samples within
    ``rail_noise_band_sd`` * 4 noise sd of the extreme. It is a rail when runs of at least ``rail_min_run_samples``
    within ``rail_noise_band_sd`` sd of that level come two times or more (a clip is hit by every excursion beyond
    it), and they hold ``rail_overpopulation_ratio`` times the samples of the band just inside them (as wide as
    they: the clip's signal crosses it fast; a peak's rounded top spends about as long in each). (value or None,
    samples in the runs, runs, mask of them.)"""
    none = (None, 0, 0, x[:0].astype(bool))
    if sigma <= 0:
        return none
    y = side * x
    k = s.rail_noise_band_sd
    top = float(y.max())
    level = float(np.median(y[y >= top - 4 * k * sigma]))
    near = y >= level - k * sigma
    starts, lengths = _runs(near)
    good = lengths >= s.rail_min_run_samples
    band = max(2 * k * sigma, s.rail_band_fraction * abs(level - side * median))
    # the excursions that reach the level: stretches above the band's lower edge (noise splits one visit to the level
    # into several runs near it; the band holds them together)
    ex_starts, _ = _runs(y >= level - k * sigma - band)
    owner = np.searchsorted(ex_starts, starts[good], side="right") - 1
    # each visit flat (a clipped level is constant under its noise; a peak's top near it is curved or sloped), and
    # every visit at one level: a rail is one value for all of them (tops of the drive's own that happen to come near
    # each other differ by more than their noise)
    visits = [(starts[good][owner == e], lengths[good][owner == e]) for e in np.unique(owner)]
    flat = [e for e, (st, ln) in zip(np.unique(owner), visits)
            if _flat(y, st, ln, sigma, s.rail_noise_shape_z, s.rail_noise_min_visit_samples)]
    # two events at least (a clip is hit by every one beyond it): visits further apart than rail_noise_event_gap
    if len(flat) < 2 or np.count_nonzero(np.diff(ex_starts[flat]) > s.rail_noise_event_gap_samples) < 1:
        return none
    spans = [y[int(st[0]):int(st[-1] + ln[-1])] for e, (st, ln) in zip(np.unique(owner), visits) if e in flat]
    means = np.array([v.mean() for v in spans])
    counts = np.array([v.size for v in spans], dtype=float)
    centre = float(np.sum(counts * means) / counts.sum())
    chi2 = float(np.sum(counts * (means - centre) ** 2)) / sigma ** 2
    dof = len(spans) - 1
    if (chi2 - dof) / math.sqrt(2.0 * dof) > s.rail_noise_shape_z:
        return none
    good &= np.isin(np.searchsorted(ex_starts, starts, side="right") - 1, flat)
    n_in = int(lengths[good].sum())
    n_band = int(np.count_nonzero((y < level - k * sigma) & (y >= level - k * sigma - band)))
    if n_in < s.rail_overpopulation_ratio * max(n_band, s.rail_min_run_samples):
        return none
    mask = np.zeros(x.size, dtype=bool)
    for start, length in zip(starts[good], lengths[good]):
        mask[start:start + length] = True
    return side * level, n_in, int(good.sum()), mask


def assess_signal(x, name: str, settings: SaturationSettings | None = None) -> SignalSaturation:
    """Saturated and stuck samples of one signal's stretch (non-finite samples are not looked at)."""
    s = settings or SaturationSettings()
    x = np.asarray(x, dtype=float).ravel()
    if not math.isfinite(np.add.reduce(x)):
        x = x[np.isfinite(x)]
    if x.size == 0:
        return SignalSaturation(name)
    diff = np.abs(np.diff(x))
    change = np.flatnonzero(diff) + 1
    if not change.size:                              # one value throughout: stuck (dead), no rail
        stuck = x.size if x.size >= s.stuck_min_run_samples else 0
        return SignalSaturation(name, int(x.size), stuck=stuck, stuck_value=float(x[0]) if stuck else None)
    starts = np.concatenate(([0], change))          # runs of one value
    lengths = np.diff(np.concatenate((starts, [x.size])))
    median = float(np.median(x))
    none = (None, 0, 0, x[:0].astype(bool))
    up, n_up, runs_up, mask_up = lo, n_lo, runs_lo, mask_lo = none
    step, q = 0.0, False
    if lengths.max() >= min(s.rail_min_run_samples, s.stuck_min_run_samples):   # runs of one value: a rail, a hold
        step = float(diff[change - 1].min())        # the smallest change: an ADC's step, ~0 unquantised
        q = _quantised(x, diff, step)
        cache = []

        def levels() -> tuple[np.ndarray, np.ndarray]:   # the distinct values, sorted, and their runs: when asked
            if not cache:
                cache.append(np.unique(x[starts], return_counts=True))
            return cache[0]
        up, n_up, runs_up, mask_up = _rail(x, +1, median, step, (starts, lengths), s, q, levels)
        lo, n_lo, runs_lo, mask_lo = _rail(x, -1, median, step, (starts, lengths), s, q, levels)
    else:
        def levels() -> tuple[np.ndarray, np.ndarray]:
            return np.unique(x[starts], return_counts=True)
    # a rail with noise on it, where no value repeats at that extreme
    band = 0.0
    if s.rail_noise_band_sd > 0 and (up is None or lo is None):
        sigma = _noise_sd(diff)
        if up is None:
            up, n_up, runs_up, mask_up = _noisy_rail(x, +1, median, sigma, s)
            band = s.rail_noise_band_sd * sigma if up is not None else band
        if lo is None:
            lo, n_lo, runs_lo, mask_lo = _noisy_rail(x, -1, median, sigma, s)
            band = s.rail_noise_band_sd * sigma if lo is not None else band
    railed = np.zeros(x.size, dtype=bool)
    for mask in (mask_up, mask_lo):
        if mask.size:
            railed |= mask
    # stuck: runs of one value (not at a rail) at least stuck_min_run_samples long, but a quantised signal's
    # quiet stretch
    long_ = (lengths >= s.stuck_min_run_samples) & ~railed[starts]
    if long_.any():
        long_[_quiet_quantised_runs(x, step, starts, lengths, np.flatnonzero(long_), s, q, levels)] = False
    stuck = int(lengths[long_].sum())
    stuck_value = float(x[starts[long_][np.argmax(lengths[long_])]]) if stuck else None
    return SignalSaturation(name, int(x.size), n_up + n_lo, runs_up + runs_lo, up, lo, stuck, stuck_value, band)


def assess(signals: Mapping[str, np.ndarray], settings: SaturationSettings | None = None) -> dict[str, SignalSaturation]:
    """``assess_signal`` for each signal: {name: SignalSaturation}."""
    return {name: assess_signal(x, name, settings) for name, x in signals.items()}


class SaturationCounter:
    """Counts a recording's (a stream's) saturated and stuck samples in blocks of ``block_samples``.

    ``feed({name: chunk})`` (the chunks of one sample range, equal lengths), ``flush()`` at the end (the
    last, shorter block); ``totals()`` -> {name: SignalSaturation}; ``faulty_blocks``; ``last`` (the
    latest block's counts). A gap in the stream needs nothing: blocks are stretches of samples.
    """

    def __init__(self, signals: Sequence[str], settings: SaturationSettings | None = None):
        self.settings = settings or SaturationSettings()
        self._stuck_only = replace(self.settings, rail_noise_band_sd=0.0)
        self.signals = tuple(signals)
        self._parts: dict[str, list[np.ndarray]] = {s: [] for s in self.signals}
        self._held = 0
        self._totals = {s: SignalSaturation(s) for s in self.signals}
        self.blocks = 0
        self.faulty_blocks = 0
        self.last: dict[str, SignalSaturation] = {}

    def feed(self, signals: Mapping[str, np.ndarray]) -> dict[str, SignalSaturation] | None:
        """Adds one range; returns the counts of the block it completed (None: none)."""
        n = min(len(signals[s]) for s in self.signals)
        done = None
        offset = 0
        while offset < n:
            take = min(n - offset, self.settings.block_samples - self._held)
            for s in self.signals:
                self._parts[s].append(np.asarray(signals[s][offset:offset + take], dtype=float))
            self._held += take
            offset += take
            if self._held >= self.settings.block_samples:
                done = self._assess_block()
        return done

    def flush(self) -> dict[str, SignalSaturation] | None:
        return self._assess_block() if self._held else None

    def _assess_block(self) -> dict[str, SignalSaturation]:
        block = {s: np.concatenate(self._parts[s]) for s in self.signals}
        self._parts = {s: [] for s in self.signals}
        self._held = 0
        result = assess(block, self.settings)
        for s, r in result.items():
            self._totals[s] = self._totals[s].merged(r)
        self.blocks += 1
        self.faulty_blocks += any(r.faulty for r in result.values())
        self.last = result
        return result

    def rails(self) -> dict[str, tuple[float | None, float | None]]:
        """The rails found so far: {name: (upper or None, lower or None)}."""
        return {s: (r.upper_rail, r.lower_rail) for s, r in self._totals.items()}

    def check_window(self, signals: Mapping[str, np.ndarray]) -> dict[str, SignalSaturation]:
        """A window's analysed stretch against the rails found so far (the stream's, not the window's
        own extremes: 2048 samples hold too few peaks to tell a rail from a held or quantised top):
        its samples at a rail in runs of ``rail_min_run_samples``, and its stuck samples."""
        out = {}
        for name in self.signals:
            x = np.asarray(signals[name], dtype=float).ravel()
            up, lo = self.rails().get(name, (None, None))
            band = self._totals[name].rail_band if name in self._totals else 0.0
            at, runs = 0, 0
            for rail in (up, lo):
                if rail is not None:
                    _, lengths = _runs(np.abs(x - rail) <= band)
                    long_ = lengths >= self.settings.rail_min_run_samples
                    at += int(lengths[long_].sum())
                    runs += int(long_.sum())
            own = assess_signal(x, name, self._stuck_only)     # its stuck samples (its rails: the stream's)
            out[name] = SignalSaturation(name, int(x.size), at, runs, up if at else None, lo if at else None,
                                         own.stuck, own.stuck_value, band)
        return out

    def totals(self) -> dict[str, SignalSaturation]:
        return dict(self._totals)

    def messages(self) -> list[str]:
        return [m for m in (r.message() for r in self._totals.values()) if m]
