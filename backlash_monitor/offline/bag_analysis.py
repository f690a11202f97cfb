"""One bag through the signal chain offline: the core of ``python -m backlash_monitor analyze``.

Reads the drive's SignalChunk topics (plant/a1, plant/a2, plant/angle_difference -- or
plant/omega1/omega2 with angle_source "integrated") in the order they were recorded, runs the same
stages as the live graph (backlash_monitor.chain: join, check and window; backlash_monitor.denoise; classify, fuse)
and writes the estimates to PREFIX.csv, PREFIX.json and PREFIX.mcap (topic ``estimate``, the live
pipeline's message type). Given the same recorded chunks, the estimates equal the live pipeline's.

Every input is checked where the live chain checks it, with the live chain's fault vocabulary
(input_faults.REASONS): a range with a bad sample period, unequal lengths, non-finite samples or an
accelerometer sample outside the sensor's declared range is dropped and counted by the
WindowingStage, a window at another rate than the pattern library's by the DriveEstimator. What is
refused outright (UsageError, one line): a bag whose first chunks are sampled at another rate than
the library was trained at, or whose topics carry other signals (or units) than their names say.

``analyze_bag(bag, out_prefix, options)`` is the whole of it; ``options`` is an
:class:`AnalyzeOptions` (the fleet's jobs are (bag, out, options) too). No rclpy, no argparse.
"""
from __future__ import annotations

import csv
import functools
import json
import math
import sys
import pathlib
import time
from dataclasses import dataclass

import numpy as np

from backlash_monitor.errors import RunFailure, UsageError
from backlash_monitor.classifier.patterns import PatternLibraryError, flagged_warning, load_library as load
from backlash_monitor.windowing import default_window_offset, DEFAULTS
from backlash_monitor.signals import SIGNAL_UNITS
from backlash_monitor.stream_time import stamp_seconds, stream_origin_s
from backlash_monitor.windowing.faults import is_period
from backlash_monitor.bag import (
    BagError,
    BagReader,
    DamagedBagError,
    TruncatedBagError,
    Stamp,
    SignalChunkRecord,
    BACKLASH_ESTIMATE,
    BagWriter,
)
from backlash_monitor.chain.block_feeder import BlockFeeder
from backlash_monitor.chain.joiner import ChunkJoiner
from backlash_monitor.chain.stage import WindowingStage
from backlash_monitor.denoise import denoise_pairs
from backlash_monitor.estimation import DEFAULT_MODE, DriveEstimator
from backlash_monitor.files.outputs import OutputError, check_outputs, staged_outputs
from backlash_monitor.process.memory import reuse_freed_memory
from backlash_monitor.windowing.offset import implausible_offsets

ESTIMATE_BATCH = 64   # onset windows per batched denoise + DriveEstimator.estimate_many call

CSV_COLUMNS = ("entry_sample_index", "entry_time_s", "signal", "mode", "width_m", "width_index",
               "b_margin", "continuous_width_m", "fused_width_m", "fused_events", "true_width_m",
               "b_vector", "fused_continuous_width_m", "a1_offset_m_s2", "a2_offset_m_s2",
               "offset_periods", "fused_width_uncertainty_m", "fused_from_signal")
TRIGGERS = ("contact_loss", "paper")
ANGLE_SOURCES = ("measured", "integrated")


@dataclass(frozen=True)
class AnalyzeOptions:
    """How one bag is analysed (the `analyze` command's options, docs in its --help).

    namespace: the drive's topic namespace in the bag ("" = none); trigger: entry trigger, the
    library must be trained with it; width_m: backlash width for the 'paper' trigger [m];
    window_offset_samples: entry to window start [samples] (None: the trigger's configured value);
    angle_source: 'measured' (encoders) or 'integrated' (speeds); mode: classifier mode ("" =
    the default, shape); n1: absorber flow index [-]; library: pattern library path ("" = the
    packaged one); fusion_events: onset events fused into one estimate; recover: analyse what is
    intact of a damaged bag; overwrite: replace existing outputs."""
    namespace: str = ""
    trigger: str = "contact_loss"
    width_m: float = 0.0
    window_offset_samples: int | None = None
    angle_source: str = "measured"
    mode: str = ""
    n1: float = 0.89
    library: str = ""
    fusion_events: int = 8
    recover: bool = False
    overwrite: bool = False

    def check(self) -> None:
        """UsageError naming the first bad option and its allowed values."""
        if self.trigger not in TRIGGERS:
            raise UsageError(f"trigger {self.trigger!r}; allowed: {', '.join(TRIGGERS)}")
        if self.angle_source not in ANGLE_SOURCES:
            raise UsageError(f"angle source {self.angle_source!r}; allowed: {', '.join(ANGLE_SOURCES)}")
        if self.trigger == "paper" and not (0 < self.width_m <= 0.05):
            raise UsageError(f"--width-m {self.width_m:g}: out of range, allowed 0..0.05 m, above 0 (the paper "
                             "trigger needs the drive's width)")
        if self.fusion_events < 1:
            raise UsageError(f"--fusion-events {self.fusion_events}: out of range, allowed 1..inf")


def load_library(options: AnalyzeOptions):
    """(pattern library, window offset [samples]) for these options; UsageError for a bad option or
    file. The fleet's workers load it once and pass it to every :func:`analyze_bag`."""
    offset = (default_window_offset(options.trigger) if options.window_offset_samples is None
              else options.window_offset_samples)
    if not 0 <= offset <= 65536:
        raise UsageError(f"--window-offset {offset}: out of range, allowed 0..65536 samples")
    try:
        library = load(options.library or None, trigger=options.trigger, window_offset_samples=offset)
    except (PatternLibraryError, ValueError) as error:
        raise UsageError(str(error)) from None
    warning = flagged_warning(library)     # a library train --model flagged (it disagrees with the one before)
    if warning:
        print(f"WARNING: {warning}", file=sys.stderr)
    return library, offset


def default_out_prefix(bag_path) -> pathlib.Path:
    """The bag's path without .mcap, plus '.estimates'."""
    bag_path = pathlib.Path(bag_path)
    return bag_path.with_suffix("").with_name(bag_path.with_suffix("").name + ".estimates")


def output_paths(out_prefix) -> dict[str, pathlib.Path]:
    """PREFIX.csv, PREFIX.json, PREFIX.mcap: the suffix is appended (a prefix such as
    ``run.estimates`` keeps its dots; ``with_suffix`` would turn it into ``run.mcap``)."""
    prefix = str(out_prefix)
    return {ext: pathlib.Path(f"{prefix}.{ext}") for ext in ("csv", "json", "mcap")}


def topic_name(namespace: str, name: str) -> str:
    ns = namespace.strip("/")
    return f"/{ns}/plant/{name}" if ns else f"/plant/{name}"


def drive_namespace(available, bag_path) -> str:
    """The namespace of the one drive whose plant topics the bag holds (``<ns>/plant/a1``), as the workbench
    finds it; several drives: refused, naming them (``--namespace`` chooses)."""
    found = sorted({t[:-len("/plant/a1")].strip("/") for t in available if t.endswith("plant/a1")
                    and (t == "/plant/a1" or t == "plant/a1" or t.endswith("/plant/a1"))})
    if len(found) > 1:
        raise UsageError(f"bag {bag_path} holds several drives' plant topics ({', '.join('/' + f for f in found)}); "
                         "choose one with --namespace")
    return found[0] if found else ""


def find_topic(available, namespace, name):
    for candidate in (topic_name(namespace, name), topic_name(namespace, name).lstrip("/")):
        if candidate in available:
            return candidate
    return None


def recorded_drive(bag, namespace: str = "", recover: bool = False) -> tuple[str, str]:
    """(the namespace of the drive's topics, the first a1 chunk's frame_id: its recorded drive name) of a bag, read
    before its analysis: the fleet picks the drive's pattern library by them (fleet/folder_analysis.py). One chunk
    is read. ("", "") where the bag cannot be read this way: its analysis then says what is wrong with it."""
    try:
        with BagReader(pathlib.Path(bag), recover=recover, chunks_ahead=0) as reader:
            available = set(reader.topics)
            found = namespace or drive_namespace(available, bag)
            topic = find_topic(available, found, "a1")
            for m in reader.signal_chunks([topic], copy=False) if topic else ():
                return found, m.frame_id
            return found, ""
    except (BagError, UsageError, ValueError, OSError):
        return "", ""


class SourceCheck:
    """What makes a bag the wrong input (refused, never counted as faults): a chunk sampled at
    another rate than the pattern library's, or a topic carrying another signal (or unit) than its
    name says. Refused while no chunk was accepted yet; after that such a chunk is passed on (the
    chain counts what it does to the windows) or, for a wrong signal, dropped and counted as
    ``wrong_signal`` in the stage's fault log. Checked once per (topic, period, name, unit): a
    recording's chunks repeat them, so the per-chunk cost is one tuple comparison."""

    def __init__(self, bag_path, library, faults):
        self.bag_path = bag_path
        self.library = library
        self.period_s = library.sample_period_s
        self.units = SIGNAL_UNITS
        self.faults = faults
        self.accepted = False
        self._known: dict[str, tuple] = {}     # topic -> the (period, name, unit) last found good

    def ok(self, m, name: str) -> bool:
        key = (m.sample_period_s, m.signal_name, m.unit)
        if self._known.get(m.topic) == key:
            return True
        return self._check(m, name, key)

    def passes(self, topic: str, period, signal_name: str, unit: str) -> bool:
        """True when :meth:`ok` passes a chunk on ``topic`` with these fields without a look (they
        are the ones last found good there): nothing to check, nothing to count."""
        return self._known.get(topic) == (period, signal_name, unit)

    def wrong(self, topic: str, name: str, signal_name: str, unit: str) -> str | None:
        """What is wrong with a chunk on ``topic`` (signal ``name``) that carries ``signal_name``
        in ``unit`` (another signal, another unit), or None."""
        if signal_name and signal_name != name:
            return (f"topic {topic} carries signal {signal_name!r} ({unit}), not {name!r}; "
                    f"allowed: {name} in {self.units.get(name, '?')} on this topic")
        if unit and self.units.get(name) and unit != self.units[name]:
            return (f"topic {topic} carries {name} in {unit!r}; the pattern library expects "
                    f"{self.units[name]!r}")
        return None

    def _check(self, m, name, key) -> bool:
        period = m.sample_period_s
        wrong_rate = is_period(period) and not math.isclose(float(period), self.period_s, rel_tol=1e-6)
        if wrong_rate and not self.accepted:
            raise UsageError(
                f"bag {self.bag_path} is sampled at {1 / period:g} Hz (sample_period_s {period:g} s on "
                f"{m.topic}); the pattern library {self.library.path} was trained at "
                f"{1 / self.period_s:g} Hz ({self.period_s:g} s), its patterns do not fit; allowed: a bag "
                f"sampled at {1 / self.period_s:g} Hz, or --library trained at the bag's rate")
        wrong = self.wrong(m.topic, name, m.signal_name, m.unit)
        if wrong:
            if not self.accepted:
                raise UsageError(wrong)
            self.faults.add("wrong_signal", wrong.split(";")[0])
            return False
        self.accepted = True
        if is_period(period) and not wrong_rate:
            self._known[m.topic] = key
        return True


def analyze_bag(bag, out_prefix, options: AnalyzeOptions, library=None,
                chunks_ahead: int | None = None, summary_fields=None) -> dict:
    """One bag through the chain; writes PREFIX.csv/.json/.mcap (``out_prefix`` None or "": the
    default beside the bag) and returns rows, summary, discarded windows, samples, seconds,
    outputs, the bag's integrity, the faults (stage, estimator), lost samples, the sensor offsets,
    and ``drive``/``first_stamp_s`` (the first a1 chunk's frame_id and the stamp of its first
    sample). ``library``: (library, offset) from :func:`load_library`, loaded here when None.
    ``chunks_ahead``: the bag reader's decompression thread (BagReader; None: its default; 0: none,
    for a pool with a worker per core). ``summary_fields``: called with the analysis (the returned dict, before
    the outputs are written) for fields added to its summary, which OUT.json holds too (one bag's model fit:
    fleet/folder_analysis.one_bag_fit); None: none. Raises UsageError (one line) for anything wrong with the
    bag or the options. ``a1_chain``: a1 checked against the recorded motor speed (windowing/a1_chain.A1ChainResult;
    None: the bag has no motor speed)."""
    options.check()
    reuse_freed_memory()   # no page fault per freed-and-reallocated array (process/memory.py)
    bag_path = pathlib.Path(bag)
    if not bag_path.is_file():
        raise UsageError(f"bag {bag_path} does not exist; give the path of an .mcap file")
    mode = options.mode or DEFAULT_MODE
    library, offset = library or load_library(options)
    try:
        estimator = DriveEstimator(library, mode=mode, n1=options.n1,
                                   fusion_events=options.fusion_events)
        # the stage's settings, once: built here (its checks of them), and again with a1's check where the bag has the
        # motor speed (below)
        windowing_stage = functools.partial(WindowingStage, trigger=options.trigger,
                                            width_m=options.width_m if options.trigger == "paper" else None,
                                            angle_source=options.angle_source, window_offset_samples=offset)
        stage = windowing_stage()
    except (PatternLibraryError, ValueError) as error:
        raise UsageError(str(error)) from None
    missing = [name for name in stage.input_signals[:2] if name not in library.signals]
    if missing:
        raise UsageError(f"pattern library {library.path} has no patterns for {', '.join(missing)} "
                         f"(it has {', '.join(library.signals)}); allowed: a library trained on "
                         f"{', '.join(stage.input_signals[:2])}")

    outputs = output_paths(out_prefix or default_out_prefix(bag_path))
    try:
        check_outputs(outputs.values(), inputs=[bag_path], overwrite=options.overwrite, option="--out")
    except OutputError as error:
        raise UsageError(str(error)) from None
    started = time.perf_counter()
    rows, estimates_msgs, discarded = [], [], []
    source = SourceCheck(bag_path, library, stage.faults)
    integrity = None
    try:
        with BagReader(bag_path, recover=options.recover, chunks_ahead=chunks_ahead) as reader:
            available = set(reader.topics)
            namespace = options.namespace or drive_namespace(available, bag_path)
            if find_topic(available, namespace, "omega1"):
                # the motor speed is recorded: a1 is checked against it as the samples come (windowing/a1_chain.py)
                stage = windowing_stage(faults=stage.faults, check_a1_chain=True)
            topics = {}
            for name in stage.input_signals:
                topic = find_topic(available, namespace, name)
                if topic is None:
                    raise UsageError(
                        f"bag {bag_path} has no topic {topic_name(namespace, name)}; it has: "
                        f"{', '.join(sorted(available))}")
                topics[topic] = name
            width_topic = find_topic(available, namespace, "true_width_m")
            true_width = math.nan
            if width_topic:
                for m in reader.messages([width_topic]):
                    true_width = float(m.message.data)
            joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
            # contiguous ranges go to the stage in blocks: the same windows as range by range
            feeder = BlockFeeder(stage)
            batch = []   # onset windows, denoised and estimated together (same numbers as one by one)
            last_offsets = ({}, 0)   # the latest window's sensor offset estimate, periods
            saturated_windows = [0, 0]   # windows with samples at a rail or stuck, windows checked
            # the drive's name and the first sample's time, from the first a1 chunk
            first_a1 = [("", math.nan)]
            # a file without chunks: its ranges joined at once when they come whole, one after the
            # other (the same ranges as chunk by chunk); otherwise (or when they do not) chunk by
            # chunk. copy=False: samples in the file's map (a bag without chunks, or uncompressed
            # ones) are read in place: the feeder joins them into blocks, the stage copies what it keeps
            ranges = _ranges_at_once(reader, topics, source, joiner, first_a1)
            if ranges is None:
                ranges = _ranges_by_batch(reader.signal_chunk_batches(list(topics)), topics,
                                          source, joiner, first_a1)
            for joined in _then_none(ranges):
                if joined is None:
                    joiner.flush()      # ranges never completed: counted, not silently lost
                    windows, dropped = feeder.flush()
                else:
                    windows, dropped = feeder.add(joined)
                if dropped:
                    discarded.extend(dropped)
                for window, completing in windows:   # completing: the range completing it, one by one
                    last_offsets = (window.sensor_offsets, window.offset_periods)
                    saturated_windows[0] += window.saturated_samples > 0
                    saturated_windows[1] += 1
                    if not estimator.classifies(window.kind):
                        continue  # no estimate from it: skip denoising it (live: denoised, unused)
                    batch.append((completing, window))
                if len(batch) >= ESTIMATE_BATCH or (joined is None and batch):
                    denoised = denoise_pairs([(w.signals["a1"], w.signals["a2"]) for _, w in batch])
                    results = estimator.estimate_many([(a1, a2, w.kind, w.sample_period_s, w.sensor_offsets,
                                                        w.a1_chain)
                                                       for (_, w), (a1, a2) in zip(batch, denoised)])
                    for (completing, window), estimates in zip(batch, results):
                        for est in estimates:
                            rows.append(_row(window, est, true_width))
                            rows[-1]["saturated_samples"] = window.saturated_samples   # JSON, not CSV
                            estimates_msgs.append((completing, window, est))
                    batch = []
            integrity = reader.recovery.to_dict()
    except (TruncatedBagError, DamagedBagError) as error:   # the data is damaged, not the command line
        raise RunFailure(str(error)) from None
    except BagError as error:
        raise UsageError(str(error)) from None
    except ValueError as error:   # a core's check of its input: one line, never a traceback
        raise UsageError(f"bag {bag_path}: {error}") from None
    elapsed = time.perf_counter() - started
    n_samples = stage.fed_samples
    if n_samples == 0:   # nothing analysed is no result: never an empty "success"
        why = ("; ".join(f"{n} x {r}" for r, n in sorted(stage.faults.counts.items())) if stage.faults.total
               else "no complete range of " + ", ".join(stage.input_signals) + " in it")
        raise UsageError(f"bag {bag_path}: no samples could be analysed ({why})")

    summary = _summary(rows, true_width)
    sensor_offsets = _sensor_offsets(*last_offsets, estimator.waiting_for_offset)
    saturation = saturation_report(stage.saturation, *saturated_windows)
    a1_chain = stage.a1_chain.result() if stage.a1_chain is not None else None
    result = {"rows": rows, "summary": summary, "discarded": discarded, "n_samples": n_samples,
              "seconds": elapsed, "outputs": outputs, "integrity": integrity,
              "faults": (stage.faults, estimator.faults), "lost_samples": stage.lost_samples,
              "drive": first_a1[0][0], "first_stamp_s": first_a1[0][1], "sensor_offsets": sensor_offsets,
              "input_saturation": saturation, "namespace": namespace, "a1_chain": a1_chain}
    if summary_fields is not None:
        summary.update(summary_fields(result))
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
            f.write(json.dumps({"bag": str(bag_path), "mode": mode, "trigger": options.trigger,
                       "samples_analysed": n_samples, "seconds": elapsed,
                       "discarded_windows": [{"entry_sample_index": d.entry_sample_index,
                                              "reason": d.reason} for d in discarded],
                       "bag_integrity": integrity,
                       "input_faults": {**stage.faults.counts, **estimator.faults.counts},
                       "input_fault_examples": [{"reason": r, "detail": d} for r, d in stage.faults.take()[:20]],
                       "lost_samples": stage.lost_samples, "sensor_offsets": sensor_offsets,
                       "input_saturation": saturation,
                       "a1_chain": a1_chain.as_dict() if a1_chain is not None else None,
                       "summary": summary, "estimates": rows}, allow_nan=True))
        _write_estimate_bag(mcap_tmp, estimates_msgs, true_width)
    return result


def saturation_report(counter, saturated_windows: int, windows: int) -> dict:
    """The recording's sensors at a rail or stuck (windowing/saturation.py; counted in blocks of 1 s as
    the live windowing node counts them): per signal counts and shares, the windows with such samples
    in their analysed stretch, and one message per fault ('' when none)."""
    counter.flush()
    totals = counter.totals()
    return {"saturated": any(r.faulty for r in totals.values()),
            "signals": {name: r.as_dict() for name, r in totals.items()},
            "saturated_windows": int(saturated_windows), "windows_checked": int(windows),
            "messages": counter.messages()}


def _ranges_one_by_one(chunks, topics: dict, source: SourceCheck, joiner, first_a1: list,
                       state: dict | None = None):
    """The joined ranges of ``chunks`` (SignalChunkRecords of ``topics``: topic -> signal), chunk by
    chunk: each checked (``source``), the first a1 chunk's (frame_id, time of its first sample)
    put in ``first_a1[0]``. ``state``: {"a1_topics": ...} shared by calls that go on where the
    one before ended (None once the first a1 chunk is seen)."""
    if state is None:
        state = {"a1_topics": {t for t, n in topics.items() if n == "a1"}}
    a1_topics = state["a1_topics"]
    source_ok = source.ok
    join = joiner.add
    for m in chunks:
        name = topics[m.topic]
        if not source_ok(m, name):
            continue
        if a1_topics and m.topic in a1_topics:
            first_a1[0] = _first_sample_time(m.frame_id, m.stamp, m.first_sample_index, m.sample_period_s)
            a1_topics = state["a1_topics"] = None
        joined = join(name, m.first_sample_index, m.sample_period_s, m.samples, m.stamp,
                      m.frame_id)
        if joined is not None:
            yield joined


def _ranges_by_batch(batches, topics: dict, source: SourceCheck, joiner, first_a1: list):
    """What :func:`_ranges_one_by_one` gives for the records of ``batches``
    (BagReader.signal_chunk_batches: a chunk's records as columns, or as a list of records),
    with a chunk's whole ranges joined at once (``ChunkJoiner.add_rows``) when nothing in it
    needs a look chunk by chunk: every topic's chunks in it at the sample period, signal and
    unit ``source`` found good before (so ``source.ok`` passes each, as it would), the first a1
    chunk seen. The rows of a range begun in the chunk before are added one by one until it is
    complete, and so are those of a range the next chunk completes; anything else that is not
    whole ranges one after the other goes one by one (the joiner counts what is wrong)."""
    state = {"a1_topics": {t for t, n in topics.items() if n == "a1"}}
    signals = joiner.signals
    width = len(signals)
    join = joiner.add
    for batch in batches:
        if type(batch) is list or state["a1_topics"]:
            yield from _ranges_one_by_one(batch if type(batch) is list else batch.records(),
                                          topics, source, joiner, first_a1, state)
            continue
        passed = True
        for k, (topic, (_frame_id, signal_name, unit)) in enumerate(zip(batch.topics, batch.texts)):
            periods = batch.sample_period_s[batch.topic == k]
            if not ((periods == periods[0]).all()
                    and source.passes(topic, float(periods[0]), signal_name, unit)):
                passed = False
                break
        if not passed:
            yield from _ranges_one_by_one(batch.records(), topics, source, joiner, first_a1, state)
            continue
        # each row's signal as its index in the joiner's signals
        code = np.array([signals.index(topics[t]) for t in batch.topics])[batch.topic]
        firsts = batch.first_sample_index
        samples = batch.samples
        frame_ids = [texts[0] for texts in batch.texts]
        n = code.size
        i = 0
        while i < n and joiner.pending:      # the rest of a range begun before
            joined = join(signals[code[i]], int(firsts[i]), float(batch.sample_period_s[i]),
                          samples[i], Stamp(int(batch.sec[i]), int(batch.nanosec[i])),
                          frame_ids[batch.topic[i]])
            i += 1
            if joined is not None:
                yield joined
        whole = i + (n - i) // width * width
        ranges = None
        if whole > i:
            sec, nanosec, topic = (batch.sec[i:whole].tolist(), batch.nanosec[i:whole].tolist(),
                                   batch.topic[i:whole].tolist())

            def meta(j):
                return Stamp(sec[j], nanosec[j]), frame_ids[topic[j]]
            ranges = joiner.add_rows(code[i:whole], firsts[i:whole],
                                     batch.sample_period_s[i:whole], samples[i:whole], meta)
        if ranges is not None:
            yield from ranges
            i = whole
        for j in range(i, n):                # a range the next chunk completes, or not whole ranges
            joined = join(signals[code[j]], int(firsts[j]), float(batch.sample_period_s[j]),
                          samples[j], Stamp(int(batch.sec[j]), int(batch.nanosec[j])),
                          frame_ids[batch.topic[j]])
            if joined is not None:
                yield joined


def _ranges_at_once(reader, topics: dict, source: SourceCheck, joiner, first_a1: list):
    """The joined ranges of a file without chunks, taken at once (BagReader.signal_chunk_columns,
    ChunkJoiner.add_rows), when that gives what :func:`_ranges_one_by_one` gives: every topic's
    chunks alike (one sample period, the right signal and unit: ``source`` checks each topic's
    first chunk, as it would, and passes the others, as it would), whole ranges one after the
    other. None otherwise (nothing done that chunk by chunk would not do alike)."""
    columns = reader.signal_chunk_columns(list(topics))
    if columns is None:
        return None
    firsts = [int(np.argmax(columns.topic == k)) for k in range(len(columns.topics))]
    for k, (topic, (frame_id, signal_name, unit)) in enumerate(zip(columns.topics, columns.texts)):
        periods = columns.sample_period_s[columns.topic == k]
        if not (periods == periods[0]).all() or source.wrong(topic, topics[topic], signal_name, unit):
            return None      # (a period that is NaN, too)
    first_chunks = []
    for k, i in enumerate(firsts):     # in file order, as chunk by chunk
        frame_id, signal_name, unit = columns.texts[k]
        m = SignalChunkRecord(columns.topics[k], 0, int(columns.first_sample_index[i]),
                              float(columns.sample_period_s[i]), columns.samples[i],
                              Stamp(int(columns.sec[i]), int(columns.nanosec[i])), frame_id,
                              signal_name, unit)
        if not source.ok(m, topics[m.topic]):     # (not wrong: it does not refuse)
            return None   # pragma: no cover
        first_chunks.append(m)
    # each chunk's signal as its index in the joiner's signals (topics of other signals: -1)
    signal_of = np.array([joiner.signals.index(topics[t]) if topics[t] in joiner.signals else -1
                          for t in columns.topics])
    frame_ids = [texts[0] for texts in columns.texts]
    sec, nanosec, topic = columns.sec.tolist(), columns.nanosec.tolist(), columns.topic.tolist()

    def meta(i):
        return Stamp(sec[i], nanosec[i]), frame_ids[topic[i]]
    ranges = joiner.add_rows(signal_of[columns.topic], columns.first_sample_index,
                             columns.sample_period_s, columns.samples, meta)
    if ranges is not None:
        a1 = [m for m in first_chunks if topics[m.topic] == "a1"]
        if a1:
            m = a1[0]
            first_a1[0] = _first_sample_time(m.frame_id, m.stamp, m.first_sample_index, m.sample_period_s)
    return ranges


def _first_sample_time(frame_id, stamp, first_sample_index, sample_period_s):
    """(frame_id, time of the stream's sample 0 [s]: NaN without a usable stamp) from a chunk's stamp."""
    stamp_s = stamp_seconds(stamp)
    return frame_id, (math.nan if stamp_s is None else stream_origin_s(stamp_s, first_sample_index, sample_period_s))


def _sensor_offsets(offsets: dict, periods: int, waiting: int) -> dict:
    """The drive's latest sensor offset estimate for OUT.json, judged against the plausible range."""
    limit = float(DEFAULTS["sensor_offset"]["plausible_abs_m_s2"])
    return {**{f"{name}_m_s2": value for name, value in offsets.items()}, "periods": periods,
            "plausible_abs_m_s2": limit,
            "implausible": {f"{k}_m_s2": v for k, v in implausible_offsets(offsets, limit).items()},
            "onset_windows_before_offset_known": waiting,
            "method": "mean over the last whole load periods (onset window end to onset window end), "
                      "removed from every window before the classifier"}


def _row(window, est, true_width) -> dict:
    return {
        "entry_sample_index": window.entry_sample_index,
        "entry_time_s": window.entry_sample_index * window.sample_period_s,
        "signal": est.signal_name, "mode": est.mode, "width_m": est.width_m,
        "width_index": est.width_index, "b_margin": est.b_margin,
        "continuous_width_m": est.continuous_width_m, "fused_width_m": est.fused_width_m,
        "fused_events": est.fused_events, "true_width_m": true_width,
        "b_vector": np.asarray(est.b_vector, dtype=np.float64).tolist(),   # (Python floats)
        "fused_continuous_width_m": est.fused_continuous_width_m,
        "fused_width_uncertainty_m": est.fused_width_uncertainty_m,
        # the signal whose fusion the fused fields carry (a1+a2's checked against a1's: classifier/signal_check.py)
        "fused_from_signal": est.fused_from_signal, "departure_sigmas": est.departure_sigmas,
        "scatter_ratio": est.scatter_ratio, "check_reason": est.check_reason,
        "a1_offset_m_s2": window.sensor_offsets.get("a1", math.nan),
        "a2_offset_m_s2": window.sensor_offsets.get("a2", math.nan),
        "offset_periods": window.offset_periods,
        "candidate_widths_m": np.asarray(est.candidate_widths_m, dtype=np.float64).tolist(),
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
        s["fused_width_uncertainty_m"] = r.get("fused_width_uncertainty_m", math.nan)
        s["fused_from_signal"] = r.get("fused_from_signal", "")
        s["check_reason"] = r.get("check_reason", "")
    return {"true_width_m": true_width, "per_signal": per}


def _write_estimate_bag(path, estimates_msgs, true_width):
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
                "fused_continuous_width_m": est.fused_continuous_width_m,
                "fused_width_uncertainty_m": est.fused_width_uncertainty_m}, log_time_ns=stamp_ns)
