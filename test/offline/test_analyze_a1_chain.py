"""analyze where a1's own sensor chain is what is wrong (windowing/a1_chain.py, classifier/signal_check.py), on
recordings of the independent simulator (foreign_drives/; spent sets 12 and 7): a quadratic characteristic on a1 and a
telemetry AGC on a1. Both accelerometer fusions read a1, so the signal check's motor side is no help there; a1 does
not follow the recorded motor speed, and a1+a2's fused width is a2's, within a few tenths of a millimetre of the truth
(a1+a2 was 4.5 and 1.0 mm off). A clean drive of the same simulator keeps its own fusion, its a1 checked sound."""
import json

import pytest

pytest.importorskip("foreign_drives")

from backlash_monitor.classifier.signal_check import BOTH_SIGNALS, LOAD_SIDE_SIGNAL  # noqa: E402
from backlash_monitor.commands.analyze import print_signal_check  # noqa: E402
from backlash_monitor.offline.bag_analysis import AnalyzeOptions, analyze_bag  # noqa: E402
from backlash_monitor.windowing.a1_chain import MAX_MISMATCH  # noqa: E402


def _analyzed(suite_name: str, label: str, tmp_path):
    from foreign_drives.drive import make_recording
    from foreign_drives.files import write_bag
    from foreign_drives.suites import suite
    spec = next(s for s in suite(suite_name) if s.label == label)
    rec = make_recording(spec)
    bag = write_bag(spec, tmp_path / "drive.mcap", recording=rec)
    result = analyze_bag(bag, tmp_path / "out", AnalyzeOptions())
    return rec.truth.true_width_m, result, json.loads(result["outputs"]["json"].read_text())


@pytest.mark.parametrize("suite_name,label", [("outside_sealed12", "os12_a1_quadratic_distortion"),
                                              ("outside_sealed7", "os7_a1_telemetry_agc")])
def test_an_a1_that_does_not_follow_the_motor_speed_gives_the_load_sides_width(suite_name, label, tmp_path, capsys):
    truth_m, result, doc = _analyzed(suite_name, label, tmp_path)
    chain = doc["a1_chain"]
    assert chain["faulty"] and chain["mismatch"] > MAX_MISMATCH
    both = [r for r in doc["estimates"] if r["signal"] == BOTH_SIGNALS]
    load = {r["entry_sample_index"]: r for r in doc["estimates"] if r["signal"] == LOAD_SIDE_SIGNAL}
    last = both[-1]
    assert last["fused_from_signal"] == LOAD_SIDE_SIGNAL
    assert last["fused_continuous_width_m"] == load[last["entry_sample_index"]]["fused_continuous_width_m"]
    assert "a1 does not follow" in last["check_reason"]
    summary = result["summary"]["per_signal"][BOTH_SIGNALS]
    assert abs(summary["fused_continuous_width_m"] - truth_m) < 0.3e-3, (summary, truth_m)
    # the fleet table's row of the same bag (analyze FOLDER): its width is a2's median over the recording
    from backlash_monitor.fleet.folder_analysis import recording_fields
    row = recording_fields(str(tmp_path / "drive.mcap"), result)
    assert row["signal"] == LOAD_SIDE_SIGNAL and abs(row["width_m"] - truth_m) < 0.3e-3, (row, truth_m)
    assert row["a1_chain_mismatch"] > MAX_MISMATCH and row["a1_chain_fault"].endswith("its width is a2's")
    print_signal_check(result["summary"])
    line = capsys.readouterr().out
    assert line.startswith("WARN: a1+a2's fused width is a2's: a1+a2 reads a1, and a1 does not follow")
    assert "check a1's sensor chain" in line


def test_a_clean_drive_keeps_both_together_with_its_a1_checked_sound(tmp_path, capsys):
    truth_m, result, doc = _analyzed("outside_sealed12", "os12_clean_w7.6_eta0.0320_n0.92", tmp_path)
    chain = doc["a1_chain"]
    assert chain["mismatch"] < 0.01 and not chain["faulty"] and chain["seconds"] >= 2.5
    assert all(r["fused_from_signal"] != LOAD_SIDE_SIGNAL for r in doc["estimates"] if r["signal"] == BOTH_SIGNALS)
    print_signal_check(result["summary"])
    assert "a2's" not in capsys.readouterr().out
