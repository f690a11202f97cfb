"""The model_watch node: a drive's plant topics in its namespace against the model version's reference; OK while
the drive is its model, WARN with a snapshot once an effect switches on mid-run; /diagnostics per drive,
model_fit messages; bad parameters stop it with one line."""
import os
import subprocess

import pytest
import rclpy
from ament_index_python.packages import get_package_prefix
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rclpy.parameter import Parameter

from backlash_monitor.nodes.model_watch import MODEL_FIT_QOS, ModelWatchNode
from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
from backlash_monitor.workbench.measurement import load_measurement
from backlash_monitor.workbench.model import load_model
from backlash_monitor_msgs.msg import ModelFit
import shared_cache                                             # test/: built by one process, the others wait

EXECUTABLE = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", "model_watch")
NS = "/line1/drive7"


@pytest.fixture(scope="module")
def ref_path():
    """The default model's reference at 5 mm (the cache; built there once, ~30 s)."""
    return str(shared_cache.watch_reference(load_model(None, width_m=0.005)).path)


@pytest.mark.ros
@pytest.mark.process
@pytest.mark.slow
def test_ok_on_its_model_then_warn_with_a_snapshot_when_friction_switches_on(ros_env, ref_path, tmp_path):
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    rclpy.init()
    fits, diags = [], []
    try:
        watch = ModelWatchNode(namespace=NS, parameter_overrides=[
            Parameter("drive_name", value="line1/drive7"), Parameter("reference", value=ref_path),
            Parameter("window_events", value=8), Parameter("qos", value="reliable"),
            Parameter("snapshot_dir", value=str(tmp_path)), Parameter("snapshot_before_s", value=0.5),
            Parameter("snapshot_after_s", value=1.0)])
        plant = PlantSimulatorNode(namespace=NS, parameter_overrides=[
            Parameter("drive_name", value="line1/drive7"), Parameter("width_m", value=0.005),
            Parameter("rate_factor", value=0.0), Parameter("duration_s", value=9.0),
            Parameter("qos", value="reliable"), Parameter("seed", value=11),
            Parameter("wait_for_subscribers", value=["model_watch:a1,a2,angle_difference,omega1"]),
            Parameter("plant_set_at", value=["5:effects.wheel_coulomb_friction=true;"
                                             "wheel_coulomb_friction.torque_Nm=2.5"])])
        probe = rclpy.create_node("probe", namespace=NS)
        probe.create_subscription(ModelFit, "model_fit", fits.append, MODEL_FIT_QOS)
        probe.create_subscription(DiagnosticArray, "/diagnostics", diags.append, 100)
        executor = rclpy.executors.SingleThreadedExecutor()
        for node in (watch, plant, probe):
            executor.add_node(node)
        for _ in range(4000):
            executor.spin_once(timeout_sec=0.01)
            if plant.finished and watch.counts["chunks"] >= 450:
                break
        watch.update_diagnostics(publish_now=True)
        for _ in range(20):
            executor.spin_once(timeout_sec=0.01)
        watch.destroy_node()          # writes what the snapshot holds
    finally:
        rclpy.try_shutdown()
    switch = int(5.0 * 50_000)
    before = [f for f in fits if f.entry_sample_index < switch]
    after = [f for f in fits if f.entry_sample_index >= switch]
    assert len(before) >= 8 and all(f.level == ModelFit.OK for f in before)
    assert any(f.level == ModelFit.WARN for f in after)
    warn = next(f for f in after if f.level == ModelFit.WARN)
    assert warn.model == "default v1" and warn.header.frame_id == "line1/drive7"
    assert list(warn.signal_names) == ["a1", "a2"] and len(warn.residual_over_noise) == 2
    assert "event_average" in list(warn.view_names) and len(warn.t2) == len(warn.view_names)
    assert warn.phase in ("before_entry", "gap_traversal", "impact", "settling") and warn.wavelet_level
    statuses = [s for d in diags for s in d.status if s.name == "line1/drive7/model_watch: model fit"]
    assert statuses and all(s.hardware_id == "line1/drive7" for s in statuses)
    warned = [s for s in statuses if s.level == DiagnosticStatus.WARN]
    assert warned and "no longer explains the drive since" in warned[0].message
    assert "snapshot line1_drive7_" in warned[0].message
    snaps = list(tmp_path.glob("line1_drive7_*.mcap"))
    assert len(snaps) == 1
    meas = load_measurement(snaps[0])                 # an ordinary bag: diagnose reads it
    # the signals diagnose reads (omega1: the record-mean view's motor speed)
    assert meas.duration_s >= 1.0 and set(meas.signals) == {"a1", "a2", "angle_difference", "omega1"}


@pytest.mark.ros
def test_a_drive_without_the_motor_speed_is_named_and_the_parameter_to_set_is_said(ros_env, ref_path, tmp_path):
    """The watch joins omega1 with a1, a2 and the angle difference (its record mean has the motor speed); a drive
    that publishes the three but no plant/omega1 gets no evaluation, and /diagnostics says WARN naming the missing
    topic and watch_omega1 false, instead of 'collecting onset events' for ever. With watch_omega1 false the same
    stream is watched."""
    import numpy as np
    from backlash_monitor_msgs.msg import SignalChunk
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    rclpy.init()
    try:
        for watch_omega1 in (True, False):
            watch = ModelWatchNode(namespace=NS, parameter_overrides=[
                Parameter("reference", value=ref_path), Parameter("qos", value="reliable"),
                Parameter("snapshot_dir", value=""), Parameter("watch_omega1", value=watch_omega1),
                Parameter("stale_after_s", value=0.5), Parameter("batch_s", value=0.0)])
            talker = rclpy.create_node("talker", namespace=NS)
            qos = rclpy.qos.QoSProfile(depth=100, reliability=rclpy.qos.ReliabilityPolicy.RELIABLE)
            pubs = {n: talker.create_publisher(SignalChunk, f"plant/{n}", qos) for n in ("a1", "a2", "angle_difference")}
            executor = rclpy.executors.SingleThreadedExecutor()
            executor.add_node(watch)
            executor.add_node(talker)
            for _ in range(200):
                if all(p.get_subscription_count() for p in pubs.values()):
                    break
                executor.spin_once(timeout_sec=0.01)
            for c in range(40):
                for name, pub in pubs.items():
                    msg = SignalChunk(signal_name=name, unit="rad" if name == "angle_difference" else "m/s^2",
                                      sample_period_s=2e-5, first_sample_index=1000 * c,
                                      samples=np.zeros(1000).tolist())
                    pub.publish(msg)
                executor.spin_once(timeout_sec=0.01)
            for _ in range(100):
                executor.spin_once(timeout_sec=0.01)
            missing = watch.missing_streams()
            joined = watch.counts["chunks"]
            watch.destroy_node()
            talker.destroy_node()
            if watch_omega1:
                assert joined == 0
                assert "/line1/drive7/plant/omega1" in missing and "set watch_omega1 false" in missing
            else:
                assert joined == 40 and missing == ""
    finally:
        rclpy.try_shutdown()


@pytest.mark.ros
@pytest.mark.process
@pytest.mark.parametrize("override, named", [("window_events:=2", "window_events"),
                                             ("reference:=/nonexistent.watch.npz", "does not exist"),
                                             ("view_p:=0.5", "view_p"),
                                             ("batch_s:=0.9", "batch_s"),
                                             ("stale_after_s:=0.1", "batch_s <= stale_after_s / 2"),
                                             ("width_m:=0.0123", "watch-reference --width-m 0.0123"),
                                             ("snapshot_signals:=[a1,a2,angle_difference]",
                                              "without omega1 while watch_omega1 is true")])
def test_bad_parameters_stop_the_node_with_a_clear_line(ros_env, override, named):
    proc = subprocess.run([EXECUTABLE, "--ros-args", "-p", override], env=ros_env, capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 2, proc.stderr
    assert named in proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.ros
@pytest.mark.process
@pytest.mark.parametrize("args, named", [
    (["--set-at", "abc", "effects.wheel_coulomb_friction=true"], "--set-at abc: the time"),
    (["--set-at", "30s"], "--set-at 30s: allowed"),
    (["--set-at", "30s", "torque"], "expected SECTION.KEY=VALUE"),
    (["--model", "m.yaml"], "add --watch"),
    (["--watch", "--library", "/nonexistent.npz"], "--library /nonexistent.npz: no such file"),
])
def test_the_pipelines_watch_options_are_checked_before_anything_runs(ros_env, args, named):
    import sys
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "pipeline", *args], env=ros_env,
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and named in proc.stderr, proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.process
@pytest.mark.parametrize("args,named", [
    (["--output", "ref.txt"], "--output ref.txt: a reference is an .npz file"),
    (["--ensemble", "3"], "--ensemble 3: the cache holds references of 6 seeds"),
    (["--seeds", "3"], "--ensemble 3: the cache holds references of 6 seeds"),    # the old spelling, one release
    (["--width-m", "-1"], "width"),
])
def test_watch_reference_refuses_bad_input_before_building(tmp_path, args, named):
    """`watch-reference` names the bad option and exits 2 before any simulation (no traceback)."""
    import subprocess
    import sys
    p = subprocess.run([sys.executable, "-m", "backlash_monitor", "watch-reference", *args], cwd=tmp_path,
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 2, (p.returncode, p.stdout, p.stderr)
    assert named in p.stderr + p.stdout
    assert "Traceback" not in p.stderr
    assert not any(tmp_path.iterdir())


@pytest.mark.ros
def test_an_a1_that_does_not_follow_the_motor_speed_is_a_warning_on_the_watchs_diagnostics(ros_env, ref_path):
    """a1 = r·dΩ₁/dt (SPEC 2): a drive whose a1 reads 1.3x the motor's motion (a wrong sensitivity) is WARN on the
    model watch's /diagnostics with the words to check a1's chain (windowing/a1_chain.py); the same stream with a1
    as the speed's derivative is not. The motion is a closed form (test/windowing/test_a1_chain.py), not simulated."""
    import sys
    from pathlib import Path

    import numpy as np
    from backlash_monitor_msgs.msg import SignalChunk
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "windowing"))
    from test_a1_chain import R, motion
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    w, dw = motion(duration_s=3.0)
    rclpy.init()
    try:
        for gain in (1.3, 1.0):
            watch = ModelWatchNode(namespace=NS, parameter_overrides=[
                Parameter("reference", value=ref_path), Parameter("qos", value="reliable"),
                Parameter("snapshot_dir", value=""), Parameter("stale_after_s", value=5.0),
                Parameter("batch_s", value=0.0)])
            talker = rclpy.create_node("talker", namespace=NS)
            qos = rclpy.qos.QoSProfile(depth=200, reliability=rclpy.qos.ReliabilityPolicy.RELIABLE)
            signals = {"a1": gain * R * dw, "a2": np.zeros_like(w), "angle_difference": np.zeros_like(w), "omega1": w}
            pubs = {n: talker.create_publisher(SignalChunk, f"plant/{n}", qos) for n in signals}
            executor = rclpy.executors.SingleThreadedExecutor()
            executor.add_node(watch)
            executor.add_node(talker)
            for _ in range(200):
                if all(p.get_subscription_count() for p in pubs.values()):
                    break
                executor.spin_once(timeout_sec=0.01)
            n = 5000
            for first in range(0, w.size, n):
                for name, pub in pubs.items():
                    unit = {"angle_difference": "rad", "omega1": "rad/s"}.get(name, "m/s^2")
                    pub.publish(SignalChunk(signal_name=name, unit=unit, sample_period_s=2e-5,
                                            first_sample_index=first, samples=signals[name][first:first + n].tolist()))
                for _ in range(4):
                    executor.spin_once(timeout_sec=0.01)
            for _ in range(200):
                if watch.counts["chunks"] >= w.size // n:
                    break
                executor.spin_once(timeout_sec=0.01)
            watch.update_diagnostics()
            level, message = watch.diagnostics.level, watch.diagnostics.message
            chunks = watch.counts["chunks"]
            watch.destroy_node()
            talker.destroy_node()
            assert chunks == w.size // n
            if gain != 1.0:
                assert level == "WARN" and "a1 does not follow r·dΩ₁/dt" in message, message
                assert "not to be trusted" in message
            else:
                assert "a1 does not follow" not in message, message
    finally:
        rclpy.try_shutdown()
