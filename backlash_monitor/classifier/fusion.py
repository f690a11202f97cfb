"""Fusion of the consecutive onset events of one drive into one width estimate (no rclpy).

A clutch's backlash changes over hours, a single window's gap-traversal time varies by ~1 ms from
event to event (the disturbances act on the load moment), so the classifier fuses the last N onset
events of a drive.

Rule (``sum_normalised_b``, the default): each event's B vector is divided by its own mean (so paper-
mode B, whose scale depends on l2 and epochs, and shape-mode B, squared Mahalanobis distances, fuse the
same way and no single event dominates through its scale), the normalised vectors of the last
``window_events`` onset events are summed, and the fused width is the candidate with the smallest sum.
``vote`` is the alternative (majority of the per-event argmins, ties broken by the normalised sum).

Rule ``trimmed_normalised_b`` (the default of the ``shape`` mode, ``default_fusion_rule``): the same
normalised vectors, but for each candidate width the largest and the smallest of the events' values are
left out of the sum (with 3 or more events; fewer: the plain sum). One outlier window (a feature that
caught the wrong kink, w_hat 2-5 mm off) then cannot move the fused width, whichever side it lies on.
The paper modes keep ``sum_normalised_b``. All rules are measured in docs/classifier.md.

Fused continuous width: the fused width above is one of the candidate widths (a drive at 6 mm reads
5 or 7.5 mm, and its wear shows only as a jump between them). Where the mode gives a continuous
width per window (``shape``), the median of the last ``window_events`` onset windows' continuous
widths is fused beside it: one outlier window cannot move it (as the trimmed rule above), and the
window-to-window scatter (~0.1-0.2 mm: the gap-traversal time varies from event to event) falls by
about the square root of the number of events (docs/classifier.md "Fused continuous width").

Its uncertainty (``continuous_width_se_m``): the robust standard error of that median over the same
fused events, sqrt(pi/2) * sigma / sqrt(n) with sigma = 1.4826 * MAD * b_n (b_n: the MAD's small-sample
correction, Croux & Rousseeuw 1992); the events are the independent units. NaN with fewer than 3 finite
continuous widths (docs/classifier.md section 5.2). +inf when the median lies at the top of the continuous range
(shape.continuous_top_m): the windows were clipped there, so their spread (often 0) is the clip's, not the
drive's, and the width is only known to be at least that top (a censored value; ``fused_width_uncertainty_m``).
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from .shape import continuous_top_m

FUSION_RULES = ("sum_normalised_b", "vote", "trimmed_normalised_b")
DEFAULT_WINDOW_EVENTS = 8
SHAPE_FUSION_RULE = "trimmed_normalised_b"
PAPER_FUSION_RULE = "sum_normalised_b"


def default_fusion_rule(mode: str) -> str:
    """The documented fusion rule of a classifier mode: trimmed sum for ``shape``, plain sum otherwise."""
    return SHAPE_FUSION_RULE if mode == "shape" else PAPER_FUSION_RULE


def normalise_b(b) -> np.ndarray:
    """B divided by its mean (all-zero B stays zero). Taken as (B / max) / mean(B / max): the same
    value, without the mean overflowing for entries near the float64 limit (1e308: the sum is inf,
    and B / inf would read as a perfect match on every candidate)."""
    b = np.asarray(b, dtype=float)
    top = b.max(axis=-1, keepdims=True)
    scaled = np.divide(b, top, out=np.zeros_like(b), where=top > 0)
    m = scaled.mean(axis=-1, keepdims=True)
    return np.divide(scaled, m, out=np.zeros_like(b), where=m > 0)


def fuse_b_vectors(bs, rule: str = "sum_normalised_b") -> tuple[int, np.ndarray]:
    """Fuse B vectors (n_events, n_widths) -> (index, summed normalised B; smaller is better)."""
    if rule not in FUSION_RULES:
        raise ValueError(f"unknown fusion rule {rule!r}; allowed: {', '.join(FUSION_RULES)}")
    bs = np.atleast_2d(np.asarray(bs, dtype=float))
    if bs.shape[0] == 0:
        raise ValueError("no events to fuse")
    return _fuse_normalised(bs, normalise_b(bs), rule)


def _fuse_normalised(bs: np.ndarray, nb: np.ndarray, rule: str) -> tuple[int, np.ndarray]:
    """fuse_b_vectors of the events ``bs`` (n_events, n_widths) whose normalised vectors ``nb``
    are at hand."""
    if rule == "trimmed_normalised_b" and nb.shape[0] >= 3:
        score = np.sort(nb, axis=0)[1:-1].sum(axis=0)
    else:
        score = nb.sum(axis=0)
    if rule == "vote":
        votes = np.bincount(np.argmin(bs, axis=1), minlength=bs.shape[1]).astype(float)
        best = np.flatnonzero(votes == votes.max())
        return int(best[np.argmin(score[best])]), score
    return int(np.argmin(score)), score


@dataclass
class FusedEstimate:
    index: int
    width_m: float
    events: int
    score: np.ndarray       # fused score per candidate width (smaller is better)
    continuous_width_m: float = float("nan")  # median of the events' continuous widths (NaN: none)
    continuous_width_se_m: float = float("nan")  # its robust standard error over the events (NaN: < 3; +inf:
                                                 # the median is at the range's top, a censored width)

    @cached_property
    def margin(self) -> float:
        """Second-smallest over smallest score (taken when asked: analyze writes every event's
        fused width, not its margin)."""
        s = np.sort(self.score)
        with np.errstate(over="ignore"):   # s[0] subnormal: the ratio is +inf, as for s[0] == 0
            return float(s[1] / s[0]) if s[0] > 0 else (1.0 if s[1] == s[0] else float("inf"))


class WidthFusion:
    """Keeps the B vectors of the last ``window_events`` onset events of one drive.

    >>> f = WidthFusion(widths_m, window_events=8)
    >>> est = f.add(b_vector)        # after each onset window's classification -> FusedEstimate
    ``reset()`` when the drive changes (e.g. a new bag, a different drive name). Return entries must
    not be added (classification uses onset entries); ``add`` takes ``kind`` and ignores non-onsets.
    """

    def __init__(self, widths_m, window_events: int = DEFAULT_WINDOW_EVENTS, rule: str = "sum_normalised_b"):
        if int(window_events) < 1:
            raise ValueError(f"window_events must be >= 1, got {window_events}")
        if rule not in FUSION_RULES:
            raise ValueError(f"unknown fusion rule {rule!r}; allowed: {', '.join(FUSION_RULES)}")
        self.widths_m = np.asarray(widths_m, dtype=float)
        self.top_m = continuous_top_m(self.widths_m)    # the continuous widths' clip (a censored fused width)
        self.window_events = int(window_events)
        self.rule = rule
        self._bs: deque = deque(maxlen=self.window_events)
        self._continuous: deque = deque(maxlen=self.window_events)   # per fused event; NaN: none
        self.rejected = 0       # B vectors not fused: non-finite or negative entries

    def reset(self) -> None:
        self._bs.clear()
        self._continuous.clear()

    def __len__(self) -> int:
        return len(self._bs)

    def add(self, b, kind: str = "onset", continuous_width_m: float = float("nan")) -> FusedEstimate | None:
        """Fuse one event's B vector (and its continuous width [m], NaN when the mode gives none)."""
        b = np.asarray(b, dtype=float)
        if b.shape != self.widths_m.shape:
            raise ValueError(f"B vector has {b.size} entries, expected {self.widths_m.size}")
        if not fusable(b[None])[0]:
            # a B vector of a bad window must not steer the fused width for the next N events
            self.rejected += 1
        elif kind == "onset":
            self._bs.append(b)
            c = float(continuous_width_m)
            self._continuous.append(c if math.isfinite(c) else math.nan)
        return self.estimate()

    def add_many(self, bs, continuous_widths_m=None, kind: str = "onset") -> list[FusedEstimate | None]:
        """``add`` of each event's B vector in turn (and its continuous width [m]; None: NaN for
        all): the fused estimate after each, the same numbers as one by one. Each event's B vector
        is normalised once here, not again in each of the ``window_events`` fusions it takes part
        in (normalise_b works row by row: a row's values do not depend on the rows beside it;
        test_classifier_fusion.py checks the whole against ``add``, bit for bit). analyze's
        estimates come this way, a batch of windows at a time (estimation.py)."""
        n = len(bs)
        bs = [np.asarray(b, dtype=float) for b in bs]
        given = [math.nan] * n if continuous_widths_m is None else list(continuous_widths_m)
        if len(given) != n:
            raise ValueError(f"{n} B vectors, {len(given)} continuous widths")
        try:
            widths = [float(c) for c in given]
        except (TypeError, ValueError):
            widths = None
        if kind != "onset" or widths is None or any(b.shape != self.widths_m.shape for b in bs):
            # one by one: not fused, or add raises where it raises (after the events before it)
            return [self.add(b, kind=kind, continuous_width_m=c) for b, c in zip(bs, given)]
        if not n:
            return []
        new = np.stack(bs)
        good = fusable(new).tolist()
        widths = [c if math.isfinite(c) else math.nan for c in widths]
        held = len(self._bs)
        rows = np.concatenate((np.array(self._bs) if held else np.empty((0, self.widths_m.size)),
                               new[good]))
        normalised = normalise_b(rows)
        continuous = list(self._continuous) + [c for c, g in zip(widths, good) if g]
        out = []
        last = held - 1                     # the row of the latest fused event
        for accepted in good:
            if accepted:
                last += 1
            else:
                self.rejected += 1
            if last < 0:
                out.append(None)
                continue
            lo = max(0, last + 1 - self.window_events)
            out.append(self._fused(rows[lo:last + 1], normalised[lo:last + 1],
                                   continuous[lo:last + 1]))
        self._bs.extend(b for b, g in zip(bs, good) if g)
        self._continuous.extend(c for c, g in zip(widths, good) if g)
        return out

    def estimate(self) -> FusedEstimate | None:
        if not self._bs:
            return None
        bs = np.array(self._bs)
        return self._fused(bs, normalise_b(bs), self._continuous)

    def _fused(self, bs: np.ndarray, normalised: np.ndarray, continuous) -> FusedEstimate:
        """The estimate from the fused events' B vectors, their normalised vectors and their
        continuous widths."""
        idx, score = _fuse_normalised(bs, normalised, self.rule)
        return FusedEstimate(index=idx, width_m=float(self.widths_m[idx]), events=len(bs),
                             score=score, continuous_width_m=fused_continuous_width(continuous),
                             continuous_width_se_m=fused_width_uncertainty_m(continuous, self.top_m))


def fusable(bs: np.ndarray) -> np.ndarray:
    """Per row of ``bs`` (n_events, n_widths): whether WidthFusion takes that event's B vector (every entry
    finite and >= 0; another is a bad window's and counted as rejected)."""
    return np.isfinite(bs).all(axis=1) & (bs >= 0).all(axis=1)


def fused_continuous_width(continuous_m) -> float:
    """Median [m] of the finite continuous widths of the fused events; NaN when there is none."""
    # np.median's value (the middle one, or the mean of the two middle ones), without its
    # overhead: it is taken once per estimate of a few dozen events
    c = sorted(x for x in map(float, continuous_m) if math.isfinite(x))
    n = len(c)
    if not n:
        return math.nan
    return c[n // 2] if n % 2 else (c[n // 2 - 1] + c[n // 2]) / 2


# The MAD's small-sample consistency factor b_n for a normal sample of n (Croux & Rousseeuw 1992, table;
# n/(n - 0.8) beyond it): 1.4826 * MAD * b_n estimates sigma without bias for small n.
_MAD_SMALL_SAMPLE = {3: 1.495, 4: 1.363, 5: 1.206, 6: 1.200, 7: 1.140, 8: 1.129, 9: 1.107}
MIN_EVENTS_FOR_SE = 3


def median_standard_error(values) -> float:
    """Robust standard error [same unit] of the median of the finite ``values`` (one per event, the
    independent units): sqrt(pi/2) * sigma / sqrt(n), sigma = 1.4826 * MAD * b_n. The asymptotic
    efficiency of the median of a normal sample (pi/2) is used for every n. NaN with fewer than
    MIN_EVENTS_FOR_SE finite values (no spread to read)."""
    # plain Python, as fused_continuous_width: taken once per estimate of a few dozen events
    c = [x for x in map(float, values) if math.isfinite(x)]
    n = len(c)
    if n < MIN_EVENTS_FOR_SE:
        return math.nan
    middle = fused_continuous_width(c)
    mad = fused_continuous_width([abs(x - middle) for x in c])
    sigma = 1.4826 * mad * _MAD_SMALL_SAMPLE.get(n, n / (n - 0.8))
    return math.sqrt(math.pi / 2) * sigma / math.sqrt(n)


def fused_width_uncertainty_m(values, top_m: float = math.inf) -> float:
    """The uncertainty [m] of the fused continuous width of ``values`` (one per event): the median's robust standard
    error (median_standard_error), or +inf when that median is at ``top_m``, the top of the continuous range the
    windows are clipped to (shape.continuous_top_m): a censored width, known only to be >= top_m. Measured on a drive
    with rail joints outside the catalogue (outside_sealed5): every window read the 20 mm clip, the MAD was 0, and the
    monitor printed "20.00 ± 0.00 mm" on a 4.5 mm drive."""
    middle = fused_continuous_width(values)
    if math.isfinite(middle) and middle >= top_m * (1.0 - 1e-9):
        return math.inf
    return median_standard_error(values)


def fused_indices(b_sequence, window_events: int = DEFAULT_WINDOW_EVENTS, rule: str = "sum_normalised_b",
                  full_only: bool = True) -> np.ndarray:
    """Offline: fused index after each event of one drive's ordered B sequence (n_events, n_widths).

    With ``full_only`` the first window_events-1 events (a not yet full buffer) are left out.
    """
    bs = np.atleast_2d(np.asarray(b_sequence, dtype=float))
    out = []
    start = window_events - 1 if full_only else 0
    for k in range(min(start, len(bs) - 1) if len(bs) else 0, len(bs)):
        lo = max(0, k + 1 - window_events)
        out.append(fuse_b_vectors(bs[lo:k + 1], rule)[0])
    return np.array(out, dtype=int)
