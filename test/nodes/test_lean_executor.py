"""LeanExecutor serves what the project's nodes use, as rclpy's own executor would.

Subscriptions, timers, the parameter services (get/set, with the node's validation), QoS-event
callbacks, entities created while spinning, and a clean release of the node at the end.
"""
import threading
import time

import pytest
import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.event_handler import SubscriptionEventCallbacks
from rclpy.parameter import Parameter
from rclpy.parameter_client import AsyncParameterClient
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import Float64

from backlash_monitor.ros.lean_executor import LeanExecutor, make_executor
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)


@pytest.fixture
def context():
    ctx = rclpy.Context()
    rclpy.init(context=ctx)
    yield ctx
    rclpy.try_shutdown(context=ctx)


class Served:
    """A node on a LeanExecutor spinning in a thread."""

    def __init__(self, context):
        self.node = rclpy.create_node("served", context=context)
        declare_and_validate(self.node, (ParameterSpec("width_m", 0.005, "width [m]", 1e-4, 0.05,
                                                           read_only=False),))
        self.received, self.ticks, self.late = [], [], []
        self.node.create_subscription(Float64, "lean/in", lambda m: self.received.append(m.data), 10)
        self.node.create_timer(0.05, lambda: self.ticks.append(time.monotonic()))
        self.executor = LeanExecutor(context=context)
        self.executor.add_node(self.node)
        self.thread = threading.Thread(target=self.executor.spin, daemon=True)
        self.thread.start()

    def stop(self):
        self.executor.shutdown()
        self.thread.join(timeout=10)
        assert not self.thread.is_alive()
        self.node.destroy_node()   # the executor released every handle: this does not block


@pytest.fixture
def served(context):
    served = Served(context)
    yield served
    served.stop()


@pytest.fixture
def client(context):
    """A second node on rclpy's own executor: (node, executor)."""
    node = rclpy.create_node("client", context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    yield node, executor
    node.destroy_node()


def _spin_until(executor, condition, timeout_s=20.0):
    deadline = time.monotonic() + timeout_s
    while not condition() and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.05)
    return condition()


@pytest.mark.ros
def test_subscriptions_timers_and_parameter_services(served, client):
    client_node, executor = client
    pub = client_node.create_publisher(Float64, "lean/in", 10)
    assert _spin_until(executor, lambda: pub.get_subscription_count() == 1)
    for value in (1.0, 2.0, 3.0):
        pub.publish(Float64(data=value))
    assert _spin_until(executor, lambda: len(served.received) == 3)
    assert served.received == [1.0, 2.0, 3.0]
    assert _spin_until(executor, lambda: len(served.ticks) >= 3)

    params = AsyncParameterClient(client_node, "served")
    assert params.wait_for_services(timeout_sec=20.0)
    future = params.get_parameters(["width_m"])
    executor.spin_until_future_complete(future, timeout_sec=20.0)
    assert future.result().values[0].double_value == 0.005
    future = params.set_parameters([Parameter("width_m", value=0.0075)])
    executor.spin_until_future_complete(future, timeout_sec=20.0)
    assert future.result().results[0].successful
    assert served.node.get_parameter("width_m").value == 0.0075
    future = params.set_parameters([Parameter("width_m", value=0.5)])   # out of range
    executor.spin_until_future_complete(future, timeout_sec=20.0)
    result = future.result().results[0]
    assert not result.successful and "0.05" in result.reason   # the range is named
    assert served.node.get_parameter("width_m").value == 0.0075


@pytest.mark.ros
def test_entities_created_while_spinning_and_qos_events_are_served(served, client):
    events = []
    served.node.create_subscription(   # created after the executor built its wait set
        Float64, "lean/late", lambda m: served.late.append(m.data),
        QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE),
        event_callbacks=SubscriptionEventCallbacks(incompatible_qos=events.append))
    client_node, executor = client
    good = client_node.create_publisher(Float64, "lean/late", 10)
    assert _spin_until(executor, lambda: good.get_subscription_count() == 1)
    good.publish(Float64(data=7.0))
    assert _spin_until(executor, lambda: served.late == [7.0])
    client_node.create_publisher(   # best effort cannot serve a reliable reader: a QoS event
        Float64, "lean/late", QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT))
    assert _spin_until(executor, lambda: len(events) >= 1)
    assert events[0].total_count >= 1


@pytest.mark.ros
def test_the_environment_variable_chooses_the_executor(monkeypatch, context):
    monkeypatch.setenv("BACKLASH_MONITOR_EXECUTOR", "rclpy")
    assert type(make_executor(context)) is SingleThreadedExecutor
    monkeypatch.setenv("BACKLASH_MONITOR_EXECUTOR", "lean")
    assert type(make_executor(context)) is LeanExecutor
    monkeypatch.setenv("BACKLASH_MONITOR_EXECUTOR", "fast")
    with pytest.raises(ParameterValueError, match="allowed: lean, rclpy"):
        make_executor(context)


@pytest.mark.ros
def test_batching_takes_every_waiting_message_one_subscription_after_the_other(context, client):
    """batch_s: the messages collect, then every waiting one is taken, the subscriptions in turn (a joiner's
    chunks of one range stay together), none lost, each topic in its order."""
    node = rclpy.create_node("batched", context=context)
    got = []
    for topic in ("lean/a", "lean/b"):
        node.create_subscription(Float64, topic, lambda m, t=topic: got.append((t, m.data)),
                                 QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE))
    executor = LeanExecutor(context=context, batch_s=0.2)
    executor.add_node(node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    try:
        client_node, client_executor = client
        pubs = [client_node.create_publisher(Float64, t, QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE))
                for t in ("lean/a", "lean/b")]
        assert _spin_until(client_executor, lambda: all(p.get_subscription_count() == 1 for p in pubs))
        for i in range(30):
            for p in pubs:
                p.publish(Float64(data=float(i)))
        assert _spin_until(client_executor, lambda: len(got) == 60)
        time.sleep(0.3)
    finally:
        executor.shutdown()
        thread.join(timeout=10)
        node.destroy_node()
    assert len(got) == 60
    for topic in ("lean/a", "lean/b"):
        assert [v for t, v in got if t == topic] == [float(i) for i in range(30)]
    runs, run = [], 1
    for (t0, _), (t1, _) in zip(got, got[1:]):
        run = run + 1 if t1 == t0 else 1
        runs.append(run)
    assert max(runs) <= 3          # in turn, not one topic's 30 and then the other's


@pytest.mark.ros
def test_batching_pauses_adapt_to_the_fullest_queue(context):
    executor = LeanExecutor(context=context, batch_s=0.1)
    assert executor._took_at is None and executor._pause_s == pytest.approx(0.1 / 16)
    executor._adapt(1.0, took=4, fullest=0.004)       # queues nearly empty: the pause grows to batch_s
    assert executor._took_at == 1.0 and executor._pause_s == pytest.approx(0.1 / 8)
    for k in range(6):
        executor._adapt(1.0 + k, took=4, fullest=0.004)
    assert executor._pause_s == pytest.approx(0.1)
    executor._adapt(7.0, took=8, fullest=0.6)         # a queue more than half full (best effort, depth 5): halved
    assert executor._pause_s == pytest.approx(0.05)
    executor._adapt(8.0, took=3, fullest=0.4)         # between: kept
    assert executor._pause_s == pytest.approx(0.05)
    executor._adapt(9.0, took=0, fullest=0.0)         # nothing was waiting: no pause before the next wake-up
    assert executor._took_at is None
    with pytest.raises(ValueError, match="batch_s"):
        LeanExecutor(context=context, batch_s=2.0)
