"""`python -m backlash_monitor simulate`: run the plant model for a set of scenarios and write an NPZ.

The NPZ layout is documented in docs/model.md ("NPZ layout of `simulate`").
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from backlash_monitor.commands._args import float_list, seed_list
from backlash_monitor.signals import STREAM_SIGNALS
from backlash_monitor.errors import DeprecatedSpelling
from backlash_monitor.commands.vocabulary import deprecated
from backlash_monitor.plant.scenarios import ETA_K_VALUES, K2_WIDTHS_M, N1_VALUES   # light: no simulator
from backlash_monitor.files.outputs import missing_folder_message, OutputError, check_outputs, staged_outputs   # never over existing data

NAME = "simulate"
HELP = "simulate the drive (plant model, docs/model.md) for a grid of scenarios: signals to NPZ and/or MCAP bags"
DESCRIPTION = (
    "Simulate the drive (per-unit induction motor, backlash clutch, spring + power-law absorber load, "
    "pulse load and disturbances; docs/model.md) from a settled start at the 50 kHz sample rate, for every "
    "combination of the given widths, eta_k, n1 and seeds (default: the paper's full 6 x 4 x 5 grid, seed 0), "
    "and write a1, a2, omega1, omega2, angle_difference, the scenario table, the true backlash entries and "
    "the config to an NPZ file. Memory: 5 arrays x 8 bytes x 50000 samples/s per scenario (240 MB for the "
    "full grid and 1 s).")

FORMAT_VERSION = 1
ENTRY_KINDS = ("onset", "return")
SIGNALS = STREAM_SIGNALS


def add_arguments(parser: argparse.ArgumentParser) -> None:
    join = lambda xs: ",".join(f"{x:g}" for x in xs)  # noqa: E731
    parser.add_argument("--widths", type=float_list, default=list(K2_WIDTHS_M), metavar="M[,M...]",
                        help=f"backlash widths b [m], 0 < b <= 1 (paper K2: {join(K2_WIDTHS_M)})")
    parser.add_argument("--eta-k", type=float_list, default=list(ETA_K_VALUES), metavar="PAS[,...]",
                        help=f"absorber fluid consistency eta_k [Pa*s^n], 0 < eta_k <= 100 "
                             f"(paper: {join(ETA_K_VALUES)})")
    parser.add_argument("--n1", type=float_list, default=list(N1_VALUES), metavar="N[,N...]",
                        help=f"absorber fluid flow index n1 [-], 0 < n1 <= 3 (paper: {join(N1_VALUES)})")
    parser.add_argument("--seeds", type=seed_list, default=[0], metavar="S[,S...]",
                        help="noise seeds, integers >= 0; each scenario's two generators are seeded from its "
                             "seed and its parameters")
    parser.add_argument("--duration", type=float, default=1.0, metavar="S",
                        help="simulated time per scenario after the settled start [s], 0 < duration <= 3600")
    parser.add_argument("--no-noise", action="store_true",
                        help="switch both disturbance generators off (the pulse load stays on)")
    parser.add_argument("-o", "--output", default="simulation.npz", metavar="FILE.npz",
                        help="output NPZ file (its folder must exist)")
    parser.add_argument("--config", default=None, metavar="YAML",
                        help="plant config file (default: config/plant.yaml of the package)")
    parser.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                        help="override one config value, e.g. --set load.mass_kg=12 or --set effects.spring=false; "
                             "switch on and parameterise a catalogue effect: --set effects.wheel_coulomb_friction=true "
                             "--set wheel_coulomb_friction.torque_Nm=1.5 (docs/effects.md lists them); repeatable")
    parser.add_argument("--effects-file", action="append", default=[], metavar="FILE.py",
                        help="a Python file defining your own Effect classes (docs/effects.md); they are registered "
                             "and can then be switched on with --set effects.NAME=true; repeatable")
    parser.add_argument("--effects", dest="effects_file", action=DeprecatedSpelling, new="--effects-file",
                        append=True, metavar="FILE.py", help=argparse.SUPPRESS)
    parser.add_argument("--noise-seed", type=int, default=None, metavar="N",
                        help="common random numbers: every scenario on the same noise realisation drawn from this "
                             "seed (default: each scenario's own noise from its seed, width, eta_k and n1)")
    parser.add_argument("--backend", choices=("auto", "numba", "numba-scalar", "numpy"), default=None,
                        help="integration backend (default: simulation.backend of the config)")
    parser.add_argument("--chunk", type=float, default=0.05, metavar="S",
                        help="simulated time per progress step [s], 0 < chunk <= duration")
    parser.add_argument("--mcap", default=None, metavar="DIR",
                        help="also write one rosbag2 MCAP bag per scenario into DIR (created if missing), "
                             "with the live graph's topics (/plant/a1, ..., /plant/true_width_m), chunked as "
                             "the plant_simulator node publishes; for `analyze`, `replay` and Foxglove (default: no bags)")
    parser.add_argument("--no-npz", action="store_true", help="write no NPZ (use with --mcap)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar and no progress notes on stderr")
    deprecated(parser, "--quiet", "--no-progress", "no_progress", const=True)
    parser.add_argument("--overwrite", action="store_true",
                        help="replace an existing NPZ or bag (without it an existing one is an error, "
                             "reported before simulating); outputs are renamed into place when complete")


def _parse_override(text: str):
    # deferred: backlash_monitor.plant.config costs ~640 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.plant.config import parse_override
    return parse_override(text)


def _error(message: str) -> int:
    print(f"python -m backlash_monitor simulate: error: {message}", file=sys.stderr)
    return 2


def run(args) -> int:
    # deferred: backlash_monitor.plant costs ~690 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.plant import PlantSimulator, Scenario, builtin_catalogue, load_plant_config
    # deferred: backlash_monitor.plant.analysis costs ~630 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.plant.analysis import impact_times_ms

    # the grid's ranges, as Scenario checks them, named by the option (docs/cli.md: one range form)
    for option, values, high, unit in (("--widths", args.widths, 1.0, "m"), ("--eta-k", args.eta_k, 100.0, "Pa*s^n"),
                                       ("--n1", args.n1, 3.0, "")):
        bad = [v for v in values if not 0.0 < v <= high]
        if bad:
            return _error(f"{option} {bad[0]:g}: out of range, allowed 0..{high:g}{' ' + unit if unit else ''}, "
                          "above 0")
    try:
        catalogue = builtin_catalogue().with_files(args.effects_file)
        if args.noise_seed is not None and args.noise_seed < 0:
            raise ValueError(f"--noise-seed {args.noise_seed}: out of range, allowed 0..inf")
        overrides = dict(_parse_override(t) for t in args.set)
        cfg = load_plant_config(args.config, overrides=overrides or None, catalogue=catalogue)
        scenarios = [Scenario(width_m=w, eta_k=e, n1=n, seed=s)
                     for s in args.seeds for e in args.eta_k for n in args.n1 for w in args.widths]
    except ValueError as exc:
        return _error(str(exc))
    if not (0.0 < args.duration <= 3600.0):
        return _error(f"--duration {args.duration:g}: out of range, allowed 0..3600 s, above 0")
    if not (0.0 < args.chunk):
        return _error(f"--chunk {args.chunk:g}: out of range, allowed 0..--duration s, above 0")
    if args.no_npz and not args.mcap:
        return _error("--no-npz without --mcap would write nothing; allowed: --mcap DIR with --no-npz")
    out_path = Path(args.output)
    if not out_path.parent.exists() and str(out_path.parent) != "":
        return _error(missing_folder_message("--output", out_path))
    if out_path.is_dir():
        return _error(f"--output {args.output!r} is a directory; allowed: a file path ending in .npz")
    try:
        check_outputs([] if args.no_npz else [_npz_path(out_path)], overwrite=args.overwrite,
                      option="--output")
        check_outputs([Path(args.mcap) / bag_name(s) for s in scenarios] if args.mcap else [],
                      overwrite=args.overwrite, option="--mcap")
    except OutputError as exc:
        return _error(str(exc))
    fs = cfg.simulation.sample_rate_hz
    n_total = int(round(args.duration * fs))
    if n_total < 1:
        return _error(f"--duration {args.duration:g} is shorter than one sample period ({1 / fs:g} s)")
    n_scen = len(scenarios)
    mem_gb = len(SIGNALS) * 8 * n_scen * n_total / 1e9
    if mem_gb > 16:
        return _error(f"{n_scen} scenarios x {args.duration:g} s need {mem_gb:.1f} GB; allowed: <= 16 GB "
                      "(fewer scenarios or a shorter --duration)")

    if not args.no_progress:
        print(f"settling {n_scen} scenarios (computed steady state + {cfg.simulation.run_in_s:g} s run-in) ...",
              file=sys.stderr)
    try:
        sim = PlantSimulator(scenarios, config=cfg, noise=not args.no_noise, backend=args.backend,
                             noise_seed=args.noise_seed)
    except ValueError as exc:
        return _error(str(exc))
    data = {s: np.empty((n_scen, n_total)) for s in SIGNALS}
    entries: list[list] = [[] for _ in range(n_scen)]
    chunk_n = max(1, min(n_total, int(round(args.chunk * fs))))
    try:
        # deferred: tqdm costs ~40-140 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from tqdm import tqdm
        bar = tqdm(total=n_total / fs, unit="s", unit_scale=False, file=sys.stderr, disable=args.no_progress,
                   desc=f"simulate {n_scen} scenarios", bar_format="{l_bar}{bar}| {n:.2f}/{total:.2f} s "
                                                                 "[{elapsed}<{remaining}]")
    except ImportError:  # pragma: no cover
        bar = None
    t0 = time.perf_counter()
    k = 0
    while k < n_total:
        n = min(chunk_n, n_total - k)
        ch = sim.run(n)
        for s in SIGNALS:
            data[s][:, k:k + n] = getattr(ch, s)
        for i in range(n_scen):
            entries[i].extend(ch.entries[i])
        k += n
        if bar is not None:
            bar.update(n / fs)
    if bar is not None:
        bar.close()
    wall = time.perf_counter() - t0

    if args.mcap:
        bags = _write_bags(Path(args.mcap), scenarios, data, 1.0 / fs, quiet=args.no_progress)
        if not args.no_progress:
            print(f"wrote {len(bags)} bag(s) into {args.mcap}", file=sys.stderr)
    if args.no_npz:
        _print_summary(scenarios, data, entries, sim, args.duration, wall, Path(args.mcap or "."), fs,
                           impact_times_ms)
        return 0
    entry_rows = np.array([(i, k_, ENTRY_KINDS.index(kind)) for i in range(n_scen) for k_, kind in entries[i]],
                          dtype=np.int64).reshape(-1, 3)
    _staged_savez(_npz_path(out_path),
             format_version=np.int64(FORMAT_VERSION),
             **data,
             scenario_width_m=np.array([s.width_m for s in scenarios]),
             scenario_eta_k=np.array([s.eta_k for s in scenarios]),
             scenario_n1=np.array([s.n1 for s in scenarios]),
             scenario_seed=np.array([s.seed for s in scenarios], dtype=np.int64),
             entries=entry_rows,
             entry_kinds=np.array(ENTRY_KINDS),
             sample_period_s=np.float64(1.0 / fs),
             first_sample_index=np.int64(0),
             noise=np.bool_(not args.no_noise),
             config_json=np.array(cfg.to_json()))

    _print_summary(scenarios, data, entries, sim, args.duration, wall, out_path, fs, impact_times_ms)
    return 0


def _npz_path(out_path: Path) -> Path:
    """The file np.savez writes for --output (it appends .npz to a name without it)."""
    return out_path if out_path.suffix == ".npz" else Path(f"{out_path}.npz")


def _staged_savez(path: Path, **arrays) -> None:
    """np.savez into PATH.partial, renamed onto PATH when complete (never a half-written NPZ)."""
    with staged_outputs([path]) as (tmp,), open(tmp, "wb") as f:
        np.savez(f, **arrays)


def bag_name(scenario) -> str:
    """File name of a scenario's bag: width [mm], eta_k, n1 and seed."""
    return (f"w{scenario.width_m * 1e3:g}mm_eta{scenario.eta_k:g}_n{scenario.n1:g}_s{scenario.seed}.mcap")


def _write_bags(directory: Path, scenarios, data, sample_period_s: float, quiet: bool) -> list[Path]:
    # deferred: backlash_monitor.bag.simulated costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.bag.simulated import DEFAULT_CHUNK_SAMPLES, SimulationBagWriter
    directory.mkdir(parents=True, exist_ok=True)
    paths = []
    n_total = data["a1"].shape[1]
    for i, scenario in enumerate(scenarios):
        path = directory / bag_name(scenario)
        with staged_outputs([path]) as (tmp,), SimulationBagWriter(tmp, true_width_m=scenario.width_m) as bag:
            for k in range(0, n_total, DEFAULT_CHUNK_SAMPLES):
                bag.write_chunk(k, sample_period_s,
                                {s: data[s][i, k:k + DEFAULT_CHUNK_SAMPLES] for s in SIGNALS})
        paths.append(path)
    return paths


def _print_summary(scenarios, data, entries, sim, duration, wall, out_path, fs, impact_times_ms):
    """Per width: onset/return entries per second, mean far-side impact time after onsets, RMS of a1/a2."""
    widths = sorted({s.width_m for s in scenarios})
    chunk = SimpleNamespace(entries=entries, angle_difference=data["angle_difference"], first_sample_index=0,
                            n_samples=data["a1"].shape[1], sample_period_s=1.0 / fs)
    impacts = impact_times_ms(chunk, sim.beta)
    print(f"{'width [m]':>10} {'scen':>5} {'onset/s':>8} {'return/s':>9} {'impact [ms]':>12} "
          f"{'a1 rms':>9} {'a2 rms':>8}")
    for w in widths:
        idx = [i for i, s in enumerate(scenarios) if s.width_m == w]
        on = np.mean([sum(1 for _, kd in entries[i] if kd == "onset") for i in idx]) / duration
        ret = np.mean([sum(1 for _, kd in entries[i] if kd == "return") for i in idx]) / duration
        imp = [t for i in idx for t in impacts[i]]
        imp_s = f"{np.mean(imp):12.2f}" if imp else f"{'-':>12}"
        a1 = float(np.sqrt(np.mean(data["a1"][idx] ** 2)))
        a2 = float(np.sqrt(np.mean(data["a2"][idx] ** 2)))
        print(f"{w:10.5f} {len(idx):5d} {on:8.2f} {ret:9.2f} {imp_s} {a1:9.3f} {a2:8.4f}")
    scen_s = len(scenarios) * duration
    print(f"{len(scenarios)} scenarios x {duration:g} s in {wall:.1f} s wall ({scen_s / wall:.0f} x real time, "
          f"backend {sim.backend}) -> {out_path}")
