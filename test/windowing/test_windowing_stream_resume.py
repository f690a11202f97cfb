"""The windowing stage (chain.stage.WindowingStage, fed by ChunkJoiner as the live node and ``analyze``
do) resumes after any cluster of stream faults: swaps, lost chunks, duplicates, index jumps,
restarts and bad ranges close together, then a clean stream. Its clean ranges are fed to the
detector again after at most RESTART_CONFIRM_RANGES of them are dropped, windows come again,
and the offline BlockFeeder gives the same windows and fault counts as the ranges one by one.

(bench/reliability.py found two such clusters on main -- test/chain/test_fuzz_cores.py keeps
them; this property generates the class.)"""
import pytest
from hypothesis import HealthCheck, given, settings

import fuzz_cores as fc
from backlash_monitor.chain.block_feeder import BlockFeeder
from backlash_monitor.chain.stage import RESTART_CONFIRM_RANGES, WindowingStage

SETTINGS = settings(max_examples=300, deadline=None, database=None, derandomize=True,
                    suppress_health_check=list(HealthCheck))


def dropped_clean_ranges(sizes, faults, order, resync_samples=50_000):
    trace = []
    windows, stage, _, clean_from = fc.run_stream(sizes, faults, order, resync_samples, trace=trace)
    clean = [fed for lo, _, fed in trace if lo >= clean_from]
    return clean.count(False), windows, clean_from, stage, trace


@pytest.mark.slow
@SETTINGS
@given(fc.clustered_chunk_streams())
def test_a_clean_stream_after_clustered_faults_is_windowed_again(stream):
    dropped, windows, clean_from, stage, _ = dropped_clean_ranges(*stream)
    counts = dict(stage.faults.counts)
    assert dropped <= RESTART_CONFIRM_RANGES, (stream, counts)
    assert [w for w, lo in windows if lo >= clean_from], (stream, counts)
    if dropped:          # a dropped range is counted, never silently lost
        assert stage.faults.counts["out_of_order"] > 0, (stream, counts)


@settings(SETTINGS, max_examples=60)
@given(fc.clustered_chunk_streams())
def test_a_short_resync_distance_resumes_too(stream):
    _, windows, clean_from, stage, _ = dropped_clean_ranges(*stream, resync_samples=1000)
    assert [w for w, lo in windows if lo >= clean_from], (stream, dict(stage.faults.counts))


def _key(windows):
    return [(w.entry_sample_index, w.kind, w.signals["a1"].tobytes(), r.first_sample_index)
            for w, r in windows]


@settings(SETTINGS, max_examples=60)
@given(fc.clustered_chunk_streams())
def test_offline_blocks_give_the_live_windows_and_faults_after_clustered_faults(stream):
    _, _, _, _, trace = dropped_clean_ranges(*stream)
    ranges = [joined for _, joined, _ in trace]
    live = WindowingStage(window_length=fc.WINDOW_LENGTH)
    ref = []
    for r in ranges:
        ref += [(w, r) for w in live.feed(r)[0]]
    offline = WindowingStage(window_length=fc.WINDOW_LENGTH)
    feeder = BlockFeeder(offline, block_samples=3000)
    got = []
    for r in ranges:
        got += feeder.add(r)[0]
    got += feeder.flush()[0]
    assert _key(got) == _key(ref), stream
    assert offline.faults.counts == live.faults.counts, stream
    assert (offline.lost_samples, offline.fed_samples) == (live.lost_samples, live.fed_samples)
