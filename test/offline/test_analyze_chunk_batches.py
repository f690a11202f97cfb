"""`analyze` of a chunked bag takes each chunk's SignalChunk messages as columns
(BagReader.signal_chunk_batches) and joins the chunk's whole ranges at once (ChunkJoiner.add_rows),
the rows of a range split over two chunks one by one: the same estimates, discards, faults and
outputs, byte for byte, as reading it message by message -- with ranges split over chunks, chunks
of every compression, a missing message, a damaged chunk recovered, a payload changed mid-file."""

import numpy as np
import pytest

pytest.importorskip("backlash_monitor.plant")

from backlash_monitor.chain import joiner  # noqa: E402
from backlash_monitor.bag import BagReader, BagWriter  # noqa: E402
import bag_damage  # noqa: E402
from backlash_monitor.bag import reader as reader_module  # noqa: E402
from backlash_monitor.offline.bag_analysis import AnalyzeOptions, analyze_bag  # noqa: E402

from bag_helpers import analyze_outputs, write_simulated_drive  # noqa: E402


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    return write_simulated_drive(tmp_path_factory.mktemp("sim") / "drive.mcap")


def rewritten(src, dst, *, drop=None, change=None, **writer):
    """``src`` written again by our writer with ``writer``'s chunking and compression (message
    ``drop`` left out, ``change(index, topic, data)`` applied)."""
    with BagReader(src) as bag, BagWriter(dst, **writer) as out:
        for topic in bag.topics.values():
            out.add_topic(topic.name, topic.type)
        for i, m in enumerate(bag.messages(decode=False)):
            if i != drop:
                out.write_raw(m.topic, change(i, m.topic, m.data) if change else m.data,
                              log_time_ns=m.log_time_ns)
    return dst


def analyzed(bag, out, monkeypatch, batches: bool, recover: bool = False):
    """(result without run time, fault counts, CSV, MCAP bytes, JSON without run time and bag path)
    of analyze, and how many chunks went as columns and how many ranges add_rows joined."""
    columns, joined = [], []
    chunk_columns, add_rows = reader_module._chunk_signal_columns, joiner.ChunkJoiner.add_rows

    def spy_columns(*args):
        got = chunk_columns(*args) if batches else None
        columns.append(got is not None)
        return got

    def spy_rows(self, *args):
        got = add_rows(self, *args)
        joined.append(len(got) if got else 0)
        return got
    with monkeypatch.context() as patch:
        patch.setattr(reader_module, "_chunk_signal_columns", spy_columns)
        patch.setattr(joiner.ChunkJoiner, "add_rows", spy_rows)
        out.mkdir()
        result = analyze_bag(bag, out / "estimates", AnalyzeOptions(recover=recover), chunks_ahead=0)
    return analyze_outputs(result), sum(columns), sum(joined)


def both_ways(bag, tmp_path, monkeypatch, **kw):
    fast, n_columns, n_joined = analyzed(bag, tmp_path / "batches", monkeypatch, True, **kw)
    slow, _, _ = analyzed(bag, tmp_path / "one_by_one", monkeypatch, False, **kw)
    assert fast == slow
    assert fast[0]["rows"]
    return fast, n_columns, n_joined


@pytest.mark.parametrize("compression", ["zstd", "lz4", ""])
def test_ranges_split_over_chunks_give_the_same_outputs(tmp_path, recording, monkeypatch, compression):
    """Chunks of 50 kB (each ~6 messages: nearly every chunk begins or ends inside a range)."""
    bag = rewritten(recording, tmp_path / "small.mcap", compression=compression, chunk_size=50_000,
                    chunk_duration_s=None)
    with BagReader(bag) as reader:
        assert len(reader.chunks) > 50
    _, n_columns, n_joined = both_ways(bag, tmp_path, monkeypatch)
    assert n_columns > 40 and n_joined > 0


def test_the_project_layout_joins_whole_chunks(tmp_path, recording, monkeypatch):
    (result, *_), n_columns, n_joined = both_ways(recording, tmp_path, monkeypatch)
    with BagReader(recording) as reader:
        assert n_columns == len(reader.chunks) - 1      # the first chunk one by one (its strings)
    ranges = result["n_samples"] / 1000     # of 1000 samples; the first 0.5 s chunk's one by one
    assert n_joined >= 0.7 * ranges


def test_a_missing_message_gives_the_same_outputs(tmp_path, recording, monkeypatch):
    bag = rewritten(recording, tmp_path / "dropped.mcap", drop=500)
    fast, n_columns, _ = both_ways(bag, tmp_path, monkeypatch)
    assert fast[1][0].get("incomplete_range") == 1 and n_columns > 0


def test_a_damaged_chunk_recovered_gives_the_same_outputs(tmp_path, recording, monkeypatch):
    with BagReader(recording) as reader:
        middle = reader.chunks[len(reader.chunks) // 2]
    bag = tmp_path / "damaged.mcap"
    bag.write_bytes(bag_damage.chunk_payload_byte(recording.read_bytes(), middle.offset, middle.length))
    fast, n_columns, _ = both_ways(bag, tmp_path, monkeypatch, recover=True)
    assert fast[0]["integrity"]["damaged_chunks"] and n_columns > 0


def test_a_payload_laid_out_otherwise_mid_file_gives_the_same_outputs(tmp_path, recording,
                                                                      monkeypatch):
    """From message 300 on, a1's frame_id is 8 bytes longer (its string section, so every offset
    after it, moves): that chunk goes one by one, the next ones as columns again."""
    def longer_frame(i, topic, data):
        if i < 300 or topic != "/plant/a1":
            return data
        return data.replace(b"\x06\x00\x00\x00drive\x00", b"\x0e\x00\x00\x00drive_b_pad_x\x00", 1)
    bag = rewritten(recording, tmp_path / "frame.mcap", change=longer_frame)
    with BagReader(bag) as reader:
        frames = {m.frame_id for m in reader.signal_chunks(["/plant/a1"])}
    assert frames == {"drive", "drive_b_pad_x"}
    _, n_columns, _ = both_ways(bag, tmp_path, monkeypatch)
    assert n_columns > 0


def test_columns_hold_what_signal_chunks_yields(recording):
    topics = ["/plant/a1", "/plant/a2", "/plant/angle_difference"]
    with BagReader(recording, chunks_ahead=0) as reader:
        want = list(reader.signal_chunks(topics, copy=False))
        batches = list(reader.signal_chunk_batches(topics))
        got = [r for b in batches for r in (b if type(b) is list else b.records())]
    assert any(type(b) is not list for b in batches)
    assert len(got) == len(want)
    for g, w in zip(got, want):
        assert g._replace(samples=None) == w._replace(samples=None)
        assert g.samples.dtype == w.samples.dtype and np.array_equal(g.samples, w.samples)
        assert not g.samples.flags.writeable
