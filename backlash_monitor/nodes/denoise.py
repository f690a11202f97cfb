"""denoise: removes the sym5 wavelet details 1..6 from every window (SPEC section 2, paper section 3).

    ros2 run backlash_monitor denoise

Subscribes to ``windows/raw`` and publishes ``windows/denoised``: the same windows with a1 and a2
decomposed to level 6 with sym5, details d1..d6 zeroed and reconstructed (backlash_monitor.denoise).
A window that cannot be denoised (a1 and a2 of unequal lengths, non-finite samples, too short for
the level; backlash_monitor.denoise.denoise_checked) is dropped and counted with its reason;
``/diagnostics`` says WARN with it while such windows come, STALE when none came for
``stale_after_s``.
"""
from __future__ import annotations

import sys
import time

from rclpy.node import Node

from backlash_monitor.denoise import denoise_checked, denoising_label
from backlash_monitor.windowing.faults import FaultLog, InputHealth
from backlash_monitor.ros.drive_diagnostics import DriveDiagnostics
from backlash_monitor.ros.history_subscription import HistorySubscription
from backlash_monitor.denoise import DEFAULT_MODE
from backlash_monitor.ros.conversions import from_float64_field, to_float64_array
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.ros.qos import WINDOW_QOS
from backlash_monitor.ros.runtime import run_node
from backlash_monitor_msgs.msg import BacklashWindow

PARAMETERS = (
    ParameterSpec("level", 6, "wavelet decomposition level", 1, 10),
    ParameterSpec("details_removed", [1, 2, 3, 4, 5, 6], "detail levels zeroed (1 = finest)"),
    ParameterSpec("mode", DEFAULT_MODE, "signal extension mode at the window's edges (PyWavelets)",
                  choices=("symmetric", "smooth", "periodization", "reflect", "zero", "constant",
                           "periodic", "antisymmetric", "antireflect")),
    ParameterSpec("drive_name", "drive", "the drive's name: diagnostics hardware_id"),
    ParameterSpec("stale_after_s", 60.0, "seconds without a window after which /diagnostics "
                  "says STALE (windows come only with load pulses)", 0.01, 86400.0),
    ParameterSpec("fault_hold_s", 10.0, "seconds /diagnostics stays WARN after the last "
                  "window dropped as bad", 0.01, 3600.0),
)


class DenoiseNode(Node):
    def __init__(self, **overrides):
        super().__init__("denoise", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        details = tuple(int(d) for d in p["details_removed"])
        if any(d < 1 or d > p["level"] for d in details):
            raise ParameterValueError(f"parameter 'details_removed' = {list(details)}: allowed: "
                                      f"levels between 1 and level = {p['level']}")
        self.options = dict(level=p["level"], details_removed=details, mode=p["mode"])
        self.label = denoising_label(p["level"], details, p["mode"])
        self.publisher = self.create_publisher(BacklashWindow, "windows/denoised", WINDOW_QOS)
        self.faults = FaultLog()
        self.health = InputHealth(p["stale_after_s"], p["fault_hold_s"], "windows")
        self.counts = {"denoised": 0, "dropped": 0}
        self.diagnostics = DriveDiagnostics(self, "denoise", p["drive_name"],
                                            refresh=self.update_diagnostics)
        self.windows_in = HistorySubscription(self, BacklashWindow, "windows/raw", self.on_window, WINDOW_QOS,
                                              faults=self.faults, on_passed_over=self.on_history_passed_over)

    def on_window(self, msg: BacklashWindow):
        now = time.monotonic()
        self.health.arrived(now)
        a1, a2 = from_float64_field(msg.a1), from_float64_field(msg.a2)
        clean, reason = denoise_checked(a1, a2, **self.options)
        if reason is not None:
            self.faults.add(reason, f"window at sample {msg.entry_sample_index}")
            self.counts["dropped"] += 1
            self.health.update(now, self.faults)
            self.get_logger().warning(f"window at sample {msg.entry_sample_index} dropped: "
                                      f"{reason}", throttle_duration_sec=5.0)
            self.update_diagnostics(publish_now=True)
            return
        msg.a1 = to_float64_array(clean[0])
        msg.a2 = to_float64_array(clean[1])
        msg.denoising = self.label
        self.publisher.publish(msg)
        self.counts["denoised"] += 1

    def on_history_passed_over(self) -> None:
        """A restarted denoise node's windows/raw history came from its middle: an input fault (WARN for
        fault_hold_s; ros/history_subscription.py added it to self.faults)."""
        self.health.update(time.monotonic(), self.faults)
        self.update_diagnostics(publish_now=True)

    def update_diagnostics(self, publish_now: bool = False):
        level, problem = self.health.state(time.monotonic())
        summary = f"{self.counts['denoised']} windows denoised, {self.counts['dropped']} dropped"
        self.diagnostics.set(level, f"{problem}; {summary}" if problem else summary,
                             publish_now=publish_now, input_faults=self.faults.summary(),
                             history_passed_over=self.windows_in.check.passed_over, **self.counts)


def main(args=None):
    return run_node(DenoiseNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
