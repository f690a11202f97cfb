"""BagReader: reads rosbag2 MCAP files -- ours, `ros2 bag record`'s with any writer options,
Foxglove's, the `mcap` tools', rosbags' -- decoding CDR to numpy.

>>> with BagReader("run.mcap") as bag:
...     bag.topics["/plant/a1"].count
...     for m in bag.messages(["/plant/a1"]):
...         m.topic, m.log_time_ns, m.message.samples      # numpy float64 array
...     series = bag.read_signal("/plant/a1")               # all samples concatenated, gaps listed

Every valid MCAP layout is read completely: chunked or not (compression none, zstd or lz4); with
or without a summary; schemas and channels repeated in the summary or only in the data section
(unchunked or inside the chunks); with or without message indexes, chunk indexes, statistics and
summary offsets (index.py builds what the reader needs from what the file has). A layout it cannot
read (another chunk compression) is refused with UnsupportedBagError naming it.

A file without its footer (the recorder was killed) or with a damaged summary raises
TruncatedBagError, a file with damaged chunks DamagedBagError, unless opened with ``recover=True``:
then every intact chunk is read (integrity.py; ``bag.recovery`` is the RecoveryReport).

The layers (as the `mcap` package has them): records.py (the records, shared with writer.py),
summary.py (footer and summary), index.py (what the file has), integrity.py (checks, scan,
recovery), prefetch.py (chunks decompressed ahead, as far as each reader says), this module (the
reading), cdr.py (the payloads).
"""
from __future__ import annotations

import mmap
import os
import struct
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field
from itertools import compress
from operator import itemgetter
from pathlib import Path
from typing import NamedTuple

import numpy as np
import yaml

from .cdr import Codec, RosMessage
from .errors import BagError, CorruptBagError, MissingTopicError, NotABagError, TruncatedBagError, \
    UnknownSchemaError
from .index import BagIndex, ChunkInfo, walk_data
from .integrity import DamagedChunk, Integrity, RecoveryReport, raise_for
from .prefetch import ChunkPrefetcher
from .records import (MAGIC, MALFORMED, MESSAGE_HEAD, OP_CHUNK, OP_HEADER, OP_MESSAGE,
                      RECORD_HEADER, WRITER_METADATA, chunk_compression_name, chunk_records, crc32,
                      U64, message_bodies, parse_header)
from .signal_table import gather, signal_chunk_table
from .summary import FooterState, Summary, read_footer, read_summary

__all__ = ["BagMessage", "BagReader", "ChunkInfo", "DamagedChunk", "RecoveryReport",
           "SignalChunkColumns", "SignalChunkRecord", "SignalSeries", "Stamp", "TopicInfo", "WRITER_METADATA"]


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


class SignalChunkColumns(NamedTuple):
    """The SignalChunk messages ``BagReader.signal_chunks(topics, copy=False)`` yields, as columns
    (one entry per message, in file order): what a file without chunks gives at once."""
    topics: tuple[str, ...]          # the topics, in the order of their first message
    topic: np.ndarray                # per message: its topic's index in ``topics`` (int64)
    first_sample_index: np.ndarray   # uint64
    sample_period_s: np.ndarray      # float64
    sec: np.ndarray                  # header.stamp.sec (int64)
    nanosec: np.ndarray              # header.stamp.nanosec (int64)
    samples: list[np.ndarray]        # read-only float64 views of the file's map (or of a chunk)
    texts: tuple[tuple[str, str, str], ...]   # per topic: (frame_id, signal_name, unit), alike for all its messages
    log_time_ns: np.ndarray          # per message: its log time (uint64)

    def records(self) -> list[SignalChunkRecord]:
        """The same messages as the SignalChunkRecords ``signal_chunks(copy=False)`` yields."""
        topics, texts = self.topics, self.texts
        return [SignalChunkRecord(topics[k], log_time, first, period, samples, Stamp(sec, nanosec),
                                  *texts[k])
                for k, log_time, first, period, samples, sec, nanosec in zip(
                    self.topic.tolist(), self.log_time_ns.tolist(),
                    self.first_sample_index.tolist(), self.sample_period_s.tolist(), self.samples,
                    self.sec.tolist(), self.nanosec.tolist())]


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


class BagReader:
    """Open an MCAP file (or a rosbag2 directory holding one .mcap file).

    ``recover``: read the intact part of a damaged or incomplete file instead of raising.
    ``chunks_ahead``: chunks decompressed ahead in a worker thread while the caller works on the
    current one (default: 6 where the process may use two CPUs, else 0 = no thread; a pool with a
    worker per core passes 0). prefetch.py.
    """

    def __init__(self, path, *, recover: bool = False, chunks_ahead: int | None = None):
        self.path = Path(path)
        self._recover = bool(recover)
        if not self.path.exists():
            raise FileNotFoundError(f"bag file {str(self.path)!r} does not exist")
        if self.path.is_dir():
            found = sorted(self.path.glob("*.mcap"))
            if len(found) != 1:
                raise NotABagError(f"{self.path} is a directory with {len(found)} .mcap files; "
                                   "give the .mcap file")
            self.path = found[0]
        self._prefetcher = ChunkPrefetcher(chunks_ahead)
        self._f = open(self.path, "rb")
        self.file_size = os.fstat(self._f.fileno()).st_size
        self._mm = (mmap.mmap(self._f.fileno(), 0, access=mmap.ACCESS_READ)
                    if self.file_size else b"")
        self._buf = memoryview(self._mm) if self.file_size else memoryview(b"")
        self.profile = ""
        self.library = ""
        self._index = BagIndex(data_end=self.file_size)
        self._integrity: Integrity | None = None
        self._codecs: dict[int, Codec] = {}
        self._schema_codecs: dict[tuple, Codec] = {}   # (type, encoding, text) -> its codec
        self._last_chunk = None          # (offset, records) of the last chunk decompressed
        self.recovery: RecoveryReport | None = None
        try:
            self._open()
        except BaseException:
            self.close()
            raise

    @property
    def recover(self) -> bool:
        """Read what is intact in a damaged or incomplete file instead of raising."""
        return self._recover

    @recover.setter
    def recover(self, value: bool) -> None:
        self._recover = bool(value)
        if self._integrity is not None:
            self._integrity.recover = self._recover

    # ------------------------------------------------------------------ open / close
    def __enter__(self) -> "BagReader":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._last_chunk = None
        self._index.layout = []
        buf, self._buf = self._buf, memoryview(b"")
        try:
            buf.release()
        except Exception:  # noqa: BLE001
            pass
        if self._integrity is not None:
            self._integrity.buf = self._integrity.mm = None
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
        try:
            self.profile, self.library = parse_header(b[pos + 9:pos + 9 + length])
        except MALFORMED:
            raise NotABagError(f"{self.path}: MCAP header record is unreadable") from None
        if self.profile != "ros2":
            raise NotABagError(f"{self.path} is an MCAP file with profile {self.profile!r}, "
                               "not a ROS 2 bag (profile 'ros2')")
        idx = self._index
        idx.data_start = pos + 9 + length
        integrity = self._integrity = Integrity(self.path, self._mm, b, self.file_size, idx,
                                                self.recover)
        state = read_footer(b, self.file_size, idx.data_start)
        summary, reason = None, state.problem
        if state.has_summary:
            try:
                summary = read_summary(b, state)
            except ValueError as exc:
                reason = f"unreadable summary section ({exc})"
        if state.footer is None or (state.has_summary and summary is None):
            report = integrity.scan(reason)   # no usable footer or summary: scan the data section
        else:
            report = self._read_complete(state, summary)
        report.origin_ns = idx.start
        report.last_message_ns = idx.end
        report.messages = idx.message_count
        duration = idx.metadata.get(WRITER_METADATA, {}).get("chunk_duration_s", "")
        try:
            report.chunk_duration_s = float(duration) if duration else None
        except ValueError:
            report.chunk_duration_s = None
        self.recovery = report
        if not self.recover:
            raise_for(report, self.path, self.file_size)

    def _read_complete(self, state: FooterState, summary: Summary | None) -> RecoveryReport:
        """A file that ends with its footer (with a summary section or without one: both valid):
        index it from what it has, walking the data section where the summary does not say."""
        b = self._buf
        idx = self._index
        integrity = self._integrity
        idx.data_end = state.footer.summary_start if summary is not None else state.footer_at
        if summary is not None:
            idx.from_summary(summary, b, self.file_size)
        count = idx.statistics is None
        if idx.chunks:   # a chunk index: checked chunk by chunk against it
            report, uncounted = integrity.check_indexed(count=count)
        else:            # none (no summary, or none written): the records' own length fields
            walk = walk_data(b, idx, count=count)
            crc_ok = walk is not None and (not walk.data_crc
                                           or crc32(b[:walk.data_end_at]) == walk.data_crc)
            if not crc_ok:   # damaged: every chunk decompressed and checked, damage skipped
                report = integrity.scan("", idx.data_end)
                report.complete = True
                if walk is not None and not report.damaged:
                    report.problems.append("data section CRC mismatch outside the chunks (every "
                                           "chunk's own CRC is correct)")
                uncounted = None   # the scan read every chunk: counts and channels are known
            else:
                report = RecoveryReport(True, self.file_size, self.file_size,
                                        sum(1 for r in idx.layout if r[0] == OP_CHUNK),
                                        verified=bool(walk.data_crc))
                integrity.report = report
                uncounted = walk.uncounted
        missing = idx.channels_incomplete() if uncounted is not None else ""
        if uncounted or missing:
            integrity.inspect(uncounted, count=count, until_channels_known=bool(missing))
        unknown = idx.unknown_channels()
        if unknown:
            report.problems.append(
                f"{sum(unknown.values())} message(s) on channel id(s) {sorted(unknown)} that no "
                "Channel record in the file defines (they cannot be read)")
        report.layout = self._layout_text(summary)
        return report

    def _layout_text(self, summary: Summary | None) -> str:
        idx = self._index
        chunks = [c for c in idx.chunks.values() if c.offset not in idx.corrupt]
        parts = ["footer"]
        if summary is None:
            parts.append("no summary section (the data section was read)")
        else:
            have = [name for name, present in (
                ("statistics", summary.statistics is not None),
                ("chunk index", bool(summary.chunk_indexes)),
                ("repeated channels", bool(summary.channels)),
                ("repeated schemas", bool(summary.schemas))) if present]
            parts.append("summary" + (f" with {', '.join(have)}" if have else " (empty)"))
        if chunks:
            names = sorted({chunk_compression_name(c.compression) for c in chunks})
            parts.append(f"{len(chunks)} chunk(s) ({', '.join(names)})")
        unchunked = sum(1 for r in idx.layout if r[0] != OP_CHUNK)
        if unchunked:
            parts.append(f"{unchunked} unchunked message(s)")
        return ", ".join(parts)

    def _cut_header(self, where: str) -> None:
        self.recovery = RecoveryReport(False, self.file_size, 0, 0,
                                       reason=f"file of {self.file_size} bytes ends {where}")
        if not self.recover:
            raise TruncatedBagError(f"{self.path} is truncated: {self.recovery.reason}; "
                                    "nothing in it is readable", path=str(self.path),
                                    file_size=self.file_size)
        self._index.data_end = 0

    # ------------------------------------------------------------------ info
    @property
    def schemas(self) -> dict:
        """{schema id: records.Schema}"""
        return self._index.schemas

    @property
    def channels(self) -> dict:
        """{channel id: records.Channel}"""
        return self._index.channels

    @property
    def metadata(self) -> dict[str, dict[str, str]]:
        """{name: values} of the Metadata records."""
        return self._index.metadata

    @property
    def chunks(self) -> list[ChunkInfo]:
        """The readable chunks in file order (offset, length, start, end: log-time range)."""
        idx = self._index
        return sorted((c for c in idx.chunks.values() if c.offset not in idx.corrupt),
                      key=lambda c: c.offset)

    @property
    def message_count(self) -> int:
        return self._index.message_count

    @property
    def start_ns(self) -> int | None:
        return self._index.start

    @property
    def end_ns(self) -> int | None:
        return self._index.end

    @property
    def duration_ns(self) -> int:
        idx = self._index
        return (idx.end - idx.start) if idx.start is not None else 0

    @property
    def topics(self) -> dict[str, TopicInfo]:
        out = {}
        idx = self._index
        for cid, ch in sorted(idx.channels.items()):
            s = idx.schemas.get(ch.schema_id)
            sname, senc, stext = ((s.name, s.encoding, s.data.decode("utf-8", errors="replace"))
                                  if s is not None else ("", "", ""))
            out[ch.topic] = TopicInfo(ch.topic, sname, idx.counts.get(cid, 0), cid,
                                      ch.message_encoding, senc, stext,
                                      ch.metadata.get("offered_qos_profiles", ""),
                                      ch.metadata.get("topic_type_hash", ""))
        return out

    @property
    def rosbag2_metadata(self) -> dict | None:
        """The `rosbag2` metadata record's BagMetadata (parsed YAML), if present."""
        text = self.metadata.get("rosbag2", {}).get("serialized_metadata")
        if not text:
            return None
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
            # channels of one schema (a drive's SignalChunk topics) share its codec: parsed once
            key = (info.type, info.schema_encoding, info.schema_text)
            codec = self._schema_codecs.get(key)
            if codec is None:
                try:
                    codec = Codec.from_schema(info.type, info.schema_text, info.schema_encoding)
                except UnknownSchemaError as exc:
                    raise UnknownSchemaError(f"topic {topic!r} ({info.type}): {exc}") from None
                self._schema_codecs[key] = codec
            self._codecs[info.channel_id] = codec
        return codec

    def verify(self) -> RecoveryReport:
        """Decompress and CRC-check every chunk not verified yet (a file without a data-section
        CRC); damaged ones are added to ``recovery`` and skipped from then on. Raises
        DamagedBagError for a new damaged chunk unless the reader recovers."""
        if self._integrity is None:   # nothing readable in the file
            return self.recovery
        return self._integrity.verify()

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
                codecs[cid] = self.codec(self.channels[cid].topic)
        names = {cid: ch.topic for cid, ch in self.channels.items()}
        for cid, seq, log_time, pub, body in self._wanted_messages(wanted, start_ns, end_ns):
            data = bytes(body[MESSAGE_HEAD.size:])
            codec = codecs.get(cid)
            yield BagMessage(names[cid], log_time, pub, seq, data,
                             codec.decode(data) if codec is not None else None)

    def signal_chunks(self, topics: Iterable[str] | str, *,
                      copy: bool = True) -> Iterator[SignalChunkRecord]:
        """The SignalChunk messages of ``topics`` in file order, as flat :class:`SignalChunkRecord`
        tuples: the fields ``messages`` decodes (the same values), without building message
        objects -- the offline analysis reads its millions of samples this way (a chunk at a time:
        :meth:`signal_chunk_batches`). ``samples`` of a
        message in a compressed chunk is a read-only view of the decompressed chunk (no
        allocation per message: fresh memory costs a page fault per 4 KiB); elsewhere (an
        uncompressed chunk, a message outside chunks: views of the file's map) it is a copy, or
        with ``copy=False`` a read-only view of the map as well: for a caller that copies what it
        keeps (analyze joins the chunks into blocks), it saves a copy of every sample (on a file
        without chunks, 1500 copies of 8 KB in analyze's 10 s bag: ~2 ms). Such a view keeps the
        map alive after ``close`` until it is dropped, and reads the file: it must not be
        truncated meanwhile. A payload the SignalChunk fast path does not take (big endian) goes
        through the generic decoder (a copy); a malformed one raises its CdrError."""
        wanted, fast, names = self._signal_codecs(topics)
        records = self._records_to_read(wanted, None, None)
        if records and all(op == OP_MESSAGE and len(body) >= MESSAGE_HEAD.size
                           for op, _pos, body in records):
            # a file without chunks: each topic's fields taken from the file at once
            yield from self._unchunked_signal_chunks(records, fast, names, copy)
            return
        head = MESSAGE_HEAD.size
        for cid, _seq, log_time, _pub, body in self._messages_in(records, wanted, None, None):
            sec, nanosec, frame_id, signal_name, unit, period, first, samples = _signal_fields(
                *fast[cid], body[head:], copy and type(body.obj) is not bytes)
            yield SignalChunkRecord(names[cid], log_time, first, period, samples,
                                    Stamp(sec, nanosec), frame_id, signal_name, unit)

    def _signal_codecs(self, topics) -> tuple[set, dict, dict]:
        """(wanted channel ids, per wanted channel (its codec, its string cache), channel id ->
        topic) for reading SignalChunk ``topics``; BagError for a topic of another type."""
        wanted = self._channel_ids(topics)
        infos = {t.channel_id: t for t in self.topics.values()}
        fast = {}
        for cid in wanted:
            if not infos[cid].type.endswith("/SignalChunk"):
                raise BagError(f"topic {infos[cid].name!r} has type {infos[cid].type}, "
                               "not SignalChunk")
            fast[cid] = (self.codec(infos[cid].name), [None])   # its codec, its last string section
        return wanted, fast, {cid: ch.topic for cid, ch in self.channels.items()}

    def signal_chunk_batches(self, topics: Iterable[str] | str
                             ) -> Iterator[SignalChunkColumns | list[SignalChunkRecord]]:
        """What ``signal_chunks(topics, copy=False)`` yields, a batch at a time, in file order:
        for each chunk, its messages of ``topics`` as :class:`SignalChunkColumns` when each
        topic's payloads in it are laid out alike (signal_table.py; the samples read-only views
        of the decompressed chunk), else as the list of records ``signal_chunks`` yields for it;
        a message outside chunks as a list of its one record. The same values, errors and
        damaged-chunk handling as ``signal_chunks``, without a Python step per message for the
        fields of a chunk's messages (``analyze`` joins a chunk's whole ranges at once)."""
        wanted, fast, names = self._signal_codecs(topics)
        records = self._records_to_read(wanted, None, None)
        idx = self._index
        chunks = [(pos, body) for op, pos, body in records if op == OP_CHUNK]
        decompressed = self._prefetcher.map(self._chunk_records, chunks)
        head = MESSAGE_HEAD.size
        unpack = MESSAGE_HEAD.unpack_from
        try:
            for op, pos, body in records:
                if op != OP_CHUNK:    # (a message on a wanted channel, or too short: unpack names it)
                    cid, _seq, log_time, _pub = unpack(body, 0)
                    yield [self._signal_record(fast, names, cid, log_time, body[head:])]
                    continue
                try:
                    buf = next(decompressed)()
                    columns = _chunk_signal_columns(buf, wanted, fast, names)
                    bodies = message_bodies(buf) if columns is None else ()
                except CorruptBagError as error:
                    if pos not in idx.corrupt:
                        self._integrity.chunk_failed(pos, body, str(error))   # raises unless recovering
                    continue
                if columns is not None:
                    yield columns
                    continue
                batch = []
                for rbody in bodies:
                    cid, _seq, log_time, _pub = unpack(rbody, 0)
                    if cid in wanted:
                        batch.append(self._signal_record(fast, names, cid, log_time, rbody[head:]))
                yield batch
        finally:
            decompressed.close()   # waits for a chunk still being decompressed (the map stays valid)

    @staticmethod
    def _signal_record(fast: dict, names: dict, cid: int, log_time: int,
                       payload) -> SignalChunkRecord:
        """The SignalChunkRecord of one payload, as ``signal_chunks(copy=False)`` makes it."""
        sec, nanosec, frame_id, signal_name, unit, period, first, samples = _signal_fields(
            *fast[cid], payload, False)
        return SignalChunkRecord(names[cid], log_time, first, period, samples,
                                 Stamp(sec, nanosec), frame_id, signal_name, unit)

    def signal_chunk_columns(self, topics: Iterable[str] | str) -> SignalChunkColumns | None:
        """``signal_chunks(topics, copy=False)`` at once, as columns, when the file holds those
        messages outside chunks (rosbag2's noChunking) and each topic's payloads are laid out
        alike (signal_table.py: the same string section, every field inside the payload, at
        least one sample): the same values, with no Python step per message but making each
        one's samples view. None otherwise: read them with :meth:`signal_chunks`."""
        wanted, fast, _names = self._signal_codecs(topics)     # (as signal_chunks checks them)
        codecs = {cid: codec for cid, (codec, _strings) in fast.items()}
        head = MESSAGE_HEAD.size
        # a file of unchunked messages only (no chunk; each message holds its head): the records
        # of the wanted channels, in file order, are what _records_to_read gives
        channels, offsets, sizes = self._index.record_columns(self._buf)
        if not channels.size or (channels < 0).any():
            return None
        rows = np.flatnonzero(np.isin(channels, np.fromiter(wanted, dtype=np.int32,
                                                            count=len(wanted))))
        if not rows.size:
            return None
        n = rows.size
        starts = offsets[rows] + 9
        sizes = sizes[rows]
        channels = channels[rows]
        data = np.frombuffer(self._buf, dtype=np.uint8)
        log_time = gather(data, starts + 6, 8).view("<u8")[:, 0]
        first_rows = {int(c): int(np.argmax(channels == c)) for c in np.unique(channels)}
        order = sorted(first_rows, key=first_rows.get)       # topics by their first message
        topic = np.empty(n, dtype=np.int64)
        first = np.empty(n, dtype=np.uint64)
        period = np.empty(n, dtype=np.float64)
        sec = np.empty(n, dtype=np.int64)
        nanosec = np.empty(n, dtype=np.int64)
        count = np.empty(n, dtype=np.int64)
        at = np.empty(n, dtype=np.int64)
        texts = []
        for k, cid in enumerate(order):
            codec = codecs[cid]
            rows = np.flatnonzero(channels == cid)
            found = (signal_chunk_table(codec, data, starts[rows] + head, sizes[rows] - head, [None])
                     if codec.is_signal_chunk else None)
            if found is None or len(found.rows) != rows.size or 0 in found.samples:
                return None     # a payload laid out otherwise, or one without samples
            topic[rows] = k
            first[rows] = found.first_sample_index
            period[rows] = found.sample_period_s
            sec[rows] = found.sec
            nanosec[rows] = found.nanosec
            count[rows] = found.samples
            at[rows] = found.samples_at
            texts.append((found.frame_id, found.signal_name, found.unit))
        del data
        samples = _sample_slices(self._buf, at.tolist(), count.tolist())
        return SignalChunkColumns(tuple(self.channels[cid].topic for cid in order), topic, first,
                                  period, sec, nanosec, samples, tuple(texts), log_time)

    def _unchunked_signal_chunks(self, records: list, fast: dict, names: dict,
                                 copy: bool) -> Iterator[SignalChunkRecord]:
        """signal_chunks of ``records``, all unchunked Message records of the wanted channels (a
        file written without chunks): each topic's SignalChunk fields from the file at once
        (signal_table.py), the samples then a view of the map (or its copy) per message; a
        payload laid out otherwise than its topic's first one, one by one as in a chunk."""
        head = MESSAGE_HEAD.size
        n = len(records)
        starts = np.fromiter(map(itemgetter(1), records), dtype=np.int64, count=n) + 9
        sizes = np.fromiter(map(len, map(itemgetter(2), records)), dtype=np.int64, count=n)
        data = np.frombuffer(self._buf, dtype=np.uint8)
        heads = gather(data, starts, head).view(_MESSAGE_HEAD)[:, 0]
        channels = heads["channel"]
        table: list = [None] * n      # per record: its fields from a topic's table, or None
        for cid, (codec, strings) in fast.items():
            rows = np.flatnonzero(channels == cid)
            found = (signal_chunk_table(codec, data, starts[rows] + head, sizes[rows] - head,
                                        strings) if codec.is_signal_chunk and rows.size else None)
            if found is None:
                continue
            texts = (found.frame_id, found.signal_name, found.unit)
            for row, *fields in zip(rows[found.rows].tolist(), found.sec, found.nanosec,
                                    found.sample_period_s, found.first_sample_index,
                                    found.samples, found.samples_at):
                table[row] = (*fields, texts)
        del data   # no export of the map left behind but the samples' views
        buf = self._buf
        for (_op, _pos, body), cid, log_time, fields in zip(records, channels.tolist(),
                                                            heads["log_time"].tolist(), table):
            if fields is None:   # as in a chunk (the same parse, or the error it names)
                sec, nanosec, frame_id, signal_name, unit, period, first, samples = _signal_fields(
                    *fast[cid], body[head:], copy)
                yield SignalChunkRecord(names[cid], log_time, first, period, samples,
                                        Stamp(sec, nanosec), frame_id, signal_name, unit)
                continue
            sec, nanosec, period, first, count, at, (frame_id, signal_name, unit) = fields
            samples = (np.frombuffer(buf[at:at + 8 * count], dtype=_F64_LE) if count
                       else np.zeros(0, dtype=_F64_LE))
            yield SignalChunkRecord(names[cid], log_time, first, period,
                                    samples.copy() if copy and count else samples,
                                    Stamp(sec, nanosec), frame_id, signal_name, unit)

    def _wanted_messages(self, wanted: set[int], start_ns: int | None, end_ns: int | None):
        """(channel_id, sequence, log_time_ns, publish_time_ns, record body) of the messages on
        the ``wanted`` channels (log time within the range), in file order. Chunks are
        decompressed ahead by the reader's prefetcher (prefetch.py)."""
        return self._messages_in(self._records_to_read(wanted, start_ns, end_ns), wanted,
                                 start_ns, end_ns)

    def _records_to_read(self, wanted: set[int], start_ns: int | None,
                         end_ns: int | None) -> list:
        """(opcode, offset, body) of the layout's records that may hold messages on the
        ``wanted`` channels in the log-time range, in file order: the chunks (their index says
        what is in them, when it does) and the unchunked messages on those channels."""
        idx = self._index
        layout = idx.layout
        # unchunked messages on other channels are passed over at once (index.py), chunks kept
        channels = idx.message_channels(self._buf)
        keep = (channels < 0) | np.isin(channels, np.fromiter(wanted, dtype=np.int32,
                                                               count=len(wanted)))
        records = []   # (op, offset, body) of the records to read, in file order
        for op, pos, body in (layout if keep.all() else compress(layout, keep.tolist())):
            if op == OP_CHUNK:
                if pos in idx.corrupt:
                    continue
                info = idx.chunks.get(pos)
                if info is not None:
                    if info.channels is not None and not (info.channels & wanted):
                        continue
                    if (start_ns is not None and info.end < start_ns) or (
                            end_ns is not None and info.start > end_ns):
                        continue
            records.append((op, pos, body))
        return records

    def _messages_in(self, records: list, wanted: set[int], start_ns: int | None,
                     end_ns: int | None):
        """_wanted_messages of ``records`` (from _records_to_read)."""
        idx = self._index
        chunks = [(pos, body) for op, pos, body in records if op == OP_CHUNK]
        decompressed = self._prefetcher.map(self._chunk_records, chunks)
        unpack = MESSAGE_HEAD.unpack_from
        try:
            for op, pos, body in records:
                if op == OP_CHUNK:
                    try:
                        bodies = message_bodies(next(decompressed)())
                    except CorruptBagError as error:
                        if pos not in idx.corrupt:
                            self._integrity.chunk_failed(pos, body, str(error))   # raises unless recovering
                        continue
                else:   # (a message on a wanted channel, or too short: unpack names it)
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

    def _chunk_records(self, chunk) -> memoryview:
        """The records of the chunk (offset, body): decompressed, or the last chunk again (a
        second pass over another topic, e.g. analyze's latched true width then the signals,
        starts where the first ended)."""
        pos, body = chunk
        last = self._last_chunk
        if last is not None and last[0] == pos:
            return last[1]
        records = chunk_records(body)
        self._last_chunk = (pos, records)
        return records

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
            # the flat records (signal_chunks: the fields messages() decodes, no message objects; a
            # diagnose or model fit of a 3 s bag read it in 18 ms per bag message by message)
            for r in self.signal_chunks(topics):
                per[r.topic].append(r)
        return {t: _series(t, records) for t, records in per.items()}


_MESSAGE_HEAD = np.dtype([("channel", "<u2"), ("sequence", "<u4"), ("log_time", "<u8"),
                          ("publish_time", "<u8")])   # records.MESSAGE_HEAD's fields, as numpy's
_F64_LE = np.dtype("<f8")


def _signal_fields(codec: Codec, strings: list, payload, copy: bool) -> tuple:
    """(sec, nanosec, frame_id, signal_name, unit, sample_period_s, first_sample_index, samples)
    of one SignalChunk payload: its codec's fast path (``strings``: its string cache), or the
    generic decoder for one the fast path does not take (big endian), which names a malformed
    one (CdrError)."""
    if codec.is_signal_chunk:
        try:
            fields = codec.signal_chunk_fields(payload, copy=copy, strings=strings)
        except Exception:  # noqa: BLE001 - malformed: the generic decoder names it
            fields = None
        if fields is not None:
            return fields
    msg = codec.decode(bytes(payload))
    stamp = msg.header.stamp
    return (stamp.sec, stamp.nanosec, msg.header.frame_id, msg.signal_name, msg.unit,
            msg.sample_period_s, msg.first_sample_index, msg.samples)


_RECORD_CHANNEL = struct.Struct("<BQH")   # a record's opcode and length, a Message's channel id
_STAMP = struct.Struct("<iI")              # a SignalChunk's header.stamp (sec, nanosec)
_TAIL = struct.Struct("<dQI")              # its sample_period_s, first_sample_index, sample count


def _chunk_signal_columns(buf, wanted: set, fast: dict,
                          names: dict) -> SignalChunkColumns | None:
    """The SignalChunk messages of the ``wanted`` channels in a decompressed chunk's records
    ``buf``, as columns, when every one of them is laid out as its channel's last payload read
    (``fast``: per channel its codec and string cache, which ``Codec.signal_chunk_fields`` keeps:
    plain little-endian CDR, the same string section byte for byte, so the same offsets after
    it) and holds samples: their fields read at those offsets as ``signal_chunk_fields`` reads
    them (the same bytes as the same types: the same values). None for anything else -- a
    channel not read before, a payload laid out otherwise, one without samples, a record that
    does not fit the chunk -- which is then read one by one (and named when malformed). One
    Python step per record, a few struct reads per message, no numpy call per message."""
    n = len(buf)
    pos = 0
    rows = []                       # (channel id, record body offset, body length)
    unpack = _RECORD_CHANNEL.unpack_from
    message = OP_MESSAGE
    while pos + 11 <= n:
        op, length, cid = unpack(buf, pos)
        end = pos + 9 + length
        if end > n:
            return None
        if op == message and cid in wanted:
            rows.append((cid, pos + 9, length))
        pos = end
    if pos != n or not rows:
        return None
    layouts = {}                    # channel id -> (its topic's index, string section, its end, tail offset)
    order = []
    head = MESSAGE_HEAD.size
    stamp_of, tail_of, u64 = _STAMP.unpack_from, _TAIL.unpack_from, U64.unpack_from
    topic, log_time, first, period, sec, nanosec, samples_at, count = ([] for _ in range(8))
    for cid, at, length in rows:
        layout = layouts.get(cid)
        if layout is None:
            codec, strings = fast[cid]
            if not codec.is_signal_chunk or strings[0] is None:
                return None         # (read one by one first: that parses its string section)
            raw, _frame_id, _signal_name, _unit, strings_end = strings[0]
            layout = layouts[cid] = (len(order), raw, strings_end,
                                     strings_end + ((-(strings_end - 4)) & 7))
            order.append(cid)
        k, raw, strings_end, tail_at = layout
        p = at + head               # the payload
        size = length - head
        if (size < tail_at + _TAIL.size or buf[p] != 0 or buf[p + 1] != 1
                or buf[p + 12:p + strings_end] != raw):
            return None
        t_period, t_first, t_count = tail_of(buf, p + tail_at)
        if not t_count or tail_at + 24 + 8 * t_count > size:
            return None
        s, ns = stamp_of(buf, p + 4)
        topic.append(k)
        log_time.append(u64(buf, at + 6)[0])
        first.append(t_first)
        period.append(t_period)
        sec.append(s)
        nanosec.append(ns)
        samples_at.append(p + tail_at + 24)
        count.append(t_count)
    samples = _sample_slices(buf, samples_at, count)
    texts = tuple(tuple(fast[cid][1][0][1:4]) for cid in order)
    return SignalChunkColumns(tuple(names[cid] for cid in order), np.array(topic, dtype=np.int64),
                              np.array(first, dtype=np.uint64), np.array(period, dtype=np.float64),
                              np.array(sec, dtype=np.int64), np.array(nanosec, dtype=np.int64),
                              samples, texts, np.array(log_time, dtype=np.uint64))


def _sample_slices(buf, offsets: list, counts: list) -> list[np.ndarray]:
    """Each message's samples (``counts[i]`` float64 at byte ``offsets[i]`` of ``buf``) as a
    read-only slice of one float64 view of ``buf`` per byte alignment: no allocation per message."""
    views = {}
    samples = []
    for offset, count in zip(offsets, counts):
        shift = offset & 7
        base = views.get(shift)
        if base is None:
            base = views[shift] = np.frombuffer(buf, dtype=_F64_LE, count=(len(buf) - shift) // 8,
                                                offset=shift)
        i = offset >> 3
        samples.append(base[i:i + count])
    return samples


def _series(topic: str, msgs: list) -> SignalSeries:
    """A topic's SignalChunkRecords (file order) as one series in stream order."""
    msgs.sort(key=lambda r: r.first_sample_index)
    if not msgs:
        return SignalSeries(topic, "", "", float("nan"), np.zeros(0), np.zeros(0, np.uint64),
                            np.zeros(0, np.uint64), np.zeros(0, np.int64))
    first = msgs[0]
    samples = np.concatenate([np.asarray(r.samples, dtype=np.float64) for r in msgs])
    starts = np.array([r.first_sample_index for r in msgs], dtype=np.uint64)
    lengths = np.array([len(r.samples) for r in msgs], dtype=np.int64)
    offsets = np.concatenate(([0], np.cumsum(lengths)[:-1])).astype(np.uint64)
    idx = (np.repeat(starts - offsets, lengths)
           + np.arange(samples.size, dtype=np.uint64)) if samples.size else np.zeros(0, np.uint64)
    ends = starts + lengths.astype(np.uint64)
    bad = np.nonzero(starts[1:] != ends[:-1])[0]
    gaps = [(int(ends[k]), int(starts[k + 1])) for k in bad]
    if starts[0] != first.first_sample_index:  # pragma: no cover - sorted above
        gaps.insert(0, (int(first.first_sample_index), int(starts[0])))
    return SignalSeries(topic, first.signal_name, first.unit, first.sample_period_s, samples, idx,
                        starts, np.array([r.log_time_ns for r in msgs], dtype=np.int64),
                        first.frame_id, gaps)
