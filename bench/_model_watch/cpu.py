"""cpu_per_drive: the model_watch node's CPU share of one core while a 50 kHz drive streams in real time.

`pipeline --watch --processes` runs every node in its own process; the model_watch process's CPU time (user +
system, /proc/PID/stat) is read at two moments inside the stream (after its start-up: the reference loaded, the
views built) and divided by the wall time between them. The windowing node's process is read in the same run, side
by side: it takes the same three plant topics and runs the same onset detector. And a node with model_watch's
subscriptions, QoS and batched executor and no work (null_node.py, its own process in the same ROS domain, started
before the pipeline): what any node reading a 50 kHz drive pays in DDS and the executor; the watch's own work is the
difference.
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
import time


def _cpu_s(pid: int) -> float:
    with open(f"/proc/{pid}/stat") as f:
        fields = f.read().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def watch_settings() -> tuple[str, float]:
    """The QoS pipeline --watch gives the model_watch node's subscriptions and the node's batching (batch_s: its
    executor's wake-ups); the null node takes the same."""
    import argparse
    from backlash_monitor.nodes import pipeline
    from backlash_monitor.nodes.model_watch import _parameters
    parser = argparse.ArgumentParser()
    pipeline.add_arguments(parser)
    params = pipeline.node_parameters(parser.parse_args(["--watch"]))["model_watch"]
    batch_s = params.get("batch_s", next(s.default for s in _parameters() if s.name == "batch_s"))
    return params["qos"], float(batch_s)


def cpu_per_drive(duration_s: float = 40.0, skip_s: float = 10.0, log=print) -> dict:
    qos, batch_s = watch_settings()
    null = subprocess.Popen([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)), "null_node.py"),
                             qos, str(batch_s)], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(2.0)
    try:
        out = _cpu_run(duration_s, skip_s, log, null.pid)
        out["cpu_subscriptions_qos"] = qos
        out["cpu_batch_s"] = batch_s
    finally:
        null.send_signal(2)
        try:
            null.wait(timeout=20)
        except subprocess.TimeoutExpired:
            null.kill()
    return out


def _cpu_run(duration_s: float, skip_s: float, log, null_pid: int) -> dict:
    cmd = [sys.executable, "-m", "backlash_monitor", "pipeline", "--watch", "--processes", "--duration",
           str(duration_s), "--snapshot-dir", os.path.join("/tmp", f"model_watch_cpu_{os.getpid()}")]
    log("cpu: " + " ".join(cmd[2:]))
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    pids, started = {}, None
    samples = {}
    out = []
    try:
        for line in proc.stdout:
            out.append(line)
            m = re.search(r"node processes: (.*?); restart", line)
            if m:
                pids = {name: int(pid) for name, pid in re.findall(r"(\w+) pid (\d+)", m.group(1))}
                pids["null_watch"] = null_pid
            if started is None and line.startswith("t="):
                started = time.monotonic()            # the first estimate: the stream runs
            if started is not None and "a" not in samples and time.monotonic() - started >= skip_s:
                samples["a"] = (time.monotonic(), {n: _cpu_s(p) for n, p in pids.items()})
            if "a" in samples and "b" not in samples and \
                    time.monotonic() - started >= duration_s - 5.0:
                samples["b"] = (time.monotonic(), {n: _cpu_s(p) for n, p in pids.items()})
    finally:
        proc.wait(timeout=120)
    if "b" not in samples:
        raise RuntimeError("cpu: the pipeline ended before the second sample:\n" + "".join(out[-20:]))
    (ta, ca), (tb, cb) = samples["a"], samples["b"]
    share = {n: (cb[n] - ca[n]) / (tb - ta) for n in ca}
    log(f"cpu: over {tb - ta:.1f} s: " + ", ".join(f"{n} {v * 100:.1f} %" for n, v in share.items()))
    w, n = share.get("model_watch"), share.get("null_watch")
    return {"cpu_per_drive": w, "cpu_same_subscriptions_no_work": n,
            "cpu_watch_work": (w - n) if w is not None and n is not None else None,
            "cpu_per_drive_over_no_work": (w / n) if w and n else None,
            "cpu_windowing_same_run": share.get("windowing"),
            "cpu_plant_simulator_same_run": share.get("plant_simulator"), "cpu_window_s": round(tb - ta, 1)}
