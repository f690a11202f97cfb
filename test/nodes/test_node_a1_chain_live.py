"""The live chain checks a1 against the motor speed as `analyze` does (windowing node ``check_a1_chain``, each window
carrying the check to the classifier; docs/classifier.md 5.4): on a recording of the independent simulator whose a1
has a quadratic characteristic (foreign_drives, spent set 12), replayed over DDS into the `chain` executable, every
a1+a2 estimate takes a2's fusion, as the offline analysis of the same bag does, and reads what it reads. Before, the
live width there was a1+a2's, 4.5 mm off, while `analyze` of the same bag was right."""
import json
import os
import subprocess
import sys
import textwrap

import pytest

pytest.importorskip("foreign_drives")

from ament_index_python.packages import get_package_prefix  # noqa: E402

from backlash_monitor.classifier.signal_check import BOTH_SIGNALS, LOAD_SIDE_SIGNAL  # noqa: E402

PREFIX = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor")

_MONITOR = textwrap.dedent("""
    import json, sys, time, rclpy
    from backlash_monitor.nodes.classifier import ESTIMATE_QOS
    from backlash_monitor_msgs.msg import BacklashEstimate
    rclpy.init()
    node = rclpy.create_node("monitor")
    got = []
    node.create_subscription(BacklashEstimate, sys.argv[1] + "/estimate", got.append, ESTIMATE_QOS)
    deadline, quiet = time.monotonic() + float(sys.argv[2]), None
    while time.monotonic() < deadline:
        n = len(got)
        rclpy.spin_once(node, timeout_sec=0.1)
        if got and len(got) == n:
            quiet = quiet or time.monotonic()
            if time.monotonic() - quiet > 8.0:
                break          # no estimate for 8 s after the last: the replay is over
        else:
            quiet = None
    print(json.dumps([{"entry": int(m.entry_sample_index), "signal": m.signal_name,
                       "fused": m.fused_continuous_width_m} for m in got]))
""")


@pytest.mark.process
@pytest.mark.ros
def test_a_live_chain_takes_a2s_width_where_a1_does_not_follow_the_motor_speed_as_analyze_does(ros_env, tmp_path):
    from foreign_drives.drive import make_recording
    from foreign_drives.files import topic_prefix, write_bag
    from foreign_drives.suites import suite
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions, analyze_bag
    spec = next(s for s in suite("outside_sealed12") if s.label == "os12_a1_quadratic_distortion")
    rec = make_recording(spec)
    bag = write_bag(spec, tmp_path / "drive.mcap", recording=rec)
    offline = json.loads(analyze_bag(bag, tmp_path / "out", AnalyzeOptions())["outputs"]["json"].read_text())
    offline_both = {e["entry_sample_index"]: e for e in offline["estimates"] if e["signal"] == BOTH_SIGNALS}
    assert offline["a1_chain"]["faulty"]

    ns = topic_prefix(spec.namespace)[: -len("/plant")]     # the drive's namespace ("" at the root)
    chain = subprocess.Popen([os.path.join(PREFIX, "chain"), "--ros-args", *(["-r", f"__ns:={ns}"] if ns else []),
                              "-p", "qos:=reliable", "-p", "check_a1_chain:=true", "-p", f"drive_name:={spec.drive_name}"],
                             env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    monitor = subprocess.Popen([sys.executable, "-c", _MONITOR, ns, "150"], env=ros_env,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    topics = ",".join(f"{ns}/plant/{s}" for s in ("a1", "a2", "angle_difference", "omega1"))
    try:
        play = subprocess.run([sys.executable, "-m", "backlash_monitor.nodes.replay", "--ros-args",
                               "-p", f"bag:={bag}", "-p", "rate:=0.0", "-p", "qos:=reliable",
                               "-p", f"topics:={topics}", "-p", "wait_for_subscribers:=1",
                               "-p", "wait_timeout_s:=60.0"],
                              env=ros_env, capture_output=True, text=True, timeout=180)
        assert play.returncode == 0, play.stdout + play.stderr
        out, err = monitor.communicate(timeout=200)
    finally:
        for proc in (monitor, chain):
            if proc.poll() is None:
                proc.terminate()
        chain_out, _ = chain.communicate(timeout=30)
    assert out.strip(), err + chain_out
    estimates = json.loads(out)
    live = [e for e in estimates if e["signal"] == BOTH_SIGNALS]
    live_a2 = {e["entry"]: e["fused"] for e in estimates if e["signal"] == LOAD_SIDE_SIGNAL}
    assert len(live) >= 8, out + err + chain_out
    # the live check takes a2's once it has compared enough of the stream (about 2 s here: live ranges are single
    # chunks; analyze's blocks are larger, so the offline check has seen more at the same window and switches a
    # window or two sooner); from then on every a1+a2 width is a2's fusion, and the offline analysis's
    switched = [i for i, e in enumerate(live) if e["fused"] == live_a2[e["entry"]]]
    assert switched and live[switched[0]]["entry"] <= live[len(live) // 2]["entry"], (live, live_a2)
    for e in live[switched[0]:]:
        assert e["fused"] == live_a2[e["entry"]], (e, chain_out)
        assert offline_both[e["entry"]]["fused_from_signal"] == LOAD_SIDE_SIGNAL
        assert e["fused"] == offline_both[e["entry"]]["fused_continuous_width_m"], e
    assert abs(live[-1]["fused"] - rec.truth.true_width_m) < 0.3e-3, (live[-1], rec.truth.true_width_m)
