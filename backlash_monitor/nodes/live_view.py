"""live_view: the drives' topics and widths served to Foxglove over its WebSocket protocol.

    ros2 run backlash_monitor live_view --ros-args -p namespaces:="[/line1/drive01, /line1/drive02]"
    python -m backlash_monitor fleet --drives 4 --foxglove-port 8765       # the same, in `fleet`

Open Foxglove, "Open connection" -> Foxglove WebSocket -> ws://localhost:8765, and import the
layout config/foxglove_fleet_layout.json. For every namespace the node forwards, as received
(serialized CDR, no decoding; schema = the ROS 2 message definition, as a bag holds it):
``<ns>/plant/a1``, ``<ns>/plant/a2``, ``<ns>/windows/denoised``, ``<ns>/estimate``, ``<ns>/model_fit``
(the model watch's, docs/model_watch.md) and the one ``/diagnostics``; and it publishes per drive
``<ns>/width`` (JSON: the last estimate's width, continuous and fused widths in mm), the fleet's
``/fleet/widths`` (JSON: drive -> fused width in mm) and ``/fleet/model_fit`` (JSON: drive -> the model
watch's residual over the noise floor and level), which the layout plots.

Needs the Foxglove SDK (``pip install foxglove-sdk``, an optional extra): without it the node stops
at start with one line saying so.
"""
from __future__ import annotations

import sys
import time
import importlib

from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from rclpy.serialization import deserialize_message

from backlash_monitor.ros.parameters import ParameterSpec, ParameterValueError, declare_and_validate
from backlash_monitor.ros.qos import DIAGNOSTICS_DEPTH, ESTIMATE_QOS, WINDOW_QOS
from backlash_monitor.ros.runtime import run_node
from backlash_monitor.bag.schema import full_definition

PARAMETERS = (
    ParameterSpec("namespaces", ["/line1/drive01"], "the drives' namespaces to serve"),
    ParameterSpec("host", "127.0.0.1", "address the WebSocket server binds to (0.0.0.0: every "
                  "interface; then anyone on the network can watch)"),
    ParameterSpec("port", 8765, "WebSocket port (Foxglove's default 8765; 0: any free port)",
                  0, 65535),
)

# (topic under the namespace, message type, QoS the subscription asks for)
FORWARDED = (("plant/a1", "backlash_monitor_msgs/msg/SignalChunk", "sensor"),
             ("plant/a2", "backlash_monitor_msgs/msg/SignalChunk", "sensor"),
             ("windows/denoised", "backlash_monitor_msgs/msg/BacklashWindow", "window"),
             ("estimate", "backlash_monitor_msgs/msg/BacklashEstimate", "estimate"),
             ("model_fit", "backlash_monitor_msgs/msg/ModelFit", "model_fit"))

WIDTH_SCHEMA = {"type": "object", "properties": {
    "drive": {"type": "string"}, "signal": {"type": "string"},
    "width_mm": {"type": "number"}, "continuous_width_mm": {"type": "number"},
    "fused_width_mm": {"type": "number"}, "fused_events": {"type": "integer"},
    "fused_continuous_width_mm": {"type": "number"},
    "true_width_mm": {"type": "number"}}}


def _message_class(type_name: str):
    pkg, _, name = type_name.split("/")
    return getattr(importlib.import_module(f"{pkg}.msg"), name)


class LiveViewNode(Node):
    def __init__(self, **overrides):
        super().__init__("live_view", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        try:
            # deferred: optional: foxglove may be missing (the ImportError is handled here)
            import foxglove
        except ImportError:
            raise ParameterValueError("live_view needs the Foxglove SDK: pip install "
                                      "foxglove-sdk (an optional extra)") from None
        namespaces = ["/" + ns.strip("/") for ns in p["namespaces"] if ns.strip("/")]
        if not namespaces:
            raise ParameterValueError("parameter 'namespaces' is empty; allowed: one or more "
                                      "namespaces such as /line1/drive01")
        self.foxglove = foxglove
        self.server = foxglove.start_server(name="backlash_monitor", host=p["host"],
                                            port=p["port"])
        self.port = self.server.port
        # deferred: nodes.model_watch (the watch core) costs ~470 ms at start-up (python -X importtime, 29 Nov); only its QoS is used here
        from backlash_monitor.nodes.model_watch import MODEL_FIT_QOS
        qos = {"sensor": qos_profile_sensor_data, "window": WINDOW_QOS, "estimate": ESTIMATE_QOS,
               "model_fit": MODEL_FIT_QOS}
        self.channels = {}
        self.estimate_type = _message_class("backlash_monitor_msgs/msg/BacklashEstimate")
        self.fleet_widths: dict[str, float] = {}
        self.fleet_fits: dict[str, dict] = {}
        self.fit_type = _message_class("backlash_monitor_msgs/msg/ModelFit")
        self.width_channels = {}
        for ns in namespaces:
            for topic, type_name, qos_name in FORWARDED:
                self._forward(f"{ns}/{topic}", type_name, qos[qos_name], full_definition,
                              on_estimate=ns if topic == "estimate" else None,
                              on_model_fit=ns if topic == "model_fit" else None)
            self.width_channels[ns] = foxglove.Channel(f"{ns}/width", schema=WIDTH_SCHEMA)
        self._forward("/diagnostics", "diagnostic_msgs/msg/DiagnosticArray", DIAGNOSTICS_DEPTH,
                      full_definition)
        self.fleet_channel = foxglove.Channel("/fleet/widths", schema={
            "type": "object", "additionalProperties": {"type": "number"}})
        self.fit_channel = foxglove.Channel("/fleet/model_fit", schema={
            "type": "object", "additionalProperties": {"type": "object", "properties": {
                "residual_over_noise": {"type": "number"}, "level": {"type": "string"},
                "model": {"type": "string"}, "width_mm": {"type": "number"}}}})
        self.get_logger().info(f"Foxglove WebSocket on ws://{p['host']}:{self.port}: "
                               f"{len(namespaces)} drives")

    def _forward(self, topic, type_name, qos, full_definition, on_estimate=None, on_model_fit=None):
        schema = self.foxglove.Schema(name=type_name, encoding="ros2msg",
                                      data=full_definition(type_name).encode())
        channel = self.foxglove.Channel(topic, schema=schema, message_encoding="cdr")
        self.channels[topic] = channel

        def callback(data: bytes, channel=channel):
            channel.log(bytes(data), log_time=time.time_ns())
            if on_estimate is not None:
                self._on_estimate(on_estimate, data)
            if on_model_fit is not None:
                self._on_model_fit(on_model_fit, data)
        self.create_subscription(_message_class(type_name), topic, callback, qos, raw=True)

    def _on_estimate(self, ns: str, data: bytes) -> None:
        msg = deserialize_message(bytes(data), self.estimate_type)
        drive = ns.strip("/")
        self.width_channels[ns].log({
            "drive": drive, "signal": msg.signal_name, "width_mm": msg.width_m * 1e3,
            "continuous_width_mm": msg.continuous_width_m * 1e3 if msg.continuous_width_m
            == msg.continuous_width_m else None,
            "fused_width_mm": msg.fused_width_m * 1e3, "fused_events": msg.fused_events,
            "fused_continuous_width_mm": msg.fused_continuous_width_m * 1e3
            if msg.fused_continuous_width_m == msg.fused_continuous_width_m else None,
            "true_width_mm": msg.true_width_m * 1e3 if msg.true_width_m == msg.true_width_m
            else None})
        self.fleet_widths[drive] = msg.fused_width_m * 1e3
        self.fleet_channel.log(dict(self.fleet_widths))

    def _on_model_fit(self, ns: str, data: bytes) -> None:
        msg = deserialize_message(bytes(data), self.fit_type)
        self.fleet_fits[ns.strip("/")] = {"residual_over_noise": msg.residual_over_noise_overall,
                                          "level": "WARN" if msg.level == msg.WARN else "OK", "model": msg.model,
                                          "width_mm": msg.width_m * 1e3}
        self.fit_channel.log(dict(self.fleet_fits))

    def destroy_node(self):
        server = getattr(self, "server", None)
        if server is not None:
            server.stop()
            self.server = None
        return super().destroy_node()


def main(args=None):
    return run_node(LiveViewNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
