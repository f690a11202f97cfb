"""BagWriter: writes one rosbag2-compatible MCAP file (what `ros2 bag record -s mcap` writes).

File layout (see docs/bags.md):

    magic, Header(profile "ros2")
    Metadata "backlash_monitor.writer" {chunk_duration_s, chunk_size_bytes, compression}
    Schema / Channel records, unchunked, as topics are added (before any message that uses them)
    Chunk (zstd) + its MessageIndex records, Chunk + MessageIndex, ...   <- flushed to the OS per chunk
    Metadata "rosbag2" {serialized_metadata: <BagMetadata YAML, version 9>}     (at close)
    DataEnd
    summary: Schema*, Channel*, Statistics, ChunkIndex*, MetadataIndex, SummaryOffset*
    Footer, magic

Channels: message encoding `cdr`, metadata `offered_qos_profiles` (YAML list of QoS, rosbag2 v9
strings) and `topic_type_hash` (RIHS01_...). Schemas: name `pkg/msg/Name`, encoding `ros2msg`, the
full concatenated definition (schema.full_definition).

A chunk is closed when its uncompressed records reach `chunk_size` bytes (1 MiB) or its messages
span `chunk_duration_s` of log time (0.5 s), or on `flush()`. A process killed with SIGKILL loses
at most the open chunk: at the nominal 50 kHz x 5 signals (~2 MB/s of SignalChunk messages) that is
0.5 s of data.
"""
from __future__ import annotations

import os
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
import array
import struct

import zstandard
import lz4.frame

import backlash_monitor.bag.schema as schema_mod
from .cdr import Codec
from .errors import BagError, MissingTopicError
from .records import (MAGIC, MESSAGE_HEAD, OP_CHANNEL, OP_CHUNK_INDEX, OP_MESSAGE,
                      OP_METADATA_INDEX, OP_SCHEMA, OP_STATISTICS, RECORD_HEADER, U32, WRITER_METADATA,
                      ChunkIndex, MetadataIndex, Statistics, channel_record, chunk_index_record,
                      chunk_record_head, crc32, data_end_record, footer_head, header_record,
                      message_index_record, metadata_index_record, metadata_record, schema_record,
                      statistics_record, summary_offset_record)

LIBRARY = "backlash_monitor.bag (rosbag2_storage_mcap compatible)"
ROSBAG2_METADATA_VERSION = 9
DEFAULT_CHUNK_SIZE = 1 << 20
DEFAULT_CHUNK_DURATION_S = 0.5

# rmw's RMW_DURATION_INFINITE as rosbag2 writes it
INFINITE = {"sec": 9223372036, "nsec": 854775807}


def qos_profile(history: str = "keep_last", depth: int = 10, reliability: str = "reliable",
                durability: str = "volatile", deadline: dict | None = None,
                lifespan: dict | None = None, liveliness: str = "automatic",
                liveliness_lease_duration: dict | None = None,
                avoid_ros_namespace_conventions: bool = False) -> dict[str, Any]:
    """One offered QoS profile as rosbag2 (metadata version 9) stores it."""
    return {
        "history": history, "depth": int(depth), "reliability": reliability,
        "durability": durability, "deadline": dict(deadline or INFINITE),
        "lifespan": dict(lifespan or INFINITE), "liveliness": liveliness,
        "liveliness_lease_duration": dict(liveliness_lease_duration or INFINITE),
        "avoid_ros_namespace_conventions": bool(avoid_ros_namespace_conventions),
    }


# ----------------------------------------------------------------------------------------------
# YAML as yaml-cpp's YAML::Dump writes it (block style, 2-space indent, "" for empty strings)


def _yaml_scalar(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if v is None:
        return "~"
    if isinstance(v, (int, float)):
        return str(v)
    s = str(v)
    if s == "":
        return '""'
    if (s[0] in "!&*-?{}[],#|>@`\"'%: " or s[-1] == " " or ": " in s or " #" in s or "\n" in s
            or s.lower() in ("true", "false", "yes", "no", "null", "~", "on", "off")
            or _looks_numeric(s)):
        return '"' + s.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    return s


def _looks_numeric(s: str) -> bool:
    try:
        float(s)
        return True
    except ValueError:
        return False


def yaml_dump(node, indent: int = 0) -> str:
    """Dump dicts/lists/scalars like yaml-cpp: no trailing newline."""
    return "\n".join(_yaml_lines(node, indent))


def _yaml_lines(node, indent: int) -> list[str]:
    pad = " " * indent
    lines: list[str] = []
    if isinstance(node, dict):
        if not node:
            return [pad + "{}"]
        for k, v in node.items():
            if isinstance(v, dict) and v:
                lines.append(f"{pad}{k}:")
                lines += _yaml_lines(v, indent + 2)
            elif isinstance(v, list) and v:
                lines.append(f"{pad}{k}:")
                lines += _yaml_lines(v, indent + 2)
            elif isinstance(v, list):
                lines.append(f"{pad}{k}: []")
            elif isinstance(v, dict):
                lines.append(f"{pad}{k}: ~")  # yaml-cpp: an empty map node is Null
            else:
                lines.append(f"{pad}{k}: {_yaml_scalar(v)}")
    elif isinstance(node, list):
        if not node:
            return [pad + "[]"]
        for item in node:
            if isinstance(item, (dict, list)) and item:
                sub = _yaml_lines(item, indent + 2)
                sub[0] = pad + "- " + sub[0][indent + 2:]
                lines += sub
            else:
                lines.append(f"{pad}- {_yaml_scalar(item) if not isinstance(item, (dict, list)) else '[]'}")
    else:
        lines.append(pad + _yaml_scalar(node))
    return lines


# ----------------------------------------------------------------------------------------------


@dataclass
class _Topic:
    name: str
    type: str
    channel_id: int
    schema_id: int
    qos: list[dict]
    type_hash: str
    count: int = 0
    sequence: int = 0
    codec: Codec | None = None


@dataclass
class WriterStats:
    messages: int = 0
    chunks: int = 0
    bytes_written: int = 0
    per_topic: dict[str, int] = field(default_factory=dict)


class BagWriter:
    """Write a rosbag2-compatible MCAP file.

    >>> with BagWriter("run.mcap") as w:
    ...     w.add_topic("/plant/a1", "backlash_monitor_msgs/msg/SignalChunk")
    ...     w.write("/plant/a1", msg, log_time_ns=t)          # encodes (RosMessage/rclpy/dict)
    ...     w.write_raw("/plant/a1", cdr_bytes, log_time_ns=t)  # already serialized (recorder)

    compression: "zstd" (default), "lz4" or "" (none). `fsync=True` also fsyncs each chunk.
    `exclusive=True` refuses (FileExistsError) to open a path that exists already.
    """

    def __init__(self, path, *, compression: str = "zstd", compression_level: int = 1,
                 chunk_size: int = DEFAULT_CHUNK_SIZE,
                 chunk_duration_s: float | None = DEFAULT_CHUNK_DURATION_S,
                 ros_distro: str = "jazzy", fsync: bool = False, custom_data: dict | None = None,
                 exclusive: bool = False):
        if compression not in ("zstd", "lz4", ""):
            raise ValueError(f"compression must be 'zstd', 'lz4' or '' (none), not {compression!r}")
        if chunk_size <= 0:
            raise ValueError(f"chunk_size must be > 0 bytes, not {chunk_size}")
        self.path = Path(path)
        self.compression = compression
        self.chunk_size = int(chunk_size)
        self.chunk_duration_ns = (None if not chunk_duration_s
                                  else int(round(chunk_duration_s * 1e9)))
        self.ros_distro = ros_distro
        self.fsync = fsync
        self.custom_data = dict(custom_data or {})
        if compression == "zstd":
            self._compress = zstandard.ZstdCompressor(level=compression_level).compress
        elif compression == "lz4":
            self._compress = lz4.frame.compress
        else:
            self._compress = None
        self._lock = threading.RLock()
        self._topics: dict[str, _Topic] = {}
        self._schemas: dict[str, tuple[int, str, bytes]] = {}  # type -> (id, encoding, data)
        self._schema_records: list[bytes] = []
        self._channel_records: list[bytes] = []
        self._chunk_indexes: list[ChunkIndex] = []
        self._channel_counts: dict[int, int] = {}
        self._start = None
        self._end = None
        self._message_count = 0
        self._reset_chunk()
        self.path.parent.mkdir(parents=True, exist_ok=True)
        # exclusive: fail with FileExistsError instead of replacing an existing file (no race)
        self._f = open(self.path, "xb" if exclusive else "wb")
        self._pos = 0
        self._crc = 0
        self._summary_crc = None
        self._closed = False
        self._write(MAGIC)
        self._write(header_record("ros2", LIBRARY))
        # the chunk limits, first in the file: a reader of a killed writer's file can say how much
        # the lost open chunk held at most (the summary, written at close, is missing then)
        self._writer_meta = (self._pos, metadata_record(WRITER_METADATA, {
            "chunk_duration_s": "" if self.chunk_duration_ns is None else repr(chunk_duration_s),
            "chunk_size_bytes": str(self.chunk_size), "compression": compression}))
        self._write(self._writer_meta[1])
        self._f.flush()

    # ------------------------------------------------------------------ context manager
    def __enter__(self) -> "BagWriter":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    @property
    def closed(self) -> bool:
        return self._closed

    @property
    def topics(self) -> dict[str, str]:
        return {t.name: t.type for t in self._topics.values()}

    def stats(self) -> WriterStats:
        return WriterStats(self._message_count, len(self._chunk_indexes), self._pos,
                           {t.name: t.count for t in self._topics.values()})

    # ------------------------------------------------------------------ topics
    def add_topic(self, topic: str, type_name: str, *, qos_profiles: list[dict] | None = None,
                  definition: str | None = None, type_hash: str | None = None,
                  serialization_format: str = "cdr") -> int:
        """Declare a topic; returns its channel id. Idempotent for the same topic and type.

        definition: the concatenated ros2msg text; default: looked up (schema.full_definition).
        qos_profiles: list of dicts (see qos_profile()); default: one rosbag2 default profile.
        type_hash: RIHS01_...; default: from the installed type's rosidl JSON ("" if unknown).
        """
        with self._lock:
            self._check_open()
            type_name = schema_mod.normalize_type_name(type_name)
            if topic in self._topics:
                t = self._topics[topic]
                if t.type != type_name:
                    raise BagError(f"topic {topic!r} already added with type {t.type}, not {type_name}")
                return t.channel_id
            if type_name not in self._schemas:
                text = definition if definition is not None else schema_mod.full_definition(type_name)
                sid = len(self._schemas) + 1
                data = text.encode("utf-8")
                self._schemas[type_name] = (sid, "ros2msg", data)
                rec = schema_record(sid, type_name, "ros2msg", data)
                self._schema_records.append(rec)
                self._write(rec)
            sid = self._schemas[type_name][0]
            cid = len(self._topics) + 1
            qos = list(qos_profiles) if qos_profiles is not None else [qos_profile()]
            th = type_hash if type_hash is not None else schema_mod.type_hash(type_name)
            meta = {"offered_qos_profiles": yaml_dump(qos) if qos else "",
                    "topic_type_hash": th}
            rec = channel_record(cid, sid, topic, serialization_format, meta)
            self._channel_records.append(rec)
            self._write(rec)
            self._f.flush()
            self._topics[topic] = _Topic(topic, type_name, cid, sid, qos, th)
            self._channel_counts[cid] = 0
            return cid

    def codec(self, topic: str) -> Codec:
        t = self._topic(topic)
        if t.codec is None:
            sid, enc, data = self._schemas[t.type]
            t.codec = Codec.from_schema(t.type, data.decode("utf-8"), enc)
        return t.codec

    def _topic(self, topic: str) -> _Topic:
        try:
            return self._topics[topic]
        except KeyError:
            raise MissingTopicError(topic, self._topics) from None

    # ------------------------------------------------------------------ messages
    def write(self, topic: str, msg, log_time_ns: int | None = None,
              publish_time_ns: int | None = None, sequence: int | None = None) -> None:
        """Encode `msg` (RosMessage, rclpy message, dict) as CDR and write it."""
        self.write_raw(topic, self.codec(topic).encode(msg), log_time_ns, publish_time_ns, sequence)

    def write_raw(self, topic: str, data, log_time_ns: int | None = None,
                  publish_time_ns: int | None = None, sequence: int | None = None) -> None:
        """Write an already CDR-serialized message. log_time defaults to now (system clock)."""
        if log_time_ns is None:
            log_time_ns = time.time_ns()
        if publish_time_ns is None:
            publish_time_ns = log_time_ns
        with self._lock:
            self._check_open()
            t = self._topic(topic)
            if sequence is None:
                sequence = t.sequence
                t.sequence = (t.sequence + 1) & 0xFFFFFFFF
            cid = t.channel_id
            buf = self._chunk
            offset = len(buf)
            body_len = MESSAGE_HEAD.size + len(data)
            buf += RECORD_HEADER.pack(OP_MESSAGE, body_len)
            buf += MESSAGE_HEAD.pack(cid, sequence, log_time_ns, publish_time_ns)
            buf += data
            idx = self._chunk_msgs.get(cid)
            if idx is None:
                idx = self._chunk_msgs[cid] = []
            idx.append(log_time_ns)
            idx.append(offset)
            if self._chunk_start is None or log_time_ns < self._chunk_start:
                self._chunk_start = log_time_ns
            if self._chunk_end is None or log_time_ns > self._chunk_end:
                self._chunk_end = log_time_ns
            t.count += 1
            self._channel_counts[cid] += 1
            self._message_count += 1
            if self._start is None or log_time_ns < self._start:
                self._start = log_time_ns
            if self._end is None or log_time_ns > self._end:
                self._end = log_time_ns
            if len(buf) >= self.chunk_size or (
                    self.chunk_duration_ns is not None
                    and self._chunk_end - self._chunk_start >= self.chunk_duration_ns):
                self._close_chunk()

    def flush(self) -> None:
        """Close the open chunk (if any) and hand it to the OS: it survives a SIGKILL from now on."""
        with self._lock:
            if not self._closed:
                self._close_chunk()

    @property
    def pending_bytes(self) -> int:
        """Uncompressed bytes in the open chunk (lost if the process is killed now)."""
        return len(self._chunk)

    # ------------------------------------------------------------------ internals
    def _check_open(self) -> None:
        if self._closed:
            raise BagError(f"bag {self.path} is closed")

    def _write(self, b: bytes) -> None:
        self._f.write(b)
        self._pos += len(b)
        self._crc = crc32(b, self._crc)
        if self._summary_crc is not None:
            self._summary_crc = crc32(b, self._summary_crc)

    def _reset_chunk(self) -> None:
        self._chunk = bytearray()
        self._chunk_msgs: dict[int, list[int]] = {}
        self._chunk_start = None
        self._chunk_end = None

    def _close_chunk(self) -> None:
        if not self._chunk_msgs:
            return
        data = bytes(self._chunk)
        crc = crc32(data)
        comp = self._compress(data) if self._compress else data
        chunk_offset = self._pos
        self._write(chunk_record_head(self._chunk_start, self._chunk_end, len(data), crc,
                                      self.compression, len(comp)))
        self._write(comp)
        chunk_length = self._pos - chunk_offset
        index_offsets = {}
        index_start = self._pos
        for cid in sorted(self._chunk_msgs):
            entries = self._chunk_msgs[cid]
            index_offsets[cid] = self._pos
            self._write(message_index_record(cid, _pack_u64s(entries)))
        self._chunk_indexes.append(ChunkIndex(
            self._chunk_start, self._chunk_end, chunk_offset, chunk_length, index_offsets,
            self._pos - index_start, self.compression, len(comp), len(data)))
        self._f.flush()
        if self.fsync:
            os.fsync(self._f.fileno())
        self._reset_chunk()

    def _bag_metadata(self) -> dict:
        start = self._start or 0
        duration = (self._end - self._start) if self._start is not None else 0
        # the name it will have: outputs are written as NAME.partial and renamed when complete
        rel = self.path.name.removesuffix(".partial")
        topics = []
        for t in self._topics.values():
            topics.append({
                "topic_metadata": {
                    "name": t.name, "type": t.type, "serialization_format": "cdr",
                    "offered_qos_profiles": t.qos, "type_description_hash": t.type_hash},
                "message_count": t.count})
        return {
            "version": ROSBAG2_METADATA_VERSION,
            "storage_identifier": "mcap",
            "duration": {"nanoseconds": duration},
            "starting_time": {"nanoseconds_since_epoch": start},
            "message_count": self._message_count,
            "topics_with_message_count": topics,
            "compression_format": "",
            "compression_mode": "",
            "relative_file_paths": [rel],
            "files": [{"path": rel, "starting_time": {"nanoseconds_since_epoch": start},
                       "duration": {"nanoseconds": duration},
                       "message_count": self._message_count}],
            "custom_data": dict(self.custom_data),
            "ros_distro": self.ros_distro,
        }

    def serialized_metadata(self) -> str:
        """The BagMetadata YAML (rosbag2 version 9) as written into the `rosbag2` metadata record."""
        return yaml_dump(self._bag_metadata())

    def close(self) -> None:
        """Write the last chunk, the `rosbag2` metadata record, the summary and the footer."""
        with self._lock:
            if self._closed:
                return
            try:
                self._close_chunk()
                meta_offset = self._pos
                meta_rec = metadata_record("rosbag2",
                                           {"serialized_metadata": self.serialized_metadata()})
                self._write(meta_rec)
                meta_length = self._pos - meta_offset
                self._write(data_end_record(self._crc))
                summary_start = self._pos
                self._summary_crc = 0
                groups = []

                def group(op: int, recs: list[bytes]) -> None:
                    if not recs:
                        return
                    start = self._pos
                    for r in recs:
                        self._write(r)
                    groups.append((op, start, self._pos - start))

                group(OP_SCHEMA, self._schema_records)
                group(OP_CHANNEL, self._channel_records)
                group(OP_STATISTICS, [statistics_record(Statistics(
                    self._message_count, len(self._schemas), len(self._topics), 0, 2,
                    len(self._chunk_indexes), self._start or 0, self._end or 0,
                    self._channel_counts))])
                group(OP_CHUNK_INDEX, [chunk_index_record(ci) for ci in self._chunk_indexes])
                writer_offset, writer_rec = self._writer_meta
                group(OP_METADATA_INDEX, [
                    metadata_index_record(MetadataIndex(writer_offset, len(writer_rec),
                                                        WRITER_METADATA)),
                    metadata_index_record(MetadataIndex(meta_offset, meta_length, "rosbag2"))])
                summary_offset_start = self._pos
                for op, start, length in groups:
                    self._write(summary_offset_record(op, start, length))
                head = footer_head(summary_start, summary_offset_start)
                # summary CRC: from summary_start through the footer up to the crc field
                summary_crc = crc32(head, self._summary_crc)
                self._write(head + U32.pack(summary_crc))
                self._write(MAGIC)
                self._f.flush()
                if self.fsync:
                    os.fsync(self._f.fileno())
            finally:
                self._closed = True
                self._f.close()


def _pack_u64s(values: list[int]) -> bytes:
    a = array.array("Q", values)
    if a.itemsize != 8:  # pragma: no cover - all supported platforms have 8-byte Q
        return struct.pack(f"<{len(values)}Q", *values)
    if not _LITTLE:  # pragma: no cover
        a.byteswap()
    return a.tobytes()


_LITTLE = __import__("sys").byteorder == "little"
