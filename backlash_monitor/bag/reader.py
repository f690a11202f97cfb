"""BagReader: reads rosbag2 MCAP files (ours, `ros2 bag record`'s, rosbags'), decoding CDR to numpy.

>>> with BagReader("run.mcap") as bag:
...     bag.topics["/plant/a1"].count
...     for m in bag.messages(["/plant/a1"]):
...         m.topic, m.log_time_ns, m.message.samples      # numpy float64 array
...     series = bag.read_signal("/plant/a1")               # all samples concatenated, gaps listed

A file without a valid footer/summary (the recorder was killed, the disk filled) raises
TruncatedBagError unless opened with `recover=True`: then the data section is scanned from the start
and every complete, CRC-valid chunk is read; `bag.recovery` reports what was intact and what was
lost (the bytes after the last complete record: at most the chunk that was being written).
"""
from __future__ import annotations

import mmap
import os
import threading
from collections import deque
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import NamedTuple

import numpy as np

from .cdr import Codec, RosMessage
from .errors import (BagError, CorruptBagError, MissingTopicError, NotABagError,
                     TruncatedBagError, UnknownSchemaError)
from .mcap_format import (CHUNK_HEAD, FOOTER_BODY, FOOTER_RECORD_LEN, MAGIC, MESSAGE_HEAD,
                          OP_CHANNEL, OP_CHUNK, OP_CHUNK_INDEX, OP_DATA_END, OP_FOOTER, OP_HEADER,
                          OP_MESSAGE, OP_METADATA, OP_METADATA_INDEX, OP_SCHEMA, OP_STATISTICS,
                          OP_SUMMARY_OFFSET, RECORD_HEADER, Cursor, crc32)

_MAX_OPCODE = 0x0F


@dataclass
class TopicInfo:
    name: str
    type: str
    count: int
    channel_id: int
    message_encoding: str
    schema_encoding: str
    schema_text: str
    offered_qos_profiles: str = ""   # YAML text, as in the channel metadata
    type_hash: str = ""


@dataclass
class BagMessage:
    topic: str
    log_time_ns: int
    publish_time_ns: int
    sequence: int
    data: bytes                      # the CDR payload
    message: RosMessage | None = None  # decoded (None with decode=False)


class Stamp(NamedTuple):
    """A header stamp (builtin_interfaces/Time's fields)."""
    sec: int
    nanosec: int


class SignalChunkRecord(NamedTuple):
    """One SignalChunk message as ``BagReader.signal_chunks`` yields it (no message objects)."""
    topic: str
    log_time_ns: int
    first_sample_index: int
    sample_period_s: float
    samples: np.ndarray              # float64 (read-only view of a decompressed chunk, or a copy)
    stamp: Stamp                     # header.stamp
    frame_id: str                    # header.frame_id
    signal_name: str
    unit: str


@dataclass
class RecoveryReport:
    complete: bool                   # footer and summary present and valid
    file_size: int
    intact_bytes: int                # bytes up to the end of the last complete record
    complete_chunks: int
    corrupt_chunks: int = 0          # complete by length but failing CRC / decompression
    messages: int = 0
    reason: str = ""

    @property
    def lost_bytes(self) -> int:
        return self.file_size - self.intact_bytes

    def describe(self) -> str:
        if self.complete:
            return "complete (footer, summary and statistics present)"
        return (f"INCOMPLETE: {self.reason}; {self.complete_chunks} complete chunk(s) with "
                f"{self.messages} message(s) recovered from the first {self.intact_bytes} of "
                f"{self.file_size} bytes; {self.lost_bytes} trailing byte(s) lost"
                + (f"; {self.corrupt_chunks} corrupt chunk(s) skipped" if self.corrupt_chunks else ""))


@dataclass
class SignalSeries:
    """All samples of one SignalChunk topic, concatenated in stream order."""
    topic: str
    signal_name: str
    unit: str
    sample_period_s: float
    samples: np.ndarray              # float64
    sample_index: np.ndarray         # uint64 stream index of every sample
    chunk_first_index: np.ndarray    # first_sample_index of each chunk
    chunk_log_time_ns: np.ndarray
    frame_id: str = ""
    gaps: list[tuple[int, int]] = field(default_factory=list)  # (expected index, got index)


@dataclass
class _Chunk:
    offset: int
    start: int
    end: int
    channels: frozenset | None       # from the chunk index (None: unknown)


class BagReader:
    def __init__(self, path, *, recover: bool = False):
        self.path = Path(path)
        self.recover = recover
        if not self.path.exists():
            raise FileNotFoundError(f"bag file {str(self.path)!r} does not exist")
        if self.path.is_dir():
            found = sorted(self.path.glob("*.mcap"))
            if len(found) != 1:
                raise NotABagError(f"{self.path} is a directory with {len(found)} .mcap files; "
                                   "give the .mcap file")
            self.path = found[0]
        self._f = open(self.path, "rb")
        self.file_size = os.fstat(self._f.fileno()).st_size
        self._mm = (mmap.mmap(self._f.fileno(), 0, access=mmap.ACCESS_READ)
                    if self.file_size else b"")
        self._buf = memoryview(self._mm) if self.file_size else memoryview(b"")
        self.schemas: dict[int, tuple[str, str, str]] = {}   # id -> (name, encoding, text)
        self.channels: dict[int, tuple[str, int, str, dict]] = {}  # id -> (topic, sid, enc, meta)
        self.metadata: dict[str, dict[str, str]] = {}
        self.profile = ""
        self.library = ""
        self._chunks: dict[int, _Chunk] = {}
        self._counts: dict[int, int] = {}
        self._start = self._end = None
        self._message_count = 0
        self._codecs: dict[int, Codec] = {}
        self._data_start = 0
        self._data_end = self.file_size
        self._have_stats = False
        self._corrupt: set[int] = set()
        self._last_chunk = None          # (offset, records) of the last chunk decompressed
        try:
            self._open()
        except BaseException:
            self.close()
            raise

    # ------------------------------------------------------------------ open / close
    def __enter__(self) -> "BagReader":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._last_chunk = None
        buf, self._buf = self._buf, memoryview(b"")
        try:
            buf.release()
        except Exception:  # noqa: BLE001
            pass
        if isinstance(self._mm, mmap.mmap):
            try:
                self._mm.close()
            except BufferError:  # a decoded view still references the map; freed with it
                pass
        self._mm = b""
        if self._f:
            self._f.close()
            self._f = None

    def _open(self) -> None:
        b = self._buf
        head = bytes(b[:8])
        if head != MAGIC:
            if self.file_size < 8 and MAGIC.startswith(head) and head:
                return self._cut_header("inside the MCAP magic")
            raise NotABagError(f"{self.path} is not an MCAP file (bad magic)")
        pos = 8
        if self.file_size < pos + 9:
            return self._cut_header("inside the MCAP header")
        op, length = RECORD_HEADER.unpack_from(b, pos)
        if op != OP_HEADER:
            raise NotABagError(f"{self.path}: MCAP file without a header record")
        if pos + 9 + length > self.file_size:
            return self._cut_header("inside the MCAP header")
        c = Cursor(b[pos + 9:pos + 9 + length])
        self.profile = c.string()
        self.library = c.string()
        if self.profile != "ros2":
            raise NotABagError(f"{self.path} is an MCAP file with profile {self.profile!r}, "
                               "not a ROS 2 bag (profile 'ros2')")
        self._data_start = pos + 9 + length
        reason = self._read_summary()
        if reason is None:
            self.recovery = RecoveryReport(True, self.file_size, self.file_size,
                                           len(self._chunks), 0, self._message_count)
            return
        # no usable summary: scan the data section
        report = self._scan(reason)
        self.recovery = report
        if not self.recover:
            raise TruncatedBagError(
                f"{self.path} is incomplete ({reason}): the recorder did not close it. "
                f"{report.complete_chunks} complete chunk(s) with {report.messages} message(s) "
                f"are intact in the first {report.intact_bytes} of {report.file_size} bytes; "
                "read them with recovery (BagReader(path, recover=True), "
                "`bag-info --recover`)",
                path=str(self.path), file_size=self.file_size, intact_bytes=report.intact_bytes,
                complete_chunks=report.complete_chunks)

    def _cut_header(self, where: str) -> None:
        self.recovery = RecoveryReport(False, self.file_size, 0, 0,
                                       reason=f"file of {self.file_size} bytes ends {where}")
        if not self.recover:
            raise TruncatedBagError(f"{self.path} is truncated: {self.recovery.reason}; "
                                    "nothing in it is readable", path=str(self.path),
                                    file_size=self.file_size)
        self._data_end = 0

    def _read_summary(self) -> str | None:
        """Parse footer + summary. Returns None when fine, else the reason it is unusable."""
        b = self._buf
        n = self.file_size
        if n < self._data_start + FOOTER_RECORD_LEN + 8 or bytes(b[n - 8:]) != MAGIC:
            return "no footer (file ends without the closing MCAP magic)"
        fpos = n - 8 - FOOTER_RECORD_LEN
        op, length = RECORD_HEADER.unpack_from(b, fpos)
        if op != OP_FOOTER or length != FOOTER_BODY.size:
            return "invalid footer record"
        summary_start, summary_offset_start, _crc = FOOTER_BODY.unpack_from(b, fpos + 9)
        if summary_start == 0:
            return "footer without summary section"
        if not self._data_start <= summary_start <= fpos:
            return "footer points outside the file"
        self._data_end = summary_start
        end = summary_offset_start or fpos
        pos = summary_start
        try:
            while pos < end:
                op, length = RECORD_HEADER.unpack_from(b, pos)
                body = b[pos + 9:pos + 9 + length]
                if pos + 9 + length > end:
                    return "summary record runs past the summary section"
                self._summary_record(op, body)
                pos += 9 + length
        except (ValueError, UnicodeDecodeError) as exc:
            return f"unreadable summary section ({exc})"
        if not self._have_stats:
            # a valid file whose writer left out the statistics: count by scanning the data
            report = self._scan("", self._data_end)
            if report.reason:
                return f"data section damaged ({report.reason})"
        return None

    def _summary_record(self, op: int, body) -> None:
        c = Cursor(body)
        if op == OP_SCHEMA:
            self._schema(c)
        elif op == OP_CHANNEL:
            self._channel(c)
        elif op == OP_STATISTICS:
            self._have_stats = True
            self._message_count = c.u64()
            c.u16(); c.u32(); c.u32(); c.u32(); c.u32()  # noqa: E702 - counts we recompute
            self._start = c.u64()
            self._end = c.u64()
            end = c.pos + c.u32()
            while c.pos < end:
                cid = c.u16()
                self._counts[cid] = c.u64()
        elif op == OP_CHUNK_INDEX:
            start, end_t, offset, _length = c.u64(), c.u64(), c.u64(), c.u64()
            mend = c.pos + c.u32()
            chans = set()
            while c.pos < mend:
                chans.add(c.u16())
                c.u64()
            self._chunks[offset] = _Chunk(offset, start, end_t, frozenset(chans) if chans else None)
        elif op == OP_METADATA_INDEX:
            offset, length = c.u64(), c.u64()
            name = c.string()
            if offset + length <= self.file_size:
                rop, rlen = RECORD_HEADER.unpack_from(self._buf, offset)
                if rop == OP_METADATA:
                    mc = Cursor(self._buf[offset + 9:offset + 9 + rlen])
                    mname = mc.string()
                    self.metadata[mname or name] = mc.map_str()

    def _schema(self, c: Cursor) -> None:
        sid = c.u16()
        name = c.string()
        enc = c.string()
        data = c.bytes_()
        self.schemas[sid] = (name, enc, data.decode("utf-8", errors="replace"))

    def _channel(self, c: Cursor) -> None:
        cid = c.u16()
        sid = c.u16()
        topic = c.string()
        enc = c.string()
        meta = c.map_str()
        self.channels[cid] = (topic, sid, enc, meta)

    # ------------------------------------------------------------------ scanning
    def _iter_records(self, start: int, end: int, report: RecoveryReport | None = None):
        """Yield (op, offset, body_view) of the records in [start, end); stop at a cut record."""
        b = self._buf
        pos = start
        while pos < end:
            if pos + 9 > end:
                if report is not None:
                    report.reason = report.reason or f"record header cut off at byte {pos}"
                return
            op, length = RECORD_HEADER.unpack_from(b, pos)
            if op == 0 or op > 0x7F or pos + 9 + length > end:
                if report is not None:
                    report.reason = report.reason or (
                        f"record at byte {pos} (opcode 0x{op:02x}, {length} bytes) is cut off "
                        "by the end of the file" if op and op <= 0x7F else
                        f"garbage record at byte {pos}")
                return
            yield op, pos, b[pos + 9:pos + 9 + length]
            pos += 9 + length
            if report is not None:
                report.intact_bytes = pos
            if op in (OP_DATA_END, OP_FOOTER):
                return

    def _scan(self, reason: str, data_end: int | None = None) -> RecoveryReport:
        report = RecoveryReport(False, self.file_size, self._data_start, 0, reason=reason)
        chunk_index = dict(self._chunks)
        self._chunks.clear()
        self._counts.clear()
        self._message_count = 0
        self._start = self._end = None
        self._corrupt.clear()
        data_end = self.file_size if data_end is None else data_end
        for op, pos, body in self._iter_records(self._data_start, data_end, report):
            c = Cursor(body)
            try:
                if op == OP_SCHEMA:
                    self._schema(c)
                elif op == OP_CHANNEL:
                    self._channel(c)
                elif op == OP_METADATA:
                    name = c.string()
                    self.metadata[name] = c.map_str()
                elif op == OP_MESSAGE:
                    self._count_message(body)
                elif op == OP_CHUNK:
                    try:
                        records = self._decompress(body)
                    except CorruptBagError:
                        report.corrupt_chunks += 1
                        self._corrupt.add(pos)
                        continue
                    start, end_t = CHUNK_HEAD.unpack_from(body, 0)[:2]
                    chans = set()
                    for rop, _rpos, rbody in _iter_plain(records):
                        if rop == OP_MESSAGE:
                            chans.add(self._count_message(rbody))
                        elif rop == OP_SCHEMA:
                            self._schema(Cursor(rbody))
                        elif rop == OP_CHANNEL:
                            self._channel(Cursor(rbody))
                    self._chunks[pos] = chunk_index.get(pos) or _Chunk(pos, start, end_t,
                                                                       frozenset(chans))
                    report.complete_chunks += 1
            except (ValueError, UnicodeDecodeError):
                report.reason += f"; malformed record at byte {pos}"
                break
        self._data_end = report.intact_bytes
        report.messages = self._message_count
        return report

    def _count_message(self, body) -> int:
        cid, _seq, log_time, _pub = MESSAGE_HEAD.unpack_from(body, 0)
        self._counts[cid] = self._counts.get(cid, 0) + 1
        self._message_count += 1
        if self._start is None or log_time < self._start:
            self._start = log_time
        if self._end is None or log_time > self._end:
            self._end = log_time
        return cid

    def _chunk_records(self, chunk) -> memoryview:
        """The records of the chunk (offset, body): decompressed, or the last chunk again (a
        second pass over another topic, e.g. analyze's latched true width then the signals,
        starts where the first ended)."""
        pos, body = chunk
        last = self._last_chunk
        if last is not None and last[0] == pos:
            return last[1]
        records = self._decompress(body)
        self._last_chunk = (pos, records)
        return records

    def _decompress(self, body) -> memoryview:
        start, end_t, usize, ucrc = CHUNK_HEAD.unpack_from(body, 0)
        c = Cursor(body, CHUNK_HEAD.size)
        comp = c.string()
        n = c.u64()
        if c.pos + n > len(body):
            raise CorruptBagError("chunk records run past the chunk")
        data = body[c.pos:c.pos + n]
        try:
            if comp == "":
                out = data
            elif comp == "zstd":
                out = _zstd_decompressor().decompress(data, max_output_size=usize)
            elif comp == "lz4":
                import lz4.frame

                out = lz4.frame.decompress(bytes(data))
            else:
                raise CorruptBagError(f"chunk compression {comp!r} is not supported")
        except CorruptBagError:
            raise
        except Exception as exc:  # noqa: BLE001 - zstd/lz4 errors
            raise CorruptBagError(f"chunk does not decompress: {exc}") from None
        if len(out) != usize:
            raise CorruptBagError(f"chunk decompresses to {len(out)} bytes, header says {usize}")
        if ucrc:
            if crc32(out) != ucrc:
                raise CorruptBagError("chunk CRC mismatch")
        return memoryview(out)

    # ------------------------------------------------------------------ info
    @property
    def message_count(self) -> int:
        return self._message_count

    @property
    def start_ns(self) -> int | None:
        return self._start

    @property
    def end_ns(self) -> int | None:
        return self._end

    @property
    def duration_ns(self) -> int:
        return (self._end - self._start) if self._start is not None else 0

    @property
    def topics(self) -> dict[str, TopicInfo]:
        out = {}
        for cid, (topic, sid, enc, meta) in sorted(self.channels.items()):
            sname, senc, stext = self.schemas.get(sid, ("", "", ""))
            out[topic] = TopicInfo(topic, sname, self._counts.get(cid, 0), cid, enc, senc, stext,
                                   meta.get("offered_qos_profiles", ""),
                                   meta.get("topic_type_hash", ""))
        return out

    @property
    def rosbag2_metadata(self) -> dict | None:
        """The `rosbag2` metadata record's BagMetadata (parsed YAML), if present."""
        text = self.metadata.get("rosbag2", {}).get("serialized_metadata")
        if not text:
            return None
        import yaml

        return yaml.safe_load(text)

    def codec(self, topic: str) -> Codec:
        """The decoder of a topic (built from the schema stored in the bag)."""
        info = self.topics.get(topic)
        if info is None:
            raise MissingTopicError(topic, self.topics)
        codec = self._codecs.get(info.channel_id)
        if codec is None:
            if info.message_encoding != "cdr":
                raise UnknownSchemaError(f"topic {topic!r} has message encoding "
                                         f"{info.message_encoding!r}; only 'cdr' is supported")
            if not info.type:
                raise UnknownSchemaError(f"topic {topic!r} has no schema in the bag")
            try:
                codec = Codec.from_schema(info.type, info.schema_text, info.schema_encoding)
            except UnknownSchemaError as exc:
                raise UnknownSchemaError(f"topic {topic!r} ({info.type}): {exc}") from None
            self._codecs[info.channel_id] = codec
        return codec

    # ------------------------------------------------------------------ messages
    def _channel_ids(self, topics: Iterable[str] | str | None) -> set[int]:
        if isinstance(topics, str):
            topics = [topics]
        by_topic = {t.name: t.channel_id for t in self.topics.values()}
        if topics is None:
            return set(self.channels)
        wanted = set()
        for t in topics:
            if t not in by_topic:
                raise MissingTopicError(t, by_topic)
            wanted.add(by_topic[t])
        return wanted

    def messages(self, topics: Iterable[str] | str | None = None, *, decode: bool = True,
                 start_ns: int | None = None, end_ns: int | None = None) -> Iterator[BagMessage]:
        """Messages in file order (= receive order for our recorder), optionally filtered."""
        wanted = self._channel_ids(topics)
        codecs = {}
        if decode:
            for cid in wanted:
                codecs[cid] = self.codec(self.channels[cid][0])
        names = {cid: self.channels[cid][0] for cid in self.channels}
        for cid, seq, log_time, pub, body in self._wanted_messages(wanted, start_ns, end_ns):
            data = bytes(body[MESSAGE_HEAD.size:])
            codec = codecs.get(cid)
            yield BagMessage(names[cid], log_time, pub, seq, data,
                             codec.decode(data) if codec is not None else None)

    def signal_chunks(self, topics: Iterable[str] | str) -> Iterator[SignalChunkRecord]:
        """The SignalChunk messages of ``topics`` in file order, as flat :class:`SignalChunkRecord`
        tuples: the fields ``messages`` decodes (the same values), without building message
        objects -- the offline analysis reads its millions of samples this way. ``samples`` of a
        message in a compressed chunk is a read-only view of the decompressed chunk (no
        allocation per message: fresh memory costs a page fault per 4 KiB); elsewhere (an
        uncompressed chunk, a message outside chunks: views of the file's map) it is a copy.
        A payload the SignalChunk fast path does not take (big endian) goes through the generic
        decoder; a malformed one raises its CdrError."""
        wanted = self._channel_ids(topics)
        infos = {t.channel_id: t for t in self.topics.values()}
        codecs = {}
        for cid in wanted:
            if not infos[cid].type.endswith("/SignalChunk"):
                raise BagError(f"topic {infos[cid].name!r} has type {infos[cid].type}, "
                               "not SignalChunk")
            codecs[cid] = self.codec(infos[cid].name)
        names = {cid: self.channels[cid][0] for cid in self.channels}
        # per topic: (fast field parser or None, its last string section)
        fast = {cid: (codecs[cid].signal_chunk_fields if codecs[cid].is_signal_chunk else None,
                      [None]) for cid in wanted}
        head = MESSAGE_HEAD.size
        for cid, _seq, log_time, _pub, body in self._wanted_messages(wanted, None, None):
            parse, strings = fast[cid]
            fields = None
            if parse is not None:
                try:
                    fields = parse(body[head:], copy=type(body.obj) is not bytes, strings=strings)
                except Exception:  # noqa: BLE001 - malformed: the generic decoder names it
                    fields = None
            if fields is None:
                codec = codecs[cid]
                msg = codec.decode(bytes(body[head:]))
                stamp = msg.header.stamp
                fields = (stamp.sec, stamp.nanosec, msg.header.frame_id, msg.signal_name,
                          msg.unit, msg.sample_period_s, msg.first_sample_index, msg.samples)
            sec, nanosec, frame_id, signal_name, unit, period, first, samples = fields
            yield SignalChunkRecord(names[cid], log_time, first, period, samples,
                                    Stamp(sec, nanosec), frame_id, signal_name, unit)

    def _wanted_messages(self, wanted: set[int], start_ns: int | None, end_ns: int | None):
        """(channel_id, sequence, log_time_ns, publish_time_ns, record body) of the messages on
        the ``wanted`` channels (log time within the range), in file order. Chunks are
        decompressed ahead in a worker thread (``_prefetch``)."""
        records = []   # (op, offset, body) of the records to read, in file order
        for op, pos, body in self._iter_records(self._data_start, self._data_end):
            if op == OP_CHUNK:
                if pos in self._corrupt:
                    continue
                info = self._chunks.get(pos)
                if info is not None:
                    if info.channels is not None and not (info.channels & wanted):
                        continue
                    if (start_ns is not None and info.end < start_ns) or (
                            end_ns is not None and info.start > end_ns):
                        continue
                elif self.recover and not self.recovery.complete:
                    continue  # not validated by the scan
                records.append((op, pos, body))
            elif op == OP_MESSAGE:
                records.append((op, pos, body))
        chunks = [(pos, body) for op, pos, body in records if op == OP_CHUNK]
        decompressed = _prefetch(self._chunk_records, chunks, CHUNKS_AHEAD)
        unpack = MESSAGE_HEAD.unpack_from
        try:
            for op, _pos, body in records:
                if op == OP_CHUNK:
                    try:
                        chunk_records = next(decompressed)()
                    except CorruptBagError:
                        if self.recover:
                            continue
                        raise
                    bodies = _message_bodies(chunk_records)
                else:
                    bodies = (body,)
                for rbody in bodies:
                    cid, seq, log_time, pub = unpack(rbody, 0)
                    if cid not in wanted:
                        continue
                    if (start_ns is not None and log_time < start_ns) or (
                            end_ns is not None and log_time > end_ns):
                        continue
                    yield cid, seq, log_time, pub, rbody
        finally:
            decompressed.close()   # waits for a chunk still being decompressed (the map stays valid)

    def read_signal(self, topic: str) -> SignalSeries:
        """Concatenate a SignalChunk topic. Chunks are ordered by first_sample_index; a missing
        or overlapping range is listed in `gaps` (and the samples simply follow each other)."""
        return self.read_signals([topic])[topic]

    def read_signals(self, topics: Iterable[str] | None = None) -> dict[str, SignalSeries]:
        """read_signal for several SignalChunk topics in one pass over the file (default: all)."""
        infos = self.topics
        if topics is None:
            topics = [t for t, i in infos.items() if i.type.endswith("/SignalChunk")]
        topics = list(topics)
        for topic in topics:
            info = infos.get(topic)
            if info is None:
                raise MissingTopicError(topic, infos)
            if not info.type.endswith("/SignalChunk"):
                raise BagError(f"topic {topic!r} has type {info.type}, not SignalChunk")
        per: dict[str, list] = {t: [] for t in topics}
        if topics:
            for m in self.messages(topics):
                per[m.topic].append((m.message, m.log_time_ns))
        return {t: _series(t, msgs) for t, msgs in per.items()}


def _series(topic: str, msgs: list) -> SignalSeries:
    msgs.sort(key=lambda x: x[0].first_sample_index)
    if not msgs:
        return SignalSeries(topic, "", "", float("nan"), np.zeros(0), np.zeros(0, np.uint64),
                            np.zeros(0, np.uint64), np.zeros(0, np.int64))
    first = msgs[0][0]
    samples = np.concatenate([m.samples for m, _ in msgs])
    starts = np.array([m.first_sample_index for m, _ in msgs], dtype=np.uint64)
    lengths = np.array([len(m.samples) for m, _ in msgs], dtype=np.int64)
    offsets = np.concatenate(([0], np.cumsum(lengths)[:-1])).astype(np.uint64)
    idx = (np.repeat(starts - offsets, lengths)
           + np.arange(samples.size, dtype=np.uint64)) if samples.size else np.zeros(0, np.uint64)
    ends = starts + lengths.astype(np.uint64)
    bad = np.nonzero(starts[1:] != ends[:-1])[0]
    gaps = [(int(ends[k]), int(starts[k + 1])) for k in bad]
    if starts[0] != first.first_sample_index:  # pragma: no cover - sorted above
        gaps.insert(0, (int(first.first_sample_index), int(starts[0])))
    return SignalSeries(topic, first.signal_name, first.unit, first.sample_period_s, samples, idx,
                        starts, np.array([t for _, t in msgs], dtype=np.int64),
                        first.header.frame_id, gaps)


CHUNKS_AHEAD = 6   # chunks decompressed ahead of the one being read (~6 MiB at the default chunk size)

_DECOMPRESS_POOL = None
_POOL_LOCK = threading.Lock()
_THREAD_STATE = threading.local()


def _zstd_decompressor():
    """This thread's zstd decompressor (a ZstdDecompressor must not be shared between threads)."""
    d = getattr(_THREAD_STATE, "zstd", None)
    if d is None:
        import zstandard

        d = _THREAD_STATE.zstd = zstandard.ZstdDecompressor()
    return d


def _decompress_pool():
    """The one worker thread shared by all readers (started on first use)."""
    global _DECOMPRESS_POOL
    with _POOL_LOCK:
        if _DECOMPRESS_POOL is None:
            from concurrent.futures import ThreadPoolExecutor

            _DECOMPRESS_POOL = ThreadPoolExecutor(max_workers=1,
                                                  thread_name_prefix="bag-decompress")
    return _DECOMPRESS_POOL


def _prefetch(fn, items, ahead: int):
    """Yields, for each item in order, a callable returning ``fn(item)`` (or raising its error).

    ``fn`` runs in a worker thread up to ``ahead`` items before the one being consumed: zstd/lz4
    decompression and the CRC release the GIL (or are short), so on a second core a chunk is decompressed
    and checked while the caller decodes and processes the messages of the previous one. Same
    results and errors as calling ``fn`` item by item. ``close()`` (or exhausting it) waits for
    the work still running: the items (views of the reader's map) are not used after that."""
    pending = deque()
    try:
        for item in items:
            pending.append(_decompress_pool().submit(fn, item))
            if len(pending) > ahead:
                yield pending.popleft().result
        while pending:
            yield pending.popleft().result
    finally:
        for future in pending:
            future.cancel()
        for future in pending:
            if not future.cancelled():
                try:
                    future.result()
                except Exception:  # noqa: BLE001 - its chunk is not read any more
                    pass


def _message_bodies(buf) -> list:
    """Bodies of the Message records inside a decompressed chunk, in order."""
    return [body for op, _pos, body in _iter_plain(buf) if op == OP_MESSAGE]


def _iter_plain(buf):
    """Records inside a decompressed chunk."""
    pos = 0
    n = len(buf)
    while pos + 9 <= n:
        op, length = RECORD_HEADER.unpack_from(buf, pos)
        end = pos + 9 + length
        if end > n:
            raise CorruptBagError(f"record inside a chunk runs past the chunk (at {pos})")
        yield op, pos, buf[pos + 9:end]
        pos = end
