"""pipeline: the main job — plant_simulator -> windowing -> denoise -> classifier, with a live view.

    ros2 run backlash_monitor pipeline                       # in a ROS 2 install
    python -m backlash_monitor pipeline --duration 10        # from this repo (source env.sh)

Runs the whole graph (one process by default, each node in its own process with --processes),
prints every estimate and the fused estimate against the simulator's true width as it arrives, and
ends with a summary table. With no arguments it runs its embedded default: a 5 mm clutch at
eta_k = 0.025 Pa*s^n, n1 = 0.89, real time, for 10 simulated seconds.
"""
from __future__ import annotations

import argparse
import math
import os
import signal
import subprocess
import sys
import time
from dataclasses import dataclass, field

DEFAULTS = dict(width_m=0.005, eta_k=0.025, n1=0.89, seed=0, duration=10.0, rate_factor=1.0)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--width-m", type=float, default=DEFAULTS["width_m"],
                        help="backlash width of the simulated clutch [m] (the truth the estimates "
                             "are compared with)")
    parser.add_argument("--eta-k", type=float, default=DEFAULTS["eta_k"],
                        help="absorber fluid consistency [Pa*s^n]")
    parser.add_argument("--n1", type=float, default=DEFAULTS["n1"],
                        help="absorber flow (creep) index; the classifier uses the patterns of this n1")
    parser.add_argument("--seed", type=int, default=DEFAULTS["seed"],
                        help="seed of the simulator's disturbance generators")
    parser.add_argument("--duration", type=float, default=DEFAULTS["duration"],
                        help="simulated seconds to run (8 backlash entries per second, 4 onsets)")
    parser.add_argument("--events", type=int, default=0,
                        help="stop after this many onset estimates (0 = run for --duration)")
    parser.add_argument("--rate-factor", type=float, default=DEFAULTS["rate_factor"],
                        help="simulated seconds per wall second (1 = real time)")
    parser.add_argument("--trigger", choices=("contact_loss", "paper"), default="contact_loss",
                        help="entry trigger of the windowing node")
    parser.add_argument("--mode", default="",
                        help="classifier mode (empty: the classifier's default, the best mode)")
    parser.add_argument("--drive-name", default="drive", help="the drive's name (hardware_id)")
    parser.add_argument("--processes", action="store_true",
                        help="run each node in its own process (as `ros2 run` would) instead of one")
    parser.add_argument("--record", metavar="FILE.mcap", default="",
                        help="also record every topic of the run into this MCAP file (an existing "
                             "file is an error unless --overwrite)")
    parser.add_argument("--overwrite", action="store_true",
                        help="with --record: replace an existing file (the new recording replaces it "
                             "only once it is complete)")


def validate(args) -> None:
    from backlash_monitor.errors import UsageError
    checks = [("--width-m", args.width_m, 1e-4, 0.05), ("--eta-k", args.eta_k, 1e-4, 1.0),
              ("--n1", args.n1, 0.5, 1.5), ("--duration", args.duration, 0.1, 1e6),
              ("--rate-factor", args.rate_factor, 0.01, 1000.0)]
    for name, value, lo, hi in checks:
        if not (lo <= value <= hi):
            raise UsageError(f"{name} = {value:g} is out of range; allowed: {lo:g} .. {hi:g}")
    if args.events < 0:
        raise UsageError(f"--events = {args.events}; allowed: 0 (no limit) or more")
    if args.seed < 0:
        raise UsageError(f"--seed = {args.seed}; allowed: 0 or more")
    if args.record:
        from backlash_monitor.output_files import OutputError, check_outputs
        try:
            check_outputs([args.record], overwrite=args.overwrite, option="--record")
        except OutputError as error:
            raise UsageError(str(error)) from None


def node_parameters(args) -> dict[str, dict]:
    """The parameters each node of the graph is started with."""
    return {
        "plant_simulator": dict(drive_name=args.drive_name, width_m=args.width_m, eta_k=args.eta_k,
                                n1=args.n1, seed=args.seed, rate_factor=args.rate_factor,
                                duration_s=args.duration, qos="reliable",
                                # windowing: a1, a2, angle_difference; a recorder: all five
                                wait_for_subscriptions=8 if args.record else 3),
        "windowing": dict(drive_name=args.drive_name, trigger=args.trigger, qos="reliable",
                          width_m=args.width_m if args.trigger == "paper" else 0.0),
        "denoise": {},
        "classifier": dict(drive_name=args.drive_name, n1=args.n1, trigger=args.trigger,
                           **({"mode": args.mode} if args.mode else {})),
    }


@dataclass
class SignalTally:
    estimates: int = 0
    correct: int = 0
    fused_width_m: float = math.nan
    fused_events: int = 0
    margins: list = field(default_factory=list)
    continuous: list = field(default_factory=list)


class LiveView:
    """Prints one line per onset event as its estimates arrive; keeps tallies for the summary."""

    def __init__(self, true_width_m: float, signals: tuple[str, ...],
                 sample_period_s: float = 2e-5, out=sys.stdout):
        self.true_width_m = true_width_m
        self.sample_period_s = sample_period_s
        self.signals = signals
        self.out = out
        self.tally: dict[str, SignalTally] = {}
        self.onset_entries: set[int] = set()
        self.pending: dict[int, dict] = {}
        self.completed_events = 0         # onset events with an estimate on every signal
        self.first_arrival_s: float | None = None   # time.monotonic() of the first estimate
        self.last_arrival_s: float | None = None
        self.diagnostic = ""
        self.windowing = ""
        self.mode = ""

    def on_estimate(self, msg) -> None:
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
        t.margins.append(msg.b_margin)
        if not math.isnan(msg.continuous_width_m):
            t.continuous.append(msg.continuous_width_m)
        self.onset_entries.add(msg.entry_sample_index)
        event = self.pending.setdefault(msg.entry_sample_index, {})
        event[msg.signal_name] = msg
        if len(event) >= len(self.signals):
            self.print_event(self.pending.pop(msg.entry_sample_index))
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
        last = event.get("a1+a2", first)
        fused_ok = abs(last.fused_width_m - self.true_width_m) < 1e-9
        print(f"t={first.entry_sample_index * self.sample_period_s:8.3f} s  onset  "
              + " | ".join(parts)
              + f" | fused {last.fused_width_m * 1e3:5.2f} mm over {last.fused_events} "
              f"{'ok' if fused_ok else 'MISS'}   true {self.true_width_m * 1e3:.2f} mm",
              file=self.out, flush=True)

    def on_diagnostics(self, msg) -> None:
        for status in msg.status:
            level = status.level if isinstance(status.level, int) else ord(status.level)
            text = f"{['OK', 'WARN', 'ERROR', 'STALE'][min(level, 3)]}: {status.message}"
            values = {kv.key: kv.value for kv in status.values}
            if "classifier" in status.name:
                self.diagnostic = text
            elif "windowing" in status.name:
                self.windowing = (f"{text} (incomplete chunk ranges "
                                  f"{values.get('incomplete_chunks', '0')}, last discard: "
                                  f"{values.get('last_discard') or 'none'})")

    def summary(self) -> str:
        rows = [("signal", "estimates", "correct", "accuracy", "median margin", "fused width",
                 "fused events", "fused ok")]
        for name, t in sorted(self.tally.items()):
            margins = sorted(t.margins)
            rows.append((name, str(t.estimates), str(t.correct),
                         f"{t.correct / t.estimates:.0%}" if t.estimates else "-",
                         f"{margins[len(margins) // 2]:.2f}" if margins else "-",
                         f"{t.fused_width_m * 1e3:.2f} mm", str(t.fused_events),
                         "yes" if abs(t.fused_width_m - self.true_width_m) < 1e-9 else "no"))
        widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
        lines = ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
        lines.insert(1, "  ".join("-" * w for w in widths))
        head = (f"summary: true width {self.true_width_m * 1e3:.2f} mm, mode {self.mode or '-'}, "
                f"{len(self.onset_entries)} onset windows classified")
        tail = [f"last diagnostics (sent once a second): classifier {self.diagnostic}"] \
            if self.diagnostic else []
        tail += [f"last diagnostics (sent once a second): windowing {self.windowing}"] \
            if self.windowing else []
        return "\n".join([head] + lines + tail)


def _executable(name: str) -> str:
    from ament_index_python.packages import get_package_prefix
    return os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", name)


def run(args) -> int:
    validate(args)
    import rclpy
    from rclpy.executors import ExternalShutdownException
    from rclpy.parameter import Parameter
    from diagnostic_msgs.msg import DiagnosticArray
    from backlash_monitor_msgs.msg import BacklashEstimate
    from backlash_monitor.nodes.qos import ESTIMATE_QOS
    from backlash_monitor.nodes.parameters import ParameterValueError
    from backlash_monitor.nodes.runtime import freeze_startup_objects

    from backlash_monitor.estimation import DEFAULT_MODE, default_signals
    from backlash_monitor.nodes.fast_dds import configure_fast_dds
    from backlash_monitor.nodes.lean_executor import make_executor
    configure_fast_dds()  # before rclpy.init; the child processes inherit it
    from backlash_monitor.nodes.parameters import ros_parameter_args
    params = node_parameters(args)
    view = LiveView(args.width_m, default_signals(args.mode or DEFAULT_MODE))
    children: list[subprocess.Popen] = []
    rclpy.init()
    nodes = []
    executor = None
    try:
        monitor = rclpy.create_node("pipeline_monitor")
        nodes.append(monitor)
        monitor.create_subscription(BacklashEstimate, "estimate", view.on_estimate, ESTIMATE_QOS)
        monitor.create_subscription(DiagnosticArray, "/diagnostics", view.on_diagnostics, 10)
        if args.record:
            from backlash_monitor.nodes.record import RecordNode
            nodes.append(RecordNode(parameter_overrides=[Parameter("output", value=args.record),
                                                         Parameter("overwrite", value=args.overwrite)]))
        if args.processes:
            for name in ("classifier", "denoise", "windowing", "plant_simulator"):
                children.append(subprocess.Popen([_executable(name)]
                                                 + ros_parameter_args(params[name])))
        else:
            from backlash_monitor.nodes.classifier import ClassifierNode
            from backlash_monitor.nodes.denoise import DenoiseNode
            from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
            from backlash_monitor.nodes.windowing import WindowingNode
            for cls, name in ((ClassifierNode, "classifier"), (DenoiseNode, "denoise"),
                              (WindowingNode, "windowing"), (PlantSimulatorNode, "plant_simulator")):
                nodes.append(cls(parameter_overrides=[Parameter(k, value=v)
                                                      for k, v in params[name].items()]))
        executor = make_executor()
        for node in nodes:
            executor.add_node(node)
        freeze_startup_objects()
        print(f"pipeline: {args.drive_name}, true width {args.width_m * 1e3:g} mm, eta_k "
              f"{args.eta_k:g}, n1 {args.n1:g}, trigger {args.trigger}, "
              f"{'one process per node' if args.processes else 'one process'}; "
              f"{args.duration:g} simulated s at x{args.rate_factor:g}", flush=True)
        stream_wall_s = args.duration / args.rate_factor
        wall_limit = stream_wall_s + 30.0
        started = time.monotonic()
        while rclpy.ok() and time.monotonic() - started < wall_limit:
            executor.spin_once(timeout_sec=0.05)
            if args.events and view.completed_events >= args.events:
                break
            if view.first_arrival_s is not None:
                # The stream started before the first estimate arrived, so it has ended by
                # first arrival + its wall duration; then wait until the estimates stop coming.
                now = time.monotonic()
                if now > view.first_arrival_s + stream_wall_s + 1.0 \
                        and now - view.last_arrival_s > 1.0:
                    break
            for child in children:
                if child.poll() not in (None, 0):
                    print(f"pipeline: a node exited with code {child.returncode}", file=sys.stderr)
                    return 1
    except ParameterValueError as error:
        print(f"pipeline: error: {error}", file=sys.stderr)
        return 2
    except (KeyboardInterrupt, ExternalShutdownException):
        print("pipeline: interrupted", file=sys.stderr)
    finally:
        for child in children:
            if child.poll() is None:
                child.send_signal(signal.SIGINT)
        for child in children:
            try:
                child.wait(timeout=10)
            except subprocess.TimeoutExpired:
                child.kill()
        if executor is not None:
            executor.shutdown()
        for node in nodes:
            node.destroy_node()
        rclpy.try_shutdown()
    view.flush()
    print(view.summary(), flush=True)
    return 0 if view.tally else 1


def main(argv=None) -> int:
    """`ros2 run backlash_monitor pipeline [options]` (ROS arguments are passed through)."""
    from rclpy.utilities import remove_ros_args
    from backlash_monitor.errors import UsageError
    parser = argparse.ArgumentParser(prog="pipeline", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    add_arguments(parser)
    args = parser.parse_args(remove_ros_args(sys.argv if argv is None else argv)[1:])
    try:
        return run(args)
    except UsageError as error:
        print(f"pipeline: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
