"""HistorySubscription on the LeanExecutor: a late reader gets a transient-local writer's history, every
message handed on once and in order, and a history the check calls passed over is reported, not dropped.

The middleware's passing-over of a history under load (docs/graph.md "Not always 0") cannot be made to happen
on demand. What the check reads can: rmw's sequence numbers and time stamps on a real writer. A history cut
by a depth of 5 within milliseconds looks to it like a history passed over (its first message is young and
not the writer's first; no writer of windows publishes 1000 in 2 s), so the report's path runs on it.
"""
import threading
import time

import pytest
import rclpy
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Int32

from backlash_monitor.ros.history_subscription import HistorySubscription
from backlash_monitor.ros.lean_executor import LeanExecutor
from backlash_monitor.windowing.faults import FaultLog


def _qos(depth: int) -> QoSProfile:
    return QoSProfile(depth=depth, reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST)


@pytest.fixture
def context():
    ctx = rclpy.Context()
    rclpy.init(context=ctx)
    yield ctx
    rclpy.try_shutdown(context=ctx)


def _late_reader(context, depth: int, published: int, timeout_s: float = 30.0):
    """A writer publishes ``published`` messages (depth ``depth``); then a reader with a HistorySubscription
    joins on a LeanExecutor. -> (the values handed on, the check, the checks reported as passed over)."""
    writer = rclpy.create_node("history_writer", context=context)
    pub = writer.create_publisher(Int32, "history/in", _qos(depth))
    for k in range(1, published + 1):
        pub.publish(Int32(data=k))
    reader = rclpy.create_node("history_reader", context=context)
    got, reported, faults = [], [], FaultLog()
    sub = HistorySubscription(reader, Int32, "history/in", lambda m: got.append(m.data), _qos(depth),
                              faults=faults, on_passed_over=lambda: reported.append(sub.check.missed_before))
    executor = LeanExecutor(context=context)
    executor.add_node(reader)
    executor.add_node(writer)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and len(got) < min(depth, published):
        time.sleep(0.05)
    time.sleep(0.5)    # anything handed on twice would come now
    executor.shutdown()
    thread.join(timeout=10)
    reader.destroy_node()
    writer.destroy_node()
    assert faults.counts["history_passed_over"] == len(reported)
    if reported:
        assert faults.last == ("history_passed_over", f"history/in before sequence number {reported[-1]}")
    return got, sub.check, reported


@pytest.mark.ros
def test_a_late_reader_gets_the_whole_history_once_in_order(context):
    got, check, reported = _late_reader(context, depth=50, published=20)
    assert got == list(range(1, 21))
    assert check.passed_over == 0 and reported == []
    assert not check.judging                        # sequence number 1 first: the whole history


@pytest.mark.ros
def test_a_history_the_check_calls_passed_over_is_reported_and_every_message_handed_on(context):
    got, check, reported = _late_reader(context, depth=5, published=20)
    assert got == [16, 17, 18, 19, 20]              # the writer's depth: its last 5, in order, once
    assert check.passed_over == 1 and reported == [16]
    assert check.last_span == 0                     # judged at the first message: young, and not number 1
