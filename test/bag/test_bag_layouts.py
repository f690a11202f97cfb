"""Every valid MCAP layout is read completely (docs/bags.md, "Layouts").

- The MCAP project's conformance corpus (github.com/foxglove/mcap tests/conformance: 208 variants
  without the padded ones, derived into test/data/mcap_conformance.json) written again by the
  official `mcap` writer under profile ros2 in chunk compression none, zstd and lz4: each of the
  624 files read with exactly the corpus's messages (topic, log and publish time, sequence, bytes),
  its topics and counts as the corpus has them, and called complete and intact.
- A project recording rewritten by the `mcap` writer with each of rosbag2's MCAP writer options
  (rosbag2_storage_mcap's `--storage-config-file` keys) and storage presets: the same messages,
  topics and counts as the original; `bag-info` exits 0; `analyze` gives the same estimates; the
  workbench's measurement (compare, diagnose) the same samples.
- A layout this package cannot read is refused with one line naming it; a valid file without a
  summary is not "incomplete", a cut one still is.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

from backlash_monitor.bag import BagReader, TruncatedBagError, UnsupportedBagError
from backlash_monitor.bag import records

import mcap_conformance as mc
from bag_helpers import write_sample_bag, write_simulated_drive

CORPUS = mc.load_corpus()


def test_the_corpus_fixture_is_the_whole_unpadded_corpus():
    variants = CORPUS["variants"]
    assert len(variants) == 208 and len({v["name"] for v in variants}) == 208
    assert not any("pad" in v["features"] for v in variants)
    assert len(mc.layouts(CORPUS)) == 624
    # every feature of the format's writers is on and off somewhere
    for feature in ("ch", "mx", "chx", "st", "rsh", "rch", "sum", "ax", "mdx"):
        assert any(feature in v["features"] for v in variants)
        assert any(feature not in v["features"] for v in variants)


@pytest.mark.parametrize("compression", mc.COMPRESSIONS)
def test_every_conformance_layout_is_read_completely(tmp_path, compression):
    read_ok, wrong = 0, []
    for variant in CORPUS["variants"]:
        recs = CORPUS["inputs"][variant["input"]]
        path = mc.write_variant(variant, recs, tmp_path / f"{variant['name']}.mcap", compression)
        want = mc.expected_messages(recs)
        try:
            with BagReader(path) as bag:
                got = [(m.topic, m.log_time_ns, m.publish_time_ns, m.sequence, m.data)
                       for m in bag.messages(decode=False)]
                counts = {name: t.count for name, t in bag.topics.items()}
                state = (bag.recovery.complete, bag.recovery.intact, bag.message_count)
                chunked = bool(bag.chunks)
        except Exception as error:  # noqa: BLE001 - collected: the test names every failure
            wrong.append(f"{variant['name']}: {type(error).__name__}: {error}")
            continue
        want_counts = {}
        for topic, *_ in want:
            want_counts[topic] = want_counts.get(topic, 0) + 1
        problems = []
        if got != want:
            problems.append(f"messages {got} != {want}")
        if {t: n for t, n in counts.items() if n} != want_counts:
            problems.append(f"counts {counts} != {want_counts}")
        if state != (True, True, len(want)):
            problems.append(f"complete/intact/count {state}")
        if chunked != ("ch" in variant["features"] and bool(want)):
            problems.append(f"chunks found: {chunked}")
        if problems:
            wrong.append(f"{variant['name']}: " + "; ".join(problems))
        else:
            read_ok += 1
    assert wrong == [] and read_ok == 208, f"{read_ok} of 208 read exactly: " + "\n".join(wrong[:10])


def test_the_channels_are_listed_when_only_the_chunks_hold_them(tmp_path):
    """The layout read as empty before: chunked, chunk index and summary, channels not repeated."""
    variant = next(v for v in CORPUS["variants"]
                   if v["name"] == "TenMessages-ch-chx-mx-rsh-st-sum")
    path = mc.write_variant(variant, CORPUS["inputs"]["TenMessages"], tmp_path / "t.mcap", "zstd")
    with BagReader(path) as bag:
        assert set(bag.topics) == {"example"} and bag.topics["example"].count == 10
        assert bag.topics["example"].type == "Example"   # its schema (repeated) named
        assert len(list(bag.messages(["example"], decode=False))) == 10


# ---------------------------------------------------------------------------------------------
# rosbag2's writer options on a project recording


@pytest.fixture(scope="module")
def project_bag(tmp_path_factory):
    path = tmp_path_factory.mktemp("layouts") / "project.mcap"
    write_sample_bag(path, n_chunks=120, chunk_size=256 * 1024)   # several chunks
    return path


def _content(path):
    with BagReader(path) as bag:
        topics = {n: (t.type, t.count, t.schema_text, t.offered_qos_profiles)
                  for n, t in bag.topics.items()}
        messages = [(m.topic, m.log_time_ns, m.publish_time_ns, m.sequence, m.data)
                    for m in bag.messages(decode=False)]
        decoded = [repr(m.message.to_dict()) if hasattr(m.message, "to_dict") else None
                   for m in bag.messages(["/estimate"])]
        report = bag.recovery
        return topics, messages, decoded, (report.complete, report.intact, bag.message_count)


OPTION_SETS = {
    **{name: {name: True} for name in ("noChunking", "noSummary", "noMessageIndex", "noChunkIndex",
                                       "noRepeatedChannels", "noRepeatedSchemas", "noStatistics",
                                       "noSummaryOffsets", "noChunkCRC", "noSummaryCRC")},
    "lz4": {"compression": "Lz4"},
    "uncompressed": {"compression": "None"},
    "noRepeatedChannels+noStatistics+noMessageIndex": {
        "noRepeatedChannels": True, "noStatistics": True, "noMessageIndex": True},
    "noSummary+noMessageIndex": {"noSummary": True, "noMessageIndex": True},
    **{f"preset {name}": options for name, options in mc.ROSBAG2_PRESETS.items()},
}


@pytest.fixture(scope="module")
def rewritten(tmp_path_factory, project_bag):
    """The project bag written again under one of OPTION_SETS, once per name for the whole module (the tests
    only read these files)."""
    folder = tmp_path_factory.mktemp("rewritten")
    paths = {}

    def get(name: str) -> Path:
        if name not in paths:
            paths[name] = mc.rewrite_with_mcap(project_bag, folder / f"{len(paths)}.mcap", **OPTION_SETS[name])
        return paths[name]
    return get


@pytest.fixture(scope="module")
def original_content(project_bag):
    return _content(project_bag)


@pytest.mark.parametrize("name", ["noChunking", "noSummary", "uncompressed"])
def test_some_topics_and_a_time_range_read_as_the_whole_file_filtered(rewritten, name):
    """messages(topics, start_ns, end_ns) and signal_chunks(topics) give exactly the file's messages
    of those topics (in that log-time range) in file order: in a file without chunks the other
    topics' messages are passed over by their channel ids, all at once (BagIndex.message_channels),
    the true width's one message of thousands as analyze reads it first."""
    with BagReader(rewritten(name)) as bag:
        everything = [(m.topic, m.log_time_ns, m.sequence, m.data) for m in bag.messages(decode=False)]
        lo, hi = everything[len(everything) // 3][1], everything[2 * len(everything) // 3][1]
        for topics in (["/estimate"], ["/plant/a2"], ["/plant/omega1", "/diagnostics", "/plant/a1"],
                       sorted(bag.topics)):
            for start, end in ((None, None), (lo, hi), (lo, None), (None, lo)):
                want = [m for m in everything if m[0] in topics
                        and (start is None or m[1] >= start) and (end is None or m[1] <= end)]
                got = [(m.topic, m.log_time_ns, m.sequence, m.data)
                       for m in bag.messages(topics, decode=False, start_ns=start, end_ns=end)]
                assert got == want, (topics, start, end)
        signals = ["/plant/angle_difference", "/plant/a1"]
        assert [(r.topic, r.log_time_ns) for r in bag.signal_chunks(signals)] == [
            (m[0], m[1]) for m in everything if m[0] in signals]


@pytest.mark.parametrize("name", sorted(OPTION_SETS))
def test_rosbag2_writer_options_read_as_the_original(original_content, rewritten, name):
    original = original_content
    topics, messages, decoded, state = _content(rewritten(name))
    assert state == (True, True, len(original[1]))      # complete and intact, every message
    assert messages == original[1]
    assert topics == original[0] and decoded == original[2]


def test_the_presets_are_what_rosbag2_sets(rewritten):
    """fastwrite: no chunks, no summary CRC; zstd_fast: zstd chunks without CRCs; zstd_small:
    zstd in chunks of up to 4 MiB (rosbag2_storage_mcap's SetOptionsForPreset)."""
    assert all(OPTION_SETS[f"preset {n}"] == o for n, o in mc.ROSBAG2_PRESETS.items())
    files = {n: rewritten(f"preset {n}") for n in mc.ROSBAG2_PRESETS}
    from mcap.stream_reader import StreamReader

    def chunk_fields(path):
        with open(path, "rb") as f:
            return [(r.compression, r.uncompressed_crc, r.uncompressed_size)
                    for r in StreamReader(f, emit_chunks=True).records
                    if type(r).__name__ == "Chunk"]

    def footer_crc(path):
        data = Path(path).read_bytes()
        return records.parse_footer(data[-8 - 20:-8]).summary_crc

    assert chunk_fields(files["fastwrite"]) == [] and footer_crc(files["fastwrite"]) == 0
    fast = chunk_fields(files["zstd_fast"])
    assert fast and all(c == "zstd" and crc == 0 for c, crc, _ in fast)
    small = chunk_fields(files["zstd_small"])
    assert all(c == "zstd" and crc != 0 for c, crc, _ in small)
    assert len(small) < len(chunk_fields(files["none"]))      # bigger chunks


def test_bag_info_reads_every_option(rewritten, capsys):
    from backlash_monitor.commands import bag_info

    for name in OPTION_SETS:
        assert bag_info.main([str(rewritten(name)), "--format", "json"]) == 0, name
        info = json.loads(capsys.readouterr().out)
        assert info["complete"] and info["intact"], (name, info["integrity"])
        assert {t["topic"]: t["count"] for t in info["topics"]} == {
            "/plant/a1": 120, "/plant/a2": 120, "/plant/omega1": 120, "/plant/omega2": 120,
            "/plant/angle_difference": 120, "/windows/raw": 12, "/estimate": 12,
            "/diagnostics": 12}, name


# ---------------------------------------------------------------------------------------------
# analyze and the workbench on a recording in other layouts


@pytest.fixture(scope="module")
def simulated_bag(tmp_path_factory):
    return write_simulated_drive(tmp_path_factory.mktemp("sim") / "drive.mcap")


def _analyze(bag: Path, out: Path) -> str:
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions, analyze_bag

    analyze_bag(bag, out, AnalyzeOptions())
    return out.with_suffix(".csv").read_text()


@pytest.mark.parametrize("options", [{"noSummary": True}, {"noChunking": True},
                                     {"noRepeatedChannels": True, "noStatistics": True}],
                         ids=["noSummary", "noChunking", "noRepeatedChannels+noStatistics"])
def test_analyze_gives_the_same_estimates_in_other_layouts(tmp_path, simulated_bag, options):
    reference = _analyze(simulated_bag, tmp_path / "default")
    assert reference.count("\n") > 2                    # estimates to compare
    other = mc.rewrite_with_mcap(simulated_bag, tmp_path / "other.mcap", **options)
    assert _analyze(other, tmp_path / "other_out") == reference


@pytest.mark.parametrize("options", [None, {"noSummary": True}, {"noChunking": True},
                                     {"noRepeatedChannels": True, "noStatistics": True}],
                         ids=["default", "noSummary", "noChunking", "noRepeatedChannels+noStatistics"])
def test_read_signals_is_the_decoded_messages_joined_in_stream_order(tmp_path, simulated_bag, options):
    """read_signals (the flat records of signal_chunks) gives what the decoded messages give, joined by their
    first_sample_index: every sample, index, chunk start, log time, name, unit, period and frame id."""
    import numpy as np
    path = simulated_bag if options is None else mc.rewrite_with_mcap(simulated_bag, tmp_path / "o.mcap", **options)
    with BagReader(path) as bag:
        topics = [t for t, i in bag.topics.items() if i.type.endswith("/SignalChunk")]
        got = bag.read_signals(topics)
        decoded = {t: [] for t in topics}
        for m in bag.messages(topics):
            decoded[m.topic].append((m.message, m.log_time_ns))
    assert topics and set(got) == set(topics)
    for t in topics:
        msgs = sorted(decoded[t], key=lambda x: x[0].first_sample_index)
        s = got[t]
        assert np.array_equal(s.samples, np.concatenate([m.samples for m, _ in msgs]))
        assert s.samples.dtype == np.float64 and s.sample_index.dtype == np.uint64
        assert s.chunk_first_index.tolist() == [m.first_sample_index for m, _ in msgs]
        assert s.chunk_log_time_ns.tolist() == [lt for _, lt in msgs]
        assert s.sample_index[0] == msgs[0][0].first_sample_index and len(s.sample_index) == len(s.samples)
        first = msgs[0][0]
        assert (s.signal_name, s.unit, s.sample_period_s, s.frame_id) == \
            (first.signal_name, first.unit, first.sample_period_s, first.header.frame_id)
        assert s.gaps == []


def test_the_workbench_measures_the_same_samples_without_a_summary(tmp_path, simulated_bag):
    from backlash_monitor.workbench.measurement import load_measurement

    other = mc.rewrite_with_mcap(simulated_bag, tmp_path / "nosummary.mcap", noSummary=True)
    a, b = load_measurement(simulated_bag), load_measurement(other)
    assert a.sample_period_s == b.sample_period_s and set(a.signals) == set(b.signals)
    for name in a.signals:
        assert (a.signals[name] == b.signals[name]).all()


# ---------------------------------------------------------------------------------------------
# valid and unreadable, complete and cut


def test_a_cut_file_without_summary_is_incomplete_and_recovers(tmp_path, project_bag):
    path = mc.rewrite_with_mcap(project_bag, tmp_path / "nosum.mcap", noSummary=True,
                                chunkSize=64 * 1024)
    with BagReader(path) as bag:
        chunks = bag.chunks
        total = bag.message_count
    cut = tmp_path / "cut.mcap"
    keep = chunks[len(chunks) // 2]
    cut.write_bytes(path.read_bytes()[:keep.offset + keep.length // 2])   # inside a chunk
    with pytest.raises(TruncatedBagError, match="incomplete"):
        BagReader(cut)
    with BagReader(cut, recover=True) as bag:
        assert not bag.recovery.complete
        assert bag.recovery.complete_chunks == len(chunks) // 2
        assert 0 < len(list(bag.messages(decode=False))) < total


def _file_with_chunk_compression(path: Path, compression: str, with_summary: bool) -> Path:
    """A ros2 MCAP file whose one chunk says it is compressed with ``compression``."""
    from backlash_monitor.bag.records import (ChunkIndex, MAGIC, U32, chunk_index_record,
                                              chunk_record_head, data_end_record, footer_head,
                                              header_record)

    out = bytearray(MAGIC + header_record("ros2", "test"))
    payload = b"\x28\xb5\x2f\xfd" + bytes(20)
    chunk_at = len(out)
    out += chunk_record_head(1, 2, 100, 0, compression, len(payload)) + payload
    chunk_len = len(out) - chunk_at
    out += data_end_record(0)
    summary_start = 0
    if with_summary:
        summary_start = len(out)
        out += chunk_index_record(ChunkIndex(1, 2, chunk_at, chunk_len, {}, 0, compression,
                                             len(payload), 100))
    out += footer_head(summary_start, 0) + U32.pack(0) + MAGIC
    path.write_bytes(bytes(out))
    return path


@pytest.mark.parametrize("with_summary", [True, False], ids=["chunk index", "no summary"])
def test_an_unknown_chunk_compression_is_refused_naming_it(tmp_path, with_summary, capsys):
    from backlash_monitor.commands import bag_info

    path = _file_with_chunk_compression(tmp_path / "b.mcap", "bz2", with_summary)
    with pytest.raises(UnsupportedBagError, match="'bz2' is not supported"):
        BagReader(path)
    with pytest.raises(UnsupportedBagError):
        BagReader(path, recover=True)          # not damage: recovery does not read it short
    assert bag_info.main([str(path)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "bz2" in err[0] and "not supported" in err[0]


@pytest.mark.parametrize("options", [{"noStatistics": True, "noMessageIndex": True},
                                     {"noSummary": True, "noMessageIndex": True},
                                     {"noSummary": True}],
                         ids=["counted at open", "no summary, counted at open",
                              "no summary, found while reading"])
def test_a_damaged_chunk_in_another_layout_is_named_and_skipped(tmp_path, project_bag, options):
    """Damage is still damage in these layouts: the chunk is named (DamagedBagError; bag-info exit
    1), and recovery reads every other chunk and counts only what it read."""
    import bag_damage
    from backlash_monitor.bag import DamagedBagError
    from backlash_monitor.commands import bag_info

    path = mc.rewrite_with_mcap(project_bag, tmp_path / "layout.mcap", chunkSize=128 * 1024,
                                **options)
    with BagReader(path) as bag:
        chunks = bag.chunks
        everything = [(m.topic, m.log_time_ns, m.sequence) for m in bag.messages(decode=False)]
    bad = chunks[len(chunks) // 2]
    damaged = tmp_path / "damaged.mcap"
    damaged.write_bytes(bag_damage.chunk_payload_byte(path.read_bytes(), bad.offset, bad.length))
    with pytest.raises(DamagedBagError, match=f"byte {bad.offset}"):
        with BagReader(damaged) as bag:
            list(bag.messages(decode=False))
    assert bag_info.main([str(damaged)]) == 1
    with BagReader(damaged, recover=True) as bag:
        got = [(m.topic, m.log_time_ns, m.sequence) for m in bag.messages(decode=False)]
        assert [d.offset for d in bag.recovery.skipped] == [bad.offset]
        assert bag.recovery.complete                # the file itself ends properly
        assert bag.message_count == len(got)        # the counts drop what was skipped
    lost = [k for k in everything if k not in got]
    assert got == [k for k in everything if k not in lost] and 0 < len(lost) < len(everything)
    assert all(bad.start <= t <= bad.end for _topic, t, _seq in lost)
