"""The evidence on a WARN (watch/snapshot.py): the ring of the plant topics as serialized, the bag of the X s
before and the Y s after a trigger, an ordinary project bag, never overwriting, never losing what it held."""
import datetime as dt
import threading

import numpy as np
import pytest

from backlash_monitor.bag.cdr import Codec
from backlash_monitor.watch.snapshot import PlantRing, SnapshotRecorder, snapshot_stem, unique_path, write_bag
from backlash_monitor.workbench.measurement import load_measurement

SIGNALS = ("a1", "a2", "omega1", "omega2", "angle_difference")
DT = 2e-5
CHUNK = 1000


def _chunk(codec, name, first, n=CHUNK):
    """A SignalChunk whose samples are their own stream index (plus an offset per signal): every sample of the
    bag can be checked against where it came from."""
    msg = codec.new(signal_name=name, unit="m/s^2", sample_period_s=DT, first_sample_index=first,
                    samples=np.arange(first, first + n, dtype=np.float64) + SIGNALS.index(name) * 1e7)
    msg.header.stamp.sec = 1_700_000_000 + first // 50_000
    msg.header.frame_id = "drive7"
    return codec.encode(msg)


def _stream(recorder, codec, chunks, start=0):
    for k in range(start, start + chunks):
        for name in SIGNALS:
            recorder.add(f"/line1/drive7/plant/{name}", k * CHUNK, CHUNK, 1_700_000_000_000_000_000 + k * 20_000_000,
                         _chunk(codec, name, k * CHUNK))


@pytest.fixture(scope="module")
def codec():
    return Codec.for_type("backlash_monitor_msgs/msg/SignalChunk")


def test_the_snapshot_is_an_ordinary_bag_of_the_samples_around_the_trigger(tmp_path, codec):
    types = {f"/line1/drive7/plant/{n}": "backlash_monitor_msgs/msg/SignalChunk" for n in SIGNALS}
    rec = SnapshotRecorder(tmp_path, "line1/drive7", DT, before_s=0.2, after_s=0.3, topics_types=types)
    when = dt.datetime(2026, 11, 24, 12, 3, 11, tzinfo=dt.timezone.utc)
    _stream(rec, codec, 40)                        # 0.8 s of stream
    snap = rec.trigger(40_000, when)               # at 0.8 s: 0.2 s before, 0.3 s after
    assert snap.path.name == "line1_drive7_20261124T120311.mcap" and snap.state == "recording"
    _stream(rec, codec, 20, start=40)              # 0.4 s more: the 0.3 s after have come
    rec.flush()
    assert snap.state == "written", snap.error
    meas = load_measurement(snap.path)             # what diagnose reads: contiguous, every plant signal
    assert set(meas.signals) == set(SIGNALS)
    a1 = meas.signals["a1"]
    assert a1[0] <= 40_000 - 10_000 and a1[-1] >= 40_000 + 15_000 - 1     # covers [trigger - 0.2 s, + 0.3 s)
    assert np.array_equal(np.diff(a1), np.ones(len(a1) - 1))              # no sample lost, none twice
    assert not list(tmp_path.glob("*.partial"))


def test_a_snapshot_never_replaces_a_file_and_a_second_trigger_waits(tmp_path, codec):
    types = {"/plant/a1": "backlash_monitor_msgs/msg/SignalChunk"}
    when = dt.datetime(2026, 11, 24, 12, 3, 11, tzinfo=dt.timezone.utc)
    taken = tmp_path / (snapshot_stem("drive7", when) + ".mcap")
    taken.write_bytes(b"someone's recording")
    rec = SnapshotRecorder(tmp_path, "drive7", DT, 0.02, 0.02, types, max_snapshots=1)
    for k in range(5):
        rec.add("/plant/a1", k * CHUNK, CHUNK, k, _chunk(codec, "a1", k * CHUNK))
    first = rec.trigger(3000, when)
    assert first.path.name == "drive7_20261124T120311_2.mcap"
    assert rec.trigger(4000, when) is None and rec.skipped == 1        # one at a time / max_snapshots
    rec.add("/plant/a1", 5 * CHUNK, CHUNK, 5, _chunk(codec, "a1", 5 * CHUNK))
    rec.flush()
    assert taken.read_bytes() == b"someone's recording"
    assert first.state == "written"
    assert unique_path(tmp_path, "drive7_20261124T120311").name == "drive7_20261124T120311_3.mcap"


def test_a_write_that_fails_keeps_its_partial_file_and_says_why(tmp_path, codec, monkeypatch):
    import backlash_monitor.bag as bag
    rec = SnapshotRecorder(tmp_path, "d", DT, 0.0, 0.02, {"/plant/a1": "backlash_monitor_msgs/msg/SignalChunk"})
    real = bag.BagWriter

    class Full(real):
        def close(self):
            raise OSError(28, "No space left on device")
    monkeypatch.setattr(bag, "BagWriter", Full)
    rec.add("/plant/a1", 0, CHUNK, 0, _chunk(codec, "a1", 0))
    snap = rec.trigger(0, dt.datetime(2026, 1, 1, tzinfo=dt.timezone.utc))
    rec.add("/plant/a1", CHUNK, CHUNK, 1, _chunk(codec, "a1", CHUNK))
    rec.flush()
    assert snap.state.startswith("failed") and "No space" in snap.error
    assert not snap.path.exists() and snap.path.with_name(snap.path.name + ".partial").exists()


def test_the_ring_drops_only_what_is_older_than_its_capacity():
    ring = PlantRing(capacity_samples=3000)
    for k in range(10):
        ring.add("/t", k * CHUNK, CHUNK, k, b"x")
    firsts = [c.first_sample_index for c in ring.chunks["/t"]]
    assert firsts == [7000, 8000, 9000]              # the chunks that hold the last 3000 samples (to 10000)
    assert ring.end() == 10_000
    assert [c.first_sample_index for c in ring.between(7500, 8500)] == [7000, 8000]
    ring.add("/t", 0, CHUNK, 11, b"y")               # the stream restarted: a new stream
    assert [c.first_sample_index for c in ring.chunks["/t"]] == [0]


def test_writer_threads_do_not_block_the_stream(tmp_path, codec):
    """The bag is written in a thread: trigger and add return at once."""
    types = {"/plant/a1": "backlash_monitor_msgs/msg/SignalChunk"}
    rec = SnapshotRecorder(tmp_path, "d", DT, 0.5, 0.02, types)
    for k in range(30):
        rec.add("/plant/a1", k * CHUNK, CHUNK, k, _chunk(codec, "a1", k * CHUNK))
    snap = rec.trigger(29_000, dt.datetime(2026, 1, 1, tzinfo=dt.timezone.utc))
    rec.add("/plant/a1", 30 * CHUNK, CHUNK, 30, _chunk(codec, "a1", 30 * CHUNK))
    assert snap.thread is not None and snap.thread is not threading.current_thread()
    rec.flush()
    assert snap.state == "written"
    assert write_bag  # the same writer, also usable directly
