"""`analyze FOLDER`: many recordings in parallel into one fleet table, with each drive's trend."""
import csv
import json
import math
import subprocess
import sys

import pytest

from backlash_monitor.fleet.trend import SECONDS_PER_DAY, TrendRule, drive_trend, slope_per_day
from backlash_monitor.fleet.recordings import write_fleet_bags

RULE = TrendRule(warn_growth_m_per_day=5e-5, warn_width_m=0.0075, error_width_m=0.009)


def test_the_slope_is_the_least_squares_growth_per_day():
    days = [0, 10, 20, 30]
    assert slope_per_day([d * SECONDS_PER_DAY for d in days],
                         [0.005 + 1e-5 * d for d in days]) == pytest.approx(1e-5)
    # alternating +-1 um around the line: symmetric residuals of the 4 points change the fit by
    # sum((x - 15) * e) / sum((x - 15)^2) = (15 - 5 - 5 + 15) * 1e-6 / 500 per day
    noisy = [0.005 + 1e-5 * d + (1e-6 if i % 2 else -1e-6) for i, d in enumerate(days)]
    assert slope_per_day([d * SECONDS_PER_DAY for d in days], noisy) == pytest.approx(
        1e-5 + 20e-6 / 500)
    assert math.isnan(slope_per_day([0.0], [0.005]))
    assert math.isnan(slope_per_day([5.0, 5.0], [0.004, 0.005]))   # no time span: no slope


def test_a_fast_growing_narrow_drive_is_warned_before_the_limit_with_the_days_left():
    pts = [(d * SECONDS_PER_DAY, 0.004 + 1e-4 * d) for d in (0, 5, 10)]   # 0.1 mm/day, 5 mm now
    t = drive_trend(pts, RULE)
    assert t.level == "WARN" and t.last_width_m < RULE.warn_width_m
    assert t.days_to_limit == pytest.approx((0.009 - 0.005) / 1e-4)       # 40 days
    slow = drive_trend([(d * SECONDS_PER_DAY, 0.005 + 1e-6 * d) for d in (0, 5, 10)], RULE)
    assert slow.level == "OK"
    wide = drive_trend([(0.0, 0.0075), (SECONDS_PER_DAY, 0.0075)], RULE)
    assert wide.level == "WARN" and "7.50 mm" in wide.reason             # the width alone
    assert drive_trend([(0.0, 0.0095)], RULE).level == "ERROR"


@pytest.fixture(scope="module")
def fleet_bags(tmp_path_factory):
    # drive A wears fast (5 -> 7.5 mm in 20 days: 0.125 mm/day), drive B stays at 5 mm.
    return write_fleet_bags(tmp_path_factory.mktemp("bags"), [
        ("line1/driveA", 0, 0.005, 1), ("line1/driveA", 10, 0.005, 2),
        ("line1/driveA", 20, 0.0075, 3), ("line1/driveB", 0, 0.005, 4),
        ("line1/driveB", 20, 0.005, 5)], duration_s=1.2)


@pytest.mark.process
@pytest.mark.parametrize("engine_args", [["--jobs", "2"], ["--jobs", "1"]])
def test_a_folder_of_bags_becomes_one_fleet_table_with_trends(fleet_bags, tmp_path, engine_args):
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze",
                           str(fleet_bags[0].parent), "--out-dir", str(out), "--no-model-fit", *engine_args],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    result = json.loads((out / "fleet.json").read_text())
    rows = result["rows"]
    assert len(rows) == 5 and all(not r["error"] for r in rows)
    by_bag = {r["bag"].rsplit("/", 1)[1]: r for r in rows}
    for name, r in by_bag.items():
        assert r["fused_width_m"] == r["true_width_m"], r            # 1.2 s: 4-5 onsets fused
        assert r["time_s"] == pytest.approx(1_760_000_000 + 86400 * int(name[-8:-5]), abs=1e-3)
    assert result["trends"]["line1/driveA"]["level"] == "WARN"
    # the trend follows each recording's continuous width (median over its windows), not the
    # candidate grid: its slope over the three recordings, near the true 0.125 mm/day
    driveA = sorted((r for r in rows if r["drive"] == "line1/driveA"), key=lambda r: r["time_s"])
    assert all(abs(r["width_m"] - r["true_width_m"]) < 3e-4 for r in rows)
    # each recording's width carries the standard error of its windows' median (4-5 onset windows)
    assert all(0 < r["width_uncertainty_m"] < 3e-4 for r in rows), [r["width_uncertainty_m"] for r in rows]
    assert all(r["width_caveat"] == "" for r in rows)       # --no-model-fit: no fit, no caveat
    assert result["trends"]["line1/driveA"]["rate_m_per_day"] == pytest.approx(
        slope_per_day([r["time_s"] for r in driveA], [r["width_m"] for r in driveA]), rel=1e-9)
    assert result["trends"]["line1/driveA"]["rate_m_per_day"] == pytest.approx(1.25e-4, abs=2e-5)
    assert result["trends"]["line1/driveB"]["level"] == "OK"
    assert (out / "trend_fleet.png").stat().st_size > 0
    assert (out / "trend_line1_driveA.png").is_file()
    assert "line1/driveA: WARN: grows 0.1" in proc.stdout


@pytest.mark.process
def test_the_model_fit_column_holds_each_bag_against_the_drives_model(tmp_path):
    """Two 2 s recordings of a 5 mm drive, one on its model and one with 2.5 N*m of wheel friction the model
    lacks: the fleet table's model-fit column says OK for the first and WARN (with where the residual sits) for
    the second, and the command names the bag to run diagnose on. The reference is the default model's at the
    pattern width nearest the measured width (5 mm: the cache)."""
    from backlash_monitor.workbench.model import load_model
    from shared_cache import watch_reference
    watch_reference(load_model(None, width_m=0.005))
    bags = tmp_path / "bags"
    for name, sets in (("clean", []), ("friction", ["effects.wheel_coulomb_friction=true",
                                                     "wheel_coulomb_friction.torque_Nm=2.5"])):
        subprocess.run([sys.executable, "-m", "backlash_monitor", "simulate", "--widths", "0.005", "--eta-k", "0.025",
                        "--n1", "0.89", "--seeds", "21", "--duration", "2", "--no-npz", "--mcap", str(bags / name),
                        *[x for s_ in sets for x in ("--set", s_)]], check=True, capture_output=True, timeout=300)
    for d in ("clean", "friction"):
        for f in (bags / d).glob("*.mcap"):
            f.rename(bags / f"{d}_{f.name}")
    out = tmp_path / "out"
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(bags), "--out-dir", str(out),
                           "--jobs", "1", "--no-plots"], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    rows = {r["bag"].rsplit("/", 1)[1].split("_")[0]: r for r in json.loads((out / "fleet.json").read_text())["rows"]}
    assert rows["clean"]["model_fit"]["level"] == "OK"
    assert rows["friction"]["model_fit"]["level"] == "WARN"
    assert rows["friction"]["model_fit"]["model"] == "default v1"
    assert "model fit" in proc.stdout.splitlines()[0]
    assert "does not explain friction_" in proc.stdout and "run diagnose on it" in proc.stdout
    # the width of the recording its model does not explain says so in the same line (table, CSV, JSON); the
    # other's width stands alone
    assert rows["clean"]["width_caveat"] == ""
    assert rows["friction"]["width_caveat"].startswith("model default v1 does not explain this drive (residual ")
    friction_line = next(line for line in proc.stdout.splitlines() if "friction_" in line and " mm" in line)
    assert " mm — model default v1 does not explain this drive" in friction_line
    clean_line = next(line for line in proc.stdout.splitlines() if "clean_" in line and " mm" in line)
    assert "does not explain" not in clean_line
    fleet_csv = list(csv.DictReader((out / "fleet.csv").open()))
    assert {r["bag"].rsplit("/", 1)[1].split("_")[0]: r["width_caveat"] for r in fleet_csv}["friction"] \
        == rows["friction"]["width_caveat"]
    # two workers: the fits in their own stage (the first bag of the reference fitted by the command itself, the
    # other by a worker forked after it): the same fits, the same verdicts
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(bags), "--out-dir",
                           str(tmp_path / "two"), "--jobs", "2", "--no-plots"], capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    two = {r["bag"].rsplit("/", 1)[1].split("_")[0]: r for r in json.loads((tmp_path / "two" / "fleet.json").read_text())["rows"]}
    for k, r in rows.items():     # (BLAS of one thread in the workers: the last digits may differ)
        assert two[k]["model_fit"]["level"] == r["model_fit"]["level"]
        assert two[k]["model_fit"]["exceeding"] == r["model_fit"]["exceeding"]
        assert two[k]["model_fit"]["residual_over_noise"] == pytest.approx(r["model_fit"]["residual_over_noise"], rel=1e-9)


def test_the_model_fit_reference_is_the_one_given_else_the_librarys_else_the_default_models_nearest_width(tmp_path):
    """--watch-reference wins; without it a --library with a LIB.watch.npz beside it (train --model) gives that;
    else the default model's cache entry at the pattern width nearest the measured width, with analyze's n1."""
    from backlash_monitor.fleet.folder_analysis import WatchOptions, default_model, reference_for_bag
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions
    from backlash_monitor.plant.scenarios import K2_WIDTHS_M
    from backlash_monitor.workbench import reference
    library = tmp_path / "drive7_v3.npz"
    beside = reference.reference_path_for_library(library)
    given = str(tmp_path / "other.watch.npz")
    options = AnalyzeOptions(library=str(library), n1=0.95)
    assert reference_for_bag(options, WatchOptions(reference=given), 0.005) == given
    nearest = min(K2_WIDTHS_M, key=lambda k: abs(k - 0.0051))
    cache = str(reference.cache_path(default_model(0.95, nearest)))
    assert reference_for_bag(options, WatchOptions(), 0.0051) == cache      # no LIB.watch.npz yet
    beside.write_bytes(b"")
    assert reference_for_bag(options, WatchOptions(), 0.0051) == str(beside)
    assert default_model(0.95, 0.0051).nominal == {"width_m": nearest, "eta_k": 0.025, "n1": 0.95}


def test_the_command_line_becomes_typed_fleet_options_checked_with_the_allowed_ranges():
    """`analyze FOLDER`'s flags become one FleetOptions (its WatchOptions among them); run_many reads no
    command line. --jobs outside 0..1024 is refused with the allowed range; the old spelling of the folder,
    --out, still gives it for one release."""
    from backlash_monitor.__main__ import build_parser
    from backlash_monitor.commands.analyze import fleet_options_from_args
    from backlash_monitor.errors import UsageError
    from backlash_monitor.fleet.folder_analysis import FleetOptions, WatchOptions
    args = build_parser("analyze").parse_args(
        ["analyze", "bags/*.mcap", "--out-dir", "o", "--jobs", "3", "--engine", "dask", "--scheduler",
         "tcp://h:8786", "--trend-config", "t.yaml", "--no-plots", "--watch-reference", "r.watch.npz"])
    assert fleet_options_from_args(args) == FleetOptions(
        bags="bags/*.mcap", out="o", jobs=3, engine="dask", scheduler="tcp://h:8786",
        trend_config="t.yaml", plots=False, watch=WatchOptions(enabled=True, reference="r.watch.npz"))
    old = build_parser("analyze").parse_args(["analyze", "bags/*.mcap", "--out", "o"])
    assert fleet_options_from_args(old).out == "o"
    defaults = fleet_options_from_args(build_parser("analyze").parse_args(["analyze", "d", "--no-model-fit"]))
    assert defaults == FleetOptions(bags="d", watch=WatchOptions(enabled=False))
    FleetOptions(bags="d", jobs=1024).check()
    for jobs in (-1, 1025):
        with pytest.raises(UsageError, match=rf"--jobs {jobs}: out of range, allowed 0\.\.1024 \(0: this machine's cores\)"):
            FleetOptions(bags="d", jobs=jobs).check()
    with pytest.raises(UsageError, match="engine 'spark'; allowed: local, dask"):
        FleetOptions(bags="d", engine="spark").check()


@pytest.mark.process
def test_a_glob_without_bags_is_one_clear_error(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze",
                           str(tmp_path / "*.mcap")], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2
    assert "no .mcap bags" in proc.stderr and "Traceback" not in proc.stderr


@pytest.mark.process
def test_the_dask_engine_gives_the_same_table_on_a_local_cluster(fleet_bags, tmp_path):
    pytest.importorskip("dask.distributed", reason="dask is an optional extra (pip install dask "
                                                   "distributed)")
    out = tmp_path / "dask"
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze",
                           str(fleet_bags[0].parent / "*.mcap"), "--out-dir", str(out),
                           "--engine", "dask", "--jobs", "2", "--no-plots", "--no-model-fit"],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    rows = json.loads((out / "fleet.json").read_text())["rows"]
    assert len(rows) == 5
    assert {r["drive"] for r in rows} == {"line1/driveA", "line1/driveB"}
    assert all(r["fused_width_m"] == r["true_width_m"] for r in rows)


def _wider_library(path, extra_m: float):
    """The packaged library made to read every window ``extra_m`` wider: its shape regressions' intercepts
    (the width at the mean features) moved by ``extra_m`` (a stand-in for a drive's own trained library)."""
    import dataclasses
    from backlash_monitor.classifier.patterns import load_library
    packaged = load_library()
    arrays = dict(packaged.arrays)
    for key in [k for k in arrays if k.startswith("shape/") and k.endswith("/scalars")]:
        arrays[key] = arrays[key].copy()
        arrays[key][0] += extra_m       # (intercept, sigma, sample period, ridge)
    return dataclasses.replace(packaged, arrays=arrays, created_utc="2026-11-29T00:00:00+00:00").save(path)


@pytest.mark.process
def test_each_bag_takes_its_registered_drives_library_and_an_explicit_library_overrides_them(tmp_path):
    """Two drives record the same 5 mm run (same seed); the registry gives drive B a library that reads 1 mm
    wider, drive A none (the packaged one). With --registry, B's width is A's + 1 mm and each row names the
    library and the drive version it was held against; a bag of no registered drive takes the packaged library
    and is named. With --library given, that one library gives every bag's width (said in the output)."""
    import yaml
    from backlash_monitor.classifier.patterns import default_library_path
    bags = write_fleet_bags(tmp_path / "bags", [("line1/driveA", 0, 0.005, 7), ("line1/driveB", 0, 0.005, 7),
                                                ("line9/stranger", 0, 0.005, 7)], duration_s=1.2)
    wider = _wider_library(tmp_path / "line1_driveB_v2.npz", 0.001)
    registry = tmp_path / "drives.yaml"
    registry.write_text(yaml.safe_dump({"lines": {"line1": {
        "driveA": {"width_m": 0.005},
        "driveB": {"width_m": 0.005, "library": "line1_driveB_v2.npz",
                   "versions": [{"version": 1, "model": None, "library": None, "watch_reference": None}]}}}}))

    def analyze(out, *extra):
        proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(bags[0].parent),
                               "--out-dir", str(tmp_path / out), "--no-plots", "--no-model-fit", "--registry",
                               str(registry), *extra], capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stdout + proc.stderr
        rows = json.loads((tmp_path / out / "fleet.json").read_text())["rows"]
        return {r["drive"].split("/")[1]: r for r in rows}, proc.stdout

    rows, stdout = analyze("own", "--jobs", "2")
    a, b, stranger = rows["driveA"], rows["driveB"], rows["stranger"]
    assert abs(a["width_m"] - 0.005) < 3e-4                          # the packaged library on a 5 mm drive
    assert b["width_m"] - a["width_m"] == pytest.approx(0.001, abs=1e-9)    # the same windows, its own library
    assert stranger["width_m"] == a["width_m"]
    assert a["library"] == stranger["library"] == str(default_library_path())
    assert b["library"] == str(wider) and b["library_created_utc"] == "2026-11-29T00:00:00+00:00"
    assert (a["registry_drive"], a["drive_version"], b["registry_drive"], b["drive_version"]) == \
        ("line1/driveA", 1, "line1/driveB", 2)
    assert (a["library_from"], b["library_from"], stranger["library_from"]) == ("packaged", "registry", "packaged")
    assert stranger["registry_drive"] == "" and "matched no drive" in stdout and "line9_stranger_day000" in stdout
    by_csv = {r["bag"].rsplit("/", 1)[1]: r for r in csv.DictReader((tmp_path / "own" / "fleet.csv").open())}
    assert by_csv[bags[1].name]["library"] == str(wider) and by_csv[bags[1].name]["drive_version"] == "2"
    b_line = next(line for line in stdout.splitlines() if bags[1].name in line)
    assert " v2 " in b_line and "line1_driveB_v2.npz" in b_line
    # one bag with --registry: its drive's library too, the same estimates as the folder's row of it
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(bags[1]), "--out",
                           str(tmp_path / "one_b"), "--no-model-fit", "--registry", str(registry)],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    one = json.loads((tmp_path / "one_b.json").read_text())["estimates"]
    folder = json.loads((tmp_path / "own" / f"{bags[1].stem}.estimates.json").read_text())["estimates"]
    assert [e["continuous_width_m"] for e in one] == [e["continuous_width_m"] for e in folder]

    rows, stdout = analyze("given", "--jobs", "1", "--library", str(default_library_path()))
    assert rows["driveB"]["width_m"] == rows["driveA"]["width_m"] == a["width_m"]
    assert rows["driveB"]["library"] == str(default_library_path()) and rows["driveB"]["library_from"] == "--library"
    assert "every bag's widths from it, not from the registry's libraries of 1 drives (line1/driveB)" in stdout

    # a drive's library that is not there: its bags' rows are errors naming the drive and the file (exit 1); the
    # other bags are analysed
    wider.rename(tmp_path / "moved.npz")
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(bags[0].parent), "--out-dir",
                           str(tmp_path / "missing"), "--no-plots", "--no-model-fit", "--jobs", "1", "--registry",
                           str(registry)], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 1 and "Traceback" not in proc.stderr
    rows = {r["drive"]: r for r in json.loads((tmp_path / "missing" / "fleet.json").read_text())["rows"]}
    assert rows["line1/driveB"]["error"].startswith("drive line1/driveB's library: pattern library ")
    assert "line1_driveB_v2.npz does not exist" in rows["line1/driveB"]["error"]
    assert not rows["line1/driveA"]["error"] and rows["line1/driveA"]["width_m"] == a["width_m"]
