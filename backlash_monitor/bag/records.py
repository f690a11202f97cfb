"""MCAP records: the opcodes, every record's fields, and the functions that build them (writer.py)
and parse them (summary.py, index.py, integrity.py, reader.py). The format lives here only.

Spec: https://mcap.dev/spec (MCAP v0). A file is the magic, a Header record, the data section
(Schema, Channel, Message, Chunk + MessageIndex, Attachment, Metadata records, ended by DataEnd),
an optional summary section (Schema, Channel, Statistics, ChunkIndex, AttachmentIndex,
MetadataIndex, SummaryOffset records), a Footer and the magic again. Every record is
``opcode:uint8 length:uint64 body``; integers are little endian; a string is ``uint32 length +
UTF-8``, bytes ``uint32 length + bytes``, a map ``uint32 byte length + entries``. A chunk's records
(Schema, Channel, Message) are compressed together with "" (none), "zstd" or "lz4".
"""
from __future__ import annotations

import struct
import threading
from typing import NamedTuple

import zstandard
import lz4.frame

from .errors import CorruptBagError, UnsupportedBagError

try:  # ISA-L's CRC-32 (SIMD): the same checksum as zlib.crc32, ~10x faster (21 vs 284 us per MiB)
    from isal.isal_zlib import crc32
except ImportError:  # pragma: no cover - isal is in requirements.txt; zlib gives the same values
    from zlib import crc32

MAGIC = b"\x89MCAP0\r\n"

OP_HEADER = 0x01
OP_FOOTER = 0x02
OP_SCHEMA = 0x03
OP_CHANNEL = 0x04
OP_MESSAGE = 0x05
OP_CHUNK = 0x06
OP_MESSAGE_INDEX = 0x07
OP_CHUNK_INDEX = 0x08
OP_ATTACHMENT = 0x09
OP_ATTACHMENT_INDEX = 0x0A
OP_STATISTICS = 0x0B
OP_METADATA = 0x0C
OP_METADATA_INDEX = 0x0D
OP_SUMMARY_OFFSET = 0x0E
OP_DATA_END = 0x0F
MAX_OPCODE = 0x0F             # the spec's records; 0x80-0xFF are private records (skipped)

COMPRESSIONS = {"": "none", "zstd": "zstd", "lz4": "lz4"}   # chunk compression -> its name

# this package's Metadata record with the writer's chunk limits (writer.py writes it first: a reader
# of a killed writer's file can bound what the lost open chunk held)
WRITER_METADATA = "backlash_monitor.writer"

RECORD_HEADER = struct.Struct("<BQ")         # opcode, body length
U16 = struct.Struct("<H")
U32 = struct.Struct("<I")
U64 = struct.Struct("<Q")
MESSAGE_HEAD = struct.Struct("<HIQQ")        # channel_id, sequence, log_time, publish_time
CHUNK_HEAD = struct.Struct("<QQQI")          # start, end, uncompressed_size, uncompressed_crc
CHUNK_CRC_AT = 9 + 24                        # the uncompressed_crc field, from the record start
FOOTER_BODY = struct.Struct("<QQI")          # summary_start, summary_offset_start, summary_crc
FOOTER_RECORD_LEN = 1 + 8 + FOOTER_BODY.size  # 29 bytes, then the 8-byte magic
DATA_END_RECORD_LEN = 1 + 8 + 4

# ----------------------------------------------------------------------------------------------
# building (writer.py)


def pstr(s: str) -> bytes:
    b = s.encode("utf-8")
    return U32.pack(len(b)) + b


def pbytes(b: bytes) -> bytes:
    return U32.pack(len(b)) + b


def pmap_str(d: dict[str, str]) -> bytes:
    body = b"".join(pstr(k) + pstr(v) for k, v in d.items())
    return U32.pack(len(body)) + body


def record(op: int, body: bytes) -> bytes:
    return RECORD_HEADER.pack(op, len(body)) + body


def header_record(profile: str, library: str) -> bytes:
    return record(OP_HEADER, pstr(profile) + pstr(library))


def schema_record(schema_id: int, name: str, encoding: str, data: bytes) -> bytes:
    return record(OP_SCHEMA, U16.pack(schema_id) + pstr(name) + pstr(encoding) + pbytes(data))


def channel_record(channel_id: int, schema_id: int, topic: str, message_encoding: str,
                   metadata: dict[str, str]) -> bytes:
    return record(OP_CHANNEL, U16.pack(channel_id) + U16.pack(schema_id) + pstr(topic)
                  + pstr(message_encoding) + pmap_str(metadata))


def chunk_record_head(start_ns: int, end_ns: int, uncompressed_size: int, uncompressed_crc: int,
                      compression: str, compressed_size: int) -> bytes:
    """The chunk record up to its records (which follow: ``compressed_size`` bytes)."""
    body_head = (CHUNK_HEAD.pack(start_ns, end_ns, uncompressed_size, uncompressed_crc)
                 + pstr(compression) + U64.pack(compressed_size))
    return RECORD_HEADER.pack(OP_CHUNK, len(body_head) + compressed_size) + body_head


def message_index_record(channel_id: int, entries: bytes) -> bytes:
    """``entries``: packed (log_time, offset) uint64 pairs."""
    return record(OP_MESSAGE_INDEX, U16.pack(channel_id) + pbytes(entries))


def metadata_record(name: str, metadata: dict[str, str]) -> bytes:
    return record(OP_METADATA, pstr(name) + pmap_str(metadata))


def data_end_record(data_section_crc: int) -> bytes:
    return record(OP_DATA_END, U32.pack(data_section_crc))


def statistics_record(s: "Statistics") -> bytes:
    counts = b"".join(U16.pack(c) + U64.pack(n) for c, n in sorted(s.channel_message_counts.items()))
    return record(OP_STATISTICS, U64.pack(s.message_count) + U16.pack(s.schema_count)
                  + U32.pack(s.channel_count) + U32.pack(s.attachment_count)
                  + U32.pack(s.metadata_count) + U32.pack(s.chunk_count) + U64.pack(s.start_ns)
                  + U64.pack(s.end_ns) + pbytes(counts))


def chunk_index_record(ci: "ChunkIndex") -> bytes:
    offsets = b"".join(U16.pack(c) + U64.pack(o)
                       for c, o in sorted(ci.message_index_offsets.items()))
    return record(OP_CHUNK_INDEX, U64.pack(ci.start_ns) + U64.pack(ci.end_ns) + U64.pack(ci.offset)
                  + U64.pack(ci.length) + pbytes(offsets) + U64.pack(ci.message_index_length)
                  + pstr(ci.compression) + U64.pack(ci.compressed_size)
                  + U64.pack(ci.uncompressed_size))


def metadata_index_record(mi: "MetadataIndex") -> bytes:
    return record(OP_METADATA_INDEX, U64.pack(mi.offset) + U64.pack(mi.length) + pstr(mi.name))


def summary_offset_record(group_opcode: int, group_start: int, group_length: int) -> bytes:
    return record(OP_SUMMARY_OFFSET, bytes((group_opcode,)) + U64.pack(group_start)
                  + U64.pack(group_length))


def footer_head(summary_start: int, summary_offset_start: int) -> bytes:
    """The footer record up to its summary_crc field (which the summary CRC covers)."""
    return RECORD_HEADER.pack(OP_FOOTER, FOOTER_BODY.size) + U64.pack(summary_start) + U64.pack(
        summary_offset_start)


# ----------------------------------------------------------------------------------------------
# the records' fields (parsed; built by the *_record functions)


class Header(NamedTuple):
    profile: str
    library: str


class Footer(NamedTuple):
    summary_start: int           # 0: no summary section
    summary_offset_start: int    # 0: no summary offsets
    summary_crc: int             # 0: not computed


class Schema(NamedTuple):
    id: int
    name: str
    encoding: str
    data: bytes


class Channel(NamedTuple):
    id: int
    schema_id: int               # 0: no schema
    topic: str
    message_encoding: str
    metadata: dict


class ChunkHeader(NamedTuple):
    start_ns: int                # the chunk's messages' log-time range
    end_ns: int
    uncompressed_size: int
    uncompressed_crc: int        # 0: not computed
    compression: str
    records_at: int              # offset of the (compressed) records in the chunk record's body
    records_size: int


class ChunkIndex(NamedTuple):
    start_ns: int
    end_ns: int
    offset: int                  # chunk record's offset in the file
    length: int                  # chunk record's length (opcode and length field included)
    message_index_offsets: dict  # channel id -> offset of its MessageIndex record
    message_index_length: int
    compression: str
    compressed_size: int
    uncompressed_size: int


class Statistics(NamedTuple):
    message_count: int
    schema_count: int
    channel_count: int
    attachment_count: int
    metadata_count: int
    chunk_count: int
    start_ns: int
    end_ns: int
    channel_message_counts: dict  # channel id -> messages


class MetadataIndex(NamedTuple):
    offset: int
    length: int
    name: str


class Cursor:
    """Reads MCAP primitive fields from a bytes-like object."""

    __slots__ = ("buf", "pos")

    def __init__(self, buf, pos: int = 0):
        self.buf = buf
        self.pos = pos

    def u8(self) -> int:
        v = self.buf[self.pos]
        self.pos += 1
        return v

    def u16(self) -> int:
        (v,) = U16.unpack_from(self.buf, self.pos)
        self.pos += 2
        return v

    def u32(self) -> int:
        (v,) = U32.unpack_from(self.buf, self.pos)
        self.pos += 4
        return v

    def u64(self) -> int:
        (v,) = U64.unpack_from(self.buf, self.pos)
        self.pos += 8
        return v

    def raw(self, n: int) -> bytes:
        if self.pos + n > len(self.buf):
            raise ValueError("field runs past the end of its record")
        b = bytes(self.buf[self.pos:self.pos + n])
        self.pos += n
        return b

    def string(self) -> str:
        return self.raw(self.u32()).decode("utf-8")

    def bytes_(self) -> bytes:
        return self.raw(self.u32())

    def map_str(self) -> dict[str, str]:
        end = self.pos + self.u32()
        if end > len(self.buf):
            raise ValueError("map runs past the end of its record")
        out = {}
        while self.pos < end:
            k = self.string()
            out[k] = self.string()
        return out

    def map_u16_u64(self) -> dict[int, int]:
        end = self.pos + self.u32()
        if end > len(self.buf):
            raise ValueError("map runs past the end of its record")
        out = {}
        while self.pos < end:
            k = self.u16()
            out[k] = self.u64()
        return out


# Parsers: each takes a record's body and raises ValueError, IndexError or struct.error (all
# `MALFORMED`) when the body does not hold its fields.
MALFORMED = (ValueError, IndexError, UnicodeDecodeError, struct.error)


def parse_header(body) -> Header:
    c = Cursor(body)
    return Header(c.string(), c.string())


def parse_footer(body) -> Footer:
    return Footer(*FOOTER_BODY.unpack_from(body, 0))


def parse_schema(body) -> Schema:
    c = Cursor(body)
    return Schema(c.u16(), c.string(), c.string(), c.bytes_())


def parse_channel(body) -> Channel:
    c = Cursor(body)
    return Channel(c.u16(), c.u16(), c.string(), c.string(), c.map_str())


def parse_metadata(body) -> tuple[str, dict[str, str]]:
    c = Cursor(body)
    return c.string(), c.map_str()


def parse_statistics(body) -> Statistics:
    c = Cursor(body)
    return Statistics(c.u64(), c.u16(), c.u32(), c.u32(), c.u32(), c.u32(), c.u64(), c.u64(),
                      c.map_u16_u64())


def parse_chunk_index(body) -> ChunkIndex:
    c = Cursor(body)
    return ChunkIndex(c.u64(), c.u64(), c.u64(), c.u64(), c.map_u16_u64(), c.u64(), c.string(),
                      c.u64(), c.u64())


def parse_metadata_index(body) -> MetadataIndex:
    c = Cursor(body)
    return MetadataIndex(c.u64(), c.u64(), c.string())


def parse_chunk_header(body) -> ChunkHeader:
    """The chunk's fields before its records; CorruptBagError when its records do not end where
    the record does (a damaged length field)."""
    start, end, usize, ucrc = CHUNK_HEAD.unpack_from(body, 0)
    c = Cursor(body, CHUNK_HEAD.size)
    compression = c.string()
    size = c.u64()
    if c.pos + size != len(body):
        raise CorruptBagError(f"chunk records ({size} bytes) do not end where the chunk record "
                              f"does ({len(body) - c.pos} bytes): a damaged length field")
    return ChunkHeader(start, end, usize, ucrc, compression, c.pos, size)


def message_index_count(body) -> tuple[int, int]:
    """(channel id, messages) of a MessageIndex record's body."""
    (cid,) = U16.unpack_from(body, 0)
    (n,) = U32.unpack_from(body, 2)
    if 6 + n > len(body):
        raise ValueError("message index runs past its record")
    return cid, n // 16


def chunk_compression_name(compression: str) -> str:
    """The name of a chunk compression for messages ("none" for "")."""
    return COMPRESSIONS.get(compression, repr(compression))


def unsupported_compression(compression: str) -> UnsupportedBagError:
    return UnsupportedBagError(
        f"chunk compression {compression!r} is not supported (supported: none, zstd, lz4)")


# ----------------------------------------------------------------------------------------------
# chunks

_THREAD_STATE = threading.local()


def _zstd_decompressor():
    """This thread's zstd decompressor (a ZstdDecompressor must not be shared between threads)."""
    d = getattr(_THREAD_STATE, "zstd", None)
    if d is None:
        d = _THREAD_STATE.zstd = zstandard.ZstdDecompressor()
    return d


def chunk_records(body) -> memoryview:
    """The records of a chunk (the chunk record's body): decompressed, size and CRC checked.
    CorruptBagError for a damaged chunk, UnsupportedBagError for an unknown compression."""
    head = parse_chunk_header(body)
    data = body[head.records_at:head.records_at + head.records_size]
    compression = head.compression
    if compression not in COMPRESSIONS:
        raise unsupported_compression(compression)
    try:
        if compression == "":
            out = data
        elif compression == "zstd":
            out = _zstd_decompressor().decompress(data, max_output_size=head.uncompressed_size)
        else:
            out = lz4.frame.decompress(bytes(data))
    except Exception as exc:  # noqa: BLE001 - zstd/lz4 errors
        raise CorruptBagError(f"chunk does not decompress: {exc}") from None
    if len(out) != head.uncompressed_size:
        raise CorruptBagError(f"chunk decompresses to {len(out)} bytes, header says "
                              f"{head.uncompressed_size}")
    if head.uncompressed_crc and crc32(out) != head.uncompressed_crc:
        raise CorruptBagError("chunk CRC mismatch")
    return memoryview(out)


def iter_records(buf):
    """(opcode, offset, body) of the records in ``buf`` (a chunk's records); CorruptBagError when
    one runs past the end."""
    pos = 0
    n = len(buf)
    while pos + 9 <= n:
        op, length = RECORD_HEADER.unpack_from(buf, pos)
        end = pos + 9 + length
        if end > n:
            raise CorruptBagError(f"record inside a chunk runs past the chunk (at {pos})")
        yield op, pos, buf[pos + 9:end]
        pos = end
    if pos != n:
        raise CorruptBagError(f"record header inside a chunk cut off by the chunk's end (at {pos})")


def message_bodies(buf) -> list:
    """Bodies of the Message records in a chunk's records, in order."""
    return [body for op, _pos, body in iter_records(buf) if op == OP_MESSAGE]
