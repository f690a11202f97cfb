"""The plant waits for the subscribers it names, up to a limit, and says who is missing."""
import pytest
import os
import subprocess
import sys

from ament_index_python.packages import get_package_prefix

PLANT = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor",
                     "plant_simulator")


@pytest.mark.process
@pytest.mark.ros
def test_a_subscriber_that_never_comes_is_named_when_the_wait_times_out(ros_env):
    # A subscriber of every plant topic is there (a recorder, say), but not the one named.
    other = subprocess.Popen([sys.executable, "-c", """
import time, rclpy
from backlash_monitor_msgs.msg import SignalChunk
from rclpy.qos import QoSProfile, ReliabilityPolicy
rclpy.init()
node = rclpy.create_node("other_reader")
for name in ("a1", "a2", "omega1", "omega2", "angle_difference"):
    node.create_subscription(SignalChunk, "plant/" + name, lambda m: None,
                             QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE))
end = time.monotonic() + 60
while time.monotonic() < end:
    rclpy.spin_once(node, timeout_sec=0.1)
"""], env=ros_env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        proc = subprocess.run([PLANT, "--ros-args", "-p", "qos:=reliable", "-p", "duration_s:=0.2",
                               "-p", "rate_factor:=0.0", "-p", "wait_timeout_s:=2.0",
                               "-p", "wait_for_subscribers:=['windowing:a1,angle_difference']"],
                              env=ros_env, capture_output=True, text=True, timeout=120)
    finally:
        other.kill()
        other.wait()
    assert proc.returncode == 0, proc.stderr
    assert ("waiting for subscribers before streaming (up to 2 s): /windowing on a1, "
            "angle_difference") in proc.stderr
    assert ("streaming without them after waiting 2 s for subscribers: missing /windowing on a1, "
            "angle_difference") in proc.stderr, proc.stderr
    assert "published 10 chunks" in proc.stderr      # then it streamed its 0.2 s


@pytest.mark.process
@pytest.mark.ros
def test_a_bad_subscriber_entry_stops_the_plant_with_one_clear_line(ros_env):
    proc = subprocess.run([PLANT, "--ros-args", "-p", "wait_for_subscribers:=['windowing:a3']"],
                          env=ros_env, capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2, proc.stderr
    assert "unknown signal a3" in proc.stderr and "allowed: a1, a2" in proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.process
@pytest.mark.ros
def test_a_restart_policy_without_processes_is_refused(ros_env):
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "pipeline", "--restart",
                           "on-failure"], env=ros_env, capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert "--restart on-failure needs --processes" in proc.stderr and "allowed" in proc.stderr
