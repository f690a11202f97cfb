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
from hypothesis import strategies as st

import fuzz_cores as fc
from backlash_monitor.chain import denoising_label
from backlash_monitor.nodes.conversions import to_float64_array
from backlash_monitor_msgs.msg import BacklashWindow, SignalChunk

pytestmark = pytest.mark.filterwarnings("ignore::hypothesis.errors.HypothesisWarning")

SETTINGS = settings(max_examples=120, deadline=None, database=None, derandomize=True,
                    suppress_health_check=list(HealthCheck))


class Sink:
    def __init__(self):
        self.messages = []

    def publish(self, msg):
        self.messages.append(msg)


@pytest.fixture(scope="module")
def rclpy_context():
    from conftest import fresh_domain_id
    os.environ["ROS_DOMAIN_ID"] = str(fresh_domain_id())
    os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    rclpy.init()
    yield
    rclpy.try_shutdown()


def _attach(node):
    node.publisher = Sink()
    node.diagnostics.publisher = Sink()
    return node


def _levels(node):
    return [m.status[0].level for m in node.diagnostics.publisher.messages]


def _chunk(name, first, period, samples):
    msg = SignalChunk(signal_name=name, sample_period_s=float(period), first_sample_index=int(first))
    msg.samples = to_float64_array(samples)
    return msg


ANY_FLOAT = st.floats(allow_nan=True, allow_infinity=True)


@st.composite
def chunk_messages(draw):
    out = []
    for _ in range(draw(st.integers(1, 12))):
        name = draw(st.sampled_from(fc.SIGNALS + ("omega1",)))
        first = draw(st.one_of(st.integers(0, 5000), st.integers(0, 2 ** 64 - 1)))
        period = draw(st.one_of(st.just(2e-5), ANY_FLOAT))
        n = draw(st.integers(0, 400))
        samples = np.linspace(0.04, -0.04, n)
        for k in draw(st.lists(st.integers(0, max(n - 1, 0)), max_size=2)) if n else []:
            samples[k] = draw(ANY_FLOAT)
        out.append(_chunk(name, first, period, samples))
    return out


@pytest.fixture(scope="module")
def windowing_node(rclpy_context):
    from backlash_monitor.nodes.windowing import WindowingNode
    node = _attach(WindowingNode())
    yield node
    node.destroy_node()


@SETTINGS
@given(chunk_messages())
def test_fuzz_windowing_node_takes_any_chunk(windowing_node, messages):
    node = windowing_node
    for msg in messages:
        node.on_chunk(msg.signal_name, msg)
    for w in node.publisher.messages:
        assert len(w.a1) == len(w.a2) == 2048
        assert np.isfinite(w.a1).all() and np.isfinite(w.a2).all()
    assert DiagnosticStatus.ERROR not in _levels(node)


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


def _window_msg(a1, a2, kind="onset", period=2e-5, denoised=True, index=0):
    msg = BacklashWindow(entry_sample_index=int(index), entry_kind=kind, trigger="contact_loss",
                         sample_period_s=float(period),
                         denoising=denoising_label(6, (1, 2, 3, 4, 5, 6), "symmetric") if denoised else "",
                         true_width_m=float("nan"))
    msg.a1, msg.a2 = to_float64_array(a1), to_float64_array(a2)
    return msg


@st.composite
def window_messages(draw):
    a1, a2, kind, period = draw(fc.estimator_windows())
    return _window_msg(a1, a2, kind, 2e-5 if period is None else period,
                       denoised=draw(st.booleans()) or draw(st.booleans()),
                       index=draw(st.integers(0, 2 ** 64 - 1)))


@pytest.fixture(scope="module")
def denoise_node(rclpy_context):
    from backlash_monitor.nodes.denoise import DenoiseNode
    node = _attach(DenoiseNode())
    yield node
    node.destroy_node()


@SETTINGS
@given(window_messages())
def test_fuzz_denoise_node_takes_any_window(denoise_node, msg):
    node = denoise_node
    before = len(node.publisher.messages)
    node.on_window(msg)
    for w in node.publisher.messages[before:]:
        assert len(w.a1) == len(w.a2) and np.isfinite(w.a1).all() and np.isfinite(w.a2).all()
    assert DiagnosticStatus.ERROR not in _levels(node)


@pytest.fixture(scope="module")
def classifier_node(rclpy_context):
    from rclpy.parameter import Parameter
    from backlash_monitor.nodes.classifier import ClassifierNode
    # thresholds no width reaches: an ERROR could only come from bad input
    node = _attach(ClassifierNode(parameter_overrides=[
        Parameter("warn_width_m", value=1.0), Parameter("error_width_m", value=1.0)]))
    yield node
    node.destroy_node()


GOOD_INDEX = iter(range(10 ** 9))


@SETTINGS
@given(window_messages())
def test_fuzz_classifier_node_takes_any_window_and_then_classifies_a_good_one(classifier_node, msg):
    node = classifier_node
    widths = set(np.round(node.estimator.widths_m, 12))
    g1, g2 = fc.good_window()
    before = len(node.publisher.messages)
    node.on_window(msg)
    good = _window_msg(g1, g2, index=next(GOOD_INDEX))
    good.header.frame_id = "good"      # not a repeat of a generated window
    node.on_window(good)
    new = node.publisher.messages[before:]
    assert len([e for e in new if e.header.frame_id == "good"]) == 3   # the good window
    for e in new:
        assert round(e.width_m, 12) in widths and round(e.fused_width_m, 12) in widths
        assert len(e.b_vector) == 6 and np.isfinite(e.b_vector).all() and min(e.b_vector) >= 0
    assert DiagnosticStatus.ERROR not in _levels(node)


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
