"""The plant_simulator node: validated parameters, and a continuous, indexed, stamped chunk stream."""
import os
import subprocess

import numpy as np
import pytest
import rclpy
from ament_index_python.packages import get_package_prefix
from rclpy.parameter import Parameter

from backlash_monitor.ros.conversions import SIGNAL_UNITS, from_float64_field
from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
from backlash_monitor_msgs.msg import SignalChunk

EXECUTABLE = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor",
                          "plant_simulator")


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("override, named", [
    ("width_m:=-0.001", "width_m"),
    ("rate_factor:=5000.0", "rate_factor"),
    ("qos:=fast", "qos"),
    ("chunk_samples:=3", "chunk_samples"),
])
def test_bad_parameter_is_named_with_its_allowed_range_and_the_node_does_not_start(
        ros_env, override, named):
    proc = subprocess.run([EXECUTABLE, "--ros-args", "-p", override], env=ros_env,
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert f"parameter '{named}'" in proc.stderr and "allowed" in proc.stderr
    assert "Traceback" not in proc.stderr + proc.stdout


@pytest.mark.process
@pytest.mark.ros
def test_streams_every_signal_in_continuous_indexed_chunks(ros_env):
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    rclpy.init()
    try:
        plant = PlantSimulatorNode(parameter_overrides=[
            Parameter("rate_factor", value=0.0), Parameter("duration_s", value=0.2),
            Parameter("qos", value="reliable"), Parameter("chunk_samples", value=500)])
        listener = rclpy.create_node("listener")
        received = {name: [] for name in SIGNAL_UNITS}
        for name in SIGNAL_UNITS:
            listener.create_subscription(SignalChunk, f"plant/{name}",
                                         lambda msg, n=name: received[n].append(msg), 100)
        executor = rclpy.executors.SingleThreadedExecutor()
        executor.add_node(plant)
        executor.add_node(listener)
        for _ in range(300):
            executor.spin_once(timeout_sec=0.05)
            if all(len(v) == 20 for v in received.values()):
                break
    finally:
        rclpy.try_shutdown()
    for name, msgs in received.items():
        assert [m.first_sample_index for m in msgs] == [500 * i for i in range(20)], name
        assert all(m.unit == SIGNAL_UNITS[name] and m.sample_period_s == 2e-5 for m in msgs)
        stamps = [m.header.stamp.sec + m.header.stamp.nanosec * 1e-9 for m in msgs]
        assert np.allclose(np.diff(stamps), 500 * 2e-5, atol=1e-6), name
    # The drive runs near its synchronous speed: omega1 about 157 rad/s minus the slip.
    omega1 = np.concatenate([from_float64_field(m.samples) for m in received["omega1"]])
    assert 140 < omega1.mean() < 157.1
