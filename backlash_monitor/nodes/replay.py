"""replay: publish a recorded MCAP bag into the graph (like `ros2 bag play`).

    ros2 run backlash_monitor replay --ros-args -p bag:=run.mcap                 # recorded rate
    ros2 run backlash_monitor replay --ros-args -p bag:=run.mcap -p rate:=10.0   # 10x faster
    ros2 run backlash_monitor replay --ros-args -p bag:=run.mcap -p rate:=0.0    # flow-controlled

rate > 0: messages leave at their recorded log-time spacing divided by `rate`.
rate = 0: as fast as the subscribers take them without drops: reliable keep-all publishers, the
replay waits for `wait_for_subscribers` matched subscriptions per topic (or `wait_timeout_s`), then
publishes in windows of `window` messages per topic and waits for every subscriber to acknowledge
each window before the next (`wait_for_all_acked`).

stamps = "original" keeps every header stamp as recorded; "fresh" shifts every header.stamp by one
constant offset so that the bag's first stamp becomes the replay's start time (relative timing is
kept exactly; only messages whose first field is a std_msgs/Header are touched, by patching the
CDR bytes, no re-serialization). Messages are published serialized, as read from the file.
The node exits 0 when the bag has been played (or `loop` until SIGINT/SIGTERM).
"""
from __future__ import annotations

import struct
import time

import yaml

import rclpy
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

from backlash_monitor.bag import BagReader
from backlash_monitor.bag.errors import BagError, DamagedBagError, TruncatedBagError
from backlash_monitor.ros.delivery import wait_acknowledged
from backlash_monitor.ros.fast_dds import configure_fast_dds
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.ros.runtime import run_node
from backlash_monitor.nodes.record import message_class

PARAMETERS = (
    ParameterSpec("bag", "", "the .mcap file to play (required)"),
    ParameterSpec("rate", 1.0, "playback speed factor (1 = recorded rate; 0 = as fast as the "
                  "subscribers acknowledge, no drops)", 0.0, 1000.0),
    ParameterSpec("topics", "", "comma-separated topics to play (default, empty: all)"),
    ParameterSpec("stamps", "original", "header stamps: as recorded, or shifted to now",
                  choices=("original", "fresh")),
    ParameterSpec("qos", "recorded", "publisher QoS: as offered when recorded, or reliable",
                  choices=("recorded", "reliable")),
    ParameterSpec("wait_for_subscribers", 0, "wait until every topic has this many matched "
                  "subscriptions before playing (rate 0: at least 1)", 0, 1000),
    ParameterSpec("wait_timeout_s", 30.0, "longest wait for subscribers [s]", 0.0, 3600.0),
    ParameterSpec("window", 50, "rate 0: messages per topic between acknowledgement waits",
                  1, 100000),
    ParameterSpec("recover", False, "play what is intact in a bag whose recorder was killed"),
    ParameterSpec("loop", False, "play again from the start when done, until SIGINT/SIGTERM"),
)

_STAMP = struct.Struct("<iI")

def _publisher_qos(offered_yaml: str, mode: str, flow_control: bool) -> QoSProfile:
    if flow_control or mode == "reliable":
        return QoSProfile(history=HistoryPolicy.KEEP_ALL, depth=1000,
                          reliability=ReliabilityPolicy.RELIABLE)
    reliable, latched, depth = True, False, 100
    try:
        offers = yaml.safe_load(offered_yaml) or []
        if offers:
            reliable = all(o.get("reliability") == "reliable" for o in offers)
            latched = all(o.get("durability") == "transient_local" for o in offers)
    except Exception:  # noqa: BLE001 - unreadable offers: rosbag2's default (reliable, volatile)
        pass
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.RELIABLE if reliable else ReliabilityPolicy.BEST_EFFORT,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE)


SERVE_EVERY_MESSAGES = 64   # as fast as possible (rate 0): serve the services between messages


class ReplayNode(Node):
    def __init__(self, **overrides):
        super().__init__("replay", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        self.params = p
        if not p["bag"]:
            raise ParameterValueError("parameter 'bag' is empty; allowed: the path of an .mcap file")
        try:
            self.reader = BagReader(p["bag"], recover=p["recover"])
        except FileNotFoundError as error:
            raise ParameterValueError(f"parameter 'bag' = {p['bag']!r}: {error}; allowed: the path "
                                      "of an existing .mcap file") from None
        except (TruncatedBagError, DamagedBagError) as error:
            raise ParameterValueError("parameter 'bag': " + str(error).replace(
                "(--recover)", "(recover:=true, `replay --recover`)")) from None
        except BagError as error:
            raise ParameterValueError(f"parameter 'bag' = {p['bag']!r}: {error}") from None
        topics = self.reader.topics
        wanted = [t.strip() for t in p["topics"].split(",") if t.strip()]
        wanted = [t if t.startswith("/") else "/" + t for t in wanted]
        unknown = [t for t in wanted if t not in topics]
        if unknown:
            raise ParameterValueError(f"parameter 'topics': {', '.join(unknown)} not in the bag; "
                                      f"allowed: {', '.join(sorted(topics))}")
        self.topics = wanted or sorted(topics)
        flow = p["rate"] == 0.0
        self.publishers_by_topic = {}
        self.header_first = {}
        for topic in self.topics:
            info = topics[topic]
            try:
                msg_type = message_class(info.type)
            except (ImportError, AttributeError, ValueError) as error:
                raise ParameterValueError(f"topic {topic}: message type {info.type} is not "
                                          f"installed ({error}); leave it out with 'topics'") from None
            self.publishers_by_topic[topic] = self.create_publisher(
                msg_type, topic, _publisher_qos(info.offered_qos_profiles, p["qos"], flow))
            try:
                spec = self.reader.codec(topic).specs[self.reader.codec(topic).type_name]
                self.header_first[topic] = bool(spec.fields) and \
                    spec.fields[0].type == "std_msgs/msg/Header"
            except BagError:
                self.header_first[topic] = False
        self.published = 0
        if not self.reader.recovery.intact:
            self.get_logger().warning(f"{p['bag']}: {self.reader.recovery.describe()}")
        # Called while playing, so that the node's parameter services and QoS events are served
        # (set by main() to spin its executor; the waits below block at most this long).
        self.serve = lambda timeout_s: time.sleep(timeout_s)

    # ------------------------------------------------------------------ playing
    def wait_for_subscribers(self) -> bool:
        need = self.params["wait_for_subscribers"]
        if self.params["rate"] == 0.0:
            need = max(need, 1)
        if need == 0:
            return True
        deadline = time.monotonic() + self.params["wait_timeout_s"]
        while rclpy.ok() and time.monotonic() < deadline:
            if all(pub.get_subscription_count() >= need for pub in self.publishers_by_topic.values()):
                self._serve_for(0.2)  # let reliable readers finish matching both ways
                return True
            self._serve_for(0.02)
        missing = [t for t, pub in self.publishers_by_topic.items()
                   if pub.get_subscription_count() < need]
        self.get_logger().warning(f"no subscriber after {self.params['wait_timeout_s']} s on: "
                                  + ", ".join(missing))
        return False

    def _first_stamp_ns(self):
        for m in self.reader.messages(self.topics, decode=False):
            if self.header_first.get(m.topic) and len(m.data) >= 12:
                sec, nsec = _STAMP.unpack_from(m.data, 4)
                return sec * 1_000_000_000 + nsec
        return None

    def play(self) -> None:
        self.wait_for_subscribers()
        while True:
            self.play_once()
            if not self.params["loop"] or not rclpy.ok():
                break
        self.get_logger().info(f"played {self.published} messages from {self.params['bag']}")
        report = self.reader.recovery
        if report.damaged_any:   # also damage found while playing (a chunk's CRC)
            self.get_logger().warning(f"skipped: {report.damage_text()}")

    def play_once(self) -> None:
        rate = self.params["rate"]
        offset_ns = 0
        if self.params["stamps"] == "fresh":
            first = self._first_stamp_ns()
            if first is not None:
                offset_ns = time.time_ns() - first
        window = self.params["window"]
        in_window = 0
        start_wall = time.monotonic()
        start_log = None
        for m in self.reader.messages(self.topics, decode=False):
            if not rclpy.ok():
                return
            if rate > 0:
                if start_log is None:
                    start_log = m.log_time_ns
                target = start_wall + (m.log_time_ns - start_log) / 1e9 / rate
                self._serve_until(target)
            elif self.published % SERVE_EVERY_MESSAGES == 0:
                self.serve(0.0)
            data = m.data
            if offset_ns and self.header_first.get(m.topic) and len(data) >= 12:
                sec, nsec = _STAMP.unpack_from(data, 4)
                t = sec * 1_000_000_000 + nsec + offset_ns
                data = data[:4] + _STAMP.pack(t // 1_000_000_000, t % 1_000_000_000) + data[12:]
            self.publishers_by_topic[m.topic].publish(data)
            self.published += 1
            if rate == 0.0:
                in_window += 1
                if in_window >= window * len(self.topics):
                    self.wait_acked()
                    in_window = 0
        if rate == 0.0 or self.params["qos"] == "reliable":
            behind = self.wait_acked()
            if behind:
                self.get_logger().warning(
                    f"exiting with messages not acknowledged after {self.params['wait_timeout_s']:g} s on "
                    f"{', '.join(behind)}: a subscriber still behind the bag loses its end (raise wait_timeout_s "
                    "to wait longer)")

    def _serve_until(self, deadline: float) -> None:
        """Serve the node's services until time.monotonic() reaches ``deadline``."""
        while (left := deadline - time.monotonic()) > 0:
            self.serve(left)

    def _serve_for(self, seconds: float) -> None:
        self._serve_until(time.monotonic() + seconds)

    def wait_acked(self) -> list[str]:
        """Wait (up to wait_timeout_s) until every reliable subscriber has acknowledged every message published so
        far; -> the topics still behind (ros/delivery.py)."""
        return wait_acknowledged(self.publishers_by_topic, self.params["wait_timeout_s"])

    def destroy_node(self):
        try:
            self.reader.close()
        finally:
            return super().destroy_node()


def _spin(node: ReplayNode, executor) -> None:
    node.serve = lambda timeout_s: executor.spin_once(timeout_sec=timeout_s)
    try:
        node.play()
    except BagError as error:   # a chunk found damaged while playing (its CRC), recover false
        raise ParameterValueError("parameter 'bag': " + str(error).replace(
            "(--recover)", "(recover:=true, `replay --recover`)")
            + f"; {node.published} messages were played before it") from None


def main(args=None) -> int:
    configure_fast_dds()
    return run_node(ReplayNode, args=args, spin=_spin)


if __name__ == "__main__":
    import sys

    sys.exit(main())
