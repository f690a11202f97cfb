"""A hop of `pipeline --processes` stalls (SIGSTOP for 3 s, then SIGCONT): nothing is lost (issue 34).

A stalled process takes no message: the chunk and window topics (reliable, 1000 deep) hold what
comes meanwhile, and after SIGCONT the signals' topics arrive seconds apart (a chunk the
transport dropped while the reader's queue was full is sent again; the executor takes one
message per topic per wake-up). With a joiner that gave a range up after 16 others waited, one
3 s stall of the windowing process lost 109 of 120 onsets (docs/graph.md, "While a consumer is
away"). Now every onset of the stream is classified, in order, once, whichever hop stalls, on an
idle machine and beside a CPU hog.
"""
import os
import re
import signal
import time

import pytest

from process_fault_helpers import ONSET, PipelineRun

ONSET_PERIOD_S = 0.25      # the simulated drive's onsets: 0.054 s + k * 0.25 s
FIRST_ONSET_S = 0.054
STALL_S = 3.0
INCOMPLETE = re.compile(r"incomplete chunk ranges (\d+)")


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("node", ["windowing", "denoise", "classifier"])
def test_a_stalled_hop_loses_no_onset(node, ros_env, machine_load):
    run = PipelineRun(["--duration", "20", "--rate-factor", "2"], ros_env)
    try:
        assert run.wait_for(lambda line: ONSET.match(line), timeout_s=300), run.output
        victim = run.pids[node]
        time.sleep(1.0)
        os.kill(victim, signal.SIGSTOP)
        try:
            time.sleep(STALL_S)
        finally:
            os.kill(victim, signal.SIGCONT)
        code = run.finish(timeout_s=300)
    finally:
        run.kill_group()
    out = run.output
    assert code == 0, out
    assert "onset estimates missing" not in out, out
    # every onset of the 20 s stream (0.054 s + k 0.25 s), in order, each once (from the second:
    # the first comes before one whole load period, which the sensor offset estimate needs)
    events = [round((t - FIRST_ONSET_S) / ONSET_PERIOD_S) for _, t in run.onsets()]
    assert events == list(range(1, 80)), out
    windowing = [line for line in run.lines if "diagnostics" in line and "windowing" in line]
    assert windowing and INCOMPLETE.search(windowing[-1]).group(1) == "0", out
