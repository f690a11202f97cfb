"""The live width trend: the offline trend's rule over a running drive's fused widths (core), and
the width_trend node's status on /diagnostics (node)."""
import math
import os
import time

import numpy as np
import pytest

from backlash_monitor.fleet.trend import LiveTrend, TrendRule, drive_trend, load_rule

DAY = 86400.0
RULE = TrendRule(warn_growth_m_per_day=5e-5, warn_width_m=0.0075, error_width_m=0.009,
                 live_point_period_s=60.0, live_history_s=7 * DAY, live_min_span_s=DAY)


def _ramp(trend, rate_m_per_day, days, start_m=0.004, every_s=30.0, noise_m=1e-4, t0=1.76e9,
          seed=0):
    """Fused widths of a drive wearing at ``rate_m_per_day`` (+ scatter), one every ``every_s``."""
    rng = np.random.default_rng(seed)
    times = t0 + np.arange(0.0, days * DAY, every_s)
    widths = start_m + rate_m_per_day * (times - t0) / DAY + rng.normal(0, noise_m, times.size)
    for t, w in zip(times, widths):
        trend.add(float(t), float(w))
    return times, widths


def test_a_drive_wearing_faster_than_the_rule_warns_with_the_days_left():
    live = LiveTrend(RULE)
    rate = 2e-4                               # 0.2 mm/day: 4x the allowed 0.05 mm/day
    times, _ = _ramp(live, rate, days=0.5)
    half_day = live.trend()
    assert half_day.level == "OK" and math.isnan(half_day.rate_m_per_day)   # < live_min_span_s
    assert "no trend yet" in half_day.reason
    _ramp(live, rate, days=2.0, t0=times[0], seed=1)[0]
    t = live.trend()
    assert t.level == "WARN" and "grows" in t.reason
    assert t.rate_m_per_day == pytest.approx(rate, rel=0.05)
    # days left from the last width at that rate: (9 mm - (4 mm + 2 days x 0.2 mm)) / 0.2 mm/day
    assert t.days_to_limit == pytest.approx((0.009 - 0.0044) / rate, rel=0.05)
    assert t.last_width_m < RULE.warn_width_m          # warned while still narrow
    assert t.points == pytest.approx(2 * DAY / 60, abs=2)   # one point a minute


def test_a_drive_wearing_slowly_stays_ok_and_its_rate_is_measured():
    live = LiveTrend(RULE)
    _ramp(live, 1e-5, days=3.0)               # 0.01 mm/day: a normal coupling's wear
    t = live.trend()
    assert t.level == "OK"
    assert t.rate_m_per_day == pytest.approx(1e-5, abs=3e-6)


def test_live_points_are_the_offline_trend_of_per_minute_medians():
    live = LiveTrend(RULE)
    times, widths = _ramp(live, 1e-4, days=1.5, every_s=20.0)
    minute = np.floor(times / 60.0)
    points = [(float(np.median(times[minute == m])), float(np.median(widths[minute == m])))
              for m in np.unique(minute)[:-1]]          # the last minute is still open
    offline = drive_trend(points, RULE, RULE.live_min_span_s)
    t = live.trend()
    assert (t.level, t.points) == (offline.level, offline.points)
    assert t.rate_m_per_day == pytest.approx(offline.rate_m_per_day, rel=1e-12)


def test_history_limits_the_rate_to_the_last_days_and_bad_input_is_not_used():
    rule = TrendRule(5e-5, 0.0075, 0.009, live_point_period_s=60.0, live_history_s=2 * DAY,
                     live_min_span_s=DAY)
    live = LiveTrend(rule)
    times, _ = _ramp(live, 0.0, days=5.0, start_m=0.003)     # flat for 5 days ...
    _ramp(live, 3e-4, days=3.0, start_m=0.003, t0=times[-1] + 30.0, seed=2)   # ... then wears
    t = live.trend()
    assert t.rate_m_per_day == pytest.approx(3e-4, rel=0.05)   # not diluted by the flat days
    assert t.level == "WARN"
    span = live.points[-1][0] - live.points[0][0]
    assert span <= 2 * DAY
    live.add(live.points[0][0] - 3600.0, 0.004)     # out of order (older than the open minute)
    live.add(times[-1] + 9 * DAY, float("nan"))
    assert live.ignored == 2


def test_packaged_rule_has_the_live_settings():
    rule = load_rule()
    assert rule.live_min_span_s >= rule.live_point_period_s > 0
    assert rule.live_history_s > rule.live_min_span_s


@pytest.mark.process
@pytest.mark.ros
def test_node_publishes_the_trend_warn_per_drive_on_diagnostics(ros_env, tmp_path):
    """Two drives' width_trend nodes; estimates with stamps a minute apart (a day's wear in 30
    messages, rule scaled to match): the wearing drive is WARN on /diagnostics with its
    hardware_id, the steady one OK; the other signal's estimates do not count."""
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    import rclpy
    from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
    from rclpy.parameter import Parameter

    from backlash_monitor.ros.qos import ESTIMATE_QOS
    from backlash_monitor.nodes.width_trend import WidthTrendNode
    from backlash_monitor_msgs.msg import BacklashEstimate
    config = tmp_path / "trend.yaml"
    config.write_text("warn_growth_m_per_day: 5.0e-5\nwarn_width_m: 0.0075\nerror_width_m: 0.009\n"
                      "live_point_period_s: 1.0\nlive_history_s: 86400.0\nlive_min_span_s: 600.0\n")
    rclpy.init()
    try:
        nodes = {d: WidthTrendNode(namespace=f"/line1/{d}", parameter_overrides=[
            Parameter("drive_name", value=f"line1/{d}"),
            Parameter("trend_config", value=str(config))]) for d in ("drive01", "drive02")}
        probe = rclpy.create_node("probe")
        statuses = {}
        probe.create_subscription(DiagnosticArray, "/diagnostics", lambda m: statuses.update(
            {s.hardware_id: s for s in m.status if s.name.endswith("width trend")}), 10)
        pubs = {d: probe.create_publisher(BacklashEstimate, f"/line1/{d}/estimate", ESTIMATE_QOS)
                for d in nodes}
        executor = rclpy.executors.SingleThreadedExecutor()
        for node in (*nodes.values(), probe):
            executor.add_node(node)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and not all(p.get_subscription_count() for p in pubs.values()):
            executor.spin_once(timeout_sec=0.05)
        t0 = 1_760_000_000
        for k in range(31):                      # 30 minutes of stamps
            for d, rate in (("drive01", 0.5e-3), ("drive02", 0.0)):   # m/day
                for signal, offset in (("a1+a2", 0.0), ("a1", 0.002)):
                    # drive01 publishes its fused continuous width (the grid width stays at 5 mm: the
                    # trend follows the continuous one); drive02 leaves it unset (0): its fused width
                    width = 0.004 + offset + rate * k * 60 / 86400
                    msg = (BacklashEstimate(signal_name=signal, mode="shape", fused_width_m=0.005,
                                            fused_continuous_width_m=width) if d == "drive01" else
                           BacklashEstimate(signal_name=signal, mode="shape", fused_width_m=width))
                    msg.header.stamp.sec = t0 + 60 * k
                    msg.header.frame_id = f"line1/{d}"
                    pubs[d].publish(msg)
            executor.spin_once(timeout_sec=0.01)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.1)
            wear = statuses.get("line1/drive01")
            if wear is not None and wear.level == DiagnosticStatus.WARN and "line1/drive02" in statuses \
                    and dict((kv.key, kv.value) for kv in statuses["line1/drive02"].values)["points"] == "30":
                break
        wear, steady = statuses["line1/drive01"], statuses["line1/drive02"]
        # 31 minutes of estimates: 30 closed minutes (the 31st is still being collected)
        assert {kv.key: kv.value for kv in wear.values}["points"] == "30"
        assert wear.level == DiagnosticStatus.WARN, wear.message
        assert "grows 0.500 mm/day" in wear.message
        assert wear.name == "line1/drive01/width_trend: width trend"
        values = {kv.key: kv.value for kv in wear.values}
        assert float(values["rate_m_per_day"]) == pytest.approx(0.5e-3, rel=1e-6)
        assert values["signal"] == "a1+a2"
        assert steady.level == DiagnosticStatus.OK, steady.message
        assert float({kv.key: kv.value for kv in steady.values}["last_fused_width_m"]) == \
            pytest.approx(0.004)                  # a1's estimates (6 mm) were not used
    finally:
        rclpy.shutdown()


def test_saved_points_give_the_same_trend_after_a_restart(tmp_path):
    from backlash_monitor.fleet.trend import load_live_points, save_live_points
    live = LiveTrend(RULE)
    _ramp(live, 2e-4, days=2.0)                       # 2 days of wear at 0.2 mm/day: WARN
    before = live.trend()
    path = str(tmp_path / "line1_drive07.json")
    save_live_points(path, "line1/drive07", live)
    restarted = LiveTrend(RULE)
    assert load_live_points(path, "line1/drive07", restarted) == ""
    after = restarted.trend()
    assert (after.level, after.points) == (before.level, before.points) and after.level == "WARN"
    assert after.rate_m_per_day == pytest.approx(before.rate_m_per_day, rel=1e-12)
    assert restarted.open_samples == live.open_samples      # the minute being collected too
    # what is not this drive's trend state is not taken, and says why; no file yet is no problem
    assert "holds drive 'line1/drive07'" in load_live_points(path, "line1/drive08", LiveTrend(RULE))
    (tmp_path / "bad.json").write_text('{"version": 1, "drive": "line1/drive07", "points": [[1')
    fresh = LiveTrend(RULE)
    assert "not read" in load_live_points(str(tmp_path / "bad.json"), "line1/drive07", fresh)
    assert fresh.points == [] and fresh.open_samples == []
    assert load_live_points(str(tmp_path / "none.json"), "line1/drive07", LiveTrend(RULE)) == ""


@pytest.mark.process
@pytest.mark.ros
def test_node_goes_on_with_its_saved_history_and_keeps_it(ros_env, tmp_path):
    """A width_trend node started with a state file holding two days of fast wear is WARN from
    its first status (no day without a rate after a restart), adds the new estimates and writes
    them back; a state file it cannot write is a WARN, not a silent loss of history."""
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    import rclpy
    from rclpy.parameter import Parameter

    from backlash_monitor.fleet.trend import load_live_points, save_live_points
    from backlash_monitor.nodes.width_trend import WidthTrendNode
    from backlash_monitor_msgs.msg import BacklashEstimate
    saved = LiveTrend(load_rule())
    times, _ = _ramp(saved, 2e-4, days=2.0, every_s=120.0)
    state = tmp_path / "line1_drive07.json"
    save_live_points(str(state), "line1/drive07", saved)
    rclpy.init()
    try:
        node = WidthTrendNode(namespace="/line1/drive07", parameter_overrides=[
            Parameter("drive_name", value="line1/drive07"), Parameter("state_file", value=str(state))])
        t = node.trend.trend()
        assert t.level == "WARN" and t.points == len(saved.points) and not node.state_problem
        assert node.diagnostics.level == "WARN" and "grows 0.2" in node.diagnostics.message
        # an hour of new estimates (a point a minute): points close and the file follows them
        for k in range(1, 61):
            msg = BacklashEstimate(signal_name="a1+a2", mode="shape", fused_width_m=0.005,
                                   fused_continuous_width_m=0.0044 + 2e-4 * k * 60 / DAY)
            msg.header.stamp.sec = int(times[-1]) + 60 * k
            node.on_estimate(msg)
        kept = LiveTrend(load_rule())
        assert load_live_points(str(state), "line1/drive07", kept) == ""
        assert len(kept.points) == len(node.trend.points) > len(saved.points)
        node.destroy_node()
        bad = WidthTrendNode(namespace="/line1/drive08", parameter_overrides=[
            Parameter("drive_name", value="line1/drive08"),
            Parameter("state_file", value=str(tmp_path / "no_such_dir" / "x.json"))])
        for k in range(3):
            msg = BacklashEstimate(signal_name="a1+a2", mode="shape", fused_width_m=0.005,
                                   fused_continuous_width_m=0.005)
            msg.header.stamp.sec = 1_760_000_000 + 3600 * k
            bad.on_estimate(msg)
        assert "not written" in bad.state_problem
        bad.update_diagnostics()
        assert bad.diagnostics.level == "WARN" and "not written" in bad.diagnostics.message
        bad.destroy_node()
    finally:
        rclpy.try_shutdown()


@pytest.mark.ros
def test_the_trend_does_not_follow_a_width_fused_over_fewer_than_three_events(ros_env, tmp_path):
    """A stream's first two estimates fuse 1 and 2 onset events (no uncertainty, not signal-checked: the classifier
    raises no level from them, estimation.level_events): read past the error threshold there, then 4 mm from 3
    events on, the trend follows the 4 mm only and stays OK; with the classifier's fusion_events at 1 every estimate
    is a whole fusion and is followed (a publisher that leaves fused_events unset, 0, is followed as before: the
    test above)."""
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    import rclpy
    from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus
    from rclpy.parameter import Parameter

    from backlash_monitor.estimation import level_events
    from backlash_monitor.nodes.width_trend import WidthTrendNode
    from backlash_monitor.ros.qos import ESTIMATE_QOS
    from backlash_monitor_msgs.msg import BacklashEstimate
    assert level_events() == 3 and level_events(1) == 1 and level_events(2) == 2
    rclpy.init()
    try:
        drives = {"drive01": 8, "drive02": 1}           # the classifier's fusion_events
        nodes = {d: WidthTrendNode(namespace=f"/line1/{d}", parameter_overrides=[
            Parameter("drive_name", value=f"line1/{d}"), Parameter("fusion_events", value=n)])
            for d, n in drives.items()}
        probe = rclpy.create_node("probe")
        statuses = {}
        probe.create_subscription(DiagnosticArray, "/diagnostics", lambda m: statuses.update(
            {s.hardware_id: s for s in m.status if s.name.endswith("width trend")}), 10)
        pubs = {d: probe.create_publisher(BacklashEstimate, f"/line1/{d}/estimate", ESTIMATE_QOS) for d in nodes}
        executor = rclpy.executors.SingleThreadedExecutor()
        for node in (*nodes.values(), probe):
            executor.add_node(node)
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline and not all(p.get_subscription_count() for p in pubs.values()):
            executor.spin_once(timeout_sec=0.05)
        t0 = 1_760_000_000
        for k, (events, width) in enumerate([(1, 0.016), (2, 0.018), (3, 0.004)]):
            for d in nodes:
                msg = BacklashEstimate(signal_name="a1+a2", mode="shape", fused_width_m=0.005,
                                       fused_continuous_width_m=width, fused_events=events)
                msg.header.stamp.sec = t0 + k
                pubs[d].publish(msg)
            executor.spin_once(timeout_sec=0.01)
        deadline = time.monotonic() + 10
        values = {}
        while time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.1)
            values = {d: {kv.key: kv.value for kv in statuses[f"line1/{d}"].values}
                      for d in nodes if f"line1/{d}" in statuses}
            if len(values) == 2 and values["drive01"].get("estimates_too_few_events") == "2" and \
                    values["drive02"].get("last_fused_width_m"):
                break
        ruled, every = statuses["line1/drive01"], statuses["line1/drive02"]
        assert values["drive01"]["estimates_too_few_events"] == "2"
        assert ruled.level == DiagnosticStatus.OK, ruled.message
        assert float(values["drive01"]["last_fused_width_m"]) == pytest.approx(0.004)
        # fusion_events 1: each estimate is a whole fusion, every one followed: the open minute's median is 16 mm
        assert values["drive02"]["estimates_too_few_events"] == "0"
        assert float(values["drive02"]["last_fused_width_m"]) == pytest.approx(0.016)
        assert every.level == DiagnosticStatus.ERROR, every.message
    finally:
        rclpy.shutdown()


def test_a_fleet_drive_gives_its_trend_the_classifiers_fusion_events():
    """The fleet starts each drive's width_trend with the classifier's fusion_events where the drive sets one, so
    that the trend follows the same estimates the classifier raises a level from."""
    from backlash_monitor.fleet.drives import Drive
    short = Drive("line1", "drive01", {"fusion_events": 2}).node_parameters()
    assert short["classifier"]["fusion_events"] == 2 and short["width_trend"]["fusion_events"] == 2
    assert "fusion_events" not in Drive("line1", "drive02", {}).node_parameters()["width_trend"]
