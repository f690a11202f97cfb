"""Damage injected into MCAP files, as disks, copies and killed writers damage them: used by the
tests (test/bag/test_bag_damage.py) and the reliability bench (bench/_reliability/bags.py).

Each function takes the file's bytes (and the layout of the intact file, `chunk_layout`) and returns
damaged bytes; none changes the file it was read from.
"""
from __future__ import annotations

from backlash_monitor.bag.records import CHUNK_HEAD, FOOTER_RECORD_LEN, OP_DATA_END, RECORD_HEADER, U32, U64


def chunk_layout(path) -> list[tuple[int, int, int, int]]:
    """(offset, length_bytes, start_ns, end_ns) of every chunk of an intact bag, in file order."""
    from backlash_monitor.bag.reader import BagReader

    with BagReader(path) as bag:
        return [(c.offset, c.length, c.start, c.end) for c in bag.chunks]


def chunk_length_field(data: bytes, offset: int, length: int) -> bytes:
    """The chunk record at ``offset`` says its body has ``length`` bytes (its real length aside)."""
    out = bytearray(data)
    out[offset + 1:offset + 9] = U64.pack(length)
    return bytes(out)


def chunk_crc_field(data: bytes, offset: int) -> bytes:
    """The chunk's uncompressed-CRC field is wrong (the data is as written)."""
    out = bytearray(data)
    p = offset + 9 + CHUNK_HEAD.size - 4
    (crc,) = U32.unpack_from(out, p)
    out[p:p + 4] = U32.pack(crc ^ 0x5A5A5A5A or 1)
    return bytes(out)


def chunk_payload_byte(data: bytes, offset: int, length: int) -> bytes:
    """One byte in the middle of the chunk's compressed records is flipped (a bad sector)."""
    out = bytearray(data)
    out[offset + length // 2] ^= 0xFF
    return bytes(out)


def truncate(data: bytes, size: int) -> bytes:
    """The file ends after ``size`` bytes (a writer killed, a copy cut short)."""
    return data[:size]


def without_summary(data: bytes) -> bytes:
    """The file ends right after its DataEnd record: no summary, no footer."""
    return data[:data_end_offset(data) + 9 + 4]


def summary_byte(data: bytes) -> bytes:
    """One byte of the summary section is flipped (its CRC then fails)."""
    out = bytearray(data)
    start = data_end_offset(data) + 9 + 4
    out[start + (len(data) - FOOTER_RECORD_LEN - 8 - start) // 2] ^= 0xFF
    return bytes(out)


def data_end_offset(data: bytes) -> int:
    """Offset of the DataEnd record (found from the footer's summary start)."""
    fpos = len(data) - 8 - FOOTER_RECORD_LEN
    (summary_start,) = U64.unpack_from(data, fpos + 9)
    pos = summary_start - 9 - 4
    op, length = RECORD_HEADER.unpack_from(data, pos)
    if op != OP_DATA_END or length != 4:
        raise ValueError("no DataEnd record before the summary")
    return pos


def rewrite_signals(src, dst, change) -> None:
    """Copy the bag ``src`` to ``dst`` with every SignalChunk message passed through
    ``change(topic, fields) -> fields | None`` (fields: dict with first_sample_index,
    sample_period_s, samples, signal_name, unit; None drops the message). Other topics are copied
    as they are. For bags whose signals are wrong in a given way (another sample rate, a2 chunks
    shorter than a1, a NaN sample period, signals under another name)."""
    from backlash_monitor.bag.reader import BagReader
    from backlash_monitor.bag.writer import BagWriter

    with BagReader(src) as bag, BagWriter(dst) as out:
        topics = bag.topics
        for name, info in topics.items():
            out.add_topic(name, info.type, definition=info.schema_text, type_hash=info.type_hash)
        for m in bag.messages():
            if topics[m.topic].type.endswith("/SignalChunk"):
                msg = m.message
                fields = change(m.topic, {"first_sample_index": int(msg.first_sample_index),
                                          "sample_period_s": float(msg.sample_period_s),
                                          "samples": msg.samples.copy(),
                                          "signal_name": msg.signal_name, "unit": msg.unit})
                if fields is None:
                    continue
                out.write(m.topic, {"header": msg.header.to_dict() if hasattr(msg.header, "to_dict")
                                    else msg.header, **fields}, log_time_ns=m.log_time_ns,
                          publish_time_ns=m.publish_time_ns)
            else:
                out.write_raw(m.topic, m.data, log_time_ns=m.log_time_ns,
                              publish_time_ns=m.publish_time_ns)
