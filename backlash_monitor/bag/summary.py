"""The end of an MCAP file: its Footer and summary section (records.py parses each record).

`read_footer` says whether the file ends with a footer and whether it has a summary; a valid file
may have none (rosbag2's `noSummary`: the footer's summary_start is 0). `read_summary` parses the
summary section's records into a `Summary`: repeated schemas and channels, statistics, chunk and
metadata indexes -- each of them optional in a valid file.
"""
from __future__ import annotations

from dataclasses import dataclass, field

from .records import (FOOTER_BODY, FOOTER_RECORD_LEN, MAGIC, MALFORMED, OP_ATTACHMENT_INDEX,
                      OP_CHANNEL, OP_CHUNK_INDEX, OP_FOOTER, OP_METADATA_INDEX, OP_SCHEMA,
                      OP_STATISTICS, OP_SUMMARY_OFFSET, RECORD_HEADER, Channel, ChunkIndex, Footer,
                      MetadataIndex, Schema, Statistics, crc32, parse_channel, parse_chunk_index,
                      parse_footer, parse_metadata_index, parse_schema, parse_statistics)


@dataclass
class FooterState:
    """What the end of the file says. ``footer`` is None when the file does not end with a valid
    footer (``problem`` says why: a killed writer, a damaged footer or summary)."""
    footer: Footer | None
    footer_at: int               # offset of the footer record (file size when there is none)
    problem: str = ""

    @property
    def has_summary(self) -> bool:
        return self.footer is not None and self.footer.summary_start != 0


@dataclass
class Summary:
    schemas: dict[int, Schema] = field(default_factory=dict)
    channels: dict[int, Channel] = field(default_factory=dict)
    statistics: Statistics | None = None
    chunk_indexes: list[ChunkIndex] = field(default_factory=list)
    metadata_indexes: list[MetadataIndex] = field(default_factory=list)
    attachment_indexes: int = 0
    summary_offsets: int = 0


def read_footer(buf, file_size: int, data_start: int) -> FooterState:
    """The footer and, when it has a summary, the summary's CRC and bounds checked."""
    if file_size < data_start + FOOTER_RECORD_LEN + 8 or bytes(buf[file_size - 8:]) != MAGIC:
        return FooterState(None, file_size, "no footer (file ends without the closing MCAP magic)")
    fpos = file_size - 8 - FOOTER_RECORD_LEN
    op, length = RECORD_HEADER.unpack_from(buf, fpos)
    if op != OP_FOOTER or length != FOOTER_BODY.size:
        return FooterState(None, file_size, "invalid footer record")
    footer = parse_footer(buf[fpos + 9:fpos + 9 + length])
    if footer.summary_start == 0:   # a valid file without a summary section
        return FooterState(footer, fpos)
    if not data_start <= footer.summary_start <= fpos:
        return FooterState(None, file_size, "footer points outside the file")
    if footer.summary_offset_start and not footer.summary_start <= footer.summary_offset_start <= fpos:
        return FooterState(None, file_size, "footer's summary offset points outside the summary")
    # the summary CRC covers the summary through the footer's two offsets
    if footer.summary_crc and crc32(buf[footer.summary_start:fpos + 9 + 16]) != footer.summary_crc:
        return FooterState(None, file_size, "summary section CRC mismatch (the summary is damaged)")
    return FooterState(footer, fpos)


def read_summary(buf, state: FooterState) -> Summary:
    """The summary section's records. ValueError naming the problem when it is unreadable."""
    summary = Summary()
    pos = state.footer.summary_start
    end = state.footer_at
    while pos < end:
        if pos + 9 > end:
            raise ValueError("summary record header runs past the summary section")
        op, length = RECORD_HEADER.unpack_from(buf, pos)
        if pos + 9 + length > end:
            raise ValueError("summary record runs past the summary section")
        body = buf[pos + 9:pos + 9 + length]
        try:
            if op == OP_SCHEMA:
                s = parse_schema(body)
                summary.schemas[s.id] = s
            elif op == OP_CHANNEL:
                c = parse_channel(body)
                summary.channels[c.id] = c
            elif op == OP_STATISTICS:
                summary.statistics = parse_statistics(body)
            elif op == OP_CHUNK_INDEX:
                summary.chunk_indexes.append(parse_chunk_index(body))
            elif op == OP_METADATA_INDEX:
                summary.metadata_indexes.append(parse_metadata_index(body))
            elif op == OP_ATTACHMENT_INDEX:
                summary.attachment_indexes += 1
            elif op == OP_SUMMARY_OFFSET:
                summary.summary_offsets += 1
        except MALFORMED as exc:
            raise ValueError(f"record 0x{op:02x} at byte {pos}: {exc}") from None
        pos += 9 + length
    return summary
