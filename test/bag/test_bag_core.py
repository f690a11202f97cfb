"""Bag core: writer/reader round trip, the file's structure (checked with the `mcap` library),
independent readers (mcap_ros2, rosbags), the schema text, recovery after a kill, clear errors."""
from __future__ import annotations

import io
import math

import numpy as np
import pytest
import yaml

from backlash_monitor.bag import (SIGNAL_CHUNK, BagReader, BagWriter, MissingTopicError,
                                  NotABagError, TruncatedBagError, UnknownSchemaError,
                                  full_definition, type_hash)
from backlash_monitor.bag.schema import parse_schema
from bag_helpers import PERIOD_NS, SIGNALS, T0, write_sample_bag


@pytest.fixture(scope="module")
def sample_bag(tmp_path_factory):
    path = tmp_path_factory.mktemp("bag") / "run.mcap"
    written = write_sample_bag(path)
    return path, written


def _same(a, b):
    if hasattr(a, "to_dict"):
        a = a.to_dict()
    if hasattr(b, "to_dict"):
        b = b.to_dict()
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, (list, tuple, np.ndarray)):
        a, b = list(a), list(b)
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _same(x, y)
    elif isinstance(a, float) and math.isnan(a):
        assert isinstance(b, float) and math.isnan(b)
    elif isinstance(a, bytes):
        assert bytes(a) == bytes(b)
    else:
        assert a == b, (a, b)


def test_round_trip_every_topic_and_value(sample_bag):
    path, written = sample_bag
    with BagReader(path) as bag:
        assert bag.recovery.complete
        assert {t: i.count for t, i in bag.topics.items()} == {t: len(m) for t, m in written.items()}
        assert bag.topics["/plant/a1"].type == SIGNAL_CHUNK
        assert bag.message_count == sum(len(m) for m in written.values())
        assert bag.start_ns == T0 + 1000
        got: dict[str, list] = {}
        for m in bag.messages():
            got.setdefault(m.topic, []).append(m)
        for topic, msgs in written.items():
            assert len(got[topic]) == len(msgs)
            for w, r in zip(msgs, got[topic]):
                _same(w, r.message)
            assert [m.sequence for m in got[topic]] == list(range(len(msgs)))
        a1 = got["/plant/a1"]
        assert [m.log_time_ns for m in a1] == [T0 + i * PERIOD_NS + 1000 for i in range(len(a1))]
        assert [m.publish_time_ns for m in a1] == [T0 + i * PERIOD_NS for i in range(len(a1))]
        assert a1[0].message.samples.dtype == np.float64
        # topic filter and time filter
        only = list(bag.messages(["/estimate"]))
        assert {m.topic for m in only} == {"/estimate"} and len(only) == len(written["/estimate"])
        window = list(bag.messages("/plant/a2", start_ns=T0 + 10 * PERIOD_NS,
                                   end_ns=T0 + 19 * PERIOD_NS + 5000))
        assert [m.message.first_sample_index for m in window] == [i * 1000 for i in range(10, 20)]
        series = bag.read_signal("/plant/omega1")
        assert series.samples.shape == (60 * 1000,) and series.gaps == []
        assert series.unit == "rad/s" and series.sample_period_s == 2e-5
        np.testing.assert_array_equal(series.samples[:1000], written["/plant/omega1"][0].samples)
        meta = bag.rosbag2_metadata
        assert meta["version"] == 9 and meta["storage_identifier"] == "mcap"


def test_file_structure_as_the_mcap_library_sees_it(sample_bag):
    from mcap.reader import make_reader

    path, written = sample_bag
    with open(path, "rb") as f:
        reader = make_reader(f)
        header = reader.get_header()
        assert header.profile == "ros2"
        summary = reader.get_summary()
        assert summary is not None and summary.statistics is not None
        stats = summary.statistics
        assert stats.message_count == sum(len(m) for m in written.values())
        assert stats.chunk_count == len(summary.chunk_indexes) > 1
        assert stats.metadata_count == 2   # rosbag2's, and the writer's chunk limits
        for schema in summary.schemas.values():
            assert schema.encoding == "ros2msg"
            assert schema.data.decode() == full_definition(schema.name)
        by_topic = {c.topic: c for c in summary.channels.values()}
        assert set(by_topic) == set(written)
        for topic, ch in by_topic.items():
            assert ch.message_encoding == "cdr"
            assert set(ch.metadata) == {"offered_qos_profiles", "topic_type_hash"}
            assert ch.metadata["topic_type_hash"].startswith("RIHS01_")
            qos = yaml.safe_load(ch.metadata["offered_qos_profiles"])
            assert isinstance(qos, list) and qos[0]["reliability"] == "reliable"
            assert set(qos[0]) == {"history", "depth", "reliability", "durability", "deadline",
                                   "lifespan", "liveliness", "liveliness_lease_duration",
                                   "avoid_ros_namespace_conventions"}
            assert stats.channel_message_counts[ch.id] == len(written[topic])
        assert by_topic["/plant/a1"].metadata["topic_type_hash"] == type_hash(SIGNAL_CHUNK)
        for ci in summary.chunk_indexes:
            assert ci.compression == "zstd" and ci.compressed_size < ci.uncompressed_size
            assert ci.message_index_offsets  # per-channel message indexes are written
        metas = list(reader.iter_metadata())
        assert [m.name for m in metas] == ["backlash_monitor.writer", "rosbag2"]
        assert metas[0].metadata["chunk_duration_s"] == "0.5"
        bag_meta = yaml.safe_load(metas[1].metadata["serialized_metadata"])
        assert bag_meta["ros_distro"] == "jazzy" and bag_meta["message_count"] == stats.message_count
        counts = {t["topic_metadata"]["name"]: t["message_count"]
                  for t in bag_meta["topics_with_message_count"]}
        assert counts == {t: len(m) for t, m in written.items()}
        tm = bag_meta["topics_with_message_count"][0]["topic_metadata"]
        assert isinstance(tm["offered_qos_profiles"], list)  # Jazzy (v9) wants a list, not a string
        assert bag_meta["duration"]["nanoseconds"] == stats.message_end_time - stats.message_start_time
        # every message is reachable through the index, and the CRCs check out
        n = sum(1 for _ in reader.iter_messages())
        assert n == stats.message_count
    # a streaming (non-seeking) read of the whole file validates every record and CRC
    from mcap.stream_reader import StreamReader

    with open(path, "rb") as f:
        records = list(StreamReader(f, validate_crcs=True).records)
    assert type(records[-1]).__name__ == "Footer"


def test_mcap_ros2_decoder_decodes_every_message_equal(sample_bag):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    path, written = sample_bag
    got: dict[str, list] = {}
    with open(path, "rb") as f:
        for _s, ch, _m, dec in make_reader(f, decoder_factories=[DecoderFactory()]).iter_decoded_messages(
                log_time_order=False):
            got.setdefault(ch.topic, []).append(dec)
    for topic in SIGNALS:
        w = written[f"/plant/{topic}"]
        g = got[f"/plant/{topic}"]
        assert len(g) == len(w)
        for a, b in zip(w, g):
            assert a.first_sample_index == b.first_sample_index and a.unit == b.unit
            assert a.header.frame_id == b.header.frame_id
            np.testing.assert_array_equal(a.samples, np.asarray(b.samples))
    est = got["/estimate"][0]
    assert math.isnan(est.continuous_width_m) and list(est.b_vector) == []
    assert got["/diagnostics"][0].status[0].values[0].key == "width_m"


def test_rosbags_reads_and_decodes_every_message_equal(sample_bag):
    from pathlib import Path

    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    path, written = sample_bag
    got: dict[str, list] = {}
    with AnyReader([Path(path)], default_typestore=get_typestore(Stores.ROS2_JAZZY)) as reader:
        assert reader.message_count == sum(len(m) for m in written.values())
        for conn, _ts, raw in reader.messages():
            got.setdefault(conn.topic, []).append(reader.deserialize(raw, conn.msgtype))
    assert set(got) == set(written)
    for topic, msgs in written.items():
        assert len(got[topic]) == len(msgs)
    for a, b in zip(written["/plant/a1"], got["/plant/a1"]):
        assert (a.first_sample_index, a.signal_name, a.header.stamp.sec, a.header.stamp.nanosec) == \
            (b.first_sample_index, b.signal_name, b.header.stamp.sec, b.header.stamp.nanosec)
        np.testing.assert_array_equal(a.samples, b.samples)
    w, r = written["/windows/raw"][0], got["/windows/raw"][0]
    np.testing.assert_array_equal(w.a2, r.a2)
    assert math.isnan(r.true_width_m) and r.entry_kind == "onset"
    assert got["/diagnostics"][0].status[0].name == "backlash_monitor: drive"


def test_full_definition_is_rosbag2s_concatenation():
    text = full_definition("backlash_monitor_msgs/msg/SignalChunk")
    from backlash_monitor.bag.schema import find_msg_file

    root = find_msg_file("backlash_monitor_msgs/msg/SignalChunk").read_text()
    header = find_msg_file("std_msgs/msg/Header").read_text()
    time_ = find_msg_file("builtin_interfaces/msg/Time").read_text()
    bar = "=" * 80
    assert text == (root + "\n" + bar + "\nMSG: std_msgs/Header\n" + header
                    + "\n" + bar + "\nMSG: builtin_interfaces/Time\n" + time_)
    specs = parse_schema("backlash_monitor_msgs/msg/SignalChunk", text)
    assert set(specs) == {"backlash_monitor_msgs/msg/SignalChunk", "std_msgs/msg/Header",
                          "builtin_interfaces/msg/Time"}
    diag = parse_schema("diagnostic_msgs/msg/DiagnosticArray",
                        full_definition("diagnostic_msgs/msg/DiagnosticArray"))
    status = diag["diagnostic_msgs/msg/DiagnosticStatus"]
    assert [f.name for f in status.fields] == ["level", "name", "message", "hardware_id", "values"]
    assert status.constants["ERROR"] == ("byte", "2")


@pytest.mark.parametrize("compression", ["", "lz4"])
def test_other_chunk_compressions_read_back(tmp_path, compression):
    written = write_sample_bag(tmp_path / "c.mcap", n_chunks=12, compression=compression)
    with BagReader(tmp_path / "c.mcap") as bag:
        got = [m.message for m in bag.messages("/plant/a2")]
    assert len(got) == 12
    np.testing.assert_array_equal(got[-1].samples, written["/plant/a2"][-1].samples)


def test_a_killed_recorder_loses_at_most_the_open_chunk(tmp_path):
    """Simulate SIGKILL: the file stops inside chunk k; chunks 0..k-1 stay readable (recover=True).

    A chunk is closed at 1 MiB or 0.5 s of log time, so the loss is at most 0.5 s of the stream."""
    path = tmp_path / "full.mcap"
    write_sample_bag(path, n_chunks=100, chunk_duration_s=0.5)
    data = path.read_bytes()
    with BagReader(path) as bag:
        chunks = bag.chunks
    assert len(chunks) >= 4
    assert all(c.end - c.start < 500_000_000 for c in chunks)
    prefix_counts = []
    for k in range(1, len(chunks)):
        for extra in (0, 9, 5000):  # at a record boundary, inside the record header, inside the body
            cut_path = tmp_path / f"cut{k}_{extra}.mcap"
            cut_path.write_bytes(data[:chunks[k].offset + extra])
            with pytest.raises(TruncatedBagError) as err:
                BagReader(cut_path)
            assert "recover" in str(err.value) and err.value.complete_chunks == k
            with BagReader(cut_path, recover=True) as bag:
                rep = bag.recovery
                assert not rep.complete and rep.complete_chunks == k
                assert rep.lost_bytes == extra
                msgs = list(bag.messages())
                assert len(msgs) == rep.messages == bag.message_count
                a1 = [m.message.first_sample_index for m in msgs if m.topic == "/plant/a1"]
                assert a1 == [i * 1000 for i in range(len(a1))]  # a contiguous prefix
                assert max(m.log_time_ns for m in msgs) >= chunks[k - 1].end
        prefix_counts.append(len(a1))
    assert prefix_counts == sorted(prefix_counts) and prefix_counts[-1] < 100


def test_killed_before_the_first_chunk_still_names_the_topics(tmp_path):
    path = tmp_path / "early.mcap"
    w = BagWriter(path)
    w.add_topic("/plant/a1", SIGNAL_CHUNK)
    w.write("/plant/a1", {"samples": np.ones(10)}, log_time_ns=T0)
    w._f.flush()  # the process dies here: no chunk was closed
    with BagReader(path, recover=True) as bag:
        assert list(bag.topics) == ["/plant/a1"] and bag.message_count == 0
        assert bag.recovery.complete_chunks == 0
    w.close()
    with BagReader(path) as bag:
        assert bag.message_count == 1


def test_clear_errors(tmp_path, sample_bag):
    path, _ = sample_bag
    with BagReader(path) as bag:
        with pytest.raises(MissingTopicError, match="/plant/a1"):
            list(bag.messages(["/nope"]))
        with pytest.raises(MissingTopicError):
            bag.read_signal("/nope")
    bad = tmp_path / "not.mcap"
    bad.write_bytes(b"hello world, not a bag at all" * 3)
    with pytest.raises(NotABagError):
        BagReader(bad)
    with pytest.raises(FileNotFoundError):
        BagReader(tmp_path / "missing.mcap")
    odd = tmp_path / "odd.mcap"
    with BagWriter(odd) as w:
        w.add_topic("/weird", "foo_msgs/msg/Weird", definition="float64[ broken\n", type_hash="")
        w.write_raw("/weird", b"\x00\x01\x00\x00" + bytes(8), log_time_ns=T0)
    with BagReader(odd) as bag:
        assert bag.topics["/weird"].count == 1
        with pytest.raises(UnknownSchemaError, match="/weird"):
            list(bag.messages(["/weird"]))
        assert len(list(bag.messages(["/weird"], decode=False))) == 1
    with pytest.raises(UnknownSchemaError, match="no .msg definition"):
        BagWriter(tmp_path / "x.mcap").add_topic("/x", "nope_msgs/msg/Nothing")


def test_writer_rejects_bad_options(tmp_path):
    with pytest.raises(ValueError, match="compression"):
        BagWriter(tmp_path / "a.mcap", compression="gzip")
    w = BagWriter(tmp_path / "b.mcap")
    with pytest.raises(MissingTopicError):
        w.write_raw("/unknown", b"\x00\x01\x00\x00")
    w.close()
    w.close()  # idempotent
    assert io.BytesIO((tmp_path / "b.mcap").read_bytes()).read(8) == b"\x89MCAP0\r\n"
