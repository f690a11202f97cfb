"""The pipeline's live view after a node restart (no ROS): an estimate re-sent by a restarted
classifier counts once, a restarted plant's new stream is not merged with the old one, and a
range of the stream with no onset estimate is named in the summary."""
import pytest
import io
from types import SimpleNamespace

from backlash_monitor.nodes.pipeline import PipelineConsole

PERIOD_S = 2e-5
SIGNALS = ("a1", "a2", "a1+a2")


def estimate(entry: int, signal: str, stream_start_s: float = 100.0, width_m: float = 0.005):
    t = stream_start_s + entry * PERIOD_S
    return SimpleNamespace(
        signal_name=signal, entry_sample_index=entry, entry_kind="onset", mode="shape",
        header=SimpleNamespace(stamp=SimpleNamespace(sec=int(t), nanosec=int(round((t % 1) * 1e9)))),
        width_m=width_m, true_width_m=0.005, continuous_width_m=width_m, fused_width_m=width_m,
        fused_events=1, b_margin=2.0, fused_continuous_width_m=width_m)


def onset(k: int) -> int:
    """Entry index of the simulated drive's k-th onset (0.054 s + k * 0.25 s)."""
    return int(round((0.054 + 0.25 * k) / PERIOD_S))


def feed(view, entries, **kw):
    for entry in entries:
        for signal in SIGNALS:
            view.on_estimate(estimate(entry, signal, **kw))


@pytest.mark.ros
def test_a_re_sent_estimate_counts_once():
    view = PipelineConsole(0.005, SIGNALS, PERIOD_S, out=io.StringIO())
    feed(view, [onset(k) for k in range(4)])
    feed(view, [onset(k) for k in range(4)])          # a restarted classifier sends them again
    assert view.repeated == 12
    assert view.tally["a1"].estimates == 4 and view.completed_events == 4
    assert "repeated estimates ignored: 12" in view.summary()
    assert view.onset_gaps() == []


@pytest.mark.ros
def test_a_gap_in_the_onsets_is_named_with_the_onsets_missing():
    view = PipelineConsole(0.005, SIGNALS, PERIOD_S, out=io.StringIO())
    feed(view, [onset(k) for k in (0, 1, 2, 3, 9, 10, 11)])     # 4..8 lost (a windowing restart)
    (before, after, missing), = view.onset_gaps()
    assert (round(before, 3), round(after, 3), missing) == (0.804, 2.304, 5)
    assert "onset estimates missing: t=0.804..2.304 s (5 onsets at the median spacing)" \
        in view.summary()


@pytest.mark.ros
def test_a_restarted_plants_new_stream_is_kept_apart_from_the_old_one():
    view = PipelineConsole(0.005, SIGNALS, PERIOD_S, out=io.StringIO())
    feed(view, [onset(k) for k in range(6)], stream_start_s=100.0)
    feed(view, [onset(k) for k in range(6)], stream_start_s=103.7)     # from sample 0 again
    assert view.repeated == 0 and view.completed_events == 12
    assert len(view.onset_entries) == 12
    assert view.onset_gaps() == []          # neither stream has a gap


@pytest.mark.ros
def test_a_node_fault_is_printed_at_once_and_listed_in_the_summary():
    out = io.StringIO()
    view = PipelineConsole(0.005, SIGNALS, PERIOD_S, out=out)
    feed(view, [onset(0)])
    view.on_fault("node denoise (pid 7) was killed by signal SIGKILL (9)")
    assert out.getvalue().splitlines()[-1] == (
        "pipeline: node denoise (pid 7) was killed by signal SIGKILL (9); last estimate before it: "
        "event at t=0.054 s")
    assert "node fault: node denoise (pid 7) was killed by signal SIGKILL (9)" in view.summary()
