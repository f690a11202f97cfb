"""Latency and throughput of the node graph over DDS (prints one JSON object).

latency: the windowing, denoise and classifier nodes run each in its own process (as `ros2 run`
starts them); this process runs the plant simulator in real time and a monitor.
latency_ms_chain_in_one_process: the same with the three nodes in one process (the `chain`
executable), the plant and the monitor still in this one. For every estimate,
latency = the wall time it is received - the wall time the chunk holding its window's last sample
was published. Reported: median and p99 [ms]. latency_stages_ms: from a second real-time run whose
monitor also subscribes to windows/raw and windows/denoised, the same times to each stage and the
hops between them (where the latency goes).

realtime_factor: the same graph with the simulator unthrottled-by-factor (rate_factor R) and
reliable QoS; simulated seconds per wall second until the last expected estimate arrives, for a
rising R; the result is the highest R whose run lost nothing (discarded_windows == 0 and every
onset window classified).

--check-a1-chain: the windowing node checks a1 against the motor speed (check_a1_chain:=true, as `pipeline` and
`fleet` run it: it joins plant/omega1 too); without it, as `ros2 run` with config/drive.yaml starts it.
"""
import json
import os
import subprocess
import sys
import time

import numpy as np

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.setdefault("ROS_DOMAIN_ID", str(os.getpid() % 90 + 5))

from backlash_monitor.ros.fast_dds import configure_fast_dds  # noqa: E402

configure_fast_dds()  # as every node of the project does, before rclpy.init

import rclpy  # noqa: E402
from ament_index_python.packages import get_package_prefix  # noqa: E402
from diagnostic_msgs.msg import DiagnosticArray  # noqa: E402
from rclpy.parameter import Parameter  # noqa: E402

from backlash_monitor.ros.qos import ESTIMATE_QOS  # noqa: E402
from backlash_monitor.ros.lean_executor import make_executor  # noqa: E402
from backlash_monitor.ros.runtime import freeze_startup_objects  # noqa: E402
from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode  # noqa: E402
from backlash_monitor.windowing import default_window_offset  # noqa: E402
from backlash_monitor_msgs.msg import BacklashEstimate  # noqa: E402

CHUNK = 1000
WINDOW = 2048
TRIGGER = "contact_loss"
WINDOW_OFFSET = default_window_offset(TRIGGER)


CHECK_A1_CHAIN = False     # --check-a1-chain: the windowing node joins plant/omega1 and checks a1 against it


def start_chain(trigger="contact_loss", one_process=False):
    """The windowing, denoise and classifier nodes: three processes, or the `chain` executable."""
    prefix = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")
    check = ["-p", "check_a1_chain:=true"] if CHECK_A1_CHAIN else []
    if one_process:
        specs = [("chain", ["-p", f"trigger:={trigger}", "-p", "qos:=reliable", *check])]
    else:
        specs = [("classifier", ["-p", f"trigger:={trigger}"]),
                 ("denoise", []),
                 ("windowing", ["-p", "qos:=reliable", "-p", f"trigger:={trigger}", *check])]
    return [subprocess.Popen([os.path.join(prefix, name), "--ros-args", *params],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            for name, params in specs]


def stop(children):
    for child in children:
        child.terminate()
    for child in children:
        try:
            child.wait(timeout=10)
        except subprocess.TimeoutExpired:
            child.kill()


def run_graph(duration_s, rate_factor, chunk=None, stages=None, one_process=False):
    """Returns (latencies_s, wall_s, n_onset_estimates, discarded_windows, expected).

    stages: a dict to fill with {"window": [...], "denoised": [...], "estimate": [...]}, the
    times [s] from the chunk holding a window's last sample published to that window received
    raw, denoised and classified (the monitor then also subscribes to both window topics).
    one_process: the chain runs as the `chain` executable (its three nodes in one process)."""
    chunk = chunk or CHUNK
    children = start_chain(one_process=one_process)
    rclpy.init()
    try:
        monitor = rclpy.create_node("bench_monitor")
        received = {}
        discarded = [0]
        arrivals = {"window": {}, "denoised": {}}
        if stages is not None:
            from backlash_monitor.ros.qos import WINDOW_QOS
            from backlash_monitor_msgs.msg import BacklashWindow
            for key, topic in (("window", "windows/raw"), ("denoised", "windows/denoised")):
                monitor.create_subscription(
                    BacklashWindow, topic,
                    lambda msg, k=key: arrivals[k].setdefault(msg.entry_sample_index, time.time()),
                    WINDOW_QOS)

        def on_estimate(msg):
            received.setdefault(msg.entry_sample_index, time.time())

        def on_diag(msg):
            for status in msg.status:
                if status.name.endswith("windowing: windowing"):
                    for kv in status.values:
                        if kv.key == "discarded":
                            discarded[0] = max(discarded[0], int(kv.value))

        monitor.create_subscription(BacklashEstimate, "estimate", on_estimate, ESTIMATE_QOS)
        monitor.create_subscription(DiagnosticArray, "/diagnostics", on_diag, 10)
        # Wait until the chain's subscriptions exist before the stream starts.
        probe = rclpy.create_node("bench_probe")
        deadline = time.time() + 60
        while time.time() < deadline and probe.count_subscribers("plant/a1") == 0:
            rclpy.spin_once(monitor, timeout_sec=0.1)
        while time.time() < deadline and monitor.count_publishers("estimate") == 0:
            rclpy.spin_once(monitor, timeout_sec=0.1)
        time.sleep(1.0)
        plant = PlantSimulatorNode(parameter_overrides=[
            Parameter("rate_factor", value=float(rate_factor)),
            Parameter("duration_s", value=float(duration_s)), Parameter("qos", value="reliable"),
            Parameter("chunk_samples", value=chunk), Parameter("wait_for_subscriptions", value=4 if CHECK_A1_CHAIN else 3)])
        published = {}
        original = plant.publish_chunk

        def publish_chunk():
            first = plant.simulator.sample_index
            original()
            published[first] = time.time()

        plant.publish_chunk = publish_chunk
        executor = make_executor()   # as the project's nodes and the pipeline spin
        executor.add_node(plant)
        executor.add_node(monitor)
        freeze_startup_objects()     # as the nodes do once built (ros/runtime.run_nodes)
        started = time.time()
        # onsets whose window ends inside the run (4 per second), less the first (no sensor offset
        # estimate before one whole load period: not classified) and one of margin
        expected = int(duration_s * 4) - 2
        limit = started + duration_s / rate_factor + 30
        last_count, last_change = 0, time.time()
        while time.time() < limit:
            executor.spin_once(timeout_sec=0.01)
            if len(received) != last_count:
                last_count, last_change = len(received), time.time()
            if plant.finished and (len(received) >= expected or time.time() - last_change > 10.0):
                break
        wall = (max(received.values()) if received else time.time()) - started
        latencies = []
        for entry, t_recv in received.items():
            last_sample = entry + WINDOW_OFFSET + WINDOW - 1   # the window starts after the entry
            last_chunk = last_sample // chunk * chunk
            if last_chunk in published:
                latencies.append(t_recv - published[last_chunk])
                if stages is not None and all(entry in arrivals[k] for k in arrivals):
                    for key in arrivals:
                        stages.setdefault(key, []).append(arrivals[key][entry] - published[last_chunk])
                    stages.setdefault("estimate", []).append(t_recv - published[last_chunk])
        executor.shutdown()
        for node in (plant, monitor, probe):
            node.destroy_node()
        return latencies, wall, len(received), discarded[0], expected
    finally:
        rclpy.try_shutdown()
        stop(children)


def _stage_summary(stages) -> dict:
    """Median and p99 [ms] of each stage's time since the chunk was published, and of each hop."""
    out = {}
    previous = None
    for key in ("window", "denoised", "estimate"):
        t = np.array(stages.get(key, [])) * 1e3
        if not t.size:
            continue
        out[f"to_{key}"] = {"median": float(np.median(t)), "p99": float(np.percentile(t, 99))}
        if previous is not None:
            hop = t - previous
            out[f"hop_to_{key}"] = {"median": float(np.median(hop)),
                                    "p99": float(np.percentile(hop, 99))}
        previous = t
    return out


LATENCY_RUN_S = 60.0   # 240 onset windows: the p99 is the 3rd-slowest (of 60 it was the slowest)


def main():
    latencies, _, n_rt, discarded_rt, expected_rt = run_graph(duration_s=LATENCY_RUN_S,
                                                              rate_factor=1.0)
    lat_ms = np.array(latencies) * 1e3
    # Where the time goes: a second real-time run whose monitor also takes both window topics.
    stages = {}
    run_graph(duration_s=15.0, rate_factor=1.0, stages=stages)
    # The same chain as the `chain` executable: its three nodes in one process.
    latencies_one, _, n_one, discarded_one, _ = run_graph(duration_s=LATENCY_RUN_S,
                                                          rate_factor=1.0, one_process=True)
    one_ms = np.array(latencies_one) * 1e3
    throughput = []
    for factor in (10.0, 20.0, 40.0):
        _, wall, n, discarded, expected = run_graph(duration_s=20.0, rate_factor=factor)
        throughput.append({"rate_factor": factor, "realtime_factor": 20.0 / wall,
                           "onset_windows_classified": n, "expected": expected,
                           "discarded_windows": discarded})
    sustained = [t for t in throughput
                 if t["discarded_windows"] == 0 and t["onset_windows_classified"] >= t["expected"]]
    best = max(sustained, key=lambda t: t["realtime_factor"]) if sustained else None
    print(json.dumps({
        "latency_ms": {"median": float(np.median(lat_ms)) if lat_ms.size else None,
                       "p99": float(np.percentile(lat_ms, 99)) if lat_ms.size else None,
                       "max": float(lat_ms.max()) if lat_ms.size else None,
                       "n": int(lat_ms.size)},
        "latency_run": {"onset_windows_classified": n_rt, "expected": expected_rt,
                        "discarded_windows": discarded_rt},
        "latency_stages_ms": _stage_summary(stages),
        "latency_ms_chain_in_one_process": {
            "median": float(np.median(one_ms)) if one_ms.size else None,
            "p99": float(np.percentile(one_ms, 99)) if one_ms.size else None,
            "max": float(one_ms.max()) if one_ms.size else None, "n": int(one_ms.size),
            "onset_windows_classified": n_one, "discarded_windows": discarded_one},
        "realtime_factor": best["realtime_factor"] if best else None,
        "discarded_windows": best["discarded_windows"] if best else None,
        "throughput_runs": throughput,
        "goal": {"latency_p99_ms": 10.0, "realtime_factor": 10.0, "discarded_windows": 0},
        "check_a1_chain": CHECK_A1_CHAIN,
    }))


if __name__ == "__main__":
    # no options: --help says what it measures instead of starting the run
    import argparse
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check-a1-chain", action="store_true",
                    help="the windowing node checks a1 against the motor speed (joins plant/omega1), as pipeline runs it")
    CHECK_A1_CHAIN = ap.parse_args().check_a1_chain
    sys.exit(main())
