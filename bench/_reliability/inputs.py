"""A table of named bad inputs (chunks, windows, messages, configs, command lines), each tried once.

``run() -> dict``: bad_inputs_tried, escapes, details. An *escape* is a traceback (an exception
out of a core or a callback, or "Traceback" in a command's output), a crash (a non-zero exit that is
not the documented exit 2 with one line), a hang (a command past its time limit), a wrong or
non-finite estimate (a published width that is not a candidate, a B vector with a non-finite or
negative entry, a window of the wrong length or with non-finite samples) or a silent loss (input
dropped without being counted, a stream that stops giving windows after the fault, an input fault
that leaves /diagnostics OK or turns it to ERROR).
"""
from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import tempfile
import traceback
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
for extra in (REPO, REPO / "test"):
    if str(extra) not in sys.path:
        sys.path.insert(0, str(extra))

import fuzz_cores as fc  # noqa: E402

PERIOD_S = 2e-5


class Escape(Exception):
    """The input got through: what kind (traceback, crash, hang, wrong estimate, silent loss)."""

    def __init__(self, kind: str, detail: str):
        super().__init__(f"{kind}: {detail}")
        self.kind = kind


def _valid_estimates(estimates, widths):
    for e in estimates:
        b = np.asarray(e.b_vector, dtype=float)
        if not (np.isfinite(b).all() and (b >= 0).all() and b.size == 6):
            raise Escape("non-finite estimate", f"B = {b}")
        if not (np.isclose(widths, e.width_m).any() and np.isclose(widths, e.fused_width_m).any()):
            raise Escape("wrong estimate", f"width {e.width_m} not a candidate")


# ---------------------------------------------------------------- chunks (the windowing cores)
def _chunk_case(fault, at=6):
    def run():
        windows, stage, _, clean_from = fc.run_stream([1000] * 30, {at: fault}, fc.SIGNALS)
        for w, _ in windows:
            for s in ("a1", "a2"):
                if w.signals[s].shape != (fc.WINDOW_LENGTH,) or not np.isfinite(w.signals[s]).all():
                    raise Escape("wrong estimate", f"window {w.entry_sample_index} malformed")
        if fault not in ("period_other",) and stage.faults.total == 0:
            raise Escape("silent loss", "fault not counted")
        if not [w for w, lo in windows if lo >= clean_from]:
            raise Escape("silent loss", f"no window after the fault ({dict(stage.faults.counts)})")
        return dict(stage.faults.counts)
    return run


def _chunk_cases():
    cases = {f"chunk: {fault}": _chunk_case(fault) for fault in fc.FAULTS if fault != "none"}
    cases["chunk: two faults in a row (nan, then restart)"] = lambda: _two_faults()
    cases["chunk: restart 3000 samples back (not at 0)"] = lambda: _small_restart()
    cases["chunk: samples are not numbers"] = lambda: _not_numbers()
    cases["chunk: 2-D samples"] = lambda: _two_d()
    return cases


def _two_faults():
    windows, stage, _, clean_from = fc.run_stream([1000] * 30, {5: "nan", 6: "restart"}, fc.SIGNALS)
    if not [w for w, lo in windows if lo >= clean_from] or stage.faults.total < 2:
        raise Escape("silent loss", str(stage.faults.counts))
    return dict(stage.faults.counts)


def _small_restart():
    from backlash_monitor.chain.joiner import ChunkJoiner
    from backlash_monitor.chain.stage import WindowingStage
    data, _ = fc.synthetic_stream()
    stage = WindowingStage()
    joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
    windows = []
    for lo in range(0, data["a1"].size, 1000):
        first = lo if lo < 8000 else lo - 3000
        for s in fc.SIGNALS:
            j = joiner.add(s, first, PERIOD_S, data[s][lo:lo + 1000])
            if j is not None:
                windows += stage.feed(j)[0]
    if stage.faults.counts["out_of_order"] != 3 or not windows:
        raise Escape("silent loss", str(stage.faults.counts))
    return dict(stage.faults.counts)


def _not_numbers():
    from backlash_monitor.chain.joiner import ChunkJoiner
    from backlash_monitor.chain.stage import WindowingStage
    stage = WindowingStage()
    joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
    joiner.add("a1", 0, PERIOD_S, ["x"] * 10)
    joiner.add("a2", 0, PERIOD_S, np.zeros(10))
    stage.feed(joiner.add("angle_difference", 0, PERIOD_S, np.zeros(10)))
    if not stage.faults.total:
        raise Escape("silent loss", "not counted")
    return dict(stage.faults.counts)


def _two_d():
    from backlash_monitor.chain.joiner import ChunkJoiner
    from backlash_monitor.chain.stage import WindowingStage
    stage = WindowingStage()
    joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
    for s in stage.input_signals:
        j = joiner.add(s, 0, PERIOD_S, np.zeros((2, 10)))
    stage.feed(j)
    if not stage.faults.counts["bad_shape"]:
        raise Escape("silent loss", str(stage.faults.counts))
    return dict(stage.faults.counts)


# ---------------------------------------------------------------- windows (denoise, estimator)
def _window_cases():
    g1, g2 = fc.good_window()
    n = fc.WINDOW_LENGTH

    def nan_at(x, k=100, v=np.nan):
        y = np.array(x, dtype=float)
        y[k] = v
        return y
    windows = {
        "window: one NaN sample": (nan_at(g1), g2, "onset", PERIOD_S),
        "window: one +inf sample": (g1, nan_at(g2, 7, np.inf), "onset", PERIOD_S),
        "window: all NaN": (np.full(n, np.nan), np.full(n, np.nan), "onset", PERIOD_S),
        "window: 2047 samples": (g1[:-1], g2[:-1], "onset", PERIOD_S),
        "window: 4096 samples": (np.tile(g1, 2), np.tile(g2, 2), "onset", PERIOD_S),
        "window: a1 and a2 of unequal length": (g1, g2[:1000], "onset", PERIOD_S),
        "window: empty": (np.zeros(0), np.zeros(0), "onset", PERIOD_S),
        "window: sample period 1e-5 (not the library's)": (g1, g2, "onset", 1e-5),
        "window: sample period 0": (g1, g2, "onset", 0.0),
        "window: sample period NaN": (g1, g2, "onset", float("nan")),
        "window: entry kind ''": (g1, g2, "", PERIOD_S),
        "window: entry kind 'garbage'": (g1, g2, "garbage", PERIOD_S),
        "window: values 1e300": (np.full(n, 1e300), np.full(n, -1e300), "onset", PERIOD_S),
        "window: all zeros": (np.zeros(n), np.zeros(n), "onset", PERIOD_S),
        "window: denormal values": (np.full(n, 5e-324), np.full(n, 5e-324), "onset", PERIOD_S),
    }
    estimators = {}

    def case(window):
        def run():
            from backlash_monitor.denoise import denoise_checked
            clean, reason = denoise_checked(window[0], window[1])
            if clean is not None and not (np.isfinite(clean[0]).all() and np.isfinite(clean[1]).all()):
                raise Escape("non-finite estimate", "denoised window not finite")
            out = {"denoise": reason or "ok"}
            for mode in ("shape", "paper"):
                if mode not in estimators:
                    estimators[mode] = fc.make_estimator(mode)
                est = estimators[mode]
                widths = est.widths_m
                estimates = est.estimate(*window)
                _valid_estimates(estimates, widths)
                reason = est.last_reasons[0]
                if reason is None and window[2] == "onset" and not estimates:
                    raise Escape("silent loss", "onset window neither classified nor rejected")
                good = est.estimate(g1, g2, "onset", PERIOD_S)       # the next good window
                if len(good) != len(est.signals):
                    raise Escape("silent loss", "the good window after it was not classified")
                _valid_estimates(good, widths)
                out[mode] = reason or "classified"
            return out
        return run
    return {name: case(w) for name, w in windows.items()}


# ---------------------------------------------------------------- messages (node callbacks)
class _Sink:
    def __init__(self):
        self.messages = []

    def publish(self, msg):
        self.messages.append(msg)


def _message_cases():
    cases = {}

    def node_of(kind):
        from rclpy.parameter import Parameter
        if kind == "windowing":
            from backlash_monitor.nodes.windowing import WindowingNode as N
            node = N()
        elif kind == "denoise":
            from backlash_monitor.nodes.denoise import DenoiseNode as N
            node = N()
        else:
            from backlash_monitor.nodes.classifier import ClassifierNode as N
            node = N(parameter_overrides=[Parameter("warn_width_m", value=1.0),
                                          Parameter("error_width_m", value=1.0)])
        node.publisher = _Sink()
        node.diagnostics.publisher = _Sink()
        return node

    def check_diag(node, want_warn=True):
        from diagnostic_msgs.msg import DiagnosticStatus
        levels = [m.status[0].level for m in node.diagnostics.publisher.messages]
        if DiagnosticStatus.ERROR in levels:
            raise Escape("silent loss", "a bad input turned the status to ERROR")
        if want_warn and DiagnosticStatus.WARN not in levels:
            raise Escape("silent loss", "a bad input left /diagnostics without WARN")
        return node.diagnostics.publisher.messages[-1].status[0].message if levels else ""

    def chunk(name, first, period, samples):
        from backlash_monitor.ros.conversions import to_float64_array
        from backlash_monitor_msgs.msg import SignalChunk
        msg = SignalChunk(signal_name=name, sample_period_s=float(period), first_sample_index=int(first))
        msg.samples = to_float64_array(samples)
        return msg

    def windowing(mutate):
        def run():
            node = node_of("windowing")
            try:
                data, _ = fc.synthetic_stream()
                before_tail = 0
                for lo in range(0, data["a1"].size, 1000):
                    if lo == 14000:     # the fault is at 5000: the tail from here is clean
                        before_tail = len(node.publisher.messages)
                    for s in fc.SIGNALS:
                        first, period, x = mutate(lo, s, lo, PERIOD_S, data[s][lo:lo + 1000].copy())
                        node.on_chunk(s, chunk(s, first, period, x))
                for w in node.publisher.messages:
                    if len(w.a1) != fc.WINDOW_LENGTH or not np.isfinite(w.a1).all():
                        raise Escape("wrong estimate", "malformed window published")
                if len(node.publisher.messages) <= before_tail:
                    raise Escape("silent loss", "no windows after the fault")
                return check_diag(node)
            finally:
                node.destroy_node()
        return run

    def at(k, fn):
        return lambda lo, s, first, period, x: fn(s, first, period, x) if lo == k * 1000 else (first, period, x)

    def nan_angle(s, f, p, x):
        if s == "angle_difference":
            x[:] = np.nan
        return f, p, x
    cases["message: windowing, a chunk of NaN angle samples"] = windowing(at(5, nan_angle))
    cases["message: windowing, index 2**64-1"] = windowing(at(5, lambda s, f, p, x: (2 ** 64 - 1, p, x)))
    cases["message: windowing, period NaN"] = windowing(at(5, lambda s, f, p, x: (f, float("nan"), x)))
    cases["message: windowing, period -2e-5"] = windowing(at(5, lambda s, f, p, x: (f, -p, x)))
    cases["message: windowing, empty samples"] = windowing(at(5, lambda s, f, p, x: (f, p, x[:0])))
    cases["message: windowing, a1 shorter than a2"] = windowing(
        at(5, lambda s, f, p, x: (f, p, x[:-10] if s == "a1" else x)))
    cases["message: windowing, index jump 10**12 ahead"] = windowing(
        lambda lo, s, f, p, x: (f + 10 ** 12 if lo >= 5000 else f, p, x))
    cases["message: windowing, index restarts at 0 (drive restart)"] = windowing(
        lambda lo, s, f, p, x: (f - 5000 if lo >= 5000 else f, p, x))

    def window_msg(a1, a2, kind="onset", period=PERIOD_S, denoised=True, index=0):
        from backlash_monitor.denoise import denoising_label
        from backlash_monitor.ros.conversions import to_float64_array
        from backlash_monitor_msgs.msg import BacklashWindow
        msg = BacklashWindow(entry_sample_index=index, entry_kind=kind, trigger="contact_loss",
                             sample_period_s=period, true_width_m=float("nan"),
                             denoising=denoising_label(6, (1, 2, 3, 4, 5, 6), "symmetric") if denoised else "",
                             # the windowing node's sensor offset estimate (none: not classified)
                             a1_offset_m_s2=0.0, a2_offset_m_s2=0.0, offset_periods=8)
        msg.a1, msg.a2 = to_float64_array(a1), to_float64_array(a2)
        return msg

    g1, g2 = fc.good_window()
    bad_windows = {
        "NaN sample": dict(a1=np.where(np.arange(2048) == 9, np.nan, g1), a2=g2),
        "a1 and a2 of unequal length": dict(a1=g1, a2=g2[:100]),
        "10 samples": dict(a1=g1[:10], a2=g2[:10]),
        "2047 samples": dict(a1=g1[:-1], a2=g2[:-1]),
        "sample period 1e-5": dict(a1=g1, a2=g2, period=1e-5),
        "entry kind 'x'": dict(a1=g1, a2=g2, kind="x"),
        "not denoised": dict(a1=g1, a2=g2, denoised=False),
    }

    def node_window(kind, fields):
        def run():
            node = node_of(kind)
            try:
                node.on_window(window_msg(**fields))
                node.on_window(window_msg(g1, g2, index=99))        # the next good window
                published = node.publisher.messages
                if kind == "denoise":
                    if any(not np.isfinite(m.a1).all() or len(m.a1) != len(m.a2) for m in published):
                        raise Escape("non-finite estimate", "bad window published")
                    if not published or published[-1].entry_sample_index != 99:
                        raise Escape("silent loss", "the good window was not denoised")
                    if fields.get("denoised", True) is False or fields.get("kind") == "x" \
                            or fields.get("period") or len(fields["a1"]) == 2047:
                        return check_diag(node, want_warn=False)   # not the denoise node's concern
                else:
                    estimates = [m for m in published]
                    widths = node.estimator.widths_m
                    _valid_estimates(estimates, widths)
                    if [m.entry_sample_index for m in estimates] != [99, 99, 99]:
                        raise Escape("wrong estimate", "the bad window gave estimates, or the good none")
                return check_diag(node)
            finally:
                node.destroy_node()
        return run
    for kind in ("denoise", "classifier"):
        for name, fields in bad_windows.items():
            cases[f"message: {kind}, window {name}"] = node_window(kind, fields)
    return cases


# ---------------------------------------------------------------- configs
def _config_cases(tmp: Path):
    from backlash_monitor.ros.params_file import check_params_file
    from backlash_monitor.windowing import load_windowing_config

    def expect_one_line(loader, text, *needles):
        def run():
            path = tmp / f"cfg{abs(hash(text)) % 10 ** 8}.yaml"
            if text is not None:
                path.write_text(text)
            try:
                loader(path)
            except ValueError as error:
                message = str(error)
                if "\n" in message or not all(n in message for n in needles):
                    raise Escape("silent loss", f"unclear message: {message!r}")
                return message
            raise Escape("silent loss", "accepted")
        return run
    w = load_windowing_config
    p = check_params_file
    return {
        "config: windowing.yaml unknown key": expect_one_line(w, "detector:\n  confirm_radd: 1\n", "confirm_radd", "confirm_rad'"),
        "config: windowing.yaml unknown section": expect_one_line(w, "captur:\n  window_length: 1\n", "captur", "capture"),
        "config: windowing.yaml unknown field": expect_one_line(w, "capture:\n  window_length: {value: 1, unti: x}\n", "unti", "unit"),
        "config: windowing.yaml broken YAML": expect_one_line(w, "detector:\n  confirm_rad: [1\n", ":3:", "broken YAML"),
        "config: windowing.yaml a list": expect_one_line(w, "- 1\n- 2\n", "mapping"),
        "config: windowing.yaml missing": expect_one_line(w, None, "cannot be read"),
        "config: params file misspelled key": expect_one_line(p, "/**:\n  ros__parameters:\n    warn_widht_m: 0.1\n", "warn_widht_m", "warn_width_m"),
        "config: params file key of another node": expect_one_line(p, "/**/denoise:\n  ros__parameters:\n    mode: shape\n    fusion_events: 3\n", "fusion_events", "denoise"),
        "config: params file unknown node": expect_one_line(p, "/**/clasifier:\n  ros__parameters:\n    mode: shape\n", "clasifier", "classifier"),
        "config: params file broken YAML": expect_one_line(p, "/**:\n  ros__parameters:\n    mode: 'shape\n", "broken YAML", "line 3"),
        "config: params file without ros__parameters": expect_one_line(p, "/**:\n  ros_parameters:\n    mode: shape\n", "ros__parameters"),
        "config: params file a list": expect_one_line(p, "- 1\n", "mapping"),
        "config: params file missing": expect_one_line(p, None, "cannot be read"),
        "config: params file tab indentation": expect_one_line(p, "/**:\n\tros__parameters: {}\n", "broken YAML"),
    }


# ---------------------------------------------------------------- command lines
def _run_cli(argv, env, timeout=240):
    try:
        proc = subprocess.run(argv, capture_output=True, text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        raise Escape("hang", " ".join(map(str, argv[-3:]))) from None
    text = proc.stdout + proc.stderr
    if "Traceback" in text:
        raise Escape("traceback", text.strip().splitlines()[-1])
    if proc.returncode not in (0, 2):
        raise Escape("crash", f"exit {proc.returncode}")
    if proc.returncode == 2 and len([line for line in proc.stderr.splitlines() if line.strip()]) != 1:
        raise Escape("crash", f"exit 2 without one clear line: {proc.stderr!r}")
    return proc


def _write_bag(path: Path, mutate):
    from backlash_monitor.bag import SIGNAL_CHUNK, BagWriter, Codec
    from backlash_monitor.signals import SIGNAL_UNITS
    codec = Codec.for_type(SIGNAL_CHUNK)
    data, _ = fc.synthetic_stream()
    t0 = 1_763_000_000_000_000_000
    with BagWriter(path) as writer:
        for s in fc.SIGNALS:
            writer.add_topic(f"/plant/{s}", SIGNAL_CHUNK)
        for lo in range(0, data["a1"].size, 1000):
            for s in fc.SIGNALS:
                first, period, x = mutate(lo, s, lo, PERIOD_S, data[s][lo:lo + 1000].copy())
                t = t0 + lo * 20_000
                msg = codec.new(header=codec.new("std_msgs/msg/Header",
                                                 stamp=codec.new("builtin_interfaces/msg/Time",
                                                                 sec=t // 10 ** 9, nanosec=t % 10 ** 9),
                                                 frame_id="drive"),
                                signal_name=s, unit=SIGNAL_UNITS[s], sample_period_s=period,
                                first_sample_index=first, samples=x)
                writer.write(f"/plant/{s}", msg, log_time_ns=t)


def _cli_cases(tmp: Path, env):
    def analyze(name, mutate, extra=(), want_faults=True):
        def run():
            bag = tmp / f"{name}.mcap"
            _write_bag(bag, mutate)
            out = tmp / f"{name}.estimates"
            proc = _run_cli([sys.executable, "-m", "backlash_monitor", "analyze", str(bag), "--out",
                             str(out), "--overwrite", *extra], env)
            if proc.returncode == 2:
                return proc.stderr.strip()
            result = json.loads(Path(f"{out}.json").read_text())
            for row in result["estimates"]:
                if not (np.isfinite(row["b_vector"]).all() and min(row["b_vector"]) >= 0
                        and np.isclose(row["candidate_widths_m"], row["width_m"]).any()):
                    raise Escape("non-finite estimate", f"row {row['entry_sample_index']}")
            if want_faults and not result.get("input_faults"):
                raise Escape("silent loss", "analyze did not report the dropped input")
            return result.get("input_faults")
        return run

    def at(k, fn):
        return lambda lo, s, first, period, x: fn(s, first, period, x) if lo == k * 1000 else (first, period, x)

    def nan_a1(s, f, p, x):
        if s == "a1":
            x[3] = np.nan
        return f, p, x
    return {
        "command: analyze, a NaN sample": analyze("nan", at(4, nan_a1)),
        "command: analyze, sample period 0": analyze("period0", at(4, lambda s, f, p, x: (f, 0.0, x))),
        "command: analyze, sample period NaN": analyze("periodnan", at(4, lambda s, f, p, x: (f, float("nan"), x))),
        "command: analyze, a1 and a2 chunks of unequal length": analyze(
            "lengths", at(4, lambda s, f, p, x: (f, p, x[:500] if s == "a1" else x))),
        "command: analyze, index restarts at 0": analyze(
            "restart", lambda lo, s, f, p, x: (f - 8000 if lo >= 8000 else f, p, x)),
        "command: analyze, recorded at 100 kHz (not the library's rate)": analyze(
            "rate", lambda lo, s, f, p, x: (f, 1e-5, x)),
        "command: analyze --window-offset -5": analyze("offset", lambda lo, s, f, p, x: (f, p, x),
                                                       ("--window-offset", "-5")),
        "command: analyze --fusion-events 0": analyze("fusion", lambda lo, s, f, p, x: (f, p, x),
                                                      ("--fusion-events", "0")),
        "command: classifier node with a misspelled params file key": lambda: _node_cli(
            tmp, env, "/**:\n  ros__parameters:\n    warn_widht_m: 0.1\n"),
        "command: classifier node with broken params YAML": lambda: _node_cli(
            tmp, env, "/**:\n  ros__parameters:\n    mode: [shape\n"),
    }


def _node_cli(tmp, env, text):
    path = tmp / f"params{abs(hash(text)) % 10 ** 8}.yaml"
    path.write_text(text)
    proc = _run_cli([sys.executable, "-m", "backlash_monitor.nodes.classifier", "--ros-args",
                     "--params-file", str(path)], env, timeout=60)
    if proc.returncode != 2:
        raise Escape("silent loss", "the node started with a bad parameters file")
    return proc.stderr.strip()


# ---------------------------------------------------------------- run
def run() -> dict:
    import rclpy
    env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST")
    results = []
    with tempfile.TemporaryDirectory(prefix="reliability_inputs_") as tmp:
        tmp = Path(tmp)
        rclpy.init()
        try:
            cases = {**_chunk_cases(), **_window_cases(), **_message_cases(), **_config_cases(tmp),
                     **_cli_cases(tmp, env)}
            every = every_command(tmp / "every_command", env) if parts_wanted("every") else []
            if not parts_wanted("table"):
                cases = {}
            for name, case in cases.items():
                try:
                    outcome, escape = case(), None
                except Escape as error:
                    outcome, escape = str(error), error.kind
                except Exception as error:  # noqa: BLE001 - an exception out of a core is an escape
                    outcome = "".join(traceback.format_exception_only(type(error), error)).strip()
                    escape = "traceback"
                results.append({"name": name, "category": name.split(":")[0],
                                "escape": escape, "outcome": _short(outcome)})
                print(f"{'ESCAPE ' + escape if escape else 'ok':>22}  {name}", file=sys.stderr)
        finally:
            rclpy.try_shutdown()
    results += every
    return {"bad_inputs_tried": len(results),
            "escapes": sum(r["escape"] is not None for r in results),
            "command_bad_inputs": len(every),
            "command_tracebacks": sum(r["escape"] == "traceback" for r in every),
            "command_internal_names": sum(r["escape"] == "internal name" for r in every),
            "command_other_escapes": sum(r["escape"] not in (None, "traceback", "internal name") for r in every),
            "details": {"inputs": results}}


def parts_wanted(part: str) -> bool:
    """RELIABILITY_INPUTS=every: only every command's bad command lines (bench/reliability.py --modules inputs
    --inputs every); =table: only the named table; unset: both."""
    wanted = os.environ.get("RELIABILITY_INPUTS", "")
    return not wanted or wanted == part


def _short(outcome) -> str:
    text = outcome if isinstance(outcome, str) else json.dumps(outcome, default=str)
    return text if len(text) < 300 else text[:297] + "..."


# ---------------------------------------------------------------- every command's bad inputs (issue 33)
# One error policy (docs/cli.md): exit 2 for bad input, 1 for a failure while running (a truncated bag), the last
# stderr line "python -m backlash_monitor <command>: error: ...", never a traceback, never an internal name.
INTERNAL_NAMES = re.compile(r"Traceback|NoneType|object has no attribute|\b[A-Z]\w+Error\b|\b[A-Z]\w+\([a-z_]+="
                            r"|\bbacklash_monitor\.[a-z_]+\.|\bself\.|<class |<function |0x[0-9a-f]{6,}")


def _command_fixtures(tmp: Path) -> dict:
    intact = tmp / "intact.mcap"
    _write_bag(intact, lambda lo, s, first, period, x: (first, period, x))
    truncated = tmp / "truncated.mcap"
    data = intact.read_bytes()
    truncated.write_bytes(data[:len(data) * 2 // 3])
    (tmp / "notabag.txt").write_text("not a bag\n")
    (tmp / "syntax_error.py").write_text("def broken(:\n")
    (tmp / "bad_model.yaml").write_text("workbench_model: [1\n")
    (tmp / "garbage.json").write_text("{\"verdict\": 3}\n")
    (tmp / "empty_dir").mkdir()
    (tmp / "exists.yaml").write_text("x: 1\n")
    return {"intact": str(intact), "truncated": str(truncated), "notabag": str(tmp / "notabag.txt"),
            "syntax": str(tmp / "syntax_error.py"), "bad_model": str(tmp / "bad_model.yaml"),
            "garbage_json": str(tmp / "garbage.json"), "empty_dir": str(tmp / "empty_dir"),
            "missing": str(tmp / "missing.mcap"), "nodir": str(tmp / "no_such_folder" / "out"),
            "exists": str(tmp / "exists.yaml"), "out": str(tmp / "out")}


# (name, argv after `python -m backlash_monitor`, exit code the policy wants)
EVERY_COMMAND = [
    ("no command", [], 2),
    ("unknown command", ["frobnicate"], 2),
    ("simulate --widths abc", ["simulate", "--widths", "abc"], 2),
    ("simulate --widths 0", ["simulate", "--widths", "0", "--no-progress"], 2),
    ("simulate --duration 0", ["simulate", "--duration", "0"], 2),
    ("simulate --duration 1e9", ["simulate", "--duration", "1e9"], 2),
    ("simulate -o into a missing folder", ["simulate", "-o", "{nodir}.npz", "--duration", "0.01"], 2),
    ("simulate --set unknown key", ["simulate", "--set", "nosuch.key=1"], 2),
    ("simulate --set unknown effect", ["simulate", "--set", "effects.nosuch=true"], 2),
    ("simulate --effects-file not Python", ["simulate", "--effects-file", "{notabag}"], 2),
    ("simulate --effects-file missing", ["simulate", "--effects-file", "{missing}.py"], 2),
    ("simulate --effects-file with a syntax error", ["simulate", "--effects-file", "{syntax}"], 2),
    ("simulate --config missing", ["simulate", "--config", "{missing}.yaml"], 2),
    ("simulate --noise-seed -1", ["simulate", "--noise-seed", "-1"], 2),
    ("simulate --no-npz without --mcap", ["simulate", "--no-npz"], 2),
    ("simulate --seeds -1", ["simulate", "--seeds", "-1"], 2),
    ("pipeline --width-m 0.2", ["pipeline", "--width-m", "0.2"], 2),
    ("pipeline --rate-factor 0", ["pipeline", "--rate-factor", "0"], 2),
    ("pipeline --duration -1", ["pipeline", "--duration", "-1"], 2),
    ("pipeline --restart without --processes", ["pipeline", "--restart", "on-failure"], 2),
    ("pipeline --library missing", ["pipeline", "--library", "{missing}.npz"], 2),
    ("pipeline --record into a missing folder", ["pipeline", "--record", "{nodir}.mcap"], 2),
    ("pipeline --set-at garbage", ["pipeline", "--set-at", "soon", "x=1"], 2),
    ("pipeline --model without --watch", ["pipeline", "--model", "{exists}"], 2),
    ("pipeline --effects-file not Python", ["pipeline", "--effects-file", "{notabag}"], 2),
    ("fleet --drives 0", ["fleet", "--drives", "0"], 2),
    ("fleet --config missing", ["fleet", "--config", "{missing}.yaml"], 2),
    ("fleet --drives and --config", ["fleet", "--drives", "2", "--config", "config/fleet.yaml"], 2),
    ("fleet --rate-factor 0", ["fleet", "--rate-factor", "0"], 2),
    ("fleet --json into a missing folder", ["fleet", "--drives", "1", "--json", "{nodir}.json"], 2),
    ("record --chunk-size-bytes 1", ["record", "--chunk-size-bytes", "1"], 2),
    ("record --compression brotli", ["record", "--compression", "brotli"], 2),
    ("record --output into a missing folder", ["record", "--output", "{nodir}.mcap"], 2),
    ("record --duration -1", ["record", "--duration", "-1"], 2),
    ("replay without a bag", ["replay"], 2),
    ("replay of a missing file", ["replay", "{missing}"], 2),
    ("replay of a text file", ["replay", "{notabag}"], 2),
    ("replay --rate-factor -1", ["replay", "{intact}", "--rate-factor", "-1"], 2),
    ("replay of a truncated bag", ["replay", "{truncated}", "--rate-factor", "0"], 1),
    ("bag-info of a missing file", ["bag-info", "{missing}"], 2),
    ("bag-info of a text file", ["bag-info", "{notabag}"], 2),
    ("bag-info of an empty folder", ["bag-info", "{empty_dir}"], 2),
    ("bag-info of a truncated bag", ["bag-info", "{truncated}"], 1),
    ("bag-info --topic not in the bag", ["bag-info", "{intact}", "--topic", "/nope"], 2),
    ("analyze of a missing file", ["analyze", "{missing}"], 2),
    ("analyze of a text file", ["analyze", "{notabag}", "--out", "{out}"], 2),
    ("analyze of a truncated bag", ["analyze", "{truncated}", "--out", "{out}"], 1),
    ("analyze --fusion-events 0", ["analyze", "{intact}", "--fusion-events", "0", "--out", "{out}"], 2),
    ("analyze --trigger paper without a width", ["analyze", "{intact}", "--trigger", "paper", "--out", "{out}"], 2),
    ("analyze --library a text file", ["analyze", "{intact}", "--library", "{notabag}", "--out", "{out}"], 2),
    ("analyze --out into a missing folder", ["analyze", "{intact}", "--out", "{nodir}"], 2),
    ("analyze an empty folder", ["analyze", "{empty_dir}"], 2),
    ("analyze --out-dir with one bag", ["analyze", "{intact}", "--out-dir", "{out}"], 2),
    ("train --epochs 0", ["train", "--epochs", "0"], 2),
    ("train --l1 2", ["train", "--l1", "2"], 2),
    ("train --output not .npz", ["train", "--output", "{out}.txt"], 2),
    ("train --model missing", ["train", "--model", "{missing}.yaml", "-o", "{out}.npz"], 2),
    ("train --seeds a,b", ["train", "--seeds", "a,b"], 2),
    ("train --duration 100", ["train", "--duration", "100"], 2),
    ("evaluate --fusion-events 9", ["evaluate", "--fusion-events", "9"], 2),
    ("evaluate --library without a trigger", ["evaluate", "--library", "{notabag}"], 2),
    ("evaluate --library missing", ["evaluate", "--library", "paper={missing}.npz", "--out-dir", "{out}"], 2),
    ("compare of a missing recording", ["compare", "{missing}"], 2),
    ("compare of a text file", ["compare", "{notabag}"], 2),
    ("compare --ensemble 2", ["compare", "{intact}", "--ensemble", "2"], 2),
    ("compare --model missing", ["compare", "{intact}", "--model", "{missing}.yaml"], 2),
    ("compare --model broken YAML", ["compare", "{intact}", "--model", "{bad_model}"], 2),
    ("compare --effects-file not Python", ["compare", "{intact}", "--effects-file", "{notabag}"], 2),
    ("compare --width-m 0.2", ["compare", "{intact}", "--width-m", "0.2"], 2),
    ("diagnose --candidates unknown", ["diagnose", "{intact}", "--candidates", "nosuch", "--json", "{out}.json"], 2),
    ("diagnose --effects-file not Python", ["diagnose", "{intact}", "--effects-file", "{notabag}",
                                            "--json", "{out}.json"], 2),
    ("diagnose --json into a missing folder", ["diagnose", "{intact}", "--json", "{nodir}.json"], 2),
    ("diagnose of a truncated bag", ["diagnose", "{truncated}", "--json", "{out}.json"], 1),
    ("add-effect of a missing diagnosis", ["add-effect", "{missing}.json", "-o", "{out}.yaml"], 2),
    ("add-effect of a garbage JSON", ["add-effect", "{garbage_json}", "-o", "{out}.yaml"], 2),
    ("add-effect of an unknown effect", ["add-effect", "nosuch_effect", "-o", "{out}.yaml"], 2),
    ("add-effect --value unknown parameter", ["add-effect", "wheel_coulomb_friction", "--value", "bad=1",
                                              "-o", "{out}.yaml"], 2),
    ("add-effect -o existing", ["add-effect", "wheel_coulomb_friction", "-o", "{exists}"], 2),
    ("record with no publishers", ["record", "--output", "{out}.mcap", "--duration", "0.5"], 1),
    ("history of a missing folder", ["history", "{nodir}"], 2),
    ("history of a folder without history", ["history", "{empty_dir}"], 2),
    ("watch-reference --ensemble 2", ["watch-reference", "--ensemble", "2", "-o", "{out}.watch.npz"], 2),
    ("watch-reference --output not .npz", ["watch-reference", "--output", "{out}.txt"], 2),
    ("watch-reference --model missing", ["watch-reference", "--model", "{missing}.yaml"], 2),
]


def every_command(tmp: Path, env, cases=EVERY_COMMAND) -> list[dict]:
    """Each bad command line once: its exit code, last stderr line, and what escaped (a traceback, an internal
    name, another exit code than the policy's, no one-line error)."""
    tmp.mkdir(parents=True, exist_ok=True)
    fx = _command_fixtures(tmp)
    rows = []
    for name, argv, want in cases:
        argv = [a.format(**fx) for a in argv]
        try:
            proc = subprocess.run([sys.executable, "-m", "backlash_monitor", *argv], capture_output=True,
                                  text=True, timeout=120, env=env, cwd=REPO)
            rc, text, err = proc.returncode, proc.stdout + proc.stderr, proc.stderr
        except subprocess.TimeoutExpired:
            rc, text, err = None, "", ""
        lines = [ln for ln in err.splitlines() if ln.strip()]
        last = lines[-1] if lines else ""
        escape = None
        if rc is None:
            escape = "hang"
        elif "Traceback" in text:
            escape = "traceback"
        elif INTERNAL_NAMES.search(err):
            escape = "internal name"
        elif rc != want:
            escape = f"exit {rc}, wanted {want}"
        elif not re.match(r"python -m backlash_monitor( [a-z-]+)?: (error|warning): ", last) and not (
                rc == 1 and ": error: " in last or rc == 1 and "ERROR" in last):
            escape = "no one-line error"
        rows.append({"name": f"every command: {name}", "category": "every command", "escape": escape,
                     "outcome": f"exit {rc}: {_short(last)}"})
        print(f"{'ESCAPE ' + escape if escape else 'ok':>22}  {name}: exit {rc}: {last[:150]}", file=sys.stderr)
    return rows
