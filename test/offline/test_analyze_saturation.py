"""A recording whose a2 is clipped (made by the foreign generator, clipped after its sensor chain): analyze's
JSON and console line and bag-info name the rail and the share of samples; the same recording unclipped is
clean in both."""
import dataclasses
import json

import numpy as np
import pytest

pytest.importorskip("foreign_drives")
pytest.importorskip("backlash_monitor.plant")

from backlash_monitor.commands import bag_info  # noqa: E402
from backlash_monitor.commands.analyze import print_saturation  # noqa: E402
from backlash_monitor.offline.bag_analysis import AnalyzeOptions, analyze_bag  # noqa: E402


@pytest.fixture(scope="module")
def bags(tmp_path_factory):
    from foreign_drives.drive import make_recording
    from foreign_drives.files import write_bag
    from foreign_drives.suites import BENCH
    spec = dataclasses.replace(next(s for s in BENCH if s.label == "clean_w5.0_eta0.025_n0.89"), duration_s=2.0)
    rec = make_recording(spec)
    folder = tmp_path_factory.mktemp("sat")
    clean = write_bag(spec, folder / "clean.mcap", recording=rec)
    a2 = rec.signals["a2"]
    rail = 0.75 * float(np.abs(a2).max())
    clipped_share = float(np.mean(np.abs(a2) > rail))
    rec.signals["a2"] = np.clip(a2, -rail, rail)
    clipped = write_bag(spec, folder / "clipped.mcap", recording=rec)
    return {"clean": clean, "clipped": clipped, "rail": rail, "share": clipped_share, "topic_ns": spec.namespace}


def test_analyze_reports_the_rail_in_its_json_and_line(bags, tmp_path, capsys):
    result = analyze_bag(bags["clipped"], tmp_path / "clipped", AnalyzeOptions())
    doc = json.loads(result["outputs"]["json"].read_text())
    sat = doc["input_saturation"]
    assert sat["saturated"] and sat["signals"]["a1"]["at_rail"] == 0
    a2 = sat["signals"]["a2"]
    assert a2["at_rail"] > 0 and a2["rail_percent"] == pytest.approx(100 * bags["share"], rel=0.2)
    assert bags["rail"] in [abs(v) for v in (a2["upper_rail"], a2["lower_rail"]) if v is not None]
    assert sat["saturated_windows"] > 0
    # a2 peaks at the end of a load pulse: its clipped stretches lie in the return windows, not in the
    # onset windows the estimates come from; each estimate says how many of its window's samples were
    assert doc["estimates"] and all(r["saturated_samples"] >= 0 for r in doc["estimates"])
    print_saturation(result["input_saturation"])
    line = capsys.readouterr().out
    assert line.startswith("WARN: input saturation: a2 at its rail (") and "range is too small" in line


def test_analyze_of_the_clean_recording_says_none(bags, tmp_path, capsys):
    result = analyze_bag(bags["clean"], tmp_path / "clean", AnalyzeOptions())
    sat = json.loads(result["outputs"]["json"].read_text())["input_saturation"]
    assert not sat["saturated"] and sat["saturated_windows"] == 0 and sat["messages"] == []
    print_saturation(result["input_saturation"])
    assert capsys.readouterr().out.startswith("input saturation: none")


def test_bag_info_names_the_rail(bags, capsys):
    assert bag_info.main([str(bags["clipped"]), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)["input_saturation"]
    by_signal = {topic.rsplit("/", 1)[-1]: v for topic, v in info.items()}
    assert by_signal["a2"]["at_rail"] > 0 and by_signal["a1"]["at_rail"] == 0
    assert bag_info.main([str(bags["clipped"])]) == 0
    text = capsys.readouterr().out
    assert "a2 at its rail" in text and "accelerometer's range is too small" in text
    assert bag_info.main([str(bags["clean"])]) == 0
    assert "at its rail" not in capsys.readouterr().out
