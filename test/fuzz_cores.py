"""Fuzz properties of the signal chain's cores, shared by test/test_fuzz_*.py (a few hundred
examples each) and bench/reliability.py (>= 10,000 each).

Each ``check_*`` takes one generated input and asserts the core's invariants:

- windowing (ChunkJoiner + WindowingStage + detector + capture): a stream of chunks with
  generated faults (NaN/inf samples, a lost chunk, a lost signal, unequal lengths, a bad or
  other sample period, an index jump, a restart at 0, a repeated or swapped range, a bad index):
  no exception; every window has the configured length and finite samples; every fault that
  loses data is counted; after the last fault, the clean rest of the stream gives windows again.
- denoise (denoise_checked): a reason from input_faults.REASONS, or two finite arrays of the
  input's length.
- estimator (DriveEstimator): a window is either rejected with a reason or gives one estimate per
  signal whose width is a candidate and whose B vector has 6 finite, non-negative entries; a good
  onset window after a bad one is classified.
- fusion (WidthFusion): any B vectors; the fused width is always a candidate.

``INPUTS`` counts the examples run per core (the bench reports it).
"""
from __future__ import annotations

from collections import Counter, namedtuple
from functools import lru_cache

import numpy as np
from hypothesis import strategies as st

from backlash_monitor.chain.joiner import ChunkJoiner

from backlash_monitor.chain.stage import WindowingStage

from backlash_monitor.denoise import denoise_checked
from backlash_monitor.windowing.faults import REASONS

INPUTS: Counter = Counter()

WINDOW_LENGTH = 2048
PERIOD_S = 2e-5
SIGNALS = ("a1", "a2", "angle_difference")


# ------------------------------------------------------------------ windowing
@lru_cache(maxsize=1)
def synthetic_stream():
    """A short synthetic drive stream (backlash_monitor.windowing.synthetic): 0.1 s periods, one
    onset and one return each, exactly known; a1/a2 are the relative acceleration plus noise."""
    from backlash_monitor.windowing.synthetic import synthetic_period, tile_record
    p = synthetic_period(period_s=0.1, t_on_s=0.02, pulse_s=0.045)
    delta, w, _, entries = tile_record(p, 6)
    rng = np.random.default_rng(7)
    accel = np.gradient(w, PERIOD_S)
    a1 = 0.01 * accel + rng.normal(0, 0.05, delta.size)   # |a1| <= ~1050 m/s^2: inside the sensors' range
    a2 = -0.01 * accel + rng.normal(0, 0.05, delta.size)
    return {"a1": a1, "a2": a2, "angle_difference": delta}, p.delta.size


FAULTS = ("none", "nan", "inf", "lose_chunk", "lose_signal", "short_signal", "period_zero",
          "period_nan", "period_negative", "period_other", "jump", "far_jump", "restart",
          "repeat", "swap", "bad_index", "huge_index")
# faults that lose or change data and must be counted when a clean range follows them
LOSSY = set(FAULTS) - {"none"}


def _draw_chunks(draw):
    """(chunk sizes covering the synthetic stream, the chunk numbers that may carry a fault: those
    before its clean tail of two periods and a window)."""
    data, period = synthetic_stream()
    n = data["a1"].size
    clean_tail = 2 * period + WINDOW_LENGTH + 400
    sizes, total = [], 0
    while total < n:
        size = draw(st.sampled_from([200, 500, 1000, 1000, 1000, 2500, 4000]))
        sizes.append(min(size, n - total))
        total += sizes[-1]
    return sizes, [i for i in range(len(sizes)) if sum(sizes[:i + 1]) < n - clean_tail]


@st.composite
def chunk_streams(draw):
    """(chunk sizes, {chunk number: fault}, signal order) of a stream whose last two periods
    (and a window) are clean."""
    sizes, faultable = _draw_chunks(draw)
    faults = draw(st.dictionaries(st.sampled_from(faultable), st.sampled_from(FAULTS),
                                  max_size=4)) if faultable else {}
    order = draw(st.permutations(SIGNALS))
    return sizes, faults, tuple(order)


# a chunk's header stamp, as builtin_interfaces/Time holds it
Stamp = namedtuple("Stamp", "sec nanosec")
# a restarted stream begins this long after the old one's last chunk [s] (a process restart takes
# seconds; chain/stage.py STAMP_BACKSTEP_S)
RESTART_DELAY_S = 1.0


def stamp_at(seconds: float) -> Stamp:
    ns = int(round(seconds * 1e9))
    return Stamp(ns // 1_000_000_000, ns % 1_000_000_000)


# the faults that move or lose ranges (swaps, gaps, duplicates, index jumps, restarts) and a bad
# range; swaps and restarts twice as often (late chunks around a restart are what interacts)
STREAM_FAULTS = ("swap", "swap", "restart", "restart", "lose_chunk", "lose_signal", "repeat", "jump",
                 "far_jump", "nan")


@st.composite
def clustered_chunk_streams(draw, kinds=STREAM_FAULTS):
    """Like :func:`chunk_streams`, with 1 to 4 faults of ``kinds`` within 4 consecutive chunks
    (each chunk faulty or not) -- the cases that interact: a swap before or after a restart, a lost
    chunk before them, ... -- then a clean tail of two periods and a window."""
    sizes, faultable = _draw_chunks(draw)
    faults = {}
    if faultable:
        k = draw(st.sampled_from(faultable))
        run = draw(st.lists(st.sampled_from(tuple(kinds) + ("none",) * 3), min_size=4, max_size=4)
                   .filter(lambda r: any(f != "none" for f in r)))
        faults = {k + j: f for j, f in enumerate(run) if f != "none" and k + j in faultable}
    return sizes, faults, tuple(draw(st.permutations(SIGNALS)))


def run_stream(sizes, faults, order, resync_samples=50_000, trace=None, stamps=True):
    """Feeds the stream with its faults through ChunkJoiner + WindowingStage (as the node and
    analyze do); returns (windows, stage, joiner, clean_from: the sample index from which the
    stream was clean for good). ``trace``: a list to which (the range's place in the data, the
    JoinedRange, whether the stage fed it to the detector) is appended for every joined range.
    ``stamps``: each chunk carries the header stamp of its first sample (its place in the data x
    the period, plus RESTART_DELAY_S per restart before it), as the plant's publisher stamps them;
    False: none, as an offline record without stamps."""
    data, _ = synthetic_stream()
    stage = WindowingStage(window_length=WINDOW_LENGTH, resync_samples=resync_samples)
    joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
    windows = []
    shift = 0                       # index shift of the chunks after a jump / restart
    delay_s = 0.0                   # time added to the stamps by the restarts so far
    chunks = []
    lo = 0
    for i, size in enumerate(sizes):
        chunks.append((i, lo, size))
        lo += size
    pending_swap = None
    last_fault_end = 0
    for i, lo, size in chunks:
        fault = faults.get(i, "none")
        arrays = {s: data[s][lo:lo + size].copy() for s in SIGNALS}
        first, period = lo + shift, PERIOD_S
        periods = {s: period for s in SIGNALS}
        send = list(order)
        if fault == "nan":
            arrays["angle_difference"][size // 2] = np.nan
        elif fault == "inf":
            arrays["a2"][0] = -np.inf
        elif fault == "lose_chunk":
            send = []
        elif fault == "lose_signal":
            send = [s for s in send if s != "a1"]
        elif fault == "short_signal":
            arrays["a2"] = arrays["a2"][:-1]
        elif fault == "period_zero":
            periods = {s: 0.0 for s in SIGNALS}
        elif fault == "period_nan":
            periods["a2"] = float("nan")
        elif fault == "period_negative":
            periods = {s: -PERIOD_S for s in SIGNALS}
        elif fault == "period_other":
            periods = {s: PERIOD_S / 2 for s in SIGNALS}
        elif fault == "jump":
            shift += 7919
            first = lo + shift
        elif fault == "far_jump":
            shift += 10 ** 12
            first = lo + shift
        elif fault == "restart":
            shift = -lo
            first = 0
            delay_s += RESTART_DELAY_S
        elif fault == "bad_index":
            first = -5
        elif fault == "huge_index":
            first = 2 ** 64 - 1
        if fault != "none":
            last_fault_end = lo + size
        stamp = stamp_at(lo * PERIOD_S + delay_s) if stamps else None
        out = [(first, arrays, periods, send, lo, stamp)]
        if fault == "repeat":
            out = out + out
        if fault == "swap":
            pending_swap = out
            continue
        if pending_swap is not None:
            out, pending_swap = out + pending_swap, None
        for first_, arrays_, periods_, send_, lo_, stamp_ in out:
            for name in send_:
                joined = joiner.add(name, first_, periods_[name], arrays_[name], stamp=stamp_)
                if joined is not None:
                    fed = stage.fed_samples
                    w, _ = stage.feed(joined)
                    if trace is not None:
                        trace.append((lo_, joined, stage.fed_samples > fed))
                    windows += [(x, lo) for x in w]
    return windows, stage, joiner, last_fault_end


def check_windowing(sizes, faults, order, resync_samples=50_000):
    INPUTS["windowing"] += 1
    data, period = synthetic_stream()
    windows, stage, joiner, clean_from = run_stream(sizes, faults, order, resync_samples)
    for window, _ in windows:
        for s in ("a1", "a2"):
            x = window.signals[s]
            assert x.shape == (WINDOW_LENGTH,), (s, x.shape)
            assert np.isfinite(x).all(), s
        assert window.sample_period_s > 0
    # no silent loss: a lossy fault followed by clean data is counted
    # (a chunk lost or moved before anything arrived cannot be told from a later stream start)
    first_only = {"lose_chunk", "lose_signal", "jump", "far_jump", "restart", "period_other"}
    lead = 0                        # chunks 0..lead-1 lost or moved before anything arrived
    while faults.get(lead) in first_only:
        lead += 1
    if any(f in LOSSY and i >= lead and f != "period_other" for i, f in faults.items()):
        assert stage.faults.total > 0, (faults, stage.faults.counts)
    # the stream resumes: windows whose samples all come after the last fault
    after = [w for w, lo in windows if lo >= clean_from]
    assert after, (faults, stage.faults.counts, clean_from)
    return windows, stage


@st.composite
def detector_chunks(draw):
    """Raw detector/capture input: a list of (first_index, arrays, period) with arbitrary values."""
    out = []
    for _ in range(draw(st.integers(1, 6))):
        n = draw(st.integers(0, 300))
        values = st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                           st.floats(-0.1, 0.1))
        base = draw(st.sampled_from([np.zeros(n), np.linspace(0.04, -0.04, n)]))
        arr = base.copy()
        for k in draw(st.lists(st.integers(0, max(n - 1, 0)), max_size=3)) if n else []:
            arr[k] = draw(values)
        first = draw(st.one_of(st.integers(0, 10 ** 6), st.integers(0, 2 ** 52)))
        period = draw(st.one_of(st.just(PERIOD_S), st.floats(allow_nan=True, allow_infinity=True)))
        out.append((first, arr, period))
    return out


def check_detector(chunks):
    """BacklashEntryDetector + WindowCapture fed arbitrary 1-D chunks: never raise; entries and
    windows are inside the samples given."""
    from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture
    INPUTS["windowing"] += 1
    det = BacklashEntryDetector()
    cap = WindowCapture(window_length=64, signals=("angle_difference",))
    for first, arr, period in chunks:
        entries = det.feed(first, {"angle_difference": arr}, period)
        for e in entries:
            assert e.sample_index <= e.confirm_sample_index < first + arr.size
        windows, _ = cap.feed(first, {"angle_difference": arr}, entries, period)
        for w in windows:
            assert w.signals["angle_difference"].shape == (64,)
            assert np.isfinite(w.signals["angle_difference"]).all()


# ------------------------------------------------------------------ denoise
FLOATS = st.one_of(st.floats(-10.0, 10.0), st.floats(allow_nan=True, allow_infinity=True),
                   st.sampled_from([0.0, 1e300, -1e300, 5e-324]))


@st.composite
def window_pairs(draw, lengths=(2048, 2048, 2048, 2047, 1024, 100, 63, 1, 0)):
    n1 = draw(st.sampled_from(lengths))
    n2 = n1 if draw(st.booleans()) or draw(st.booleans()) else draw(st.sampled_from(lengths))
    rng = np.random.default_rng(draw(st.integers(0, 2 ** 32 - 1)))
    scale = draw(st.sampled_from([1e-3, 1.0, 50.0, 1e6]))
    base = draw(st.sampled_from(["noise", "noise", "noise", "zeros", "constant", "denormal", "huge"]))

    def make(n):
        if base == "noise":
            return rng.normal(0, scale, n)
        return np.full(n, {"zeros": 0.0, "constant": scale, "denormal": 5e-324, "huge": 1e300}[base])
    a1 = make(n1)
    a2 = make(n2) if draw(st.booleans()) else rng.normal(0, scale, n2)
    for arr in (a1, a2):
        for k in draw(st.lists(st.integers(0, max(arr.size - 1, 0)), max_size=3)) if arr.size else []:
            arr[k] = draw(FLOATS)
    return a1, a2


def check_denoise(a1, a2):
    INPUTS["denoise"] += 1
    clean, reason = denoise_checked(a1, a2)
    if reason is not None:
        assert clean is None and reason in REASONS
        from backlash_monitor.denoise import max_level
        assert (a1.size != a2.size or a1.size == 0 or max_level(a1.size) < 6 or not np.isfinite(a1).all()
                or not np.isfinite(a2).all() or reason == "denoise_failed"), reason
        return
    assert clean[0].shape == a1.shape and clean[1].shape == a2.shape
    assert np.isfinite(clean[0]).all() and np.isfinite(clean[1]).all()


# ------------------------------------------------------------------ estimator
@lru_cache(maxsize=1)
def estimator_library():
    from backlash_monitor.classifier.patterns import load_library
    return load_library()


def make_estimator(mode="shape"):
    from backlash_monitor.estimation import DriveEstimator
    return DriveEstimator(estimator_library(), mode=mode, n1=0.89)


@lru_cache(maxsize=1)
def good_window():
    """A denoised onset-like window (smooth a1 step, a2 impact later): finite features."""
    t = np.arange(WINDOW_LENGTH) * PERIOD_S
    a1 = np.where(t < 0.004, 0.0, -40.0) + np.where(t > 0.025, 60.0 * np.exp(-(t - 0.025) / 0.004), 0.0)
    a2 = np.where(t > 0.025, -300.0 * np.exp(-(t - 0.025) / 0.003), 0.0) + 2.0
    from backlash_monitor.denoise import denoise_pair
    return denoise_pair(a1, a2)


@st.composite
def estimator_windows(draw):
    a1, a2 = draw(window_pairs(lengths=(2048, 2048, 2048, 2048, 2047, 4096, 100, 0)))
    kind = draw(st.sampled_from(["onset", "onset", "return", "", "Onset", "onset\x00"]))
    period = draw(st.sampled_from([None, PERIOD_S, PERIOD_S, 1e-5, 0.0, float("nan"), -PERIOD_S]))
    offset = st.one_of(st.floats(-3.0, 3.0), st.sampled_from([0.0, float("nan"), float("inf"), 1e308, -5e-324]))
    offsets = draw(st.one_of(st.none(), st.tuples(offset, offset)))   # the window's sensor offsets
    return a1, a2, kind, period, offsets


def check_estimate(estimator, window, follow_with_good=True):
    from backlash_monitor.estimation import OFFSET_UNKNOWN
    INPUTS["estimator"] += 1
    a1, a2, kind, period, offsets = window
    widths = set(np.round(estimator.widths_m, 12))
    before = {s: len(f) for s, f in estimator.fusion.items()}
    waiting = estimator.waiting_for_offset
    estimates = estimator.estimate(a1, a2, kind, period, sensor_offsets=offsets)
    reason = estimator.last_reasons[0]
    if reason == OFFSET_UNKNOWN:   # an onset window whose offset is not known: waits, no fault
        assert estimates == [] and kind == "onset" and not np.isfinite(offsets).all()
        assert estimator.waiting_for_offset == waiting + 1
        assert {s: len(f) for s, f in estimator.fusion.items()} == before   # nothing fused
    elif reason is not None:
        assert estimates == [] and reason in REASONS
        assert {s: len(f) for s, f in estimator.fusion.items()} == before   # nothing fused
    for e in estimates:
        assert round(e.width_m, 12) in widths and round(e.fused_width_m, 12) in widths
        assert e.b_vector.shape == (6,) and np.isfinite(e.b_vector).all() and (e.b_vector >= 0).all()
    if kind == "onset" and reason is None:
        assert len(estimates) == len(estimator.signals)
    if follow_with_good:
        g1, g2 = good_window()
        good = estimator.estimate(g1, g2, "onset", PERIOD_S)
        assert len(good) == len(estimator.signals), estimator.last_reasons


# ------------------------------------------------------------------ fusion
@st.composite
def b_sequences(draw):
    entry = st.one_of(st.floats(0, 1e3), st.floats(allow_nan=True, allow_infinity=True),
                      st.sampled_from([0.0, 1e308, -1.0, 5e-324]))
    return draw(st.lists(st.lists(entry, min_size=6, max_size=6), min_size=1, max_size=20)), \
        draw(st.sampled_from(["sum_normalised_b", "vote", "trimmed_normalised_b"])), \
        draw(st.integers(1, 10))


def check_fusion(bs, rule, events):
    from backlash_monitor.classifier.fusion import WidthFusion
    INPUTS["fusion"] += 1
    widths = np.array([0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01])
    fusion = WidthFusion(widths, window_events=events, rule=rule)
    good = 0
    for b in bs:
        b = np.array(b)
        est = fusion.add(b)
        good += bool(np.isfinite(b).all() and (b >= 0).all())
        assert len(fusion) == min(good, events)
        if good:
            assert est is not None and est.width_m in widths and 1 <= est.events <= events
        else:
            assert est is None
