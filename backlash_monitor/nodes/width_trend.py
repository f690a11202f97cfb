"""width_trend: the drive's width trend live, as a status on /diagnostics.

    ros2 run backlash_monitor width_trend --ros-args -r __ns:=/line1/drive07 -p drive_name:=line1/drive07

Subscribes to the classifier's ``estimate``; feeds each fused continuous width of the drive's primary
signal (the median of the fused events' continuous widths; the fused candidate width where the mode
gives none; a1+a2 where the classifier publishes it, else the first signal it publishes) with its window's
stamp to the offline trend's core (backlash_monitor/fleet/trend.py: LiveTrend, drive_trend, the
rule of config/trend.yaml) and publishes, once a second, the status ``<node>: width trend`` with
hardware_id = the drive's name: WARN when the drive grows faster than ``warn_growth_m_per_day``
(with the days left to ``error_width_m``) or is past ``warn_width_m``, ERROR past
``error_width_m``, OK otherwise (also before the first estimate and while the points span less
than ``live_min_span_s``: no rate yet). A width fused over fewer than 3 onset events (a stream's first
windows; ``fusion_events``: the classifier's, where it fuses fewer) is not followed, as the classifier
raises no level from it (estimation.level_events). With ``state_file`` the trend's points are kept in that
file (written when a point closes, once per ``live_point_period_s``, and at shutdown) and read at
start: a restarted monitor goes on with the drive's history; without it the trend starts anew
when the node starts. The offline trend (`analyze FOLDER`) covers the recordings of any length
of time. When the model watch of the same namespace says the drive's model does not explain it
(``model_fit`` level WARN), the status says so in the same line (backlash_monitor/fleet/caveat.py):
a WARN or ERROR on the width never stands alone when the model fit fails.
"""
from __future__ import annotations

import math
import sys

from rclpy.node import Node

from backlash_monitor.estimation import DEFAULT_FUSION_EVENTS, level_events, level_width
from backlash_monitor.fleet.caveat import with_caveat
from backlash_monitor.fleet.trend import (PRIMARY_SIGNAL, LiveTrend, load_live_points, load_rule,
                                          save_live_points)
from backlash_monitor.ros.drive_diagnostics import DriveDiagnostics
from backlash_monitor.ros.model_fit_caveat import follow_model_fit
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.ros.qos import ESTIMATE_QOS
from backlash_monitor.ros.runtime import run_node
from backlash_monitor_msgs.msg import BacklashEstimate
from backlash_monitor.stream_time import stamp_seconds


PARAMETERS = (
    ParameterSpec("drive_name", "drive", "the drive's name: diagnostics hardware_id"),
    ParameterSpec("trend_config", "", "trend rule file (empty: the packaged config/trend.yaml)"),
    ParameterSpec("signal", "", "signal whose fused width is followed (empty: a1+a2 where the "
                  "classifier publishes it, else the first signal it publishes)"),
    ParameterSpec("state_file", "", "file that keeps the trend's points over restarts (JSON, "
                  "written once per point period and at shutdown; empty: the trend starts anew)"),
    ParameterSpec("fusion_events", DEFAULT_FUSION_EVENTS, "the classifier's fusion_events: a width fused over "
                  "fewer than min(3, this) onset events is not followed (no uncertainty, not signal-checked; "
                  "estimation.level_events), as the classifier raises no level from it", 1, 1000),
)


class WidthTrendNode(Node):
    def __init__(self, **overrides):
        super().__init__("width_trend", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        try:
            self.rule = load_rule(p["trend_config"] or None)
        except (OSError, KeyError, TypeError, ValueError) as error:
            raise ParameterValueError(
                f"parameter 'trend_config' = {p['trend_config']!r}: {error}; it needs "
                "warn_growth_m_per_day, warn_width_m, error_width_m (config/trend.yaml)") from None
        self.trend = LiveTrend(self.rule)
        self.drive_name = p["drive_name"]
        self.state_file = p["state_file"]
        self.state_problem = (load_live_points(self.state_file, self.drive_name, self.trend)
                              if self.state_file else "")
        self.saved_points = len(self.trend.points)
        self.signal = p["signal"]
        self.min_events = level_events(p["fusion_events"])
        self.too_few_events = 0     # estimates not followed: fused over fewer than min_events (a stream's first)
        self.first_signal = ""
        self.create_subscription(BacklashEstimate, "estimate", self.on_estimate, ESTIMATE_QOS)
        self.model_fit = None       # the model watch's last FitVerdict (None: none heard)
        follow_model_fit(self, self.on_model_fit)
        self.diagnostics = DriveDiagnostics(self, "width trend", p["drive_name"],
                                            refresh=self.update_diagnostics)
        self.update_diagnostics()

    def on_model_fit(self, verdict) -> None:
        changed = self.model_fit is None or verdict.explains != self.model_fit.explains
        self.model_fit = verdict
        if changed:
            self.update_diagnostics(publish_now=True)

    def on_estimate(self, msg: BacklashEstimate):
        if not self.signal:
            if msg.signal_name == PRIMARY_SIGNAL:
                self.signal = PRIMARY_SIGNAL
            elif not self.first_signal:
                self.first_signal = msg.signal_name
        if msg.signal_name != (self.signal or self.first_signal):
            return
        if 0 < msg.fused_events < self.min_events:      # 0: a publisher that does not set the field
            self.too_few_events += 1
            return
        # the continuous width: wear shows as it grows, not as a jump from one candidate width to the next
        # (NaN: the mode gives none; 0: the message default of a publisher that does not set it)
        width = level_width(msg.fused_continuous_width_m, msg.fused_width_m)
        self.trend.add(stamp_seconds(msg.header.stamp), width)
        if self.state_file and len(self.trend.points) != self.saved_points:
            self.save_state()        # a point closed: once per live_point_period_s

    def save_state(self) -> None:
        self.saved_points = len(self.trend.points)     # tried for these points, written or not
        try:
            save_live_points(self.state_file, self.drive_name, self.trend)
            self.state_problem = ""
        except OSError as error:    # the monitor goes on; the status says the history is not kept
            self.state_problem = f"state file {self.state_file} not written ({error.strerror})"

    def destroy_node(self):
        if getattr(self, "state_file", "") and (self.trend.points or self.trend.open_samples):
            self.save_state()
        return super().destroy_node()

    def update_diagnostics(self, publish_now: bool = False):
        t = self.trend.trend()
        rule = self.rule
        if t.points == 0:
            level, message = "OK", "no estimate yet"
        else:
            level = "OK" if t.level == "STALE" else t.level
            rate = ("no rate" if math.isnan(t.rate_m_per_day)
                    else f"{t.rate_m_per_day * 1e3:+.3f} mm/day")
            message = with_caveat(f"{rate}; {t.reason}" if t.reason else rate, self.model_fit)
        if self.state_problem:      # the history is not kept (or was not read): never silently
            level = "WARN" if level == "OK" else level
            message = f"{message}; {self.state_problem}"
        self.diagnostics.set(
            level, message, publish_now=publish_now,
            rate_m_per_day="" if math.isnan(t.rate_m_per_day) else f"{t.rate_m_per_day:.3e}",
            days_to_limit="" if not math.isfinite(t.days_to_limit) else f"{t.days_to_limit:.1f}",
            last_fused_width_m="" if math.isnan(t.last_width_m) else f"{t.last_width_m:.5f}",
            points=t.points, estimates_not_used=self.trend.ignored,
            estimates_too_few_events=self.too_few_events,
            signal=self.signal or self.first_signal, state_file=self.state_file,
            warn_growth_m_per_day=rule.warn_growth_m_per_day,
            min_span_s=rule.live_min_span_s, point_period_s=rule.live_point_period_s)


def main(args=None):
    return run_node(WidthTrendNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
