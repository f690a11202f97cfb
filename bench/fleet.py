"""A fleet of drives on this machine (prints one JSON object; progress on stderr).

drives_realtime: the most 50 kHz simulated drives `fleet` runs in real time with every drive
  monitored in real time (every chunk taken, no window discarded, every onset window classified,
  each estimate within 1 s of its window's last sample after the start-up), for each layout (one
  process per drive; every drive in one process), N = 2, 4, 6, ... until a run fails; with the CPU
  per drive (plant simulator + chain, share of one core, over the stream) at that N, and the
  whole command's CPU seconds per drive (every process, start-up and the fleet monitor included). The drives' plants run on the
  same machine: a real line's drives would not cost this machine their simulation.
diagnostics_complete: over a 60 s window of a run of that many drives, the share of
  (drive, second) pairs for which the drive's classifier status arrived on /diagnostics (each
  drive's 1 Hz status at its own phase, within +-0.5 s of its second: status_share).
fleet_analyze_speedup: `analyze FOLDER` (its model fit on, the references built before) on 100 recorded bags
  (3 s each, simulated: 12 onsets per bag), `--jobs 1` pinned to ONE CPU (os.sched_setaffinity: one core is one core; unpinned,
  the bag reader's decompression thread would use the second) vs `--jobs <cores>` on all CPUs,
  each the whole command with its start-up, alternated --analyze-repeats times: the median of the
  side-by-side pairs' ratios (each pair within seconds: this VM's capacity moves from minute to
  minute, two pinned busy loops get 1.3-2.1x of one), with the ratio of the best times of each side
  (fleet_analyze_speedup_best_of), each pair's ratio and the load average before each run. From CPU accounting
  (the command's fleet.json cpu_s): fleet_analyze_serial_fraction (the many-worker run's CPU outside the bags over
  the one-core run's CPU), the parallel run's extra CPU and the speed-up both allow on idle cores.
two_host_estimates_delivered: plant and monitor in one network namespace, the chain in another
  (veth pair, DDS on exactly those two addresses): onset estimates received back / onset windows.

The machine is shared with other jobs; load_average says how busy it was: real-time capacity
measured on a busy machine is a lower bound.

    python bench/fleet.py [--quick] [--parts capacity diagnostics analyze two_host]
    python bench/fleet.py --parts analyze                         # only the analysis speed-up
    python bench/fleet.py --parts capacity --layouts process single --counts 8 10
    python bench/fleet.py --parts capacity --layouts process --watch both     # without and with the model watch
    python bench/fleet.py --parts model_fit [--compare-default]    # the registry's per-drive model fit
    python bench/fleet.py --parts model_fit_null [--null-own-s 45 --null-foreign-s 45]   # the folder rule on healthy bags
    python bench/fleet.py --parts registry_loop                   # a live fleet picks up one drive's new version
fleet_model_fit_false_warn / fleet_model_fit_detected: `analyze FOLDER --registry` on 12 healthy foreign drives of
  different nominal conditions and 6 foreign drives with effects, each registered at its own nominal (docs/registry.md):
  model-fit WARNs on the healthy ones, and the share of the others with a WARN.
model_fit_null (--parts model_fit_null): the folder rule's false-WARN rate (config/folder_model_fit.yaml): healthy
  own-simulator drives at the model_fit part's 15 nominal conditions and its 12 healthy foreign rows on other seeds,
  cut into disjoint 4.5 s bags (one test each; bench/_fleet/model_fit_null.py), with the WARNs, their 95 % bound and
  the statistics' null distribution; --null-rows-out keeps every bag's statistics for any other rule.
registry_loop_pickup_s / registry_loop_changed_drives / registry_loop_other_drives_missed_onsets: a live fleet of 8
  drives picks up one drive's new version registered while it runs (bench/_fleet/registry_loop.py).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.setdefault("ROS_DOMAIN_ID", str(os.getpid() % 90 + 5))


def log(*args):
    print(*args, file=sys.stderr, flush=True)


WITH_WATCH = "_watch"      # a capacity variant's suffix: the layout with `fleet --model-watch` (a model watch per drive)


def run_fleet(n, layout, duration_s, workdir):
    """The `fleet` command's summary, with ``command_cpu_s`` (CPU of the command and every process
    it started, start-up included: rusage of the waited-for children) and ``command_wall_s``."""
    import resource
    summary = os.path.join(workdir, f"fleet_{layout}_{n}.json")
    watch = ["--model-watch"] if layout.endswith(WITH_WATCH) else []
    layout = layout[:-len(WITH_WATCH)] if watch else layout
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    started = time.perf_counter()
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "fleet", "--drives", str(n),
                           "--duration", str(duration_s), "--layout", layout,
                           "--view-period", "0", "--json", summary, *watch],
                          capture_output=True, text=True, timeout=duration_s * 4 + 300)
    wall = time.perf_counter() - started
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if not os.path.isfile(summary):
        log(proc.stdout[-2000:], proc.stderr[-2000:])
        return None
    with open(summary) as f:
        result = json.load(f)
    result.update(command_wall_s=wall, command_cpu_s=after.ru_utime + after.ru_stime
                  - before.ru_utime - before.ru_stime)
    return result


def capacity_alternated(layouts, counts, duration_s, workdir):
    """:func:`capacity` of each layout, their runs alternated at each N (layout A at N, layout B
    at N, then the next N): both see the machine's load of the same minutes. A layout stops at its
    first failed N."""
    per_layout = {name: {"drives_realtime": 0, "runs": [], "failed": False} for name in layouts}
    for n in counts:
        for name in layouts:
            entry = per_layout[name]
            if entry["failed"]:
                continue
            best, runs = capacity(name, [n], duration_s, workdir)
            entry["runs"].extend(runs)
            if best:
                entry["drives_realtime"] = best
            else:
                entry["failed"] = True
    return per_layout


def capacity(layout, counts, duration_s, workdir):
    best, runs = 0, []
    for n in counts:
        load_before = os.getloadavg()[0]
        result = run_fleet(n, layout, duration_s, workdir)
        rows = result["drives"] if result else []
        ok = bool(rows) and all(r["realtime"] for r in rows)
        cpu = [r["cpu_percent"] for r in rows if r["cpu_percent"] == r["cpu_percent"]]
        lag = [r["lag_ms_max"] for r in rows if r["lag_ms_max"] == r["lag_ms_max"]]
        run = {"drives": n, "realtime_drives": sum(r["realtime"] for r in rows),
               "discarded": sum(r["discarded"] for r in rows),
               # the first onset of a stream has no sensor offset estimate yet: not classified, not missed
               "onsets_missed": sum(r["onset_windows"] - r.get("onsets_before_offset", 0)
                                    - r["onsets_estimated"] for r in rows),
               "lag_ms_max": max(lag) if lag else None,
               "cpu_percent_per_drive": sum(cpu) / len(cpu) if cpu else None,
               "command_cpu_s_per_drive": result["command_cpu_s"] / n if result else None,
               "command_wall_s": result["command_wall_s"] if result else None,
               "load_average_1min_before": load_before,
               "load_average_1min": os.getloadavg()[0]}
        runs.append(run)
        log(f"fleet {layout} {n} drives: {run}")
        if not ok:
            break
        best = n
    return best, runs


def status_share(rows, window_s):
    """Share of (drive, second) pairs with the drive's classifier status: from the moment every
    drive publishes, each drive's 1 Hz status has ``window_s`` slots at its own phase (its first
    status there + k seconds); a slot is filled by a status arriving within +-0.5 s of it."""
    if not rows or not all(r["status_times"] for r in rows):
        return 0.0
    t_start = max(min(r["status_times"]) for r in rows)
    filled = 0
    for r in rows:
        times = sorted(t for t in r["status_times"] if t >= t_start)
        slots = {round(t - times[0]) for t in times if t - times[0] < window_s - 0.5}
        filled += len(slots)
    return filled / (len(rows) * window_s)


def diagnostics_complete(n, layout, workdir, window_s=60):
    result = run_fleet(n, layout, window_s + 10, workdir)
    return status_share(result["drives"] if result else [], window_s)


def analyze_speedup(workdir, n_bags=100, repeats=7, bag_s=3.0):
    """`analyze FOLDER --jobs 1` on ONE core vs `--jobs <cores>` on all of them, each the command
    as a user runs it (start-up included), alternated ``repeats`` times; the median of the pairs'
    ratios (side by side), and the ratio of each side's best time.

    One core means one core: the `--jobs 1` process is pinned to one CPU (os.sched_setaffinity,
    the CPUs taken in turn over the repeats); unpinned, its bag reader's decompression thread runs
    on the second core (1.1 cores busy), which is not a one-core baseline."""
    from backlash_monitor.fleet.recordings import write_fleet_bags
    import compileall
    # the package byte-compiled, as installed (make setup, pip, colcon): neither run compiles sources
    compileall.compile_dir(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..",
                                        "backlash_monitor"), quiet=1)
    bag_dir = os.path.join(workdir, "bags")
    widths = (0.0025, 0.005, 0.0075, 0.009)
    recordings = [(f"line{1 + i // 20}/drive{i % 20 + 1:02d}", i // 20, widths[i % 4], i + 1)
                  for i in range(n_bags)]
    started = time.perf_counter()
    write_fleet_bags(bag_dir, recordings, duration_s=bag_s)
    log(f"wrote {n_bags} bags of {bag_s:g} s in {time.perf_counter() - started:.1f} s")
    # the model fit's references (the default model's at each width, the cache) built before the timed runs: a
    # missing one is built by the command once, serially (~30 s each), which is not the analysis measured here
    from backlash_monitor.workbench import reference
    from backlash_monitor.workbench.model import load_model
    for w in sorted(set(widths)):
        reference.cached(load_model(None, width_m=w, eta_k=0.025, n1=0.89),
                         log=lambda text: log(f"reference: {text}"))
    cpus = sorted(os.sched_getaffinity(0))
    cores = len(cpus)
    import resource
    runs = {"one_core": [], "cores": []}
    work_ratio = []
    for repeat in range(repeats):
        work_ratio.append(parallel_work_ratio())
        log(f"machine: {cores} pinned busy loops do {work_ratio[-1]:.2f}x the work of one")
        for label, n_jobs in (("one_core", 1), ("cores", cores)):
            out = os.path.join(workdir, f"out_{label}_{repeat}")   # fresh: no --overwrite
            cpu_pin = cpus[repeat % cores] if n_jobs == 1 else None
            load = os.getloadavg()[0]
            started = time.perf_counter()
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", bag_dir,
                                   "--out-dir", out, "--jobs", str(n_jobs), "--no-plots"],
                                  capture_output=True, text=True, timeout=1800,
                                  preexec_fn=(None if cpu_pin is None else
                                              lambda: os.sched_setaffinity(0, {cpu_pin})))
            wall = time.perf_counter() - started
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
            # the command's own CPU accounting (fleet.json cpu_s): its process before and after the bags (with the
            # interpreter's start and what follows fleet.json: the serial part) and during them, its workers
            try:
                split = json.load(open(os.path.join(out, "fleet.json")))["cpu_s"]
            except (OSError, KeyError, ValueError):
                split = {}
            parallel = split.get("this_process_during_bags", 0.0) + split.get("workers", 0.0)
            serial = cpu - parallel if n_jobs > 1 and split else None
            runs[label].append({"wall_s": wall, "cpu_s": cpu, "cores_busy": cpu / wall,
                                "cpu": "all" if cpu_pin is None else cpu_pin,
                                "load_average_1min": load, "exit": proc.returncode,
                                "command_cpu_s": split, "serial_cpu_s": serial})
            log(f"analyze {n_bags} bags, --jobs {n_jobs} on "
                f"{'CPU ' + str(cpu_pin) if cpu_pin is not None else str(cores) + ' CPUs'}: "
                f"{wall:.2f} s, CPU {cpu:.2f} s ({cpu / wall:.2f} cores busy)"
                + (f", serial CPU {serial:.2f} s" if serial is not None else "")
                + f", exit {proc.returncode}, load {load:.2f}")
            if proc.returncode != 0:
                log(proc.stdout[-2000:], proc.stderr[-2000:])
    best = {k: min(r["wall_s"] for r in v) for k, v in runs.items()}
    pairs = [a["wall_s"] / b["wall_s"] for a, b in zip(runs["one_core"], runs["cores"])]
    import statistics
    # Amdahl from CPU accounting, pair by pair: the serial fraction f = the many-worker run's serial CPU (its
    # command process outside the bags) over the one-core run's CPU; the extra CPU the parallel run spends
    # (work done in every worker, contention of the cores); the speed-up they allow on idle cores:
    # T1 / (serial + (T1 - serial + extra) / cores)
    serial_fraction = [b["serial_cpu_s"] / a["cpu_s"] for a, b in zip(runs["one_core"], runs["cores"])
                       if b["serial_cpu_s"] is not None]
    extra = [(b["cpu_s"] - a["cpu_s"]) / a["cpu_s"] for a, b in zip(runs["one_core"], runs["cores"])]
    bound = [a["cpu_s"] / (b["serial_cpu_s"] + (b["cpu_s"] - b["serial_cpu_s"]) / cores)
             for a, b in zip(runs["one_core"], runs["cores"]) if b["serial_cpu_s"] is not None]
    med = statistics.median
    return statistics.median(pairs), {"runs": runs, "pair_ratios": pairs,
                                      "best_of": best["one_core"] / best["cores"],
                                      "machine_parallel_work_ratio": work_ratio,
                                      "serial_fraction": med(serial_fraction) if serial_fraction else None,
                                      "parallel_extra_cpu_fraction": med(extra),
                                      "speedup_from_cpu_accounting": med(bound) if bound else None}, cores


# the registry's model fit (fleet_model_fit_false_warn, fleet_model_fit_detected): foreign drives (foreign_drives/,
# an independent simulator), each in its own namespace fleetA/dNN and registered at its own nominal conditions
EXTRA_HEALTHY = (("clean_w4.0_eta0.03_n0.92", 0.004, 0.03, 0.92), ("clean_w8.5_eta0.02_n0.94", 0.0085, 0.02, 0.94))
EFFECT_LABELS = ("mass_+0.3", "spring_+0.5", "absorber_eta_+0.6", "wheel_drag_quadratic_1.2Nm",
                 "clutch_hunt_crossley_+0.6", "gain_a2_+0.15")


def registry_model_fit(workdir, duration_s=5.0, compare_default=False):
    """`analyze FOLDER --registry` on >= 12 healthy foreign drives of different nominal conditions (the bench
    suite's clean rows and two more) and 6 with effects diagnose finds: WARNs on the healthy ones (false) and on
    the sick ones (detected). Each drive is registered with its own nominal (width, eta_k, n1): its reference is
    the default model's at those conditions (built into the cache once when missing: ~30 s each)."""
    import dataclasses
    import yaml
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    from foreign_drives.drive import make_recording
    from foreign_drives.files import write_bag
    from foreign_drives.suites import suite
    bench = {s.label: s for s in suite("bench")}
    healthy = _healthy_specs()
    sick = [bench[label] for label in EFFECT_LABELS]
    # healthy and sick by the recordings' truth (the effects simulated), not by what the rule says
    assert all(not s.effects for s in healthy) and all(s.effects for s in sick)
    bag_dir = os.path.join(workdir, "registry_bags")
    os.makedirs(bag_dir, exist_ok=True)
    lines, kinds = {"fleetA": {}}, {}
    started = time.perf_counter()
    for i, s in enumerate(healthy + sick):
        name = f"d{i + 1:02d}"
        spec = dataclasses.replace(s, namespace=f"fleetA/{name}", drive_name=f"fleetA/{name}",
                                   duration_s=duration_s).check()
        write_bag(spec, os.path.join(bag_dir, f"{name}_{s.label}.mcap"), recording=make_recording(spec))
        lines["fleetA"][name] = {"width_m": s.width_m, "eta_k": s.eta_k, "n1": s.n1}
        kinds[f"fleetA/{name}"] = (s.label, "healthy" if s.kind == "clean" else "effect")
    log(f"wrote {len(kinds)} foreign bags of {duration_s:g} s in {time.perf_counter() - started:.0f} s")
    reg = os.path.join(workdir, "drives.yaml")
    with open(reg, "w") as f:
        yaml.safe_dump({"lines": lines}, f)

    def run(extra, tag):
        out = os.path.join(workdir, f"registry_out_{tag}")
        t0 = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", bag_dir, "--out", out,
                               "--no-plots", *extra], capture_output=True, text=True, timeout=7200)
        log(proc.stdout[-3000:], proc.stderr[-1500:])
        rows = json.load(open(os.path.join(out, "fleet.json")))["rows"]
        per = {r["drive"]: {"label": kinds.get(r["drive"], ("?", "?"))[0], "kind": kinds.get(r["drive"], ("?", "?"))[1],
                            "level": r.get("model_fit_level") or "", "ratio": r.get("model_fit_ratio"),
                            "p_min": (r["model_fit"].get("p_min") if isinstance(r.get("model_fit"), dict) else None),
                            "exceeding": (r["model_fit"].get("exceeding") if isinstance(r.get("model_fit"), dict)
                                          else None)}
               for r in rows}
        healthy_rows = [v for v in per.values() if v["kind"] == "healthy"]
        sick_rows = [v for v in per.values() if v["kind"] == "effect"]
        return {"false_warn": sum(v["level"] not in ("OK",) for v in healthy_rows), "healthy": len(healthy_rows),
                "detected": sum(v["level"] in ("WARN", "ERROR") for v in sick_rows) / max(len(sick_rows), 1),
                "sick": len(sick_rows), "per_drive": per, "seconds": time.perf_counter() - t0,
                "exit": proc.returncode}
    out = {"registry": run(["--registry", reg], "registry")}
    if compare_default:
        out["default_model"] = run([], "default")
    return out


def _healthy_specs():
    """The model_fit part's 12 healthy foreign drives: the bench suite's clean rows and EXTRA_HEALTHY."""
    import dataclasses
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    from foreign_drives.suites import suite
    healthy = [s for s in suite("bench") if s.kind == "clean"]
    return healthy + [dataclasses.replace(healthy[0], label=label, width_m=w, eta_k=e, n1=n, seed=7700 + i)
                      for i, (label, w, e, n) in enumerate(EXTRA_HEALTHY)]


def model_fit_null(own_s, foreign_s, rows_out="", sources=("own", "foreign")):
    """The folder rule's false-WARN rate on healthy drives (bench/_fleet/model_fit_null.py): the model_fit part's
    healthy conditions and the effect rows' nominal ones (own simulator), and its healthy rows on other seeds
    (foreign drives), cut into disjoint pieces, one test each."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from _fleet import model_fit_null as null
    from backlash_monitor.watch.alarm import load_folder_rule, load_rule
    from backlash_monitor.workbench import reference
    from backlash_monitor.workbench.model import load_model
    healthy = _healthy_specs()
    from foreign_drives.suites import suite
    rule, watch_rule = load_folder_rule(), load_rule()
    refs = {}

    def reference_for(w, e, n1):
        if (w, e, n1) not in refs:
            ref = reference.cached(load_model(None, width_m=w, eta_k=e, n1=n1), log=log)
            refs[(w, e, n1)] = (ref, ref.view_dof())
        return refs[(w, e, n1)]
    bench = {s.label: s for s in suite("bench")}
    conditions = list(dict.fromkeys([(s.width_m, s.eta_k, s.n1) for s in healthy]
                                    + [(bench[x].width_m, bench[x].eta_k, bench[x].n1) for x in EFFECT_LABELS]))
    started = time.perf_counter()
    rows = []
    # one condition at a time, the rows written after each (a long run's statistics are kept as they come); the
    # own conditions in reverse (another run building the same references from the front meets this one midway)
    for i, c in enumerate(conditions[::-1] if "own" in sources else []):
        rows += null.own_pieces([c], reference_for, own_s, rule.event_clip_p, seed0=91_000 + i, log=log)
        if rows_out:
            with open(rows_out, "w") as f:
                json.dump(rows, f)
    for i, s in enumerate(healthy if "foreign" in sources else []):
        rows += null.foreign_pieces([s], reference_for, foreign_s, rule.event_clip_p, seed0=92_000 + i, log=log)
        if rows_out:
            with open(rows_out, "w") as f:
                json.dump(rows, f)
    return {"model_fit_null": null.summarize(rows, rule, watch_rule),
            "model_fit_null_rule": dataclasses_asdict(rule), "model_fit_null_seconds": time.perf_counter() - started}


def dataclasses_asdict(x):
    import dataclasses
    return dataclasses.asdict(x)


PARTS = ("capacity", "diagnostics", "analyze", "two_host", "model_fit", "model_fit_null", "registry_loop")


def _autogroup() -> str:
    try:
        with open("/proc/self/autogroup") as f:
            return f.read().strip()
    except OSError:
        return ""


def _spin(cpu, seconds, queue):
    os.sched_setaffinity(0, {cpu})
    end, n = time.perf_counter() + seconds, 0
    while time.perf_counter() < end:
        for _ in range(10000):
            n += 1
    queue.put(n)


def parallel_work_ratio(seconds=1.0) -> float:
    """What this machine gives two cores right now: the work of busy loops pinned one per CPU,
    all at once, over the work of one loop alone (2.0 on two free cores; about 1 when other
    sessions hold the CPUs). The ceiling of any speed-up measured beside it."""
    import multiprocessing
    cpus = sorted(os.sched_getaffinity(0))
    ctx = multiprocessing.get_context("fork")

    def run(on):
        queue = ctx.Queue()
        procs = [ctx.Process(target=_spin, args=(c, seconds, queue)) for c in on]
        for p in procs:
            p.start()
        work = sum(queue.get() for _ in on)
        for p in procs:
            p.join()
        return work
    alone = run(cpus[:1])
    return run(cpus) / alone


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true", help="fewer drive counts, shorter runs")
    parser.add_argument("--parts", nargs="+", choices=PARTS, default=list(PARTS),
                        help="measure only these (default: all; 'diagnostics' runs at the "
                             "capacity found, or --drives)")
    parser.add_argument("--layouts", nargs="+", choices=("process", "single"),
                        default=["process", "single"], help="layouts of the capacity part")
    parser.add_argument("--counts", type=int, nargs="+", default=None, metavar="N",
                        help="drive counts of the capacity part, in order, until one fails "
                             "(default: 2 4 6 ... 16; --quick: 2 4 8)")
    parser.add_argument("--watch", choices=("on", "off", "both"), default="off",
                        help="the capacity part without the model watch (off: fleet's default), with every "
                             "drive's model watch (on: fleet --model-watch), or both alternated at each N "
                             "(drives_realtime and drives_realtime_watch side by side)")
    parser.add_argument("--drives", type=int, default=0,
                        help="drives of the diagnostics part when capacity is not measured")
    parser.add_argument("--analyze-repeats", type=int, default=7,
                        help="alternated pairs of the analyze part (each ~5 s; the best time of each "
                             "side is its least disturbed run on a shared machine)")
    parser.add_argument("--compare-default", action="store_true",
                        help="model_fit part: also run the same bags without the registry (every drive against the "
                             "default model, as before)")
    parser.add_argument("--null-own-s", type=float, default=45.0,
                        help="model_fit_null part: seconds of clean own-simulator drive per nominal condition (cut "
                             "into disjoint 4.5 s pieces: one folder test each)")
    parser.add_argument("--null-foreign-s", type=float, default=45.0,
                        help="model_fit_null part: seconds of clean foreign drive per healthy row's condition")
    parser.add_argument("--null-sources", nargs="+", choices=("own", "foreign"), default=["own", "foreign"],
                        help="model_fit_null part: the simulators of the healthy drives (default: both)")
    parser.add_argument("--null-rows-out", default="",
                        help="model_fit_null part: write every piece's statistics (views' T^2, residual ratio, "
                             "leave-one-out windows) to this JSON file (any rule can be applied to them later)")
    parser.add_argument("--registry-loop-drives", type=int, default=8,
                        help="registry_loop part: drives of the live fleet (one of them picks up a new version)")
    parser.add_argument("--registry-loop-stream-s", type=float, default=60.0,
                        help="registry_loop part: the fleet's stream [s] (with --registry-loop-live-train it must "
                             "outlast the live train --drive: 533 s at load 16)")
    parser.add_argument("--registry-loop-live-train", action="store_true",
                        help="registry_loop part: run the real train --drive live beside the fleet (default: the "
                             "library is trained before the fleet, and the registering step runs live)")
    args = parser.parse_args()
    result = {"load_average_1min_start": os.getloadavg()[0], "cores": os.cpu_count(),
              "parts": args.parts,
              # on a machine shared with other sessions the scheduler shares the CPUs between
              # sessions (autogroups: a process's nice counts only inside its session); run as
              #   setsid sh -c 'echo -10 > /proc/self/autogroup; exec python bench/fleet.py ...'
              # to take most of the CPU the others would: recorded here
              "autogroup": _autogroup()}
    with tempfile.TemporaryDirectory() as workdir:
        duration = 10 if args.quick else 20
        counts = args.counts or ((2, 4, 8) if args.quick else (2, 4, 6, 8, 10, 12, 14, 16))
        layout, best = "process", args.drives
        if "capacity" in args.parts:
            variants = [v for name in args.layouts for v in
                        {"off": [name], "on": [name + WITH_WATCH], "both": [name, name + WITH_WATCH]}[args.watch]]
            per_layout = capacity_alternated(variants, counts, duration, workdir)
            if args.watch == "both":
                on = {k: v for k, v in per_layout.items() if k.endswith(WITH_WATCH)}
                per_layout = {k: v for k, v in per_layout.items() if not k.endswith(WITH_WATCH)}
                result["drives_realtime_watch"] = max(v["drives_realtime"] for v in on.values())
                result["drives_realtime_watch_by_layout"] = on
            layout = max(per_layout, key=lambda k: per_layout[k]["drives_realtime"])
            best = per_layout[layout]["drives_realtime"]
            best_run = next((r for r in per_layout[layout]["runs"] if r["drives"] == best), None)
            result.update(drives_realtime=best, drives_realtime_layout=layout,
                          cpu_percent_per_drive=(best_run["cpu_percent_per_drive"] if best_run
                                                 else None),
                          drives_realtime_by_layout=per_layout, capacity_run_s=duration,
                          model_watch=args.watch)
        if "diagnostics" in args.parts:
            n_diag = max(best, 2)
            result["diagnostics_complete"] = diagnostics_complete(
                n_diag, layout, workdir, window_s=30 if args.quick else 60)
            result["diagnostics_complete_drives"] = n_diag
        if "analyze" in args.parts:
            n_bags = 20 if args.quick else 100
            speedup, times, cores = analyze_speedup(workdir, n_bags, repeats=args.analyze_repeats)
            result.update(fleet_analyze_speedup=speedup, fleet_analyze=times,
                          fleet_analyze_speedup_best_of=times["best_of"],
                          fleet_analyze_bags=n_bags, fleet_analyze_bag_s=3.0,
                          fleet_analyze_serial_fraction=times["serial_fraction"],
                          fleet_analyze_cores=cores)
        if "model_fit" in args.parts:
            fit = registry_model_fit(workdir, compare_default=args.compare_default)
            result.update(fleet_model_fit_false_warn=fit["registry"]["false_warn"],
                          fleet_model_fit_healthy_drives=fit["registry"]["healthy"],
                          fleet_model_fit_detected=fit["registry"]["detected"],
                          fleet_model_fit_effect_drives=fit["registry"]["sick"], fleet_model_fit=fit)
        if "model_fit_null" in args.parts:
            result.update(model_fit_null(args.null_own_s, args.null_foreign_s, args.null_rows_out, args.null_sources))
        if "registry_loop" in args.parts:
            sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
            from _fleet.registry_loop import registry_loop
            result.update(registry_loop(workdir, n_drives=args.registry_loop_drives,
                                        stream_s=args.registry_loop_stream_s,
                                        live_train=args.registry_loop_live_train))
        if "two_host" in args.parts:
            from backlash_monitor.ros.netns import can_make_namespaces, run_two_hosts
            reason = can_make_namespaces()
            if reason:
                result["two_host_estimates_delivered"] = None
                result["two_host_skipped"] = reason
            else:
                two = run_two_hosts(workdir, dict(os.environ), int(os.environ["ROS_DOMAIN_ID"]),
                                    duration_s=10.0)
                result["two_host_estimates_delivered"] = two["delivered"]
                result["two_host_onsets"] = [two["onsets_estimated"], two["onset_windows"]]
    result["load_average_1min_end"] = os.getloadavg()[0]
    print(json.dumps(result))


if __name__ == "__main__":
    main()
