"""ros/delivery.wait_acknowledged: one deadline over every topic, the topics still behind named, a zero bound
never read as rclpy's "wait for ever" -- on publishers standing in for rclpy's (their wait_for_all_acked), and
on a real reliable publisher."""
import time

import pytest
import rclpy
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import Int32

from backlash_monitor.ros.delivery import MIN_WAIT_S, wait_acknowledged


class _Publisher:
    """Acknowledged after ``ack_s`` of waiting (None: never); records the durations it was given."""

    def __init__(self, ack_s):
        self.ack_s, self.asked_s = ack_s, []

    def wait_for_all_acked(self, duration):
        asked = duration.nanoseconds / 1e9
        self.asked_s.append(asked)
        if self.ack_s is not None and self.ack_s <= asked:
            time.sleep(self.ack_s)
            return True
        time.sleep(asked)
        return False


def test_all_acknowledged_names_none():
    pubs = {"plant/a1": _Publisher(0.0), "plant/a2": _Publisher(0.01)}
    assert wait_acknowledged(pubs, 1.0) == []


def test_the_topics_behind_are_named_and_one_deadline_bounds_them_all():
    slow, never, late = _Publisher(None), _Publisher(None), _Publisher(0.05)
    t0 = time.monotonic()
    behind = wait_acknowledged({"x": slow, "y": never, "z": late}, 0.3)
    spent = time.monotonic() - t0
    assert behind == ["x", "y", "z"]          # z's 0.05 s no longer fits: the deadline has passed
    assert slow.asked_s[0] == pytest.approx(0.3, abs=0.05)
    assert never.asked_s == [MIN_WAIT_S] and late.asked_s == [MIN_WAIT_S]   # what was left: the least wait
    assert spent < 0.3 + 0.3                  # not 3 x the bound (a loose bound: no wall-clock claim)


@pytest.mark.parametrize("bound_s", [0.0, -1.0])
def test_a_zero_bound_waits_the_least_not_for_ever(bound_s):
    pub = _Publisher(None)
    assert wait_acknowledged({"t": pub}, bound_s) == ["t"]
    assert pub.asked_s == [MIN_WAIT_S]


@pytest.mark.ros
def test_a_real_reliable_publisher_without_subscribers_has_nothing_to_wait_for():
    ctx = rclpy.Context()
    rclpy.init(context=ctx)
    try:
        node = rclpy.create_node("delivery_probe", context=ctx)
        pub = node.create_publisher(Int32, "delivery_probe", QoSProfile(depth=10,
                                    reliability=ReliabilityPolicy.RELIABLE))
        pub.publish(Int32(data=1))
        assert wait_acknowledged({"delivery_probe": pub}, 5.0) == []
        node.destroy_node()
    finally:
        rclpy.shutdown(context=ctx)
