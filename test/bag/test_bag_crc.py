"""The bag CRC-32 (ISA-L's when installed) is zlib's checksum: the same values, a running value
continued, any buffer type."""
import os
import zlib

from backlash_monitor.bag.records import crc32


def test_same_checksum_as_zlib():
    for n in (0, 1, 7, 64, 5000, 1 << 20):
        data = os.urandom(n)
        assert crc32(data) == zlib.crc32(data)
        assert crc32(memoryview(data)) == zlib.crc32(data)
        assert crc32(bytearray(data), 12345) == zlib.crc32(data, 12345)
    a, b = os.urandom(3000), os.urandom(70000)
    assert crc32(b, crc32(a)) == zlib.crc32(a + b)
