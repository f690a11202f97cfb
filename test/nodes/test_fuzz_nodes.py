"""Fuzz the nodes' message handling: the windowing, denoise and classifier callbacks called with
generated messages (no DDS traffic: the publishers are replaced by lists). No exception escapes a
callback; what a node publishes is valid (windows of the configured length with finite samples,
estimates with a candidate width and 6 finite non-negative B entries); a bad input never turns
the drive's status to ERROR; after bad input the next good input is handled."""
import os

import numpy as np
import pytest
import rclpy
from diagnostic_msgs.msg import DiagnosticStatus
from hypothesis import HealthCheck, given, settings

import fuzz_cores as fc
import fuzz_nodes_checks as nc

pytestmark = pytest.mark.filterwarnings("ignore::hypothesis.errors.HypothesisWarning")

SETTINGS = settings(max_examples=120, deadline=None, database=None, derandomize=True,
                    suppress_health_check=list(HealthCheck))


@pytest.fixture(scope="module")
def rclpy_context():
    from conftest import fresh_domain_id
    os.environ["ROS_DOMAIN_ID"] = str(fresh_domain_id())
    os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    rclpy.init()
    yield
    rclpy.try_shutdown()


_attach, _levels, _chunk, _window_msg = nc.attach, nc.levels, nc.chunk, nc.window_msg


@pytest.fixture(scope="module")
def windowing_node(rclpy_context):
    node = nc.windowing_node()
    yield node
    node.destroy_node()


@pytest.mark.ros
@SETTINGS
@given(nc.chunk_messages())
def test_fuzz_windowing_node_takes_any_chunk(windowing_node, messages):
    nc.check_windowing_node(windowing_node, messages)


@pytest.fixture(scope="module")
def denoise_node(rclpy_context):
    node = nc.denoise_node()
    yield node
    node.destroy_node()


@pytest.mark.ros
@SETTINGS
@given(nc.window_messages())
def test_fuzz_denoise_node_takes_any_window(denoise_node, msg):
    nc.check_denoise_node(denoise_node, msg)


@pytest.fixture(scope="module")
def classifier_node(rclpy_context):
    node = nc.classifier_node()
    yield node
    node.destroy_node()


@pytest.mark.ros
@SETTINGS
@given(nc.window_messages())
def test_fuzz_classifier_node_takes_any_window_and_then_classifies_a_good_one(classifier_node, msg):
    nc.check_classifier_node(classifier_node, msg)


@pytest.mark.ros
def test_windowing_node_warns_on_a_nan_chunk_and_windows_resume(rclpy_context):
    from backlash_monitor.nodes.windowing import WindowingNode
    node = _attach(WindowingNode())
    data, _ = fc.synthetic_stream()
    try:
        for lo in range(0, data["a1"].size, 1000):
            for name in fc.SIGNALS:
                x = data[name][lo:lo + 1000].copy()
                if lo == 3000 and name == "angle_difference":
                    x[10] = np.nan
                node.on_chunk(name, _chunk(name, lo, 2e-5, x))
        entries = [w.entry_sample_index for w in node.publisher.messages]
        assert any(e > 4000 for e in entries) and len(entries) >= 8
        status = node.diagnostics.publisher.messages[-1].status[0]
        assert status.level == DiagnosticStatus.WARN and "non_finite_samples" in status.message
        node.health.last_fault_s -= 3600          # the fault is over: OK again
        node.diagnostics.publish()
        assert node.diagnostics.publisher.messages[-1].status[0].level == DiagnosticStatus.OK
        node.health.last_input_s -= 3600          # and no chunk for an hour: STALE
        node.diagnostics.publish()
        assert node.diagnostics.publisher.messages[-1].status[0].level == DiagnosticStatus.STALE
    finally:
        node.destroy_node()


@pytest.mark.ros
def test_classifier_node_bad_windows_warn_with_the_reason_not_error(rclpy_context):
    from backlash_monitor.nodes.classifier import ClassifierNode
    node = _attach(ClassifierNode())
    try:
        a1 = np.zeros(2048)
        a1[5] = np.nan
        node.on_window(_window_msg(a1, np.zeros(2048)))
        node.on_window(_window_msg(np.zeros(1000), np.zeros(1000), index=1))
        assert node.publisher.messages == []
        status = node.diagnostics.publisher.messages[-1].status[0]
        assert status.level == DiagnosticStatus.WARN, status
        assert "wrong_window_length" in status.message
        values = {kv.key: kv.value for kv in status.values}
        assert values["windows_rejected"] == "2"
        assert "non_finite_samples 1" in values["input_faults"]
    finally:
        node.destroy_node()
