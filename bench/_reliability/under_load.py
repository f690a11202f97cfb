"""Node kills under load (issue 34): a node that dies loses nothing upstream, with every core busy.

    python bench/_reliability/under_load.py    # one JSON object on stdout, progress on stderr

``run()`` returns {"under_load_kill_onsets_lost", "under_load_kills", "under_load_ros_test_runs_passed"
(when measured), "cases": [...]} (bench/reliability.py puts the first keys at its top level).

For each of the four chain nodes (plant_simulator, windowing, denoise, classifier), one
`pipeline --processes --restart on-failure --max-restarts 10` at x2 real time, in one process per
node, beside a CPU hog (one busy loop per core at normal priority, started before the pipeline and
killed after it: process_fault_helpers.CpuHog). After the first estimate the node is SIGKILLed 10
times; before each next kill the pipeline has named the restart and printed an onset estimate
after it (for the windowing node: of an event over 1 s of stream after the last estimate before
the kill, which the new process windowed). Then the pipeline is interrupted (SIGINT: it prints its summary) and the gaps in the
onset estimates it reports ("onset estimates missing: t=a..b s (n onsets ...)") are read, GRACE_S (15 s)
after the last restarted process's first estimate (the history reaches it late under load).

``onsets_lost_upstream`` (summed into under_load_kill_onsets_lost), per node:

- denoise, classifier: every onset missing. The hops upstream (plant, windowing, and denoise for
  the classifier) kept running, and the window topics keep the last 1000 windows for the
  restarted process: nothing may be missing.
- windowing: the onsets missing in gaps that no windowing outage explains. The chunk topics are
  volatile: what the plant published while the windowing process was down is the killed node's
  own loss (docs/graph.md): a gap that begins at most 2 s of stream before the "last estimate
  before it" of one of its kills (the pipeline's fault line; the windows still queued in the
  killed process go with it), or before the stream's place at a kill, and ends after it
  (``own_outage_gaps``). Any other gap is an upstream loss.
- plant_simulator: every onset missing inside a stream (a restarted plant starts a new stream
  at sample 0: the end of the killed one is its own, not a gap).

A gap that begins at the last estimate before a kill while the estimates were at least QUEUE_FULL_S (0.9 x 125 s)
of stream behind counts apart (``onsets_lost_beyond_history``, summed into
under_load_kill_onsets_lost_beyond_history): the killed node held about a full history of windows in its queue,
more than its upstream writer keeps for a restarted reader (the bound of docs/graph.md "While a consumer is away";
the chain falls that far behind only under more load than the hog alone).

Each case also records where the stream was at each kill (``stream_at_kills_s``, from the plant's
stream start) and how far the estimates were behind it (``estimates_behind_at_kills_s``): a node
far behind has more queued in it, which the upstream writers must still hold.

``under_load_ros_test_runs_passed`` is measured apart (`tools/ros_tests_under_load.py`, several
minutes per run): this module reports it when BENCH_ROS_TEST_RUNS_JSON names that tool's output.
"""
from __future__ import annotations

import json
import os
import pathlib
import re
import signal
import sys
import time

REPO = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "test"))

from process_fault_helpers import ONSET, CpuHog, PipelineRun  # noqa: E402

RATE = 2.0
KILLS = 10
NODES = ("plant_simulator", "windowing", "denoise", "classifier")
DURATION_S = 400          # simulated; the run is interrupted after the last kill has been survived
TIMEOUT_S = 300           # for a restart or an estimate under load (a timeout, not a measurement)
HISTORY_S = 1000 / 8.0    # the window topics' history: 1000 windows at 8 per s of stream (4 onsets, 4 returns)
QUEUE_FULL_S = 0.9 * HISTORY_S   # estimates this far behind: the killed node's queue held about a full history
OWN_QUEUE_S = 2.0         # a killed windowing process's own queue: onsets up to this far [s of stream] before its mark
GRACE_S = 15.0            # after the last restart's first estimate: read on this long, then interrupt [s] (a
                          # loaded classifier takes seconds for the up to 1000 windows of the history)
MISSING = re.compile(r"^onset estimates missing: t=([0-9.]+)\.\.([0-9.]+) s \((\d+) onsets")
FAULT = re.compile(r"^pipeline: node (\w+) \(pid (\d+)\) was killed by signal SIGKILL \(9\); "
                   r"restarted as pid (\d+)(?:; last estimate before it: event at t=([0-9.]+) s)?")


def _env(offset: int) -> dict:
    env = dict(os.environ)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    # the same domains as processes.py (ROS_DOMAIN_ID + 1 ...): the modules run one after another
    env["ROS_DOMAIN_ID"] = str((int(os.environ.get("ROS_DOMAIN_ID", "50")) + offset) % 101 + 1)
    env["PYTHONUNBUFFERED"] = "1"
    return env


def kill_repeatedly(node: str, offset: int) -> dict:
    case = {"case": f"kill_{node}_x{KILLS}_under_load", "kills": 0}
    killed_wall_s: list[float] = []
    run = PipelineRun(["--duration", str(DURATION_S), "--rate-factor", str(RATE), "--restart",
                       "on-failure", "--max-restarts", str(KILLS)], _env(offset))
    try:
        if not run.wait_for(lambda line: ONSET.match(line), timeout_s=TIMEOUT_S):
            case["reason"] = "no estimate before the first kill"
            return case
        pid = run.pids[node]
        for _ in range(KILLS):
            killed_wall_s.append(time.time())
            os.kill(pid, signal.SIGKILL)
            case["kills"] += 1
            line = run.wait_for(lambda text, p=pid: (m := FAULT.match(text)) is not None
                                and int(m.group(2)) == p, timeout_s=TIMEOUT_S)
            if line is None:
                case["reason"] = f"no restart after kill {case['kills']}"
                return case
            pid = int(FAULT.match(line).group(3))
            last = FAULT.match(line).group(4)
            # the restarted process works: a windowing node's estimate from after its outage (an
            # event over 1 s of stream past the last one before the kill: not a late one of the
            # killed process), any onset for the others (a restarted plant's stream starts at 0)
            after_s = float(last) + 1.0 if node == "windowing" and last else -1.0
            if not run.wait_for(lambda text: (m := ONSET.match(text)) is not None
                                and float(m.group(1)) > after_s, timeout_s=TIMEOUT_S):
                case["reason"] = f"no estimate after restart {case['kills']}"
                return case
        # the windows the last restarted process missed come from the upstream history, after a restart that
        # takes seconds under load: read on for GRACE_S before interrupting (2 s cut off onsets still on their way)
        run.wait_for(lambda text: False, timeout_s=GRACE_S)
        run.process.send_signal(signal.SIGINT)      # the pipeline prints its summary
        case["exit_code"] = run.finish(timeout_s=TIMEOUT_S)
    finally:
        run.kill_group()
    faults = [m for line in run.lines if (m := FAULT.match(line))]
    before = [float(m.group(4)) for m in faults if m.group(4)]
    gaps = [(float(m.group(1)), float(m.group(2)), int(m.group(3)))
            for line in run.lines if (m := MISSING.match(line))]
    # where the stream was at each kill, and how far the node's estimates were behind it [s of stream]
    start = run.stream_start_wall_s()
    at_kill = [round((t - start) * RATE, 2) for t in killed_wall_s] if start is not None else []
    own = own_outage_gaps(gaps, before, at_kill) if node == "windowing" else []
    behind = [round(k - b, 2) for k, b in zip(at_kill, before)] if node != "plant_simulator" else []
    # a gap that begins at the last estimate before a kill when the estimates were a full history behind: the
    # windows queued in the killed node were more than its upstream writer keeps (docs/graph.md, "While a consumer
    # is away": the documented bound, not a loss upstream of it)
    beyond = [g for g in gaps if g not in own and any(abs(g[0] - t) < 1e-3 and lag >= QUEUE_FULL_S
                                                      for t, lag in zip(before, behind))]
    lost = sum(g[2] for g in gaps if g not in own and g not in beyond)
    case.update(stream_at_kills_s=at_kill, estimates_behind_at_kills_s=behind)
    case.update(restarts_named=len(faults), onsets_estimated=len(run.onsets()),
                gaps=[f"{a:.3f}..{b:.3f} s ({n})" for a, b, n in gaps],
                onsets_missing_own_outage=sum(g[2] for g in own),
                onsets_lost_beyond_history=sum(g[2] for g in beyond), onsets_lost_upstream=lost)
    case["survived"] = case["kills"] == KILLS and len(faults) == KILLS
    if not case["survived"] or lost:
        case["output_tail"] = run.lines[-15:] + run.stderr.splitlines()[-10:]
    return case


def own_outage_gaps(gaps, before, at_kill) -> list:
    """The gaps (start s, end s, onsets) of a killed windowing node's own outage: a gap that holds, or begins up to
    OWN_QUEUE_S of stream before, either the last estimate before a kill (the pipeline's fault line) or the stream's
    place at a kill (``at_kill``, from the wall clock). The chunk topics are volatile: what the plant published
    while the process was down, and what was still queued in it, is its own loss (docs/graph.md). Both marks are
    needed: under load the estimates run seconds behind the stream, and the fault line's last estimate can lie
    further back than the onsets the killed process had not yet windowed (stop 49: a gap at 35.30-36.55 s, the kill
    at 35.45 s of stream, the last estimate before it at 32.56 s with the estimates 2.9 s behind)."""
    marks = list(before) + list(at_kill)
    return [g for g in gaps if any(g[0] - OWN_QUEUE_S <= t <= g[1] + 1e-3 for t in marks)]


def ros_test_runs() -> dict:
    path = os.environ.get("BENCH_ROS_TEST_RUNS_JSON", "")
    if not path:
        return {}
    with open(path, encoding="utf-8") as f:
        measured = json.load(f)
    return {"under_load_ros_test_runs_passed": measured["passed"],
            "under_load_ros_test_runs": measured["runs"], "ros_test_runs_details": measured}


def run() -> dict:
    cases = []
    with CpuHog(max_s=1800.0) as hog:
        for offset, node in enumerate(NODES):
            print(f"under_load: kill {node} {KILLS} times beside {hog.loops} busy loops",
                  file=sys.stderr, flush=True)
            cases.append(kill_repeatedly(node, offset))
            print(f"under_load: {json.dumps({k: v for k, v in cases[-1].items() if k != 'output_tail'})}",
                  file=sys.stderr, flush=True)
    lost = sum(c.get("onsets_lost_upstream", 0) for c in cases)
    beyond = sum(c.get("onsets_lost_beyond_history", 0) for c in cases)
    incomplete = [c["case"] for c in cases if not c.get("survived")]
    return {"under_load_kill_onsets_lost": lost if not incomplete else None,
            "under_load_kill_onsets_lost_beyond_history": beyond if not incomplete else None,
            "under_load_kills": sum(c["kills"] for c in cases),
            "under_load_cases_incomplete": incomplete, **ros_test_runs(), "cases": cases}


if __name__ == "__main__":
    started = time.monotonic()
    result = run()
    print(f"under_load: {time.monotonic() - started:.0f} s", file=sys.stderr)
    print(json.dumps(result))
