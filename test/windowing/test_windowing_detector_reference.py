"""The streaming detector against a per-sample reference written from its documented rules
(docs/windowing.md: "Trigger paper", "Trigger contact_loss", "Chunk continuity and discards").

The detector searches whole blocks with numpy (a block-wise exponential average, sliding ranges,
early exits); the reference below steps sample by sample with plain Python floats and knows
nothing of blocks, chunks or history buffers: each contiguous stretch of the stream (between
resets) is processed as one array. They must give the same entries (index, kind, trigger,
confirmation) whatever the chunking: chunks of one sample, random chunkings, gaps, repeated or
older chunks, a chunk with a NaN.

The streams are synthetic traverses (backlash_monitor.windowing.synthetic) with white noise from a
seeded generator, so no decision sits on a threshold to the last bit: the reference's exponential
average is the plain recurrence and rounds differently from the detector's blocked one (~1e-16).
The departure fit itself is ``fit_departure`` (tested against its inline least squares in
test_windowing_fit_departure.py).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from backlash_monitor.windowing import DEFAULTS, BacklashEntryDetector, fit_departure
from backlash_monitor.windowing.synthetic import synthetic_period

APEX_LAG = 50        # docs: the end of a traverse = delta stops moving in its direction (1 ms lag)
LEVEL_SAMPLES = 200  # docs: contact level = mean of the 200 samples before the departure
DRIFT_BASELINE_S = 10.0


class ReferenceDetector:
    """docs/windowing.md's detector, one sample at a time."""

    def __init__(self, trigger="contact_loss", width_m=None, **kw):
        p = dict(DEFAULTS["detector"], trigger=trigger, width_m=width_m, **kw)
        self.p = p
        self.trigger = trigger
        self.dt = p["sample_period_s"]
        self.beta = None if width_m is None else width_m / p["radius_m"]
        self.entries = []
        self.next_index = None
        self.segment = None          # (first index, [samples]) of the stretch being collected
        self.source = None
        self.side0 = p["initial_contact_side"]   # side at stream start; None after every reset
        self.segments = []

    # ---------------------------------------------------------------- chunk continuity
    def feed(self, first, signals, period=None):
        if period is not None:
            if not (isinstance(period, float) and math.isfinite(period) and period > 0):
                self._break()
                self.next_index = None
                return
            if abs(period - self.dt) > 1e-9 * self.dt:
                self._break()
                self.dt = period
                self.next_index = None
        if self.next_index is not None:
            if first < self.next_index:
                return                                   # older chunk: ignored
            if first > self.next_index:
                self._break()                            # samples dropped: start again
        src = "measured" if "angle_difference" in signals else "integrated"
        if self.source is not None and src != self.source:
            self._break()
        x = np.concatenate([np.asarray(v, dtype=float) for v in signals.values()])
        n = len(next(iter(signals.values())))
        if not np.isfinite(x).all():
            self._break()
            self.next_index = first + n
            return
        self.source = src
        if self.segment is None:
            self.segment = (first, [], src)
        self.segment[1].append({k: np.asarray(v, dtype=float) for k, v in signals.items()})
        self.next_index = first + n

    def _break(self):
        if self.segment is not None:
            self.segments.append((self.segment, self.side0))
            self.side0 = None                # after a reset the contact side is unknown
        self.segment = None
        self.source = None

    def finish(self):
        self._break()
        for (first, parts, src), side in self.segments:
            if src == "measured":
                d = np.concatenate([c["angle_difference"] for c in parts]).tolist()
            else:
                w = (np.concatenate([c["omega1"] for c in parts]) - np.concatenate([c["omega2"] for c in parts]))
                d = self._integrate(w.tolist())
            if d:
                self._run(first, d, src, side)
        return self.entries

    def _integrate(self, w):
        """Eq. 2-3 from 0 at the stretch's first sample (trapezoid or rectangle rule)."""
        d = [0.0]
        for k in range(1, len(w)):
            inc = 0.5 * self.dt * (w[k] + w[k - 1]) if self.p["integration"] == "trapezoid" else self.dt * w[k]
            d.append(d[-1] + inc)
        return d

    # ---------------------------------------------------------------- one contiguous stretch
    def _run(self, s0, d, src, side):
        p = self.p
        n_end = s0 + len(d)
        at = lambda i: d[i - s0]        # noqa: E731  delta at absolute index i
        paper_int = self.trigger == "paper" and src == "integrated"
        lam = 1.0 - math.exp(-self.dt / p["reference_tau_s"])
        w_settle, confirm = p["settle_samples"], p["confirm_rad"]
        holdoff_end = -(1 << 62)
        state, pos = "unarmed", s0
        trav_dir = trav_from = 0
        ema = last_ref = None
        entry_delta = None
        offset, drift, offset_idx, offset_valid, anchor = 0.0, 0.0, 0, False, None
        interval = int(round(p["rereference_interval_s"] / self.dt))
        baseline = int(round(DRIFT_BASELINE_S / self.dt))

        def off(i):
            return offset + drift * (i - offset_idx)

        def set_offset(level, idx):
            nonlocal offset, drift, offset_idx, offset_valid, anchor
            new = self.beta + p["contact_deflection_rad"] - level
            if anchor is None:
                anchor = (idx, new)
            elif idx - anchor[0] >= baseline:
                drift = (new - anchor[1]) / (idx - anchor[0])
                anchor = (idx, new)
            offset, offset_idx, offset_valid = new, idx, True

        def window_range(i, w):
            win = d[i - w + 1 - s0:i + 1 - s0]
            return max(win) - min(win)

        def emit(idx, kind, conf):
            nonlocal holdoff_end, trav_dir, trav_from, state
            self.entries.append((idx, kind, self.trigger, conf))
            holdoff_end = idx + p["holdoff_samples"]
            trav_dir, trav_from, state = (-1 if kind == "onset" else 1), max(conf, idx + APEX_LAG) + 1, "traverse"

        i = pos
        while i < n_end:
            if state == "traverse":       # the far side: delta stops moving in the traverse direction
                i = max(i, trav_from, s0 + APEX_LAG)
                while i < n_end and (at(i) - at(i - APEX_LAG)) * trav_dir > 0:
                    i += 1
                if i < n_end:
                    state = "unarmed"
                continue
            if state == "unarmed":        # re-arm on a settled contact, not before the hold-off ends
                w = 4 * w_settle if (paper_int and side == 1) else w_settle
                i = max(i, holdoff_end, s0 + w - 1)
                while i < n_end:
                    ok = window_range(i, w) <= p["settle_range_rad"]
                    if ok and self.trigger == "paper" and src == "measured":
                        ok = abs(at(i)) >= self.beta
                    elif ok and paper_int and offset_valid and side == -1:
                        ok = abs(at(i) + off(i)) >= self.beta
                    if ok:
                        break
                    i += 1
                if i >= n_end:
                    break
                level = float(np.mean(d[i - w_settle + 1 - s0:i + 1 - s0]))   # the contact level
                ema, last_ref = level, i
                if paper_int:
                    if entry_delta is not None:
                        side = 1 if level > entry_delta else -1
                    if side == 1:
                        set_offset(level, i)
                state, i = "armed", i + 1
                continue
            # armed
            if self.trigger == "contact_loss" or (paper_int and not offset_valid):
                # confirmed when delta is confirm_rad away from the contact reference (causal EMA)
                while i < n_end:
                    dev = at(i) - ema
                    if abs(dev) > confirm:
                        break
                    ema = lam * at(i) + (1.0 - lam) * ema
                    i += 1
                if i >= n_end:
                    break
                conf, direction = i, (1 if dev > 0 else -1)
                lo = max(conf - p["fit_samples"] + 1, s0, last_ref - w_settle + 1)
                t0 = lo + fit_departure(np.array(d[lo - s0:conf + 1 - s0]), direction)
                if self.trigger == "paper":          # learning the contact side: no entry
                    entry_delta, side = at(t0), direction
                    holdoff_end = t0 + p["holdoff_samples"]
                    trav_dir, trav_from, state = direction, conf + 1, "traverse"
                    i = conf + 1
                    continue
                # the entry: the torque-zero crossing after the departure
                entry = t0
                a = max(lo, t0 - LEVEL_SAMPLES)
                if t0 - a >= 16:
                    level = float(np.mean(d[a - s0:t0 - s0]))
                    thr = p["contact_deflection_rad"]
                    for k in range(t0, conf + 1):
                        if (at(k) - level) * direction > thr:
                            if k > t0:
                                y0, y1 = (at(k - 1) - level) * direction, (at(k) - level) * direction
                                x = (k - 1 - t0) + (thr - y0) / (y1 - y0)
                                entry = t0 + math.floor(x + 0.5)
                            break
                emit(entry, "onset" if direction < 0 else "return", conf)
                i = conf + 1
                continue
            # paper trigger, eq. 1: the first sample inside the zone
            nxt = last_ref + interval if src == "integrated" else None
            while i < n_end:
                if abs(at(i) + off(i)) < self.beta:
                    prev = at(i - 1) + off(i - 1) if i - 1 >= s0 else at(i) + off(i)
                    entry_delta, side = at(i), (-1 if prev > 0 else 1)
                    emit(i, "onset" if prev > 0 else "return", i)
                    i += 1
                    break
                if i == nxt:             # integrated: re-reference while quietly in contact
                    lo = nxt - 4 * w_settle + 1
                    if side == 1 and lo >= s0 and window_range(nxt, 4 * w_settle) <= p["settle_range_rad"]:
                        set_offset(float(np.mean(d[nxt - w_settle + 1 - s0:nxt + 1 - s0])), nxt)
                    last_ref = nxt
                    nxt = last_ref + interval
                i += 1
            else:
                break


# ------------------------------------------------------------------------------ streams
def stream(seed: int, n_periods: int, width: float, noise: float, source: str, kinds=None):
    """Synthetic periods with random timing, acceleration and bounce, white noise on Delta (or on
    the speed difference, integrated), drawn from ``seed``."""
    rng = np.random.default_rng(seed)
    parts, speeds = [], []
    for _ in range(n_periods):
        period = synthetic_period(width_m=width, period_s=rng.uniform(0.15, 0.3), t_on_s=rng.uniform(0.03, 0.06),
                                  pulse_s=rng.uniform(0.04, 0.08), accel=rng.uniform(80.0, 200.0),
                                  defl_hi=rng.uniform(1e-3, 2.5e-3), defl_lo=rng.uniform(2e-3, 4e-3),
                                  bounce_rad=rng.choice([0.0, 0.002]))
        parts.append(period.delta)
        speeds.append(period.w_rel)
    if source == "measured":
        d = np.concatenate(parts)
        return {"angle_difference": d + noise * rng.standard_normal(d.size)}
    w = np.concatenate(speeds)          # speed noise: 5000 x the angle noise [rad/s per rad]
    return {"omega1": 150.0 + w + 5e3 * noise * rng.standard_normal(w.size), "omega2": np.full(w.size, 150.0)}


def chunks_of(sig, sizes, first=0):
    n = len(next(iter(sig.values())))
    out, lo, k = [], 0, 0
    while lo < n:
        c = int(sizes[k % len(sizes)])
        out.append((first + lo, {key: v[lo:lo + c] for key, v in sig.items()}))
        lo += c
        k += 1
    return out


def run_both(kw, feeds, period=None):
    det, ref = BacklashEntryDetector(**kw), ReferenceDetector(**kw)
    got = []
    for first, sig in feeds:
        got += [(e.sample_index, e.kind, e.trigger, e.confirm_sample_index) for e in det.feed(first, sig, period)]
        ref.feed(first, sig, period)
    return got, ref.finish()


CASES = {
    "contact_loss": ({"trigger": "contact_loss"}, "measured"),
    "contact_loss_integrated": ({"trigger": "contact_loss"}, "integrated"),
    "paper": ({"trigger": "paper"}, "measured"),
    "paper_integrated": ({"trigger": "paper"}, "integrated"),
}


def kwargs_for(case, width):
    kw, source = CASES[case]
    return (dict(kw, width_m=width) if kw["trigger"] == "paper" else dict(kw)), source


@pytest.mark.parametrize("case", list(CASES))
@pytest.mark.parametrize("chunk", [None, 1000, 777, 4096, 65536])
def test_detector_equals_the_per_sample_reference(case, chunk):
    kw, source = kwargs_for(case, 0.005)
    sig = stream(11, 10, 0.005, 1e-4, source)
    feeds = [(0, sig)] if chunk is None else chunks_of(sig, [chunk])
    got, ref = run_both(kw, feeds)
    assert len(ref) >= 18 and got == ref


@pytest.mark.parametrize("case", list(CASES))
def test_chunks_of_one_sample(case):
    kw, source = kwargs_for(case, 0.0025)
    sig = stream(5, 2, 0.0025, 1e-4, source)
    got, ref = run_both(kw, chunks_of(sig, [1]))
    assert len(ref) >= 3 and got == ref


def faulty(feeds, rng):
    """Drop a run of chunks, repeat one, send an older one, put a NaN in one."""
    out = []
    k_drop, k_rep, k_nan = rng.integers(len(feeds) // 5, len(feeds), size=3)
    for k, (first, sig) in enumerate(feeds):
        if k_drop <= k < k_drop + 3:
            continue
        if k == k_nan:
            sig = {key: v.copy() for key, v in sig.items()}
            x = next(iter(sig.values()))
            x[len(x) // 2] = np.nan
        out.append((first, sig))
        if k == k_rep:
            out += [(first, sig), (max(0, first - 3000), sig)]
    return out


SETTINGS = settings(max_examples=30, deadline=None, database=None, derandomize=True,
                    suppress_health_check=list(HealthCheck))


@pytest.mark.slow
@SETTINGS
@given(case=st.sampled_from(list(CASES)), seed=st.integers(0, 10_000),
       width=st.sampled_from([0.0025, 0.00375, 0.005, 0.0075, 0.01]),
       noise=st.floats(0.0, 2e-4), sizes=st.lists(st.integers(1, 9000), min_size=1, max_size=12),
       faults=st.booleans(), holdoff=st.sampled_from([2048, 300]), initial_side=st.sampled_from([1, None]))
def test_random_streams_and_chunkings(case, seed, width, noise, sizes, faults, holdoff, initial_side):
    kw, source = kwargs_for(case, width)
    kw.update(holdoff_samples=holdoff, initial_contact_side=initial_side)
    sig = stream(seed, 4, width, noise, source)
    feeds = chunks_of(sig, sizes)
    if faults and len(feeds) > 5:
        feeds = faulty(feeds, np.random.default_rng(seed))
    got, ref = run_both(kw, feeds)
    assert got == ref
