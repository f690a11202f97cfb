"""HistorySubscription on the LeanExecutor: a late reader gets a transient-local writer's history, and
one that asks again (a new subscription) gets it again, each message handed on once and in order.

The middleware's passing-over of a history under load (docs/graph.md "Not always 0") cannot be made
to happen on demand; the way back from it can: a writer whose history its depth has cut and whose
messages are young looks to the check like a live first message, so the reader asks again (a new
subscription, the old one destroyed while the executor spins) until it goes on with what comes.
"""
import threading
import time

import pytest
import rclpy
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import Int32

from backlash_monitor.chain.late_join import MAX_RESUBSCRIBES, LateJoinCheck
from backlash_monitor.ros.history_subscription import HistorySubscription
from backlash_monitor.ros.lean_executor import LeanExecutor


def _qos(depth: int) -> QoSProfile:
    return QoSProfile(depth=depth, reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST)


@pytest.fixture
def context():
    ctx = rclpy.Context()
    rclpy.init(context=ctx)
    yield ctx
    rclpy.try_shutdown(context=ctx)


def _late_reader(context, depth: int, published: int, timeout_s: float = 30.0, check=None):
    """A writer publishes ``published`` messages (depth ``depth``); then a reader with a HistorySubscription
    joins on a LeanExecutor. -> (the values it handed on, its check, its node's subscription count)."""
    writer = rclpy.create_node("history_writer", context=context)
    pub = writer.create_publisher(Int32, "history/in", _qos(depth))
    for k in range(1, published + 1):
        pub.publish(Int32(data=k))
    reader = rclpy.create_node("history_reader", context=context)
    got = []
    sub = HistorySubscription(reader, Int32, "history/in", lambda m: got.append(m.data), _qos(depth), check)
    executor = LeanExecutor(context=context)
    executor.add_node(reader)
    executor.add_node(writer)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    expected = min(depth, published)
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline and (len(got) < expected or sub.check.in_a_row or sub.check.holding):
        time.sleep(0.05)
    time.sleep(0.5)    # anything handed on twice would come now
    executor.shutdown()
    thread.join(timeout=10)
    n_subs = len(list(reader.subscriptions))
    reader.destroy_node()
    writer.destroy_node()
    return got, sub.check, n_subs


@pytest.mark.ros
def test_a_late_reader_gets_the_whole_history_once_in_order(context):
    got, check, n_subs = _late_reader(context, depth=50, published=20)
    assert got == list(range(1, 21))
    assert (check.resubscribes, check.gave_up) == (0, 0)
    assert n_subs == 1


@pytest.mark.ros
def test_asking_again_gets_the_history_again_and_hands_each_message_on_once(context):
    # depth 5 of 20 published: the first message is number 16, just published -- a live one to the check
    got, check, n_subs = _late_reader(context, depth=5, published=20)
    assert check.resubscribes == MAX_RESUBSCRIBES
    assert check.gave_up == 1
    assert check.last_span == 0                  # each new match was served the same history again: 16 first
    assert got == [16, 17, 18, 19, 20]           # the first of each dropped one handed on after the last ask
    assert n_subs == 1                           # the replaced subscriptions are gone


@pytest.mark.ros
def test_a_cut_history_older_than_a_live_message_is_taken_at_once(context):
    # the same cut history, with a check for which a live message is at most 1 ns old: held till the depth's
    # 5 messages came, then handed on whole
    got, check, n_subs = _late_reader(context, depth=5, published=20, check=LateJoinCheck(depth=5, live_age_s=1e-9))
    assert got == [16, 17, 18, 19, 20]
    assert (check.resubscribes, check.gave_up, check.last_release) == (0, 0, "whole")
    assert n_subs == 1
