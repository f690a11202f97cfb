"""What a reader knows about a bag once it is open: schemas, channels, chunks, message counts and
the records to read, and how a valid file's layout gives them.

Every part of an MCAP summary is optional, so the index is built from what the file has:

- the summary's repeated schemas and channels, else the Schema/Channel records of the data
  section -- unchunked, or inside the chunks (then the chunks are decompressed at open until every
  channel is known: the statistics' channel count says when);
- the statistics' counts and time range, else the MessageIndex records after each chunk (counted
  without decompressing), else the chunks' own records;
- the chunk index, else a walk over the data section's records by their length fields
  (`walk_data`: a file written without a summary, `noSummary`, or without a chunk index).

integrity.py checks the chunks against the index and scans damaged files; reader.py reads.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from operator import itemgetter

import numpy as np

from .errors import CorruptBagError
from .records import (COMPRESSIONS, MALFORMED, MESSAGE_HEAD, OP_CHANNEL, OP_CHUNK, OP_DATA_END,
                      OP_MESSAGE, OP_MESSAGE_INDEX, OP_METADATA, OP_SCHEMA, RECORD_HEADER, U32,
                      Channel, Schema, Statistics, chunk_records, iter_records, message_index_count,
                      parse_channel, parse_chunk_header, parse_metadata, parse_schema,
                      unsupported_compression)


@dataclass
class ChunkInfo:
    """A chunk of the data section (from the chunk index, or found by a walk or a scan)."""
    offset: int
    start: int                       # log-time range of its messages [ns]
    end: int
    channels: frozenset | None       # channel ids of its messages (None: unknown)
    length: int = 0                  # record length (opcode and length field included; 0: unknown)
    index_offsets: dict | None = None  # channel id -> offset of its MessageIndex record
    compression: str = ""


@dataclass
class BagIndex:
    data_start: int = 0
    data_end: int = 0
    schemas: dict[int, Schema] = field(default_factory=dict)
    channels: dict[int, Channel] = field(default_factory=dict)
    metadata: dict[str, dict[str, str]] = field(default_factory=dict)
    chunks: dict[int, ChunkInfo] = field(default_factory=dict)
    statistics: Statistics | None = None
    summary_channels: bool = False   # the summary repeats the channels
    counts: dict[int, int] = field(default_factory=dict)   # channel id -> messages
    message_count: int = 0
    start: int | None = None         # log-time range of the messages [ns]
    end: int | None = None
    layout: list = field(default_factory=list)   # (opcode, offset, body): chunks, messages
    corrupt: set[int] = field(default_factory=set)   # offsets of damaged chunks (not read)
    # (layout, its message_channels): kept while ``layout`` is the same list
    _message_channels: tuple | None = field(default=None, repr=False, compare=False)

    # ------------------------------------------------------------------ records
    def add_schema(self, body) -> None:
        s = parse_schema(body)
        self.schemas[s.id] = s

    def add_channel(self, body) -> None:
        c = parse_channel(body)
        self.channels[c.id] = c

    def add_metadata(self, body) -> None:
        name, values = parse_metadata(body)
        self.metadata[name] = values

    def from_summary(self, summary, buf, file_size: int) -> None:
        """What the summary section has: schemas, channels, statistics, chunk index, and the
        Metadata records its metadata index points at."""
        self.schemas.update(summary.schemas)
        self.channels.update(summary.channels)
        self.summary_channels = bool(summary.channels)
        if summary.statistics is not None:
            self.use_statistics(summary.statistics)
        for ci in summary.chunk_indexes:
            self.chunks[ci.offset] = ChunkInfo(
                ci.offset, ci.start_ns, ci.end_ns,
                frozenset(ci.message_index_offsets) if ci.message_index_offsets else None,
                ci.length, dict(ci.message_index_offsets), ci.compression)
        for mi in summary.metadata_indexes:
            if mi.offset + 9 <= file_size and mi.offset + mi.length <= file_size:
                op, length = RECORD_HEADER.unpack_from(buf, mi.offset)
                if op == OP_METADATA and mi.offset + 9 + length <= file_size:
                    try:
                        name, values = parse_metadata(buf[mi.offset + 9:mi.offset + 9 + length])
                    except MALFORMED:
                        continue   # the data-section walk meets the record again
                    self.metadata[name or mi.name] = values

    def use_statistics(self, stats: Statistics) -> None:
        self.statistics = stats
        self.message_count = stats.message_count
        self.counts = dict(stats.channel_message_counts)
        if stats.message_count:
            self.start, self.end = stats.start_ns, stats.end_ns

    # ------------------------------------------------------------------ counts
    def reset_counts(self) -> None:
        self.counts.clear()
        self.message_count = 0
        self.start = self.end = None

    def count_message(self, body) -> int:
        """Count one Message record (its body); returns its channel id."""
        cid, _seq, log_time, _pub = MESSAGE_HEAD.unpack_from(body, 0)
        self.counts[cid] = self.counts.get(cid, 0) + 1
        self.message_count += 1
        if self.start is None or log_time < self.start:
            self.start = log_time
        if self.end is None or log_time > self.end:
            self.end = log_time
        return cid

    def count_indexed(self, per_channel: dict[int, int], start: int, end: int) -> None:
        """Count a chunk's messages from its MessageIndex records (its log-time range given)."""
        n = 0
        for cid, k in per_channel.items():
            self.counts[cid] = self.counts.get(cid, 0) + k
            n += k
        if n:
            self.message_count += n
            self.start = start if self.start is None else min(self.start, start)
            self.end = end if self.end is None else max(self.end, end)

    def lose_messages(self, per_channel: dict | None) -> int | None:
        """Take the messages of a skipped chunk out of the counts; None when unknown."""
        if per_channel is None:
            return None
        for cid, n in per_channel.items():
            if cid in self.counts:
                self.counts[cid] = max(0, self.counts[cid] - n)
        total = sum(per_channel.values())
        self.message_count = max(0, self.message_count - total)
        return total

    # ------------------------------------------------------------------ records to read
    def message_channels(self, buf) -> np.ndarray:
        """The channel id of every unchunked Message record of ``layout`` (int32, one per layout
        entry; -1 for a chunk, and for a message too short to hold its head: that one is read, and
        its error named, as before). Taken from the file ``buf`` at each record's offset + 9 (the
        body's first field) for all records at once, so a reader can pass over the messages of
        other topics without a Python step per message: a file written without chunks holds every
        message as a record of its own (2501 in bench/bags.py's 10 s bag; analyze reads 1500 of
        them and, before those, the one true-width message). Kept while ``layout`` is the same
        list (integrity.py replaces it when it drops a damaged chunk)."""
        return self.record_columns(buf)[0]

    def record_columns(self, buf) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(:meth:`message_channels`, each layout record's offset in the file (int64), its body's
        size (int64)): the layout as columns, taken once per layout (as message_channels)."""
        layout = self.layout
        kept = self._message_channels
        if kept is not None and kept[0] is layout and kept[1].size == len(layout):
            return kept[1:]
        n = len(layout)
        ops = np.fromiter(map(itemgetter(0), layout), dtype=np.uint8, count=n)
        sizes = np.fromiter(map(len, map(itemgetter(2), layout)), dtype=np.int64, count=n)
        offsets = np.fromiter(map(itemgetter(1), layout), dtype=np.int64, count=n)
        heads = (ops == OP_MESSAGE) & (sizes >= MESSAGE_HEAD.size)
        channels = np.full(n, -1, dtype=np.int32)
        if heads.any():
            at = offsets[heads] + 9
            file_bytes = np.frombuffer(buf, dtype=np.uint8)
            channels[heads] = file_bytes[at] | (file_bytes[at + 1].astype(np.int32) << 8)
            del file_bytes   # no export of the file's map is left behind (the reader unmaps it)
        self._message_channels = (layout, channels, offsets, sizes)
        return channels, offsets, sizes

    # ------------------------------------------------------------------ channels
    def channels_incomplete(self) -> str:
        """Why the known channels may not be all of the file's ('' when they are): messages on
        channel ids without a Channel record, channels whose schema is missing, fewer channels
        than the statistics count, or chunks whose channels only their own records say (no
        message index) while the summary does not repeat the channels."""
        needed = {c for c, n in self.counts.items() if n}
        unread = False
        for info in self.chunks.values():
            if info.channels is not None:
                needed |= info.channels
            elif info.offset not in self.corrupt:
                unread = True
        unknown = sorted(needed - set(self.channels))
        if unknown:
            return f"messages on channel id(s) {unknown} that no Channel record seen so far defines"
        schemas = sorted({c.schema_id for c in self.channels.values()
                          if c.schema_id and c.schema_id not in self.schemas})
        if schemas:
            return f"channels use schema id(s) {schemas} that no Schema record seen so far defines"
        if self.statistics is not None:
            if len(self.channels) < self.statistics.channel_count:
                return (f"{self.statistics.channel_count} channels in the statistics, "
                        f"{len(self.channels)} known")
        elif unread and not self.summary_channels:
            return "chunks whose channels the summary does not repeat"
        return ""

    def unknown_channels(self) -> dict[int, int]:
        """{channel id: messages} of messages on channels no Channel record defines."""
        return {c: n for c, n in self.counts.items() if n and c not in self.channels}

    def inspect_chunk(self, offset: int, body, *, count: bool) -> None:
        """Decompress a chunk (CorruptBagError when damaged) and take its Schema and Channel
        records; ``count``: count its messages too (and learn its channels)."""
        records = chunk_records(body)
        channels = set()
        for op, _pos, rbody in iter_records(records):
            try:
                if op == OP_MESSAGE and count:
                    channels.add(self.count_message(rbody))
                elif op == OP_SCHEMA:
                    self.add_schema(rbody)
                elif op == OP_CHANNEL:
                    self.add_channel(rbody)
            except MALFORMED as exc:
                raise CorruptBagError(f"malformed record inside the chunk: {exc}") from None
        info = self.chunks.get(offset)
        if count and info is not None and info.channels is None:
            info.channels = frozenset(channels)


@dataclass
class Walk:
    """A data section walked by its records' length fields."""
    uncounted: list[int] = field(default_factory=list)   # chunks without MessageIndex records
    data_crc: int = 0                # DataEnd's CRC (0: not computed)
    data_end_at: int | None = None   # offset of the DataEnd record


def walk_data(buf, index: BagIndex, *, count: bool) -> Walk | None:
    """Walk a complete file's data section (``index.data_start`` to ``index.data_end``) record by
    record: chunks (their header: time range, compression; their MessageIndex records: channels and
    counts), unchunked Schema/Channel/Metadata/Message records. ``count``: count messages (no
    statistics). None when a record does not fit or does not parse: the file is damaged
    (integrity.py's scan takes over). UnsupportedBagError for a chunk compression it cannot read."""
    walk = Walk()
    layout = []
    pos, end = index.data_start, index.data_end
    last = None            # the chunk whose MessageIndex records may follow
    last_counts = None
    chunks = {}
    while pos < end:
        if pos + 9 > end:
            return None
        op, length = RECORD_HEADER.unpack_from(buf, pos)
        rec_end = pos + 9 + length
        if op == 0 or rec_end > end:
            return None
        body = buf[pos + 9:rec_end]
        try:
            if op == OP_MESSAGE_INDEX:
                if last is not None:
                    cid, n = message_index_count(body)
                    last.index_offsets[cid] = pos
                    last_counts[cid] = last_counts.get(cid, 0) + n
                pos = rec_end
                continue
            if last is not None:
                _close_chunk(index, walk, last, last_counts, count)
                last = None
            if op == OP_CHUNK:
                head = parse_chunk_header(body)
                if head.compression not in COMPRESSIONS:
                    raise unsupported_compression(head.compression)
                last = chunks[pos] = ChunkInfo(pos, head.start_ns, head.end_ns, None, 9 + length,
                                               {}, head.compression)
                last_counts = {}
                layout.append((OP_CHUNK, pos, body))
            elif op == OP_MESSAGE:
                if not count:   # the messages up to the next other record, in a loop of their own
                    pos = _message_run(buf, pos, end, layout)
                    if pos is None:
                        return None
                    continue
                index.count_message(body)
                layout.append((OP_MESSAGE, pos, body))
            elif op == OP_SCHEMA:
                index.add_schema(body)
            elif op == OP_CHANNEL:
                index.add_channel(body)
            elif op == OP_METADATA:
                index.add_metadata(body)
            elif op == OP_DATA_END:
                (walk.data_crc,) = U32.unpack_from(body, 0)
                walk.data_end_at = pos
                break
        except (CorruptBagError, *MALFORMED):
            return None
        pos = rec_end
    if last is not None:
        _close_chunk(index, walk, last, last_counts, count)
    index.chunks.update(chunks)
    index.layout = layout
    return walk


def _message_run(buf, pos: int, end: int, layout: list) -> int | None:
    """walk_data's step over consecutive unchunked Message records from ``pos`` (one starts there,
    it fits): each added to ``layout`` as the walk adds one, with only what the walk checks of it
    (it fits before ``end``, its body holds the message head). Returns the offset of the first
    other record (or of a header that does not fit: the walk decides), None when a message does
    not fit or is too short (damaged: the walk gives up). A file written without chunks is all
    such records (2501 in bench/bags.py's 10 s bag): one short loop each instead of the walk's."""
    unpack = RECORD_HEADER.unpack_from
    append = layout.append
    head = MESSAGE_HEAD.size
    while True:
        op, length = unpack(buf, pos)
        if op != OP_MESSAGE:
            return pos
        rec_end = pos + 9 + length
        if rec_end > end or length < head:
            return None
        append((OP_MESSAGE, pos, buf[pos + 9:rec_end]))
        pos = rec_end
        if pos + 9 > end:
            return pos


def _close_chunk(index: BagIndex, walk: Walk, info: ChunkInfo, counts: dict, count: bool) -> None:
    if info.index_offsets:
        info.channels = frozenset(info.index_offsets)
        if count:
            index.count_indexed(counts, info.start, info.end)
    elif count:
        walk.uncounted.append(info.offset)
