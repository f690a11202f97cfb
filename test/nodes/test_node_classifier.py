"""The classifier node: estimates from denoised windows, diagnostics per drive under a namespace."""
import os
import subprocess

import numpy as np
import pytest
import rclpy
from ament_index_python.packages import get_package_prefix
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
from rclpy.parameter import Parameter

from backlash_monitor.denoise import denoise_pair, denoising_label
from backlash_monitor.classifier.fusion import median_standard_error
from backlash_monitor.nodes.classifier import ClassifierNode, ESTIMATE_QOS
from backlash_monitor.ros.conversions import to_float64_array
from backlash_monitor.nodes.windowing import WINDOW_QOS
from backlash_monitor.plant import PlantSimulator, Scenario
from backlash_monitor.windowing import extract_windows
from backlash_monitor_msgs.msg import BacklashEstimate, BacklashWindow, ModelFit

EXECUTABLE = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor",
                          "classifier")


def _onset_windows(width_m, seconds=2.5, seed=3):
    chunk = PlantSimulator([Scenario(width_m=width_m, seed=seed)]).run(int(seconds * 50000))
    signals = {name: getattr(chunk, name)[0] for name in ("a1", "a2", "angle_difference")}
    return [w for w in extract_windows(signals, trigger="contact_loss") if w.kind == "onset"]


def _message(window, true_width_m):
    a1, a2 = denoise_pair(window.signals["a1"], window.signals["a2"])
    msg = BacklashWindow(entry_sample_index=window.entry_sample_index, entry_kind=window.kind,
                         trigger=window.trigger, sample_period_s=window.sample_period_s,
                         denoising=denoising_label(6, (1, 2, 3, 4, 5, 6), "symmetric"),
                         true_width_m=true_width_m,
                         a1_offset_m_s2=window.sensor_offsets["a1"],
                         a2_offset_m_s2=window.sensor_offsets["a2"],
                         offset_periods=window.offset_periods)
    msg.header.frame_id = "drive7"
    msg.a1, msg.a2 = to_float64_array(a1), to_float64_array(a2)
    return msg


def _probe_graph(node, namespace=None):
    """A probe node beside ``node`` on one executor: (executor, window publisher, estimates list),
    returned once the classifier has matched the publisher."""
    probe = rclpy.create_node("probe", **({"namespace": namespace} if namespace else {}))
    estimates = []
    probe.create_subscription(BacklashEstimate, "estimate", estimates.append, ESTIMATE_QOS)
    pub = probe.create_publisher(BacklashWindow, "windows/denoised", WINDOW_QOS)
    executor = rclpy.executors.SingleThreadedExecutor()
    executor.add_node(node)
    executor.add_node(probe)
    for _ in range(100):
        executor.spin_once(timeout_sec=0.05)
        if pub.get_subscription_count():
            break
    return executor, pub, estimates, probe


@pytest.mark.process
@pytest.mark.ros
def test_estimates_and_namespaced_diagnostics(ros_env):
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    windows = _onset_windows(0.009)
    assert len(windows) >= 9
    # the stream's first onset window has no whole load period behind it: no sensor offset yet
    assert [w.offset_periods for w in windows][:2] == [0, 1]
    rclpy.init()
    try:
        node = ClassifierNode(namespace="/line1/drive7", parameter_overrides=[
            Parameter("drive_name", value="drive7")])
        executor, pub, estimates, probe = _probe_graph(node, namespace="/line1/drive7")
        diagnostics = []
        probe.create_subscription(DiagnosticArray, "/diagnostics", diagnostics.append, 10)
        for window in windows:
            pub.publish(_message(window, 0.009))
        for _ in range(200):
            executor.spin_once(timeout_sec=0.05)
            if len(estimates) >= (len(windows) - 1) * len(node.estimator.signals) and \
                    any(d.status[0].level != DiagnosticStatus.STALE for d in diagnostics):
                break
        # the model watch of the same namespace says the model does not explain the drive: the width's
        # status says so in the same line
        fit_pub = probe.create_publisher(ModelFit, "model_fit", 10)
        fit = ModelFit(level=ModelFit.WARN, model="drive7 v1", residual_over_noise_overall=2.5)
        for _ in range(100):
            executor.spin_once(timeout_sec=0.05)
            if fit_pub.get_subscription_count():
                break
        before = len(diagnostics)
        fit_pub.publish(fit)
        for _ in range(100):
            executor.spin_once(timeout_sec=0.05)
            if len(diagnostics) > before and "does not explain" in diagnostics[-1].status[0].message:
                break
    finally:
        rclpy.try_shutdown()
    # every onset window but the first (not classified, counted, no fault)
    assert len(estimates) == (len(windows) - 1) * len(node.estimator.signals)
    assert windows[0].entry_sample_index not in {e.entry_sample_index for e in estimates}
    assert node.estimator.waiting_for_offset == 1 and node.estimator.faults.total == 0
    est = estimates[-1]
    assert list(est.candidate_widths_m) == [0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01]
    assert len(est.b_vector) == 6 and est.width_m == est.candidate_widths_m[est.width_index]
    assert est.width_index == int(np.argmin(est.b_vector))
    smallest, second = np.sort(np.asarray(est.b_vector))[:2]     # the margin of this B vector
    assert est.b_margin == pytest.approx(second / smallest, rel=1e-12)
    assert est.fused_events == min(8, len(windows) - 1)
    # the fused continuous width: the median of the same events' continuous widths: this signal's, or a1's where
    # a1+a2's departed from a1's (classifier/signal_check.py; the node's /diagnostics value says which)
    source = {kv.key: kv.value for kv in diagnostics[-1].status[0].values}["fused_from_signal"]
    assert source in (est.signal_name, "a1")
    if source != est.signal_name:
        a1 = [e for e in estimates if e.signal_name == "a1"][-1]
        assert "a1's: a1+a2 departed by" in diagnostics[-1].status[0].message or \
            "a1's: a1+a2 scattered" in diagnostics[-1].status[0].message
        assert (est.fused_continuous_width_m, est.fused_width_uncertainty_m) == (
            a1.fused_continuous_width_m, a1.fused_width_uncertainty_m)
        both = [e.continuous_width_m for e in estimates if e.signal_name == est.signal_name][-est.fused_events:]
        # taken because both together departed beyond 2 combined errors, or scattered more than twice a1
        se = median_standard_error(both)
        assert (abs(float(np.median(both)) - a1.fused_continuous_width_m)
                > 2 * np.hypot(a1.fused_width_uncertainty_m, se)) or se > 2 * a1.fused_width_uncertainty_m
    mine = [e.continuous_width_m for e in estimates if e.signal_name == source][-est.fused_events:]
    assert est.fused_continuous_width_m == pytest.approx(float(np.median(mine)), rel=1e-12)
    # and its uncertainty: the robust standard error of that median over the same events
    assert est.fused_width_uncertainty_m == pytest.approx(median_standard_error(mine), rel=1e-12)
    assert 0 < est.fused_width_uncertainty_m < 5e-4
    assert est.true_width_m == 0.009
    last = diagnostics[-1].status[0]
    assert last.message.endswith("— model drive7 v1 does not explain this drive (residual 2.5× its floor): "
                                 "run diagnose before acting"), last.message
    assert {kv.key: kv.value for kv in last.values}["model_fit"] == "does not explain"
    assert not any("does not explain" in d.status[0].message for d in diagnostics[:before])
    status = [d.status[0] for d in diagnostics[:before] if d.status[0].level != DiagnosticStatus.STALE][-1]
    assert status.name == "line1/drive7/classifier: backlash width"
    assert status.hardware_id == "drive7"
    assert {kv.key: kv.value for kv in status.values}["windows_waiting_for_offset"] == "1"
    # 9 mm is at the ERROR threshold of config/diagnostics.yaml: the level follows the fused continuous width (the
    # class width, the nearest pattern width, only where the mode gives no continuous width), and the message shows it
    # with its uncertainty and the class beside it
    fused = est.fused_continuous_width_m
    expected = (DiagnosticStatus.ERROR if fused >= 0.009 else
                DiagnosticStatus.WARN if fused >= 0.0075 else DiagnosticStatus.OK)
    assert status.level == expected
    assert status.message.startswith(f"backlash {fused * 1e3:.2f} ± ") and \
        f"nearest pattern width {est.fused_width_m * 1e3:.2f} mm" in status.message, status.message


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("override, named", [("mode:=magic", "mode"),
                                             ("library:=/nonexistent.npz", "library"),
                                             ("error_width_m:=0.001", "error_width_m")])
def test_bad_parameters_stop_the_node_with_a_clear_line(ros_env, override, named):
    proc = subprocess.run([EXECUTABLE, "--ros-args", "-p", override], env=ros_env,
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert named in proc.stderr or "pattern library" in proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.process
@pytest.mark.ros
def test_windows_sent_again_are_not_fused_twice(ros_env):
    """A restarted upstream node re-sends the transient-local history: the classifier skips the
    windows it has already classified, so the fused estimate counts each event once."""
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    windows = [w for w in _onset_windows(0.005, seconds=1.5) if w.offset_periods > 0]
    assert len(windows) >= 4
    rclpy.init()
    try:
        node = ClassifierNode()
        executor, pub, estimates, _ = _probe_graph(node)
        messages = [_message(window, 0.005) for window in windows]
        for msg in messages + messages:          # the history arrives a second time
            pub.publish(msg)
        expected = len(windows) * len(node.estimator.signals)
        for _ in range(100):
            executor.spin_once(timeout_sec=0.05)
            if node.repeated.repeats == len(windows) and len(estimates) >= expected:
                break
        for _ in range(10):                      # anything more would arrive now
            executor.spin_once(timeout_sec=0.05)
    finally:
        rclpy.try_shutdown()
    assert len(estimates) == expected
    assert node.repeated.repeats == len(windows)
    assert estimates[-1].fused_events == len(windows)


@pytest.mark.ros
def test_a_late_classifier_gets_the_history_and_says_when_it_was_passed_over(ros_env):
    """A classifier started after its windows were published (a restart) gets the writer's history from its
    first window (chain/late_join.py: not passed over). A history the middleware passed over (under load,
    docs/graph.md "Not always 0") is an input fault on /diagnostics: WARN, named, and not a rejected window."""
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    windows = [w for w in _onset_windows(0.005, seconds=1.5) if w.offset_periods > 0]
    rclpy.init()
    try:
        probe = rclpy.create_node("probe")
        pub = probe.create_publisher(BacklashWindow, "windows/denoised", WINDOW_QOS)
        diagnostics = []
        probe.create_subscription(DiagnosticArray, "/diagnostics", diagnostics.append, 10)
        for window in windows:
            pub.publish(_message(window, 0.005))
        node = ClassifierNode()
        executor = rclpy.executors.SingleThreadedExecutor()
        executor.add_node(node)
        executor.add_node(probe)
        for _ in range(200):
            executor.spin_once(timeout_sec=0.05)
            if node.classified == len(windows):
                break
        whole = (node.classified, node.windows_in.check.passed_over, node.windows_in.check.judging)
        node.windows_in.check.missed_before = 330          # what the under-load bench's restarted classifier saw
        node.windows_in.check.passed_over += 1
        node.windows_in.report_passed_over()
        for _ in range(40):
            executor.spin_once(timeout_sec=0.05)
            if diagnostics and "history_passed_over" in diagnostics[-1].status[0].message:
                break
    finally:
        rclpy.try_shutdown()
    assert whole == (len(windows), 0, False)
    status = diagnostics[-1].status[0]
    values = {kv.key: kv.value for kv in status.values}
    assert status.level == DiagnosticStatus.WARN
    assert "history_passed_over (windows/denoised before sequence number 330)" in status.message
    assert values["history_passed_over"] == "1" and values["windows_rejected"] == "0"
    assert "history_passed_over 1" in values["input_faults"]
