"""windowing: detects backlash-zone entries in a drive's stream and publishes the windows after them.

    ros2 run backlash_monitor windowing --ros-args -p trigger:=contact_loss

Subscribes to ``plant/a1``, ``plant/a2`` and ``plant/angle_difference`` (or ``plant/omega1`` and
``plant/omega2`` with ``angle_source:=integrated``), joins the chunks of one sample range, feeds the
windowing core (backlash_monitor.windowing) and publishes each captured window (a1 and a2, 2048
samples from the entry + ``window_offset_samples``, tagged onset/return) on ``windows/raw``. A window that spans a dropped or
out-of-order chunk is discarded with its reason (logged, counted on ``/diagnostics``), never used.
"""
from __future__ import annotations

import math
import sys

from rclpy.node import Node
from std_msgs.msg import Float64

from backlash_monitor.nodes.conversions import (from_float64_field, stamp_of_sample,
                                                 seconds_from_time, to_float64_array)
from backlash_monitor.nodes.drive_diagnostics import DriveDiagnostics
from backlash_monitor.nodes.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.nodes.qos import LATCHED, WINDOW_QOS, chunk_qos
from backlash_monitor.nodes.runtime import run_node
from backlash_monitor.chain import ChunkJoiner, WindowingStage
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
                                       else p["window_offset_samples"]))
        except ValueError as error:
            raise ParameterValueError(str(error)) from None
        self.signals = self.stage.input_signals
        self.joiner = ChunkJoiner(self.signals)
        self.true_width_m = math.nan
        self.stream_start_s = None
        self.counts = {"windows": 0, "onsets": 0, "discarded": 0, "chunks": 0}
        self.last_discard = ""
        qos = chunk_qos(p["qos"])
        for name in self.signals:
            self.create_subscription(SignalChunk, f"plant/{name}",
                                     lambda msg, n=name: self.on_chunk(n, msg), qos)
        self.create_subscription(Float64, "plant/true_width_m", self.on_true_width, LATCHED)
        self.publisher = self.create_publisher(BacklashWindow, "windows/raw", WINDOW_QOS)
        self.diagnostics = DriveDiagnostics(self, "windowing", p["drive_name"])
        self.get_logger().info(f"trigger {p['trigger']}, angles {p['angle_source']}, "
                               f"{p['window_length']} samples per window, starting "
                               f"{self.stage.window_offset_samples} samples after the entry")

    def on_true_width(self, msg: Float64):
        self.true_width_m = msg.data

    def on_chunk(self, name: str, msg: SignalChunk):
        joined = self.joiner.add(name, msg.first_sample_index, msg.sample_period_s,
                                 from_float64_field(msg.samples), msg.header.stamp,
                                 msg.header.frame_id)
        if joined is not None:
            self.process(joined)

    def process(self, joined):
        if self.stream_start_s is None:
            self.stream_start_s = (seconds_from_time(joined.stamp)
                                   - joined.first_sample_index * joined.sample_period_s)
            # > 0: this process joined a running stream (started late or restarted); the samples
            # before it were not windowed here (docs/graph.md, process faults)
            self.counts["joined_at_sample"] = joined.first_sample_index
        windows, discarded = self.stage.feed(joined)
        self.counts["chunks"] += 1
        for window in windows:
            self.publish_window(window, joined.frame_id or self.params["drive_name"])
        for item in discarded:
            self.counts["discarded"] += 1
            self.last_discard = f"entry {item.entry_sample_index}: {item.reason}"
            self.get_logger().warning(f"window discarded ({self.last_discard})")
        incomplete = self.joiner.dropped_ranges
        level = "WARN" if self.counts["discarded"] or incomplete else "OK"
        self.diagnostics.set(level, f"{self.counts['windows']} windows, "
                                    f"{self.counts['discarded']} discarded",
                             publish_now=bool(discarded), last_discard=self.last_discard,
                             incomplete_chunks=incomplete, **self.counts)

    def publish_window(self, window, frame_id: str):
        msg = BacklashWindow()
        msg.header.stamp = stamp_of_sample(self.stream_start_s, window.entry_sample_index,
                                           window.sample_period_s)
        msg.header.frame_id = frame_id
        msg.entry_sample_index = window.entry_sample_index
        msg.entry_kind = window.kind
        msg.trigger = window.trigger
        msg.sample_period_s = window.sample_period_s
        msg.denoising = ""
        msg.a1 = to_float64_array(window.signals["a1"])
        msg.a2 = to_float64_array(window.signals["a2"])
        msg.true_width_m = self.true_width_m
        self.publisher.publish(msg)
        self.counts["windows"] += 1
        self.counts["onsets"] += window.kind == "onset"


def main(args=None):
    return run_node(WindowingNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
