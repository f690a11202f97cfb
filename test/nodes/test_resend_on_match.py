"""ResendOnMatch (ros/resend_on_match.py): a window publisher sends its last windows again when a reader matches.

A reader with VOLATILE durability gets nothing of the writer's DDS history, so every window it receives from before it
matched came from the re-send: that is the path a restarted node takes when the history is not delivered to it
(docs/graph.md "What a restart loses"). Then the denoise node, fed the same windows twice, denoises each once."""
import threading
import time

import pytest
import rclpy
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

from backlash_monitor.ros.lean_executor import LeanExecutor
from backlash_monitor.ros.qos import WINDOW_QOS
from backlash_monitor.ros.resend_on_match import ResendOnMatch
from backlash_monitor_msgs.msg import BacklashWindow

VOLATILE = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE,
                      history=HistoryPolicy.KEEP_LAST)


@pytest.fixture
def context():
    ctx = rclpy.Context()
    rclpy.init(context=ctx)
    yield ctx
    rclpy.try_shutdown(context=ctx)


def _window(i: int) -> BacklashWindow:
    msg = BacklashWindow()
    msg.header.frame_id = "drive"
    msg.header.stamp.sec = 100 + i
    msg.entry_sample_index = 1000 * i
    msg.entry_kind = "onset"
    return msg


class Spinning:
    def __init__(self, context, *nodes):
        self.executor = LeanExecutor(context=context)
        for node in nodes:
            self.executor.add_node(node)
        self.thread = threading.Thread(target=self.executor.spin, daemon=True)
        self.thread.start()

    def stop(self):
        self.executor.shutdown()
        self.thread.join(timeout=10)


def _wait(predicate, timeout_s=30.0):
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and not predicate():
        time.sleep(0.02)
    return predicate()


@pytest.mark.ros
def test_a_reader_that_gets_no_history_gets_the_last_windows_again_in_order(context):
    writer = rclpy.create_node("writer", context=context)
    reader = rclpy.create_node("reader", context=context)
    resender = ResendOnMatch(writer, BacklashWindow, "windows/test", WINDOW_QOS, depth=5, resend_after_s=(0.3,))
    spinning = Spinning(context, writer, reader)
    try:
        for i in range(8):                       # published before any reader: only the last 5 are kept
            resender.publish(_window(i))
        got = []
        reader.create_subscription(BacklashWindow, "windows/test", lambda m: got.append(m.entry_sample_index),
                                   VOLATILE)
        assert _wait(lambda: len(got) >= 5), got
        assert got[:5] == [1000 * i for i in range(3, 8)]          # the kept ones, oldest first
        resender.publish(_window(8))                                # live after the match
        assert _wait(lambda: 8000 in got), got
        assert resender.matches == 1 and resender.resent == 5
        # a second reader matches: the first one sees the kept windows once more (its node skips them)
        second = []
        reader.create_subscription(BacklashWindow, "windows/test", lambda m: second.append(m.entry_sample_index),
                                   VOLATILE)
        assert _wait(lambda: len(second) >= 5 and got.count(8000) == 2), (got, second)
        assert second[:5] == [1000 * i for i in range(4, 9)] and resender.resent == 10
    finally:
        spinning.stop()
        writer.destroy_node()
        reader.destroy_node()


@pytest.mark.ros
def test_the_kept_windows_are_sent_again_at_each_delay_after_a_match_in_slices(context, monkeypatch):
    """A reader that matches back late (under load: seconds) still gets them: each delay sends them once more."""
    writer = rclpy.create_node("writer3", context=context)
    reader = rclpy.create_node("reader3", context=context)
    import backlash_monitor.ros.resend_on_match as module
    monkeypatch.setattr(module, "SLICE", 3)         # 4 windows: two slices per re-send
    resender = ResendOnMatch(writer, BacklashWindow, "windows/three", WINDOW_QOS, depth=4,
                             resend_after_s=(0.2, 0.6, 1.2))
    spinning = Spinning(context, writer, reader)
    try:
        for i in range(4):
            resender.publish(_window(i))
        got = []
        reader.create_subscription(BacklashWindow, "windows/three", lambda m: got.append(m.entry_sample_index),
                                   VOLATILE)
        assert _wait(lambda: len(got) >= 12), got
        time.sleep(0.5)
        assert got == [0, 1000, 2000, 3000] * 3 and resender.resent == 12 and resender.matches == 1
        assert resender.timer.is_canceled()          # nothing due: the timer does not wake the node
    finally:
        spinning.stop()
        writer.destroy_node()
        reader.destroy_node()


@pytest.mark.ros
def test_depth_zero_sends_nothing_again_and_a_negative_depth_is_refused(context):
    writer = rclpy.create_node("writer0", context=context)
    reader = rclpy.create_node("reader0", context=context)
    with pytest.raises(ValueError, match="allowed: 0"):
        ResendOnMatch(writer, BacklashWindow, "windows/none", WINDOW_QOS, depth=-1)
    resender = ResendOnMatch(writer, BacklashWindow, "windows/zero", WINDOW_QOS, depth=0, resend_after_s=(0.1,))
    spinning = Spinning(context, writer, reader)
    try:
        resender.publish(_window(0))
        got = []
        reader.create_subscription(BacklashWindow, "windows/zero", lambda m: got.append(m.entry_sample_index),
                                   VOLATILE)
        assert _wait(lambda: resender.matches == 1)
        resender.publish(_window(1))
        assert _wait(lambda: got == [1000])
        time.sleep(0.5)
        assert resender.resent == 0 and got == [1000]
    finally:
        spinning.stop()
        writer.destroy_node()
        reader.destroy_node()


@pytest.mark.ros
def test_the_denoise_node_denoises_a_window_sent_twice_once(context):
    from backlash_monitor.nodes.denoise import DenoiseNode
    import numpy as np
    from backlash_monitor.ros.conversions import to_float64_array
    upstream = rclpy.create_node("upstream", context=context)
    denoise = DenoiseNode(context=context)
    listener = rclpy.create_node("listener", context=context)
    raw = upstream.create_publisher(BacklashWindow, "windows/raw", WINDOW_QOS)
    out = []
    listener.create_subscription(BacklashWindow, "windows/denoised", lambda m: out.append(m.entry_sample_index),
                                 WINDOW_QOS)
    spinning = Spinning(context, upstream, denoise, listener)
    try:
        rng = np.random.default_rng(0)
        windows = []
        for i in range(3):
            w = _window(i)
            w.a1, w.a2 = to_float64_array(rng.normal(size=2048)), to_float64_array(rng.normal(size=2048))
            windows.append(w)
        assert _wait(lambda: raw.get_subscription_count() >= 1)
        for w in windows + windows:             # the same three windows twice (a re-send)
            raw.publish(w)
        assert _wait(lambda: len(out) >= 3)
        time.sleep(0.5)
        # each denoised once; the listener may see them again (the denoise node's own re-send after it matched)
        assert sorted(set(out)) == [0, 1000, 2000]
        assert denoise.repeated.repeats == 3 and denoise.counts["denoised"] == 3
    finally:
        spinning.stop()
        for node in (upstream, denoise, listener):
            node.destroy_node()
