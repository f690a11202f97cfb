"""The fleet's diagnostic_aggregator file against the real analyzer's parameters, and our view of it.

The schema below is what diagnostic_aggregator reads (ros/diagnostics, branch ros2-jazzy, 4.0.0):
aggregator.cpp takes pub_rate, path, other_as_errors, history_depth, critical; analyzer_group.cpp
takes each entry's `type` and `path` and a group's `analyzers`; generic_analyzer.cpp takes path,
find_and_remove_prefix, remove_prefix, startswith, contains, expected, regex (string arrays),
timeout (double), num_items (int), discard_stale (bool), and refuses an analyzer with no way of
matching (no startswith/contains/expected/regex). A key it does not read (e.g. `name`, which the
ROS 2 version no longer parses) would be silently ignored there, so it is an error here.
"""
import pathlib

import pytest
import yaml

from backlash_monitor.errors import UsageError
from backlash_monitor.fleet.aggregator import (ERROR, OK, STALE, WARN, AggregatorView,
                                               analyzer_config, drive_status_names, format_table)
from backlash_monitor.fleet.drives import drives_from_config, drives_from_count, load_drives

CONFIG = pathlib.Path(__file__).resolve().parents[2] / "config"

AGGREGATOR_SCHEMA = {"pub_rate": float, "path": str, "other_as_errors": bool,
                     "history_depth": int, "critical": bool}
ANALYZER_TYPES = {"diagnostic_aggregator/GenericAnalyzer", "diagnostic_aggregator/AnalyzerGroup",
                  "diagnostic_aggregator/DiscardAnalyzer", "diagnostic_aggregator/IgnoreAnalyzer"}
GENERIC_SCHEMA = {"type": str, "path": str, "find_and_remove_prefix": list, "remove_prefix": list,
                  "startswith": list, "contains": list, "expected": list, "regex": list,
                  "timeout": float, "num_items": int, "discard_stale": bool}
GROUP_SCHEMA = {"type": str, "path": str, "analyzers": dict}


def check_analyzer(where, spec, problems):
    if not isinstance(spec, dict) or spec.get("type") not in ANALYZER_TYPES:
        problems.append(f"{where}: type {spec.get('type') if isinstance(spec, dict) else spec!r}")
        return
    if not isinstance(spec.get("path"), str) or not spec["path"]:
        problems.append(f"{where}: no path")
    schema = GROUP_SCHEMA if spec["type"].endswith("AnalyzerGroup") else GENERIC_SCHEMA
    for key, value in spec.items():
        if key not in schema:
            problems.append(f"{where}: key {key!r} is not read by {spec['type']}")
        elif not isinstance(value, schema[key]) or isinstance(value, bool) != (schema[key] is bool):
            problems.append(f"{where}.{key}: {value!r} is not {schema[key].__name__}")
        elif schema[key] is list and not all(isinstance(v, str) for v in value):
            problems.append(f"{where}.{key}: not a string array")
    if spec["type"].endswith("GenericAnalyzer") and not any(
            spec.get(k) for k in ("startswith", "contains", "expected", "regex",
                                  "find_and_remove_prefix")):
        problems.append(f"{where}: no way of matching a status")
    if spec["type"].endswith("AnalyzerGroup"):
        if not spec.get("analyzers"):
            problems.append(f"{where}: a group without analyzers")
        for name, child in spec.get("analyzers", {}).items():
            check_analyzer(f"{where}.analyzers.{name}", child, problems)


def schema_problems(config) -> list[str]:
    params = config["analyzers"]["ros__parameters"]
    problems = []
    for key, value in params.items():
        if key in AGGREGATOR_SCHEMA:
            if not isinstance(value, AGGREGATOR_SCHEMA[key]):
                problems.append(f"{key}: {value!r} is not {AGGREGATOR_SCHEMA[key].__name__}")
        else:
            check_analyzer(key, value, problems)
    return problems


def test_the_installed_fleet_analyzers_follow_the_aggregators_schema():
    config = yaml.safe_load((CONFIG / "fleet_aggregator.yaml").read_text())
    assert schema_problems(config) == []


def test_the_schema_check_catches_what_the_aggregator_would_ignore_or_refuse():
    config = analyzer_config(drives_from_count(2))
    group = config["analyzers"]["ros__parameters"]["line1"]
    group["analyzers"]["drive01"]["name"] = ["line1/drive01"]          # not read by ROS 2's
    group["analyzers"]["drive02"] = {"type": "diagnostic_aggregator/GenericAnalyzer",
                                     "path": "drive02", "timeout": 3}  # int, and no matcher
    problems = schema_problems(config)
    assert any("'name'" in p for p in problems)
    assert any("drive02.timeout" in p for p in problems)
    assert any("no way of matching" in p for p in problems)


def test_the_installed_analyzers_are_config_fleet_yamls_drives():
    drives = load_drives(str(CONFIG / "fleet.yaml"))
    installed = yaml.safe_load((CONFIG / "fleet_aggregator.yaml").read_text())
    assert installed == analyzer_config(drives)


def test_every_drive_has_one_analyzer_under_its_line_and_takes_no_other_drives_statuses():
    # drive1 and drive10 share a prefix: the analyzer must not take the other's statuses.
    drives = drives_from_config({"lines": {"line1": {"drive1": {}, "drive10": {}},
                                           "line2": {"drive1": {}}}})
    view = AggregatorView(analyzer_config(drives))
    for drive in drives:
        for name in drive_status_names(drive):
            matched = [a.path for a in view.analyzers if a.match(name)]
            assert matched == [f"/BacklashMonitor/{drive.line}/{drive.name}"], (name, matched)
    assert set(view.groups) == {"/BacklashMonitor/line1", "/BacklashMonitor/line2"}


def status(view, drive, task, level, t, message="m"):
    name = next(n for n in drive_status_names(drive) if task in n)
    view.update(name, level, message, drive.hardware_id, {}, t)


def test_the_view_marks_a_silent_drive_stale_and_a_half_silent_one_error():
    drives = drives_from_count(3)
    view = AggregatorView(analyzer_config(drives, timeout_s=3.0), now_s=0.0)
    for t in range(0, 6):                       # drive01 reports every second
        status(view, drives[0], "classifier", WARN, t)
        status(view, drives[0], "windowing", OK, t)
        status(view, drives[0], "width_trend", OK, t)
    status(view, drives[1], "classifier", OK, 1.0)   # drive02: only its classifier, then silence
    status(view, drives[1], "windowing", OK, 5.0)
    status(view, drives[1], "width_trend", OK, 5.0)
    levels = {row["path"].rsplit("/", 1)[1]: row["level"] for row in view.report(5.5)}
    assert levels["drive01"] == WARN           # the highest of its items
    assert levels["drive02"] == ERROR          # one item stale (4.5 s > 3 s), one not
    assert levels["drive03"] == STALE          # never heard: its expected items are stale
    assert view.group_levels(5.5) == {"/BacklashMonitor/line1": ERROR}
    # A drive heard again is no longer stale.
    status(view, drives[1], "classifier", OK, 6.0)
    assert {r["path"].rsplit("/", 1)[1]: r["level"] for r in view.report(6.5)}["drive02"] == OK
    table = format_table(view, 6.5)
    assert "line1/drive03  STALE" in table and "never heard" in table


def test_the_table_has_a_model_fit_column_per_drive_and_a_drive_without_a_watch_expects_none():
    drives = drives_from_config({"lines": {"line1": {"drive01": {"watch": True}, "drive02": {}}}})
    assert [n.rsplit(": ", 1)[1] for n in drive_status_names(drives[0])][-1] == "model fit"
    assert not any("model_watch" in n for n in drive_status_names(drives[1]))
    assert "model_watch" in drives[0].node_parameters() and drives[0].node_parameters()["model_watch"]["width_m"] \
        == 0.005
    view = AggregatorView(analyzer_config(drives), now_s=0.0)
    for d in drives:
        for task in ("classifier", "windowing", "width_trend"):
            status(view, d, task, OK, 1.0)
    status(view, drives[0], "model_watch", WARN, 1.0, message=(
        "model drive7 v3 no longer explains the drive since 12:03:11: residual 2.8x the noise floor, in the gap "
        "traversal, wavelet level d4; snapshot drive7_20261124T120311.mcap; run diagnose on it"))
    table = format_table(view, 1.5)
    head, rows = table.splitlines()[1], table.splitlines()[3:]
    assert "model fit" in head
    assert "WARN 2.8x since 12:03:11 (drive7 v3, gap traversal d4)" in rows[0]
    assert rows[0].split()[1] == "WARN"            # the drive's level: its model fit's
    assert "WARN" not in rows[1] and "OK" in rows[1]


def test_a_fleet_file_with_an_unknown_key_or_a_bad_name_is_refused_with_the_allowed_values():
    with pytest.raises(UsageError, match="unknown key.*width_mm.*allowed: .*width_m"):
        drives_from_config({"lines": {"line1": {"drive01": {"width_mm": 5}}}})
    with pytest.raises(UsageError, match="drive name '7drive' is not allowed"):
        drives_from_config({"lines": {"line1": {"7drive": {}}}})
    with pytest.raises(UsageError, match="--drives 0: out of range"):
        drives_from_count(0)
    with pytest.raises(UsageError, match="line1/drive01: watch = 'yes'; allowed: true or false"):
        drives_from_config({"lines": {"line1": {"drive01": {"watch": "yes"}}}})


def test_the_model_watch_is_opt_in_and_a_drives_own_watch_key_wins_over_the_flag(tmp_path):
    import argparse
    from backlash_monitor.nodes.fleet import add_arguments, validate
    parser = argparse.ArgumentParser()
    add_arguments(parser)
    assert not any(d.watched for d in validate(parser.parse_args(["--drives", "2"])))
    assert all(d.watched for d in validate(parser.parse_args(["--drives", "2", "--model-watch"])))
    assert "model_watch" not in " ".join(drive_status_names(drives_from_count(1)[0]))
    fleet_file = tmp_path / "fleet.yaml"
    fleet_file.write_text(yaml.safe_dump(
        {"lines": {"line1": {"drive01": {"watch": False}, "drive02": {}, "drive03": {"watch": True}}}}))
    assert [d.watched for d in validate(parser.parse_args(["--config", str(fleet_file)]))] == [False, False, True]
    assert [d.watched for d in validate(parser.parse_args(["--config", str(fleet_file), "--model-watch"]))] \
        == [False, True, True]


def test_drive_namespaces_and_hardware_ids_are_unique_and_reach_every_node():
    drives = drives_from_count(12)
    assert len({d.namespace for d in drives}) == 12
    assert drives[6].namespace == "/line1/drive07"
    params = drives[6].node_parameters(duration_s=5.0)
    assert {params[n]["drive_name"] for n in ("plant_simulator", "windowing", "classifier")} \
        == {"line1/drive07"}
    assert params["plant_simulator"]["seed"] == 7


def test_a_simulated_drives_plant_waits_for_every_signal_its_windowing_node_reads():
    """The plant streams once its windowing node subscribes to what it reads (fleet and pipeline): with the a1 check
    on, the motor speed too, as the windowing stage's own rule gives it; a signal left out would be read without its
    stream's start."""
    from backlash_monitor.chain.stage import WindowingStage
    from backlash_monitor.fleet.drives import SIMULATED_WINDOWING_READS
    params = drives_from_count(1)[0].node_parameters(duration_s=5.0)
    assert params["windowing"]["check_a1_chain"] is True
    node, signals = SIMULATED_WINDOWING_READS.split(":")
    assert node == "windowing"
    assert tuple(signals.split(",")) == WindowingStage(check_a1_chain=True).input_signals
    assert params["plant_simulator"]["wait_for_subscribers"] == [SIMULATED_WINDOWING_READS]
