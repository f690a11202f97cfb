"""Write docs/benchmarks.md from bench/results.json: the measured figures, never typed by hand.

    python tools/benchmarks_doc.py                 # rewrite docs/benchmarks.md
    python tools/benchmarks_doc.py --check         # exit 1 if docs/benchmarks.md is not what the JSON gives

`make bench` (tools/run_benchmarks.py) writes bench/results.json; run this after it. The headline table picks the
figures the project has goals for (HEADLINES: the key in the JSON, what it is, the goal); every bench then gets a
section with when and how it was measured (its ``measured`` entry) and every figure it recorded (numbers, flags
and short texts; nested tables one level deep). test/commands/test_benchmarks_doc.py checks that the committed
page equals this script's output.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
RESULTS = REPO / "bench" / "results.json"
DOC = REPO / "docs" / "benchmarks.md"

# (bench, key, what it is, the goal)
HEADLINES = [
    ("identification", "fused_accuracy", "identification accuracy fused over the drive's last 8 onsets, per mode "
     "and signal (trigger contact_loss)", "—"),
    ("latency", "latency_ms", "window → estimate latency across processes [ms]", "p99 ≤ 10 ms"),
    ("latency", "realtime_factor", "graph throughput with every onset window classified [× real time]", "≥ 10"),
    ("simulator", "realtime_factor", "plant: simulated scenario-seconds per wall second (one core)", "≥ 200"),
    ("bags", "analyze_vs_rosbags_read", "`analyze` against rosbags merely reading the bag", "≥ 1.0"),
    ("detector", "speedup_whole_measured_10s", "entry detector, new over old speed (10 s, measured angle)", "—"),
    ("reliability", "escapes", "bad inputs that escaped (traceback, crash, hang, wrong estimate)", "0"),
    ("reliability", "bad_inputs_tried", "named bad inputs tried", "—"),
    ("reliability", "fuzz_failures", "cores whose fuzzed property failed", "0"),
    ("reliability", "data_lost_bytes", "recorded bytes lost outside a killed recorder's open chunk", "0"),
    ("workbench", "top1_rate", "workbench: right effect first, own simulator", "≥ 0.95"),
    ("workbench", "false_discovery_rate", "workbench: false discoveries on clean drives", "0"),
    ("workbench", "width_error_after_mm", "workbench: width error after the loop [mm]", "≤ 0.1"),
    ("workbench_foreign", "foreign_top1_rate", "workbench: right family first, foreign drives", "≥ 0.9"),
    ("workbench_foreign", "foreign_loop_width_error_after_mm", "workbench: width error after the loop, foreign "
     "drives [mm]", "≤ 0.1"),
    ("model_watch", "detection_onsets_median", "model watch: onsets to WARN after an effect appears (median)",
     "≤ 16"),
    ("model_watch", "false_alarms", "model watch: false alarms over ≥ 1 h of clean drives", "0"),
    ("model_watch", "cpu_per_drive", "model watch: CPU per drive [fraction of a core]", "≤ 0.05"),
    ("fleet", "drives_realtime", "fleet: 50 kHz drives one 2-core machine monitors in real time", "≥ 8"),
    ("fleet", "fleet_analyze_speedup", "fleet: `analyze FOLDER` on 2 cores over 1 core", "≥ 1.8"),
    ("reliability", "saturation_detected_rate", "a1 or a2 clipped at 50-95 % of its peak found at its rail", "1.0"),
    ("reliability", "saturation_false_flags", "clean recordings flagged as saturated", "0"),
    ("reliability", "under_load_kill_onsets_lost", "onsets lost upstream of a chain node killed beside a CPU hog", "0"),
    ("reliability", "under_load_ros_test_runs_passed", "ros and process tests on a clean clone beside a CPU hog, runs of 5",
     "5"),
    ("reliability", "command_tracebacks", "tracebacks over every command's bad command lines", "0"),
    ("reliability", "command_internal_names", "internal names in those errors", "0"),
    ("workbench", "diagnose_peak_rss_mb", "workbench: diagnose's peak memory, 4 s recording [MB]", "≤ 1024"),
    ("workbench", "outside_proposal_consistent_rate", "workbench: outside mechanisms, model with the proposed term "
     "consistent", "≥ 0.8"),
    ("workbench", "outside_proposal_right_balance_rate", "workbench: proposed term in the true balance, on the right "
     "state", "≥ 0.8"),
    ("workbench", "proposals_on_explained", "workbench: terms proposed on clean or catalogue-explained drives", "0"),
    ("workbench", "angle_locked_plugin_named_rate", "workbench: a user's exact-law angle-locked plug-in named", "1.0"),
    ("workbench", "proposal_cpu_seconds", "workbench: CPU of one proposal on top of diagnose [s]", "≤ 60"),
    ("workbench", "confident_wrong_width_alarms", "width alarms on a drive below its threshold without the "
     "model-fit caveat", "0"),
    ("workbench", "width_plus_effect_named_rate", "width changed beside another effect: the other effect named",
     "≥ 0.8"),
    ("workbench", "width_plus_effect_width_error_sigma_max", "... the width's error in its stated uncertainties",
     "≤ 3"),
    ("fleet", "fleet_model_fit_false_warn", "fleet: model-fit WARN on healthy drives, each at its own nominal", "0"),
    ("fleet", "fleet_model_fit_detected", "fleet: model-fit WARN on drives with effects diagnose finds", "1.0"),
]

SHORT_TEXT = 160     # longer texts (logs, stderr tails) stay in the JSON


def fmt(value) -> str:
    """A figure as the page shows it: 4 significant digits, flags as yes/no, short lists inline."""
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        return f"{value:.4g}"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(fmt(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k}: {fmt(v)}" for k, v in value.items()) + "}"
    return str(value).replace("|", "\\|").replace("\n", " ")


def shown(value) -> bool:
    """A figure the page shows: a number, a flag, a short text, or a short flat list of them."""
    if value is None or isinstance(value, (bool, int, float)):
        return True
    if isinstance(value, str):
        return len(value) <= SHORT_TEXT
    if isinstance(value, (list, tuple)):
        return len(value) <= 12 and all(isinstance(v, (bool, int, float, str)) and shown(v) for v in value)
    return False


def rows_of(entry: dict, prefix: str = "", depth: int = 0) -> list[tuple[str, str]]:
    rows = []
    for key in sorted(entry):
        value = entry[key]
        if key in ("measured", "details", "error", "stderr_tail"):
            continue
        name = f"{prefix}{key}"
        if isinstance(value, dict) and depth == 0:
            rows += rows_of(value, f"{name}.", depth + 1)
        elif isinstance(value, dict) and all(shown(v) and not isinstance(v, list) for v in value.values()) \
                and len(value) <= 8:
            rows.append((name, fmt(value)))
        elif shown(value):
            rows.append((name, "—" if value is None else fmt(value)))
    return rows


def lookup(results: dict, bench: str, key: str):
    value = (results.get(bench) or {}).get(key)
    if isinstance(value, dict):      # a figure with several parts (e.g. percentiles, per trigger): shown whole
        return fmt(value) if len(fmt(value)) <= 200 else "see below"
    return "—" if value is None else fmt(value)


def render(results: dict) -> str:
    out = ["# Benchmarks: the measured figures",
           "",
           "Made by `tools/benchmarks_doc.py` from `bench/results.json` (written by `make bench`); do not edit by "
           "hand. The machines are shared 2-core machines; timings vary by ±30 % from run to run, so each bench "
           "reports ratios measured side by side in one run. How each figure came about, and the figures before: "
           "`CHANGELOG.md`.",
           "",
           "## Headline figures and their goals",
           "",
           "| figure | measured | goal | bench |",
           "|---|---|---|---|"]
    for bench, key, what, goal in HEADLINES:
        out.append(f"| {what} | {lookup(results, bench, key)} | {goal} | `{bench}.{key}` |")
    out += ["", "![confusion matrices, contact_loss trigger](img/confusion_contact_loss.png)", ""]
    for bench in sorted(results):
        entry = results[bench] or {}
        script = bench.split("_", 1)[0] if not (REPO / "bench" / f"{bench}.py").exists() else bench
        out += [f"## {bench}", "", f"`bench/{script}.py`."]
        if entry.get("measured"):
            out += ["", f"Measured: {fmt(entry['measured'])}"]
        if entry.get("error"):
            out += ["", f"The last run failed: {fmt(entry['error'])}"]
        rows = rows_of(entry)
        if rows:
            out += ["", "| figure | value |", "|---|---|"] + [f"| `{k}` | {v} |" for k, v in rows]
        out.append("")
    return "\n".join(out)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--results", default=str(RESULTS), metavar="FILE.json", help="(default: bench/results.json)")
    parser.add_argument("-o", "--output", default=str(DOC), metavar="FILE.md", help="(default: docs/benchmarks.md)")
    parser.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 when different")
    args = parser.parse_args(argv)
    text = render(json.loads(Path(args.results).read_text()))
    if args.check:
        same = Path(args.output).is_file() and Path(args.output).read_text() == text
        if not same:
            print(f"{args.output} is not what {args.results} gives: run python tools/benchmarks_doc.py",
                  file=sys.stderr)
        return 0 if same else 1
    Path(args.output).write_text(text)
    print(f"wrote {args.output}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
