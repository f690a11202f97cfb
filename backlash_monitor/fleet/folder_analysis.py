"""`analyze FOLDER` / `analyze 'GLOB'`: many recordings in parallel, into one fleet table.

Each bag goes through the single-bag `analyze` unchanged (its CSV, JSON and MCAP of estimates, in
``--out DIR``); the bags run in parallel on this machine's cores (a process pool, ``--jobs``), or
on a Dask cluster (``--engine dask``: ``--scheduler tcp://host:8786`` for an existing cluster of
many machines, a local cluster otherwise; dask and distributed are an optional extra). Every worker
must see the bags under the same path (shared storage) and have backlash_monitor installed.

The fleet table (DIR/fleet.csv and .json, printed at the end) has one row per recording: drive
(the chunks' frame_id), time (the first sample's stamp, UTC), the median per-window width (a1+a2
continuous where the mode gives it), the last fused width, and the drive's trend over all its
recordings (backlash_monitor/fleet/trend.py, config/trend.yaml: WARN for a drive that grows faster
than the configured rate, before it reaches the limit), with a plot per drive and a fleet plot.
"""
from __future__ import annotations

import csv
import gc
import glob
import json
import math
import os
import resource
import statistics
import time
from dataclasses import dataclass, replace
from datetime import datetime, timezone
from pathlib import Path
from typing import TYPE_CHECKING, NamedTuple
import multiprocessing
import sys
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
import importlib

from backlash_monitor.errors import RunFailure, UsageError
from backlash_monitor.files.locks import exclusive
from backlash_monitor.fleet.trend import PRIMARY_SIGNAL, drive_trend, load_rule, plot_trends
from backlash_monitor.fleet.caveat import FitVerdict, with_caveat, width_text, caveat

if TYPE_CHECKING:
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions

ENGINES = ("local", "dask")
THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS",
                    "NUMBA_NUM_THREADS")   # thread pools a worker's libraries would start
ESTIMATES_SUFFIX = ".estimates.mcap"   # what analyze writes: never an input


class RegisteredDrive(NamedTuple):
    """One drive of the registry (--registry, docs/registry.md) as the bags are held against it: its hardware id
    (LINE/DRIVE), its model watch's reference ("" = the default model's at its nominal, from the cache), its
    nominal (width_m, eta_k, n1), its pattern library ("" = the packaged one), its model file ("" = the default
    model at its nominal) and its version (len(versions) + 1)."""
    hardware_id: str
    reference: str
    nominal: tuple
    library: str = ""
    model: str = ""
    version: int = 1


@dataclass(frozen=True)
class WatchOptions:
    """The model-fit column's options (the model watch's test on each bag's last onset events,
    docs/model_watch.md), carried beside the AnalyzeOptions every bag shares.

    enabled: False for --no-model-fit (no column); reference: the model version's reference file
    (REF.watch.npz) every bag is held against ("" = --library's LIB.watch.npz where it exists, else
    the default model's at the pattern width nearest the drive's measured width, from the cache)."""
    enabled: bool = True
    reference: str = ""
    drives: tuple = ()      # the drive registry's drives (--registry, docs/registry.md): RegisteredDrive each; a bag
                            # is held against its own drive's version: its library's widths (unless --library is
                            # given: then that one for every bag) and, with the model fit on, its reference


@dataclass(frozen=True)
class FleetOptions:
    """How many recordings are analysed into one fleet table (the many-bag `analyze`'s options, docs
    in its --help); a fleet job is (bag, out, AnalyzeOptions), these say which bags and where.

    bags: a folder of bags or a glob of them; out: the output folder ("" = fleet_analysis beside the
    first bag); jobs: bags analysed at once (0 = this machine's cores; 1: one after the other in
    this process); engine: 'local' (a process pool) or 'dask'; scheduler: an existing Dask
    scheduler's address ("" = a local cluster); trend_config: trend rule file ("" = the packaged
    config/trend.yaml); plots: write the trend plots; watch: the model-fit column's WatchOptions."""
    bags: str
    out: str = ""
    jobs: int = 0
    engine: str = "local"
    scheduler: str = ""
    trend_config: str = ""
    plots: bool = True
    watch: WatchOptions = WatchOptions()
    progress: bool = True        # a progress bar over the bags on stderr

    def workers(self) -> int:
        """The bags analysed at once: ``jobs``, or this machine's cores for 0."""
        return self.jobs or os.cpu_count() or 1

    def check(self) -> None:
        """UsageError naming the first bad option and its allowed values."""
        if self.engine not in ENGINES:
            raise UsageError(f"engine {self.engine!r}; allowed: {', '.join(ENGINES)}")
        n_jobs = self.workers()
        if n_jobs < 1 or n_jobs > 1024:
            raise UsageError(f"--jobs {self.jobs}: out of range, allowed 0..1024 (0: this machine's cores)")


def is_many(bag: str) -> bool:
    return os.path.isdir(bag) or any(c in bag for c in "*?[")


def expand_bags(spec: str) -> list[Path]:
    if os.path.isdir(spec):
        found = Path(spec).glob("*.mcap")
    else:
        found = (Path(p) for p in glob.glob(spec))
    bags = sorted(p for p in found if p.is_file() and not p.name.endswith(ESTIMATES_SUFFIX))
    if not bags:
        raise UsageError(f"no .mcap bags in {spec!r}; give a folder of bags or a quoted glob "
                         "such as 'recordings/*.mcap'")
    return bags


_WORKER: dict = {}   # this process's worker state: the options' pattern library, loaded once


def init_worker(options, library=None, libraries=None) -> None:
    """A worker's start (ProcessPoolExecutor/Dask initializer, and the --jobs 1 loop): one core's
    worth of threads (BLAS, OpenMP and numba pools of one thread: the pool already has a worker
    per core; no bag decompression thread in a pool worker or on one CPU) and the pattern library
    loaded once for all its bags. ``library``: already loaded
    (inherited by a forked worker); ``libraries``: the registry's drives' libraries already loaded
    ({path: (library, offset)}, :func:`registry_libraries`), the others loaded when a bag needs them."""
    for var in THREAD_VARIABLES:
        os.environ[var] = "1"
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.offline.bag_analysis import load_library
    # a pool worker (a worker per core): no core for a bag reader's decompression thread, which
    # would only take turns with the worker; its readers get chunks_ahead=0 (None: the reader's
    # default, which is 0 on one CPU too)
    chunks_ahead = 0 if multiprocessing.parent_process() is not None else None
    _WORKER.update(pid=os.getpid(), options=options, chunks_ahead=chunks_ahead,
                   library=library or load_library(options))
    _WORKER.setdefault("libraries", {}).update(libraries or {})


def library_for_bag(options, drive: RegisteredDrive | None) -> str:
    """The pattern library a bag's widths come from: --library when it is given (for every bag, over the
    registry's: the user named one), else its registered drive's ``library``, else "" (the packaged one)."""
    if options.library:
        return options.library
    return drive.library if drive is not None else ""


def bag_library(options, path: str):
    """(library, window offset) for ``path`` in this worker: the options' own (loaded at its start) or one
    of the registry's, loaded once per process; UsageError naming a library that cannot be used."""
    if path == options.library:
        return _WORKER["library"]
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.offline.bag_analysis import load_library
    return _kept("libraries", path, lambda: load_library(replace(options, library=path)))


def registry_libraries(options, watch: WatchOptions) -> dict:
    """The registry's drives' libraries that load ({path: (library, offset)}), loaded once in the parent: forked
    workers inherit them. None without a registry or with --library (it overrides them); a library that does not
    load is left to the bags of its drive (their rows name the error)."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.offline.bag_analysis import load_library
    loaded = {}
    for path in sorted({d.library for d in watch.drives if d.library}) if not options.library else ():
        try:
            loaded[path] = load_library(replace(options, library=path))
        except UsageError:
            pass
    return loaded


def library_text(row: dict) -> str:
    """A bag's library as the table shows it: its file name, or 'packaged' ('-': none, its analysis failed first)."""
    if row.get("library_from") == "packaged":
        return "packaged"
    return Path(row["library"]).name if row.get("library") else "-"


def analyze_one(job: dict) -> dict:
    """One bag through the single-bag analysis (a worker's task: a job is its bag, its output prefix,
    the AnalyzeOptions and the WatchOptions of its model fit); returns its fleet-table row."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.offline.bag_analysis import analyze_bag
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.offline.bag_analysis import recorded_drive
    if _WORKER.get("options") != job["options"] or _WORKER.get("pid") != os.getpid():
        init_worker(job["options"])      # a worker started without the initializer (Dask)
    started = time.perf_counter()
    options = job["options"]
    watch = job.get("watch") or WatchOptions()
    row = {"bag": job["bag"], "drive": "", "time_s": math.nan, "width_m": math.nan,
           "fused_width_m": math.nan, "true_width_m": math.nan, "onsets": 0, "discarded": 0,
           "error": ""}
    # the bag's registered drive, known before its analysis (its topics' namespace, its first a1 chunk's drive
    # name): the drive's library gives its widths
    drive = None
    if watch.drives:
        namespace, name = recorded_drive(job["bag"], options.namespace, options.recover)
        drive = registered_drive(watch, {"namespace": namespace, "drive": name or Path(job["bag"]).stem})
    library_path = library_for_bag(options, drive)
    row.update(registry_drive=drive.hardware_id if drive else "", drive_version=drive.version if drive else "",
               drive_model=(drive.model or "default") if drive else "", library=library_path,
               library_from=("--library" if options.library else "registry" if library_path else "packaged"))
    try:
        library = bag_library(options, library_path)
    except UsageError as error:     # (only a registry's library: --library was loaded before any bag)
        row.update(drive=drive.hardware_id, error=f"drive {drive.hardware_id}'s library: {error}")
        return row
    row.update(library=library[0].path, library_created_utc=library[0].created_utc)
    try:
        result = analyze_bag(job["bag"], job["out"], options, library=library,
                             chunks_ahead=_WORKER["chunks_ahead"])
    except UsageError as error:
        row["error"] = str(error)
        return row
    row.update(recording_fields(job["bag"], result), seconds=time.perf_counter() - started)
    if watch.enabled and job.get("fit", True):     # (False: the pool's model-fit stage fits it, FitStage)
        row.update(model_fit(job["bag"], job["options"], watch, row))
    offsets = result.get("sensor_offsets", {})      # the drive's latest sensor offset estimate
    row.update(a1_offset_m_s2=offsets.get("a1_m_s2", math.nan),
               a2_offset_m_s2=offsets.get("a2_m_s2", math.nan),
               offset_implausible=sorted(k[:-len("_m_s2")] for k in offsets.get("implausible", {})))
    return row


def recording_fields(bag: str, result: dict) -> dict:
    """A bag's fields of the fleet table from its single-bag analysis (analyze_bag's result): drive, namespace,
    time, its width (the median continuous width of its primary signal's onset windows, with its uncertainty), the
    last fused width, the true width, onsets, discarded windows and the primary signal. The table, the trend and the
    model fit (of a folder's bag or of one bag) read these."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.classifier.fusion import fused_width_uncertainty_m
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.classifier.shape import continuous_top_m
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.classifier.signal_check import (BOTH_SIGNALS, LOAD_SIDE_SIGNAL, MOTOR_SIDE_SIGNAL,
                                                          a1_chain_checked, checked_width)
    rows = result["rows"]
    signals = {r["signal"] for r in rows}
    primary = PRIMARY_SIGNAL if PRIMARY_SIGNAL in signals else (sorted(signals)[0] if signals else "")

    def median_width(signal: str) -> tuple[list, float, float]:
        """The signal's rows, the median of their (continuous, else class) widths and its robust standard error."""
        mine = [r for r in rows if r["signal"] == signal]
        widths = [r["continuous_width_m"] if r["continuous_width_m"] == r["continuous_width_m"]
                  else r["width_m"] for r in mine]
        # the robust standard error of that median over the recording's onset windows (the events:
        # classifier/fusion.py); NaN where the mode gives no continuous width
        se = fused_width_uncertainty_m([r["continuous_width_m"] for r in mine],
                                       continuous_top_m(mine[0]["candidate_widths_m"]) if mine else math.inf)
        return mine, (statistics.median(widths) if widths else math.nan), se

    mine, width, se = median_width(primary)
    signal = primary
    chain = result.get("a1_chain")      # a1 against the recorded motor speed (None: the bag has none)
    if primary == BOTH_SIGNALS and MOTOR_SIDE_SIGNAL in signals:
        # checked against the motor side's, as the live estimate's fusion is (classifier/signal_check.py)
        _, motor_width, motor_se = median_width(MOTOR_SIDE_SIGNAL)
        check = checked_width(width, se, motor_width, motor_se)
        if LOAD_SIDE_SIGNAL in signals:
            # a2's where a1 does not follow the recorded motor speed (windowing/a1_chain.py)
            _, load_width, load_se = median_width(LOAD_SIDE_SIGNAL)
            check = a1_chain_checked(check, chain, load_width, load_se)
        width, se, signal = check.width_m, check.uncertainty_m, check.signal
    return dict(drive=result["drive"] or Path(bag).stem, namespace=result.get("namespace", ""),
                time_s=result["first_stamp_s"], width_m=width, width_uncertainty_m=se,
                fused_width_m=mine[-1]["fused_width_m"] if mine else math.nan,
                true_width_m=result["summary"]["true_width_m"],
                onsets=len({r["entry_sample_index"] for r in mine}),
                discarded=len(result["discarded"]), signal=signal,
                # a1 against the recorded motor speed (windowing/a1_chain.py; NaN / "": not checked or sound)
                a1_chain_mismatch=chain.mismatch if chain is not None else math.nan,
                a1_chain_fault=(chain.text() + (": its width is a2's" if signal == LOAD_SIDE_SIGNAL else "")
                                if chain is not None and chain.faulty else ""))


# ------------------------------------------------------------------------------------------- model fit

def recording_width_m(row: dict) -> float:
    """A bag's width [m]: the median continuous width of its windows where the mode gives one (wear shows as it
    grows), else its last fused class width (the paper's modes). The model fit's reference, the trend and the table
    read this one."""
    return row["width_m"] if row["width_m"] == row["width_m"] else row["fused_width_m"]


def _kept(kind: str, key, make):
    """What this worker process made once for ``key`` (``make()``), kept in its state: the model fit's references,
    default models and alarm rule, shared by all the worker's bags."""
    kept = _WORKER.setdefault(kind, {})
    if key not in kept:
        kept[key] = make()
    return kept[key]


def unmatched_text(rows: list, library, default_model_fit: bool) -> str:
    """The line that says which bags matched no drive of the registry (``rows``: each with ``bag``, ``drive``,
    ``namespace``), what their widths (``library``: None for the packaged one) and model fit came from instead, and
    what to do; one bag's analysis and a folder's say it alike."""
    came_from = (f"widths from {library or 'the packaged library'}"
                 + (", model fit against the default model" if default_model_fit else ""))
    advice = ("add it to the registry (docs/registry.md; `train --drive LINE/DRIVE` registers a version) or check its "
              "namespace")

    def named(r):
        return f"drive {r['drive']!r}, namespace {r.get('namespace') or '/'!r}"
    if len(rows) == 1:
        return f"{Path(rows[0]['bag']).name} matched no drive of the registry ({named(rows[0])}; {came_from}): {advice}"
    return (f"{len(rows)} bags matched no drive of the registry ({came_from}): "
            + ", ".join(f"{Path(r['bag']).name} ({named(r)})" for r in rows) + f"; for each, {advice}")


def registered_drive(watch: WatchOptions, row: dict):
    """The registry's drive (hardware_id, reference, nominal) a bag belongs to: by its topics' namespace
    (/LINE/DRIVE) or its recorded drive name (LINE/DRIVE); None when none matches or there is no registry."""
    for key in (row.get("namespace"), row.get("drive")):
        k = str(key or "").strip("/")
        for d in watch.drives if k else ():
            if d[0] == k:
                return d
    return None


def drive_model(nominal):
    """The default model at a registered drive's nominal (width_m, eta_k, n1), once per process."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.workbench.model import load_model
    w, eta_k, n1 = (float(x) for x in nominal)
    return _kept("drive_models", (w, eta_k, n1), lambda: load_model(None, width_m=w, eta_k=eta_k, n1=n1))


def reference_for_bag(options, watch: WatchOptions, width_m: float, row: dict | None = None) -> str:
    """The reference a bag's model fit takes (see --watch-reference): a path (may not exist yet: the default
    model's cache entry, built by the parent). ``options``: the bag's AnalyzeOptions (its library and n1);
    ``row``: the bag's row (its drive and namespace), matched to the registry's drives (--registry)."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.workbench import reference
    if watch.reference:
        return watch.reference
    drive = registered_drive(watch, row or {}) if watch.drives else None
    if drive is not None:
        return drive[1] or str(reference.cache_path(drive_model(drive[2])))
    if options.library:
        beside = reference.reference_path_for_library(options.library)
        if beside.is_file():
            return str(beside)
    return str(reference.cache_path(default_model(options.n1, width_m)))


def default_model(n1: float, width_m: float):
    """The default model at the pattern width nearest ``width_m`` (the drive's measured width), eta_k 0.025 and
    the drive's n1 (analyze's --n1): its reference covers +-40 % of that width (the width is profiled). Loaded
    once per process and (width, n1): a worker's bags share a few (~7 ms each to load and validate)."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.plant.scenarios import K2_WIDTHS_M
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.workbench.model import load_model
    w = width_m if width_m == width_m else 0.005
    nearest = min(K2_WIDTHS_M, key=lambda k: abs(k - w))
    n1 = float(n1 or 0.89)
    return _kept("default_models", (nearest, n1), lambda: load_model(None, width_m=nearest, eta_k=0.025, n1=n1))


def model_fit(bag: str, options, watch: WatchOptions, row: dict) -> dict:
    """The bag's model fit (watch/core.evaluate_recording) against its reference, judged by the folder's one-off
    rule (watch/alarm.load_folder_rule; docs/registry.md, "The folder's rule"); a missing reference or a bag
    that cannot be evaluated gives the reason instead. ``options``: the bag's AnalyzeOptions."""
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.watch.alarm import load_folder_config, load_folder_rule_from
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.watch.core import evaluate_recording
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.workbench import reference
    # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
    from backlash_monitor.workbench.measurement import MeasurementError, load_measurement
    width = recording_width_m(row)
    path = reference_for_bag(options, watch, width, row)
    out = {"model_fit_reference": path, "model_fit": "", "model_fit_level": "", "model_fit_ratio": math.nan}
    try:
        ref = _kept("references", path, lambda: reference.load(path))
    except reference.ReferenceError as error:
        out["model_fit"] = "no reference" if not Path(path).exists() else str(error)
        return out
    # the one-off rule (config/folder_model_fit.yaml: one test per bag, not the live watch's 14,400 an hour)
    cfg = _kept("folder_model_fit", None, load_folder_config)      # (its YAML: ~5 ms a bag)
    rule = _kept("alarm_rules", None, lambda: load_folder_rule_from(cfg))
    try:
        meas = load_measurement(bag, options.namespace or None)
        fit = evaluate_recording(meas, ref, rule, window_events=cfg["window_events"])
    except (MeasurementError, ValueError, RunFailure) as error:     # (RunFailure: a damaged bag, even with --recover:
        out["model_fit"] = f"not evaluated: {error}"                # the fit reads the whole recording, no gap)
        return out
    out.update(model_fit=fit, model_fit_level=fit["level"], model_fit_ratio=fit["residual_over_noise"])
    return out


def model_fit_text(r: dict) -> str:
    fit = r.get("model_fit")
    if not fit:
        return "-"
    if isinstance(fit, str):
        return fit if len(fit) < 40 else fit[:37] + "..."
    text = f"{fit['level']} {fit['residual_over_noise']:.1f}x"
    if fit["level"] != "OK":
        where = ", ".join(x for x in (fit["phase"].replace("_", " "), fit["wavelet_level"]) if x)
        text += f" ({where})" if where else ""
    return text


def missing_references(rows: list[dict], options, watch: WatchOptions, log=print) -> list[dict]:
    """Build the default model's references the workers did not find (once, into the cache); the rows they
    concern, to evaluate again. ``options``: the AnalyzeOptions (their n1)."""
    again, built = [], set()
    for r in rows:
        if r.get("model_fit") == "no reference" and not watch.reference:
            # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
            from backlash_monitor.workbench import reference     # (only then: ~0.2 s of imports)
            width = recording_width_m(r)
            drive = registered_drive(watch, r) if watch.drives else None
            model = drive_model(drive[2]) if drive is not None else default_model(options.n1, width)
            path = str(reference.cache_path(model))
            if path not in built:
                # under a lock beside the cache entry: another analyze (or test) building the same waits, then
                # loads it (files/locks.py; test/shared_cache.py takes the same lock)
                with exclusive(path + ".lock"):
                    reference.cached(model, log=lambda text: log(f"analyze: {text}"))
                built.add(path)
            again.append(r)
    return again


FIT_FIELDS = ("model_fit", "model_fit_level", "model_fit_ratio", "model_fit_reference", "width_caveat")


def one_bag_fit(bag: str, options, watch: WatchOptions, result: dict, log=print) -> dict:
    """`analyze BAG`'s model fit: the bag held against the reference the analysis of a folder holding it would take
    (reference_for_bag: --watch-reference, its --registry drive's, LIB.watch.npz beside --library, else the default
    model's cache entry at the pattern width nearest its measured width), judged by the folder's one-off rule
    (model_fit); the default model's reference, when it is not in the cache yet, built there once first
    (missing_references: ~30-60 s of one core, said by a line through ``log``). ``result``: the bag's analysis
    (analyze_bag's). -> the fields a folder's row has (FIT_FIELDS): the fit (its dict, or why there is none), its
    level and residual ratio, the reference and the width's caveat (fleet/caveat.py; "" when the model explains the
    drive or there is no fit)."""
    if not watch.enabled:
        return {"model_fit": "not run (--no-model-fit)", "model_fit_level": "", "model_fit_ratio": math.nan,
                "model_fit_reference": "", "width_caveat": ""}
    row = recording_fields(bag, result)
    fields = model_fit(bag, options, watch, row)
    if fields["model_fit"] == "no reference" and missing_references([{**row, **fields}], options, watch, log=log):
        fields = model_fit(bag, options, watch, row)
    return {**fields, "width_caveat": caveat(FitVerdict.from_recording(fields["model_fit"]))}


def _jobs(options, bags: list[Path], out_dir: Path, watch: WatchOptions | None = None) -> list[dict]:
    """{"bag", "out", "options", "watch"} per bag: its path, its output prefix in ``out_dir``, the
    AnalyzeOptions and the WatchOptions (model fit) every bag shares."""
    jobs, used = [], set()
    for b in bags:
        name = b.stem + ".estimates"      # analyze's own default name, in DIR
        while name in used:
            name += "_"
        used.add(name)
        jobs.append({"bag": str(b), "out": str(out_dir / name), "options": options,
                     "watch": watch or WatchOptions()})
    return jobs


_THREADS_LIMITED_FIRST: list[bool] = []   # whether limit_threads' first call came before numpy's import


def limit_threads() -> bool:
    """One thread per pool (BLAS, OpenMP, numba) in this process and the processes it starts;
    True when it takes effect here too (numpy not imported yet when it was first called: OpenBLAS
    reads it at import). Called again, it answers as it did the first time: the command calls it
    before it parses the analysis options (which import numpy), run_many once more."""
    for var in THREAD_VARIABLES:
        os.environ.setdefault(var, "1")
    if not _THREADS_LIMITED_FIRST:
        _THREADS_LIMITED_FIRST.append("numpy" not in sys.modules)
    return _THREADS_LIMITED_FIRST[0]


def runs_parallel_here(fleet: FleetOptions) -> bool:
    """Whether the bags run in a pool of processes forked from this one (--engine local, --jobs > 1): its
    threads are limited (limit_threads) before numpy is imported, so that the forked workers inherit it."""
    return fleet.engine == "local" and fleet.workers() > 1


class _NoBar:
    def update(self, n: int = 1) -> None:
        pass

    def close(self) -> None:
        pass


def progress_bar(total: int, progress: bool):
    """A progress bar over the bags on stderr when it is a terminal (as tqdm's own default: no bar written into a
    log or a pipe), else one that draws nothing (and tqdm, ~55-80 ms of imports, not imported)."""
    if not progress or not sys.stderr.isatty():
        return _NoBar()
    # deferred: tqdm costs ~55 ms at start-up (python -X importtime, 29 Nov); every --help imports this module
    from tqdm import tqdm
    return tqdm(total=total, unit="bag", desc="analyze")


def run_local(jobs: list[dict], n_jobs: int, library=None, progress=True,
              threads_limited: bool | None = None, libraries: dict | None = None) -> list[dict]:
    """The bags on this machine: --jobs 1 one after the other in this process; otherwise a pool of
    ``n_jobs`` worker processes, started once (each with its library, :func:`init_worker`), handed
    one bag at a time (a worker takes the next bag when it is done: no idle core while bags remain),
    their rows collected as they finish."""
    rows = []
    if n_jobs == 1:
        bar = progress_bar(len(jobs), progress)
        if jobs:
            init_worker(jobs[0]["options"], library, libraries)
        for job in jobs:
            rows.append(analyze_one(job))
            bar.update()
        bar.close()
        return rows
    if threads_limited is None:
        threads_limited = limit_threads()
    # Workers forked from this process start at once, with the chain's modules imported and the
    # library loaded; a fresh interpreter per worker would import numpy, pywt and the bag reader
    # again before its first bag. The thread pools are limited to one thread per worker before
    # numpy is imported (its OpenBLAS starts its threads then); where numpy was imported before
    # with more threads, a forkserver with the limits set in its environment starts the workers.
    modules = ["backlash_monitor.bag", "backlash_monitor.chain",
               "backlash_monitor.offline.bag_analysis", "backlash_monitor.estimation"]
    if threads_limited and "fork" in multiprocessing.get_all_start_methods():
        for name in modules:
            importlib.import_module(name)
        context = multiprocessing.get_context("fork")
        gc.freeze()     # (the workers' garbage collector leaves what they inherit alone: no page copied for it)
    else:
        context = multiprocessing.get_context("forkserver")
        context.set_forkserver_preload(modules)
        library = libraries = None          # loaded by each worker
    options = jobs[0]["options"] if jobs else None
    # the model fits in a stage of their own (FitStage) where the workers are forked: its one-time work (its
    # modules, alarm rule, references and their views: ~1 s of a core) done once here, beside the analyses,
    # instead of once in every worker before its first fit
    fits = FitStage(n_jobs, context) if context.get_start_method() == "fork" and any(
        (j.get("watch") or WatchOptions()).enabled for j in jobs) else None
    with ProcessPoolExecutor(max_workers=n_jobs, mp_context=context, initializer=init_worker,
                             initargs=(options, library, libraries)) as pool:
        # every bag handed to the pool at once (its manager thread feeds the workers: one bag at a
        # time each, so none is idle while bags remain, also while this process fits a bag)
        futures = {pool.submit(analyze_one, {**job, "fit": fits is None}): job for job in jobs}
        if fits is not None:
            fits.prepare()
        bar = progress_bar(len(jobs), progress)   # (while the workers start)
        pending = set(futures)
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                rows.append(future.result())
                bar.update()
                if fits is not None:
                    fits.add(rows[-1], futures[future], analysing=len(pending))
    bar.close()
    if fits is not None:
        fits.finish()
    return rows


def fit_one(job: dict) -> dict:
    """One bag's model fit (a FitStage worker's task: its bag, AnalyzeOptions, WatchOptions and the row fields the
    fit reads); the model-fit fields of its row."""
    return model_fit(job["bag"], job["options"], job["watch"], job["row"])


class FitStage:
    """The model fits of a pool's bags (--jobs N, forked workers), beside the analyses: this process fits the
    first bag of each reference itself as its row comes (importing the fit's modules while the analyses start,
    loading the alarm rule, the reference and its views once), then forks ``n_jobs`` workers that inherit all of
    it and fit the rest. Without it each analysis worker imported, loaded and built the same before its first fit:
    ~1 s of a core per worker (python bench/fleet.py --parts analyze, docs/fleet.md). A reference first met after
    the fork is loaded by the workers that need it (as before)."""

    def __init__(self, n_jobs: int, context):
        self.n_jobs, self.context = n_jobs, context
        self.warm: set[str] = set()         # the references this process has fitted a bag against
        self.waiting: list[tuple] = []      # (row, job) whose fit waits for the workers
        self.futures: dict = {}
        self.pool = None

    def prepare(self) -> None:
        """The fit's modules imported here (while the analysis workers start), and the allocator's setting of the
        analyses (process/memory.py: freed blocks reused, not a page fault per 4 KiB of the next bag's arrays) made
        here, so that the fit workers inherit it as a worker fitting after its analysis had it."""
        # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
        from backlash_monitor.process.memory import reuse_freed_memory
        reuse_freed_memory()
        for name in ("backlash_monitor.watch.core", "backlash_monitor.watch.alarm",
                     "backlash_monitor.workbench.reference", "backlash_monitor.workbench.measurement",
                     "backlash_monitor.workbench.model"):
            importlib.import_module(name)

    def add(self, row: dict, job: dict, analysing: int) -> None:
        """A bag's row from the analysis: fitted here when its reference is new (before the fork), else handed
        to the workers; they start once there are a few bags to fit per worker or no analysis is left."""
        watch = job.get("watch") or WatchOptions()
        if row["error"] or not watch.enabled:
            return
        if self.pool is None:
            width = recording_width_m(row)
            path = reference_for_bag(job["options"], watch, width, row)
            if path not in self.warm:
                self.warm.add(path)
                row.update(model_fit(job["bag"], job["options"], watch, row))
                return
        self.waiting.append((row, job))
        if self.pool is None and (len(self.waiting) >= 2 * self.n_jobs or not analysing):
            self.start()
        if self.pool is not None:
            for row, job in self.waiting:
                fields = {k: row.get(k) for k in ("width_m", "fused_width_m", "drive", "namespace")}
                self.futures[self.pool.submit(fit_one, {"bag": job["bag"], "options": job["options"],
                                                        "watch": job.get("watch") or WatchOptions(),
                                                        "row": fields})] = row
            self.waiting = []

    def start(self) -> None:
        """The fit workers forked: this process's objects frozen first (gc.freeze: the workers' garbage collector
        leaves the inherited ones alone, and does not copy every page that holds one by writing to it)."""
        gc.freeze()
        self.pool = ProcessPoolExecutor(max_workers=self.n_jobs, mp_context=self.context)

    def finish(self) -> None:
        """Every fit handed out, done: its fields in its row."""
        if self.waiting:
            if self.pool is None:
                self.start()
            self.add(*self.waiting.pop(), analysing=0)
        try:
            for future, row in self.futures.items():
                row.update(future.result())
        finally:
            if self.pool is not None:
                self.pool.shutdown()


def run_dask(jobs: list[dict], n_jobs: int, scheduler: str, progress=True) -> list[dict]:
    try:
        # deferred: optional: dask.distributed may be missing (the ImportError is handled here)
        from dask.distributed import Client, LocalCluster, as_completed
    except ImportError:
        raise UsageError("--engine dask needs the optional extra: pip install dask distributed "
                         "(or use --engine local)") from None
    # deferred: tqdm costs ~55 ms at start-up (python -X importtime, 29 Nov); every --help imports this module
    from tqdm import tqdm
    cluster = None
    if scheduler:
        client = Client(scheduler)
    else:
        cluster = LocalCluster(n_workers=n_jobs, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    rows = []
    try:
        futures = client.map(analyze_one, jobs, pure=False)
        for future in tqdm(as_completed(futures), total=len(jobs), unit="bag",
                           disable=not progress, desc="analyze (dask)"):
            rows.append(future.result())
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    return rows


def add_trends(rows: list[dict], rule) -> dict:
    """Each drive's trend over its rows; each row's level and reason, the reason with the model-fit caveat of
    that row's recording (fleet/caveat.py: a width alarm never stands alone when the model fit fails)."""
    points: dict[str, list] = {}
    for r in rows:
        if not r["error"]:
            # the recording's width (median continuous width of its windows) where the mode gives one:
            # wear shows as it grows, not as a jump between candidate widths
            width = recording_width_m(r)
            points.setdefault(r["drive"], []).append((r["time_s"], width))
    trends = {drive: drive_trend(pts, rule) for drive, pts in points.items()}
    for r in rows:
        t = trends.get(r["drive"])
        r["trend_m_per_day"] = math.nan if t is None else t.rate_m_per_day
        r["level"] = "ERROR" if r["error"] else t.level
        r["reason"] = r["error"] or with_caveat(t.reason, FitVerdict.from_recording(r.get("model_fit")))
    return points, trends


TABLE = ("drive", "time", "width", "fused width", "trend", "level", "model fit", "version", "library", "bag")


def format_rows(rows: list[dict]) -> list[tuple]:
    def mm(x):
        return "-" if x != x else f"{x * 1e3:.2f} mm"
    out = []
    for r in rows:
        when = ("-" if r["time_s"] != r["time_s"] else
                datetime.fromtimestamp(r["time_s"], timezone.utc).strftime("%Y-%m-%d %H:%M:%S"))
        trend = ("-" if r["trend_m_per_day"] != r["trend_m_per_day"]
                 else f"{r['trend_m_per_day'] * 1e3:+.3f} mm/day")
        # the width with its uncertainty and, when the bag's model fit fails, the caveat in the same cell
        width = with_caveat(width_text(r["width_m"], r.get("width_uncertainty_m", math.nan)),
                            FitVerdict.from_recording(r.get("model_fit")))
        version = f"v{r['drive_version']}" if r.get("drive_version") else "-"    # its registered drive's
        out.append((r["drive"] or "?", when, width, mm(r["fused_width_m"]), trend,
                    r["level"], model_fit_text(r), version, library_text(r),
                    Path(r["bag"]).name))
    return out


def run_many(fleet: FleetOptions, options: AnalyzeOptions) -> int:
    """The many-bag `analyze`: ``fleet`` its FleetOptions (the bags, the output folder, the engine,
    the model fit's WatchOptions), ``options`` the AnalyzeOptions of every bag."""
    bags = expand_bags(fleet.bags)
    fleet.check()
    n_jobs = fleet.workers()
    # before numpy is imported here: forked workers inherit this process's thread pools
    threads_limited = limit_threads() if runs_parallel_here(fleet) else None
    out_dir = Path(fleet.out) if fleet.out else bags[0].parent / "fleet_analysis"
    out_dir.mkdir(parents=True, exist_ok=True)
    try:
        rule = load_rule(fleet.trend_config or None)
    except (OSError, KeyError, TypeError, ValueError) as error:
        raise UsageError(f"trend config {fleet.trend_config or 'config/trend.yaml'}: {error}; it "
                         "needs warn_growth_m_per_day, warn_width_m, error_width_m") from None
    watch = fleet.watch
    jobs = _jobs(options, bags, out_dir, watch)
    started = time.perf_counter()
    # this process's CPU before, during and after the bags, and its workers' (children's): the serial part
    # (before + after) and the parallel part of the run (bench/fleet.py --parts analyze reports them)
    cpu_before = time.process_time()
    if fleet.engine == "dask":
        rows = run_dask(jobs, n_jobs, fleet.scheduler, progress=fleet.progress)
    else:
        # the options checked and the library loaded once, here: a bad option is one error
        # before any worker starts, and forked workers inherit the library
        # deferred: numpy not imported before limit_threads() (the forked workers inherit its thread limit)
        from backlash_monitor.offline.bag_analysis import load_library
        rows = run_local(jobs, n_jobs, library=load_library(options), progress=fleet.progress,
                         threads_limited=threads_limited, libraries=registry_libraries(options, watch))
    cpu_during = time.process_time() - cpu_before
    if watch.enabled:
        for r in missing_references(rows, options, watch):
            r.update(model_fit(r["bag"], options, watch, r))
    wall = time.perf_counter() - started
    rows.sort(key=lambda r: (r["drive"], r["time_s"] if r["time_s"] == r["time_s"] else 0.0,
                             r["bag"]))
    points, trends = add_trends(rows, rule)
    columns = ("drive", "time_s", "width_m", "fused_width_m", "trend_m_per_day", "level",
               "reason", "model_fit_level", "model_fit_ratio", "true_width_m", "onsets", "discarded", "bag",
               "a1_offset_m_s2", "a2_offset_m_s2", "width_uncertainty_m", "width_caveat", "signal",
               "a1_chain_mismatch",
               # what the bag was held against: its registered drive and version, the model and library
               "registry_drive", "drive_version", "drive_model", "library", "library_created_utc", "library_from",
               "model_fit_reference")
    for r in rows:
        r["width_caveat"] = caveat(FitVerdict.from_recording(r.get("model_fit")))
    with open(out_dir / "fleet.csv", "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(columns)
        for r in rows:
            writer.writerow([r.get(c, "") for c in columns])
    children = resource.getrusage(resource.RUSAGE_CHILDREN)     # the pools' workers, ended and waited for
    cpu_s = {"this_process_before_bags": cpu_before, "this_process_during_bags": cpu_during,
             "this_process_after_bags": time.process_time() - cpu_before - cpu_during,   # (until this file)
             "workers": children.ru_utime + children.ru_stime}
    with open(out_dir / "fleet.json", "w", encoding="utf-8") as f:
        f.write(json.dumps({"bags": len(bags), "engine": fleet.engine, "jobs": n_jobs,
                            "seconds": wall, "cpu_s": cpu_s, "rows": rows,
                            "trends": {d: t.__dict__ for d, t in trends.items()}}))
    plots = [] if not fleet.plots or not points else plot_trends(points, trends, rule, out_dir)
    table = [TABLE] + format_rows(rows)
    widths = [max(len(row[i]) for row in table) for i in range(len(TABLE))]
    for i, row in enumerate(table):
        print("  ".join(c.ljust(w) for c, w in zip(row, widths)).rstrip())
        if i == 0:
            print("  ".join("-" * w for w in widths))
    failed = [r for r in rows if r["error"]]
    for r in failed:
        print(f"{Path(r['bag']).name}: {r['error']}")
    warned = sorted(d for d, t in trends.items() if t.level != "OK")
    for d in warned:
        last = [r for r in rows if r["drive"] == d and not r["error"]]
        fit = FitVerdict.from_recording(last[-1].get("model_fit")) if last else None
        print(f"{d}: {trends[d].level}: {with_caveat(trends[d].reason, fit)}")
    for r in rows:
        fit = r.get("model_fit")
        if isinstance(fit, dict) and fit["level"] != "OK":
            print(f"{r['drive']}: model {fit['model']} does not explain {Path(r['bag']).name} (residual "
                  f"{fit['residual_over_noise']:.1f}x the noise floor; {', '.join(fit['exceeding'])}): run diagnose "
                  "on it")
        for signal in r.get("offset_implausible", []):
            print(f"{Path(r['bag']).name}: WARN: sensor offset {signal} "
                  f"{r[signal + '_offset_m_s2']:+.2f} m/s^2 beyond what a MEMS sensor shows "
                  "(config/windowing.yaml sensor_offset): check the sensor (the widths are offset-free)")
        if r.get("a1_chain_fault"):
            print(f"{Path(r['bag']).name}: WARN: {r['a1_chain_fault']}; check a1's sensor chain (and the drive-wheel "
                  "radius r) before trusting a1 (docs/classifier.md 5.4)")
    if watch.drives and options.library:
        overridden = sorted({d.hardware_id for d in watch.drives if d.library})
        if overridden:
            print(f"--library {options.library}: every bag's widths from it, not from the registry's libraries of "
                  f"{len(overridden)} drives ({', '.join(overridden)}); without --library each bag takes its drive's")
    if watch.drives:
        unmatched = [r for r in rows if not r["error"] and not r.get("registry_drive")]
        if unmatched:
            print(unmatched_text(unmatched, options.library, watch.enabled))
    print(f"analysed {len(bags)} bags of {len(points)} drives in {wall:.1f} s on {n_jobs} "
          f"{'worker' if n_jobs == 1 else 'workers'} ({fleet.engine}); wrote {out_dir / 'fleet.csv'}"
          f", .json{', ' + str(len(plots)) + ' plots' if plots else ''}")
    return 1 if failed else 0
