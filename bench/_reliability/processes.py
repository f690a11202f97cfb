"""Process faults injected into `pipeline --processes` (issue 9): node kills and restarts, parent kill.

    python bench/_reliability/processes.py        # one JSON object on stdout, progress on stderr

``run()`` returns {"faults_injected", "faults_survived", "data_lost_bytes", "cases": [...]}
(bench/reliability.py sums it with the other fault benches). Cases, each in a DDS domain of its
own on loopback:

- ``kill_<node>``: SIGKILL one node process (windowing, denoise, classifier, plant_simulator) at
  the first estimate of a run with ``--restart on-failure``. Survived: the pipeline named the
  node and its signal, restarted it, no other node faulted, the run ended with exit code 0, and
  onset estimates came from after the kill (for the windowing/denoise/classifier nodes: an
  event whose entry lies more than 1 s of stream after the kill, which the killed process cannot
  have windowed; for the plant: the onsets of its new stream, from sample 0 again).
  ``onsets_missing``: onset events with no estimate, from the gaps the pipeline's summary
  reports (measured). ``stream_missed_bytes``: the live stream that reached no window while the
  node was down, derived from them: onsets_missing x 0.25 s (the simulated drive's onset period)
  x 50 kHz x 3 signals the windowing node reads x 8 bytes. It is the bounded, reported loss of a
  restart, not lost recorded data: ``data_lost_bytes`` (the issue's goal: 0 outside the open
  chunk) counts recordings only, and is 0 for these cases.
- ``kill_parent``: SIGKILL the pipeline itself. Survived: all four node processes have ended
  within 15 s.
- ``kill_recorder``: a `record` node records plant/* (the plant waits for it), SIGKILL after about
  3 s of stream. The bag is then read with recovery (bag.BagReader(recover=True)). Survived: it
  reads, its plant/a1 chunks run without a gap from sample 0, and the stream lost at the end
  (stream time at the kill, from the plant's log stamp, minus the end of the last recovered
  chunk) is within the open chunk's bound: chunk_duration_s + the recorder's flush period
  (chunk_duration_s, at most 1 s) + 0.1 s for delivery. ``data_lost_bytes``: the sample bytes
  of the five signals lost beyond that bound (0 when within).
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

from process_fault_helpers import ONSET, STREAM_START, PipelineRun, gone, wait_until  # noqa: E402

RATE = 2.0
ONSET_PERIOD_S = 0.25
SAMPLE_RATE_HZ = 50_000
SIGNALS_WINDOWED = 3
NODES = ("windowing", "denoise", "classifier", "plant_simulator")
MISSING = re.compile(r"^onset estimates missing: t=[0-9.]+\.\.[0-9.]+ s \((\d+) onsets")


def _env(offset: int) -> dict:
    env = dict(os.environ)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env["ROS_DOMAIN_ID"] = str((int(os.environ.get("ROS_DOMAIN_ID", "50")) + offset) % 101 + 1)
    env["PYTHONUNBUFFERED"] = "1"
    return env


def kill_node(node: str, offset: int) -> dict:
    run = PipelineRun(["--duration", "30", "--rate-factor", str(RATE), "--events", "40",
                       "--restart", "on-failure"], _env(offset))
    case = {"case": f"kill_{node}", "survived": False}
    try:
        if not run.wait_for(lambda line: ONSET.match(line), timeout_s=120):
            case["reason"] = "no estimate before the kill"
            return case
        victim = run.pids[node]
        killed_wall_s = time.time()
        os.kill(victim, signal.SIGKILL)
        code = run.finish(timeout_s=120)
    finally:
        run.kill_group()
    faults = [line for line in run.lines if re.match(r"pipeline: node \w+ \(pid", line)]
    named = (len(faults) == 1 and f"node {node} (pid {victim}) was killed by signal SIGKILL"
             in faults[0] and "restarted as pid" in faults[0])
    at = run.lines.index(faults[0]) if faults else len(run.lines)
    before = [t for i, t in run.onsets() if i < at]
    after = [t for i, t in run.onsets() if i > at]
    start = run.stream_start_wall_s()
    killed_at_s = (killed_wall_s - start) * RATE if start is not None else float("nan")
    if node == "plant_simulator":
        # the new stream's onsets (from sample 0 again; the old stream's come in order)
        resumed = bool(after) and bool(before) and min(after) <= before[-1]
    else:
        resumed = bool(after) and after[-1] > killed_at_s + 1.0
    missing = sum(int(m.group(1)) for line in run.lines if (m := MISSING.match(line)))
    case.update(survived=bool(code == 0 and named and resumed), exit_code=code,
                named=named, estimates_resumed=resumed, killed_at_stream_s=round(killed_at_s, 3),
                onsets_before=len(before), onsets_after=len(after), onsets_missing=missing,
                data_lost_bytes=0,
                stream_missed_bytes=int(missing * ONSET_PERIOD_S * SAMPLE_RATE_HZ * SIGNALS_WINDOWED
                                        * 8))
    if not case["survived"]:
        case["output_tail"] = run.lines[-12:]
    return case


def kill_parent(offset: int) -> dict:
    run = PipelineRun(["--duration", "60", "--rate-factor", "1"], _env(offset))
    case = {"case": "kill_parent", "survived": False}
    try:
        if not run.wait_for(lambda line: ONSET.match(line), timeout_s=120):
            case["reason"] = "no estimate before the kill"
            return case
        pids = dict(run.pids)
        os.kill(run.process.pid, signal.SIGKILL)
        run.process.wait(timeout=10)
        ended = wait_until(lambda: all(gone(p) for p in pids.values()), timeout_s=15.0)
        case.update(survived=ended and len(pids) == 4,
                    still_running=[name for name, p in pids.items() if not gone(p)],
                    data_lost_bytes=0)
    finally:
        run.kill_group()
    return case


CHUNK_DURATION_S = 0.5       # the recorder's chunk_duration_s in the recorder case


def _executable(name: str) -> str:
    from ament_index_python.packages import get_package_prefix
    return os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", name)


def kill_recorder(offset: int) -> dict:
    import subprocess
    import tempfile
    from backlash_monitor.bag import BagReader
    case = {"case": "kill_recorder", "survived": False}
    env = _env(offset)
    with tempfile.TemporaryDirectory() as tmp:
        bag = os.path.join(tmp, "killed.mcap")
        recorder = subprocess.Popen(
            [_executable("record"), "--ros-args", "-p", f"output:={bag}", "-p", "topics:=/plant/*",
             "-p", f"chunk_duration_s:={CHUNK_DURATION_S}", "-p", "discovery_period_s:=0.05"],
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        plant = subprocess.Popen(
            [_executable("plant_simulator"), "--ros-args", "-p", "qos:=reliable",
             "-p", "duration_s:=60.0", "-p", "rate_factor:=1.0",
             "-p", "wait_for_subscribers:=['record']"],
            env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
            start_new_session=True)
        try:
            start = None
            deadline = time.monotonic() + 120
            while start is None and time.monotonic() < deadline:
                line = plant.stderr.readline()
                if not line:
                    break
                m = STREAM_START.match(line)
                if m:
                    start = float(m.group(1))
            if start is None:
                case["reason"] = "the plant did not start streaming"
                return case
            time.sleep(3.0)
            killed_wall_s = time.time()
            os.kill(recorder.pid, signal.SIGKILL)
            recorder.wait(timeout=10)
        finally:
            for proc in (plant, recorder):
                try:
                    os.killpg(proc.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
                proc.wait(timeout=10)
        try:
            with BagReader(bag, recover=True) as reader:
                chunks = sorted((c.first_sample_index, c.samples.size, c.sample_period_s)
                                for c in reader.signal_chunks("/plant/a1"))
                integrity = reader.recovery.describe()
        except Exception as error:          # any failure to read is the fault not survived
            case["reason"] = f"recovery failed: {type(error).__name__}: {error}"
            return case
    if not chunks:
        case["reason"] = "no chunk recovered"
        return case
    period = chunks[0][2]
    contiguous = chunks[0][0] == 0 and all(a[0] + a[1] == b[0] for a, b in zip(chunks, chunks[1:]))
    recovered_end_s = (chunks[-1][0] + chunks[-1][1]) * period
    lost_s = (killed_wall_s - start) - recovered_end_s
    bound_s = CHUNK_DURATION_S + min(CHUNK_DURATION_S, 1.0) + 0.1
    beyond = max(0.0, lost_s - bound_s)
    case.update(survived=bool(contiguous and lost_s <= bound_s), contiguous_from_0=contiguous,
                recovered_s=round(recovered_end_s, 3), lost_at_end_s=round(lost_s, 3),
                open_chunk_bound_s=bound_s, integrity=integrity,
                data_lost_bytes=int(beyond / period) * 5 * 8)
    return case


def run() -> dict:
    cases = []
    for offset, node in enumerate(NODES):
        print(f"processes: kill and restart {node}", file=sys.stderr, flush=True)
        cases.append(kill_node(node, offset))
    print("processes: kill the pipeline (parent)", file=sys.stderr, flush=True)
    cases.append(kill_parent(len(NODES)))
    print("processes: kill the recorder", file=sys.stderr, flush=True)
    cases.append(kill_recorder(len(NODES) + 1))
    return {"faults_injected": len(cases),
            "faults_survived": sum(1 for c in cases if c["survived"]),
            "data_lost_bytes": sum(c.get("data_lost_bytes", 0) for c in cases),
            "stream_missed_bytes": sum(c.get("stream_missed_bytes", 0) for c in cases),
            "cases": cases}


if __name__ == "__main__":
    started = time.monotonic()
    result = run()
    print(f"processes: {time.monotonic() - started:.0f} s", file=sys.stderr)
    print(json.dumps(result))
