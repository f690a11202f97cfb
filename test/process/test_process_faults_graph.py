"""Process faults in the multi-process graph (`pipeline --processes`), with SIGKILL.

Each node of the graph is killed in turn while the stream runs; with `--restart on-failure` the
pipeline names it, starts it again, the other nodes keep running (no other fault), and estimates
resume. What is lost is bounded: a restarted denoise or classifier node loses nothing (the
window topics keep the last 1000 windows for a late reader; the classifier and the pipeline skip
what they had already seen), a restarted windowing node loses the chunks published while it was
down, a restarted plant starts a new stream. Without a restart policy the run ends, naming the
node, with the summary and exit code 1. A killed pipeline takes its node processes with it.
"""
import importlib.util
import os
import re
import signal
import subprocess
import time

import pytest

from process_fault_helpers import ONSET, PipelineRun, gone, wait_until

ONSET_PERIOD_S = 0.25      # the simulated drive's onsets: 0.054 s + k * 0.25 s
FIRST_ONSET_S = 0.054


@pytest.fixture
def pipeline(ros_env):
    runs = []

    def start(*args):
        run = PipelineRun(list(args), ros_env)
        runs.append(run)
        return run

    yield start
    for run in runs:
        run.kill_group()


def event_index(t_s: float) -> int:
    return round((t_s - FIRST_ONSET_S) / ONSET_PERIOD_S)


RATE = 2.0                 # simulated seconds per wall second
# How long a run may take to print its first estimate, or to end [s]: on a 2-core machine with a
# busy loop per core beside it (machine_load 'hog') and other jobs, four node processes start
# (numba, DDS discovery) in tens of seconds; a timeout, never a measured time.
TIMEOUT_S = 300


def stream_time_at(run, wall_s: float) -> float:
    """Stream time [s] of the first stream at the wall-clock time ``wall_s`` (the plant logs,
    stamped with the wall clock, when it starts streaming)."""
    start = run.stream_start_wall_s()
    assert start is not None, run.output
    return (wall_s - start) * RATE


# The windowing node re-synchronises on a stream whose index restarts at 0 with the input checks
# of issue 9 (backlash_monitor/input_faults.py, branch inputs; with it merged this case passed).
_RESYNC = importlib.util.find_spec("backlash_monitor.windowing.faults") is not None


@pytest.mark.process
@pytest.mark.ros
# Every node on an idle machine; the denoise node (whose restart must lose nothing) also beside a CPU hog: the hog
# costs the suite two cores for the test's length, and the restart path under load is the pipeline's, the same for
# every node.
@pytest.mark.parametrize("node, machine_load", [("windowing", "idle"), ("denoise", "idle"), ("classifier", "idle"),
                                                 pytest.param("plant_simulator", "idle", marks=pytest.mark.xfail(
        not _RESYNC, strict=True, reason="the windowing node does not re-synchronise yet on a stream whose "
        "sample index restarts at 0 (issue 9, branch inputs): it drops the new stream's chunks as "
        "out of order until their index passes the old stream's, then stamps its windows with "
        "the old stream's start")), ("denoise", "hog")], indirect=["machine_load"])
def test_a_killed_node_is_restarted_and_estimates_resume(node, pipeline, machine_load):
    run = pipeline("--duration", "30", "--rate-factor", str(RATE), "--events", "40",
                   "--restart", "on-failure")
    assert run.wait_for(lambda line: ONSET.match(line), timeout_s=TIMEOUT_S), run.output
    victim = run.pids[node]
    killed_wall_s = time.time()
    os.kill(victim, signal.SIGKILL)
    code = run.finish(timeout_s=TIMEOUT_S)
    out = run.output
    assert code == 0, out
    faults = [line for line in run.lines if line.startswith("pipeline: node ") and "pid" in line
              and "processes" not in line]
    # named, with its signal; the other three processes kept running (no other fault)
    assert len(faults) == 1, out
    assert re.match(rf"pipeline: node {node} \(pid {victim}\) was killed by signal SIGKILL \(9\); "
                    r"restarted as pid \d+", faults[0]), out
    fault_at = run.lines.index(faults[0])
    onsets = run.onsets()
    before = [t for i, t in onsets if i < fault_at]
    after = [t for i, t in onsets if i > fault_at]
    assert before and after, out
    # every event printed complete (the last, cut by --events, may miss a signal) is right
    assert all(run.lines[i].count(" ok") == 4 for i, _ in onsets if "a1+a2" in run.lines[i]), out
    if node == "plant_simulator":
        # a new stream from sample 0 (a restarted plant): its onsets are classified too (the old
        # stream's, printed in order, come after the last one before the fault)
        assert min(after) <= before[-1], out
    else:
        # windows the killed process cannot have made: their entry came after the kill
        killed_at_s = stream_time_at(run, killed_wall_s)
        assert after[-1] > killed_at_s + 1.0, (killed_at_s, out)
    if node in ("denoise", "classifier"):
        # nothing lost: every onset of the stream, in order, each once (from the second: the first
        # comes before one whole load period, which the sensor offset estimate needs)
        assert [event_index(t) for t in before + after] == list(range(1, len(before + after) + 1)), out
    assert "summary:" in out and f"node fault: node {node} (pid {victim})" in out


@pytest.mark.process
@pytest.mark.ros
def test_without_a_restart_policy_a_killed_node_ends_the_run_with_its_name_and_summary(pipeline):
    run = pipeline("--duration", "30", "--rate-factor", "2")
    assert run.wait_for(lambda line: ONSET.match(line), timeout_s=TIMEOUT_S), run.output
    victim = run.pids["denoise"]
    os.kill(victim, signal.SIGKILL)
    code = run.finish(timeout_s=TIMEOUT_S)
    out = run.output
    assert code == 1, out
    assert f"pipeline: node denoise (pid {victim}) was killed by signal SIGKILL (9)" in out
    assert "restarted" not in out
    assert "summary:" in out and f"node fault: node denoise (pid {victim})" in out
    assert all(gone(pid) for pid in run.pids.values()), run.pids     # the others were stopped
    assert "Traceback" not in run.stderr


@pytest.mark.process
@pytest.mark.ros
def test_a_pipeline_killed_with_sigkill_takes_its_node_processes_with_it(pipeline, machine_load):
    run = pipeline("--duration", "60", "--rate-factor", "1")
    assert run.wait_for(lambda line: ONSET.match(line), timeout_s=TIMEOUT_S), run.output
    pids = dict(run.pids)
    assert len(pids) == 4 and not any(gone(p) for p in pids.values())
    os.kill(run.process.pid, signal.SIGKILL)
    run.process.wait(timeout=30)
    # the watchdog's 0.5 s poll and 5 s hard exit, and a clean ROS shutdown on a loaded machine
    assert wait_until(lambda: all(gone(p) for p in pids.values()), timeout_s=30.0), \
        {name: gone(p) for name, p in pids.items()}


# Another subscriber of every plant/* topic in the domain, there before the graph starts: a
# recorder. Before, the plant counted its subscriptions as the windowing node's and started the
# stream before the windowing node had matched.
@pytest.mark.process
@pytest.mark.ros
def test_estimates_arrive_with_a_recorder_of_plant_topics_in_the_same_domain(pipeline, ros_env,
                                                                             tmp_path):
    from ament_index_python.packages import get_package_prefix
    recorder = subprocess.Popen(
        [os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", "record"),
         "--ros-args", "-p", f"output:={tmp_path / 'other.mcap'}", "-p", "topics:=/plant/*",
         "-p", "discovery_period_s:=0.02"],
        env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
        start_new_session=True)
    try:
        run = pipeline("--duration", "2", "--rate-factor", "2")
        code = run.finish(timeout_s=TIMEOUT_S)
        out = run.output
        assert code == 0, out
        lines = [line for line in run.lines if ONSET.match(line)]
        assert [event_index(float(ONSET.match(line).group(1))) for line in lines] == \
            list(range(1, 8)), out       # all 8 onsets of 2 s but the first (no sensor offset yet)
        assert all(line.count(" ok") == 4 for line in lines), out
        assert "/windowing on a1, a2, angle_difference" in run.stderr, run.stderr
    finally:
        os.killpg(recorder.pid, signal.SIGINT)
        try:
            recorder.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(recorder.pid, signal.SIGKILL)
            recorder.communicate()
