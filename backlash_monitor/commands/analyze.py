"""`python -m backlash_monitor analyze BAG`: the signal chain offline, without DDS.

Reads the drive's SignalChunk topics (plant/a1, plant/a2, plant/angle_difference — or
plant/omega1/omega2 with --angle-source integrated) in the order they were recorded, runs the same
stages as the live graph (backlash_monitor.chain: join, detect entries, capture, denoise, classify,
fuse) and writes the estimates to OUT.csv, OUT.json and OUT.mcap (topic `estimate`, the live
pipeline's message type). Given the same recorded chunks, the estimates equal the live pipeline's.

The accelerometers' constant offsets are estimated over whole load periods and removed before the
classifier, as live (docs/windowing.md "Sensor offsets"): each estimate row has the offsets its
window was read with, OUT.json's "sensor_offsets" the drive's latest estimate, and an offset beyond
the plausible range (config/windowing.yaml sensor_offset.plausible_abs_m_s2) is printed as a WARN.

A damaged bag (a chunk whose length field or CRC is bad, a missing summary) is an error naming the
damage; with --recover every intact chunk is analysed and OUT.json's "bag_integrity" lists what was
skipped (chunks, log-time ranges, messages). A bag sampled at another rate than the pattern library
was trained at, or whose topics carry other signals than their names say, is refused. Chunks with
a sample period that is not a positive number, and ranges whose signals' chunks differ in length,
are discarded and counted ("discarded_chunks").
"""
from __future__ import annotations

import csv
import json
import math
import pathlib
import time

NAME = "analyze"
HELP = "run the chain offline on an MCAP bag: estimates to CSV, JSON and MCAP"
DESCRIPTION = __doc__

ESTIMATE_BATCH = 64   # onset windows per batched denoise + DriveEstimator.estimate_many call

CSV_COLUMNS = ("entry_sample_index", "entry_time_s", "signal", "mode", "width_m", "width_index",
               "b_margin", "continuous_width_m", "fused_width_m", "fused_events", "true_width_m",
               "b_vector", "fused_continuous_width_m", "a1_offset_m_s2", "a2_offset_m_s2",
               "offset_periods")


def add_arguments(parser) -> None:
    parser.add_argument("bag", help="MCAP file recorded from a drive (or by `simulate --mcap`); "
                                    "a folder or a quoted glob of them: every bag in parallel, "
                                    "into one fleet table (backlash_monitor/fleet/analyze.py)")
    parser.add_argument("--out", default="",
                        help="output prefix (default: the bag's path without .mcap, plus "
                             "'.estimates'): writes PREFIX.csv, PREFIX.json, PREFIX.mcap")
    parser.add_argument("--namespace", default="",
                        help="namespace of the drive's topics in the bag (e.g. /line1/drive7)")
    parser.add_argument("--trigger", choices=("contact_loss", "paper"), default="contact_loss",
                        help="entry trigger (the library must be trained with it)")
    parser.add_argument("--width-m", type=float, default=0.0,
                        help="backlash width for the 'paper' trigger [m] (eq. 1)")
    parser.add_argument("--window-offset", type=int, default=None, metavar="SAMPLES",
                        help="samples from the detected entry to the window start (default: the "
                             "trigger's configured value, config/windowing.yaml; the library must "
                             "have been trained with it)")
    parser.add_argument("--angle-source", choices=("measured", "integrated"), default="measured",
                        help="angle difference from the encoders' topic or integrated speeds")
    parser.add_argument("--mode", default="",
                        help="classifier mode: paper, paper_corrected or shape (default: shape)")
    parser.add_argument("--n1", type=float, default=0.89,
                        help="absorber flow index (the paper modes use this n1's patterns)")
    parser.add_argument("--library", default="", help="pattern library (default: the packaged one)")
    parser.add_argument("--fusion-events", type=int, default=8,
                        help="onset events fused into one estimate")
    parser.add_argument("--recover", action="store_true",
                        help="analyse what is intact of a damaged bag (recorder killed, damaged "
                             "chunks skipped); OUT.json lists what was skipped")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace existing output files (never the analysed bag itself); "
                             "without it an existing output is an error")
    from backlash_monitor.fleet.analyze import add_arguments as add_many_arguments
    add_many_arguments(parser)


def output_paths(out_prefix) -> dict[str, pathlib.Path]:
    """PREFIX.csv, PREFIX.json, PREFIX.mcap: the suffix is appended (a prefix such as
    ``run.estimates`` keeps its dots; ``with_suffix`` would turn it into ``run.mcap``)."""
    prefix = str(out_prefix)
    return {ext: pathlib.Path(f"{prefix}.{ext}") for ext in ("csv", "json", "mcap")}


def _topic(namespace: str, name: str) -> str:
    ns = namespace.strip("/")
    return f"/{ns}/plant/{name}" if ns else f"/plant/{name}"


def _find_topic(available, namespace, name):
    for candidate in (_topic(namespace, name), _topic(namespace, name).lstrip("/")):
        if candidate in available:
            return candidate
    return None


def run(args) -> int:
    from backlash_monitor.fleet.analyze import is_many, run_many
    if is_many(args.bag):
        return run_many(args)
    result = analyze_bag(args)
    _print_summary(result["summary"], result["rows"], result["discarded"], result["n_samples"],
                   result["seconds"], result["outputs"])
    _print_input_problems(result["check"], result["integrity"])
    _print_sensor_offsets(result["sensor_offsets"])
    stage_faults, estimator_faults = result["faults"]
    if stage_faults.total or estimator_faults.total:   # dropped input (docs/windowing.md)
        print(f"input faults: {stage_faults.summary()}; windows rejected: "
              f"{estimator_faults.summary()}; {result['lost_samples']} samples not analysed")
    return 0


def load_bag_library(args):
    """(pattern library, window offset) for these options; UsageError for a bad option or file.
    The fleet's workers load it once and pass it to every :func:`analyze_bag`."""
    from backlash_monitor.commands import UsageError
    from backlash_monitor.classifier.patterns import PatternLibraryError, load_library
    from backlash_monitor.windowing import default_window_offset
    offset = default_window_offset(args.trigger) if args.window_offset is None else args.window_offset
    if not 0 <= offset <= 65536:
        raise UsageError(f"--window-offset = {offset}; allowed: 0 <= SAMPLES <= 65536")
    try:
        return load_library(args.library or None, trigger=args.trigger,
                            window_offset_samples=offset), offset
    except (PatternLibraryError, ValueError) as error:
        raise UsageError(str(error)) from None


def analyze_bag(args, library=None, chunks_ahead: int | None = None) -> dict:
    """One bag through the chain; writes PREFIX.csv/.json/.mcap and returns what `run` prints:
    rows, summary, discarded windows, samples, seconds, outputs, the chunk check, the bag's
    integrity, the faults, and ``drive``/``first_stamp_s`` (the first a1 chunk's frame_id and the
    stamp of its first sample). ``library``: (library, offset) from :func:`load_bag_library`, loaded
    here when None. ``chunks_ahead``: the bag reader's decompression thread (BagReader; None: its
    default; 0: none, for a pool with a worker per core). Raises UsageError (one line) for
    anything wrong with the bag or the options."""
    from backlash_monitor.commands import UsageError
    from backlash_monitor.commands._memory import reuse_freed_memory
    from backlash_monitor.bag import BagError, BagReader
    from backlash_monitor.chain import BlockFeeder, ChunkJoiner, WindowingStage, denoise_pairs
    from backlash_monitor.classifier.patterns import PatternLibraryError
    from backlash_monitor.estimation import DEFAULT_MODE, DriveEstimator
    from backlash_monitor.output_files import OutputError, check_outputs, staged_outputs

    reuse_freed_memory()   # no page fault per freed-and-reallocated array (commands/_memory.py)
    bag_path = pathlib.Path(args.bag)
    if not bag_path.is_file():
        raise UsageError(f"bag {bag_path} does not exist; give the path of an .mcap file")
    if args.trigger == "paper" and not (0 < args.width_m <= 0.05):
        raise UsageError(f"--width-m = {args.width_m:g}: the paper trigger needs the width; "
                         "allowed: 0 < width <= 0.05 m")
    if args.fusion_events < 1:
        raise UsageError(f"--fusion-events = {args.fusion_events}; allowed: 1 or more")
    mode = args.mode or DEFAULT_MODE
    library, offset = library or load_bag_library(args)
    try:
        estimator = DriveEstimator(library, mode=mode, n1=args.n1,
                                   fusion_events=args.fusion_events)
        stage = WindowingStage(trigger=args.trigger,
                               width_m=args.width_m if args.trigger == "paper" else None,
                               angle_source=args.angle_source, window_offset_samples=offset)
    except (PatternLibraryError, ValueError) as error:
        raise UsageError(str(error)) from None
    missing = [name for name in stage.input_signals[:2] if name not in library.signals]
    if missing:
        raise UsageError(f"pattern library {library.path} has no patterns for {', '.join(missing)} "
                         f"(it has {', '.join(library.signals)}); allowed: a library trained on "
                         f"{', '.join(stage.input_signals[:2])}")

    out_prefix = pathlib.Path(args.out) if args.out else bag_path.with_suffix("").with_name(
        bag_path.with_suffix("").name + ".estimates")
    outputs = output_paths(out_prefix)
    try:
        check_outputs(outputs.values(), inputs=[bag_path], overwrite=args.overwrite, option="--out")
    except OutputError as error:
        raise UsageError(str(error)) from None
    started = time.perf_counter()
    rows, estimates_msgs, discarded = [], [], []
    n_samples = 0
    check = ChunkCheck(bag_path, library)
    integrity = None
    try:
        with BagReader(bag_path, recover=args.recover, chunks_ahead=chunks_ahead) as reader:
            available = set(reader.topics)
            topics = {}
            for name in stage.input_signals:
                topic = _find_topic(available, args.namespace, name)
                if topic is None:
                    raise UsageError(
                        f"bag {bag_path} has no topic {_topic(args.namespace, name)}; it has: "
                        f"{', '.join(sorted(available))}")
                topics[topic] = name
            width_topic = _find_topic(available, args.namespace, "true_width_m")
            true_width = math.nan
            if width_topic:
                for m in reader.messages([width_topic]):
                    true_width = float(m.message.data)
            joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
            # contiguous ranges go to the stage in blocks: the same windows as range by range
            feeder = BlockFeeder(stage)
            batch = []   # onset windows, denoised and estimated together (same numbers as one by one)
            last_offsets = ({}, 0)   # the latest window's sensor offset estimate, periods
            first_a1 = ("", math.nan)   # the drive's name and the first sample's time
            for m in _then_none(reader.signal_chunks(list(topics))):
                if m is not None and math.isnan(first_a1[1]) and topics[m.topic] == "a1":
                    first_a1 = (m.frame_id, m.stamp.sec + m.stamp.nanosec * 1e-9
                                - m.first_sample_index * m.sample_period_s)
                if m is None:
                    joined = None
                    joiner.flush()      # ranges never completed: counted, not silently lost
                else:
                    if not check.chunk(m, topics[m.topic]):
                        continue
                    joined = joiner.add(topics[m.topic], int(m.first_sample_index),
                                        float(m.sample_period_s), m.samples, m.stamp, m.frame_id)
                    if joined is None or not check.joined(joined):
                        continue
                    n_samples += len(joined.arrays["a1"])
                windows, dropped = feeder.flush() if joined is None else feeder.add(joined)
                discarded.extend(dropped)
                for window, source in windows:   # source: the range completing it, range by range
                    last_offsets = (window.sensor_offsets, window.offset_periods)
                    if not estimator.classifies(window.kind):
                        continue  # no estimate from it: skip denoising it (live: denoised, unused)
                    batch.append((source, window))
                if len(batch) >= ESTIMATE_BATCH or (m is None and batch):
                    denoised = denoise_pairs([(w.signals["a1"], w.signals["a2"]) for _, w in batch])
                    results = estimator.estimate_many([(a1, a2, w.kind, w.sample_period_s, w.sensor_offsets)
                                                       for (_, w), (a1, a2) in zip(batch, denoised)])
                    for (source, window), estimates in zip(batch, results):
                        for est in estimates:
                            rows.append(_row(window, est, true_width))
                            estimates_msgs.append((source, window, est))
                    batch = []
            integrity = reader.recovery.to_dict()
    except BagError as error:
        raise UsageError(str(error)) from None
    except ValueError as error:   # a core's check of its input: one line, never a traceback
        raise UsageError(f"bag {bag_path}: {error}") from None
    elapsed = time.perf_counter() - started
    if n_samples == 0:   # nothing analysed is no result: never an empty "success"
        why = ("; ".join(f"{n} x {r}" for r, n in check.discards.items()) if check.discards
               else "no complete range of " + ", ".join(stage.input_signals) + " in it")
        raise UsageError(f"bag {bag_path}: no samples could be analysed ({why})")

    summary = _summary(rows, true_width)
    sensor_offsets = _sensor_offsets(*last_offsets, estimator.waiting_for_offset)
    # written under temporary names, renamed together once all three are complete
    with staged_outputs([outputs["csv"], outputs["json"], outputs["mcap"]]) as (csv_tmp, json_tmp, mcap_tmp):
        with open(csv_tmp, "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(CSV_COLUMNS)
            for r in rows:
                writer.writerow([r[c] if c != "b_vector" else " ".join(f"{b:.9g}" for b in r[c])
                                 for c in CSV_COLUMNS])
        with open(json_tmp, "w") as f:
            # json.dumps (one shot) uses the C encoder; json.dump to a file does not
            f.write(json.dumps({"bag": str(bag_path), "mode": mode, "trigger": args.trigger,
                       "samples_analysed": n_samples, "seconds": elapsed,
                       "discarded_windows": [{"entry_sample_index": d.entry_sample_index,
                                              "reason": d.reason} for d in discarded],
                       "discarded_chunks": check.summary(), "bag_integrity": integrity,
                       "input_faults": {**stage.faults.counts, **estimator.faults.counts},
                       "lost_samples": stage.lost_samples, "sensor_offsets": sensor_offsets,
                       "summary": summary, "estimates": rows}, allow_nan=True))
        _write_estimate_bag(mcap_tmp, estimates_msgs, true_width)
    return {"rows": rows, "summary": summary, "discarded": discarded, "n_samples": n_samples,
            "seconds": elapsed, "outputs": outputs, "check": check, "integrity": integrity,
            "faults": (stage.faults, estimator.faults), "lost_samples": stage.lost_samples,
            "drive": first_a1[0], "first_stamp_s": first_a1[1], "sensor_offsets": sensor_offsets}


def _sensor_offsets(offsets: dict, periods: int, waiting: int) -> dict:
    """The drive's latest sensor offset estimate for OUT.json, judged against the plausible range."""
    from backlash_monitor.windowing import DEFAULTS
    from backlash_monitor.windowing.offset import implausible_offsets
    limit = float(DEFAULTS["sensor_offset"]["plausible_abs_m_s2"])
    return {**{f"{name}_m_s2": value for name, value in offsets.items()}, "periods": periods,
            "plausible_abs_m_s2": limit,
            "implausible": {f"{k}_m_s2": v for k, v in implausible_offsets(offsets, limit).items()},
            "onset_windows_before_offset_known": waiting,
            "method": "mean over the last whole load periods (onset window end to onset window end), "
                      "removed from every window before the classifier"}


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


class ChunkCheck:
    """The recorded chunks checked before they enter the chain: the sample rate against the pattern
    library's (a bag at another rate is refused), each topic's signal name and unit (a topic
    carrying another signal is refused), and -- counted and discarded -- a sample period that is
    not a positive number, non-finite samples and ranges whose signals' chunks differ in length."""

    def __init__(self, bag_path, library):
        import numpy as np

        from backlash_monitor.signals import SIGNAL_UNITS
        self.np = np
        self.bag_path = bag_path
        self.library = library
        self.period_s = library.sample_period_s
        self.units = SIGNAL_UNITS
        self.accepted = 0
        self.discards: dict[str, int] = {}
        self.examples: list[dict] = []

    def _discard(self, reason: str, topic: str, first: int) -> bool:
        self.discards[reason] = self.discards.get(reason, 0) + 1
        if len(self.examples) < 20:
            self.examples.append({"topic": topic, "first_sample_index": first, "reason": reason})
        return False

    def chunk(self, m, name: str) -> bool:
        from backlash_monitor.commands import UsageError
        period = float(m.sample_period_s)
        first = int(m.first_sample_index)
        if not (math.isfinite(period) and period > 0):
            return self._discard(f"sample_period_s = {period!r} is not a positive number",
                                 m.topic, first)
        if m.samples.ndim != 1 or m.samples.size == 0:
            return self._discard("no samples", m.topic, first)
        if not self.np.isfinite(m.samples).all():   # NaN/inf never reach the chain (its windows: gaps)
            return self._discard("non-finite samples", m.topic, first)
        wrong = None
        if not math.isclose(period, self.period_s, rel_tol=1e-6):
            wrong = (f"bag {self.bag_path} is sampled at {1 / period:g} Hz (sample_period_s "
                     f"{period:g} s on {m.topic}); the pattern library {self.library.path} was "
                     f"trained at {1 / self.period_s:g} Hz ({self.period_s:g} s), its patterns do not "
                     f"fit; allowed: a bag sampled at {1 / self.period_s:g} Hz, or --library trained "
                     "at the bag's rate")
        elif m.signal_name and m.signal_name != name:
            wrong = (f"topic {m.topic} carries signal {m.signal_name!r} ({m.unit}), not {name!r}; "
                     f"allowed: {name} in {self.units.get(name, '?')} on this topic")
        elif m.unit and self.units.get(name) and m.unit != self.units[name]:
            wrong = (f"topic {m.topic} carries {name} in {m.unit!r}; the pattern library expects "
                     f"{self.units[name]!r}")
        if wrong:
            if not self.accepted:
                raise UsageError(wrong)
            return self._discard(wrong.split(";")[0], m.topic, first)
        self.accepted += 1
        return True

    def joined(self, joined) -> bool:
        lengths = {name: len(a) for name, a in joined.arrays.items()}
        if len(set(lengths.values())) > 1:
            return self._discard("signals' chunks differ in length ("
                                 + ", ".join(f"{k} {v}" for k, v in lengths.items()) + ")",
                                 "", int(joined.first_sample_index))
        return True

    def summary(self) -> dict:
        return {"count": sum(self.discards.values()), "by_reason": dict(self.discards),
                "examples": list(self.examples)}


def _print_input_problems(check, integrity) -> None:
    if check.discards:
        print(f"discarded {sum(check.discards.values())} chunk(s)/range(s): "
              + "; ".join(f"{n} x {r}" for r, n in check.discards.items()))
    if integrity and (integrity["damaged_chunks"] or integrity["problems"] or not integrity["complete"]):
        print(f"bag integrity: {integrity['describe']}")


def _row(window, est, true_width) -> dict:
    return {
        "entry_sample_index": window.entry_sample_index,
        "entry_time_s": window.entry_sample_index * window.sample_period_s,
        "signal": est.signal_name, "mode": est.mode, "width_m": est.width_m,
        "width_index": est.width_index, "b_margin": est.b_margin,
        "continuous_width_m": est.continuous_width_m, "fused_width_m": est.fused_width_m,
        "fused_events": est.fused_events, "true_width_m": true_width,
        "b_vector": [float(b) for b in est.b_vector],
        "fused_continuous_width_m": est.fused_continuous_width_m,
        "a1_offset_m_s2": window.sensor_offsets.get("a1", math.nan),
        "a2_offset_m_s2": window.sensor_offsets.get("a2", math.nan),
        "offset_periods": window.offset_periods,
        "candidate_widths_m": [float(w) for w in est.candidate_widths_m],
        "entry_kind": window.kind,
    }


def _then_none(iterable):
    """The items, then None (the end: flush)."""
    yield from iterable
    yield None


def _summary(rows, true_width):
    per = {}
    for r in rows:
        s = per.setdefault(r["signal"], {"estimates": 0, "correct": 0})
        s["estimates"] += 1
        s["correct"] += int(not math.isnan(true_width) and abs(r["width_m"] - true_width) < 1e-9)
        s["fused_width_m"] = r["fused_width_m"]
        s["fused_events"] = r["fused_events"]
        s["fused_continuous_width_m"] = r.get("fused_continuous_width_m", math.nan)
    return {"true_width_m": true_width, "per_signal": per}


def _print_summary(summary, rows, discarded, n_samples, elapsed, outputs):
    true_width = summary["true_width_m"]
    print(f"analyzed {n_samples} samples in {elapsed:.2f} s; {len({r['entry_sample_index'] for r in rows})} "
          f"onset windows classified, {len(discarded)} discarded")
    header = ("signal", "estimates", "accuracy", "fused width", "fused continuous", "fused events")
    lines = [header]
    for signal, s in sorted(summary["per_signal"].items()):
        acc = "-" if math.isnan(true_width) else f"{s['correct'] / s['estimates']:.0%}"
        cont = s.get("fused_continuous_width_m", math.nan)
        lines.append((signal, str(s["estimates"]), acc, f"{s['fused_width_m'] * 1e3:.2f} mm",
                      "-" if math.isnan(cont) else f"{cont * 1e3:.2f} mm", str(s["fused_events"])))
    widths = [max(len(line[i]) for line in lines) for i in range(len(header))]
    for i, line in enumerate(lines):
        print("  ".join(c.rjust(w) for c, w in zip(line, widths)))
        if i == 0:
            print("  ".join("-" * w for w in widths))
    if not math.isnan(true_width):
        print(f"true width: {true_width * 1e3:.2f} mm")
    print(f"wrote {outputs['csv']}, {outputs['json'].name}, {outputs['mcap'].name}")


def _write_estimate_bag(path, estimates_msgs, true_width):
    from backlash_monitor.bag import BACKLASH_ESTIMATE, BagWriter
    # written in one go at the end: chunks by size only (the 0.5 s chunk span of a live recording
    # bounds what a killed recorder loses; here it would only make one chunk per 0.5 s)
    with BagWriter(path, chunk_duration_s=None) as writer:
        writer.add_topic("/estimate", BACKLASH_ESTIMATE)
        for joined, window, est in estimates_msgs:
            stamp_ns = int(round(window.entry_sample_index * window.sample_period_s * 1e9))
            if joined.stamp is not None:
                base = joined.stamp.sec * 1_000_000_000 + joined.stamp.nanosec - int(round(
                    joined.first_sample_index * joined.sample_period_s * 1e9))
                stamp_ns += base
            writer.write("/estimate", {
                "header": {"stamp": {"sec": stamp_ns // 1_000_000_000,
                                     "nanosec": stamp_ns % 1_000_000_000},
                           "frame_id": joined.frame_id},
                "signal_name": est.signal_name, "mode": est.mode,
                "entry_sample_index": window.entry_sample_index, "entry_kind": window.kind,
                "candidate_widths_m": est.candidate_widths_m, "b_vector": est.b_vector,
                "width_index": est.width_index, "width_m": est.width_m,
                "b_margin": est.b_margin, "continuous_width_m": est.continuous_width_m,
                "fused_width_m": est.fused_width_m, "fused_events": est.fused_events,
                "true_width_m": true_width,
                "fused_continuous_width_m": est.fused_continuous_width_m}, log_time_ns=stamp_ns)
