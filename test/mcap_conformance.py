"""The MCAP project's conformance corpus, written again with the official `mcap` writer.

test/data/mcap_conformance.json (tools/derive_mcap_conformance.py, from github.com/foxglove/mcap
tests/conformance/data) holds each input's records and the features of its 208 variants (the
`pad` variants aside). `write_variant` writes one variant the way the corpus's own Python writer
test does (python/mcap/tests/run_writer_test.py), under profile `ros2` and with the chunk
compression given: 208 layouts x {none, zstd, lz4} = 624 files. `expected_messages` is what a
reader must give back: (topic, log_time, publish_time, sequence, data) in the order written.

Also `rewrite_with_mcap`: a project bag written again by the `mcap` writer with rosbag2's writer
options (``ROSBAG2_OPTIONS``: the `--storage-config-file` keys of rosbag2_storage_mcap, and its
storage presets ``ROSBAG2_PRESETS``).
"""
from __future__ import annotations

import json
import struct
from pathlib import Path

CORPUS = Path(__file__).resolve().parent / "data" / "mcap_conformance.json"
COMPRESSIONS = ("none", "zstd", "lz4")


def load_corpus() -> dict:
    return json.loads(CORPUS.read_text())


def layouts(corpus: dict | None = None) -> list[tuple[dict, str]]:
    """Every (variant, compression) pair."""
    corpus = corpus or load_corpus()
    return [(v, c) for v in corpus["variants"] for c in COMPRESSIONS]


def _bytes(fields, key) -> bytes:
    return bytes(int(v) for v in fields[key])


def write_variant(variant: dict, records: list[dict], path, compression: str = "none",
                  chunk_size: int = 1024 * 1024) -> Path:
    """Write one conformance variant with mcap.writer.Writer (profile ros2)."""
    from mcap.writer import CompressionType, IndexType, Writer

    features = set(variant["features"])
    index = IndexType.NONE
    for feature, flag in (("ax", IndexType.ATTACHMENT), ("chx", IndexType.CHUNK),
                          ("mx", IndexType.MESSAGE), ("mdx", IndexType.METADATA)):
        if feature in features:
            index |= flag
    path = Path(path)
    with open(path, "wb") as f:
        writer = Writer(f, chunk_size=chunk_size,
                        compression={"none": CompressionType.NONE, "zstd": CompressionType.ZSTD,
                                     "lz4": CompressionType.LZ4}[compression],
                        index_types=index, repeat_channels="rch" in features,
                        repeat_schemas="rsh" in features, use_chunking="ch" in features,
                        use_statistics="st" in features, use_summary_offsets="sum" in features,
                        enable_crcs=True, enable_data_crcs=True)
        for r in records:
            kind, fields = r["type"], r["fields"]
            if kind == "Header":
                writer.start("ros2", fields["library"] or "mcap conformance corpus")
            elif kind == "Schema":
                writer.register_schema(name=fields["name"], encoding=fields["encoding"],
                                       data=_bytes(fields, "data"))
            elif kind == "Channel":
                writer.register_channel(schema_id=int(fields["schema_id"]), topic=fields["topic"],
                                        message_encoding=fields["message_encoding"],
                                        metadata=dict(fields["metadata"]))
            elif kind == "Message":
                writer.add_message(channel_id=int(fields["channel_id"]),
                                   log_time=int(fields["log_time"]), data=_bytes(fields, "data"),
                                   publish_time=int(fields["publish_time"]),
                                   sequence=int(fields["sequence"]))
            elif kind == "Attachment":
                writer.add_attachment(create_time=int(fields["create_time"]),
                                      log_time=int(fields["log_time"]), name=fields["name"],
                                      media_type=fields["media_type"], data=_bytes(fields, "data"))
            elif kind == "Metadata":
                writer.add_metadata(fields["name"], dict(fields["metadata"]))
        writer.finish()
    return path


def expected_messages(records: list[dict]) -> list[tuple]:
    """(topic, log_time, publish_time, sequence, data) of the input's messages, as written."""
    topics = {}
    out = []
    for r in records:
        fields = r["fields"]
        if r["type"] == "Channel":
            topics[int(fields["id"])] = fields["topic"]
        elif r["type"] == "Message":
            out.append((topics[int(fields["channel_id"])], int(fields["log_time"]),
                        int(fields["publish_time"]), int(fields["sequence"]),
                        _bytes(fields, "data")))
    return out


def read_messages(path) -> list[tuple]:
    """What backlash_monitor.bag reads: (topic, log_time, publish_time, sequence, data)."""
    from backlash_monitor.bag import BagReader

    with BagReader(path) as bag:
        return [(m.topic, m.log_time_ns, m.publish_time_ns, m.sequence, m.data)
                for m in bag.messages(decode=False)]


# ----------------------------------------------------------------------------------------------
# rosbag2's MCAP writer options (rosbag2_storage_mcap's --storage-config-file keys) on the mcap
# Python writer. Keys the Python writer has no switch for are done on the written bytes
# (noChunkCRC: the chunks' CRC fields zeroed, as the C++ writer leaves them).

ROSBAG2_OPTIONS = ("noChunking", "noSummary", "noMessageIndex", "noChunkIndex",
                   "noRepeatedChannels", "noRepeatedSchemas", "noStatistics", "noSummaryOffsets",
                   "noChunkCRC", "noSummaryCRC", "compression", "compressionLevel", "chunkSize")

# rosbag2_storage_mcap/src/mcap_storage.cpp, SetOptionsForPreset (ros2/rosbag2); the C++ writer's
# levels (cpp/mcap/include/mcap/writer.inl): zstd Fastest = -5, Slowest = 19
ROSBAG2_PRESETS = {
    "none": {},
    "fastwrite": {"noChunking": True, "noSummaryCRC": True},
    "zstd_fast": {"compression": "Zstd", "compressionLevel": -5, "noChunkCRC": True},
    "zstd_small": {"compression": "Zstd", "compressionLevel": 19, "chunkSize": 4 * 1024 * 1024},
}


class _ZstdAtLevel:
    """Stands in for the `zstandard` module in mcap.writer: compress() at a given level."""

    def __init__(self, level: int):
        import zstandard

        self._compressor = zstandard.ZstdCompressor(level=level)

    def compress(self, data: bytes) -> bytes:
        return self._compressor.compress(data)


def rewrite_with_mcap(src, dst, **options) -> Path:
    """Write the bag ``src`` again as ``dst`` with the `mcap` writer under rosbag2's writer
    ``options`` (``noSummary=True``, ``compression="Lz4"``, ...; defaults: rosbag2's, zstd).
    The source is read with the `mcap` library (not with backlash_monitor.bag)."""
    import mcap.writer as mcap_writer
    from mcap.reader import make_reader
    from mcap.writer import CompressionType, IndexType, Writer

    unknown = set(options) - set(ROSBAG2_OPTIONS)
    if unknown:
        raise ValueError(f"unknown rosbag2 MCAP writer options {sorted(unknown)}")
    o = options.get
    no_summary = bool(o("noSummary"))
    index = IndexType.NONE
    if not o("noMessageIndex"):
        index |= IndexType.MESSAGE
    if not (o("noChunkIndex") or no_summary):
        index |= IndexType.CHUNK
    if not no_summary:
        index |= IndexType.METADATA | IndexType.ATTACHMENT
    compression = {"Zstd": CompressionType.ZSTD, "Lz4": CompressionType.LZ4,
                   "None": CompressionType.NONE}[o("compression", "Zstd")]
    saved = mcap_writer.zstandard
    if o("compressionLevel") is not None:
        mcap_writer.zstandard = _ZstdAtLevel(int(o("compressionLevel")))
    dst = Path(dst)
    try:
        with open(src, "rb") as f, open(dst, "wb") as out:
            reader = make_reader(f)
            header = reader.get_header()
            summary = reader.get_summary()
            metadata = list(reader.iter_metadata())
            writer = Writer(out, chunk_size=int(o("chunkSize", 768 * 1024)), compression=compression,
                            index_types=index, use_chunking=not o("noChunking"),
                            repeat_channels=not (o("noRepeatedChannels") or no_summary),
                            repeat_schemas=not (o("noRepeatedSchemas") or no_summary),
                            use_statistics=not (o("noStatistics") or no_summary),
                            use_summary_offsets=not (o("noSummaryOffsets") or no_summary),
                            enable_crcs=not o("noSummaryCRC"), enable_data_crcs=False)
            writer.start(header.profile, header.library)
            schema_ids = {sid: writer.register_schema(s.name, s.encoding, s.data)
                          for sid, s in sorted(summary.schemas.items())}
            channel_ids = {cid: writer.register_channel(c.topic, c.message_encoding,
                                                        schema_ids.get(c.schema_id, 0), c.metadata)
                           for cid, c in sorted(summary.channels.items())}
            for _schema, channel, message in reader.iter_messages(log_time_order=False):
                writer.add_message(channel_ids[channel.id], message.log_time, message.data,
                                   message.publish_time, message.sequence)
            for m in metadata:
                writer.add_metadata(m.name, dict(m.metadata))
            writer.finish()
    finally:
        mcap_writer.zstandard = saved
    if o("noChunkCRC"):
        _zero_chunk_crcs(dst)
    return dst


def _zero_chunk_crcs(path: Path) -> None:
    """Every chunk's uncompressed_crc field set to 0 (the C++ writer's noChunkCRC); the data
    section CRC is 0 (not computed) in these files, so nothing else changes."""
    data = bytearray(Path(path).read_bytes())
    pos = 8
    while pos + 9 <= len(data):
        op, length = struct.unpack_from("<BQ", data, pos)
        if op == 0x06:
            data[pos + 9 + 24:pos + 9 + 28] = b"\0\0\0\0"
        if op == 0x0F:   # DataEnd
            break
        pos += 9 + length
    Path(path).write_bytes(bytes(data))
