"""`analyze BAG` on one bag holds it against its drive's model as `analyze FOLDER` would (issue 31 part 3: the same
truth for one bag as for a folder): the folder's reference (reference_for_bag) and one-off rule (model_fit,
config/folder_model_fit.yaml), a `model fit:` line after the table, and when the model does not explain the recording
every width row of the table carries the caveat in the same line (fleet/caveat.py), OUT.json's summary the fit's
fields as a folder's row has them.

Two recordings of a 5 mm drive: one of the default model itself (the project's simulator: the model explains it, OK),
one of the independent simulator `foreign_drives/` with a mechanism no model here has (outside_dev5's motor governor
linkage play: a development row; its fleet-table fit is WARN 2.4x, bench/results.json confident_wrong_width_alarms_set5).
Both read ~5-6 mm, so both are held against the default model's reference at 5 mm (the shared cache entry)."""
import json
import subprocess
import sys

import pytest

from backlash_monitor.fleet.caveat import says_model_fails

FOREIGN = "od5_motor_governor_linkage_play"


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "backlash_monitor", *map(str, args)], capture_output=True, text=True,
                          timeout=600)


@pytest.fixture(scope="module")
def bags(tmp_path_factory):
    """{name: bag} in one folder, and the folder's analysis of both (fleet.json's rows by name)."""
    from foreign_drives.files import write_bag
    from foreign_drives.suites import suite
    from backlash_monitor.workbench.model import load_model
    from shared_cache import watch_reference
    watch_reference(load_model(None, width_m=0.005))         # (built once per machine, under a lock)
    folder = tmp_path_factory.mktemp("bags")
    proc = _cli("simulate", "--widths", "0.005", "--eta-k", "0.025", "--n1", "0.89", "--seeds", "21", "--duration",
                "2", "--no-npz", "--mcap", folder / "sim", "--no-progress")
    assert proc.returncode == 0, proc.stderr
    [sim] = (folder / "sim").glob("*.mcap")
    clean = sim.rename(folder / "clean.mcap")
    foreign = write_bag(next(s for s in suite("outside_dev5") if s.label == FOREIGN), folder / "foreign.mcap")
    out = tmp_path_factory.mktemp("fleet")
    proc = _cli("analyze", folder, "--out-dir", out, "--jobs", "1", "--no-plots")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    rows = {r["bag"].rsplit("/", 1)[1][:-len(".mcap")]: r for r in json.loads((out / "fleet.json").read_text())["rows"]}
    return {"clean": clean, "foreign": foreign}, rows


def _one(bag, out, *extra):
    proc = _cli("analyze", bag, "--out", out, *extra)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    return proc.stdout, json.loads(out.with_suffix(".json").read_text())["summary"]


def _width_rows(stdout: str) -> list[str]:
    return [line for line in stdout.splitlines() if line.split()[:1] in (["a1"], ["a2"], ["a1+a2"])]


@pytest.mark.process
def test_one_bag_the_model_explains_reads_ok_and_its_widths_stand_alone(bags, tmp_path):
    paths, folder = bags
    stdout, summary = _one(paths["clean"], tmp_path / "clean")
    assert summary["model_fit_level"] == "OK" and summary["width_caveat"] == ""
    assert summary["model_fit"]["model"] == "default v1"
    [line] = [x for x in stdout.splitlines() if x.startswith("model fit: ")]
    assert line.startswith("model fit: OK ") and "against model default v1" in line
    rows = _width_rows(stdout)
    assert len(rows) == 3 and not any(says_model_fails(r) for r in rows)
    # the folder's analysis of the same bag: the same reference, level and ratio
    assert folder["clean"]["model_fit_reference"] == summary["model_fit_reference"]
    assert folder["clean"]["model_fit_level"] == "OK"
    assert folder["clean"]["model_fit_ratio"] == pytest.approx(summary["model_fit_ratio"], rel=1e-9)


@pytest.mark.process
def test_one_bag_its_model_does_not_explain_carries_the_caveat_on_every_width(bags, tmp_path):
    """The foreign drive: WARN, the caveat on each signal's width row (the same words as the folder's width cell),
    the `model fit:` line says where and what to do; the folder's analysis of the same bag: the same fit."""
    paths, folder = bags
    stdout, summary = _one(paths["foreign"], tmp_path / "foreign")
    assert summary["model_fit_level"] == "WARN"
    assert summary["width_caveat"].startswith("model default v1 does not explain this drive (residual ")
    rows = _width_rows(stdout)
    assert len(rows) == 3
    for row in rows:
        assert " mm" in row and row.endswith(" — " + summary["width_caveat"]), row
    [line] = [x for x in stdout.splitlines() if x.startswith("model fit: ")]
    assert line.startswith("model fit: WARN ") and "run diagnose on it" in line
    row = folder["foreign"]
    assert row["model_fit_level"] == summary["model_fit_level"]
    assert row["model_fit_ratio"] == pytest.approx(summary["model_fit_ratio"], rel=1e-9)
    assert row["model_fit"]["exceeding"] == summary["model_fit"]["exceeding"]
    assert row["width_caveat"] == summary["width_caveat"]


@pytest.mark.process
def test_no_fit_is_said_never_silent(bags, tmp_path):
    """--no-model-fit: no fit, no caveat, and the line says so; a reference that is not there: the line names it and
    how to build one (the default model's own reference is built instead, once: tested by the folder's tests)."""
    paths, _ = bags
    stdout, summary = _one(paths["foreign"], tmp_path / "skip", "--no-model-fit")
    assert "model fit: not run (--no-model-fit)" in stdout.splitlines()
    assert summary["width_caveat"] == "" and not any(says_model_fails(r) for r in _width_rows(stdout))
    missing = tmp_path / "missing.watch.npz"
    stdout, summary = _one(paths["foreign"], tmp_path / "missing", "--watch-reference", missing)
    assert f"model fit: not run — no reference {missing} (`python -m backlash_monitor watch-reference" in stdout
    assert summary["model_fit"] == "no reference" and summary["width_caveat"] == ""


@pytest.mark.process
def test_a_bag_of_no_registered_drive_is_said_not_silently_held_against_the_default(bags, tmp_path):
    """--registry naming other drives: one bag of none of them says so after its table (as a folder's analysis
    does), with its recorded drive and namespace and what its widths come from; without --registry nothing is said.
    (The match itself is folder_analysis.registered_drive's, the folder's: test_fleet_analyze's registry tests.)"""
    import yaml
    paths, _ = bags
    registry = tmp_path / "drives.yaml"
    registry.write_text(yaml.safe_dump({"lines": {"line1": {"driveA": {"width_m": 0.005}}}}))
    stdout, _ = _one(paths["clean"], tmp_path / "unmatched", "--no-model-fit", "--registry", registry)
    [line] = [x for x in stdout.splitlines() if "matched no drive of the registry" in x]
    assert line.startswith("clean.mcap matched no drive of the registry (drive ")
    assert "(drive 'drive', namespace '/'; widths from the packaged library)" in line    # simulate's bag: no LINE/
    stdout, _ = _one(paths["clean"], tmp_path / "none", "--no-model-fit")
    assert not any("registry" in x for x in stdout.splitlines())
