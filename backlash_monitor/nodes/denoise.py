"""denoise: removes the sym5 wavelet details 1..6 from every window (SPEC section 2, paper section 3).

    ros2 run backlash_monitor denoise

Subscribes to ``windows/raw`` and publishes ``windows/denoised``: the same windows with a1 and a2
decomposed to level 6 with sym5, details d1..d6 zeroed and reconstructed (backlash_monitor.denoise).
"""
from __future__ import annotations

import sys

from rclpy.node import Node

from backlash_monitor.chain import denoise_pair, denoising_label
from backlash_monitor.denoise import DEFAULT_MODE
from backlash_monitor.nodes.conversions import from_float64_field, to_float64_array
from backlash_monitor.nodes.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.nodes.qos import WINDOW_QOS
from backlash_monitor.nodes.runtime import run_node
from backlash_monitor_msgs.msg import BacklashWindow

PARAMETERS = (
    ParameterSpec("level", 6, "wavelet decomposition level", 1, 10),
    ParameterSpec("details_removed", [1, 2, 3, 4, 5, 6], "detail levels zeroed (1 = finest)"),
    ParameterSpec("mode", DEFAULT_MODE, "signal extension mode at the window's edges (PyWavelets)",
                  choices=("symmetric", "smooth", "periodization", "reflect", "zero", "constant",
                           "periodic", "antisymmetric", "antireflect")),
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
        self.create_subscription(BacklashWindow, "windows/raw", self.on_window, WINDOW_QOS)

    def on_window(self, msg: BacklashWindow):
        try:
            a1, a2 = denoise_pair(from_float64_field(msg.a1), from_float64_field(msg.a2),
                                  **self.options)
        except ValueError as error:
            self.get_logger().error(f"window at sample {msg.entry_sample_index} not denoised: {error}")
            return
        msg.a1 = to_float64_array(a1)
        msg.a2 = to_float64_array(a2)
        msg.denoising = self.label
        self.publisher.publish(msg)


def main(args=None):
    return run_node(DenoiseNode, args=args)


if __name__ == "__main__":
    sys.exit(main())
