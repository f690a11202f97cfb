"""The SignalChunk fast path of the CDR decoder gives the generic decoder's message, bit for bit."""
import struct

import numpy as np
import pytest

from backlash_monitor.bag import SIGNAL_CHUNK, BagReader, CdrError, Codec
from backlash_monitor.bag.schema import local_specs

from bag_helpers import write_sample_bag


def generic(codec: Codec, data: bytes):
    mv = memoryview(data)
    msg, _ = codec._dec(codec.specs[codec.type_name], mv, 4, mv[1] == 1)
    return msg


def same(a, b) -> None:
    assert type(a) is type(b)
    assert a == b
    assert a.samples.dtype == b.samples.dtype and a.samples.dtype.byteorder in "=<"
    assert a.samples.tobytes() == b.samples.tobytes()
    assert a.samples.flags.writeable and a.samples.flags.owndata
    for x, y in ((a.header.stamp.sec, b.header.stamp.sec), (a.sample_period_s, b.sample_period_s),
                 (a.first_sample_index, b.first_sample_index)):
        assert type(x) is type(y) and x == y


def test_fast_path_is_used_for_signal_chunk_only():
    assert Codec.for_type(SIGNAL_CHUNK)._fast is not None
    assert Codec.for_type("backlash_monitor_msgs/msg/BacklashWindow")._fast is None


def test_every_message_of_a_bag_decodes_as_the_generic_decoder(tmp_path):
    path = tmp_path / "b.mcap"
    write_sample_bag(path, n_chunks=40)
    with BagReader(path) as bag:
        topics = [t for t, i in bag.topics.items() if i.type.endswith("/SignalChunk")]
        n = 0
        for m in bag.messages(topics):
            codec = bag.codec(m.topic)
            assert codec._fast is not None
            same(m.message, generic(codec, m.data))
            n += 1
    assert n == 40 * 5


@pytest.mark.parametrize("frame_id,name,unit", [("", "", ""), ("drive_ü", "a1", "m/s^2"),
                                                ("abc", "ab", "abcd"), ("x" * 7, "y" * 5, "z")])
@pytest.mark.parametrize("n", [0, 1, 3, 1000])
def test_edge_layouts(frame_id, name, unit, n):
    codec = Codec.for_type(SIGNAL_CHUNK)
    rng = np.random.default_rng(n)
    msg = codec.new(signal_name=name, unit=unit, sample_period_s=2e-5,
                    first_sample_index=2**63 + 5, samples=rng.standard_normal(n))
    msg.header.stamp.sec, msg.header.stamp.nanosec = -5, 999_999_999
    msg.header.frame_id = frame_id
    data = codec.encode(msg)
    same(codec.decode(data), generic(codec, data))
    same(codec.decode(data + b"\x00" * 3), generic(codec, data))   # trailing padding
    assert codec.decode(data) == msg


def test_zero_length_string_and_truncation():
    codec = Codec.for_type(SIGNAL_CHUNK)
    # frame_id written with length 0 (no NUL; some writers do that)
    le = bytearray(b"\x00\x01\x00\x00")
    le += struct.pack("<iI", 3, 4) + struct.pack("<I", 0)
    le += struct.pack("<I", 3) + b"a1\x00" + b"\x00" + struct.pack("<I", 2) + b"u\x00"
    le += b"\x00" * ((-(len(le) - 4)) & 7) + struct.pack("<dQ", 2e-5, 7)
    le += struct.pack("<I", 2) + b"\x00" * 4 + np.array([1.5, -2.0]).tobytes()
    msg = codec.decode(bytes(le))
    same(msg, generic(codec, bytes(le)))
    assert msg.header.frame_id == "" and msg.signal_name == "a1" and msg.samples.tolist() == [1.5, -2.0]
    data = codec.encode(codec.new(signal_name="a1", unit="u", samples=np.arange(10.0)))
    for cut in (9, 20, len(data) - 30):
        with pytest.raises(CdrError):
            codec.decode(data[:cut])


def test_big_endian_uses_the_generic_decoder():
    specs = local_specs(SIGNAL_CHUNK)
    codec = Codec(SIGNAL_CHUNK, specs)
    msg = codec.new(signal_name="a1", unit="u", sample_period_s=2e-5, first_sample_index=7,
                    samples=np.arange(4.0))
    # hand-made big-endian payload
    be = bytearray(b"\x00\x00\x00\x00")
    be += struct.pack(">iI", 0, 0) + struct.pack(">I", 1) + b"\x00"
    be += b"\x00" * 3 + struct.pack(">I", 3) + b"a1\x00"
    be += b"\x00" + struct.pack(">I", 2) + b"u\x00"
    be += b"\x00" * ((-(len(be) - 4)) & 7) + struct.pack(">dQ", 2e-5, 7)
    be += struct.pack(">I", 4) + b"\x00" * 4 + np.arange(4.0).astype(">f8").tobytes()
    assert codec.decode(bytes(be)) == msg
