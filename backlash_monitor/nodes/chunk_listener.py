"""chunk_listener: receives SignalChunk messages on ``plant/check`` and checks their continuity.

    ros2 run backlash_monitor chunk_listener --ros-args -p count:=10

Prints one line per chunk (first sample index, length, whether it follows the previous chunk) and
exits 0 after ``count`` chunks (0 = until Ctrl-C); exits 1 if a chunk was missing or out of order.
"""
import sys

import rclpy
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
from rclpy.node import Node

from backlash_monitor_msgs.msg import SignalChunk

from backlash_monitor.ros.runtime import run_node


class ChunkListener(Node):
    def __init__(self):
        super().__init__("chunk_listener")
        self.count = self.declare_parameter(
            "count", 10, ParameterDescriptor(
                description="chunks to receive before exiting; 0 = until Ctrl-C",
                integer_range=[IntegerRange(from_value=0, to_value=1_000_000, step=1)])).value
        self.received = 0
        self.gaps = 0
        self.next_index = None
        self.create_subscription(SignalChunk, "plant/check", self.on_chunk, 10)

    def on_chunk(self, msg: SignalChunk):
        follows = self.next_index is None or msg.first_sample_index == self.next_index
        self.gaps += 0 if follows else 1
        self.next_index = msg.first_sample_index + len(msg.samples)
        self.received += 1
        print(f"chunk first_sample_index={msg.first_sample_index} samples={len(msg.samples)} "
              f"{'continuous' if follows else 'GAP'}", flush=True)

    @property
    def done(self):
        return self.count and self.received >= self.count


def main(args=None):
    built = []

    def build():
        built.append(ChunkListener())
        return built[0]

    def spin(node, executor):
        while rclpy.ok() and not node.done:
            executor.spin_once(timeout_sec=0.1)
    code = run_node(build, args=args, spin=spin)
    return code or (1 if built and built[0].gaps else 0)


if __name__ == "__main__":
    sys.exit(main())
