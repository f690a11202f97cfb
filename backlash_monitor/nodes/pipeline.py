"""pipeline: the main job — plant_simulator -> windowing -> denoise -> classifier, with a live view.

    ros2 run backlash_monitor pipeline                       # in a ROS 2 install
    python -m backlash_monitor pipeline --duration 10        # from this repo (source env.sh)

Runs the whole graph (one process by default, each node in its own process with --processes),
prints every estimate and the fused estimate against the simulator's true width as it arrives, and
ends with a summary table.

With --processes, a node process that ends before the run is over is named with its exit code or
signal; by default (--restart no) that ends the run: the summary is printed and the exit code is 1.
With --restart on-failure the node is started again (at most --max-restarts times each) and the
run goes on; the summary lists every fault. The node processes end with the pipeline, also when it
is killed with SIGKILL. With no arguments it runs its embedded default: a 5 mm clutch at
eta_k = 0.025 Pa*s^n, n1 = 0.89, real time, for 10 simulated seconds.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
from dataclasses import dataclass, field

from ament_index_python.packages import get_package_prefix

from backlash_monitor.fleet.drives import SIMULATED_WINDOWING_READS
from backlash_monitor.fleet.trend import PRIMARY_SIGNAL
from backlash_monitor.process.supervisor import RESTART_POLICIES, Supervisor
from backlash_monitor.errors import DeprecatedSpelling, UsageError, out_of_range
from backlash_monitor.files.registry import RegistryError, find
from backlash_monitor.files.outputs import OutputError, check_outputs
from backlash_monitor.ros.parameters import ParameterValueError, ros_parameter_args
from backlash_monitor.ros.fast_dds import configure_fast_dds
from backlash_monitor.stream_time import stamp_seconds

DEFAULTS = dict(width_m=0.005, eta_k=0.025, n1=0.89, seed=0, duration=10.0, rate_factor=1.0)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--width-m", type=float, default=DEFAULTS["width_m"], metavar="M",
                        help="backlash width of the simulated clutch [m] (the truth the estimates "
                             "are compared with)")
    parser.add_argument("--eta-k", type=float, default=DEFAULTS["eta_k"],
                        help="absorber fluid consistency [Pa*s^n]")
    parser.add_argument("--n1", type=float, default=DEFAULTS["n1"],
                        help="absorber flow (creep) index; the classifier uses the patterns of this n1")
    parser.add_argument("--seed", type=int, default=DEFAULTS["seed"], metavar="N",
                        help="seed of the simulator's disturbance generators")
    parser.add_argument("--duration", type=float, default=DEFAULTS["duration"], metavar="S",
                        help="simulated seconds to run [s] (8 backlash entries per second, 4 onsets)")
    parser.add_argument("--events", type=int, default=0,
                        help="stop after this many onset estimates (0 = run for --duration)")
    parser.add_argument("--rate-factor", type=float, default=DEFAULTS["rate_factor"], metavar="X",
                        help="simulated seconds per wall second (1 = real time; 0, as fast as possible, is "
                             "replay's only: the simulator paces its stream)")
    parser.add_argument("--trigger", choices=("contact_loss", "paper"), default="contact_loss",
                        help="entry trigger of the windowing node")
    parser.add_argument("--mode", default="",
                        help="classifier mode (default: the classifier's default, the best mode)")
    parser.add_argument("--drive-name", default="drive", help="the drive's name (hardware_id)")
    parser.add_argument("--processes", action="store_true",
                        help="run each node in its own process (as `ros2 run` would) instead of one")
    parser.add_argument("--restart", choices=RESTART_POLICIES, default="no",
                        help="with --processes, what to do when a node process ends before the run "
                             "is over: 'no' = end the run (summary, exit code 1); 'on-failure' = "
                             "start it again and go on (a node that refused its parameters, exit "
                             "code 2, is not restarted)")
    parser.add_argument("--max-restarts", type=int, default=3,
                        help="with --restart on-failure: restarts per node before its next failure "
                             "ends the run")
    parser.add_argument("--record", metavar="FILE.mcap", default="",
                        help="also record every topic of the run into this MCAP file (an existing "
                             "file is an error unless --overwrite; default: no recording)")
    parser.add_argument("--overwrite", action="store_true",
                        help="with --record: replace an existing file (the new recording replaces it "
                             "only once it is complete)")
    parser.add_argument("--set", dest="plant_set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                        help="plant config override as in `simulate --set`, e.g. --set effects.wheel_coulomb_friction=true "
                             "--set wheel_coulomb_friction.torque_Nm=1.5 (docs/effects.md); repeatable")
    parser.add_argument("--effects-file", dest="effects_files", action="append", default=[], metavar="FILE.py",
                        help="a Python file with your own Effect classes for the plant (docs/effects.md); repeatable")
    parser.add_argument("--set-at", dest="set_at", action="append", nargs="+", default=[],
                        metavar=("TIME", "SECTION.KEY=VALUE"),
                        help="change the simulated plant at simulated TIME (e.g. 30s) with these overrides, as "
                             "--set: --set-at 30s effects.wheel_coulomb_friction=true "
                             "wheel_coulomb_friction.torque_Nm=1.5 (an effect that appears mid-run); repeatable")
    parser.add_argument("--library", default="", metavar="LIB.npz",
                        help="the classifier's pattern library (default: the packaged one); with --watch its "
                             "model reference LIB.watch.npz beside it (written by `train --model`) is the watch's")
    parser.add_argument("--watch", action="store_true",
                        help="also run the model watch (node model_watch, docs/model_watch.md): the drive's onset "
                             "events against its model version, OK/WARN on /diagnostics and in the live view, a "
                             "snapshot bag on a WARN")
    parser.add_argument("--model", default="", metavar="M.yaml",
                        help="with --watch: the drive's model version (default: config/plant.yaml at --width-m, "
                             "--eta-k, --n1); its reference: --library's LIB.watch.npz, else the cache (built "
                             "there once, ~30 s)")
    parser.add_argument("--snapshot-dir", default=".", metavar="DIR",
                        help="with --watch: the folder the snapshot bags go into (default: the current folder)")
    parser.add_argument("--drive", default="", metavar="NAME",
                        help="a drive of the registry (docs/registry.md): its nominal width, eta_k and n1, its name, "
                             "and (unless given) its library, model version and watch reference (default: no drive of a registry)")
    parser.add_argument("--registry", default="drives.yaml", metavar="PATH",
                        help="the drive registry YAML (default: ./drives.yaml); with --drive")
    parser.add_argument("--effects", dest="effects_files", action=DeprecatedSpelling, new="--effects-file",
                        append=True, metavar="FILE.py", help=argparse.SUPPRESS)


def apply_registry(args) -> None:
    """--drive: the drive's nominal conditions and hardware id, and its library, model and watch reference where
    none is given (files/registry.py)."""
    try:
        entry = find(args.registry, args.drive)
    except RegistryError as exc:
        raise UsageError(str(exc)) from None
    args.width_m, args.eta_k, args.n1 = (entry.nominal[k] for k in ("width_m", "eta_k", "n1"))
    args.drive_name = entry.hardware_id
    if not args.library and entry.library is not None:
        args.library = str(entry.library)
    if args.watch and not args.model and entry.model is not None:
        args.model = str(entry.model)
    args.registry_reference = str(entry.watch_reference or "")


def validate(args) -> None:
    if getattr(args, "drive", ""):
        apply_registry(args)
    if args.rate_factor == 0:
        raise UsageError("--rate-factor 0 (as fast as possible) is replay's only: the simulator paces its stream; "
                         "allowed 0.01..1000")
    checks = [("--width-m", args.width_m, 1e-4, 0.05, "m"), ("--eta-k", args.eta_k, 1e-4, 1.0, "Pa*s^n"),
              ("--n1", args.n1, 0.5, 1.5, ""), ("--duration", args.duration, 0.1, 1e6, "s"),
              ("--rate-factor", args.rate_factor, 0.01, 1000.0, "")]
    for name, value, lo, hi, unit in checks:
        if not (lo <= value <= hi):
            raise out_of_range(name, value, lo, hi, unit)
    if args.events < 0:
        raise out_of_range("--events", args.events, 0, "inf (0: no limit)")
    if args.seed < 0:
        raise out_of_range("--seed", args.seed, 0, "inf")
    if args.max_restarts < 0:
        raise out_of_range("--max-restarts", args.max_restarts, 0, "inf")
    if args.restart != "no" and not args.processes:
        raise UsageError(f"--restart {args.restart} needs --processes (one process has no node "
                         "process to restart); allowed: --restart no, or add --processes")
    args.set_at_entries = set_at_entries(args.set_at)
    if (args.model or args.snapshot_dir != ".") and not args.watch:
        raise UsageError("--model and --snapshot-dir are options of the model watch; add --watch")
    if args.library and not os.path.isfile(args.library):
        raise UsageError(f"--library {args.library}: no such file; give a pattern library (train --out LIB.npz)")
    if args.record:
        try:
            check_outputs([args.record], overwrite=args.overwrite, option="--record")
        except OutputError as error:
            raise UsageError(str(error)) from None


def set_at_entries(groups) -> list[str]:
    """--set-at TIME KEY=VALUE ... groups -> the plant_simulator's plant_set_at entries 'T_S:KEY=VALUE;...'."""
    out = []
    for group in groups or []:
        if len(group) < 2:
            raise UsageError(f"--set-at {' '.join(group)}: allowed: --set-at TIME SECTION.KEY=VALUE [...], e.g. "
                             "--set-at 30s effects.wheel_coulomb_friction=true")
        head = group[0].strip()
        try:
            t_s = float(head[:-1] if head.endswith("s") else head)
        except ValueError:
            t_s = -1.0
        if not 0.0 <= t_s < 1e6:
            raise UsageError(f"--set-at {head}: the time is simulated seconds >= 0, e.g. 30s or 12.5")
        bad = [x for x in group[1:] if "=" not in x]
        if bad:
            raise UsageError(f"--set-at {head} {bad[0]}: expected SECTION.KEY=VALUE, e.g. "
                             "effects.wheel_coulomb_friction=true")
        out.append(f"{t_s:g}:" + ";".join(group[1:]))
    return out


WATCH_READS = "model_watch:a1,a2,angle_difference,omega1"    # --watch: what the model watch reads (omega1: snapshot)
RECORD_NODE = "record"                                 # --record: records every plant signal
NODE_ORDER = ("classifier", "denoise", "windowing", "plant_simulator")   # readers first
WATCH_ORDER = ("model_watch",) + NODE_ORDER
# After the stream ends the run waits for the estimates still in flight: until none has come for
# IN_FLIGHT_QUIET_S [s]; while none has come at all, up to FIRST_ESTIMATE_GRACE_S [s] (a loaded
# machine: the node processes' first window can take seconds; CI saw a 2 s run end with none).
IN_FLIGHT_QUIET_S = 2.0
FIRST_ESTIMATE_GRACE_S = 10.0
# The summary's count of onset windows before the sensor offset was known comes from the windowing
# node's 1 Hz status on /diagnostics; a status can reach this process late (DDS discovery of a node
# process): after the stream, wait up to this long for a first one rather than print a summary without it.
WINDOWING_STATUS_GRACE_S = 5.0


def node_parameters(args) -> dict[str, dict]:
    """The parameters each node of the graph is started with."""
    return {
        "plant_simulator": dict(drive_name=args.drive_name, width_m=args.width_m, eta_k=args.eta_k,
                                n1=args.n1, seed=args.seed, rate_factor=args.rate_factor,
                                duration_s=args.duration, qos="reliable",
                                plant_set=";".join(getattr(args, "plant_set", None) or []),
                                plant_set_at=getattr(args, "set_at_entries", None) or [""],
                                effects_files=";".join(getattr(args, "effects_files", None) or []),
                                # the readers the stream is for (not a count: another subscriber
                                # in the domain must not start it early)
                                wait_for_subscribers=[SIMULATED_WINDOWING_READS]
                                + ([RECORD_NODE] if args.record else [])
                                + ([WATCH_READS] if getattr(args, "watch", False) else [])),
        # the simulated drive publishes its motor speed: a1 is checked against it (docs/classifier.md 5.4)
        "windowing": dict(drive_name=args.drive_name, trigger=args.trigger, qos="reliable",
                          width_m=args.width_m if args.trigger == "paper" else 0.0, check_a1_chain=True),
        "denoise": {},
        "classifier": dict(drive_name=args.drive_name, n1=args.n1, trigger=args.trigger,
                           **({"mode": args.mode} if args.mode else {}),
                           **({"library": args.library} if getattr(args, "library", "") else {})),
        "model_watch": dict(drive_name=args.drive_name, qos="reliable",
                            reference=str(getattr(args, "watch_reference", "") or ""),
                            snapshot_dir=getattr(args, "snapshot_dir", ".")),
    }


def watch_reference(args, log=print) -> str:
    """--watch: the path of the drive's model reference (--library's LIB.watch.npz, else the model's from the
    cache, built there when missing)."""
    # deferred: the model (the simulator) costs ~800-1100 ms at start-up (python -X importtime, 29 Nov); only a model watch loads it
    from backlash_monitor.workbench import reference
    # deferred: the model (the simulator) costs ~800-1100 ms at start-up (python -X importtime, 29 Nov); only a model watch loads it
    from backlash_monitor.workbench.model import ModelError, load_model
    if getattr(args, "registry_reference", ""):
        return args.registry_reference
    if args.library:
        beside = reference.reference_path_for_library(args.library)
        if beside.is_file():
            return str(beside)
        if args.model:
            raise UsageError(f"--library {args.library} has no model reference beside it ({beside}); make it with "
                             f"`python -m backlash_monitor watch-reference --model {args.model} --out {beside}`")
    try:
        model = load_model(args.model or None, width_m=None if args.model else args.width_m,
                           eta_k=None if args.model else args.eta_k, n1=None if args.model else args.n1)
    except ModelError as error:
        raise UsageError(str(error)) from None
    return str(reference.cached(model, log=lambda text: log(f"pipeline: {text}")).path)


@dataclass
class SignalTally:
    estimates: int = 0
    correct: int = 0
    fused_width_m: float = math.nan
    fused_events: int = 0
    fused_continuous_width_m: float = math.nan
    margins: list = field(default_factory=list)
    continuous: list = field(default_factory=list)


class PipelineConsole:
    """Prints one line per onset event as its estimates arrive; keeps tallies for the summary."""

    def __init__(self, true_width_m: float, signals: tuple[str, ...],
                 sample_period_s: float = 2e-5, out=sys.stdout):
        self.true_width_m = true_width_m
        self.sample_period_s = sample_period_s
        self.signals = signals
        self.out = out
        self.tally: dict[str, SignalTally] = {}
        # events by (window stamp, entry index): a restarted plant starts its indices at 0 again
        self.onset_entries: set[tuple] = set()
        self.pending: dict[tuple, dict] = {}
        self.last_event_s = math.nan      # stream time of the latest event seen
        self.completed_events = 0         # onset events with an estimate on every signal
        self.first_arrival_s: float | None = None   # time.monotonic() of the first estimate
        self.last_arrival_s: float | None = None
        self.diagnostic = ""
        self.windowing = ""
        self.mode = ""
        self.seen: set[tuple] = set()
        self.repeated = 0                 # estimates received again (a restarted classifier)
        self.faults: list[str] = []       # node processes that ended before the run was over
        self.windowing_joined_at = 0      # first sample the (latest) windowing process saw
        self.model_fit = None             # the model watch's last ModelFit (--watch)
        self.watch_status = ""            # its last /diagnostics status, "LEVEL: message"
        self.watch_level = ""
        self.watch_snapshot = ""
        self.onsets_before_offset = 0     # onset windows published before the sensor offset was known

    def onset_gaps(self) -> list[tuple[float, float, int]]:
        """Gaps in the onset estimates of each stream: (t before, t after [s], onsets missing at
        the median spacing), where two estimates are more than 1.5 median spacings apart (a
        drive's onsets recur at its cycle; a gap is a range nothing was estimated from)."""
        streams: dict[float, list[float]] = {}
        for sec, nanosec, entry in self.onset_entries:
            t = entry * self.sample_period_s
            streams.setdefault(round(stamp_seconds((sec, nanosec)) - t, 3), []).append(t)   # by the stream's origin
        gaps = []
        for times in streams.values():
            times.sort()
            spacings = sorted(b - a for a, b in zip(times, times[1:]))
            if len(spacings) < 2:
                continue
            median = spacings[len(spacings) // 2]
            gaps += [(a, b, round((b - a) / median) - 1) for a, b in zip(times, times[1:])
                     if b - a > 1.5 * median]
        return gaps

    def on_fault(self, description: str) -> None:
        """A node process ended: say so in line with the estimates; the summary lists it."""
        last = ("" if math.isnan(self.last_event_s)
                else f"; last estimate before it: event at t={self.last_event_s:.3f} s")
        self.faults.append(description + last)
        print(f"pipeline: {description}{last}", file=self.out, flush=True)

    def on_estimate(self, msg) -> None:
        # A restarted classifier (transient local windows) classifies the windows it had seen
        # again and re-sends their estimates: count each estimate once.
        key = (msg.signal_name, msg.entry_sample_index, msg.entry_kind, msg.header.stamp.sec,
               msg.header.stamp.nanosec)
        if key in self.seen:
            self.repeated += 1
            return
        self.seen.add(key)
        self.last_arrival_s = time.monotonic()
        if self.first_arrival_s is None:
            self.first_arrival_s = self.last_arrival_s
        t = self.tally.setdefault(msg.signal_name, SignalTally())
        self.mode = msg.mode
        if not math.isnan(msg.true_width_m):
            self.true_width_m = msg.true_width_m
        t.estimates += 1
        t.correct += int(abs(msg.width_m - self.true_width_m) < 1e-9)
        t.fused_width_m, t.fused_events = msg.fused_width_m, msg.fused_events
        t.fused_continuous_width_m = msg.fused_continuous_width_m
        t.margins.append(msg.b_margin)
        if not math.isnan(msg.continuous_width_m):
            t.continuous.append(msg.continuous_width_m)
        event_key = key[3:] + (msg.entry_sample_index,)
        self.onset_entries.add(event_key)
        self.last_event_s = msg.entry_sample_index * self.sample_period_s
        event = self.pending.setdefault(event_key, {})
        event[msg.signal_name] = msg
        if len(event) >= len(self.signals):
            self.print_event(self.pending.pop(event_key))
            self.completed_events += 1

    def flush(self) -> None:
        """Print the events still missing an estimate on some signal (at the end of a run)."""
        for entry in sorted(self.pending):
            self.print_event(self.pending.pop(entry))

    def print_event(self, event: dict) -> None:
        first = next(iter(event.values()))
        parts = []
        for name, msg in event.items():
            ok = abs(msg.width_m - self.true_width_m) < 1e-9
            cont = ("" if math.isnan(msg.continuous_width_m)
                    else f" ({msg.continuous_width_m * 1e3:4.2f})")
            parts.append(f"{name} {msg.width_m * 1e3:5.2f}{cont} {'ok' if ok else 'MISS'}")
        last = event.get(PRIMARY_SIGNAL, first)
        fused_ok = abs(last.fused_width_m - self.true_width_m) < 1e-9
        cont = ("" if math.isnan(last.fused_continuous_width_m)
                else f" ({last.fused_continuous_width_m * 1e3:4.2f})")
        fit = self.model_fit
        watch = ("" if fit is None else
                 f" | model {fit.residual_over_noise_overall:3.1f}x {'WARN' if fit.level == fit.WARN else 'ok'}")
        print(f"t={first.entry_sample_index * self.sample_period_s:8.3f} s  onset  "
              + " | ".join(parts)
              + f" | fused {last.fused_width_m * 1e3:5.2f}{cont} mm over {last.fused_events} "
              f"{'ok' if fused_ok else 'MISS'}   true {self.true_width_m * 1e3:.2f} mm" + watch,
              file=self.out, flush=True)

    def on_model_fit(self, msg) -> None:
        self.model_fit = msg

    def on_diagnostics(self, msg) -> None:
        for status in msg.status:
            level = status.level if isinstance(status.level, int) else ord(status.level)
            text = f"{['OK', 'WARN', 'ERROR', 'STALE'][min(level, 3)]}: {status.message}"
            values = {kv.key: kv.value for kv in status.values}
            if "classifier" in status.name:
                self.diagnostic = text
            elif "model_watch" in status.name:
                self.watch_status = text
                name = ['OK', 'WARN', 'ERROR', 'STALE'][min(level, 3)]
                snapshot = values.get("snapshot", "")
                if name != self.watch_level and (name != "OK" or self.watch_level):
                    print(f"pipeline: model watch {text}", file=self.out, flush=True)
                elif snapshot != self.watch_snapshot and snapshot and "recording" not in snapshot:
                    print(f"pipeline: model watch: {snapshot} written", file=self.out, flush=True)
                self.watch_level, self.watch_snapshot = name, snapshot
            elif "windowing" in status.name:
                self.windowing_joined_at = int(values.get("joined_at_sample") or 0)
                self.onsets_before_offset = int(values.get("onsets_before_offset") or 0)
                self.windowing = (f"{text} (incomplete chunk ranges "
                                  f"{values.get('incomplete_chunks', '0')}, last discard: "
                                  f"{values.get('last_discard') or 'none'})")

    def summary(self) -> str:
        rows = [("signal", "estimates", "correct", "accuracy", "median margin", "fused width",
                 "fused continuous", "fused events", "fused ok")]
        for name, t in sorted(self.tally.items()):
            margins = sorted(t.margins)
            rows.append((name, str(t.estimates), str(t.correct),
                         f"{t.correct / t.estimates:.0%}" if t.estimates else "-",
                         f"{margins[len(margins) // 2]:.2f}" if margins else "-",
                         f"{t.fused_width_m * 1e3:.2f} mm",
                         "-" if math.isnan(t.fused_continuous_width_m)
                         else f"{t.fused_continuous_width_m * 1e3:.2f} mm", str(t.fused_events),
                         "yes" if abs(t.fused_width_m - self.true_width_m) < 1e-9 else "no"))
        widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
        lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
        lines.insert(1, "  ".join("-" * w for w in widths))
        head = (f"summary: true width {self.true_width_m * 1e3:.2f} mm, mode {self.mode or '-'}, "
                f"{len(self.onset_entries)} onset windows classified"
                + (f" ({self.onsets_before_offset} more before the sensor offset was known: one whole "
                   "load period is needed)" if self.onsets_before_offset else ""))
        tail = [f"last diagnostics (sent once a second): classifier {self.diagnostic}"] \
            if self.diagnostic else []
        tail += [f"last diagnostics (sent once a second): windowing {self.windowing}"] \
            if self.windowing else []
        tail += [f"last diagnostics (sent once a second): model_watch {self.watch_status}"] \
            if self.watch_status else []
        tail += [f"repeated estimates ignored: {self.repeated} (re-sent by a restarted node)"] \
            if self.repeated else []
        tail += [f"node fault: {fault}" for fault in self.faults]
        tail += [f"onset estimates missing: t={a:.3f}..{b:.3f} s ({n} onsets at the median "
                 "spacing)" for a, b, n in self.onset_gaps()]
        tail += [f"windowing: its process joined the stream at t="
                 f"{self.windowing_joined_at * self.sample_period_s:.3f} s (sample "
                 f"{self.windowing_joined_at}); it did not see the samples before"] \
            if self.windowing_joined_at else []
        return "\n".join([head] + lines + tail)


def _executable(name: str) -> str:
    return os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", name)


def run(args) -> int:
    validate(args)
    if args.watch:
        args.watch_reference = watch_reference(args)
    # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    import rclpy
    # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from rclpy.executors import ExternalShutdownException
    # deferred: rclpy costs ~60-100 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from rclpy.parameter import Parameter
    # deferred: ros.qos (rclpy) costs ~50-60 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.qos import ESTIMATE_QOS
    # deferred: ros.runtime (rclpy) costs ~75-120 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.runtime import begin_shutdown, freeze_startup_objects, release_nodes

    # deferred: estimation costs ~140 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.estimation import DEFAULT_MODE, default_signals
    # deferred: ros.lean_executor (rclpy) costs ~70-95 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.lean_executor import make_executor
    configure_fast_dds()  # before rclpy.init; the child processes inherit it
    params = node_parameters(args)
    order = WATCH_ORDER if args.watch else NODE_ORDER
    # deferred: backlash_monitor_msgs is built into install/: --help works before `source env.sh`
    from backlash_monitor_msgs.msg import BacklashEstimate, ModelFit
    # deferred: as above
    from diagnostic_msgs.msg import DiagnosticArray
    view = PipelineConsole(args.width_m, default_signals(args.mode or DEFAULT_MODE))
    supervisor = None
    exit_code = 0
    interrupted = False
    rclpy.init()
    nodes = []
    executor = None
    try:
        monitor = rclpy.create_node("pipeline_monitor")
        nodes.append(monitor)
        monitor.create_subscription(BacklashEstimate, "estimate", view.on_estimate, ESTIMATE_QOS)
        monitor.create_subscription(DiagnosticArray, "/diagnostics", view.on_diagnostics, 10)
        if args.watch:
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.model_watch import MODEL_FIT_QOS
            monitor.create_subscription(ModelFit, "model_fit", view.on_model_fit, MODEL_FIT_QOS)
        if args.record:
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.record import RecordNode
            nodes.append(RecordNode(parameter_overrides=[Parameter("output", value=args.record),
                                                         Parameter("overwrite", value=args.overwrite)]))
        plant = None
        if args.processes:
            supervisor = Supervisor({name: [_executable(name)] + ros_parameter_args(params[name])
                                     for name in order},
                                    restart=args.restart, max_restarts=args.max_restarts,
                                    finishing=("plant_simulator",))
            supervisor.start()
        else:
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.classifier import ClassifierNode
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.denoise import DenoiseNode
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
            # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
            from backlash_monitor.nodes.windowing import WindowingNode
            classes = [(ClassifierNode, "classifier"), (DenoiseNode, "denoise"),
                       (WindowingNode, "windowing"), (PlantSimulatorNode, "plant_simulator")]
            if args.watch:
                # deferred: a node module costs 60-1300 ms at start-up (python -X importtime, 29 Nov); only the nodes this run starts are imported
                from backlash_monitor.nodes.model_watch import ModelWatchNode
                classes.insert(0, (ModelWatchNode, "model_watch"))
            for cls, name in classes:
                nodes.append(cls(parameter_overrides=[Parameter(k, value=v)
                                                      for k, v in params[name].items()]))
            plant = nodes[-1]
        executor = make_executor()
        for node in nodes:
            executor.add_node(node)
        freeze_startup_objects()
        print(f"pipeline: {args.drive_name}, true width {args.width_m * 1e3:g} mm, eta_k "
              f"{args.eta_k:g}, n1 {args.n1:g}, trigger {args.trigger}, "
              f"{'one process per node' if args.processes else 'one process'}; "
              f"{args.duration:g} simulated s at x{args.rate_factor:g}", flush=True)
        for entry in args.set_at_entries:
            t_s, _, changes = entry.partition(":")
            print(f"pipeline: the plant changes at t = {float(t_s):g} s: {changes.replace(';', ', ')}", flush=True)
        if args.watch:
            print(f"pipeline: model watch on, reference {args.watch_reference}; snapshots into "
                  f"{os.path.abspath(args.snapshot_dir)}", flush=True)
        if supervisor is not None:
            print("pipeline: node processes: " + ", ".join(
                f"{name} pid {pid}" for name, pid in supervisor.pids().items())
                + f"; restart policy {args.restart}", flush=True)
        stream_wall_s = args.duration / args.rate_factor
        deadline = time.monotonic() + stream_wall_s + 30.0   # start-up included
        stream_ended_s = None
        while rclpy.ok() and time.monotonic() < deadline:
            executor.spin_once(timeout_sec=0.05)
            now = time.monotonic()
            if supervisor is not None:
                for fault in supervisor.poll():
                    view.on_fault(fault.describe())
                    if fault.node == "plant_simulator" and fault.restarted_pid is not None:
                        stream_ended_s = None           # a new stream, as long as the first
                        deadline = now + stream_wall_s + 30.0
                if supervisor.failed is not None:
                    exit_code = 1
                    break
            if args.events and view.completed_events >= args.events:
                break
            if stream_ended_s is None and (supervisor.finished("plant_simulator")
                                           if supervisor is not None else plant.finished):
                stream_ended_s = now
                deadline = min(deadline, now + 30.0)
            # The stream has ended: wait until the estimates in flight stop coming (windows and
            # estimates are transient local: a slow stage delivers late, it does not lose them).
            if stream_ended_s is not None and now - max(stream_ended_s, view.last_arrival_s or 0.0) \
                    > (IN_FLIGHT_QUIET_S if view.last_arrival_s is not None else FIRST_ESTIMATE_GRACE_S) \
                    and (view.windowing or now - stream_ended_s > WINDOWING_STATUS_GRACE_S):
                break
    except ParameterValueError as error:
        raise UsageError(str(error)) from None
    except (KeyboardInterrupt, ExternalShutdownException):
        print("pipeline: interrupted", file=sys.stderr)
        interrupted = True     # Ctrl-C reaches the node processes too: not their fault
    finally:
        begin_shutdown()   # from here a second Ctrl-C/SIGTERM is noted, not an interruption
        if supervisor is not None:
            for fault in ([] if interrupted else supervisor.poll(restart=False)):
                view.on_fault(fault.describe())     # one that ended as the run did
                exit_code = 1
            supervisor.stop()
        release_nodes(executor, nodes)
    view.flush()
    print(view.summary(), flush=True)
    return exit_code or (0 if view.tally else 1)


def main(argv=None) -> int:
    """`ros2 run backlash_monitor pipeline [options]` (ROS arguments are passed through)."""
    # deferred: ros.runtime (rclpy) costs ~75-120 ms at start-up (python -X importtime, 29 Nov); python -m backlash_monitor --help imports this module
    from backlash_monitor.ros.runtime import command_main
    return command_main("pipeline", __doc__, add_arguments, run, argv)


if __name__ == "__main__":
    sys.exit(main())
