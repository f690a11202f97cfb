"""fleet: N simulated drives on one machine, each in its namespace, with one diagnostics view.

    python -m backlash_monitor fleet --drives 8 --duration 30        # from this repo
    python -m backlash_monitor fleet --config config/fleet.yaml      # drives and their parameters
    ros2 run backlash_monitor fleet --drives 8                       # in a ROS 2 install

Drive ``drive07`` of ``line1`` runs its plant simulator, windowing, denoise and classifier nodes in
the namespace ``/line1/drive07``; every node publishes its status on the one absolute
``/diagnostics`` with hardware_id ``line1/drive07``. Layout ``process`` (the default, see
docs/fleet.md for the measurement) runs each drive in a process of its own; ``single`` runs every
drive's nodes in this one process, on one executor. This process shows the aggregator view of
config/fleet_aggregator.yaml's analyzers (a table per drive, once a second; STALE for a drive not
heard for 3 s) and ends with a summary per drive: chunks, discarded windows, onset windows and
estimates, the estimate's lag behind the stream, CPU, and whether the drive was monitored in real
time (every chunk taken, no window discarded, every onset window classified, lag under 1 s).

With ``--config`` the fleet follows its file (the drive registry, docs/registry.md): a drive whose version changes
there while the fleet runs is swapped to it by lifecycle transitions of its chain only (nodes/registry_follower.py).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field

import yaml

from backlash_monitor.fleet.trend import PRIMARY_SIGNAL
from backlash_monitor.errors import DeprecatedSpelling, UsageError, out_of_range
from backlash_monitor.fleet.drives import drives_from_count, load_drives, Drive
from backlash_monitor.fleet.registry_pickup import DriveVersion
from backlash_monitor.files.outputs import missing_folder_message
from backlash_monitor.fleet.aggregator import (
    AggregatorView,
    LEVEL_NAMES,
    short_model_fit,
    analyzer_config,
    format_table,
)
from backlash_monitor.fleet.caveat import width_text
from backlash_monitor.ros.fast_dds import configure_fast_dds
from backlash_monitor.ros.parameters import ParameterValueError
from backlash_monitor.stream_time import stamp_seconds

LAYOUTS = ("process", "single")
DEFAULT_LAYOUT = "process"     # holds more drives in real time (docs/fleet.md)
CHUNK_S = 1000 * 2e-5          # the plant's default chunk: 1000 samples at 50 kHz
WINDOW_END_S = (200 + 2048) * 2e-5   # entry -> last sample of a contact_loss window
WARMUP_S = 2.0                # after the last drive's stream started: see FleetMonitor.summary
COUNTED = ("chunks", "discarded", "incomplete_chunks", "onsets", "onsets_before_offset")   # windowing's counts
SAMPLES_PER_CHUNK = 1000       # CHUNK_S at 50 kHz
REALTIME_LAG_S = 1.0           # a chain that keeps up answers within tens of ms; one that falls
                               # behind lags more with every second of stream


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--drives", type=int, default=None, metavar="N",
                        help="simulate N drives drive01..driveNN on --line (default: 4, or the drives of "
                             "--config)")
    parser.add_argument("--config", default="", metavar="FLEET.yaml",
                        help="the drives and their parameters per line (config/fleet.yaml shows "
                             "the format; default: --drives simulated drives)")
    parser.add_argument("--line", default="line1", help="the line of the --drives drives")
    parser.add_argument("--width-m", type=float, default=0.005, metavar="M",
                        help="backlash width of the --drives drives' simulated clutches [m]")
    parser.add_argument("--duration", type=float, default=10.0, metavar="S",
                        help="simulated seconds per drive [s]")
    parser.add_argument("--rate-factor", type=float, default=1.0, metavar="X",
                        help="simulated seconds per wall second (1 = real time; 0, as fast as possible, is "
                             "replay's only: the simulators pace their streams)")
    parser.add_argument("--layout", choices=LAYOUTS, default=DEFAULT_LAYOUT,
                        help="'process': one process per drive; 'single': every drive in this "
                             "process on one executor")
    parser.add_argument("--view-period", type=float, default=1.0, metavar="S",
                        help="print the aggregator table every S seconds (0: only the summary)")
    parser.add_argument("--analyzers", default="", metavar="FILE",
                        help="diagnostic_aggregator analyzer file the view applies (default: the "
                             "one --aggregator-yaml would write for these drives; "
                             "config/fleet_aggregator.yaml is config/fleet.yaml's)")
    parser.add_argument("--aggregator-yaml", default="", metavar="FILE",
                        help="write diagnostic_aggregator's analyzer file for these drives to FILE "
                             "and exit (default: run the fleet)")
    parser.add_argument("--foxglove-port", type=int, default=-1, metavar="PORT",
                        help="also serve every drive's topics and width to Foxglove on this "
                             "WebSocket port (8765 is Foxglove's default; 0: any free port; "
                             "needs the optional foxglove-sdk; layout: "
                             "config/foxglove_fleet_layout.json; default: -1, no Foxglove server)")
    parser.add_argument("--json", dest="summary_json", default="", metavar="FILE",
                        help="also write the per-drive summary as JSON to FILE (default: none)")
    parser.add_argument("--summary-json", dest="summary_json", action=DeprecatedSpelling, new="--json",
                        metavar="FILE", help=argparse.SUPPRESS)
    parser.add_argument("--trend-state-dir", default="", metavar="DIR",
                        help="keep each drive's live width trend in DIR/<line>_<drive>.json, so that "
                             "a restarted fleet goes on with the drives' history (a drive's own "
                             "trend_state_file in the fleet YAML wins); default: the trend starts anew")
    parser.add_argument("--model-watch", action="store_true",
                        help="run a model watch beside every drive's classifier (its onset events against its "
                             "model version: the model-fit column and a snapshot bag on a WARN; "
                             "docs/model_watch.md). Off by default: it costs CPU per drive; a drive's own "
                             "'watch: true/false' in the fleet YAML wins")
    parser.add_argument("--snapshot-dir", default="", metavar="DIR",
                        help="with --model-watch: where the drives' model watches write their snapshot bags on a WARN (a drive's own "
                             "snapshot_dir in the fleet YAML wins); default: the current folder")
    parser.add_argument("--drive-json", default="", help=argparse.SUPPRESS)   # a drive's process


def validate(args):
    if args.rate_factor == 0:
        raise UsageError("--rate-factor 0 (as fast as possible) is replay's only: the simulators pace their "
                         "streams; allowed 0.01..1000")
    for name, value, lo, hi, unit in (("--duration", args.duration, 0.1, 1e6, "s"),
                                      ("--rate-factor", args.rate_factor, 0.01, 1000.0, ""),
                                      ("--width-m", args.width_m, 1e-4, 0.05, "m"),
                                      ("--view-period", args.view_period, 0.0, 3600.0, "s")):
        if not (lo <= value <= hi):
            raise out_of_range(name, value, lo, hi, unit)
    if args.config and args.drives is not None:
        raise UsageError("give --drives or --config, not both")
    for option, path in (("--json", args.summary_json), ("--aggregator-yaml", args.aggregator_yaml)):
        if path and not os.path.isdir(os.path.dirname(os.path.abspath(path))):
            raise UsageError(missing_folder_message(option, path))
    drives = (load_drives(args.config) if args.config else
              drives_from_count(4 if args.drives is None else args.drives, line=args.line,
                                width_m=args.width_m))
    if args.trend_state_dir:
        try:
            os.makedirs(args.trend_state_dir, exist_ok=True)
        except OSError as error:
            raise UsageError(f"--trend-state-dir {args.trend_state_dir}: {error.strerror}; allowed: "
                             "a folder this user can create and write") from None
        drives = [d if d.parameters.get("trend_state_file") else Drive(d.line, d.name, {
            **d.parameters, "trend_state_file": os.path.join(
                os.path.abspath(args.trend_state_dir), f"{d.line}_{d.name}.json")}) for d in drives]
    if args.model_watch:
        drives = [d if "watch" in d.parameters else Drive(d.line, d.name, {**d.parameters, "watch": True})
                  for d in drives]
    if args.snapshot_dir:
        drives = [d if d.parameters.get("snapshot_dir") else Drive(d.line, d.name, {
            **d.parameters, "snapshot_dir": os.path.abspath(args.snapshot_dir)}) for d in drives]
    return drives


def ensure_references(drives, log=print) -> None:
    """Every watched drive without its own reference needs the default model's at its nominal conditions: built
    into the cache before the drives start (~30 s each, once; the nodes never simulate)."""
    # deferred: the model (the simulator) costs ~800-1100 ms at start-up (python -X importtime, 29 Nov); only a model watch loads it
    from backlash_monitor.workbench import reference
    # deferred: the model (the simulator) costs ~800-1100 ms at start-up (python -X importtime, 29 Nov); only a model watch loads it
    from backlash_monitor.workbench.model import load_model
    done = set()
    for d in drives:
        if not d.watched or d.parameters.get("watch_reference") or d.nominal() in done:
            continue
        done.add(d.nominal())
        width, eta_k, n1 = d.nominal()
        reference.cached(load_model(None, width_m=width, eta_k=eta_k, n1=n1),
                         log=lambda text: log(f"fleet: {text}"))


def load_analyzers(path: str) -> dict:
    try:
        with open(path, encoding="utf-8") as f:
            config = yaml.safe_load(f)
        AggregatorView(config)
    except OSError as error:
        raise UsageError(f"analyzer file {path}: {error.strerror}") from None
    except (yaml.YAMLError, ValueError, KeyError, TypeError, AttributeError) as error:
        raise UsageError(f"analyzer file {path} is not a diagnostic_aggregator parameters file "
                         f"({str(error).splitlines()[0]}); config/fleet_aggregator.yaml shows "
                         "one") from None
    return config


def drive_node_factories(drive, duration_s: float, rate_factor: float) -> list:
    """Builders of one drive's nodes in its namespace, downstream first (each reader exists before
    its writer publishes)."""
    # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from rclpy.parameter import Parameter
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.classifier import ClassifierNode
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.denoise import DenoiseNode
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.width_trend import WidthTrendNode
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.windowing import WindowingNode
    params = drive.node_parameters(duration_s, rate_factor)
    out = []
    nodes = [(WidthTrendNode, "width_trend"), (ClassifierNode, "classifier"), (DenoiseNode, "denoise"),
             (WindowingNode, "windowing"), (PlantSimulatorNode, "plant_simulator")]
    if drive.watched:
        # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
        from backlash_monitor.nodes.model_watch import ModelWatchNode
        nodes.insert(0, (ModelWatchNode, "model_watch"))
    for cls, name in nodes:
        overrides = [Parameter(k, value=v) for k, v in params[name].items()]

        def build(cls=cls, overrides=overrides, parameter_overrides=()):
            """The node; ``parameter_overrides`` (the chain's routed ones: a new model version) win."""
            routed = {p.name for p in parameter_overrides}
            return cls(namespace=drive.namespace, parameter_overrides=[
                p for p in overrides if p.name not in routed] + list(parameter_overrides))
        out.append((name, build))
    return out


@dataclass
class DriveTally:
    onsets_estimated: set = field(default_factory=set)
    lags_s: list = field(default_factory=list)         # (monotonic arrival, lag [s]) per onset
    fused_width_m: float = math.nan
    fused_continuous_width_m: float = math.nan       # a1+a2's (the primary signal)
    fused_width_uncertainty_m: float = math.nan      # its standard error (BacklashEstimate)
    true_width_m: float = math.nan
    windowing: dict = field(default_factory=dict)
    classifier: dict = field(default_factory=dict)
    level: str = "STALE"
    model_fit: str = "-"             # the model watch's last status ("OK: ..." / "WARN: ..."), '-' without one
    status_times: list = field(default_factory=list)   # wall times of the classifier's statuses
    cpu_s: float = math.nan          # CPU share over the stream [%]
    stream_mark: tuple | None = None   # (monotonic, CPU seconds) when its first chunk was reported
    windowing_before: dict = field(default_factory=dict)   # counts of its chains before a rebuild (a new version)
    last_estimate_wall_s: float = math.nan
    chain_restarts: int = 0          # windowing restarts seen (its counts started anew): a version picked up live
    versions_seen: dict = field(default_factory=dict)      # model version -> wall time its classifier first said it

    def windowing_counts(self) -> dict:
        """The windowing's counts summed over the drive's chains (a chain rebuilt for a new model version starts
        them anew; the counts of the last second before the rebuild, not yet reported, are missing); ``position``:
        the chunks of the stream the windowing has reached (where the running chain joined it, plus its chunks)."""
        w = self.windowing
        out = {k: int(w.get(k, 0)) + int(self.windowing_before.get(k, 0)) for k in COUNTED}
        out["position"] = int(w.get("joined_at_sample", 0)) // SAMPLES_PER_CHUNK + int(w.get("chunks", 0))
        return out


class FleetMonitor:
    """Takes /diagnostics and every drive's estimates; keeps the aggregator view and the tallies."""

    def __init__(self, node, drives, aggregator_config: dict, rate_factor: float):
        # deferred: ros.qos (rclpy) costs ~50-60 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
        from backlash_monitor.ros.qos import DIAGNOSTICS_DEPTH, ESTIMATE_QOS
        # deferred: backlash_monitor_msgs is built into install/: --help works before `source env.sh`
        from backlash_monitor_msgs.msg import BacklashEstimate
        # deferred: as above
        from diagnostic_msgs.msg import DiagnosticArray
        self.rate_factor = rate_factor
        self.view = AggregatorView(aggregator_config, now_s=time.monotonic())
        self.tally = {d.hardware_id: DriveTally() for d in drives}
        node.create_subscription(DiagnosticArray, "/diagnostics", self.on_diagnostics,
                                 DIAGNOSTICS_DEPTH * max(1, len(drives)))
        for d in drives:
            node.create_subscription(BacklashEstimate, f"{d.namespace}/estimate",
                                     lambda msg, h=d.hardware_id: self.on_estimate(h, msg),
                                     ESTIMATE_QOS)

    def on_estimate(self, hardware_id: str, msg) -> None:
        t = self.tally[hardware_id]
        if msg.entry_sample_index not in t.onsets_estimated and self.rate_factor == 1.0:
            stamp = stamp_seconds(msg.header.stamp)
            t.lags_s.append((time.monotonic(), time.time() - (stamp + WINDOW_END_S)))
        t.onsets_estimated.add(msg.entry_sample_index)
        t.last_estimate_wall_s = time.time()
        t.fused_width_m = msg.fused_width_m
        if msg.signal_name == PRIMARY_SIGNAL:
            t.fused_continuous_width_m = msg.fused_continuous_width_m
            t.fused_width_uncertainty_m = msg.fused_width_uncertainty_m
        t.true_width_m = msg.true_width_m

    def on_diagnostics(self, msg) -> None:
        now = time.monotonic()
        for status in msg.status:
            level = status.level if isinstance(status.level, int) else ord(status.level)
            values = {kv.key: kv.value for kv in status.values}
            self.view.update(status.name, level, status.message, status.hardware_id, values, now)
            t = self.tally.get(status.hardware_id)
            if t is None:
                continue
            if status.name.endswith("classifier: backlash width"):
                t.classifier = values
                if values.get("model_version"):
                    t.versions_seen.setdefault(int(values["model_version"]), time.time())
                t.level = LEVEL_NAMES[min(level, 3)]
                t.status_times.append(time.time())
            elif status.name.endswith("windowing: windowing"):
                if int(values.get("chunks", 0)) < int(t.windowing.get("chunks", 0)):   # a new chain (new version)
                    t.chain_restarts += 1
                    t.windowing_before = {k: int(t.windowing.get(k, 0)) + int(t.windowing_before.get(k, 0))
                                          for k in COUNTED}
                t.windowing = values
            elif status.name.endswith("model_watch: model fit"):
                t.model_fit = f"{LEVEL_NAMES[min(level, 3)]}: {status.message}"

    def drive_done(self, hardware_id: str, expected_chunks: int) -> bool:
        t = self.tally[hardware_id]
        w = t.windowing_counts()
        return w["position"] >= expected_chunks and len(t.onsets_estimated) >= _classifiable_onsets(w)

    def summary(self, drives, expected_chunks: int) -> list[dict]:
        """Per drive; the lag counts from WARMUP_S after every drive's stream has started (while
        the drives' processes start, numba compiles each plant's kernel and the first drives'
        estimates wait for the CPU: a start-up transient, reported apart as lag_ms_max_startup)."""
        marks = [t.stream_mark[0] for t in self.tally.values() if t.stream_mark is not None]
        steady_from = (max(marks) if marks else 0.0) + WARMUP_S
        rows = []
        for d in drives:
            t = self.tally[d.hardware_id]
            w = t.windowing_counts()
            lags = sorted(lag for at, lag in t.lags_s if at >= steady_from)
            startup = [lag for at, lag in t.lags_s if at < steady_from]
            onsets = int(w.get("onsets", 0))
            classifiable = _classifiable_onsets(w)
            row = {"drive": d.hardware_id, "true_width_m": t.true_width_m,
                   "fused_width_m": t.fused_width_m,
                   "fused_continuous_width_m": t.fused_continuous_width_m,
                   "fused_width_uncertainty_m": t.fused_width_uncertainty_m, "level": t.level,
                   "model_fit": t.model_fit,
                   "chunks": int(w.get("chunks", 0)), "expected_chunks": expected_chunks,
                   "discarded": int(w.get("discarded", 0)),
                   "incomplete_chunks": int(w.get("incomplete_chunks", 0)),
                   "onset_windows": onsets, "onsets_estimated": len(t.onsets_estimated),
                   "onsets_before_offset": onsets - classifiable,
                   "lag_ms_median": lags[len(lags) // 2] * 1e3 if lags else math.nan,
                   "lag_ms_max": lags[-1] * 1e3 if lags else math.nan,
                   "lag_ms_max_startup": max(startup) * 1e3 if startup else math.nan,
                   "steady_estimates": len(lags),
                   "cpu_percent": t.cpu_s, "status_times": t.status_times,
                   "model_version": int(t.classifier.get("model_version", 0) or 0),
                   "library": t.classifier.get("library", ""),
                   "versions_seen_wall_s": {str(k): v for k, v in sorted(t.versions_seen.items())},
                   "chain_restarts": t.chain_restarts, "last_estimate_wall_s": t.last_estimate_wall_s,
                   "joined_at_sample": int(t.windowing.get("joined_at_sample", 0))}
            row["realtime"] = bool(
                row["chunks"] >= expected_chunks and row["discarded"] == 0
                and row["incomplete_chunks"] == 0 and onsets > 0
                and row["onsets_estimated"] >= classifiable
                and (not lags or lags[-1] <= REALTIME_LAG_S))
            rows.append(row)
        return rows


def _classifiable_onsets(windowing: dict) -> int:
    """Onset windows the classifier can classify: those published with a sensor offset estimate
    (the stream's first onset window has none: no whole load period behind it)."""
    return int(windowing.get("onsets", 0)) - int(windowing.get("onsets_before_offset", 0))


def format_summary(rows: list[dict]) -> str:
    # width: the fused continuous width with its uncertainty (what the level follows); nearest pattern: the
    # fused class, one of the pattern widths (it jumps between them as the drive wears)
    head = ("drive", "true", "width", "nearest pattern", "level", "model fit", "chunks", "discarded", "onsets",
            "estimated", "lag p50/max", "CPU", "real time")
    table = [head]
    for r in rows:
        def mm(x):
            return "-" if x != x else f"{x * 1e3:.2f} mm"
        fit = r.get("model_fit", "-")
        level, _, text = fit.partition(": ")
        table.append((r["drive"], mm(r["true_width_m"]),
                      width_text(r.get("fused_continuous_width_m", math.nan),
                                 r.get("fused_width_uncertainty_m", math.nan)), mm(r["fused_width_m"]), r["level"],
                      short_model_fit(text) if text else level,
                      f"{r['chunks']}/{r['expected_chunks']}", str(r["discarded"]),
                      str(r["onset_windows"]), str(r["onsets_estimated"]),
                      "-" if r["lag_ms_median"] != r["lag_ms_median"]
                      else f"{r['lag_ms_median']:.0f}/{r['lag_ms_max']:.0f} ms",
                      "-" if r["cpu_percent"] != r["cpu_percent"] else f"{r['cpu_percent']:.0f} %",
                      "yes" if r["realtime"] else "NO"))
    widths = [max(len(row[i]) for row in table) for i in range(len(head))]
    lines = ["  ".join(c.rjust(w) for c, w in zip(row, widths)) for row in table]
    lines.insert(1, "  ".join("-" * w for w in widths))
    n_rt = sum(r["realtime"] for r in rows)
    return "\n".join(lines + [f"{n_rt} of {len(rows)} drives monitored in real time"])


def _cpu_seconds(pid: int) -> float:
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
        return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return math.nan


def managed_drive(drive, duration_s: float, rate_factor: float) -> list:
    """The drive's chain and plant as lifecycle nodes ``<namespace>/chain`` and
    ``<namespace>/plant`` (nodes/lifecycle.py): a supervisor can take one drive down and up."""
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.lifecycle import CHAIN_ROUTES, ManagedNodes
    factories = drive_node_factories(drive, duration_s, rate_factor)
    # the chain holds the drive's model version as its parameters (docs/registry.md, live pickup)
    version = DriveVersion.of(drive).chain_parameters()
    routes = {k: (node, target, version[k]) for k, (node, target, _) in CHAIN_ROUTES.items()}
    return [ManagedNodes("chain", factories[:-1], namespace=drive.namespace, routes=routes),
            ManagedNodes("plant", factories[-1:], namespace=drive.namespace)]


def activate(managed, executor) -> None:
    for node in managed:
        node.executor_ref = executor
        node.trigger_configure()
        node.trigger_activate()


def run_one_drive(args) -> int:
    """A drive's own process (layout 'process'): its managed chain and plant on one executor."""
    # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
    from backlash_monitor.nodes.lifecycle import spin_until_shutdown
    # deferred: ros.runtime (rclpy) costs ~75-120 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.runtime import run_nodes
    drive = Drive.from_dict(json.loads(args.drive_json))
    managed = []

    def build():          # after rclpy.init (run_nodes)
        managed.extend(managed_drive(drive, args.duration, args.rate_factor))
        return managed[0]

    def spin(nodes, executor):
        activate(managed, executor)
        spin_until_shutdown(executor)
    return run_nodes([build, lambda: managed[1]], spin=spin)


def run(args) -> int:
    if args.drive_json:
        return run_one_drive(args)
    drives = validate(args)
    config = analyzer_config(drives)
    if args.analyzers:
        config = load_analyzers(args.analyzers)
    if args.aggregator_yaml:
        with open(args.aggregator_yaml, "w", encoding="utf-8") as f:
            f.write("# diagnostic_aggregator analyzers for the fleet (written by `fleet "
                    "--aggregator-yaml`)\n")
            yaml.safe_dump(config, f, sort_keys=False, default_flow_style=None, width=1000)
        print(f"fleet: wrote the analyzers of {len(drives)} drives to {args.aggregator_yaml}")
        return 0
    ensure_references(drives)
    # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    import rclpy
    # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from rclpy.executors import ExternalShutdownException
    # deferred: ros.lean_executor (rclpy) costs ~70-95 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.lean_executor import make_executor
    # deferred: ros.runtime (rclpy) costs ~75-120 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.runtime import (begin_shutdown, freeze_startup_objects,
                                               is_shutdown_error, release_nodes)
    configure_fast_dds()   # before rclpy.init; the drives' processes inherit it
    expected_chunks = int(round(args.duration / CHUNK_S))
    children: dict[str, subprocess.Popen] = {}
    nodes, executor, follower = [], None, None
    rclpy.init()
    started = time.monotonic()
    try:
        monitor_node = rclpy.create_node("fleet_monitor")
        nodes.append(monitor_node)
        monitor = FleetMonitor(monitor_node, drives, config, args.rate_factor)
        if args.foxglove_port >= 0:
            # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
            from rclpy.parameter import Parameter
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.live_view import LiveViewNode
            nodes.append(LiveViewNode(parameter_overrides=[
                Parameter("namespaces", value=[d.namespace for d in drives]),
                Parameter("port", value=args.foxglove_port)]))
        if args.layout == "process":
            for d in drives:
                children[d.hardware_id] = subprocess.Popen(
                    [sys.executable, "-m", "backlash_monitor.nodes.fleet",
                     "--drive-json", json.dumps(d.to_dict()), "--duration", str(args.duration),
                     "--rate-factor", str(args.rate_factor)])
        else:
            for d in drives:
                nodes.extend(managed_drive(d, args.duration, args.rate_factor))
        executor = make_executor()
        for node in nodes:
            executor.add_node(node)
        activate([n for n in nodes if hasattr(n, "trigger_activate")], executor)
        if args.config:
            # deferred: the follower (lifecycle and parameter services) only with a fleet file
            from backlash_monitor.nodes.registry_follower import RegistryFollower
            follower = RegistryFollower(monitor_node, args.config, drives,
                                        log=lambda text: print(text, file=sys.stderr, flush=True))
            print(f"fleet: following {args.config}: a drive's new model version is picked up live "
                  "(docs/registry.md)", file=sys.stderr, flush=True)
        freeze_startup_objects()

        def cpu_of(hardware_id: str) -> float:
            """CPU seconds of the drive's process, or this process's share per drive."""
            if hardware_id in children:
                return _cpu_seconds(children[hardware_id].pid)
            return time.process_time() / len(drives)
        print(f"fleet: {len(drives)} drives ({', '.join(sorted({d.line for d in drives}))}), "
              f"layout {args.layout}, {args.duration:g} simulated s at x{args.rate_factor:g}",
              flush=True)
        wall_limit = args.duration / args.rate_factor + 60.0 + 2.0 * len(drives)
        next_view = time.monotonic() + args.view_period
        done_since, streaming = None, False
        while rclpy.ok() and time.monotonic() - started < wall_limit:
            executor.spin_once(timeout_sec=0.05)
            now = time.monotonic()
            if follower is not None:
                follower.tick(now)
            if args.view_period and now >= next_view:
                next_view = now + args.view_period
                print(("\x1b[H\x1b[2J" if sys.stdout.isatty() else "")
                      + format_table(monitor.view, now), flush=True)
            for h, t in monitor.tally.items():   # CPU is counted from the stream's start
                if t.stream_mark is None and int(t.windowing.get("chunks", 0)) > 0:
                    t.stream_mark = (now, cpu_of(h))
            if not streaming and all(t.stream_mark is not None for t in monitor.tally.values()):
                streaming = True
                print(f"fleet: all {len(drives)} drives streaming", file=sys.stderr, flush=True)
            if all(monitor.drive_done(d.hardware_id, expected_chunks) for d in drives):
                done_since = done_since or now
                if now - done_since > 1.5:    # one more status from every drive
                    break
            for hardware_id, child in children.items():
                if child.poll() not in (None, 0):
                    print(f"fleet: drive {hardware_id}'s process exited with code "
                          f"{child.returncode}", file=sys.stderr)
                    return 1
        wall = time.monotonic() - started
        end = (time.monotonic(), {h: cpu_of(h) for h in monitor.tally})
        for h, t in monitor.tally.items():
            if t.stream_mark is not None and end[0] > t.stream_mark[0]:
                t.cpu_s = 100.0 * (end[1][h] - t.stream_mark[1]) / (end[0] - t.stream_mark[0])
    except ParameterValueError as error:
        print(f"fleet: error: {error}", file=sys.stderr)
        return 2
    except (KeyboardInterrupt, ExternalShutdownException):
        print("fleet: interrupted", file=sys.stderr)
    except Exception as error:
        if not is_shutdown_error(error):   # Ctrl-C/SIGTERM while a callback published: not a fault
            raise
        print("fleet: interrupted", file=sys.stderr)
    finally:
        begin_shutdown()   # from here a second Ctrl-C/SIGTERM is noted, not an interruption
        for child in children.values():
            if child.poll() is None:
                child.send_signal(signal.SIGINT)
        for child in children.values():
            try:
                child.wait(timeout=10)
            except subprocess.TimeoutExpired:
                child.kill()
        release_nodes(executor, nodes)
    rows = monitor.summary(drives, expected_chunks)
    print(format_table(monitor.view, time.monotonic()))
    print(format_summary(rows), flush=True)
    if args.summary_json:
        with open(args.summary_json, "w", encoding="utf-8") as f:
            json.dump({"layout": args.layout, "duration_s": args.duration,
                       "rate_factor": args.rate_factor, "wall_s": wall, "drives": rows,
                       "registry_events": follower.events if follower is not None else []}, f)
    return 0 if rows and all(r["onsets_estimated"] for r in rows) else 1


def main(argv=None) -> int:
    """`ros2 run backlash_monitor fleet [options]` (ROS arguments are passed through)."""
    # deferred: ros.runtime (rclpy) costs ~75-120 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.runtime import command_main
    return command_main("fleet", __doc__, add_arguments, run, argv)


if __name__ == "__main__":
    sys.exit(main())
