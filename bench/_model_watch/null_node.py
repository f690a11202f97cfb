"""A node with the model_watch node's subscriptions and no work: the side-by-side baseline of cpu_per_drive.

The same runtime (ros/runtime.run_node: the lean executor, batching the wake-ups as model_watch's does: the
second argument, its ``batch_s``), the same four plant topics taken serialized (``raw=True``) with the same QoS
(the first argument: the model_watch node's ``qos`` in the run measured; pipeline --watch gives it 'reliable',
whose acknowledgements cost more than best effort); the callback only counts the bytes. What model_watch costs beyond this is the
watch's own work (events, the test, the ring); this is what any node that reads a 50 kHz drive pays in DDS and
the executor.

    python bench/_model_watch/null_node.py reliable 0.25  # in the pipeline's ROS domain; ends on SIGINT/SIGTERM
"""
from __future__ import annotations

import sys

from rclpy.node import Node

from backlash_monitor.ros.qos import chunk_qos
from backlash_monitor.ros.runtime import run_node
from backlash_monitor_msgs.msg import SignalChunk

SIGNALS = ("a1", "a2", "angle_difference", "omega1")    # model_watch's (its snapshot_signals default)


QOS = sys.argv[1] if len(sys.argv) > 1 else "sensor_data"
BATCH_S = float(sys.argv[2]) if len(sys.argv) > 2 else 0.0


class NullWatch(Node):
    def __init__(self):
        super().__init__("null_watch")
        self.bytes = 0
        self.executor_batch_s = BATCH_S
        qos = chunk_qos(QOS)
        for name in SIGNALS:
            self.create_subscription(SignalChunk, f"plant/{name}", self.on_chunk, qos, raw=True)

    def on_chunk(self, data) -> None:
        self.bytes += len(data)


if __name__ == "__main__":
    sys.exit(run_node(NullWatch, args=sys.argv[:1]))
