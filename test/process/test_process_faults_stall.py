"""A hop of `pipeline --processes` stalls (SIGSTOP for 3 s, then SIGCONT): nothing is lost (issue 34).

A stalled process takes no message: the chunk and window topics (reliable, 1000 deep) hold what
comes meanwhile, and after SIGCONT the signals' topics arrive seconds apart (a chunk the
transport dropped while the reader's queue was full is sent again; the executor takes one
message per topic per wake-up). With a joiner that gave a range up after 16 others waited, one
3 s stall of the windowing process lost 109 of 120 onsets (docs/graph.md, "While a consumer is
away"). Now every onset of the stream is classified, in order, once, whichever hop stalls, on an
idle machine; and beside a CPU hog for the windowing hop (the joiner that lost onsets) and for the
one-process chain. (The hog costs the suite two cores for the test's length; the three hops share
the queue and executor code it exercises, so one hop under load stands for them.)
"""
import os
import re
import signal
import threading
import time

import pytest

from process_fault_helpers import ONSET, PipelineRun

ONSET_PERIOD_S = 0.25      # the simulated drive's onsets: 0.054 s + k * 0.25 s
FIRST_ONSET_S = 0.054
STALL_S = 3.0
INCOMPLETE = re.compile(r"incomplete chunk ranges (\d+)")


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("node, machine_load", [("windowing", "idle"), ("denoise", "idle"), ("classifier", "idle"),
                                                 ("windowing", "hog")], indirect=["machine_load"])
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


_MONITOR = """
import sys, time, rclpy
from diagnostic_msgs.msg import DiagnosticArray
from backlash_monitor.ros.qos import DIAGNOSTICS_DEPTH, ESTIMATE_QOS
from backlash_monitor_msgs.msg import BacklashEstimate
rclpy.init()
node = rclpy.create_node("monitor")
got = []
start = time.monotonic()
node.create_subscription(BacklashEstimate, "estimate", lambda m: got.append((m, time.monotonic() - start)),
                         ESTIMATE_QOS)
# the chain's own account (its /diagnostics: chunks taken, windows made, ranges incomplete), printed with the
# estimates, each with when it came (s since the monitor's start: a chain alive after the stall keeps publishing
# its diagnostics), so that a failure says which hop stopped
last_status = {}
node.create_subscription(DiagnosticArray, "/diagnostics",
                         lambda m: last_status.update({s.name: (s, time.monotonic() - start) for s in m.status}),
                         DIAGNOSTICS_DEPTH)
deadline = time.monotonic() + float(sys.argv[2])
while len(got) < int(sys.argv[1]) and time.monotonic() < deadline:
    rclpy.spin_once(node, timeout_sec=0.1)
for m, t in got:
    print(m.entry_sample_index, m.entry_kind, m.signal_name, f"at {t:.2f} s")
for name, (s, t) in sorted(last_status.items()):
    print("diagnostics", name, f"at {t:.1f} s:", s.message, " ".join(f"{v.key}={v.value}" for v in s.values))
"""


@pytest.mark.process
@pytest.mark.ros
def test_a_stalled_chain_process_loses_no_onset(ros_env, machine_load):
    """The same in one process (`chain`: windowing, denoise and classifier on one executor) fed
    by a plant process: the chain stalls 3 s, every onset of a 12 s stream is classified."""
    import subprocess
    import sys

    from ament_index_python.packages import get_package_prefix
    prefix = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")
    events = list(range(1, 48))                 # onsets 0.054 s + k 0.25 s < 12 s, from the second
    chain = subprocess.Popen([os.path.join(prefix, "chain"), "--ros-args", "-p", "qos:=reliable"],
                             env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    launched = time.monotonic()
    monitor = subprocess.Popen([sys.executable, "-c", _MONITOR, str(3 * len(events)), "300"],
                               env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    plant = subprocess.Popen([os.path.join(prefix, "plant_simulator"), "--ros-args", "-p", "qos:=reliable",
                              "-p", "duration_s:=12.0", "-p", "rate_factor:=2.0",
                              "-p", "wait_for_subscribers:=['windowing:a1,a2,angle_difference']"],
                             env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    plant_log = []
    try:
        started = None
        for line in plant.stderr:
            plant_log.append(line)
            if "streaming" in line and ("subscribers there" in line or "without them" in line):
                started = line
                break
        assert started, "the plant did not start streaming"
        # the rest of the plant's log is read as it comes (its end says whether the chain acknowledged
        # every chunk; an unread pipe could also block the plant)
        reader = threading.Thread(target=lambda: plant_log.extend(plant.stderr), daemon=True)
        reader.start()
        time.sleep(2.0)
        os.kill(chain.pid, signal.SIGSTOP)
        stall = [time.monotonic() - launched]
        try:
            time.sleep(STALL_S)
        finally:
            os.kill(chain.pid, signal.SIGCONT)
            stall.append(time.monotonic() - launched)
        out, err = monitor.communicate(timeout=400)
    finally:
        for proc in (plant, chain, monitor):
            if proc.poll() is None:
                proc.terminate()
        chain_out, _ = chain.communicate(timeout=60)
        plant.wait(timeout=60)
    onsets = sorted({round((int(index) * 2e-5 - FIRST_ONSET_S) / ONSET_PERIOD_S)
                     for index, kind, name in (row.split()[:3] for row in out.splitlines()
                                               if not row.startswith("diagnostics"))
                     if kind == "onset" and name == "a1+a2"})
    assert onsets == events, (out + err + chain_out + "\n--- plant:\n" + "".join(plant_log)
                              + f"\n--- the chain stopped {stall[0]:.1f}-{stall[-1]:.1f} s after the monitor's launch")
