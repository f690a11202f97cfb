"""A clipped accelerometer through the windowing and classifier nodes' callbacks (no DDS traffic): the
windows carry their saturated samples and /diagnostics says WARN naming the sensor's rail."""
import os

import numpy as np
import pytest

rclpy = pytest.importorskip("rclpy")
plant = pytest.importorskip("backlash_monitor.plant")

import fuzz_cores as fc  # noqa: E402
import fuzz_nodes_checks as nc  # noqa: E402


@pytest.fixture(scope="module")
def rclpy_context():
    from conftest import fresh_domain_id
    os.environ["ROS_DOMAIN_ID"] = str(fresh_domain_id())
    os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    rclpy.init()
    yield
    rclpy.try_shutdown()


def _stream(clip_fraction):
    sim = plant.PlantSimulator([plant.Scenario(width_m=0.0075, eta_k=0.025, n1=0.89, seed=5)],
                               config=plant.load_plant_config(), noise=True)
    chunks = [sim.run(5000) for _ in range(24)]                      # 2.4 s
    a2 = np.concatenate([c.a2[0] for c in chunks])
    rail = clip_fraction * float(np.abs(a2).max())
    for c in chunks:
        yield {"a1": c.a1[0], "a2": np.clip(c.a2[0], -rail, rail),
               "angle_difference": c.angle_difference[0]}, c.first_sample_index, rail


@pytest.mark.ros
def test_a_clipped_a2_gives_flagged_windows_and_a_warn(rclpy_context):
    from diagnostic_msgs.msg import DiagnosticStatus
    node = nc.windowing_node()
    try:
        for signals, first, rail in _stream(0.75):
            for name, samples in signals.items():
                node.on_chunk(name, nc.chunk(name, first, 2e-5, samples))
        windows = node.publisher.messages
        assert windows and any(w.saturated_samples > 0 for w in windows)
        node.update_diagnostics(publish_now=True)
        status = node.diagnostics.publisher.messages[-1].status[0]
        assert status.level == DiagnosticStatus.WARN
        # clipped at +-rail; the plant's a2 reaches only its lower one on this drive
        assert "a2 at its rail (" in status.message and f"{rail:.3g} m/s²)" in status.message
        assert "accelerometer's range is too small" in status.message
        assert "a1 at its rail" not in status.message
    finally:
        node.destroy_node()


@pytest.mark.ros
def test_a_clean_stream_is_not_flagged(rclpy_context):
    from diagnostic_msgs.msg import DiagnosticStatus
    node = nc.windowing_node()
    try:
        for signals, first, _ in _stream(1.0):
            for name, samples in signals.items():
                node.on_chunk(name, nc.chunk(name, first, 2e-5, samples))
        assert node.publisher.messages and all(w.saturated_samples == 0 for w in node.publisher.messages)
        node.update_diagnostics(publish_now=True)
        assert node.diagnostics.publisher.messages[-1].status[0].level == DiagnosticStatus.OK
    finally:
        node.destroy_node()


@pytest.mark.ros
def test_the_classifier_warns_for_an_estimate_from_a_saturated_window(rclpy_context):
    from diagnostic_msgs.msg import DiagnosticStatus
    node = nc.classifier_node()
    try:
        g1, g2 = fc.good_window()
        node.on_window(nc.window_msg(g1, g2, index=1))
        node.update_diagnostics(publish_now=True)
        assert node.diagnostics.publisher.messages[-1].status[0].level == DiagnosticStatus.OK
        msg = nc.window_msg(g1, g2, index=2)
        msg.saturated_samples = 40
        node.on_window(msg)
        assert node.publisher.messages            # still classified
        node.update_diagnostics(publish_now=True)
        status = node.diagnostics.publisher.messages[-1].status[0]
        assert status.level == DiagnosticStatus.WARN and "rail" in status.message
    finally:
        node.destroy_node()
