"""Fuzz properties of the nodes' message handling, shared by test/nodes/test_fuzz_nodes.py and
bench/reliability.py: the windowing, denoise and classifier callbacks are called with generated
messages (no DDS traffic: the publishers are replaced by lists). No exception escapes a
callback; what a node publishes is valid; a bad input never turns the status to ERROR; after a
bad window the next good one is classified. The nodes need rclpy.init() first."""
from __future__ import annotations

import numpy as np
from hypothesis import strategies as st

import fuzz_cores as fc
from backlash_monitor.denoise import denoising_label
from backlash_monitor.ros.conversions import to_float64_array


class Sink:
    def __init__(self):
        self.messages = []

    def publish(self, msg):
        self.messages.append(msg)


def attach(node):
    """Replace the node's publishers (data and /diagnostics) by lists."""
    node.publisher = Sink()
    node.diagnostics.publisher = Sink()
    return node


def levels(node):
    return [m.status[0].level for m in node.diagnostics.publisher.messages]


def chunk(name, first, period, samples):
    from backlash_monitor_msgs.msg import SignalChunk
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
        out.append(chunk(name, first, period, samples))
    return out


def window_msg(a1, a2, kind="onset", period=2e-5, denoised=True, index=0, offsets=(0.0, 0.0, 8)):
    """A window message; ``offsets``: (a1_offset_m_s2, a2_offset_m_s2, offset_periods)."""
    from backlash_monitor_msgs.msg import BacklashWindow
    msg = BacklashWindow(entry_sample_index=int(index), entry_kind=kind, trigger="contact_loss",
                         sample_period_s=float(period),
                         denoising=denoising_label(6, (1, 2, 3, 4, 5, 6), "symmetric") if denoised else "",
                         true_width_m=float("nan"), a1_offset_m_s2=float(offsets[0]),
                         a2_offset_m_s2=float(offsets[1]), offset_periods=int(offsets[2]))
    msg.a1, msg.a2 = to_float64_array(a1), to_float64_array(a2)
    return msg


@st.composite
def window_messages(draw):
    a1, a2, kind, period, offsets = draw(fc.estimator_windows())
    pair = (0.0, 0.0) if offsets is None else offsets
    return window_msg(a1, a2, kind, 2e-5 if period is None else period,
                      denoised=draw(st.booleans()) or draw(st.booleans()),
                      index=draw(st.integers(0, 2 ** 64 - 1)),
                      offsets=(*pair, draw(st.sampled_from([0, 1, 8, 2 ** 32 - 1]))))


def windowing_node():
    from backlash_monitor.nodes.windowing import WindowingNode
    return attach(WindowingNode())


def denoise_node():
    from backlash_monitor.nodes.denoise import DenoiseNode
    return attach(DenoiseNode())


def classifier_node():
    from rclpy.parameter import Parameter
    from backlash_monitor.nodes.classifier import ClassifierNode
    # thresholds no width reaches: an ERROR could only come from bad input
    return attach(ClassifierNode(parameter_overrides=[
        Parameter("warn_width_m", value=1.0), Parameter("error_width_m", value=1.0)]))


def _no_error(node):
    from diagnostic_msgs.msg import DiagnosticStatus
    assert DiagnosticStatus.ERROR not in levels(node)
    node.diagnostics.publisher.messages.clear()     # bounded memory over many examples


def check_windowing_node(node, messages):
    fc.INPUTS["windowing_node"] += 1
    for msg in messages:
        node.on_chunk(msg.signal_name, msg)
    for w in node.publisher.messages:
        assert len(w.a1) == len(w.a2) == 2048
        assert np.isfinite(w.a1).all() and np.isfinite(w.a2).all()
    node.publisher.messages.clear()
    _no_error(node)


def check_denoise_node(node, msg):
    fc.INPUTS["denoise_node"] += 1
    node.on_window(msg)
    for w in node.publisher.messages:
        assert len(w.a1) == len(w.a2) and np.isfinite(w.a1).all() and np.isfinite(w.a2).all()
    node.publisher.messages.clear()
    _no_error(node)


_GOOD_INDEX = iter(range(10 ** 12))


def check_classifier_node(node, msg):
    fc.INPUTS["classifier_node"] += 1
    widths = set(np.round(node.estimator.widths_m, 12))
    g1, g2 = fc.good_window()
    node.on_window(msg)
    good = window_msg(g1, g2, index=next(_GOOD_INDEX))
    good.header.frame_id = "good"      # not a repeat of a generated window
    node.on_window(good)
    new = node.publisher.messages
    assert len([e for e in new if e.header.frame_id == "good"]) == 3   # the good window
    for e in new:
        assert round(e.width_m, 12) in widths and round(e.fused_width_m, 12) in widths
        assert len(e.b_vector) == 6 and np.isfinite(e.b_vector).all() and min(e.b_vector) >= 0
    node.publisher.messages.clear()
    _no_error(node)
