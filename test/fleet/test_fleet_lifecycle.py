"""Managed drives: a supervisor brings one drive's chain down and up over the lifecycle services
(lifecycle_msgs ChangeState / GetState) while another drive keeps running."""
import os
import subprocess
import time

import pytest
from ament_index_python.packages import get_package_prefix

PREFIX = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")


def start(executable, drive, *params, activate=False):
    return subprocess.Popen(
        [os.path.join(PREFIX, executable)] + (["--activate"] if activate else [])
        + ["--ros-args", "-r", f"__ns:=/line1/{drive}", "-p", f"drive_name:=line1/{drive}",
           "-p", "qos:=reliable", *params],
        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)


@pytest.fixture
def ros(ros_env, monkeypatch):
    for key in ("ROS_DOMAIN_ID", "ROS_AUTOMATIC_DISCOVERY_RANGE"):
        monkeypatch.setenv(key, ros_env[key])
    import rclpy
    from backlash_monitor.ros.fast_dds import configure_fast_dds
    configure_fast_dds()
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node("supervisor", context=context)
    from rclpy.executors import SingleThreadedExecutor
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    yield node, executor
    node.destroy_node()
    rclpy.shutdown(context=context)


def end_all(procs, timeout=20.0) -> list[str]:
    """SIGTERM every process, then their outputs; one that has not exited ``timeout`` s after it is
    killed (no orphan left running after the test: one once spun on for 23 minutes) and the test
    fails, naming it."""
    for p in procs:
        p.terminate()
    outputs, hung = [], []
    deadline = time.monotonic() + timeout
    for p in procs:
        try:
            outputs.append(p.communicate(timeout=max(0.1, deadline - time.monotonic()))[0])
        except subprocess.TimeoutExpired:
            p.kill()
            outputs.append(p.communicate()[0])
            hung.append(" ".join(p.args[-6:]))
    assert not hung, f"no exit within {timeout} s of SIGTERM: {hung}"
    return outputs


def call(node, executor, srv_type, name, request, timeout=30.0):
    client = node.create_client(srv_type, name)
    assert client.wait_for_service(timeout_sec=timeout), f"no service {name}"
    future = client.call_async(request)
    executor.spin_until_future_complete(future, timeout_sec=timeout)
    node.destroy_client(client)
    assert future.done(), f"{name}: no answer"
    return future.result()


@pytest.mark.process
@pytest.mark.ros
def test_a_supervisor_takes_one_drive_down_and_up_without_touching_the_other(ros):
    from lifecycle_msgs.msg import State, Transition
    from lifecycle_msgs.srv import ChangeState, GetState
    from backlash_monitor.ros.qos import ESTIMATE_QOS
    from backlash_monitor_msgs.msg import BacklashEstimate
    node, executor = ros
    arrivals = {"drive01": [], "drive02": []}
    for drive in arrivals:
        node.create_subscription(BacklashEstimate, f"/line1/{drive}/estimate",
                                 lambda m, d=drive: arrivals[d].append(time.monotonic()),
                                 ESTIMATE_QOS)
    procs = [start("managed_chain", "drive01"), start("managed_chain", "drive02", activate=True),
             start("managed_plant", "drive01", "-p", "duration_s:=60.0",
                   "-p", "wait_for_subscriptions:=3", activate=True),
             start("managed_plant", "drive02", "-p", "duration_s:=60.0",
                   "-p", "wait_for_subscriptions:=3", activate=True)]
    try:
        def state():
            return call(node, executor, GetState, "/line1/drive01/chain/get_state",
                        GetState.Request()).current_state.id

        def change(transition_id):
            return call(node, executor, ChangeState, "/line1/drive01/chain/change_state",
                        ChangeState.Request(transition=Transition(id=transition_id))).success

        def spin_for(seconds):
            end = time.monotonic() + seconds
            while time.monotonic() < end:
                executor.spin_once(timeout_sec=0.05)

        def spin_until(condition, timeout_s=20.0):
            """Spin until ``condition()`` holds: after an activation the plant first discovers the chain's
            subscriptions (it waits for 3), which takes DDS discovery's time (seconds at times)."""
            end = time.monotonic() + timeout_s
            while not condition() and time.monotonic() < end:
                executor.spin_once(timeout_sec=0.05)
            return condition()

        assert state() == State.PRIMARY_STATE_UNCONFIGURED
        spin_for(3.0)
        assert arrivals["drive01"] == []              # unconfigured: no chain, no estimate
        assert change(Transition.TRANSITION_CONFIGURE) and state() == State.PRIMARY_STATE_INACTIVE
        assert change(Transition.TRANSITION_ACTIVATE) and state() == State.PRIMARY_STATE_ACTIVE
        assert spin_until(lambda: len(arrivals["drive01"]) >= 6), arrivals["drive01"]   # active: onsets every
        # 0.25 s, 3 signals
        assert change(Transition.TRANSITION_DEACTIVATE) and state() == State.PRIMARY_STATE_INACTIVE
        spin_for(0.5)
        down_at, before = time.monotonic(), len(arrivals["drive02"])
        spin_for(3.0)
        assert [t for t in arrivals["drive01"] if t > down_at] == []   # drive01 is down ...
        assert len(arrivals["drive02"]) - before >= 9                  # ... drive02 is not
        assert change(Transition.TRANSITION_ACTIVATE) and state() == State.PRIMARY_STATE_ACTIVE
        up_at = time.monotonic()
        assert spin_until(lambda: len([t for t in arrivals["drive01"] if t > up_at]) >= 6)   # and up again
        assert change(Transition.TRANSITION_DEACTIVATE)
        assert change(Transition.TRANSITION_CLEANUP) and state() == State.PRIMARY_STATE_UNCONFIGURED
    finally:
        outputs = end_all(procs)
    assert all("Traceback" not in out for out in outputs), outputs
    assert [p.returncode for p in procs] == [0] * len(procs), outputs


@pytest.mark.process
@pytest.mark.ros
def test_a_bad_parameter_fails_the_configure_transition_with_one_clear_line(ros):
    from lifecycle_msgs.msg import State, Transition
    from lifecycle_msgs.srv import ChangeState, GetState
    node, executor = ros
    proc = start("managed_chain", "drive09", "-p", "n1:=7.0")
    try:
        result = call(node, executor, ChangeState, "/line1/drive09/chain/change_state",
                      ChangeState.Request(transition=Transition(
                          id=Transition.TRANSITION_CONFIGURE)))
        assert not result.success
        assert call(node, executor, GetState, "/line1/drive09/chain/get_state",
                    GetState.Request()).current_state.id == State.PRIMARY_STATE_UNCONFIGURED
    finally:
        out = end_all([proc])[0]
    assert "configure failed: parameter 'n1'" in out and "allowed: 0.5 <= n1 <= 1.5" in out, out
    assert "Traceback" not in out


@pytest.mark.process
@pytest.mark.ros
def test_by_hand_a_new_library_is_taken_at_the_next_configure(ros, tmp_path):
    """What `ros2 param set` and `ros2 lifecycle set` do by hand (docs/registry.md, live pickup): the chain's
    library and model_version parameters reach its classifier when the chain is configured again."""
    import shutil
    from diagnostic_msgs.msg import DiagnosticArray
    from lifecycle_msgs.msg import Transition
    from lifecycle_msgs.srv import ChangeState
    from rcl_interfaces.srv import SetParameters
    from rclpy.parameter import Parameter
    from backlash_monitor.classifier.patterns import TRIGGER_LIBRARY_PATHS
    node, executor = ros
    library = tmp_path / "drive08_v3.npz"
    shutil.copy(TRIGGER_LIBRARY_PATHS["contact_loss"], library)
    said = []     # (model_version, library) of the classifier's statuses
    node.create_subscription(DiagnosticArray, "/diagnostics", lambda msg: said.extend(
        (v.get("model_version"), v.get("library", "")) for v in (
            {kv.key: kv.value for kv in s.values} for s in msg.status
            if s.name.startswith("line1/drive08/classifier"))), 50)
    procs = [start("managed_chain", "drive08", activate=True),
             start("managed_plant", "drive08", "-p", "duration_s:=60.0", "-p", "wait_for_subscriptions:=3",
                   activate=True)]

    def spin_until(condition, timeout_s=30.0):
        end = time.monotonic() + timeout_s
        while not condition() and time.monotonic() < end:
            executor.spin_once(timeout_sec=0.05)
        return condition()
    try:
        assert spin_until(lambda: ("0", str(TRIGGER_LIBRARY_PATHS["contact_loss"])) in said), said[-3:]
        result = call(node, executor, SetParameters, "/line1/drive08/chain/set_parameters", SetParameters.Request(
            parameters=[Parameter("library", value=str(library)).to_parameter_msg(),
                        Parameter("model_version", value=3).to_parameter_msg()]))
        assert all(r.successful for r in result.results)
        for transition in (Transition.TRANSITION_DEACTIVATE, Transition.TRANSITION_CLEANUP,
                           Transition.TRANSITION_CONFIGURE, Transition.TRANSITION_ACTIVATE):
            assert call(node, executor, ChangeState, "/line1/drive08/chain/change_state",
                        ChangeState.Request(transition=Transition(id=transition))).success
        assert spin_until(lambda: ("3", str(library)) in said), said[-3:]
    finally:
        outputs = end_all(procs)
    assert all("Traceback" not in out for out in outputs), outputs
