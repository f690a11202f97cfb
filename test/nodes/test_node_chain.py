"""The `chain` executable: windowing, denoise and classifier in one process, as `ros2 run` starts it."""
import pytest
import os
import subprocess
import sys
import textwrap

from ament_index_python.packages import get_package_prefix

PREFIX = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")

_MONITOR = textwrap.dedent("""
    import sys, time, rclpy
    from backlash_monitor.nodes.classifier import ESTIMATE_QOS
    from backlash_monitor_msgs.msg import BacklashEstimate
    rclpy.init()
    node = rclpy.create_node("monitor")
    got = []
    node.create_subscription(BacklashEstimate, "estimate", got.append, ESTIMATE_QOS)
    deadline = time.monotonic() + 90
    while len(got) < int(sys.argv[1]) and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    for m in got:
        print(m.entry_sample_index, m.signal_name, m.width_m, m.true_width_m)
""")


@pytest.mark.process
@pytest.mark.ros
def test_the_chain_in_one_process_classifies_a_simulated_stream(ros_env):
    chain = subprocess.Popen([os.path.join(PREFIX, "chain"), "--ros-args", "-p", "qos:=reliable",
                              "-p", "drive_name:=drive7"],
                             env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    monitor = subprocess.Popen([sys.executable, "-c", _MONITOR, "21"], env=ros_env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    plant = subprocess.Popen([os.path.join(PREFIX, "plant_simulator"), "--ros-args",
                              "-p", "qos:=reliable", "-p", "duration_s:=2.0", "-p", "rate_factor:=2.0",
                              "-p", "width_m:=0.0075", "-p", "wait_for_subscriptions:=3"],
                             env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        out, err = monitor.communicate(timeout=150)
    finally:
        for proc in (plant, chain, monitor):
            if proc.poll() is None:
                proc.terminate()
        chain_out, _ = chain.communicate(timeout=30)
        plant.wait(timeout=30)
    rows = [line.split() for line in out.splitlines()]
    # 8 onsets in 2 s (0.054 s + k * 0.25 s); the first has no sensor offset estimate yet (no whole
    # load period behind it) and is not classified; the 7 after it from a1, a2 and both.
    assert len(rows) == 21, out + err + chain_out
    assert min(int(r[0]) for r in rows) > 0.25 / 2e-5, rows     # not the first onset (t = 0.054 s)
    assert {r[1] for r in rows} == {"a1", "a2", "a1+a2"}
    # The simulated width is latched on its own topic; a window cut before the windowing node has
    # matched that topic carries NaN (unknown), never a wrong width.
    true_widths = [float(r[3]) for r in rows]
    assert all(w == 0.0075 or w != w for w in true_widths), rows
    assert all(w == 0.0075 for w in true_widths[-12:]), rows
    correct = sum(abs(float(r[2]) - 0.0075) < 1e-9 for r in rows)
    assert correct >= 19, rows          # per-window accuracy is ~0.96-0.99 (README)
    assert "Traceback" not in chain_out
    assert chain.returncode == 0, chain_out     # SIGTERM: a clean shutdown


@pytest.mark.process
@pytest.mark.ros
def test_a_bad_parameter_stops_the_chain_with_one_clear_line(ros_env):
    proc = subprocess.run([os.path.join(PREFIX, "chain"), "--ros-args", "-p", "trigger:=magic"],
                          env=ros_env, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert "trigger" in proc.stderr and "allowed" in proc.stderr
    assert "Traceback" not in proc.stderr
