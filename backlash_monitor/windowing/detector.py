"""Streaming backlash-entry detection (paper eq. 1-3 and the contact-loss trigger).

See the package docstring (``backlash_monitor.windowing``) and docs/windowing.md for the physics
and the decisions.  Everything here is vectorised per chunk: the per-sample state machine only
steps from event to event (8 entries per second), each step is a numpy search over a block.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping

import numpy as np

from .filters import first_excursion, window_range
from .config import ANGLE_SOURCES, DEFAULTS, INTEGRATION_RULES, KIND_ONSET, KIND_RETURN, TRIGGERS, load_windowing_config

__all__ = ["BacklashEntry", "BacklashEntryDetector", "fit_departure", "integrate_relative_speed"]

_BLOCK = 4096          # samples searched per step of the state machine
_FIRST_SETTLE_BLOCK = 1     # first block of the settle search (then 256, x4 up to _BLOCK): same result
_FIRST_APEX_BLOCK = 2048    # first block of the end-of-traverse search (then _BLOCK): same result
_UNARMED, _ARMED, _TRAVERSE = 0, 1, 2
_DRIFT_BASELINE_S = 10.0   # s between the offsets that give the drift rate of integrated angles
_APEX_LAG = 50          # samples (1 ms): lag of the speed sign test that finds the end of a traverse
_LEVEL_SAMPLES = 200    # samples (4 ms) before the fitted departure that give the contact level


@dataclass(frozen=True)
class BacklashEntry:
    """One detected entry into the backlash zone.

    sample_index: absolute index of the entry (the first sample of its window).
    kind: "onset" (delta leaves the + contact going down) or "return" (leaves the - contact going up).
    trigger: "contact_loss" or "paper".
    confirm_sample_index: sample at which the detector decided (>= sample_index; the difference is
        the back-dating of the contact-loss trigger, 0 for the paper trigger).
    """

    sample_index: int
    kind: str
    trigger: str
    confirm_sample_index: int


def integrate_relative_speed(w_rel: np.ndarray, dt: float, rule: str = "trapezoid",
                             delta0: float = 0.0, w_prev: float | None = None) -> np.ndarray:
    """Paper eq. 2-3 on the difference: delta[k] = delta[k-1] + dt*(w[k]+w[k-1])/2 (trapezoid) or
    dt*w[k] (rectangle, backward Euler).  ``delta0`` is the value at the sample before ``w_rel[0]``
    and ``w_prev`` the speed there; with ``w_prev=None`` the first sample is the start (delta = delta0).
    """
    w = np.asarray(w_rel, dtype=np.float64)
    if rule == "trapezoid":
        if w_prev is None:
            inc = np.concatenate(([0.0], 0.5 * dt * (w[1:] + w[:-1])))
        else:
            inc = 0.5 * dt * (w + np.concatenate(([w_prev], w[:-1])))
    elif rule == "rectangle":
        inc = dt * w
        if w_prev is None and len(inc):
            inc = inc.copy()
            inc[0] = 0.0
    else:
        raise ValueError(f"integration={rule!r}: allowed values are {INTEGRATION_RULES}")
    return delta0 + np.cumsum(inc)


def fit_departure(y: np.ndarray, direction: int, min_pre: int = 16, min_post: int = 16) -> int:
    """Change-point fit: 'ramp, then an added parabola' to ``y``; returns the departure index t0.

    Model: y[k] = L + v*k + a*max(0, k - t0)**2 with sign(a) = direction.  For every candidate t0
    the least-squares (L, v, a) is solved at once from closed-form power sums and reverse cumulative
    sums (O(N) set-up, a batched 3x3 solve).  This is the physics of a contact loss: the relative
    speed is continuous (the ramp lets the contact wander slowly under the noise torques before it),
    the relative acceleration steps by (load pulse)/(inertia) at t0.

    The candidates' arrays are held in reverse order (s = n - 1 - t: the order the reverse
    cumulative sums come in), so nothing is reversed or copied but the final argmax's view.
    """
    y = np.asarray(y, dtype=np.float64)
    n = y.size
    if n < min_pre + min_post + 3:
        return 0
    y = y - y[0]
    lo, hi = min_pre, n - min_post             # candidate departures t in [lo, hi)
    g = _departure_terms(n, lo, hi)
    k = g.k
    # sum over k >= t for the candidates, in s order: the running sums from the end, from s = n - hi
    # on.  y and y*k run as the real and imaginary parts of one complex sum (complex addition adds
    # the parts separately: the same sums, two at a time)
    m = n - lo
    both = np.empty(n, dtype=np.complex128)
    both.real = y
    yk = np.multiply(y, k, out=both.imag)
    ykk = yk * k
    a01 = both[::-1][:m].cumsum()
    # the two sums apart, each contiguous: the ten operations on them below run on contiguous
    # arrays (on the complex array's real and imaginary views they stride: ~2x the time)
    parts = a01.view(np.float64).reshape(m, 2)[min_post:].T
    a0 = parts[0].copy()
    a1 = parts[1].copy()
    a2 = ykk[::-1][:m].cumsum()[min_post:]
    # regressors 1, k (fixed) and q = (k - t)^2 for k >= t.  Project 1, k out (Frisch-Waugh):
    # r_qq = q'q - (X'q)' G^-1 X'q, r_yq = y'q - (X'q)' G^-1 X'y, a = r_yq / r_qq, SSE = SSE_lin - r_yq^2/r_qq
    xy = np.array([np.add.reduce(y), np.dot(k, y)])     # (y.sum() is np.add.reduce(y))
    gy = g.ginv @ xy
    a1 *= g.two_t
    a0 *= g.t_sq
    np.subtract(a2, a1, out=a2)
    a2 += a0                                    # a2 - 2t a1 + t^2 a0: q'y
    np.multiply(g.xq0, gy[0], out=a0)
    np.multiply(g.xq1, gy[1], out=a1)
    a0 += a1
    r_yq = np.subtract(a2, a0, out=a2)
    with np.errstate(all="ignore"):
        acc = np.divide(r_yq, g.r_qq, out=a1)
        gain = np.multiply(r_yq, acc, out=a0)   # SSE reduction over the straight-line fit
    valid = np.isfinite(gain)
    valid &= (acc > 0) if direction > 0 else (acc < 0)
    valid &= g.r_qq_positive
    gain[~valid] = -np.inf
    j = int(gain[::-1].argmax())               # the first maximum in t order
    if not valid[hi - lo - 1 - j]:
        return 0                               # no candidate valid
    return lo + j


@dataclass(frozen=True)
class _DepartureTerms:
    """The parts of fit_departure's least squares that depend only on the length n (not on y);
    all but k and ginv for the candidate departures t in [lo, hi) only, in reverse order
    (s = n - 1 - t from n - hi to n - 1 - lo)."""
    k: np.ndarray             # 0..n-1 (sample index)
    two_t: np.ndarray         # 2 t
    t_sq: np.ndarray          # t^2
    xq0: np.ndarray           # sum over k >= t of q = (k - t)^2
    xq1: np.ndarray           # sum over k >= t of k q
    ginv: np.ndarray          # inverse Gram matrix of the regressors 1, k
    r_qq: np.ndarray          # q'q with 1, k projected out
    r_qq_positive: np.ndarray


_DEPARTURE_TERMS: dict[tuple[int, int, int], _DepartureTerms] = {}
_GINV: dict[int, np.ndarray] = {}
_POWER_SUMS: list[np.ndarray] = []       # [m, s2, s3, s4] for m = 0 .. len - 1


def _power_sums(n: int) -> list[np.ndarray]:
    """sum_{j=0..m} j^2, j^3, j^4 for m = 0 .. >= n - 1, by the inline formulas on the float m (each
    value is an elementwise function of m alone, so the table's values are those of any length)."""
    if not _POWER_SUMS or _POWER_SUMS[0].size < n:
        m = np.arange(max(n, 2 * (_POWER_SUMS[0].size if _POWER_SUMS else 2048)), dtype=np.float64)
        s2 = m * (m + 1) * (2 * m + 1) / 6.0
        s3 = (m * (m + 1) / 2.0) ** 2
        s4 = m * (m + 1) * (2 * m + 1) * (3 * m * m + 3 * m - 1) / 30.0
        for a in (m, s2, s3, s4):
            a.flags.writeable = False
        _POWER_SUMS[:] = [m, s2, s3, s4]
    return _POWER_SUMS


def _departure_terms(n: int, lo: int, hi: int) -> _DepartureTerms:
    """fit_departure's y-independent terms for length n, kept for the last 64 lengths (the detector
    fits fit_samples samples, other lengths when the fit window starts at the arming window) -- by
    the same operations as inline, so the fit is bit for bit the same (elementwise: the candidates'
    values do not depend on the others).  The power sums of j = k - t (j = 0..m, m = n - 1 - t) come
    from one table; the 2x2 inverse Gram matrix is kept per length."""
    key = (n, lo, hi)
    terms = _DEPARTURE_TERMS.get(key)
    if terms is not None:
        return terms
    k = np.arange(n, dtype=np.float64)
    ginv = _GINV.get(n)
    if ginv is None:
        sk, skk = k.sum(), (k * k).sum()
        ginv = np.linalg.inv(np.array([[n, sk], [sk, skk]]))
        if len(_GINV) >= 4096:
            _GINV.clear()
        _GINV[n] = ginv
    # candidates in s order: s = m = n - 1 - t runs n - hi .. n - 1 - lo
    table_m, table_s2, table_s3, table_s4 = _power_sums(n)
    c = slice(n - hi, n - lo)
    t = (n - 1) - table_m[c]                   # the candidates' t, exact (integers)
    xq0 = table_s2[c]                          # X'q = (sum q, sum k q)
    xq1 = table_s3[c] + t * xq0
    r_qq = table_s4[c] - (ginv[0, 0] * xq0 * xq0 + 2 * ginv[0, 1] * xq0 * xq1 + ginv[1, 1] * xq1 * xq1)
    arrays = [k, 2.0 * t, t * t, xq0, xq1, ginv, r_qq, r_qq > 0]
    for a in arrays:
        a.flags.writeable = False
    terms = _DepartureTerms(*arrays)
    if len(_DEPARTURE_TERMS) >= 64:           # lengths other than fit_samples come and go: bound it
        _DEPARTURE_TERMS.clear()
    _DEPARTURE_TERMS[key] = terms
    return terms


def _mean(x: np.ndarray) -> float:
    """np.mean of a non-empty 1-D float64 array, as np.mean computes it (its pairwise sum / count),
    without np.mean's Python-level argument handling."""
    return float(np.add.reduce(x) / x.size)


def _first_true(mask: np.ndarray) -> int:
    """Index of the first True of a 1-D boolean array, -1 if none (argmax stops at the first True)."""
    if mask.size == 0:
        return -1
    i = int(mask.argmax())
    return i if mask[i] else -1


def _check_positive(name: str, value, integer: bool = False):
    if integer:
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value <= 0:
            raise ValueError(f"{name}={value!r}: must be a positive int")
        return int(value)
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}: must be a positive number") from None
    if not np.isfinite(v) or v <= 0:
        raise ValueError(f"{name}={value!r}: must be a positive number")
    return v


class BacklashEntryDetector:
    """Streaming entry detector for ONE drive (one scenario).  Feed consecutive chunks.

    ``feed(first_sample_index, signals, sample_period_s=None) -> list[BacklashEntry]``
    ``signals`` holds 1-D arrays of one chunk: ``angle_difference`` (alpha1 - alpha2 [rad]) or
    ``alpha1`` and ``alpha2`` (measured angles), or ``omega1`` and ``omega2`` (shaft speeds [rad/s],
    integrated, eq. 2-3).  ``angle_source="auto"`` uses measured angles when present.

    Continuity: a chunk whose ``first_sample_index`` is beyond the expected one (dropped chunk) or
    whose sample period differs resets the detector (it re-arms on the next settled contact); a chunk
    that starts before the expected index (out of order / duplicate) is ignored.  ``events`` keeps a
    log of those decisions.
    """

    def __init__(self, trigger: str = DEFAULTS["detector"]["trigger"], width_m: float | None = None,
                 radius_m: float = DEFAULTS["detector"]["radius_m"],
                 sample_period_s: float = DEFAULTS["detector"]["sample_period_s"],
                 holdoff_samples: int = DEFAULTS["detector"]["holdoff_samples"],
                 angle_source: str = DEFAULTS["detector"]["angle_source"],
                 integration: str = DEFAULTS["detector"]["integration"],
                 confirm_rad: float = DEFAULTS["detector"]["confirm_rad"],
                 reference_tau_s: float = DEFAULTS["detector"]["reference_tau_s"],
                 settle_samples: int = DEFAULTS["detector"]["settle_samples"],
                 settle_range_rad: float = DEFAULTS["detector"]["settle_range_rad"],
                 fit_samples: int = DEFAULTS["detector"]["fit_samples"],
                 contact_deflection_rad: float = DEFAULTS["detector"]["contact_deflection_rad"],
                 initial_contact_side: int = DEFAULTS["detector"]["initial_contact_side"],
                 rereference_interval_s: float = DEFAULTS["detector"]["rereference_interval_s"]):
        if trigger not in TRIGGERS:
            raise ValueError(f"trigger={trigger!r}: allowed values are {TRIGGERS}")
        if angle_source not in ANGLE_SOURCES:
            raise ValueError(f"angle_source={angle_source!r}: allowed values are {ANGLE_SOURCES}")
        if integration not in INTEGRATION_RULES:
            raise ValueError(f"integration={integration!r}: allowed values are {INTEGRATION_RULES}")
        if trigger == "paper":
            if width_m is None:
                raise ValueError("width_m=None: the 'paper' trigger (eq. 1) needs the backlash width K2 > 0 [m]")
            width_m = _check_positive("width_m", width_m)
        elif width_m is not None:
            width_m = _check_positive("width_m", width_m)
        self.trigger = trigger
        self.width_m = width_m
        self.radius_m = _check_positive("radius_m", radius_m)
        self.sample_period_s = _check_positive("sample_period_s", sample_period_s)
        self.holdoff_samples = _check_positive("holdoff_samples", holdoff_samples, integer=True)
        self.angle_source = angle_source
        self.integration = integration
        self.confirm_rad = _check_positive("confirm_rad", confirm_rad)
        self.reference_tau_s = _check_positive("reference_tau_s", reference_tau_s)
        self.settle_samples = _check_positive("settle_samples", settle_samples, integer=True)
        self.settle_range_rad = _check_positive("settle_range_rad", settle_range_rad)
        self.fit_samples = _check_positive("fit_samples", fit_samples, integer=True)
        if self.fit_samples < 64:
            raise ValueError(f"fit_samples={fit_samples!r}: must be >= 64")
        cd = float(contact_deflection_rad)
        if not np.isfinite(cd) or cd < 0:
            raise ValueError(f"contact_deflection_rad={contact_deflection_rad!r}: must be >= 0")
        self.contact_deflection_rad = cd
        if initial_contact_side not in (1, -1, None):
            raise ValueError(f"initial_contact_side={initial_contact_side!r}: allowed values are 1, -1, None")
        self.initial_contact_side = initial_contact_side
        self.rereference_interval_s = _check_positive("rereference_interval_s", rereference_interval_s)
        self.beta = None if width_m is None else width_m / self.radius_m
        self.events: list[tuple[int, str]] = []     # (sample index, "reset: ..." / "ignored: ...")
        self.n_rereferences = 0
        self._alpha_cache = None
        self._store: np.ndarray | None = None   # buffer of the history and the current chunk (_joined)
        self._hist_at = 0                       # offset of _hist in _store
        self._reset(stream_start=True)

    @classmethod
    def from_config(cls, cfg: Mapping | None = None, **overrides) -> "BacklashEntryDetector":
        """Build from ``load_windowing_config()["detector"]`` (or a dict like it), with overrides."""
        if cfg is None:
            cfg = load_windowing_config()["detector"]
        kw = dict(cfg)
        kw.update(overrides)
        return cls(**kw)

    # ------------------------------------------------------------------ state
    def _reset(self, stream_start: bool = False) -> None:
        self._state = _UNARMED
        self._trav = (1, 0)
        self._holdoff_end = -(1 << 62)
        self._next_index: int | None = None if stream_start else self._next_index
        self._hist = np.zeros(0)             # delta of the samples before the current chunk
        self._hist_base = 0                  # absolute index of _hist[0]
        self._seg_start = None               # first index of the current contiguous segment
        self._ema = None                     # contact level at the last re-reference
        self._trk = (0.0, 0.0)               # (s1, s2) of the contact tracker
        self._offset = 0.0                   # re-referencing offset (paper trigger, integrated angles)
        self._side = self.initial_contact_side if stream_start else None
        self._offset_valid = False            # integrated angles: offset known (a + contact was seen)
        self._offset_idx = 0                  # sample of the last re-reference
        self._drift_rate = 0.0                # estimated drift of the integrated delta [rad/sample]
        self._anchor = None                   # (index, offset) of the drift-rate baseline
        self._last_ref_index = None
        self._entry_delta = None             # delta at the last entry (side after the traverse)
        self._int_delta = 0.0                # integration state
        self._int_w = None
        self._source = None

    @property
    def latency_samples(self) -> int:
        """Upper bound of confirm_sample_index - sample_index (back-dating): size the capture history."""
        return self.fit_samples

    def _delta_from(self, signals: Mapping[str, np.ndarray]) -> tuple[np.ndarray, str]:
        have_meas = "angle_difference" in signals or ("alpha1" in signals and "alpha2" in signals)
        have_int = "omega1" in signals and "omega2" in signals
        src = self.angle_source
        if src == "auto":
            src = "measured" if have_meas else "integrated"
        if src == "measured":
            if "angle_difference" in signals:
                d = np.asarray(signals["angle_difference"], dtype=np.float64)
            elif "alpha1" in signals and "alpha2" in signals:
                d = np.asarray(signals["alpha1"], dtype=np.float64) - np.asarray(signals["alpha2"], dtype=np.float64)
            else:
                raise ValueError("signals: angle_source='measured' needs 'angle_difference' or 'alpha1' and 'alpha2'")
            return d, src
        if not have_int:
            raise ValueError("signals: need 'angle_difference', 'alpha1'+'alpha2' or 'omega1'+'omega2' "
                             f"(got {sorted(signals)})")
        w = np.asarray(signals["omega1"], dtype=np.float64) - np.asarray(signals["omega2"], dtype=np.float64)
        d = integrate_relative_speed(w, self.sample_period_s, self.integration, self._int_delta, self._int_w)
        if w.size:
            self._int_delta, self._int_w = float(d[-1]), float(w[-1])
        return d, src

    # ------------------------------------------------------------------ feed
    def feed(self, first_sample_index: int, signals: Mapping[str, np.ndarray],
             sample_period_s: float | None = None, finite: bool = False) -> list[BacklashEntry]:
        """The entries this chunk completes. ``finite``: the caller has checked that every sample
        in ``signals`` is finite (WindowingStage does): a measured angle difference given as a
        float64 array is then not tested again (a difference or an integral of the signals
        still is: it can overflow)."""
        first = int(first_sample_index)
        if sample_period_s is not None and not (isinstance(sample_period_s, float)
                                                and sample_period_s == self.sample_period_s):
            try:
                sp = _check_positive("sample_period_s", sample_period_s)
            except ValueError:
                # a chunk without a usable period cannot be placed in time: a gap, start again after it
                self.events.append((first, f"reset: bad sample period {sample_period_s!r}"))
                self._reset()
                self._next_index = None
                return []
            if abs(sp - self.sample_period_s) > 1e-9 * self.sample_period_s:
                self.events.append((first, f"reset: sample period {self.sample_period_s} -> {sp} s"))
                self.sample_period_s = sp
                self._reset()
                self._next_index = None
        if self._next_index is not None:
            if first < self._next_index:
                self.events.append((first, f"ignored: out-of-order chunk (expected {self._next_index})"))
                return []
            if first > self._next_index:
                self.events.append((first, f"reset: dropped samples {self._next_index}..{first - 1}"))
                self._reset()
        # the stream source must not change inside a segment (integration constant, offsets)
        if self._source is not None:
            want = self.angle_source
            if want == "auto":
                want = "measured" if ("angle_difference" in signals or
                                      ("alpha1" in signals and "alpha2" in signals)) else "integrated"
            if want != self._source:
                self.events.append((first, f"reset: angle source {self._source} -> {want}"))
                self._reset()
        if self._seg_start is None:                 # new segment: integration restarts at 0
            self._int_delta, self._int_w = 0.0, None
        delta, src = self._delta_from(signals)
        if delta.ndim != 1:
            raise ValueError(f"signals: arrays must be 1-D (one drive); got shape {delta.shape}")
        n = delta.size
        # a finite sum says every sample is finite (NaN/inf propagate); an infinite one may be an overflow
        known = finite and delta is signals.get("angle_difference")
        if not known and not math.isfinite(np.add.reduce(delta)) and not np.isfinite(delta).all():
            # NaN/inf would poison the contact tracker for good: drop the chunk, start again after it
            self.events.append((first, f"reset: non-finite samples in {first}..{first + n - 1}"))
            self._reset()
            self._next_index = first + n
            return []
        self._source = src
        if self._seg_start is None:
            self._seg_start = first
            self._hist = np.zeros(0)
            self._hist_base = first
        self._next_index = first + n
        if n == 0:
            return []
        buf, at = self._joined(delta)
        base = self._hist_base
        out = self._process(buf, base, first)
        keep = min(buf.size, max(self.fit_samples, self.settle_samples) + 1)
        if at < 0:                                  # buf is the caller's array: keep a copy
            self._hist = buf[-keep:].copy()
        else:                                       # buf is in the store: keep a view
            self._hist = buf[buf.size - keep:]
            self._hist_at = at + buf.size - keep
        self._hist_base = base + buf.size - keep
        return out

    def _joined(self, delta: np.ndarray) -> tuple[np.ndarray, int]:
        """(the kept history followed by ``delta`` as one array, its offset in the store or -1).
        The store is a buffer of the detector's own that chunks are copied into behind the history,
        so a chunk costs one copy of itself (the history moves to the front when the store is full)."""
        hist = self._hist
        h, n = hist.size, delta.size
        if h == 0 and delta.flags.c_contiguous:
            return delta, -1
        store = self._store
        if store is not None and h and hist.base is store:
            at = self._hist_at
            if at + h + n <= store.size:
                store[at + h:at + h + n] = delta
                return store[at:at + h + n], at
        if store is None or store.size < h + n:
            store = self._store = np.empty(max(2 * (h + n), 16384))
        store[:h] = hist
        store[h:h + n] = delta
        return store[:h + n], 0

    # ------------------------------------------------------------------ state machine
    def _alpha(self) -> float:
        """The tracker's EMA weight per sample (kept per sample period and time constant)."""
        key = (self.sample_period_s, self.reference_tau_s)
        cached = self._alpha_cache
        if cached is None or cached[0] != key:
            cached = self._alpha_cache = (key, 1.0 - np.exp(-self.sample_period_s / self.reference_tau_s))
        return cached[1]

    def _find_settled(self, buf: np.ndarray, base: int, start: int, end: int) -> int:
        """First absolute index i in [start, end) whose last settle_samples samples (all inside the
        segment) span <= settle_range_rad; -1 if none.  Paper trigger on integrated angles, before a
        re-reference on the driving (+) contact: 4*settle_samples (a quiet contact, not a relaxing one),
        and the re-referenced delta must be outside the zone."""
        w = self.settle_samples
        paper_int = self.trigger == "paper" and self._source == "integrated"
        if paper_int and self._expected_side() == 1:
            w = 4 * w
        start = max(start, self._seg_start + w - 1)
        i = start
        block = _FIRST_SETTLE_BLOCK      # the contact usually settles soon: small blocks first
        while i < end:
            j = min(end, i + block)
            block = max(256, min(4 * block, _BLOCK))
            lo = i - w + 1 - base
            seg = buf[lo:j - base]
            ok = window_range(seg, w) <= self.settle_range_rad
            if self.trigger == "paper" and self._source == "measured":
                ok &= np.abs(buf[i - base:j - base]) >= self.beta
            elif paper_int and self._offset_valid and self._expected_side() == -1:
                ok &= np.abs(buf[i - base:j - base] + self._offset_at(i, j)) >= self.beta
            k = _first_true(ok)
            if k >= 0:
                return i + k
            i = j
        return -1

    def _expected_side(self):
        """Contact side after the last traverse (integrated paper trigger): +1 after a return."""
        return self._side

    def _rereference(self, buf: np.ndarray, base: int, idx: int) -> None:
        w = self.settle_samples
        level = _mean(buf[idx - w + 1 - base:idx + 1 - base])
        self._trk = (level, 0.0)
        self._ema = level
        self._last_ref_index = idx
        self.n_rereferences += 1
        if self.trigger == "paper" and self._source == "integrated":
            if self._entry_delta is not None:
                self._side = 1 if level > self._entry_delta else -1
            if self._side == 1:   # the driving contact: its deflection is the static r*F0/k_c
                self._set_offset(level, idx)

    def _set_offset(self, level: float, idx: int) -> None:
        """Re-reference: the driving contact level maps to +(beta + contact_deflection_rad).  Offsets
        more than ``drift_baseline`` apart also give the drift rate (speed bias), which is applied
        between re-references (a long baseline, so contact-level noise hardly enters the rate)."""
        new = self.beta + self.contact_deflection_rad - level
        baseline = int(round(_DRIFT_BASELINE_S / self.sample_period_s))
        if self._anchor is None:
            self._anchor = (idx, new)
        elif idx - self._anchor[0] >= baseline:
            self._drift_rate = (new - self._anchor[1]) / (idx - self._anchor[0])
            self._anchor = (idx, new)
        self._offset, self._offset_idx, self._offset_valid = new, idx, True

    def _offset_at(self, i: int, j: int) -> np.ndarray:
        """Offset for samples i..j-1 (absolute): last re-reference plus the estimated drift since."""
        return self._offset + self._drift_rate * (np.arange(i, j) - self._offset_idx)

    def _torque_zero_crossing(self, buf: np.ndarray, base: int, lo: int, t0: int, conf: int,
                              direction: int) -> int:
        """Entry of the contact-loss trigger: the sample where delta has moved ``contact_deflection_rad``
        (the static deflection r*F0/k_c, i.e. where the contact torque reaches zero) away from the
        contact level, after the fitted departure ``t0``.  Contact level = mean of the
        ``_LEVEL_SAMPLES`` samples before ``t0`` (not before ``lo``).  Linear interpolation between the
        two samples around the crossing, rounded to the nearest sample.  Uses only buf[lo..conf]
        (the data the departure fit already has).  Measured on the plant it tracks the zone entry with
        std ~21 samples instead of the departure's ~35 (docs/windowing.md)."""
        a = max(lo, t0 - _LEVEL_SAMPLES)
        if t0 - a < 16:
            return t0
        level = _mean(buf[a - base:t0 - base])
        y = buf[t0 - base:conf + 1 - base] - level     # times direction: (y > thr) = (y < -thr) going down
        thr = self.contact_deflection_rad
        k = _first_true(y > thr if direction > 0 else y < -thr)
        if k <= 0:
            return t0
        y0, y1 = float(y[k - 1] * direction), float(y[k] * direction)
        x = (k - 1) + (thr - y0) / (y1 - y0)
        return t0 + int(np.floor(x + 0.5))

    def _emit(self, out, idx: int, kind: str, confirm: int) -> None:
        out.append(BacklashEntry(int(idx), kind, self.trigger, int(confirm)))
        # the end-of-traverse search starts at least _APEX_LAG after the entry (speed test lag)
        self._start_traverse(idx, -1 if kind == KIND_ONSET else 1, max(confirm, idx + _APEX_LAG))

    def _start_traverse(self, idx: int, direction: int, confirm: int) -> None:
        self._holdoff_end = idx + self.holdoff_samples
        self._trav = (direction, confirm + 1)
        self._state = _TRAVERSE

    def _find_apex(self, buf: np.ndarray, base: int, start: int, end: int, direction: int) -> int:
        """First index >= start where delta stops moving in ``direction`` (the far-side impact or the
        turning point of a traverse): (delta[n] - delta[n - _APEX_LAG]) * direction <= 0."""
        start = max(start, self._seg_start + _APEX_LAG, base + _APEX_LAG)
        i = start
        block = _FIRST_APEX_BLOCK              # the apex is usually within ~2100 samples
        while i < end:
            j = min(end, i + block)
            block = _BLOCK
            now = buf[i - base:j - base]
            before = buf[i - _APEX_LAG - base:j - _APEX_LAG - base]
            # (now - before) * direction <= 0, without the difference: for finite doubles the
            # rounded difference has the sign of the exact one (and is 0 only when they are equal)
            k = _first_true(now <= before if direction > 0 else now >= before)
            if k >= 0:
                return i + k
            i = j
        return -1

    def _process(self, buf: np.ndarray, base: int, first: int) -> list[BacklashEntry]:
        out: list[BacklashEntry] = []
        end = base + buf.size
        pos = first
        while pos < end:
            if self._state == _TRAVERSE:
                direction, frm = self._trav
                i = self._find_apex(buf, base, max(pos, frm), end, direction)
                if i < 0:
                    break
                self._state = _UNARMED
                pos = i
                continue
            if self._state == _UNARMED:
                i = self._find_settled(buf, base, max(pos, self._holdoff_end), end)
                if i < 0:
                    break
                self._rereference(buf, base, i)
                self._state = _ARMED
                pos = i + 1
                continue
            # ARMED
            j = min(end, pos + _BLOCK)
            seg = buf[pos - base:j - base]
            if self.trigger == "contact_loss" or (self._source == "integrated" and not self._offset_valid):
                # contact reference: a causal EMA (reference_tau_s) from the settled contact level;
                # dev[n] = delta[n] - ema[n-1].  A constant relative speed v (drift, a relaxing
                # contact) gives |dev| <= v*tau; a traverse of the gap grows until the far side.
                k, direction, last = first_excursion(seg, self._alpha(), self._trk[0], self.confirm_rad)
                if k < 0:
                    self._trk = (last, 0.0)
                    pos = j
                    continue
                conf = pos + k
                lo = max(conf - self.fit_samples + 1, self._seg_start, base,
                         self._last_ref_index - self.settle_samples + 1)
                t0 = lo + fit_departure(buf[lo - base:conf + 1 - base], direction)
                if self.trigger == "contact_loss":
                    t0 = self._torque_zero_crossing(buf, base, lo, t0, conf, direction)
                if self.trigger == "paper":            # learning the contact side after a reset
                    self._entry_delta = float(buf[t0 - base])
                    self._side = direction
                    self._start_traverse(t0, direction, conf)
                else:
                    self._emit(out, t0, KIND_ONSET if direction < 0 else KIND_RETURN, conf)
                pos = conf + 1
                continue
            # paper trigger, eq. 1 on measured or re-referenced integrated delta
            dc = seg + self._offset_at(pos, j)
            if self._source == "integrated":
                # re-reference while quietly in contact, so drift cannot accumulate between events
                nxt = self._last_ref_index + int(round(self.rereference_interval_s / self.sample_period_s))
                if pos <= nxt < j:
                    j = nxt + 1
                    dc = dc[:j - pos]
            inside = np.abs(dc) < self.beta
            k = _first_true(inside)
            if k >= 0:
                idx = pos + k
                prev = dc[k - 1] if k > 0 else (buf[idx - 1 - base] + self._offset_at(idx - 1, idx)[0]
                                                if idx - 1 >= max(base, self._seg_start) else dc[k])
                self._entry_delta = float(buf[idx - base])
                self._side = -1 if prev > 0 else 1          # contact side after this traverse
                self._emit(out, idx, KIND_ONSET if prev > 0 else KIND_RETURN, idx)
                pos = idx + 1
                continue
            if self._source == "integrated" and j - 1 == nxt:
                w4 = 4 * self.settle_samples
                lo = nxt - w4 + 1
                if (self._side == 1 and lo >= max(base, self._seg_start)
                        and np.ptp(buf[lo - base:nxt + 1 - base]) <= self.settle_range_rad):
                    level = _mean(buf[nxt - self.settle_samples + 1 - base:nxt + 1 - base])
                    self._set_offset(level, nxt)
                    self.n_rereferences += 1
                self._last_ref_index = nxt
            pos = j
        return out
