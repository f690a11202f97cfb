"""`pipeline --processes`: each node in its own process, and nothing lost while they start.

Four processes start at once and discover each other in no fixed order. A reader that matches a
writer only after the first windows (or estimates) went out must still get them: the window and
estimate topics are transient local (docs/graph.md). Before that, 2 of 5 short runs lost the
first windows or every estimate.
"""
import subprocess
import sys
import textwrap

import pytest

# The topic under test (argv[1]: window or estimate), as the graph's nodes offer it.
_TOPIC = textwrap.dedent("""
    import sys, time
    import rclpy
    from backlash_monitor.nodes.classifier import ESTIMATE_QOS
    from backlash_monitor.nodes.windowing import WINDOW_QOS
    from backlash_monitor_msgs.msg import BacklashEstimate, BacklashWindow
    msg_type, topic, qos = ((BacklashWindow, "windows/raw", WINDOW_QOS) if sys.argv[1] == "window"
                            else (BacklashEstimate, "estimate", ESTIMATE_QOS))
    rclpy.init()
""")

# A writer that publishes before any reader exists, then waits for one to match.
_EARLY_WRITER = _TOPIC + textwrap.dedent("""
    node = rclpy.create_node("early_writer")
    pub = node.create_publisher(msg_type, topic, qos)
    for i in range(5):
        msg = msg_type()
        msg.entry_sample_index = 1000 * i
        pub.publish(msg)
    print("published", flush=True)
    deadline = time.monotonic() + 60
    while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(3.0)
    node.destroy_node()
    rclpy.try_shutdown()
""")

# A reader started after that: prints the entry indices it got.
_LATE_READER = _TOPIC + textwrap.dedent("""
    node = rclpy.create_node("late_reader")
    got = []
    node.create_subscription(msg_type, topic, lambda m: got.append(m.entry_sample_index), qos)
    deadline = time.monotonic() + 30
    while len(got) < 5 and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.1)
    print(" ".join(map(str, got)))
    node.destroy_node()
    rclpy.try_shutdown()
""")


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("kind", ["window", "estimate"])
def test_a_reader_that_matches_late_still_gets_what_was_published_before(kind, ros_env):
    writer = subprocess.Popen([sys.executable, "-c", _EARLY_WRITER, kind], env=ros_env,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        assert writer.stdout.readline().strip() == "published"
        out = subprocess.run([sys.executable, "-c", _LATE_READER, kind], env=ros_env,
                             capture_output=True, text=True, timeout=90)
        assert out.returncode == 0, out.stderr
        assert out.stdout.split() == ["0", "1000", "2000", "3000", "4000"], out.stdout
    finally:
        writer.kill()
        writer.communicate()


@pytest.mark.process
@pytest.mark.ros
def test_each_node_in_its_own_process_classifies_every_onset(ros_env):
    proc = subprocess.run(
        [sys.executable, "-m", "backlash_monitor", "pipeline", "--processes", "--duration", "2",
         "--rate-factor", "2"], env=ros_env, capture_output=True, text=True, timeout=240)
    assert proc.returncode == 0, proc.stdout + proc.stderr[-3000:]
    assert "one process per node" in proc.stdout
    lines = [line for line in proc.stdout.splitlines() if line.startswith("t=") and " onset " in line]
    # The simulated drive has onsets at 0.054 s + k * 0.25 s; all 8 of 2 s end inside the run, the
    # first before the sensor offset is known (one whole load period is needed): 7 classified.
    assert len(lines) == 7, proc.stdout
    for line in lines:
        assert line.count(" ok") == 4, line     # a1, a2, a1+a2 and the fused estimate
    assert "7 onset windows classified (1 more before the sensor offset was known" in proc.stdout, proc.stdout
    assert "Traceback" not in proc.stderr
