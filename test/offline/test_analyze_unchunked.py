"""`analyze` of a file without chunks (rosbag2's noChunking) joins its ranges at once
(BagReader.signal_chunk_columns, ChunkJoiner.add_rows) when they come whole, one after the other,
and chunk by chunk otherwise: the same estimates, discards, faults and outputs either way, byte for
byte, as reading it chunk by chunk."""

import pytest

pytest.importorskip("backlash_monitor.plant")

from backlash_monitor.chain import joiner  # noqa: E402
from backlash_monitor.bag import BagReader, BagWriter  # noqa: E402
from backlash_monitor.errors import UsageError  # noqa: E402
from backlash_monitor.offline.bag_analysis import AnalyzeOptions, analyze_bag  # noqa: E402

from bag_helpers import analyze_outputs, write_simulated_drive  # noqa: E402
from mcap_conformance import rewrite_with_mcap  # noqa: E402


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    return write_simulated_drive(tmp_path_factory.mktemp("sim") / "drive.mcap")


def rewritten(src, dst, drop=None, change=None):
    """``src`` written again by our writer (message ``drop`` left out, ``change(topic, data)`` applied),
    then without chunks by the `mcap` writer."""
    tmp = dst.with_name(dst.stem + "_chunked.mcap")
    with BagReader(src) as bag, BagWriter(tmp) as out:
        for topic in bag.topics.values():
            out.add_topic(topic.name, topic.type)
        for i, m in enumerate(bag.messages(decode=False)):
            if i != drop:
                out.write_raw(m.topic, change(m.topic, m.data) if change else m.data,
                              log_time_ns=m.log_time_ns)
    return rewrite_with_mcap(tmp, dst, noChunking=True)


def analyzed(bag, out, monkeypatch, at_once: bool):
    """(result without run time, CSV, MCAP bytes, JSON without run time and bag path) of analyze,
    and whether the ranges were joined at once."""
    joined = []
    add_rows = joiner.ChunkJoiner.add_rows

    def spy(self, *args):
        got = add_rows(self, *args)
        joined.append(got is not None)
        return got
    with monkeypatch.context() as patch:
        patch.setattr(joiner.ChunkJoiner, "add_rows", spy)
        if not at_once:
            patch.setattr(BagReader, "signal_chunk_columns", lambda self, topics: None)
        out.mkdir()
        result = analyze_bag(bag, out / "estimates", AnalyzeOptions())   # (the MCAP names itself)
    return analyze_outputs(result), any(joined)


def test_whole_ranges_at_once_give_the_same_outputs(tmp_path, recording, monkeypatch):
    bag = rewrite_with_mcap(recording, tmp_path / "unchunked.mcap", noChunking=True)
    fast, took = analyzed(bag, tmp_path / "fast", monkeypatch, at_once=True)
    slow, _ = analyzed(bag, tmp_path / "slow", monkeypatch, at_once=False)
    assert took
    assert fast == slow
    assert fast[0]["rows"] and fast[0]["drive"] == "drive"


def test_a_missing_chunk_is_read_chunk_by_chunk(tmp_path, recording, monkeypatch):
    """A range missing a chunk: not whole ranges; read chunk by chunk (the joiner counts it)."""
    bag = rewritten(recording, tmp_path / "dropped.mcap", drop=200)
    fast, took = analyzed(bag, tmp_path / "fast", monkeypatch, at_once=True)
    slow, _ = analyzed(bag, tmp_path / "slow", monkeypatch, at_once=False)
    assert not took
    assert fast == slow
    assert fast[1][0].get("incomplete_range") == 1


@pytest.mark.parametrize("topic", ["/plant/a1", "/plant/a2"])
def test_a_topic_carrying_another_unit_is_handled_as_chunk_by_chunk(tmp_path, recording, monkeypatch,
                                                                    topic):
    """Refused on the first topic (its chunks dropped as wrong_signal after another topic's were
    accepted: here every range then incomplete, so nothing analysed): the same error both ways."""
    def other_unit(name, data):
        return data.replace(b"m/s^2\x00", b"m/s^3\x00") if name == topic else data
    bag = rewritten(recording, tmp_path / "unit.mcap", change=other_unit)
    errors = []
    for at_once in (True, False):
        with pytest.raises(UsageError) as error:
            analyzed(bag, tmp_path / str(at_once), monkeypatch, at_once=at_once)
        errors.append(str(error.value))
    assert errors[0] == errors[1]
    assert ("carries a1 in 'm/s^3'" if topic.endswith("a1") else "wrong_signal") in errors[0]
