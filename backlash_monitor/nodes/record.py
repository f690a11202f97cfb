"""record: write the graph's topics into one rosbag2-compatible MCAP file (like `ros2 bag record`).

    ros2 run backlash_monitor record --ros-args -p output:=run.mcap
    ros2 run backlash_monitor record --ros-args -p output:=run.mcap -p topics:="plant/*,estimate"

By default every topic the graph publishes is recorded (plant/*, windows/*, estimate, /diagnostics,
...) except /rosout and /parameter_events; topics appearing later are picked up by a periodic
discovery. Messages are taken serialized (`raw=True`) and written as they came off the wire: no
deserialization. The subscription QoS follows the publishers' offers as rosbag2 does (reliable
only if every publisher is reliable, transient-local only if every one is), and the offers are
stored in the channel's `offered_qos_profiles`. log_time = reception time, publish_time = the
publisher's source timestamp.

SIGINT and SIGTERM close the file properly (last chunk, metadata, summary, footer). After a SIGKILL
the complete chunks stay readable (`bag-info --recover`): a chunk is closed every `chunk_size_bytes`
(1 MiB) or `chunk_duration_s` (0.5 s), so at most 0.5 s of the stream is lost.
"""
from __future__ import annotations

import datetime as _dt
import fnmatch
import importlib
import os
import re
import sys
import time

from rclpy.node import Node
from rclpy.qos import (DurabilityPolicy, HistoryPolicy, LivelinessPolicy, QoSProfile,
                       ReliabilityPolicy)

from backlash_monitor.bag import BagWriter
from backlash_monitor.bag.errors import BagError
from backlash_monitor.bag.writer import INFINITE
from backlash_monitor.files.outputs import partial_path
from backlash_monitor.ros.parameters import (ParameterSpec, ParameterValueError,
                                               declare_and_validate)
from backlash_monitor.ros.runtime import begin_shutdown, run_node

DEFAULT_EXCLUDE = r"^/(rosout|parameter_events)$"

PARAMETERS = (
    ParameterSpec("output", "", "the .mcap file to write (default, empty: backlash_<UTC time>.mcap here); an "
                  "existing file is an error unless overwrite is true"),
    ParameterSpec("overwrite", False, "replace an existing output file: the new recording goes to "
                  "OUTPUT.partial and replaces OUTPUT only when it is closed"),
    ParameterSpec("topics", "", "comma-separated topic names or glob patterns to record, e.g. "
                  "'plant/*,estimate' (relative names are taken from /); default, empty: every topic"),
    ParameterSpec("exclude_regex", DEFAULT_EXCLUDE, "topics matching this regex are not recorded"),
    ParameterSpec("discovery_period_s", 0.2, "how often new topics are looked for [s]", 0.01, 60.0),
    ParameterSpec("compression", "zstd", "chunk compression", choices=("zstd", "lz4", "none")),
    ParameterSpec("chunk_size_bytes", 1 << 20, "a chunk is closed at this many uncompressed bytes",
                  4096, 1 << 30),
    ParameterSpec("chunk_duration_s", 0.5, "... or when it spans this long (bounds the loss on a "
                  "kill) [s]", 0.01, 3600.0),
    ParameterSpec("queue_depth", 1000, "history depth of each subscription", 1, 1_000_000),
    ParameterSpec("duration_s", 0.0, "stop after this long [s] (0 = until SIGINT/SIGTERM)",
                  0.0, 1e7),
)

_HISTORY = {HistoryPolicy.KEEP_LAST: "keep_last", HistoryPolicy.KEEP_ALL: "keep_all",
            HistoryPolicy.SYSTEM_DEFAULT: "system_default"}
_RELIABILITY = {ReliabilityPolicy.RELIABLE: "reliable", ReliabilityPolicy.BEST_EFFORT: "best_effort",
                ReliabilityPolicy.SYSTEM_DEFAULT: "system_default"}
_DURABILITY = {DurabilityPolicy.VOLATILE: "volatile", DurabilityPolicy.TRANSIENT_LOCAL:
               "transient_local", DurabilityPolicy.SYSTEM_DEFAULT: "system_default"}
_LIVELINESS = {LivelinessPolicy.AUTOMATIC: "automatic", LivelinessPolicy.MANUAL_BY_TOPIC:
               "manual_by_topic", LivelinessPolicy.SYSTEM_DEFAULT: "system_default"}


def message_class(type_name: str):
    """The rclpy message class of 'pkg/msg/Name'."""
    pkg, ns, name = type_name.split("/")
    return getattr(importlib.import_module(f"{pkg}.{ns}"), name)


def _duration(d) -> dict:
    ns = d.nanoseconds if hasattr(d, "nanoseconds") else int(d)
    if ns >= 0x7FFFFFFFFFFFFFFF or ns < 0:
        return dict(INFINITE)
    return {"sec": ns // 1_000_000_000, "nsec": ns % 1_000_000_000}


def qos_to_dict(qos: QoSProfile) -> dict:
    """An rclpy QoS profile as rosbag2 (metadata v9) stores an offered profile."""
    return {
        "history": _HISTORY.get(qos.history, "unknown"), "depth": int(qos.depth),
        "reliability": _RELIABILITY.get(qos.reliability, "unknown"),
        "durability": _DURABILITY.get(qos.durability, "unknown"),
        "deadline": _duration(qos.deadline), "lifespan": _duration(qos.lifespan),
        "liveliness": _LIVELINESS.get(qos.liveliness, "unknown"),
        "liveliness_lease_duration": _duration(qos.liveliness_lease_duration),
        "avoid_ros_namespace_conventions": bool(qos.avoid_ros_namespace_conventions),
    }


def request_qos(offers, depth: int) -> QoSProfile:
    """rosbag2's adapt_request_to_offers: reliable/transient-local only if every publisher is."""
    reliable = bool(offers) and all(o.reliability == ReliabilityPolicy.RELIABLE for o in offers)
    latched = bool(offers) and all(o.durability == DurabilityPolicy.TRANSIENT_LOCAL for o in offers)
    return QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=depth,
                      reliability=ReliabilityPolicy.RELIABLE if reliable else ReliabilityPolicy.BEST_EFFORT,
                      durability=DurabilityPolicy.TRANSIENT_LOCAL if latched else DurabilityPolicy.VOLATILE)


def default_output() -> str:
    return "backlash_" + _dt.datetime.now(_dt.timezone.utc).strftime("%Y_%m_%d-%H_%M_%S") + ".mcap"


class RecordNode(Node):
    def __init__(self, **overrides):
        super().__init__("record", **overrides)
        p = declare_and_validate(self, PARAMETERS)
        self.params = p
        try:
            self.exclude = re.compile(p["exclude_regex"]) if p["exclude_regex"] else None
        except re.error as error:
            raise ParameterValueError(f"parameter 'exclude_regex' = {p['exclude_regex']!r} is not a "
                                      f"valid regular expression ({error}); allowed: a Python regex") \
                from None
        self.patterns = [t.strip() if t.strip().startswith("/") else "/" + t.strip()
                         for t in p["topics"].split(",") if t.strip()]
        self.output = p["output"] or default_output()
        # Never replace an existing recording silently: without `overwrite` the file is created
        # exclusively; with it the new recording is written beside it and renamed over it at close
        # (a killed recorder then leaves the old recording intact and OUTPUT.partial readable).
        self.writing_to = str(partial_path(self.output)) if p["overwrite"] else self.output
        try:
            self.writer = BagWriter(self.writing_to, compression="" if p["compression"] == "none"
                                    else p["compression"], chunk_size=p["chunk_size_bytes"],
                                    chunk_duration_s=p["chunk_duration_s"], exclusive=True)
        except FileExistsError:
            which = self.output if self.writing_to == self.output else f"{self.writing_to} (left by a killed recorder?)"
            raise ParameterValueError(f"parameter 'output' = {self.output!r}: {which} exists already; "
                                      "allowed: a new path, or overwrite:=true to replace it") from None
        except OSError as error:
            raise ParameterValueError(f"parameter 'output' = {self.output!r}: cannot create the file "
                                      f"({error.strerror}); allowed: a writable path") from None
        self.chunk_age_ns = int(p["chunk_duration_s"] * 1e9)
        self.subscriptions_by_topic = {}
        self.failed_topics: dict[str, str] = {}
        self.counts: dict[str, int] = {}
        self.started = time.monotonic()
        self.discover()
        self.discovery_timer = self.create_timer(p["discovery_period_s"], self.discover)
        self.flush_timer = self.create_timer(min(p["chunk_duration_s"], 1.0), self.flush_old_chunk)
        self.get_logger().info(f"recording into {self.output}")

    def wanted(self, topic: str) -> bool:
        if self.exclude is not None and self.exclude.search(topic):
            return False
        if not self.patterns:
            return True
        return any(fnmatch.fnmatchcase(topic, pat) for pat in self.patterns)

    def discover(self) -> None:
        if self.params["duration_s"] > 0 and time.monotonic() - self.started >= self.params["duration_s"]:
            self.get_logger().info(f"duration_s = {self.params['duration_s']} reached")
            raise SystemExit(0)
        for topic, types in self.get_topic_names_and_types():
            if topic in self.subscriptions_by_topic or topic in self.failed_topics:
                continue
            if not self.wanted(topic):
                continue
            type_name = types[0]
            infos = self.get_publishers_info_by_topic(topic)
            if not infos:
                continue  # only subscribers so far: record once someone publishes
            try:
                msg_type = message_class(type_name)
                type_hash = ""
                th = getattr(infos[0], "topic_type_hash", None)
                if th is not None and str(th).startswith("RIHS01_"):
                    type_hash = str(th)
                self.writer.add_topic(topic, type_name,
                                      qos_profiles=[qos_to_dict(i.qos_profile) for i in infos],
                                      type_hash=type_hash or None)
            except (ImportError, AttributeError, ValueError, BagError) as error:
                self.failed_topics[topic] = str(error)
                self.get_logger().error(f"cannot record {topic} ({type_name}): {error}")
                continue
            qos = request_qos([i.qos_profile for i in infos], self.params["queue_depth"])
            self.counts[topic] = 0
            self.subscriptions_by_topic[topic] = self.create_subscription(
                msg_type, topic, self._callback(topic), qos, raw=True)
            self.get_logger().info(f"recording {topic} [{type_name}]")

    def _callback(self, topic: str):
        write = self.writer.write_raw
        counts = self.counts

        def on_message(data, info):
            received = info.get("received_timestamp") or time.time_ns()
            source = info.get("source_timestamp") or received
            write(topic, data, received, source)
            counts[topic] += 1

        return on_message

    def flush_old_chunk(self) -> None:
        """Close a chunk that has been open too long (a slow or stalled stream)."""
        w = self.writer
        start = w._chunk_start
        if start is not None and time.time_ns() - start >= self.chunk_age_ns:
            w.flush()

    def close(self) -> None:
        if not self.writer.closed:
            self.writer.close()
            if self.writing_to != self.output:
                os.replace(self.writing_to, self.output)
            total = sum(self.counts.values())
            self.recorded_messages = total
            text = f"closed {self.output}: {total} messages on {len(self.counts)} topics"
            if total == 0:     # no publisher (or none matched): a warning and exit code 1 (docs/cli.md)
                text += ("; recorded nothing: no publisher on the recorded topics"
                         + (f" ({self.params['topics']})" if self.params["topics"] else ""))
            if self.context.ok():
                (self.get_logger().warning if total == 0 else self.get_logger().info)(text)
            else:  # after SIGINT/SIGTERM the context is gone: rosout logging would complain
                print(f"[{'WARN' if total == 0 else 'INFO'}] [record]: {text}", file=sys.stderr, flush=True)

    def destroy_node(self):
        try:
            self.close()
        finally:
            return super().destroy_node()


def _spin(node: RecordNode, executor) -> None:
    try:
        executor.spin()
    except SystemExit:
        pass
    finally:
        begin_shutdown()   # a second SIGINT/SIGTERM is noted, it does not interrupt the close
        node.close()


def main(args=None, empty_exit_code: int = 0) -> int:
    """Exit code 0 (``empty_exit_code`` when the recording holds no message: the warning says so; the CLI's
    `record` gives 1), or 2 for bad parameters."""
    spun = []

    def spin(node, executor):
        spun.append(node)
        _spin(node, executor)
    code = run_node(RecordNode, args=args, spin=spin)
    if code == 0 and spun and getattr(spun[0], "recorded_messages", 1) == 0:
        return empty_exit_code
    return code


if __name__ == "__main__":
    sys.exit(main())
