"""windowing: detects backlash-zone entries in a drive's stream and publishes the windows after them.

    ros2 run backlash_monitor windowing --ros-args -p trigger:=contact_loss

Subscribes to ``plant/a1``, ``plant/a2`` and ``plant/angle_difference`` (or ``plant/omega1`` and
``plant/omega2`` with ``angle_source:=integrated``; and ``plant/omega1`` with ``check_a1_chain:=true``, a1 checked
against the motor speed, each window carrying the check), joins the chunks of one sample range, feeds the
windowing core (backlash_monitor.windowing) and publishes each captured window (a1 and a2, 2048
samples from the entry + ``window_offset_samples``, tagged onset/return) on ``windows/raw``. A window that spans a dropped or
out-of-order chunk is discarded with its reason (logged, counted on ``/diagnostics``), never used.

Every chunk is checked by the cores it enters (ChunkJoiner, WindowingStage; docs/windowing.md
"Input faults"): a bad one is dropped and counted with its reason, the stream resumes after it or
re-synchronises (an index restart), and ``/diagnostics`` says WARN with the reason while faults
come (``fault_hold_s``), STALE when no chunk arrived for ``stale_after_s``.

Each window carries the accelerometers' constant offsets estimated over the last whole load
periods (``a1_offset_m_s2``, ``a2_offset_m_s2``, ``offset_periods``; backlash_monitor.windowing.offset),
which the classifier removes. ``/diagnostics`` shows the latest estimate and says WARN while one
lies beyond +-``plausible_offset_m_s2`` (more than a MEMS sensor's offset: check the sensor).

A sensor at its rail (clipped) or stuck at one value (backlash_monitor.windowing.saturation, counted
by the core in blocks of 1 s): each window carries its samples at a rail or stuck
(``saturated_samples``), and ``/diagnostics`` says WARN naming the signal, its rail and its share of
samples ("a2 at its rail (±9.81 m/s²) in 4.1 % of samples: the accelerometer's range is too
small") while such samples come and for ``fault_hold_s`` after.
"""
from __future__ import annotations

import math
import sys
import time

from rclpy.node import Node
from std_msgs.msg import Float64

from backlash_monitor.ros.conversions import (from_float64_field, set_window_a1_chain, stamp_of_sample,
                                                 to_float64_array)
from backlash_monitor.ros.drive_diagnostics import DriveDiagnostics
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.ros.qos import LATCHED, WINDOW_QOS, chunk_qos
from backlash_monitor.ros.runtime import run_node
from backlash_monitor.chain.joiner import ChunkJoiner, pending_ranges_for
from backlash_monitor.chain.stage import WindowingStage
from backlash_monitor.stream_time import sample_time_s, stamp_seconds, stream_origin_s
from backlash_monitor.windowing.faults import FaultLog, InputHealth, is_period
from backlash_monitor.windowing import DEFAULTS as WINDOWING_DEFAULTS
from backlash_monitor.windowing.offset import implausible_offsets
from backlash_monitor_msgs.msg import BacklashWindow, SignalChunk

PARAMETERS = (
    ParameterSpec("drive_name", "drive", "the drive's name: frame_id and diagnostics hardware_id"),
    ParameterSpec("trigger", "contact_loss", "entry trigger: 'contact_loss' (angle difference "
                  "alone, for recordings and real drives) or 'paper' (eq. 1 with width_m)",
                  choices=("contact_loss", "paper")),
    ParameterSpec("width_m", 0.0, "backlash width K2 for the 'paper' trigger [m] (0 with "
                  "'contact_loss')", 0.0, 0.05),
    ParameterSpec("angle_source", "measured", "'measured': plant/angle_difference (encoders); "
                  "'integrated': integrate plant/omega1 - plant/omega2 (eq. 2-3)",
                  choices=("measured", "integrated")),
    ParameterSpec("window_length", 2048, "samples captured after each entry", 64, 65536),
    ParameterSpec("window_offset_samples", -1, "samples from the detected entry to the window start; -1 = the trigger's "
                  "configured value (config/windowing.yaml capture.window_offset_samples: "
                  "contact_loss 200, paper 0)", -1, 65536),
    ParameterSpec("qos", "sensor_data", "QoS of the chunk subscriptions",
                  choices=("sensor_data", "reliable")),
    ParameterSpec("stale_after_s", 2.0, "seconds without a chunk after which /diagnostics says "
                  "STALE (a drive streams chunks continuously)", 0.01, 3600.0),
    ParameterSpec("fault_hold_s", 10.0, "seconds /diagnostics stays WARN after the last bad "
                  "chunk (dropped, gap, restart)", 0.01, 3600.0),
    ParameterSpec("plausible_offset_m_s2",
                  float(WINDOWING_DEFAULTS["sensor_offset"]["plausible_abs_m_s2"]),
                  "largest accelerometer offset [m/s^2] taken as a sensor's own (a MEMS zero-g offset "
                  "reaches ~0.2 g); an estimate beyond it makes /diagnostics WARN (config/windowing.yaml "
                  "sensor_offset.plausible_abs_m_s2)", 0.0, 1000.0),
    ParameterSpec("check_a1_chain", False, "check a1 against the motor speed, a1 = r·dΩ₁/dt (subscribes to "
                  "plant/omega1 too: true only when the drive publishes it, else the windows wait for it); each "
                  "window carries the check, and the classifier takes a2's width where a1 does not follow "
                  "(docs/classifier.md 5.4)"),
)


class WindowingNode(Node):
    def __init__(self, **overrides):
        super().__init__("windowing", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        if p["trigger"] == "paper" and p["width_m"] <= 0:
            raise ParameterValueError("parameter 'width_m' = 0.0: the 'paper' trigger needs the "
                                      "backlash width; allowed: 0 < width_m <= 0.05")
        self.params = p
        try:
            self.stage = WindowingStage(
                trigger=p["trigger"], width_m=p["width_m"] if p["trigger"] == "paper" else None,
                angle_source=p["angle_source"], window_length=p["window_length"],
                window_offset_samples=(None if p["window_offset_samples"] < 0
                                       else p["window_offset_samples"]),
                check_a1_chain=p["check_a1_chain"])
        except ValueError as error:
            raise ParameterValueError(str(error)) from None
        self.signals = self.stage.input_signals
        self.faults = FaultLog()
        self.stage.faults = self.faults
        qos = chunk_qos(p["qos"])
        # a range waits for its last chunk as long as that can still be queued (a reliable topic's
        # 1000 chunks: under load the signals' topics run seconds apart; docs/graph.md)
        self.joiner = ChunkJoiner(self.signals, max_pending=pending_ranges_for(qos.depth),
                                  faults=self.faults)
        self.health = InputHealth(p["stale_after_s"], p["fault_hold_s"], "chunks")
        self.true_width_m = math.nan
        self.stream_start_s = None
        # onsets_before_offset: onset windows published before the sensor offsets were known (the
        # classifier does not classify them: one at a stream's start)
        self.counts = {"windows": 0, "onsets": 0, "onsets_before_offset": 0, "discarded": 0,
                       "chunks": 0}
        self.last_discard = ""
        self.sensor_offsets: tuple[dict, int] = ({}, 0)   # the last window's estimate, periods
        self.counts["saturated_windows"] = 0
        self.last_saturation_s: float | None = None   # when a block or a window last had any
        for name in self.signals:
            self.create_subscription(SignalChunk, f"plant/{name}",
                                     lambda msg, n=name: self.on_chunk(n, msg), qos)
        self.create_subscription(Float64, "plant/true_width_m", self.on_true_width, LATCHED)
        self.publisher = self.create_publisher(BacklashWindow, "windows/raw", WINDOW_QOS)
        self.diagnostics = DriveDiagnostics(self, "windowing", p["drive_name"],
                                            refresh=self.update_diagnostics)
        self.get_logger().info(f"trigger {p['trigger']}, angles {p['angle_source']}, "
                               f"{p['window_length']} samples per window, starting "
                               f"{self.stage.window_offset_samples} samples after the entry")

    def on_true_width(self, msg: Float64):
        self.true_width_m = msg.data

    def on_chunk(self, name: str, msg: SignalChunk):
        now = time.monotonic()
        self.health.arrived(now)
        joined = self.joiner.add(name, msg.first_sample_index, msg.sample_period_s,
                                 from_float64_field(msg.samples), msg.header.stamp,
                                 msg.header.frame_id)
        discarded = []
        if joined is not None:
            discarded = self.process(joined)
        new_faults = self.health.update(now, self.faults)
        for reason, detail in self.faults.take():
            self.get_logger().warning(f"input dropped or repaired: {reason} ({detail})",
                                      throttle_duration_sec=5.0)
        if new_faults or discarded:
            self.update_diagnostics(publish_now=True)   # else the periodic refresh updates it

    def process(self, joined):
        """Feeds one joined range; returns the windows it discarded."""
        resyncs = self.faults.counts["stream_restart"] + self.faults.counts["gap"]
        blocks = self.stage.saturation.blocks
        windows, discarded = self.stage.feed(joined)
        if self.stage.saturation.blocks > blocks and any(r.faulty for r in self.stage.saturation.last.values()):
            self.note_saturation()
        self.counts["chunks"] += 1
        resynced = self.faults.counts["stream_restart"] + self.faults.counts["gap"] > resyncs
        if (self.stream_start_s is None or resynced) and is_period(joined.sample_period_s):
            if self.stream_start_s is None:
                # > 0: this process joined a running stream (started late or restarted); the
                # samples before it were not windowed here (docs/graph.md, process faults)
                self.counts["joined_at_sample"] = joined.first_sample_index
            # the stream's time origin, from this range's stamp (again after a restart or a gap)
            self.stream_start_s = stream_origin_s(stamp_seconds(joined.stamp), joined.first_sample_index,
                                                  joined.sample_period_s)
        for window in windows:
            self.publish_window(window, joined.frame_id or self.params["drive_name"], joined.stamp)
        for item in discarded:
            self.counts["discarded"] += 1
            self.last_discard = f"entry {item.entry_sample_index}: {item.reason}"
            self.get_logger().warning(f"window discarded ({self.last_discard})")
        return discarded

    def note_saturation(self):
        first = self.last_saturation_s is None
        self.last_saturation_s = time.monotonic()
        if first:
            self.get_logger().warning("; ".join(self.stage.saturation.messages()) or "saturated window")
            self.update_diagnostics(publish_now=True)

    def update_diagnostics(self, publish_now: bool = False):
        level, problem = self.health.state(time.monotonic())
        saturation = "; ".join(self.stage.saturation.messages())
        if (saturation and self.last_saturation_s is not None
                and time.monotonic() - self.last_saturation_s <= self.params["fault_hold_s"]):
            problem = "; ".join(filter(None, [problem, saturation]))
            if level == "OK":
                level = "WARN"
        summary = f"{self.counts['windows']} windows, {self.counts['discarded']} discarded"
        offsets, periods = self.sensor_offsets
        values = {f"{name}_offset_m_s2": f"{value:.4f}" if math.isfinite(value) else ""
                  for name, value in offsets.items()}
        if periods:
            summary += "; sensor offsets " + ", ".join(
                f"{name} {value:+.2f}" for name, value in offsets.items()) + f" m/s^2 ({periods} periods)"
        limit = self.params["plausible_offset_m_s2"]
        wrong = implausible_offsets(offsets, limit)
        if wrong:
            problem = "; ".join(filter(None, [problem, (
                "sensor offset " + ", ".join(f"{name} {value:+.2f} m/s^2" for name, value in wrong.items())
                + f" beyond +-{limit:g} m/s^2, more than a MEMS sensor's own: check the sensor and its "
                "mounting (the width stays offset-free)")]))
            if level == "OK":
                level = "WARN"
        self.diagnostics.set(level, f"{problem}; {summary}" if problem else summary,
                             publish_now=publish_now, last_discard=self.last_discard,
                             incomplete_chunks=self.joiner.dropped_ranges,
                             pending_ranges_max=self.joiner.pending_max,
                             lost_samples=self.stage.lost_samples,
                             input_faults=self.faults.summary(), offset_periods=periods,
                             plausible_offset_m_s2=limit, saturation=saturation or "none",
                             **values, **self.counts)

    def publish_window(self, window, frame_id: str, range_stamp=None):
        msg = BacklashWindow()
        seconds = (math.nan if self.stream_start_s is None else
                   sample_time_s(self.stream_start_s, window.entry_sample_index, window.sample_period_s))
        if math.isfinite(seconds) and 0.0 <= seconds < 2.0 ** 31:
            msg.header.stamp = stamp_of_sample(self.stream_start_s, window.entry_sample_index,
                                               window.sample_period_s)
        elif range_stamp is not None:
            msg.header.stamp = range_stamp    # a stamp outside builtin_interfaces/Time's range

        msg.header.frame_id = frame_id
        msg.entry_sample_index = window.entry_sample_index
        msg.entry_kind = window.kind
        msg.trigger = window.trigger
        msg.sample_period_s = window.sample_period_s
        msg.denoising = ""
        msg.a1 = to_float64_array(window.signals["a1"])
        msg.a2 = to_float64_array(window.signals["a2"])
        msg.true_width_m = self.true_width_m
        msg.a1_offset_m_s2 = window.sensor_offsets.get("a1", math.nan)
        msg.a2_offset_m_s2 = window.sensor_offsets.get("a2", math.nan)
        msg.offset_periods = window.offset_periods
        msg.saturated_samples = min(window.saturated_samples, 2 ** 32 - 1)
        set_window_a1_chain(msg, getattr(window, "a1_chain", None))
        self.publisher.publish(msg)
        if window.saturated_samples:
            self.counts["saturated_windows"] += 1
            self.note_saturation()
        self.counts["windows"] += 1
        self.counts["onsets"] += window.kind == "onset"
        self.counts["onsets_before_offset"] += window.kind == "onset" and window.offset_periods == 0
        previous = implausible_offsets(self.sensor_offsets[0], self.params["plausible_offset_m_s2"])
        self.sensor_offsets = (dict(window.sensor_offsets), window.offset_periods)
        if implausible_offsets(window.sensor_offsets, self.params["plausible_offset_m_s2"]) and not previous:
            self.get_logger().warning(
                "sensor offset beyond +-%g m/s^2: %s" % (self.params["plausible_offset_m_s2"], ", ".join(
                    f"{k} {v:+.2f} m/s^2" for k, v in window.sensor_offsets.items())))
            self.update_diagnostics(publish_now=True)


def main(args=None):
    return run_node(WindowingNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
