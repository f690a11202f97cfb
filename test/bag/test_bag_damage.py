"""Damaged bags: every chunk is checked against the chunk index and its CRC; damage is an error
naming the chunk (offset, log time, messages) unless recovering; recovery reads every intact chunk
(past a damaged length field by the index, or by resynchronising without one) and reports the gap.

The expected messages come from the intact file (the messages of the chunks that are not damaged),
so a reader that stops at the damage, reads past it into garbage, or says nothing fails here."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from backlash_monitor.bag import BagReader, DamagedBagError, TruncatedBagError
import bag_damage
from bag_helpers import write_sample_bag

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def intact(tmp_path_factory):
    """A bag of 12 chunks (0.1 s each) and, per chunk, the keys of the messages in it."""
    path = tmp_path_factory.mktemp("damage") / "intact.mcap"
    write_sample_bag(path, n_chunks=60, chunk_duration_s=0.1)
    layout = bag_damage.chunk_layout(path)
    with BagReader(path) as bag:
        keys = [(m.topic, m.log_time_ns, m.sequence) for m in bag.messages(decode=False)]
    per_chunk = [[k for k in keys if start <= k[1] <= end] for _off, _len, start, end in layout]
    assert len(layout) >= 10 and sum(map(len, per_chunk)) == len(keys)
    return path, path.read_bytes(), layout, keys, per_chunk


def _keys(bag):
    return [(m.topic, m.log_time_ns, m.sequence) for m in bag.messages(decode=False)]


DAMAGE = {
    "length_too_long": lambda d, off, ln: bag_damage.chunk_length_field(d, off, 3 * ln),
    "length_too_short": lambda d, off, ln: bag_damage.chunk_length_field(d, off, 100),
    "length_huge": lambda d, off, ln: bag_damage.chunk_length_field(d, off, 1 << 40),
    "crc_field": lambda d, off, ln: bag_damage.chunk_crc_field(d, off),
    "payload_byte": lambda d, off, ln: bag_damage.chunk_payload_byte(d, off, ln),
}
# only a header field: the contents pass the CRC and are read
CONTENTS_INTACT = {"length_too_long", "length_too_short", "length_huge"}


@pytest.mark.parametrize("summary", [True, False], ids=["with_summary", "without_summary"])
@pytest.mark.parametrize("kind", sorted(DAMAGE))
def test_a_damaged_chunk_is_named_and_recovery_reads_every_other_chunk(intact, tmp_path, kind,
                                                                       summary):
    path, data, layout, keys, per_chunk = intact
    k = 4
    off, length, start, end = layout[k]
    damaged = DAMAGE[kind](data, off, length)
    if not summary:
        damaged = bag_damage.without_summary(damaged)
    bad = tmp_path / "bad.mcap"
    bad.write_bytes(damaged)
    with pytest.raises((DamagedBagError, TruncatedBagError)) as error:
        BagReader(bad)
    text = str(error.value)
    assert f"byte {off}" in text and "recover" in text
    if summary:
        assert isinstance(error.value, DamagedBagError)
    with BagReader(bad, recover=True) as bag:
        got = _keys(bag)
        report = bag.recovery
        ranges = [(d.offset, d.start_ns, d.end_ns) for d in report.damaged]
    assert ranges == [(off, start, end)], report.describe()
    d = report.damaged[0]
    assert d.messages == len(per_chunk[k])
    if kind in CONTENTS_INTACT:
        assert d.recovered and got == keys and report.skipped_messages == 0
    else:
        assert not d.recovered and d.length_bytes == length
        assert got == [key for key in keys if key not in per_chunk[k]]
        assert report.skipped_messages == len(per_chunk[k]) and report.skipped_bytes == length
    if summary:   # the counts no longer include what could not be read
        assert bag.message_count == len(got)


def test_damaged_record_header_without_summary_resynchronises_on_the_next_chunk(intact, tmp_path):
    path, data, layout, keys, per_chunk = intact
    off = layout[3][0]
    broken = bytearray(bag_damage.without_summary(data))
    broken[off:off + 40] = b"\xee" * 40   # opcode, length and time range of chunk 3 destroyed
    bad = tmp_path / "garbage.mcap"
    bad.write_bytes(bytes(broken))
    with BagReader(bad, recover=True) as bag:
        got = _keys(bag)
        report = bag.recovery
    assert got == [key for key in keys if key not in per_chunk[3]]
    assert [d.offset for d in report.damaged] == [off]
    assert report.damaged[0].length_bytes == layout[4][0] - off   # up to the next chunk
    assert report.damaged[0].messages == len(per_chunk[3])       # from its message index records


def test_summary_crc_mismatch_is_an_error_and_recovery_reads_everything(intact, tmp_path):
    path, data, _layout, keys, _ = intact
    bad = tmp_path / "summary.mcap"
    bad.write_bytes(bag_damage.summary_byte(data))
    with pytest.raises(TruncatedBagError, match="summary section CRC mismatch"):
        BagReader(bad)
    with BagReader(bad, recover=True) as bag:
        assert _keys(bag) == keys


def test_data_crc_mismatch_outside_the_chunks_is_reported(intact, tmp_path):
    path, data, layout, keys, _ = intact
    off, length = layout[2][:2]
    broken = bytearray(data)
    broken[off + length + 9 + 3] ^= 0x01    # inside the message index record after chunk 2
    bad = tmp_path / "index.mcap"
    bad.write_bytes(bytes(broken))
    with pytest.raises(DamagedBagError, match="data section CRC mismatch outside the chunks"):
        BagReader(bad)
    with BagReader(bad, recover=True) as bag:
        assert _keys(bag) == keys and bag.recovery.damaged == []


def test_intact_bag_is_verified_by_its_data_crc(intact):
    path, *_ = intact
    with BagReader(path) as bag:
        assert bag.recovery.intact and bag.recovery.verified


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "backlash_monitor", *map(str, args)],
                          capture_output=True, text=True, cwd=REPO, timeout=300)


@pytest.mark.process
def test_bag_info_reports_a_crc_error_and_recover_names_the_chunk(intact, tmp_path):
    path, data, layout, _keys_, per_chunk = intact
    off, length = layout[5][:2]
    bad = tmp_path / "crc.mcap"
    bad.write_bytes(bag_damage.chunk_crc_field(data, off))
    strict = _cli("bag-info", bad)
    assert strict.returncode == 1
    assert "CRC mismatch" in strict.stderr and "--recover" in strict.stderr
    assert len(strict.stderr.strip().splitlines()) == 1 and "Traceback" not in strict.stderr
    assert "complete" not in strict.stdout
    rec = _cli("bag-info", bad, "--recover", "--format", "json")
    assert rec.returncode == 0, rec.stderr
    info = json.loads(rec.stdout)
    assert not info["intact"]
    [chunk] = info["recovery"]["damaged_chunks"]
    assert chunk["offset"] == off and chunk["messages"] == len(per_chunk[5]) and not chunk["recovered"]
    assert info["recovery"]["skipped_messages"] == len(per_chunk[5])


# ------------------------------------------------------------------ analyze on damaged / wrong bags

@pytest.fixture(scope="module")
def drive_bag(tmp_path_factory):
    """A 2 s simulated drive (4 chunks of 0.5 s) and its analysis."""
    directory = tmp_path_factory.mktemp("drive")
    proc = _cli("simulate", "--widths", "0.005", "--eta-k", "0.025", "--n1", "0.89", "--duration", "2",
                "--no-npz", "--mcap", directory / "sim", "--no-progress")
    assert proc.returncode == 0, proc.stderr
    [bag] = sorted((directory / "sim").glob("*.mcap"))
    out = _cli("analyze", bag, "--out", directory / "ref", "--no-model-fit")    # (its fit: ~3.5 s of CPU)
    assert out.returncode == 0, out.stderr
    return bag, json.loads((directory / "ref.json").read_text())


def _analyze(bag, tmp_path, *extra):
    proc = _cli("analyze", bag, "--out", tmp_path / "out", "--overwrite", *extra)
    result = json.loads((tmp_path / "out.json").read_text()) if proc.returncode == 0 else None
    return proc, result


@pytest.mark.process
def test_analyze_refuses_a_damaged_length_and_recovers_all_of_it(drive_bag, tmp_path):
    bag, reference = drive_bag
    off, length = bag_damage.chunk_layout(bag)[1][:2]
    bad = tmp_path / "len.mcap"
    bad.write_bytes(bag_damage.chunk_length_field(bag.read_bytes(), off, 2 * length))
    proc, _ = _analyze(bad, tmp_path)
    assert proc.returncode == 1 and "chunk length field damaged" in proc.stderr
    assert "--recover" in proc.stderr and "Traceback" not in proc.stderr
    proc, result = _analyze(bad, tmp_path, "--recover")
    assert proc.returncode == 0, proc.stderr
    assert result["samples_analysed"] == reference["samples_analysed"]   # nothing lost
    [chunk] = result["bag_integrity"]["damaged_chunks"]
    assert chunk["offset"] == off and chunk["recovered"]


@pytest.mark.process
def test_analyze_recover_records_the_skipped_chunk(drive_bag, tmp_path):
    bag, reference = drive_bag
    layout = bag_damage.chunk_layout(bag)
    off, length, start, end = layout[2]
    bad = tmp_path / "crc.mcap"
    bad.write_bytes(bag_damage.chunk_payload_byte(bag.read_bytes(), off, length))
    proc, _ = _analyze(bad, tmp_path)
    assert proc.returncode == 1 and f"byte {off}" in proc.stderr
    proc, result = _analyze(bad, tmp_path, "--recover")
    assert proc.returncode == 0, proc.stderr
    integrity = result["bag_integrity"]
    [chunk] = integrity["damaged_chunks"]
    assert (chunk["offset"], chunk["start_ns"], chunk["end_ns"]) == (off, start, end)
    assert chunk["end_s"] - chunk["start_s"] == pytest.approx((end - start) / 1e9)
    assert chunk["messages"] == integrity["skipped_messages"] > 0
    # the ranges (1000 samples) of which an analysed signal was in the chunk are lost, no more
    with BagReader(bag) as intact:
        hit = {m.first_sample_index for m in intact.signal_chunks(
            ["/plant/a1", "/plant/a2", "/plant/angle_difference"]) if start <= m.log_time_ns <= end}
    lost_samples = reference["samples_analysed"] - result["samples_analysed"]
    assert lost_samples == len(hit) * 1000 >= 25_000
    assert "skipped" not in proc.stderr and "DAMAGED" in proc.stdout
    # the model fit reads the whole recording: on a damaged one it says why it was not run, the analysis stands
    assert "model fit: not evaluated: " in proc.stdout and "damaged" in proc.stdout.split("model fit: ")[1]


def _rewritten(bag, tmp_path, change, name):
    out = tmp_path / f"{name}.mcap"
    bag_damage.rewrite_signals(bag, out, change)
    return out


@pytest.mark.process
def test_analyze_refuses_another_sample_rate_and_another_signal(drive_bag, tmp_path):
    bag, _ = drive_bag

    def slower(topic, f):
        f["sample_period_s"] = 4e-5
        return f

    def swapped(topic, f):
        if topic.endswith("/a1"):
            f["signal_name"], f["unit"] = "omega1", "rad/s"
        return f

    proc, _ = _analyze(_rewritten(bag, tmp_path, slower, "rate"), tmp_path)
    assert proc.returncode == 2 and "25000 Hz" in proc.stderr and "50000 Hz" in proc.stderr
    assert "Traceback" not in proc.stderr
    proc, _ = _analyze(_rewritten(bag, tmp_path, swapped, "swapped"), tmp_path)
    assert proc.returncode == 2 and "carries signal 'omega1'" in proc.stderr


@pytest.mark.process
def test_analyze_counts_bad_periods_and_unequal_lengths(drive_bag, tmp_path):
    bag, reference = drive_bag

    def broken(topic, f):
        if f["first_sample_index"] == 10_000:
            f["sample_period_s"] = float("nan")
        if f["first_sample_index"] == 20_000 and topic.endswith("/a2"):
            f["samples"] = f["samples"][:500]
        if f["first_sample_index"] == 30_000 and topic.endswith("/a1"):
            f["samples"] = f["samples"].copy()
            f["samples"][17] = float("nan")
        return f

    proc, result = _analyze(_rewritten(bag, tmp_path, broken, "broken"), tmp_path)
    assert proc.returncode == 0, proc.stderr
    # counted with the live chain's reasons (input_faults.REASONS), one per sample range
    faults = result["input_faults"]
    assert (faults["bad_sample_period"], faults["length_mismatch"], faults["non_finite_samples"]) == (1, 1, 1)
    assert result["samples_analysed"] == reference["samples_analysed"] - 3000
    assert all(np.isfinite(r["width_m"]) and np.all(np.isfinite(r["b_vector"]))
               for r in result["estimates"]) and result["estimates"]

    def all_bad(topic, f):
        f["sample_period_s"] = 0.0
        return f

    proc, _ = _analyze(_rewritten(bag, tmp_path, all_bad, "zero"), tmp_path)
    assert proc.returncode == 2 and "no samples could be analysed" in proc.stderr
    assert "Traceback" not in proc.stderr


@pytest.mark.process
@pytest.mark.ros
def test_replay_names_the_damage_and_recover_plays_every_intact_chunk(intact, tmp_path, ros_env):
    path, data, layout, keys, per_chunk = intact
    off, length = layout[6][:2]
    bad = tmp_path / "replay.mcap"
    bad.write_bytes(bag_damage.chunk_payload_byte(data, off, length))

    def replay(*params):
        return subprocess.run([sys.executable, "-m", "backlash_monitor.nodes.replay", "--ros-args",
                               "-p", f"bag:={bad}", "-p", "rate:=1000.0", *params], env=ros_env,
                              cwd=REPO, capture_output=True, text=True, timeout=120)

    strict = replay()
    assert strict.returncode == 2 and f"byte {off}" in strict.stderr
    assert "recover:=true" in strict.stderr and "Traceback" not in strict.stderr
    played = replay("-p", "recover:=true")
    assert played.returncode == 0, played.stderr
    assert f"played {len(keys) - len(per_chunk[6])} messages" in played.stderr
    assert "skipped: 1 damaged chunk(s)" in played.stderr


def _mcap_library_bag(path, index_types):
    """A ROS 2 bag written by the `mcap` library (no data-section CRC, like other writers), with
    small chunks; returns the keys of its messages."""
    from mcap.writer import CompressionType, Writer

    from backlash_monitor.bag import SIGNAL_CHUNK, Codec, full_definition

    codec = Codec.for_type(SIGNAL_CHUNK)
    rng = np.random.default_rng(3)
    keys = []
    with open(path, "wb") as f:
        w = Writer(f, chunk_size=20_000, compression=CompressionType.ZSTD, index_types=index_types)
        w.start(profile="ros2", library="test")
        sid = w.register_schema(SIGNAL_CHUNK, "ros2msg", full_definition(SIGNAL_CHUNK).encode())
        cid = w.register_channel("/plant/a1", "cdr", sid)
        for i in range(40):
            data = codec.encode(codec.new(signal_name="a1", unit="m/s^2", sample_period_s=2e-5,
                                          first_sample_index=i * 1000,
                                          samples=rng.standard_normal(1000)))
            w.add_message(cid, log_time=i * 20_000_000, publish_time=i * 20_000_000, data=data,
                          sequence=i)
            keys.append(("/plant/a1", i * 20_000_000, i))
        w.finish()
    return keys


@pytest.mark.process
def test_a_bag_without_data_crc_has_its_chunk_crcs_checked_when_read(tmp_path):
    from mcap.writer import IndexType

    good = tmp_path / "other_writer.mcap"
    keys = _mcap_library_bag(good, IndexType.ALL)
    with BagReader(good) as bag:
        assert _keys(bag) == keys and not bag.recovery.verified   # nothing vouched for by a CRC
        assert bag.verify().intact
    layout = bag_damage.chunk_layout(good)
    off, _length, start, end = layout[3]
    in_chunk = [k for k in keys if start <= k[1] <= end]     # log times are unique here
    bad = tmp_path / "crc.mcap"
    bad.write_bytes(bag_damage.chunk_crc_field(good.read_bytes(), off))
    with BagReader(bad) as bag:                      # only reading can tell
        with pytest.raises(DamagedBagError, match=f"byte {off}"):
            _keys(bag)
    with BagReader(bad, recover=True) as bag:
        got = _keys(bag)
        assert [d.offset for d in bag.recovery.damaged] == [off]
        lost = bag.recovery.damaged[0].messages
    assert lost == len(in_chunk) > 0 and got == [k for k in keys if k not in in_chunk]
    proc = _cli("bag-info", bad)                      # bag-info checks every chunk
    assert proc.returncode == 1 and "CRC mismatch" in proc.stderr


def test_a_bag_without_chunk_index_is_scanned_and_a_damaged_length_recovered(tmp_path):
    from mcap.writer import IndexType

    good = tmp_path / "no_index.mcap"
    keys = _mcap_library_bag(good, IndexType.NONE)
    with BagReader(good) as bag:
        assert _keys(bag) == keys and bag.recovery.intact
    layout = bag_damage.chunk_layout(good)
    off, length = layout[2][:2]
    bad = tmp_path / "no_index_len.mcap"
    bad.write_bytes(bag_damage.chunk_length_field(good.read_bytes(), off, 5 * length))
    with pytest.raises(DamagedBagError, match="chunk length field damaged"):
        BagReader(bad)
    with BagReader(bad, recover=True) as bag:
        assert _keys(bag) == keys
        assert [(d.offset, d.recovered) for d in bag.recovery.damaged] == [(off, True)]


@pytest.mark.process
def test_analyze_refuses_a_library_without_the_signals_it_classifies(drive_bag, tmp_path):
    from backlash_monitor.classifier.patterns import load_library

    bag, _ = drive_bag
    lib = load_library(None, trigger="contact_loss")
    lib.signals = ("a1",)                       # a library trained on a1 alone
    path = lib.save(tmp_path / "a1_only.npz")
    proc, _ = _analyze(bag, tmp_path, "--library", path)
    assert proc.returncode == 2 and "has no patterns for a2" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_a_library_without_a_stored_sample_period_is_a_50_khz_one(tmp_path):
    import json as json_

    from backlash_monitor.classifier.patterns import load_library

    lib = load_library(None, trigger="contact_loss")
    assert lib.sample_period_s == 2e-5
    del lib.settings["sample_period_s"]         # as libraries made before it was stored
    path = lib.save(tmp_path / "old.npz")
    with np.load(path) as z:
        assert "sample_period_s" not in json_.loads(str(z["meta"]))["settings"]
    old = load_library(path, sample_period_s=2e-5)
    assert old.sample_period_s == 2e-5
    with pytest.raises(ValueError, match="sample_period_s"):
        load_library(path, sample_period_s=4e-5)


@pytest.mark.process
def test_analyze_counts_an_accelerometer_sample_beyond_its_range_and_keeps_the_width(drive_bag, tmp_path):
    """One finite 1e300 in a1 (far beyond the sensor's declared +-1960 m/s^2, config/windowing.yaml
    sensors) is a counted fault like a NaN: its range is dropped, the windows spanning it are
    discarded, and no estimate moves: every other window's width is the clean bag's."""
    bag, reference = drive_bag

    def spike(topic, f):
        if f["first_sample_index"] == 20_000 and topic.endswith("/a1"):
            f["samples"] = f["samples"].copy()
            f["samples"][400] = 1e300
        return f

    proc, result = _analyze(_rewritten(bag, tmp_path, spike, "spike"), tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert result["input_faults"]["out_of_range_samples"] == 1
    assert result["samples_analysed"] == reference["samples_analysed"] - 1000
    clean = {(r["entry_sample_index"], r["signal"]): r for r in reference["estimates"]}
    assert result["estimates"] and len(result["estimates"]) < len(reference["estimates"]) + 1
    for r in result["estimates"]:
        ref = clean[(r["entry_sample_index"], r["signal"])]       # no window the clean bag has not
        # the same width (B vectors differ in the last digits: the offset estimate lacks the range)
        assert r["width_m"] == ref["width_m"]
        assert not abs(r["continuous_width_m"] - ref["continuous_width_m"]) >= 1e-4   # NaN where the mode has none
    for signal, s in result["summary"]["per_signal"].items():
        assert s["fused_width_m"] == reference["summary"]["per_signal"][signal]["fused_width_m"] == 0.005
