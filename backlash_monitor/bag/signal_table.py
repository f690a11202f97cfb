"""The fields of many SignalChunk payloads in one buffer, taken at once (numpy), not one by one.

A bag written without chunks (rosbag2's ``noChunking``) holds every message as a record of its own
in the file: analyze's three topics of a 10 s bag are 1500 payloads, each parsed by
``Codec.signal_chunk_fields`` in ~1.3 us of Python steps (encapsulation, stamp, three strings, the
period, the first index, the count). A topic's payloads are laid out alike -- the same frame_id,
signal_name and unit, so the same string section and the same offsets after it -- so their fields
can be gathered from the file for all of them at once: :func:`signal_chunk_table`. What it gives is
what ``signal_chunk_fields`` gives for each (the same bytes read as the same little-endian types:
the values bit for bit, Python ints and floats); a payload laid out otherwise is left to
``signal_chunk_fields`` one by one (which parses it, or names what is wrong with it, as before).
"""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

CDR_LE = (0, 1)                 # the encapsulation's first two bytes: plain CDR, little endian
STRINGS_AT = 12                 # the string section: after the encapsulation (4) and the stamp (8)
_STAMP = np.dtype([("sec", "<i4"), ("nanosec", "<u4")])
_TAIL = np.dtype([("period", "<f8"), ("first", "<u8"), ("n", "<u4")])
_SAMPLES_AFTER_TAIL = _TAIL.itemsize + 4      # the samples' float64 alignment: 4 bytes of padding


class SignalChunkTable(NamedTuple):
    """The fields of the payloads ``rows`` (indices into the payloads given), in their order."""
    rows: list[int]
    sec: list[int]
    nanosec: list[int]
    sample_period_s: list[float]
    first_sample_index: list[int]
    samples: list[int]          # number of samples
    samples_at: list[int]       # offset of the first sample in the buffer
    frame_id: str
    signal_name: str
    unit: str


def gather(data: np.ndarray, at: np.ndarray, width: int) -> np.ndarray:
    """``data[at[i]:at[i] + width]`` for every i: rows of a (len(at), width) uint8 array."""
    return data[at[:, None] + np.arange(width)]


def signal_chunk_table(codec, data: np.ndarray, starts: np.ndarray, sizes: np.ndarray,
                       strings: list) -> SignalChunkTable | None:
    """``codec.signal_chunk_fields`` of the SignalChunk payloads at ``starts`` (``sizes`` bytes
    each) in ``data`` (the buffer's bytes, uint8; int64 offsets and sizes): the fields of those
    laid out as the first one is (plain little-endian CDR, its string section byte for byte, the
    period/first index/count and the samples inside the payload). None when the first is not
    such a payload. ``strings``: signal_chunk_fields's per-topic string cache (the first
    payload's section is parsed into it)."""
    if not len(starts):
        return None
    first = int(starts[0])
    try:
        fields = codec.signal_chunk_fields(memoryview(data[first:first + int(sizes[0])]),
                                           copy=False, strings=strings)
    except Exception:  # noqa: BLE001 - malformed: one by one, where it is named
        return None
    if fields is None or strings[0] is None:
        return None
    raw, frame_id, signal_name, unit, end = strings[0]
    tail_at = end + ((-(end - 4)) & 7)          # the period, aligned to 8 after the encapsulation
    rows = np.flatnonzero(sizes >= tail_at + _TAIL.itemsize)
    at = starts[rows]
    alike = (data[at] == CDR_LE[0]) & (data[at + 1] == CDR_LE[1])
    if raw:
        alike &= (gather(data, at + STRINGS_AT, len(raw))
                  == np.frombuffer(raw, dtype=np.uint8)).all(axis=1)
    rows, at = rows[alike], at[alike]
    tail = gather(data, at + tail_at, _TAIL.itemsize).view(_TAIL)[:, 0]
    n = tail["n"].astype(np.int64)
    fits = (n == 0) | (tail_at + _SAMPLES_AFTER_TAIL + 8 * n <= sizes[rows])
    rows, at, tail, n = rows[fits], at[fits], tail[fits], n[fits]
    stamp = gather(data, at + 4, _STAMP.itemsize).view(_STAMP)[:, 0]
    return SignalChunkTable(rows.tolist(), stamp["sec"].tolist(), stamp["nanosec"].tolist(),
                            tail["period"].tolist(), tail["first"].tolist(), n.tolist(),
                            (at + tail_at + _SAMPLES_AFTER_TAIL).tolist(),
                            frame_id, signal_name, unit)
