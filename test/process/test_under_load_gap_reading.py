"""How bench/_reliability/under_load.py reads a gap in a killed windowing node's onset estimates: its own outage when
the gap holds the kill (the stream's place at the kill, or the pipeline's last estimate before it) or begins within
its own queue before it; any other gap is an upstream loss. The case of stop 49's second run: the estimates ran 2.9 s
behind the stream under load, and the gap began 0.15 s of stream before the kill."""
import importlib.util
from pathlib import Path

BENCH = Path(__file__).resolve().parents[2] / "bench" / "_reliability" / "under_load.py"


def _under_load():
    spec = importlib.util.spec_from_file_location("under_load_bench", BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_a_gap_that_holds_the_kill_is_the_killed_nodes_own_even_when_the_estimates_ran_behind():
    ul = _under_load()
    gap = (35.304, 36.553, 4)
    assert ul.own_outage_gaps([gap], before=[32.555], at_kill=[35.45]) == [gap]
    # by the fault line's last estimate alone it read as an upstream loss (2.75 s before the gap)
    assert ul.own_outage_gaps([gap], before=[32.555], at_kill=[]) == []


def test_a_gap_away_from_every_kill_is_an_upstream_loss():
    ul = _under_load()
    far = (20.0, 21.0, 4)                    # 5 s after the kill, 8 s after its last estimate
    near = (14.9, 15.8, 3)                   # begins 0.1 s before the kill
    assert ul.own_outage_gaps([far, near], before=[12.0], at_kill=[15.0]) == [near]
    # a gap ending before the mark (more than the queue before it) is not the outage's either
    assert ul.own_outage_gaps([(10.0, 12.5, 5)], before=[15.0], at_kill=[15.2]) == []
