"""Fuzz tests of the signal chain's cores (hypothesis; the properties are in fuzz_cores.py, which
bench/reliability.py runs with >= 10,000 examples each). No exception escapes a core given any
input; windows have the configured length and finite samples; every estimate is a candidate
width with 6 finite, non-negative B entries; after a bad chunk or window the next good one is
classified."""
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

import fuzz_cores as fc
from backlash_monitor.chain.joiner import ChunkJoiner, JoinedRange
from backlash_monitor.chain.stage import WindowingStage

SETTINGS = settings(max_examples=150, deadline=None, database=None, derandomize=True,
                    suppress_health_check=list(HealthCheck))


@SETTINGS
@given(fc.chunk_streams())
def test_fuzz_windowing_stage_survives_faulty_streams_and_resumes(stream):
    fc.check_windowing(*stream)


@SETTINGS
@given(fc.chunk_streams())
def test_fuzz_windowing_stage_with_a_short_resync_distance(stream):
    fc.check_windowing(*stream, resync_samples=1000)


@SETTINGS
@given(fc.detector_chunks())
def test_fuzz_detector_and_capture_take_any_chunk(chunks):
    fc.check_detector(chunks)


@SETTINGS
@given(fc.window_pairs())
def test_fuzz_denoise_gives_finite_windows_or_a_reason(pair):
    fc.check_denoise(*pair)


@pytest.fixture(scope="module")
def estimators():
    return {mode: fc.make_estimator(mode) for mode in ("shape", "paper")}


@pytest.mark.parametrize("mode", ["shape", "paper"])
def test_fuzz_estimator_classifies_or_rejects(estimators, mode):
    estimator = estimators[mode]

    @settings(max_examples=100, deadline=None, database=None, derandomize=True,
              suppress_health_check=list(HealthCheck))
    @given(fc.estimator_windows())
    def run(window):
        fc.check_estimate(estimator, window)
    run()


@SETTINGS
@given(fc.b_sequences())
def test_fuzz_fusion_always_gives_a_candidate(seq):
    fc.check_fusion(*seq)


# ---- the faults the issue named, each once, with its reason (the fuzz finds the rest) ----
def test_a_nan_chunk_is_dropped_counted_and_the_windows_resume():
    windows, stage = fc.check_windowing([1000] * 30, {3: "nan"}, fc.SIGNALS)
    assert stage.faults.counts["non_finite_samples"] == 1
    assert stage.lost_samples == 1000
    assert min(w.entry_sample_index for w, _ in windows if w.entry_sample_index > 4000) < 8000


def test_a_restart_at_zero_resynchronises():
    windows, stage = fc.check_windowing([1000] * 30, {12: "restart"}, fc.SIGNALS)
    assert stage.faults.counts["stream_restart"] == 1
    # the stream from 0 again: windows at the same offsets as the first time
    entries = [w.entry_sample_index for w, lo in windows if lo >= 12000]
    assert entries and min(entries) < 5000


def test_a_far_jump_is_a_counted_gap_and_the_windows_resume():
    windows, stage = fc.check_windowing([1000] * 30, {5: "far_jump"}, fc.SIGNALS)
    assert stage.faults.counts["gap"] == 1 and stage.lost_samples >= 10 ** 12
    assert max(w.entry_sample_index for w, _ in windows) > 10 ** 12


def test_a_lost_range_after_a_window_is_counted():
    # no window open at chunk 6 (the windows of 1250 and 3500 are complete by 5748)
    windows, stage = fc.check_windowing([1000] * 30, {6: "lose_chunk"}, fc.SIGNALS)
    assert stage.faults.counts["gap"] == 1 and stage.lost_samples == 1000


@pytest.mark.parametrize("period", [0.0, -2e-5, float("nan"), float("inf")])
def test_a_bad_sample_period_is_dropped_not_raised(period):
    stage = WindowingStage()
    joined = JoinedRange(0, period, {s: np.zeros(100) for s in stage.input_signals})
    assert stage.feed(joined) == ([], [])
    assert stage.faults.counts["bad_sample_period"] == 1


def test_unequal_lengths_in_one_range_are_dropped():
    stage = WindowingStage()
    joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
    joiner.add("a1", 0, 2e-5, np.zeros(100))
    joiner.add("a2", 0, 2e-5, np.zeros(99))
    joined = joiner.add("angle_difference", 0, 2e-5, np.zeros(100))
    assert stage.feed(joined) == ([], [])
    assert stage.faults.counts["length_mismatch"] == 1


def test_a_range_still_incomplete_at_the_end_is_counted():
    joiner = ChunkJoiner(("a1", "a2"))
    joiner.add("a1", 0, 2e-5, np.zeros(10))
    assert joiner.flush() == 1 and joiner.faults.counts["incomplete_range"] == 1
    assert joiner.pending == {}


def test_a_restart_does_not_join_new_chunks_to_an_old_incomplete_range():
    # found by the fuzz: chunk 0 lost its a1, so a2/angle of range 0 waited in the joiner; the
    # restarted stream's range 0 completed it with its own a1 (a range of two streams)
    windows, stage = fc.check_windowing([200] * 10 + [4000] * 7, {0: "lose_signal", 6: "restart"},
                                        fc.SIGNALS)
    assert stage.faults.counts["stream_restart"] == 1
    assert stage.faults.counts["incomplete_range"] == 1 and not stage.faults.counts["out_of_order"]


# ---- found by bench/reliability.py (hypothesis), kept as regressions ----
@pytest.mark.parametrize("order", [fc.SIGNALS, tuple(reversed(fc.SIGNALS))])
def test_a_late_chunk_of_the_old_stream_after_a_restart_does_not_stall_the_stage(order):
    """The stream issue 19 quotes: an index jump at chunk 0, chunks 9 and 10 swapped, a restart at 10.
    Chunk 9 (the old stream's) arrives right after the restart; it used to be taken as a forward
    gap of the new stream, whose every following chunk was then 'out of order': no window again."""
    sizes = [200] * 8 + [2500, 4000] + [200] * 6 + [1000] + [4000] * 4 + [3700]
    windows, stage = fc.check_windowing(sizes, {0: "jump", 9: "swap", 10: "restart"}, order)
    assert stage.faults.counts["stream_restart"] == 1 and stage.faults.counts["out_of_order"] == 1


@pytest.mark.parametrize("order", [fc.SIGNALS, tuple(reversed(fc.SIGNALS))])
def test_a_stray_chunk_of_the_old_stream_after_a_restart_does_not_move_the_new_one(order):
    """bench/reliability.py on main (bench/results.json): chunks 10 and 11 swapped (the swap holds
    one chunk: 10 is lost, 11 comes late), a restart at 12. The old stream's chunk 11 came right
    after the restart chunk; it did not continue the old stream (10 lost), so it was taken as a gap
    of the new stream, whose every later chunk was then 'out of order' (8): no window again. The
    stray is dropped now (out_of_order), the new stream goes on from the restart chunk."""
    sizes = [200] * 9 + [2500, 4000, 4000] + [200] * 5 + [1000, 4000, 4000, 4000, 3700]
    windows, stage = fc.check_windowing(sizes, {10: "swap", 11: "swap", 12: "restart"}, order)
    assert stage.faults.counts == {"stream_restart": 1, "out_of_order": 1}
    assert stage.lost_samples == 0
    # the stream from 0 again: windows at the same offsets as the first time
    entries = [w.entry_sample_index for w, lo in windows if lo >= 12_500]
    assert entries and min(entries) < 5000


def test_the_old_stream_going_on_after_a_stray_restart_chunk_resumes():
    """A stray chunk at index 0 in the middle of a stream (a restart that was none): the stream
    going on is taken back after RESTART_CONFIRM_RANGES ranges, and its windows resume."""
    from backlash_monitor.chain.stage import RESTART_CONFIRM_RANGES
    data, _ = fc.synthetic_stream()
    stage = WindowingStage(window_length=fc.WINDOW_LENGTH)
    windows = []
    chunks = [(lo, lo) for lo in range(0, 12_000, 1000)] + [(0, 0)] + [(lo, lo) for lo in range(12_000, 30_000, 1000)]
    for index, lo in chunks:
        arrays = {s: data[s][lo:lo + 1000].copy() for s in fc.SIGNALS}
        w, _ = stage.feed(JoinedRange(index, fc.PERIOD_S, arrays))
        windows += [(x, index) for x in w]
    assert stage.faults.counts["stream_restart"] == 2          # to the stray, and back
    assert stage.faults.counts["out_of_order"] == RESTART_CONFIRM_RANGES - 1
    assert [w for w, index in windows if w.start_sample_index > 12_000 + RESTART_CONFIRM_RANGES * 1000]


@pytest.mark.parametrize("order", [fc.SIGNALS, tuple(reversed(fc.SIGNALS))])
def test_a_late_old_chunk_whose_index_fills_a_lost_new_one_is_told_by_its_stamp(order):
    """bench/reliability.py (stop 50): chunks 0 and 1 swapped (0 lost, 1 late), a restart at 2, the
    new stream's next chunk lost. The old chunk 1 arrives right after the restart chunk with the
    index the lost one would have had: by index it continues the new stream, and without stamps it
    was fed into it, silently (nothing counted). Its stamp lies a restart's delay before its place
    in the new stream: it is dropped (out_of_order) and the lost chunk is a gap of its length."""
    sizes, faults = [200] * 150, {0: "swap", 1: "swap", 2: "restart", 3: "lose_chunk"}
    windows, stage, _, clean_from = fc.run_stream(sizes, faults, order)
    assert stage.faults.counts == {"out_of_order": 1, "gap": 1}
    assert stage.lost_samples == 200
    (reason, detail), = [f for f in stage.faults.take() if f[0] == "out_of_order"]
    assert "stamped 1.0" in detail and "late range of an earlier stream" in detail, detail
    assert [w for w, lo in windows if lo >= clean_from]
    # without stamps the two cannot be told apart: index alone places the old chunk in the new stream
    _, blind, _, _ = fc.run_stream(sizes, faults, order, stamps=False)
    assert blind.faults.total == 0 and blind.lost_samples == 0


def test_a_stamp_that_steps_back_in_a_settled_stream_is_not_judged():
    """A settled stream (two ranges in a row, no restart) is placed by index alone: a publisher
    clock stepped back by 5 s (an NTP correction) loses nothing."""
    data, _ = fc.synthetic_stream()
    stage = WindowingStage(window_length=fc.WINDOW_LENGTH)
    windows = []
    for lo in range(0, 30_000, 1000):
        arrays = {s: data[s][lo:lo + 1000].copy() for s in fc.SIGNALS}
        stamp = fc.stamp_at(100.0 + lo * fc.PERIOD_S - (5.0 if lo >= 10_000 else 0.0))
        w, _ = stage.feed(JoinedRange(lo, fc.PERIOD_S, arrays, stamp))
        windows += w
    assert stage.faults.total == 0 and stage.fed_samples == 30_000
    assert [w for w in windows if w.start_sample_index > 10_000]


def test_an_accelerometer_sample_beyond_its_declared_range_is_a_counted_fault():
    """A finite sample beyond sensors.accelerometer_range_m_s2 (config/windowing.yaml) in a1 is
    dropped and counted as a NaN is (out_of_range_samples); the windows resume after it. The same
    stage runs in the live windowing node and in analyze."""
    data, _ = fc.synthetic_stream()
    stage = WindowingStage(window_length=fc.WINDOW_LENGTH)
    windows = []
    for lo in range(0, 30_000, 1000):
        arrays = {s: data[s][lo:lo + 1000].copy() for s in fc.SIGNALS}
        if lo == 3000:
            arrays["a1"][17] = 1e300
        w, _ = stage.feed(JoinedRange(lo, fc.PERIOD_S, arrays))
        windows += w
    assert stage.faults.counts == {"out_of_range_samples": 1}
    assert stage.lost_samples == 1000 and stage.fed_samples == 29_000
    assert all(np.abs(w.signals["a1"]).max() < 1960 for w in windows)
    assert [w for w in windows if w.start_sample_index > 4000]
    assert WindowingStage(accelerometer_range_m_s2=1e301).check(
        JoinedRange(3000, fc.PERIOD_S, {s: np.full(10, 1e300) for s in fc.SIGNALS}))[0] is None
