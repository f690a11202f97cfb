"""classifier: identifies the backlash width from each denoised onset window and reports it.

    ros2 run backlash_monitor classifier --ros-args -p mode:=shape -p n1:=0.89

Subscribes to ``windows/denoised``; for every onset window publishes one BacklashEstimate per
signal on ``estimate`` (width, index, candidate widths, B vector, margin, continuous width, fused
width over the last onset events) and keeps a ``diagnostic_msgs/DiagnosticArray`` on
``/diagnostics``: OK / WARN / ERROR by the fused width against ``warn_width_m`` and
``error_width_m`` (config/diagnostics.yaml), hardware_id = the drive's name.

Every mode reads the window minus the sensor offsets it carries (``a1_offset_m_s2``,
``a2_offset_m_s2``, estimated by the windowing node over whole load periods): a constant
accelerometer offset cannot move the width. A window with ``offset_periods`` 0 (the stream's first
onset window, before one whole load period; or a publisher that does not set them) is not
classified; ``/diagnostics`` counts them (``windows_waiting_for_offset``), it is no fault.

ERROR means one thing: the fused width is at or beyond ``error_width_m``, fused over at least 3 onset events
(estimation.LEVEL_MIN_EVENTS; fewer give the width without a level: it has no uncertainty and the signal check
cannot test it). A window that cannot be
classified (not denoised, a1/a2 of unequal or the wrong length, another sample period than the
library's, non-finite samples, an unknown entry kind; DriveEstimator.check_window) is dropped and
counted with its reason and gives WARN with the reason while such windows come (``fault_hold_s``),
never ERROR; no window for ``stale_after_s`` gives STALE. A width level of ERROR stays ERROR.

The width carries its uncertainty (``fused_width_uncertainty_m``: the robust standard error of the fused
continuous width over the fused events) and, when the model watch of the same namespace says the model does
not explain the drive (its ``model_fit``, level WARN), the status message says so in the same line:
"backlash 10.00 mm ... — model drive7 v1 does not explain this drive (residual 2.5× its floor): run diagnose
before acting" (backlash_monitor/fleet/caveat.py).
"""
from __future__ import annotations

import math
import sys
import time

from rclpy.node import Node

from backlash_monitor.classifier.patterns import PatternLibraryError, flagged_warning, load_library
from backlash_monitor.classifier.signal_check import source_text
from backlash_monitor.fleet.caveat import width_text, with_caveat
from backlash_monitor.estimation import (DEFAULT_FUSION_EVENTS, DEFAULT_MODE, MODES, DriveEstimator, estimate_level,
                                         level_events)
from backlash_monitor.windowing.faults import FaultLog, InputHealth
from backlash_monitor.ros.conversions import a1_chain_from_window, from_float64_field, to_float64_array
from backlash_monitor.ros.drive_diagnostics import DriveDiagnostics
from backlash_monitor.ros.history_subscription import HistorySubscription
from backlash_monitor.ros.model_fit_caveat import follow_model_fit
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.ros.qos import ESTIMATE_QOS, WINDOW_QOS
from backlash_monitor.ros.runtime import run_node
from backlash_monitor.classifier.repeats import RepeatedWindows
from backlash_monitor.windowing import default_window_offset
from backlash_monitor_msgs.msg import BacklashEstimate, BacklashWindow

PARAMETERS = (
    ParameterSpec("drive_name", "drive", "the drive's name: diagnostics hardware_id"),
    ParameterSpec("mode", DEFAULT_MODE, "classifier mode: 'paper' (the paper's equations as "
                  "written), 'paper_corrected', or 'shape' (the improved mode)", choices=MODES),
    ParameterSpec("signals", [""], "signals to classify (a1, a2, a1+a2); [''] = the mode's "
                  "default"),
    ParameterSpec("n1", 0.89, "absorber flow index of the drive: which patterns the paper modes "
                  "use", 0.5, 1.5),
    ParameterSpec("trigger", "contact_loss", "trigger the windows were captured with; the "
                  "library must have been trained with it", choices=("contact_loss", "paper")),
    ParameterSpec("window_offset_samples", -1, "window start offset the windows were captured "
                  "with (the windowing node's parameter); the library must have been trained with it; "
                  "samples from the detected entry to the window start; -1 = the trigger's "
                  "configured value (config/windowing.yaml capture.window_offset_samples: "
                  "contact_loss 200, paper 0)", -1, 65536),
    ParameterSpec("library", "", "pattern library file (empty: the packaged default)"),
    ParameterSpec("model_version", 0, "the drive's model version in the registry (docs/registry.md), reported in "
                  "/diagnostics so a new version's pickup is seen; 0: none given", 0, 1000000),
    ParameterSpec("fusion_events", DEFAULT_FUSION_EVENTS, "onset events fused into one estimate",
                  1, 1000),
    ParameterSpec("warn_width_m", 0.0075, "fused width from which the drive is WARN [m]",
                  0.0, 1.0),
    ParameterSpec("error_width_m", 0.009, "fused width from which the drive is ERROR [m]",
                  0.0, 1.0),
    ParameterSpec("stale_after_s", 60.0, "seconds without a window after which /diagnostics "
                  "says STALE (windows come only with load pulses)", 0.01, 86400.0),
    ParameterSpec("fault_hold_s", 10.0, "seconds /diagnostics stays WARN after the last "
                  "window dropped as bad", 0.01, 3600.0),
)


class ClassifierNode(Node):
    def __init__(self, **overrides):
        super().__init__("classifier", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        if p["error_width_m"] < p["warn_width_m"]:
            raise ParameterValueError(
                f"parameter 'error_width_m' = {p['error_width_m']} is below warn_width_m = "
                f"{p['warn_width_m']}; allowed: error_width_m >= warn_width_m")
        self.params = p
        signals = tuple(s for s in p["signals"] if s) or None
        try:
            offset = (default_window_offset(p["trigger"]) if p["window_offset_samples"] < 0
                      else p["window_offset_samples"])
            library = load_library(p["library"] or None, trigger=p["trigger"], window_offset_samples=offset)
            self.library_flag = flagged_warning(library)
            self.estimator = DriveEstimator(library, mode=p["mode"], n1=p["n1"], signals=signals,
                                            fusion_events=p["fusion_events"])
        except (PatternLibraryError, ValueError) as error:
            raise ParameterValueError(str(error)) from None
        self.library_path = str(library.path)
        self.publisher = self.create_publisher(BacklashEstimate, "estimate", ESTIMATE_QOS)
        self.classified = 0
        self.repeated = RepeatedWindows()
        self.faults = FaultLog()            # windows dropped here (not denoised), a history passed over
        self.windows_in = HistorySubscription(self, BacklashWindow, "windows/denoised", self.on_window, WINDOW_QOS,
                                              faults=self.faults, on_passed_over=self.on_history_passed_over)
        self.health = InputHealth(p["stale_after_s"], p["fault_hold_s"], "windows")
        # estimates from windows with samples at a sensor's rail or stuck: (count, when [monotonic s],
        # the last one's entry sample, its saturated samples)
        self.saturated_estimates: tuple = (0, None, 0, 0)
        self.width_state = None             # (level, message, values) of the last fused width
        self.model_fit = None               # the model watch's last FitVerdict (None: none heard)
        follow_model_fit(self, self.on_model_fit)
        self.diagnostics = DriveDiagnostics(self, "backlash width", p["drive_name"],
                                            refresh=self.update_diagnostics)
        self.get_logger().info(f"mode {p['mode']}, signals {', '.join(self.estimator.signals)}, "
                               f"library {library.path}")
        if self.library_flag:
            self.get_logger().warning(self.library_flag)

    def on_history_passed_over(self) -> None:
        """A restarted classifier's windows/denoised history came from its middle: an input fault (WARN for
        fault_hold_s; ros/history_subscription.py added it to self.faults)."""
        if self.health.update(time.monotonic(), self.faults, self.estimator.faults):
            self.update_diagnostics(publish_now=True)

    def on_model_fit(self, verdict) -> None:
        changed = self.model_fit is None or verdict.explains != self.model_fit.explains
        self.model_fit = verdict
        if changed:
            self.update_diagnostics(publish_now=True)

    def on_window(self, msg: BacklashWindow):
        now = time.monotonic()
        self.health.arrived(now)
        try:
            self.classify(msg)
        finally:
            if self.health.update(now, self.faults, self.estimator.faults):
                self.get_logger().warning(f"window at sample {msg.entry_sample_index} not "
                                          f"classified: {self.health.last_fault[0]}",
                                          throttle_duration_sec=5.0)
                self.update_diagnostics(publish_now=True)

    def classify(self, msg: BacklashWindow):
        if not msg.denoising:
            # classifying raw windows against denoised patterns is wrong
            self.faults.add("not_denoised", f"window at sample {msg.entry_sample_index}")
            return
        stamp_ns = msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec
        if self.repeated.is_repeat(stamp_ns, msg.entry_sample_index, msg.entry_kind,
                                   msg.header.frame_id):
            # Re-sent history (an upstream node restarted): fusing it again would count the
            # event twice.
            self.get_logger().info(f"window at sample {msg.entry_sample_index} arrived again: "
                                   "skipped", throttle_duration_sec=10.0)
            return
        # checked by the core (DriveEstimator.check_window): a bad window gives no estimate
        offsets = ((msg.a1_offset_m_s2, msg.a2_offset_m_s2) if msg.offset_periods > 0
                   else (math.nan, math.nan))
        # a1 checked against the motor speed upstream (check_a1_chain): a2's width where a1 does not follow it
        estimates = self.estimator.estimate(from_float64_field(msg.a1), from_float64_field(msg.a2),
                                            msg.entry_kind, msg.sample_period_s, sensor_offsets=offsets,
                                            a1_chain=a1_chain_from_window(msg))
        for estimate in estimates:
            self.publisher.publish(self.to_message(msg, estimate))
        if estimates and msg.saturated_samples:
            # a window with samples at a sensor's rail (or stuck): classified, flagged on /diagnostics
            self.saturated_estimates = (self.saturated_estimates[0] + 1, time.monotonic(),
                                        msg.entry_sample_index, msg.saturated_samples)
        if estimates:
            self.classified += 1
            # Both signals together is the most informative estimate where the mode has it.
            primary = next((e for e in estimates if e.signal_name == "a1+a2"), estimates[0])
            self.set_width(primary)

    def to_message(self, window: BacklashWindow, estimate) -> BacklashEstimate:
        out = BacklashEstimate()
        out.header = window.header
        out.signal_name = estimate.signal_name
        out.mode = estimate.mode
        out.entry_sample_index = window.entry_sample_index
        out.entry_kind = window.entry_kind
        out.candidate_widths_m = to_float64_array(estimate.candidate_widths_m)
        out.b_vector = to_float64_array(estimate.b_vector)
        out.width_index = estimate.width_index
        out.width_m = estimate.width_m
        out.b_margin = estimate.b_margin
        out.continuous_width_m = estimate.continuous_width_m
        out.fused_width_m = estimate.fused_width_m
        out.fused_events = estimate.fused_events
        out.fused_continuous_width_m = estimate.fused_continuous_width_m
        out.fused_width_uncertainty_m = estimate.fused_width_uncertainty_m
        out.true_width_m = window.true_width_m
        return out

    def set_width(self, estimate):
        p = self.params
        level = estimate_level(estimate.level_width_m, estimate.fused_events, p["warn_width_m"], p["error_width_m"],
                               p["fusion_events"])
        cont = width_text(estimate.fused_continuous_width_m, estimate.fused_width_uncertainty_m)
        shown = f"{estimate.fused_width_m * 1e3:.2f} mm" if cont == "-" else cont
        # a1+a2's fusion checked against a1's (classifier/signal_check.py): say when the width is a1's
        source = source_text(estimate.fused_from_signal, estimate.signal_name, estimate.check_reason)
        source = f"; {source}" if source else ""
        few = level_events(p["fusion_events"])
        source += (f"; no level from fewer than {few} events" if estimate.fused_events < few else "")
        self.width_state = (level, f"backlash {shown} (fused over {estimate.fused_events} events{source}; nearest "
                                   f"pattern width {estimate.fused_width_m * 1e3:.2f} mm)", dict(
            fused_width_m=f"{estimate.fused_width_m:.5f}", last_width_m=f"{estimate.width_m:.5f}",
            continuous_width_m="" if math.isnan(estimate.continuous_width_m)
            else f"{estimate.continuous_width_m:.5f}",
            fused_continuous_width_m="" if math.isnan(estimate.fused_continuous_width_m)
            else f"{estimate.fused_continuous_width_m:.5f}",
            fused_width_uncertainty_m="" if math.isnan(estimate.fused_width_uncertainty_m)
            else f"{estimate.fused_width_uncertainty_m:.5f}",
            signal=estimate.signal_name, fused_from_signal=estimate.fused_from_signal or estimate.signal_name,
            mode=estimate.mode))
        self.update_diagnostics()

    def update_diagnostics(self, publish_now: bool = False):
        """The drive's level: ERROR only from the fused width; else STALE when no window came for
        stale_after_s; WARN from the width or while bad windows come; OK."""
        p = self.params
        input_level, problem = self.health.state(time.monotonic())
        width_level, message, values = self.width_state or ("OK", "no estimate yet", {})
        if self.width_state is None and self.estimator.waiting_for_offset:
            message += (f" ({self.estimator.waiting_for_offset} onset window(s) before the sensor "
                        "offset was known: it needs one whole load period)")
        if width_level == "ERROR":
            level = "ERROR"
        elif input_level == "STALE":
            level = "STALE"
        elif "WARN" in (width_level, input_level) or self.library_flag:
            level = "WARN"
        else:
            level = "OK"
        saturated = self.saturated_estimates
        if saturated[0] and time.monotonic() - saturated[1] <= p["fault_hold_s"]:
            problem = "; ".join(filter(None, [problem, (
                f"estimate from a window with {saturated[3]} samples at a sensor's rail or stuck (entry "
                f"{saturated[2]}; the windowing node names the sensor)")]))
            level = "WARN" if level == "OK" else level
        if problem:
            message = f"{message}; {problem}"
        if self.library_flag:
            message = f"{message}; {self.library_flag}"
        if self.width_state is not None:   # every width, OK, WARN or ERROR, carries a failed model fit
            message = with_caveat(message, self.model_fit)
        rejected = (self.faults.total - self.faults.counts["history_passed_over"]   # windows, not a history
                    + self.estimator.faults.total)
        self.diagnostics.set(
            level, message, publish_now=publish_now, **values,
            windows_classified=self.classified, windows_rejected=rejected,
            windows_waiting_for_offset=self.estimator.waiting_for_offset,
            input_faults=", ".join(f for f in (self.faults.summary(), self.estimator.faults.summary())
                                   if f != "none") or "none",
            repeated_windows_skipped=self.repeated.repeats, saturated_estimates=saturated[0],
            history_passed_over=self.windows_in.check.passed_over,
            warn_width_m=p["warn_width_m"], error_width_m=p["error_width_m"],
            model_version=p["model_version"], library=self.library_path,
            model_fit="" if self.model_fit is None else
            ("explains" if self.model_fit.explains else "does not explain"))


def main(args=None):
    return run_node(ClassifierNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
