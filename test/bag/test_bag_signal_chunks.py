"""BagReader.signal_chunks (what analyze reads) yields, message for message, the fields that
BagReader.messages decodes into SignalChunk messages: the same values (samples a read-only view
of the decompressed chunk, or a copy of an uncompressed one); big-endian payloads go through the
generic decoder, malformed ones raise."""
import mmap
import struct

import numpy as np
import pytest

from backlash_monitor.bag import SIGNAL_CHUNK, BagError, BagReader, BagWriter, CdrError, Codec

from bag_helpers import write_sample_bag
from mcap_conformance import rewrite_with_mcap

SIGNALS = ("/plant/a1", "/plant/a2", "/plant/angle_difference")


def fields_of(m):
    c = m.message
    return (m.topic, m.log_time_ns, c.first_sample_index, c.sample_period_s, c.samples.tobytes(),
            (c.header.stamp.sec, c.header.stamp.nanosec), c.header.frame_id, c.signal_name, c.unit)


def fields_of_record(r):
    return (r.topic, r.log_time_ns, r.first_sample_index, r.sample_period_s, r.samples.tobytes(),
            (r.stamp.sec, r.stamp.nanosec), r.frame_id, r.signal_name, r.unit)


@pytest.mark.parametrize("compression", ["zstd", "lz4", "", "no chunks"])
def test_same_fields_as_decoded_messages(tmp_path, compression):
    path = tmp_path / "b.mcap"
    write_sample_bag(path, n_chunks=30, compression=compression if compression != "no chunks" else "")
    if compression == "no chunks":   # each topic's fields from the file at once (signal_table.py)
        path, compression = rewrite_with_mcap(path, tmp_path / "unchunked.mcap", noChunking=True), ""
    with BagReader(path) as bag:
        records = list(bag.signal_chunks(SIGNALS))
        assert [fields_of_record(r) for r in records] == [fields_of(m) for m in bag.messages(SIGNALS)]
        assert len(records) == 90
        for r in records:
            assert r.samples.dtype == np.float64
            if compression:    # a view of the decompressed chunk (bytes), never of the file's map
                assert not r.samples.flags.writeable and isinstance(r.samples.base.obj, bytes)
            else:              # an uncompressed chunk or no chunk is a view of the map: copied
                assert r.samples.flags.writeable and r.samples.flags.owndata
            assert type(r.first_sample_index) is int and type(r.sample_period_s) is float
        with pytest.raises(BagError):
            next(bag.signal_chunks(["/estimate"]))
        with pytest.raises(BagError):
            next(bag.signal_chunks(["/no/such/topic"]))


@pytest.mark.parametrize("layout", ["zstd", "uncompressed chunks", "no chunks"])
def test_without_copies_the_samples_are_read_in_place(tmp_path, layout):
    """copy=False (analyze): samples in the file's map are read-only views of it, with the values
    of the copies; they stay readable after the reader is closed (the map goes with the last)."""
    path = tmp_path / "b.mcap"
    write_sample_bag(path, n_chunks=30, compression="" if layout != "zstd" else "zstd")
    if layout == "no chunks":
        path = rewrite_with_mcap(path, tmp_path / "unchunked.mcap", noChunking=True)
    with BagReader(path) as bag:
        want = [fields_of_record(r) for r in bag.signal_chunks(SIGNALS)]
        views = list(bag.signal_chunks(SIGNALS, copy=False))
        assert [fields_of_record(r) for r in views] == want and len(want) == 90
        for r in views:
            assert not r.samples.flags.writeable
            assert isinstance(r.samples.base.obj, bytes if layout == "zstd" else mmap.mmap)
    assert [fields_of_record(r) for r in views] == want


def big_endian_chunk(first: int) -> bytes:
    be = bytearray(b"\x00\x00\x00\x00")
    be += struct.pack(">iI", 1, 2) + struct.pack(">I", 1) + b"\x00"
    be += b"\x00" * 3 + struct.pack(">I", 3) + b"a1\x00"
    be += b"\x00" + struct.pack(">I", 2) + b"u\x00"
    be += b"\x00" * ((-(len(be) - 4)) & 7) + struct.pack(">dQ", 2e-5, first)
    be += struct.pack(">I", 4) + b"\x00" * 4 + np.arange(4.0).astype(">f8").tobytes()
    return bytes(be)


@pytest.mark.parametrize("chunks", [True, False], ids=["chunked", "no chunks"])
def test_big_endian_and_malformed_payloads(tmp_path, chunks):
    """(Without chunks the fields of a topic are taken from the file at once, signal_table.py: a
    payload laid out otherwise than the topic's first goes one by one, as in a chunk.)"""
    path = tmp_path / "be.mcap"
    codec = Codec.for_type(SIGNAL_CHUNK)
    good = codec.encode(codec.new(signal_name="a1", unit="u", sample_period_s=2e-5,
                                  first_sample_index=0, samples=np.arange(3.0)))
    with BagWriter(path) as w:
        w.add_topic("/plant/a1", SIGNAL_CHUNK)
        w.write_raw("/plant/a1", good, log_time_ns=1)
        w.write_raw("/plant/a1", big_endian_chunk(3), log_time_ns=2)
        w.write_raw("/plant/a1", good[:30], log_time_ns=3)
    if not chunks:
        path = rewrite_with_mcap(path, tmp_path / "unchunked.mcap", noChunking=True)
    with BagReader(path) as bag:
        it = bag.signal_chunks("/plant/a1")
        first, second = next(it), next(it)
        assert first.samples.tolist() == [0.0, 1.0, 2.0]
        assert second.first_sample_index == 3 and second.samples.tolist() == [0.0, 1.0, 2.0, 3.0]
        assert second.stamp == (1, 2) and second.signal_name == "a1" and second.unit == "u"
        assert second.samples.dtype == np.dtype("<f8")
        with pytest.raises(CdrError):
            next(it)


@pytest.mark.parametrize("chunks", [True, False], ids=["chunked", "no chunks"])
def test_strings_changing_within_a_topic(tmp_path, chunks):
    """The per-topic string cache is only a shortcut: changed strings are parsed again (without
    chunks, a payload whose strings differ from the topic's first one's is read one by one)."""
    path = tmp_path / "s.mcap"
    codec = Codec.for_type(SIGNAL_CHUNK)
    names = [("drive", "a1", "m/s^2"), ("drive", "a1", "m/s^2"), ("drivf", "a1", "m/s^2"),
             ("drive7", "a1", "m/s^2"), ("drive", "a1", "m/s"), ("", "", ""), ("drive", "a1", "m/s^2")]
    with BagWriter(path) as w:
        w.add_topic("/plant/a1", SIGNAL_CHUNK)
        for i, (frame_id, name, unit) in enumerate(names):
            msg = codec.new(signal_name=name, unit=unit, sample_period_s=2e-5,
                            first_sample_index=i * 3, samples=np.arange(3.0) + i)
            msg.header.frame_id = frame_id
            msg.header.stamp.sec = i
            w.write("/plant/a1", msg, log_time_ns=i + 1)
    if not chunks:
        path = rewrite_with_mcap(path, tmp_path / "unchunked.mcap", noChunking=True)
    with BagReader(path) as bag:
        got = [fields_of_record(r) for r in bag.signal_chunks(["/plant/a1"])]
        assert got == [fields_of(m) for m in bag.messages(["/plant/a1"])]
    assert [(g[6], g[7], g[8]) for g in got] == names


def fields_of_columns(columns, i):
    k = int(columns.topic[i])
    frame_id, signal_name, unit = columns.texts[k]
    return (columns.topics[k], int(columns.first_sample_index[i]), float(columns.sample_period_s[i]),
            columns.samples[i].tobytes(), (int(columns.sec[i]), int(columns.nanosec[i])), frame_id,
            signal_name, unit)


@pytest.mark.parametrize("layout", ["zstd", "uncompressed chunks", "no chunks"])
def test_columns_of_a_file_without_chunks(tmp_path, layout):
    """signal_chunk_columns: without chunks, what signal_chunks(copy=False) yields, as columns (the
    same values; each message's samples a read-only view of the map); with chunks, None."""
    path = tmp_path / "b.mcap"
    write_sample_bag(path, n_chunks=30, compression="" if layout != "zstd" else "zstd")
    if layout == "no chunks":
        path = rewrite_with_mcap(path, tmp_path / "unchunked.mcap", noChunking=True)
    with BagReader(path) as bag:
        columns = bag.signal_chunk_columns(SIGNALS)
        if layout != "no chunks":
            assert columns is None
            return
        records = list(bag.signal_chunks(SIGNALS, copy=False))
        assert len(records) == len(columns.samples) == 90
        assert [fields_of_columns(columns, i) for i in range(90)] == [
            tuple(f for k, f in enumerate(fields_of_record(r)) if k != 1) for r in records]
        for view in columns.samples:
            assert view.dtype == np.float64 and not view.flags.writeable
            base = view.base
            while isinstance(base, np.ndarray):
                base = base.base
            assert isinstance(base.obj, mmap.mmap)
        with pytest.raises(BagError):
            bag.signal_chunk_columns(["/estimate"])


@pytest.mark.parametrize("case", ["big endian", "strings change", "no samples"])
def test_columns_refuse_payloads_laid_out_otherwise(tmp_path, case):
    """A payload laid out otherwise than its topic's first (read one by one by signal_chunks), or
    one without samples: no columns (None)."""
    path = tmp_path / "b.mcap"
    codec = Codec.for_type(SIGNAL_CHUNK)

    def payload(i, n=3, frame_id="drive"):
        msg = codec.new(signal_name="a1", unit="u", sample_period_s=2e-5, first_sample_index=3 * i,
                        samples=np.arange(float(n)))
        msg.header.frame_id = frame_id
        return codec.encode(msg)
    odd = {"big endian": big_endian_chunk(3), "strings change": payload(1, frame_id="drive7"),
           "no samples": payload(1, n=0)}[case]
    with BagWriter(path) as w:
        w.add_topic("/plant/a1", SIGNAL_CHUNK)
        for i, data in enumerate((payload(0), odd, payload(2))):
            w.write_raw("/plant/a1", data, log_time_ns=i + 1)
    path = rewrite_with_mcap(path, tmp_path / "unchunked.mcap", noChunking=True)
    with BagReader(path) as bag:
        assert len(list(bag.signal_chunks("/plant/a1"))) == 3
        assert bag.signal_chunk_columns("/plant/a1") is None
