"""Integrity of a bag's data section, and recovery of what is intact in a damaged one.

When a bag is opened (reader.py):

- with a chunk index (`check_indexed`): every indexed chunk's record header is checked against
  its index entry (opcode, length, log-time range); unreadable bytes are skipped to the next
  indexed chunk; the data section's CRC (DataEnd) is checked and, when it fails (or a chunk header
  is damaged), every chunk is decompressed and CRC-checked, which names the damaged ones;
- without a usable footer or summary (a killed writer, a damaged summary), or when a valid file's
  records do not fit (`scan`): the data section is read from the start, every complete chunk
  decompressed and CRC-checked; damaged bytes are skipped by resynchronising on the next
  self-consistent chunk record (opcode, compression name, records size and length agree);
- chunks decompressed at open for their counts or channels (index.py) and chunks found damaged
  while reading (`chunk_failed`: a file without a data-section CRC) are reported the same way.

The RecoveryReport says what was intact, what was damaged and skipped (DamagedChunk: offset,
bytes, log-time range, messages, reason), and what was lost at the end (at most the chunk the
writer had open; its time bound comes from the writer's `backlash_monitor.writer` metadata
record). A damaged bag raises DamagedBagError, an incomplete one TruncatedBagError, unless the
reader recovers (`recover=True`, `--recover`): then every intact chunk is read.
"""
from __future__ import annotations

import bisect
from dataclasses import asdict, dataclass, field

from .errors import CorruptBagError, DamagedBagError, TruncatedBagError
from .index import BagIndex, ChunkInfo
from .records import (CHUNK_HEAD, COMPRESSIONS, MALFORMED, MAX_OPCODE, MESSAGE_HEAD, OP_CHANNEL,
                      OP_CHUNK,
                      OP_DATA_END, OP_FOOTER, OP_MESSAGE, OP_MESSAGE_INDEX, OP_METADATA, OP_SCHEMA,
                      RECORD_HEADER, U32, U64, chunk_records, crc32, iter_records,
                      unsupported_compression)


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
    complete: bool                   # the file ends with its footer (a summary or none: both valid)
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
    layout: str = ""                 # what the complete file has (summary, statistics, indexes)

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
            text = f"complete ({self.layout or 'footer, summary and statistics present'}"
            text += ((("; every chunk's CRC verified)" if self.complete_chunks
                       else "; the data section's CRC verified)") if self.verified else ")"))
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
                "reason": self.reason, "layout": self.layout, "file_size": self.file_size,
                "intact_bytes": self.intact_bytes, "lost_trailing_bytes": self.lost_bytes,
                "complete_chunks": self.complete_chunks, "messages_read": self.messages,
                "damaged_chunks": [{**d.to_dict(), **self._relative(d)} for d in self.damaged],
                "skipped_chunks": len(self.skipped), "skipped_bytes": self.skipped_bytes,
                "skipped_messages": self.skipped_messages, "problems": list(self.problems),
                "origin_ns": self.origin_ns, "last_message_ns": self.last_message_ns,
                "open_chunk": self.open_chunk_text(), "describe": self.describe()}


def raise_for(report: RecoveryReport, path, file_size: int) -> None:
    """TruncatedBagError for an incomplete file, DamagedBagError for a damaged one (the reader
    does not call it when it recovers)."""
    if not report.complete:
        raise TruncatedBagError(
            f"{path} is incomplete ({report.reason})"
            + (": the recorder did not close it" if "footer" in report.reason else "")
            + f". {report.complete_chunks} complete chunk(s) with {report.messages} message(s) "
            f"are intact in the first {report.intact_bytes} of {report.file_size} bytes"
            + (f"; {report.damage_text()}" if report.damaged_any else "")
            + "; read them with recovery (--recover)",
            path=str(path), file_size=file_size, intact_bytes=report.intact_bytes,
            complete_chunks=report.complete_chunks)
    if report.damaged_any:
        raise DamagedBagError(f"{path} is damaged: {report.damage_text()}; read the intact "
                              "chunks with recovery (--recover)", report)


class Integrity:
    """The checks and the scan of one open file (its map ``mm`` / ``buf``, its ``index``)."""

    def __init__(self, path, mm, buf, file_size: int, index: BagIndex, recover: bool):
        self.path = path
        self.mm = mm
        self.buf = buf
        self.file_size = file_size
        self.index = index
        self.recover = recover
        self.report: RecoveryReport | None = None

    # ------------------------------------------------------------------ a file with a chunk index
    def check_indexed(self, *, count: bool) -> tuple[RecoveryReport, list[int]]:
        """Walk the data section by the chunk index (every indexed chunk's record checked against
        its index entry; unreadable bytes skipped to the next indexed chunk), take the unchunked
        Schema/Channel/Metadata/Message records, check the data section's CRC and, when it fails,
        every chunk's CRC. ``count``: count the messages (no statistics) -- from the chunks'
        MessageIndex records; returns the chunks that have none (to be counted from their
        records)."""
        b = self.buf
        idx = self.index
        index = idx.chunks
        offsets = sorted(o for o in index if idx.data_start <= o < idx.data_end)
        report = RecoveryReport(True, self.file_size, self.file_size, len(index))
        unsupported = sorted({c.compression for c in index.values()} - set(COMPRESSIONS))
        if unsupported:
            raise unsupported_compression(unsupported[0])
        for o in sorted(set(index) - set(offsets)):
            report.problems.append(f"the chunk index points at byte {o}, outside the data section "
                                   f"({idx.data_start}-{idx.data_end}); that chunk is not read")
        end = idx.data_end
        layout = []
        suspect: dict[int, str] = {}
        data_crc = None
        data_end_pos = None
        pos = idx.data_start
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
                # no readable record here (or one that runs over the next indexed chunk): skip to
                # the next indexed chunk; every chunk starts at an indexed offset: none is in these
                report.problems.append(f"unreadable bytes {pos}-{nxt} between the indexed chunks (a "
                                       "damaged message index or metadata record, or a chunk the "
                                       "index does not list)")
                pos = nxt
                continue
            body = b[pos + 9:rec_end]
            try:
                if op == OP_MESSAGE:
                    if count:
                        idx.count_message(body)
                    layout.append((op, pos, body))
                elif op == OP_SCHEMA:
                    idx.add_schema(body)
                elif op == OP_CHANNEL:
                    idx.add_channel(body)
                elif op == OP_METADATA:
                    idx.add_metadata(body)
                elif op == OP_DATA_END and length >= 4:
                    data_end_pos = pos
                    (data_crc,) = U32.unpack_from(b, pos + 9)
            except MALFORMED:
                report.problems.append(f"malformed record (opcode 0x{op:02x}) at byte {pos}")
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
                chunk_records(body)
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
            per_channel = self.index_messages(ci.index_offsets)
            messages = (sum(per_channel.values()) if per_channel is not None else None)
            if not recovered:
                if not count:
                    idx.lose_messages(per_channel)
                idx.corrupt.add(cpos)
            report.damaged.append(DamagedChunk(cpos, ci.length, reason, ci.start, ci.end,
                                               messages, recovered))
        report.damaged.sort(key=lambda d: d.offset)
        report.complete_chunks = sum(1 for op, cpos, _ in layout
                                     if op == OP_CHUNK and cpos not in idx.corrupt)
        idx.layout = [r for r in layout if r[1] not in idx.corrupt]
        uncounted = []
        if count:   # no statistics: the chunks' messages from their MessageIndex records
            for op, cpos, _body in idx.layout:
                if op != OP_CHUNK:
                    continue
                ci = index[cpos]
                per_channel = self.index_messages(ci.index_offsets)
                if per_channel is None:
                    uncounted.append(cpos)
                else:
                    idx.count_indexed(per_channel, ci.start, ci.end)
        self.report = report
        return report, uncounted

    def _chunk_header_problem(self, pos: int, ci: ChunkInfo) -> str | None:
        b = self.buf
        if not ci.length or pos + ci.length > self.index.data_end:
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

    def index_messages(self, index_offsets: dict | None) -> dict | None:
        """{channel id: messages} of a chunk from its MessageIndex records (None: unreadable)."""
        if not index_offsets:
            return None
        out = {}
        for cid, off in index_offsets.items():
            if off + 9 + 6 > self.file_size:
                return None
            op, length = RECORD_HEADER.unpack_from(self.buf, off)
            if op != OP_MESSAGE_INDEX or length < 6:
                return None
            (n,) = U32.unpack_from(self.buf, off + 9 + 2)
            out[cid] = n // 16
        return out

    # ------------------------------------------------------------------ chunks read at open
    def inspect(self, offsets: list[int], *, count: bool, until_channels_known: bool) -> None:
        """Decompress chunks at open for their records: their messages counted (``count``) and
        their Schema/Channel records taken. ``until_channels_known``: stop once the index's
        channels are complete (and nothing is left to count). A damaged chunk is reported."""
        idx = self.index
        bodies = {pos: body for op, pos, body in idx.layout if op == OP_CHUNK}
        to_count = set(offsets) if count else set()
        known = not until_channels_known
        for pos in sorted(set(offsets) | (set(bodies) if until_channels_known else set())):
            if pos not in bodies or pos in idx.corrupt:
                continue
            if pos not in to_count:
                known = known or not idx.channels_incomplete()   # (channels are only added)
                if known:
                    continue
            try:
                idx.inspect_chunk(pos, bodies[pos], count=pos in to_count)
            except CorruptBagError as error:
                self._failed_at_open(pos, bodies[pos], str(error), counted=pos not in to_count)

    def _failed_at_open(self, pos: int, body, reason: str, counted: bool) -> None:
        """A chunk decompressed at open is damaged: reported, not read; its messages taken out of
        the counts when they were in (statistics, message index)."""
        idx = self.index
        idx.corrupt.add(pos)
        idx.layout = [r for r in idx.layout if r[1] != pos]
        ci = idx.chunks.get(pos)
        start, end_t = CHUNK_HEAD.unpack_from(body, 0)[:2]
        per_channel = self.index_messages(ci.index_offsets) if ci is not None else None
        if counted:
            idx.lose_messages(per_channel)
        self.report.damaged.append(DamagedChunk(
            pos, ci.length if ci is not None and ci.length else 9 + len(body), reason, start, end_t,
            None if per_channel is None else sum(per_channel.values())))
        self.report.damaged.sort(key=lambda d: d.offset)
        self.report.complete_chunks = max(0, self.report.complete_chunks - 1)

    # ------------------------------------------------------------------ found while reading
    def verify(self) -> RecoveryReport:
        """Decompress and CRC-check every chunk not verified yet (a file without a data-section
        CRC); damaged ones are added to the report and skipped from then on. Raises
        DamagedBagError for a new damaged chunk unless the reader recovers."""
        report = self.report
        if report.verified:
            return report
        for op, pos, body in list(self.index.layout):
            if op != OP_CHUNK or pos in self.index.corrupt:
                continue
            try:
                chunk_records(body)
            except CorruptBagError as error:
                self.chunk_failed(pos, body, str(error))
        report.verified = True
        return report

    def chunk_failed(self, pos: int, body, reason: str) -> DamagedChunk:
        """Record a chunk whose contents fail (CRC, decompression) found while reading; raise
        DamagedBagError unless recovering."""
        report = self.report
        idx = self.index
        idx.corrupt.add(pos)
        ci = idx.chunks.get(pos)
        if ci is not None:
            start, end_t, length = ci.start, ci.end, ci.length or 9 + len(body)
            per_channel = self.index_messages(ci.index_offsets)
        else:
            start, end_t = CHUNK_HEAD.unpack_from(body, 0)[:2]
            length, per_channel = 9 + len(body), None
        damaged = DamagedChunk(pos, length, reason, start, end_t,
                               None if per_channel is None else sum(per_channel.values()))
        if report.complete:   # the scan already left it out of the counts
            idx.lose_messages(per_channel)
        report.damaged.append(damaged)
        report.damaged.sort(key=lambda d: d.offset)
        report.complete_chunks = max(0, report.complete_chunks - 1)
        report.messages = idx.message_count
        if not self.recover:
            raise DamagedBagError(f"{self.path} is damaged: {report.damage_text()}; read the intact "
                                  "chunks with recovery (--recover)", report)
        return damaged

    # ------------------------------------------------------------------ scanning
    def _chunk_fields(self, pos: int, end: int):
        """(start_ns, end_ns, body_length) of a self-consistent chunk record at ``pos`` whose body
        (computed from its own fields: header, compression name, records size) fits before ``end``;
        None if there is none. The record's length field is not used (it may be damaged)."""
        b = self.buf
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
        op, length = RECORD_HEADER.unpack_from(self.buf, pos)
        return 0 < op <= MAX_OPCODE and pos + 9 + length <= end

    def _next_chunk(self, pos: int, end: int) -> int | None:
        """Resynchronise: the offset of the next intact-looking chunk record in [pos, end) (its
        length field agrees with its own fields), or None."""
        mm = self.mm
        b = self.buf
        while True:
            pos = mm.find(bytes((OP_CHUNK,)), pos, end)
            if pos < 0:
                return None
            fields = self._chunk_fields(pos, end)
            if fields is not None and pos + 9 <= end and \
                    RECORD_HEADER.unpack_from(b, pos)[1] == fields[2]:
                return pos
            pos += 1

    def _index_run_before(self, lo: int, stop: int) -> dict | None:
        """{channel id: messages} of the MessageIndex records that end exactly at ``stop`` (found
        by trying every 0x07 byte in the 64 KiB before it), None if there are none."""
        mm = self.mm
        b = self.buf
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

    def scan(self, reason: str, data_end: int | None = None) -> RecoveryReport:
        """Read the data section from the start without the summary: every complete chunk is
        decompressed and CRC-checked; damaged bytes in the middle are skipped by
        resynchronising on the next self-consistent chunk record; the end of the readable data
        is where no further chunk can be found."""
        idx = self.index
        report = RecoveryReport(False, self.file_size, idx.data_start, 0, reason=reason)
        chunk_index = dict(idx.chunks)
        idx.chunks.clear()
        idx.reset_counts()
        idx.corrupt.clear()
        end = self.file_size if data_end is None else data_end
        b = self.buf
        layout = []
        last = None          # the last damaged chunk: the MessageIndex records after it count for it
        pos = idx.data_start
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
            try:
                if op == OP_SCHEMA:
                    idx.add_schema(body)
                elif op == OP_CHANNEL:
                    idx.add_channel(body)
                elif op == OP_METADATA:
                    idx.add_metadata(body)
                elif op == OP_MESSAGE:
                    idx.count_message(body)
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
            except MALFORMED:
                report.reason += f"; malformed record at byte {pos}"
                break
            if op != OP_MESSAGE_INDEX:
                last = None
            pos = rec_end
            report.intact_bytes = pos
            if op in (OP_DATA_END, OP_FOOTER):
                break
        idx.data_end = report.intact_bytes
        report.messages = idx.message_count
        report.verified = True          # every chunk was decompressed and its CRC checked
        idx.layout = layout
        self.report = report
        return report

    def _scan_chunk(self, report, layout, chunk_index, pos, body, header_problem: str):
        """Decompress, CRC-check and count one chunk found by the scan; returns its DamagedChunk
        (None when intact)."""
        idx = self.index
        start, end_t = CHUNK_HEAD.unpack_from(body, 0)[:2]
        try:
            plain = list(iter_records(chunk_records(body)))
        except CorruptBagError as error:
            reason = "; ".join(r for r in (header_problem, str(error)) if r)
            damaged = DamagedChunk(pos, 9 + len(body), reason, start, end_t)  # messages: its index
            report.damaged.append(damaged)
            idx.corrupt.add(pos)
            return damaged
        messages = [rbody for rop, _rpos, rbody in plain if rop == OP_MESSAGE]
        try:
            for rbody in messages:
                MESSAGE_HEAD.unpack_from(rbody, 0)
            for rop, _rpos, rbody in plain:
                if rop == OP_SCHEMA:
                    idx.add_schema(rbody)
                elif rop == OP_CHANNEL:
                    idx.add_channel(rbody)
        except MALFORMED as error:   # CRC-valid, but not the records it should hold
            damaged = DamagedChunk(pos, 9 + len(body), f"malformed record inside the chunk: {error}",
                                   start, end_t)
            report.damaged.append(damaged)
            idx.corrupt.add(pos)
            return damaged
        chans = {idx.count_message(rbody) for rbody in messages}
        n = len(messages)
        known = chunk_index.get(pos)
        idx.chunks[pos] = known or ChunkInfo(pos, start, end_t, frozenset(chans), 9 + len(body))
        layout.append((OP_CHUNK, pos, body))
        report.complete_chunks += 1
        if header_problem:
            report.damaged.append(DamagedChunk(pos, 9 + len(body), header_problem, start, end_t, n,
                                               True))
        return None
