"""chunk_talker: publishes a sine wave as SignalChunk messages (a DDS check for this install).

    ros2 run backlash_monitor chunk_talker --ros-args -p count:=10

Publishes ``count`` chunks of ``chunk_samples`` samples on ``plant/check`` (reliable, so that a
listener that matched receives every one), then exits 0. ``count`` 0 publishes until Ctrl-C.
"""
import math
import sys

import rclpy
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor
from rclpy.node import Node

from backlash_monitor_msgs.msg import SignalChunk

from backlash_monitor.ros.runtime import run_node

SAMPLE_PERIOD_S = 2e-5


class ChunkTalker(Node):
    def __init__(self):
        super().__init__("chunk_talker")
        self.count = self.declare_parameter(
            "count", 10, ParameterDescriptor(
                description="chunks to publish; 0 = until Ctrl-C",
                integer_range=[IntegerRange(from_value=0, to_value=1_000_000, step=1)])).value
        self.chunk_samples = self.declare_parameter(
            "chunk_samples", 1000, ParameterDescriptor(
                description="samples per chunk",
                integer_range=[IntegerRange(from_value=1, to_value=1_000_000, step=1)])).value
        self.publisher = self.create_publisher(SignalChunk, "plant/check", 10)
        self.sent = 0
        self.timer = self.create_timer(0.05, self.publish_chunk)

    def publish_chunk(self):
        # Wait for a listener so a check run with count > 0 is not lost to discovery time.
        if self.count and self.publisher.get_subscription_count() == 0:
            return
        first = self.sent * self.chunk_samples
        msg = SignalChunk()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.header.frame_id = "check"
        msg.signal_name = "check"
        msg.unit = "1"
        msg.sample_period_s = SAMPLE_PERIOD_S
        msg.first_sample_index = first
        msg.samples = [math.sin(2 * math.pi * 50 * (first + i) * SAMPLE_PERIOD_S)
                       for i in range(self.chunk_samples)]
        self.publisher.publish(msg)
        self.sent += 1

    @property
    def done(self):
        return self.count and self.sent >= self.count


def main(args=None):
    def spin(node, executor):
        while rclpy.ok() and not node.done:
            executor.spin_once(timeout_sec=0.1)
        # Give the last message time to leave before the publisher disappears.
        for _ in range(5):
            executor.spin_once(timeout_sec=0.05)
        node.get_logger().info(f"published {node.sent} chunks")
    return run_node(ChunkTalker, args=args, spin=spin)


if __name__ == "__main__":
    sys.exit(main())
