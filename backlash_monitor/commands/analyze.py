"""`python -m backlash_monitor analyze BAG`: the signal chain offline, without DDS.

Reads the drive's SignalChunk topics (plant/a1, plant/a2, plant/angle_difference — or
plant/omega1/omega2 with --angle-source integrated) in the order they were recorded, runs the same
stages as the live graph (backlash_monitor.chain: join, detect entries, capture; backlash_monitor.denoise;
classify, fuse) and writes the estimates to OUT.csv, OUT.json and OUT.mcap (topic `estimate`, the live
pipeline's message type). Given the same recorded chunks, the estimates equal the live pipeline's.

The accelerometers' constant offsets are estimated over whole load periods and removed before the
classifier, as live (docs/windowing.md "Sensor offsets"): each estimate row has the offsets its
window was read with, OUT.json's "sensor_offsets" the drive's latest estimate, and an offset beyond
the plausible range (config/windowing.yaml sensor_offset.plausible_abs_m_s2) is printed as a WARN.

A damaged bag (a chunk whose length field or CRC is bad, a missing summary) is an error naming the
damage; with --recover every intact chunk is analysed and OUT.json's "bag_integrity" lists what was
skipped (chunks, log-time ranges, messages). A bag sampled at another rate than the pattern library
was trained at, or whose topics carry other signals than their names say, is refused. Bad input
inside the bag is dropped and counted as the live chain counts it ("input_faults", the reasons of
docs/windowing.md "Input faults"): a sample period that is not a positive number, signals' chunks
of unequal length, non-finite samples, accelerometer samples outside the sensor's declared range.

The bag is held against its drive's model as `analyze FOLDER` would hold it (fleet/folder_analysis.one_bag_fit:
the same reference and one-off rule): a `model fit:` line follows the table, and when the model does not explain the
recording every width row says so in the same line (fleet/caveat.py); OUT.json's summary has the fit's fields.

This module parses and prints; the analysis is backlash_monitor/offline/bag_analysis.py.
"""
from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING

from backlash_monitor.classifier.signal_check import (BOTH_SIGNALS, LOAD_SIDE_SIGNAL, MOTOR_SIDE_SIGNAL, rule_text,
                                                      source_text)
from backlash_monitor.commands import UsageError
from backlash_monitor.fleet.caveat import FitVerdict, with_caveat, width_text
from backlash_monitor.files.registry import RegistryError, entries

if TYPE_CHECKING:
    from backlash_monitor.fleet.folder_analysis import FleetOptions
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions

NAME = "analyze"
HELP = "run the chain offline on an MCAP bag: estimates to CSV, JSON and MCAP"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    parser.add_argument("bag", help="MCAP file recorded from a drive (or by `simulate --mcap`); "
                                    "a folder or a quoted glob of them: every bag in parallel, "
                                    "into one fleet table (backlash_monitor/fleet/folder_analysis.py)")
    parser.add_argument("--out", default="", metavar="PREFIX",
                        help="one bag: the output prefix, writes PREFIX.csv, PREFIX.json, PREFIX.mcap (default: "
                             "the bag's path without .mcap, plus '.estimates')")
    parser.add_argument("--namespace", default="",
                        help="namespace of the drive's topics in the bag (e.g. /line1/drive7; default: the one drive "
                             "the bag holds, found by its plant/a1 topic)")
    parser.add_argument("--trigger", choices=("contact_loss", "paper"), default="contact_loss",
                        help="entry trigger (the library must be trained with it)")
    parser.add_argument("--width-m", type=float, default=0.0, metavar="M",
                        help="the drive's backlash width [m], which the 'paper' trigger needs (eq. 1) (default: "
                             "none; the contact_loss trigger needs no width)")
    parser.add_argument("--window-offset", type=int, default=None, metavar="SAMPLES",
                        help="samples from the detected entry to the window start (default: the "
                             "trigger's configured value, config/windowing.yaml; the library must "
                             "have been trained with it)")
    parser.add_argument("--angle-source", choices=("measured", "integrated"), default="measured",
                        help="angle difference from the encoders' topic or integrated speeds")
    parser.add_argument("--mode", default="",
                        help="classifier mode: paper, paper_corrected or shape (default: shape)")
    parser.add_argument("--n1", type=float, default=0.89,
                        help="absorber flow index n1 [-] (the paper modes use this n1's patterns)")
    parser.add_argument("--library", default="", metavar="LIB.npz",
                        help="pattern library (default: the packaged one; a folder with --registry: each drive's "
                             "registered library, the packaged one for a drive without one; --library given: that "
                             "one for every bag, over the registry's)")
    parser.add_argument("--fusion-events", type=int, default=8, metavar="N",
                        help="onset events fused into one estimate")
    parser.add_argument("--recover", action="store_true",
                        help="analyse what is intact of a damaged bag (recorder killed, damaged "
                             "chunks skipped); OUT.json lists what was skipped")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace existing output files (never the analysed bag itself); "
                             "without it an existing output is an error")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar (over the bags of a folder)")
    _add_many_arguments(parser)


def _add_many_arguments(parser) -> None:
    """The options of the many-bag path (added to `analyze`'s; backlash_monitor/fleet/folder_analysis.py)."""
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import ENGINES
    group = parser.add_argument_group("many recordings (BAG is a folder or a quoted glob)")
    group.add_argument("--out-dir", default="", metavar="DIR",
                       help="folder for the fleet table, trend plots and each bag's estimates, created if missing "
                            "(default: fleet_analysis beside the first bag)")
    group.add_argument("--jobs", type=int, default=0, metavar="N",
                       help="bags analysed at once (default: this machine's cores; 1: one after "
                            "the other in this process)")
    group.add_argument("--engine", choices=ENGINES, default="local",
                       help="'local': a process pool on this machine; 'dask': a Dask cluster "
                            "(optional extra: pip install dask distributed)")
    group.add_argument("--scheduler", default="",
                       help="address of an existing Dask scheduler (tcp://host:8786); default: a "
                            "local cluster with --jobs workers")
    group.add_argument("--trend-config", default="", metavar="FILE.yaml",
                       help="trend rule file (default: the packaged config/trend.yaml)")
    group.add_argument("--no-plots", action="store_true", help="write no trend plots")
    fit = parser.add_argument_group(
        "model fit (one bag or many)",
        "each bag's last 16 onset events held against its drive's model by the folder's one-off rule "
        "(config/folder_model_fit.yaml, docs/registry.md); one bag: a 'model fit:' line after its table; when the model "
        "does not explain the bag, every width printed for it says so in the same line")
    fit.add_argument("--watch-reference", default="", metavar="REF.watch.npz",
                     help="the model version every bag is held against (default: --library's LIB.watch.npz where it "
                          "exists, else the default model's at the pattern width nearest the drive's measured width, "
                          "eta_k 0.025 and --n1: from the cache, built there once when missing (~50 s of one "
                          "core, said by a line); docs/model_watch.md)")
    fit.add_argument("--registry", default="", metavar="PATH",
                     help="the drive registry (docs/registry.md; e.g. drives.yaml, or the fleet file): each bag's "
                          "widths come from its own drive's library and its model fit is held against the "
                          "drive's current version (matched by the bag's namespace /LINE/DRIVE or recorded drive "
                          "name LINE/DRIVE; its watch_reference, else the default model at its nominal width, "
                          "eta_k, n1); bags that match no drive are named")
    fit.add_argument("--no-model-fit", action="store_true",
                     help="no model fit: a folder's table has no model-fit column; one bag's summary says "
                          "'model fit: not run' and its widths carry no caveat (one bag: ~3.5-6 s of CPU less)")


def options_from_args(args) -> AnalyzeOptions:
    """The analysis options of a parsed `analyze` command line."""
    # deferred: backlash_monitor.offline.bag_analysis costs ~300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions
    return AnalyzeOptions(namespace=args.namespace, trigger=args.trigger, width_m=args.width_m,
                          window_offset_samples=args.window_offset, angle_source=args.angle_source,
                          mode=args.mode, n1=args.n1, library=args.library,
                          fusion_events=args.fusion_events, recover=args.recover,
                          overwrite=args.overwrite)


def fleet_options_from_args(args) -> FleetOptions:
    """The many-bag options of a parsed `analyze FOLDER` command line (a FleetOptions, its model
    fit's WatchOptions among them)."""
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import FleetOptions, WatchOptions
    if args.out and not args.out_dir:     # the release before named the folder --out
        print("python -m backlash_monitor analyze: warning: --out for a folder of bags is deprecated and will "
              "be removed in the next release; use --out-dir", file=sys.stderr)
        args.out_dir = args.out
    return FleetOptions(bags=args.bag, out=args.out_dir, jobs=args.jobs, engine=args.engine,
                        scheduler=args.scheduler, trend_config=args.trend_config,
                        plots=not args.no_plots, progress=not args.no_progress,
                        watch=WatchOptions(enabled=not args.no_model_fit,
                                           reference=args.watch_reference, drives=registry_drives(args)))


def registry_drives(args) -> tuple:
    """A RegisteredDrive (hardware id, reference, (width_m, eta_k, n1), library, model, version) of every drive of
    --registry (empty without one)."""
    if not getattr(args, "registry", ""):
        return ()
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import RegisteredDrive
    try:
        return tuple(RegisteredDrive(d.hardware_id, str(d.watch_reference or ""),
                                     tuple(d.nominal[k] for k in ("width_m", "eta_k", "n1")),
                                     library=str(d.library or ""), model=str(d.model or ""), version=d.version)
                     for d in entries(args.registry))
    except RegistryError as exc:
        raise UsageError(str(exc)) from None


def run(args) -> int:
    # the analysis (numpy) is imported here, not with the command's arguments: a many-bag run limits the
    # threads of its forked workers' pools first (they inherit this process's, set when numpy is imported)
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import is_many, limit_threads, run_many, runs_parallel_here
    if is_many(args.bag):
        fleet = fleet_options_from_args(args)
        if runs_parallel_here(fleet):
            limit_threads()
        return run_many(fleet, options_from_args(args))
    if args.out_dir:
        raise UsageError(f"--out-dir {args.out_dir}: is for a folder of bags; one bag's outputs are named by "
                         "--out PREFIX")
    # deferred: backlash_monitor.offline.bag_analysis costs ~300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.offline.bag_analysis import analyze_bag
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import WatchOptions, one_bag_fit
    options = options_from_args(args)
    watch = WatchOptions(enabled=not args.no_model_fit, reference=args.watch_reference, drives=registry_drives(args))
    # the bag's model fit, as a folder's analysis holding it would make it (its fields in the summary and OUT.json)
    result = analyze_bag(args.bag, args.out, options, library=_registered_library(args.bag, options, watch),
                         summary_fields=lambda analysis: one_bag_fit(args.bag, options, watch, analysis,
                                                                     log=_say))
    _print_summary(result["summary"], result["rows"], result["discarded"], result["n_samples"],
                   result["seconds"], result["outputs"])
    _print_model_fit(result["summary"])
    _print_registry_match(args.bag, options, watch, result)
    _print_integrity(result["integrity"])
    _print_sensor_offsets(result["sensor_offsets"])
    print_saturation(result["input_saturation"])
    stage_faults, estimator_faults = result["faults"]
    if stage_faults.total or estimator_faults.total:   # dropped input (docs/windowing.md)
        print(f"input faults: {stage_faults.summary()}; windows rejected: "
              f"{estimator_faults.summary()}; {result['lost_samples']} samples not analysed")
    return 0


def _say(text: str) -> None:
    print(text, flush=True)       # (a reference being built: said before the ~50 s of CPU it takes)


def _registered_library(bag: str, options, watch):
    """One bag's pattern library as a folder's analysis takes it (fleet/folder_analysis.library_for_bag): --library,
    else its --registry drive's library; None (analyze_bag loads --library or the packaged one) without a registry
    or when the bag's drive has no library of its own."""
    if not watch.drives or options.library:
        return None
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import library_for_bag, registered_drive
    # deferred: backlash_monitor.offline.bag_analysis costs ~300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.offline.bag_analysis import load_library, recorded_drive
    namespace, name = recorded_drive(bag, options.namespace, options.recover)
    drive = registered_drive(watch, {"namespace": namespace, "drive": name or Path(bag).stem})
    path = library_for_bag(options, drive)
    return load_library(replace(options, library=path)) if path else None


def _print_registry_match(bag: str, options, watch, result: dict) -> None:
    """With --registry, a bag of no registered drive is said (as a folder's analysis says it): its widths and model
    fit are then not its drive's own."""
    if not watch.drives:
        return
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import registered_drive, unmatched_text
    row = {"bag": bag, "namespace": result.get("namespace", ""), "drive": result["drive"] or Path(bag).stem}
    if registered_drive(watch, row) is None:
        print(unmatched_text([row], options.library, watch.enabled and not watch.reference))


def _print_model_fit(summary: dict) -> None:
    """The `model fit:` line after one bag's table: its level, residual ratio and where, against which model; or why
    there is none (never nothing)."""
    # deferred: backlash_monitor.fleet.folder_analysis costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.fleet.folder_analysis import model_fit_text
    fit, path = summary.get("model_fit"), summary.get("model_fit_reference", "")
    if isinstance(fit, dict):
        line = f"model fit: {model_fit_text(summary)} against model {fit['model']} ({fit['events']} onset events; " \
               f"reference {path})"
        if fit["level"] != "OK":
            line += (f": model {fit['model']} does not explain this recording ({', '.join(fit['exceeding'])} beyond "
                     "the folder's one-off rule): run diagnose on it")
        print(line)
    elif fit == "no reference":
        print(f"model fit: not run — no reference {path} (`python -m backlash_monitor watch-reference ...` builds "
              "one; or give --watch-reference REF.watch.npz)")
    else:
        print(f"model fit: {fit or 'not run'}")


def _print_sensor_offsets(info: dict) -> None:
    values = {k[:-len("_m_s2")]: v for k, v in info.items()
              if k.endswith("_m_s2") and k != "plausible_abs_m_s2" and isinstance(v, float)}
    if not info["periods"]:
        print("sensor offsets: not known (no whole load period between two onset windows)")
        return
    print("sensor offsets: " + ", ".join(f"{k} {v:+.3f} m/s^2" for k, v in values.items())
          + f" (over {info['periods']} load periods; removed before the classifier)")
    for key, value in info["implausible"].items():
        print(f"WARN: sensor offset {key[:-len('_m_s2')]} {value:+.2f} m/s^2 is beyond +-"
              f"{info['plausible_abs_m_s2']:g} m/s^2, more than a MEMS sensor's own offset: check the "
              "sensor and its mounting (the widths above are offset-free)")


def print_saturation(info: dict) -> None:
    """One line: 'input saturation: none', or each sensor at its rail / stuck and the windows flagged."""
    if not info["saturated"]:
        print("input saturation: none (no sensor at its rail, none stuck)")
        return
    print(f"WARN: input saturation: {'; '.join(info['messages'])} "
          f"({info['saturated_windows']} of {info['windows_checked']} windows with such samples)")


def print_signal_check(summary: dict) -> None:
    """One line when a1+a2's last fused width is a1's or a2's (classifier/signal_check.py): why, and the rule;
    nothing when it is its own."""
    both = summary["per_signal"].get(BOTH_SIGNALS, {})
    if both.get("fused_from_signal") == MOTOR_SIDE_SIGNAL:
        print(f"{BOTH_SIGNALS}'s fused width is "
              f"{source_text(MOTOR_SIDE_SIGNAL, BOTH_SIGNALS, both.get('check_reason', ''))} ({rule_text()}: the load "
              "side carries what the library does not know; docs/classifier.md 5.3)")
    elif both.get("fused_from_signal") == LOAD_SIDE_SIGNAL:
        print(f"WARN: {BOTH_SIGNALS}'s fused width is "
              f"{source_text(LOAD_SIDE_SIGNAL, BOTH_SIGNALS, both.get('check_reason', ''))}: check a1's sensor chain "
              "(and the drive-wheel radius r) before trusting a1 (docs/classifier.md 5.4)")


def _print_integrity(integrity) -> None:
    if integrity and (integrity["damaged_chunks"] or integrity["problems"] or not integrity["complete"]):
        print(f"bag integrity: {integrity['describe']}")


def _print_summary(summary, rows, discarded, n_samples, elapsed, outputs):
    fit = FitVerdict.from_recording(summary.get("model_fit"))     # its caveat on every width's line
    true_width = summary["true_width_m"]
    print(f"analyzed {n_samples} samples in {elapsed:.2f} s; {len({r['entry_sample_index'] for r in rows})} "
          f"onset windows classified, {len(discarded)} discarded")
    header = ("signal", "estimates", "accuracy", "fused width", "fused continuous", "fused events")
    lines = [header]
    for signal, s in sorted(summary["per_signal"].items()):
        acc = "-" if math.isnan(true_width) else f"{s['correct'] / s['estimates']:.0%}"
        cont = s.get("fused_continuous_width_m", math.nan)
        se = s.get("fused_width_uncertainty_m", math.nan)
        cont_text = width_text(cont, se)
        lines.append((signal, str(s["estimates"]), acc, f"{s['fused_width_m'] * 1e3:.2f} mm",
                      cont_text, str(s["fused_events"])))
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    for i, line in enumerate(lines):
        text = "  ".join(c.rjust(w) for c, w in zip(line, widths))
        # a width's row: the model-fit caveat in the same line when the model does not explain the recording
        print(text if i == 0 else with_caveat(text, fit))
        if i == 0:
            print("  ".join("-" * w for w in widths))
    print_signal_check(summary)
    if not math.isnan(true_width):
        print(f"true width: {true_width * 1e3:.2f} mm")
    print(f"wrote {outputs['csv']}, {outputs['json'].name}, {outputs['mcap'].name}")
