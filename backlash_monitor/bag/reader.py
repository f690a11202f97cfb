"""BagReader: reads rosbag2 MCAP files (ours, `ros2 bag record`'s, rosbags'), decoding CDR to numpy.

>>> with BagReader("run.mcap") as bag:
...     bag.topics["/plant/a1"].count
...     for m in bag.messages(["/plant/a1"]):
...         m.topic, m.log_time_ns, m.message.samples      # numpy float64 array
...     series = bag.read_signal("/plant/a1")               # all samples concatenated, gaps listed

Integrity is checked when the file is opened: the summary's CRC, every indexed chunk's record
header against the chunk index (opcode, length, time range), and the data section's CRC (DataEnd);
when that CRC does not match (or a header is damaged) every chunk is decompressed and CRC-checked to
find which ones are damaged. A chunk CRC failure found later while reading (a file written without
a data-section CRC) is damage too.

- A file without a valid footer/summary (the recorder was killed, the disk filled, the summary's CRC
  fails) raises TruncatedBagError unless opened with `recover=True`: then the data section is
  scanned from the start and every complete, CRC-valid chunk is read.
- A file with damaged chunks raises DamagedBagError (naming the chunks, their log-time range and
  message count) unless opened with `recover=True`: then every intact chunk is read and the damaged
  ones are skipped -- past a damaged length field by the chunk index, or, without an index, by
  resynchronising on the next record that is a self-consistent chunk. A chunk whose length field
  alone is damaged is read when its contents pass the CRC.

`bag.recovery` (RecoveryReport) says what was intact, what was damaged and skipped (DamagedChunk:
offset, bytes, log-time range, messages, reason), and what was lost at the end (at most the chunk the
writer had open; its time bound comes from the writer's `backlash_monitor.writer` metadata record).
"""
from __future__ import annotations

import bisect
import mmap
import os
import threading
from collections import deque
from collections.abc import Iterable, Iterator
from dataclasses import asdict, dataclass, field
from functools import partial
from pathlib import Path
from typing import NamedTuple

import numpy as np

from .cdr import Codec, RosMessage
from .errors import (BagError, CorruptBagError, DamagedBagError, MissingTopicError, NotABagError,
                     TruncatedBagError, UnknownSchemaError)
from .mcap_format import (CHUNK_HEAD, FOOTER_BODY, FOOTER_RECORD_LEN, MAGIC, MESSAGE_HEAD,
                          OP_CHANNEL, OP_CHUNK, OP_CHUNK_INDEX, OP_DATA_END, OP_FOOTER, OP_HEADER,
                          OP_MESSAGE, OP_MESSAGE_INDEX, OP_METADATA, OP_METADATA_INDEX, OP_SCHEMA,
                          OP_STATISTICS, OP_SUMMARY_OFFSET, RECORD_HEADER, U32, U64, Cursor, crc32)

WRITER_METADATA = "backlash_monitor.writer"   # metadata record: the writer's chunk limits

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
class DamagedChunk:
    """A damaged part of the data section: a chunk whose length field, CRC or compressed data is
    bad, or bytes between records that are no readable record."""
    offset: int                      # byte offset in the file
    length_bytes: int                # bytes it spans
    reason: str
    start_ns: int | None = None      # log-time range of its messages (chunk index / chunk header)
    end_ns: int | None = None
    messages: int | None = None      # messages in it (its message index records); None: unknown
    recovered: bool = False          # only a header field was damaged: contents CRC-verified, read

    def to_dict(self) -> dict:
        return asdict(self)


def _t(ns, origin) -> str:
    return "?" if ns is None or origin is None else f"{(ns - origin) / 1e9:.3f}"


@dataclass
class RecoveryReport:
    complete: bool                   # footer and summary present and valid
    file_size: int
    intact_bytes: int                # bytes up to the end of the last complete record
    complete_chunks: int
    messages: int = 0
    reason: str = ""
    damaged: list[DamagedChunk] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)   # damage outside the chunks (CRCs)
    verified: bool = False           # every chunk's contents checked (data CRC, or each chunk's CRC)
    origin_ns: int | None = None     # first log time of the bag (times are given relative to it)
    last_message_ns: int | None = None
    tail_start_ns: int | None = None  # the chunk cut off at the end (its header was readable)
    tail_end_ns: int | None = None
    chunk_duration_s: float | None = None  # the writer's chunk time limit: bounds the open chunk

    @property
    def lost_bytes(self) -> int:
        """Bytes after the last complete record (a writer killed while writing)."""
        return self.file_size - self.intact_bytes

    @property
    def skipped(self) -> list[DamagedChunk]:
        """Damaged chunks that were not read."""
        return [d for d in self.damaged if not d.recovered]

    @property
    def corrupt_chunks(self) -> int:
        return len(self.skipped)

    @property
    def skipped_messages(self) -> int | None:
        """Messages in skipped damaged chunks (None when a count is unknown)."""
        counts = [d.messages for d in self.skipped]
        return None if any(c is None for c in counts) else sum(counts)

    @property
    def skipped_bytes(self) -> int:
        return sum(d.length_bytes for d in self.skipped)

    @property
    def damaged_any(self) -> bool:
        return bool(self.damaged or self.problems)

    @property
    def intact(self) -> bool:
        return self.complete and not self.damaged_any

    def open_chunk_text(self) -> str:
        """What a writer killed at the end lost (the chunk it had open), when it can be said."""
        if self.complete:
            return ""
        if self.tail_start_ns is not None:
            return (f"the chunk being written when the file ends held log time "
                    f"{_t(self.tail_start_ns, self.origin_ns)}-{_t(self.tail_end_ns, self.origin_ns)} s "
                    f"({(self.tail_end_ns - self.tail_start_ns) / 1e9:.3f} s) and is lost")
        if self.chunk_duration_s and self.last_message_ns is not None:
            return (f"the writer's open chunk is lost: at most {self.chunk_duration_s:g} s "
                    f"(its chunk_duration_s) after the last recovered message at "
                    f"{_t(self.last_message_ns, self.origin_ns)} s")
        return ""

    def damage_text(self, limit: int = 4) -> str:
        """One line: the damaged chunks (offset, log time, messages, reason)."""
        parts = []
        for d in self.damaged[:limit]:
            what = (f"byte {d.offset} ({d.length_bytes} bytes, log time {_t(d.start_ns, self.origin_ns)}-"
                    f"{_t(d.end_ns, self.origin_ns)} s, "
                    f"{'?' if d.messages is None else d.messages} messages): {d.reason}")
            parts.append(what + ("; contents intact (CRC verified), read" if d.recovered else ""))
        if len(self.damaged) > limit:
            parts.append(f"... {len(self.damaged) - limit} more")
        text = ""
        if self.damaged:
            n = len(self.skipped)
            msgs = self.skipped_messages
            text = (f"{len(self.damaged)} damaged chunk(s), {n} unreadable ({self.skipped_bytes} bytes, "
                    f"{'an unknown number of' if msgs is None else msgs} message(s)): " + "; ".join(parts))
        if self.problems:
            text += ("; " if text else "") + "; ".join(self.problems)
        return text

    def describe(self) -> str:
        if self.complete:
            text = "complete (footer, summary and statistics present"
            text += "; every chunk's CRC verified)" if self.verified else ")"
        else:
            text = (f"INCOMPLETE: {self.reason}; {self.complete_chunks} complete chunk(s) with "
                    f"{self.messages} message(s) recovered from the first {self.intact_bytes} of "
                    f"{self.file_size} bytes; {self.lost_bytes} trailing byte(s) lost")
            tail = self.open_chunk_text()
            if tail:
                text += "; " + tail
        if self.damaged_any:
            text = f"DAMAGED: {self.damage_text()}. " + text
        return text

    def _relative(self, d: DamagedChunk) -> dict:
        """The chunk's log-time range in seconds from the bag's first message."""
        if d.start_ns is None or self.origin_ns is None:
            return {"start_s": None, "end_s": None}
        return {"start_s": (d.start_ns - self.origin_ns) / 1e9, "end_s": (d.end_ns - self.origin_ns) / 1e9}

    def to_dict(self) -> dict:
        return {"complete": self.complete, "intact": self.intact, "verified": self.verified,
                "reason": self.reason, "file_size": self.file_size,
                "intact_bytes": self.intact_bytes, "lost_trailing_bytes": self.lost_bytes,
                "complete_chunks": self.complete_chunks, "messages_read": self.messages,
                "damaged_chunks": [{**d.to_dict(), **self._relative(d)} for d in self.damaged],
                "skipped_chunks": len(self.skipped), "skipped_bytes": self.skipped_bytes,
                "skipped_messages": self.skipped_messages, "problems": list(self.problems),
                "origin_ns": self.origin_ns, "last_message_ns": self.last_message_ns,
                "open_chunk": self.open_chunk_text(), "describe": self.describe()}


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
    length: int = 0                  # record length from the chunk index (0: unknown)
    index_offsets: dict | None = None  # channel id -> offset of its MessageIndex record


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
        self._layout: list = []          # (opcode, offset, body) of the readable chunks and messages
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
        try:
            self.profile = c.string()
            self.library = c.string()
        except (ValueError, UnicodeDecodeError, IndexError):
            raise NotABagError(f"{self.path}: MCAP header record is unreadable") from None
        if self.profile != "ros2":
            raise NotABagError(f"{self.path} is an MCAP file with profile {self.profile!r}, "
                               "not a ROS 2 bag (profile 'ros2')")
        self._data_start = pos + 9 + length
        reason = self._read_summary()
        if reason is None and self._have_stats:
            report = self._check_data()
        elif reason is None:
            # a valid file whose writer left out the statistics: count by scanning the data
            report = self._scan("", self._data_end)
            report.complete = True
        else:   # no usable summary: scan the data section
            report = self._scan(reason)
        report.origin_ns = self._start
        report.last_message_ns = self._end
        report.messages = self._message_count
        duration = self.metadata.get(WRITER_METADATA, {}).get("chunk_duration_s", "")
        try:
            report.chunk_duration_s = float(duration) if duration else None
        except ValueError:
            report.chunk_duration_s = None
        self.recovery = report
        if self.recover:
            return
        if not report.complete:
            raise TruncatedBagError(
                f"{self.path} is incomplete ({report.reason})"
                + (": the recorder did not close it" if "footer" in report.reason else "")
                + f". {report.complete_chunks} complete chunk(s) with {report.messages} message(s) "
                f"are intact in the first {report.intact_bytes} of {report.file_size} bytes"
                + (f"; {report.damage_text()}" if report.damaged_any else "")
                + "; read them with recovery (BagReader(path, recover=True), `--recover`)",
                path=str(self.path), file_size=self.file_size, intact_bytes=report.intact_bytes,
                complete_chunks=report.complete_chunks)
        if report.damaged_any:
            raise DamagedBagError(f"{self.path} is damaged: {report.damage_text()}; read the intact "
                                  "chunks with recovery (--recover)", report)

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
        summary_start, summary_offset_start, summary_crc = FOOTER_BODY.unpack_from(b, fpos + 9)
        if summary_start == 0:
            return "footer without summary section"
        if not self._data_start <= summary_start <= fpos:
            return "footer points outside the file"
        if summary_offset_start and not summary_start <= summary_offset_start <= fpos:
            return "footer's summary offset points outside the summary"
        # summary CRC: from the summary's start through the footer's two offsets
        if summary_crc and crc32(b[summary_start:fpos + 9 + 16]) != summary_crc:
            return "summary section CRC mismatch (the summary is damaged)"
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
        except (ValueError, UnicodeDecodeError, IndexError) as exc:
            self._reset_summary()
            return f"unreadable summary section ({exc})"
        return None

    def _reset_summary(self) -> None:
        self._chunks.clear()
        self._counts.clear()
        self._message_count = 0
        self._start = self._end = None
        self._have_stats = False

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
            start, end_t, offset, length = c.u64(), c.u64(), c.u64(), c.u64()
            mend = c.pos + c.u32()
            chans = {}
            while c.pos < mend:
                cid = c.u16()
                chans[cid] = c.u64()
            self._chunks[offset] = _Chunk(offset, start, end_t, frozenset(chans) if chans else None,
                                          length, chans)
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

    # ------------------------------------------------------------------ integrity
    def _chunk_fields(self, pos: int, end: int):
        """(start_ns, end_ns, body_length) of a self-consistent chunk record at ``pos`` whose body
        (computed from its own fields: header, compression name, records size) fits before ``end``;
        None if there is none. The record's length field is not used (it may be damaged)."""
        b = self._buf
        head = pos + 9
        if head + CHUNK_HEAD.size + 4 > end or b[pos] != OP_CHUNK:
            return None
        start, end_t, usize, _crc = CHUNK_HEAD.unpack_from(b, head)
        if start > end_t or usize > 1 << 36:
            return None
        (clen,) = U32.unpack_from(b, head + CHUNK_HEAD.size)
        if clen > 4:
            return None
        p = head + CHUNK_HEAD.size + 4
        if bytes(b[p:p + clen]) not in (b"", b"zstd", b"lz4") or p + clen + 8 > end:
            return None
        (records_size,) = U64.unpack_from(b, p + clen)
        body_length = CHUNK_HEAD.size + 4 + clen + 8 + records_size
        if head + body_length > end:
            return None
        return start, end_t, body_length

    def _record_fits(self, pos: int, end: int) -> bool:
        """A plausible record starts at ``pos`` (or the data ends there)."""
        if pos == end:
            return True
        if pos + 9 > end:
            return False
        op, length = RECORD_HEADER.unpack_from(self._buf, pos)
        return 0 < op <= _MAX_OPCODE and pos + 9 + length <= end

    def _next_chunk(self, pos: int, end: int) -> int | None:
        """Resynchronise: the offset of the next intact-looking chunk record in [pos, end) (its
        length field agrees with its own fields), or None."""
        mm = self._mm
        b = self._buf
        while True:
            pos = mm.find(bytes((OP_CHUNK,)), pos, end)
            if pos < 0:
                return None
            fields = self._chunk_fields(pos, end)
            if fields is not None and pos + 9 <= end and \
                    RECORD_HEADER.unpack_from(b, pos)[1] == fields[2]:
                return pos
            pos += 1

    def _index_messages(self, index_offsets: dict | None) -> dict | None:
        """{channel id: messages} of a chunk from its MessageIndex records (None: unreadable)."""
        if not index_offsets:
            return None
        out = {}
        for cid, off in index_offsets.items():
            if off + 9 + 6 > self.file_size:
                return None
            op, length = RECORD_HEADER.unpack_from(self._buf, off)
            if op != OP_MESSAGE_INDEX or length < 6:
                return None
            (n,) = U32.unpack_from(self._buf, off + 9 + 2)
            out[cid] = n // 16
        return out

    def _index_run_before(self, lo: int, stop: int) -> dict | None:
        """{channel id: messages} of the MessageIndex records that end exactly at ``stop`` (found
        by trying every 0x07 byte in the 64 KiB before it), None if there are none."""
        mm = self._mm
        b = self._buf
        p = max(lo, stop - 65536)
        while True:
            p = mm.find(bytes((OP_MESSAGE_INDEX,)), p, stop)
            if p < 0:
                return None
            q, out = p, {}
            while q + 9 + 6 <= stop:
                op, length = RECORD_HEADER.unpack_from(b, q)
                if op != OP_MESSAGE_INDEX or q + 9 + length > stop or length < 6:
                    break
                cid = int.from_bytes(b[q + 9:q + 11], "little")
                (n,) = U32.unpack_from(b, q + 11)
                if 6 + n != length:
                    break
                out[cid] = out.get(cid, 0) + n // 16
                q += 9 + length
            if q == stop and out:
                return out
            p += 1

    def _lose_messages(self, per_channel: dict | None) -> int | None:
        """Take the messages of a skipped chunk out of the counts (summary statistics)."""
        if per_channel is None:
            return None
        for cid, n in per_channel.items():
            if cid in self._counts:
                self._counts[cid] = max(0, self._counts[cid] - n)
        total = sum(per_channel.values())
        self._message_count = max(0, self._message_count - total)
        return total

    def _check_data(self) -> RecoveryReport:
        """With a valid summary: walk the data section by the chunk index (every indexed chunk's
        record checked against its index entry; unreadable bytes skipped to the next indexed chunk),
        check the data section's CRC and, when it fails, every chunk's CRC."""
        b = self._buf
        index = self._chunks
        offsets = sorted(o for o in index if self._data_start <= o < self._data_end)
        if not offsets:
            # no chunk index to walk by (some writers leave it out): scan, every chunk checked
            report = self._scan("", self._data_end)
            report.complete = True
            return report
        report = RecoveryReport(True, self.file_size, self.file_size, len(self._chunks))
        for o in sorted(set(index) - set(offsets)):
            report.problems.append(f"the chunk index points at byte {o}, outside the data section "
                                   f"({self._data_start}-{self._data_end}); that chunk is not read")
        end = self._data_end
        layout = []
        suspect: dict[int, str] = {}
        data_crc = None
        data_end_pos = None
        pos = self._data_start
        while pos < end:
            k = bisect.bisect_left(offsets, pos)
            nxt = offsets[k] if k < len(offsets) else end
            ci = index.get(pos)
            if ci is not None:
                problem = self._chunk_header_problem(pos, ci)
                length = ci.length
                if problem:
                    suspect[pos] = problem
                    if not length or pos + length > end:   # the index's length is no help either
                        k2 = bisect.bisect_right(offsets, pos)
                        length = (offsets[k2] if k2 < len(offsets) else end) - pos
                layout.append((OP_CHUNK, pos, b[pos + 9:pos + length]))
                pos += length
                continue
            op, length = RECORD_HEADER.unpack_from(b, pos) if pos + 9 <= end else (0, 0)
            rec_end = pos + 9 + length
            if op == 0 or rec_end > nxt or op == OP_CHUNK:   # (a chunk not in the index too)
                # no readable record here (or one that runs over the next indexed chunk):
                # skip to the next indexed chunk
                # every chunk starts at an indexed offset: no chunk is in these bytes
                report.problems.append(f"unreadable bytes {pos}-{nxt} between the indexed chunks (a "
                                       "damaged message index or metadata record, or a chunk the "
                                       "index does not list)")
                pos = nxt
                continue
            if op == OP_MESSAGE:
                layout.append((op, pos, b[pos + 9:rec_end]))
            elif op == OP_DATA_END and length >= 4:
                data_end_pos = pos
                (data_crc,) = U32.unpack_from(b, pos + 9)
            pos = rec_end
            if op == OP_DATA_END:
                break
        check_all = False
        if data_crc:   # 0: the writer did not compute it
            if crc32(b[:data_end_pos]) == data_crc:
                report.verified = not suspect and not report.damaged
            else:
                check_all = True
        bad: dict[int, str] = {}
        for op, cpos, body in layout:
            if op != OP_CHUNK or not (check_all or cpos in suspect):
                continue
            try:
                self._decompress(body)
            except CorruptBagError as error:
                bad[cpos] = str(error)
        if check_all:
            report.verified = True
            if not bad and not suspect and not report.damaged:
                report.problems.append("data section CRC mismatch outside the chunks (every "
                                       "chunk's own CRC is correct: a message index or metadata "
                                       "record is damaged)")
        for cpos in sorted(set(suspect) | set(bad)):
            ci = index[cpos]
            reason = "; ".join(r for r in (suspect.get(cpos), bad.get(cpos)) if r)
            recovered = cpos not in bad
            per_channel = self._index_messages(ci.index_offsets)
            messages = (sum(per_channel.values()) if per_channel is not None else None)
            if not recovered:
                self._lose_messages(per_channel)
                self._corrupt.add(cpos)
            report.damaged.append(DamagedChunk(cpos, ci.length, reason, ci.start, ci.end,
                                               messages, recovered))
        report.damaged.sort(key=lambda d: d.offset)
        report.complete_chunks = sum(1 for op, cpos, _ in layout
                                     if op == OP_CHUNK and cpos not in self._corrupt)
        self._layout = [r for r in layout if r[1] not in self._corrupt]
        return report

    def _chunk_header_problem(self, pos: int, ci: _Chunk) -> str | None:
        b = self._buf
        if not ci.length or pos + ci.length > self._data_end:
            return (f"the chunk index gives this chunk {ci.length} bytes, past the data section")
        op, length = RECORD_HEADER.unpack_from(b, pos)
        if op != OP_CHUNK:
            return f"record at the indexed chunk offset has opcode 0x{op:02x}, not a chunk (0x06)"
        if 9 + length != ci.length:
            return (f"chunk length field damaged (the record says {9 + length} bytes, the chunk "
                    f"index {ci.length})")
        if ci.length < 9 + CHUNK_HEAD.size:
            return f"chunk of {ci.length} bytes is too short"
        start, end_t = CHUNK_HEAD.unpack_from(b, pos + 9)[:2]
        if (start, end_t) != (ci.start, ci.end):
            return "chunk header's log-time range differs from the chunk index"
        return None

    def verify(self) -> RecoveryReport:
        """Decompress and CRC-check every chunk not verified yet (a file without a data-section
        CRC); damaged ones are added to ``recovery`` and skipped from then on. Raises
        DamagedBagError for a new damaged chunk unless the reader recovers."""
        report = self.recovery
        if report.verified:
            return report
        for op, pos, body in list(getattr(self, "_layout", [])):
            if op != OP_CHUNK or pos in self._corrupt:
                continue
            try:
                self._decompress(body)
            except CorruptBagError as error:
                self._chunk_failed(pos, body, str(error))
        report.verified = True
        return report

    def _chunk_failed(self, pos: int, body, reason: str) -> DamagedChunk:
        """Record a chunk whose contents fail (CRC, decompression) found while reading; raise
        DamagedBagError unless recovering."""
        report = self.recovery
        self._corrupt.add(pos)
        ci = self._chunks.get(pos)
        if ci is not None:
            start, end_t, length = ci.start, ci.end, ci.length or 9 + len(body)
            per_channel = self._index_messages(ci.index_offsets)
        else:
            start, end_t = CHUNK_HEAD.unpack_from(body, 0)[:2]
            length, per_channel = 9 + len(body), None
        damaged = DamagedChunk(pos, length, reason, start, end_t,
                               None if per_channel is None else sum(per_channel.values()))
        if report.complete:   # the scan already left it out of the counts
            self._lose_messages(per_channel)
        report.damaged.append(damaged)
        report.damaged.sort(key=lambda d: d.offset)
        report.complete_chunks = max(0, report.complete_chunks - 1)
        report.messages = self._message_count
        if not self.recover:
            raise DamagedBagError(f"{self.path} is damaged: {report.damage_text()}; read the intact "
                                  "chunks with recovery (--recover)", report)
        return damaged

    # ------------------------------------------------------------------ scanning
    def _scan(self, reason: str, data_end: int | None = None) -> RecoveryReport:
        """Read the data section from the start without the summary: every complete chunk is
        decompressed and CRC-checked; damaged bytes in the middle are skipped by
        resynchronising on the next self-consistent chunk record; the end of the readable data
        is where no further chunk can be found."""
        report = RecoveryReport(False, self.file_size, self._data_start, 0, reason=reason)
        chunk_index = dict(self._chunks)
        self._chunks.clear()
        self._counts.clear()
        self._message_count = 0
        self._start = self._end = None
        self._corrupt.clear()
        end = self.file_size if data_end is None else data_end
        b = self._buf
        layout = []
        last = None          # the last damaged chunk: the MessageIndex records after it count for it
        pos = self._data_start
        while pos < end:
            op, length = RECORD_HEADER.unpack_from(b, pos) if pos + 9 <= end else (-1, 0)
            rec_end = pos + 9 + length
            fields = self._chunk_fields(pos, end) if op == OP_CHUNK else None
            inner_ok = fields is not None and fields[2] == length
            if (op == OP_CHUNK and not inner_ok and rec_end <= end and self._record_fits(rec_end, end)
                    and (fields is None or not self._record_fits(pos + 9 + fields[2], end))):
                fields = None   # the length field is right, the chunk's inside is damaged
            elif op in (-1, 0) or op > 0x7F or rec_end > end or (op == OP_CHUNK and not inner_ok):
                if fields is not None:   # a chunk whose length field alone is damaged
                    body = b[pos + 9:pos + 9 + fields[2]]
                    last = self._scan_chunk(report, layout, chunk_index, pos, body,
                                            f"chunk length field damaged (says {9 + length} "
                                            f"bytes, its contents {9 + fields[2]})")
                    pos = pos + 9 + fields[2]
                    report.intact_bytes = pos
                    continue
                nxt = self._next_chunk(pos + 1, end)
                if nxt is None:   # nothing readable after this: the end of the recording
                    if op == OP_CHUNK and pos + 9 + CHUNK_HEAD.size <= end:
                        report.tail_start_ns, report.tail_end_ns = CHUNK_HEAD.unpack_from(b, pos + 9)[:2]
                    if op in (-1,):
                        report.reason = report.reason or f"record header cut off at byte {pos}"
                    else:
                        report.reason = report.reason or (
                            f"record at byte {pos} (opcode 0x{op:02x}, {length} bytes) is cut off "
                            "by the end of the file" if 0 < op <= 0x7F else
                            f"garbage record at byte {pos}")
                    break
                start_end = (CHUNK_HEAD.unpack_from(b, pos + 9)[:2]
                             if op == OP_CHUNK and pos + 9 + CHUNK_HEAD.size <= nxt else (None, None))
                if start_end[0] is not None and start_end[0] > start_end[1]:
                    start_end = (None, None)
                per_channel = self._index_run_before(pos, nxt)
                report.damaged.append(DamagedChunk(
                    pos, nxt - pos, "unreadable record (damaged header); skipped to the next chunk",
                    *start_end, None if per_channel is None else sum(per_channel.values())))
                last = None
                pos = nxt
                continue
            body = b[pos + 9:rec_end]
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
                    layout.append((op, pos, body))
                elif op == OP_CHUNK:
                    last = self._scan_chunk(report, layout, chunk_index, pos, body, "")
                    pos = rec_end
                    report.intact_bytes = pos
                    continue
                elif op == OP_MESSAGE_INDEX and last is not None and len(body) >= 6:
                    (n,) = U32.unpack_from(body, 2)
                    last.messages = (last.messages or 0) + n // 16
                    pos = rec_end
                    report.intact_bytes = pos
                    continue
            except (ValueError, UnicodeDecodeError, IndexError):
                report.reason += f"; malformed record at byte {pos}"
                break
            if op != OP_MESSAGE_INDEX:
                last = None
            pos = rec_end
            report.intact_bytes = pos
            if op in (OP_DATA_END, OP_FOOTER):
                break
        self._data_end = report.intact_bytes
        report.messages = self._message_count
        report.verified = True          # every chunk was decompressed and its CRC checked
        self._layout = layout
        return report

    def _scan_chunk(self, report, layout, chunk_index, pos, body, header_problem: str):
        """Decompress, CRC-check and count one chunk found by the scan; returns its DamagedChunk
        (None when intact)."""
        start, end_t = CHUNK_HEAD.unpack_from(body, 0)[:2]
        try:
            records = self._decompress(body)
        except CorruptBagError as error:
            reason = "; ".join(r for r in (header_problem, str(error)) if r)
            damaged = DamagedChunk(pos, 9 + len(body), reason, start, end_t)  # messages: its index
            report.damaged.append(damaged)
            self._corrupt.add(pos)
            return damaged
        try:
            plain = list(_iter_plain(records))
        except CorruptBagError as error:
            damaged = DamagedChunk(pos, 9 + len(body), str(error), start, end_t)
            report.damaged.append(damaged)
            self._corrupt.add(pos)
            return damaged
        chans = set()
        n = 0
        for rop, _rpos, rbody in plain:
            if rop == OP_MESSAGE:
                chans.add(self._count_message(rbody))
                n += 1
            elif rop == OP_SCHEMA:
                self._schema(Cursor(rbody))
            elif rop == OP_CHANNEL:
                self._channel(Cursor(rbody))
        self._chunks[pos] = chunk_index.get(pos) or _Chunk(pos, start, end_t, frozenset(chans),
                                                           9 + len(body))
        layout.append((OP_CHUNK, pos, body))
        report.complete_chunks += 1
        if header_problem:
            report.damaged.append(DamagedChunk(pos, 9 + len(body), header_problem, start, end_t, n,
                                               True))
        return None

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
        if c.pos + n != len(body):
            raise CorruptBagError(f"chunk records ({n} bytes) do not end where the chunk record "
                                  f"does ({len(body) - c.pos} bytes): a damaged length field")
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
        for op, pos, body in self._layout:
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
            records.append((op, pos, body))
        chunks = [(pos, body) for op, pos, body in records if op == OP_CHUNK]
        decompressed = _prefetch(self._chunk_records, chunks, CHUNKS_AHEAD)
        unpack = MESSAGE_HEAD.unpack_from
        try:
            for op, pos, body in records:
                if op == OP_CHUNK:
                    try:
                        chunk_records = next(decompressed)()
                        bodies = _message_bodies(chunk_records)
                    except CorruptBagError as error:
                        if pos not in self._corrupt:
                            self._chunk_failed(pos, body, str(error))   # raises unless recovering
                        continue
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


CHUNKS_AHEAD = 6   # chunks decompressed ahead of the one being read (~6 MiB at the default chunk size);
                   # 0: no decompression thread (a process with no core to spare, e.g. one of a pool
                   # with a worker per core: the thread would only take turns with it)

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
    if ahead <= 0:
        for item in items:
            yield partial(fn, item)
        return
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
