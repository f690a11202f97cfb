"""`python -m backlash_monitor train`: simulate training drives and write the versioned pattern library.

Layout of the library: docs/classifier.md. The packaged defaults are made by
``python -m backlash_monitor train --trigger contact_loss`` (-> backlash_monitor/data/patterns.npz) and
``python -m backlash_monitor train --trigger paper`` (-> backlash_monitor/data/patterns_paper.npz).
"""
from __future__ import annotations

import argparse
import math
from pathlib import Path
import sys
import time

from backlash_monitor.commands import UsageError
from backlash_monitor.errors import RunFailure
from backlash_monitor.commands._args import seed_list
from backlash_monitor.commands.vocabulary import deprecated
from backlash_monitor.commands._workbench import add_drive_arguments, drive_entry
from backlash_monitor.files.outputs import OutputError, check_outputs
from backlash_monitor.classifier.training_defaults import DEFAULT_DURATION_S, DEFAULT_TRAIN_SEEDS
from backlash_monitor.files.registry import register

NAME = "train"
HELP = "simulate noisy training drives and write the versioned pattern library (all classifier modes)"
DESCRIPTION = (
    "Simulate the paper's grid (6 widths x 4 eta_k x 5 n1) for each training noise seed, capture the onset "
    "windows with the chosen trigger, denoise them (sym5, details 1-6 removed) and fit every classifier mode: "
    "the paper's counter-propagation patterns (M3, W5 per n1 for a1 and a2; 'paper' and 'paper_corrected') "
    "and the improved 'shape' regression (a1, a2, a1+a2). The library records the settings that made it; "
    "the classifier refuses a library made with other settings. Simulated windows are cached in .cache/.")

TRIGGERS = ("contact_loss", "paper")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    # deferred: backlash_monitor.classifier.cpn costs ~120 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.cpn import DEFAULT_EPOCHS, DEFAULT_L1, DEFAULT_L2
    # deferred: backlash_monitor.classifier.shape costs ~100 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.shape import DEFAULT_RIDGE
    deprecated(parser, "--out", "--output", "output", metavar="FILE.npz")
    parser.add_argument("-o", "--output", default=None, metavar="FILE.npz",
                        help="where to write the library (default: the packaged library of the trigger, "
                             "backlash_monitor/data/patterns.npz for contact_loss, patterns_paper.npz for paper)")
    parser.add_argument("--trigger", default="contact_loss", choices=TRIGGERS,
                        help="backlash-entry trigger of the training windows: 'contact_loss' (angle difference "
                             "alone, the pipeline's default) or 'paper' (eq. 1 with the true width)")
    parser.add_argument("--seeds", type=seed_list, default=list(DEFAULT_TRAIN_SEEDS), metavar="S[,S...]",
                        help="training noise seeds (each one is the full 120-scenario grid, 8 classified onset "
                             "windows per scenario); keep them apart from the evaluation seeds 0-4")
    parser.add_argument("--epochs", type=int, default=DEFAULT_EPOCHS,
                        help="counter-propagation epochs per window (paper: 30), >= 1")
    parser.add_argument("--l1", type=float, default=DEFAULT_L1,
                        help="Kohonen-layer learning coefficient l1 (paper: 0.1), 0 < l1 <= 1")
    parser.add_argument("--l2", type=float, default=DEFAULT_L2,
                        help="Grossberg-layer learning coefficient l2 (paper: 0.09), 0 < l2 <= 1")
    parser.add_argument("--ridge", type=float, default=DEFAULT_RIDGE,
                        help="ridge penalty of the shape mode's regression (per window, standardised features), > 0")
    parser.add_argument("--duration", type=float, default=DEFAULT_DURATION_S, metavar="S",
                        help="simulated seconds per scenario (4 onset windows per second; the first has no "
                             "sensor offset estimate yet and is not used, as the monitor does not classify "
                             "it), 0.5 <= S <= 60")
    parser.add_argument("--window-offset", type=int, default=None, metavar="SAMPLES",
                        help="samples from the detected entry to the window start (default: the trigger's "
                             "configured value, config/windowing.yaml capture.window_offset_samples); the "
                             "library records it and the classifier refuses windows captured with another")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace an existing --output file (without --output, the packaged library "
                             "is replaced: that is what `make patterns` asks for)")
    parser.add_argument("--model", action="append", default=None, metavar="M.yaml",
                        help="train on a workbench model version's plant config (docs/workbench.md; e.g. after "
                             "add-effect) instead of config/plant.yaml; needs --output. Repeat it to train on "
                             "several versions at once (the seeds dealt out round-robin, the windows pooled): "
                             "when diagnose names indistinguishable effects, one version per candidate. Also writes "
                             "the live model watch's reference of the (first) version beside the library: "
                             "LIB.watch.npz (~30 s more; docs/model_watch.md) (default: config/plant.yaml)")
    parser.add_argument("--previous-library", default=None, metavar="LIB.npz",
                        help="with --model: the library the monitor uses now (default: the packaged one); the "
                             "retrained library is checked against it on the diagnosed recording")
    parser.add_argument("--keep-worse", action="store_true",
                        help="with --model: write the retrained library even when it puts the monitor further from "
                             "the diagnosis than the previous library, or, after a 'partial' or 'nothing_explains' "
                             "diagnosis, no closer to it than the previous library by the diagnosis's uncertainty "
                             "(default: the previous library is written under --output, saying why, and the "
                             "retrained one as NAME.rejected.npz)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_drive_arguments(parser)


def _drive_defaults(args):
    """With --drive: --model defaults to the drive's current model version, --out to beside it (M.npz),
    --previous-library to the drive's library. -> the registry entry or None."""
    entry = drive_entry(args)
    if entry is None:
        return None
    if not args.model:
        if entry.model is None:
            raise UsageError(f"train --drive {args.drive}: the drive has no model file in {args.registry}; give "
                             "--model M.yaml (e.g. add-effect's new version)")
        args.model = [str(entry.model)]
    if args.output is None:
        args.output = str(Path(args.model[0]).with_suffix(".npz"))
    if args.previous_library is None and entry.library is not None:
        args.previous_library = str(entry.library)
    return entry


def _check(args) -> None:
    if args.epochs < 1:
        raise UsageError(f"--epochs {args.epochs}: out of range, allowed 1..inf (paper: 30)")
    for name in ("l1", "l2"):
        v = getattr(args, name)
        if not (math.isfinite(v) and 0 < v <= 1):
            raise UsageError(f"--{name} {v:g}: out of range, allowed 0..1, above 0 (paper: l1 = 0.1, l2 = 0.09)")
    if not (math.isfinite(args.ridge) and args.ridge > 0):
        raise UsageError(f"--ridge {args.ridge:g}: out of range, allowed 0..inf, above 0 (default 1e-5)")
    if not (math.isfinite(args.duration) and 0.5 <= args.duration <= 60):
        raise UsageError(f"--duration {args.duration:g}: out of range, allowed 0.5..60 s")
    if args.window_offset is not None and not 0 <= args.window_offset <= 65536:
        raise UsageError(f"--window-offset {args.window_offset}: out of range, allowed 0..65536 samples")
    if getattr(args, "model", None) and args.output is None:
        raise UsageError("--model needs -o/--output LIB.npz (the packaged library stays the default model's)")
    if getattr(args, "model", None) and len(args.model) > len(args.seeds):
        raise UsageError(f"{len(args.model)} --model files need at least {len(args.model)} --seeds "
                         f"(the seeds are dealt out one per model), got {len(args.seeds)}")
    if args.output is not None and not str(args.output).endswith(".npz"):
        raise UsageError(f"--output {args.output}: the library is an .npz file; give a name ending in .npz")
    if args.output is not None:   # before the minutes of training, not after
        # deferred: backlash_monitor.workbench.reference costs ~750 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from backlash_monitor.workbench.reference import reference_path_for_library
        outs = [args.output] + ([str(reference_path_for_library(args.output))] if getattr(args, "model", None) else [])
        try:
            if getattr(args, "model", None) and not getattr(args, "keep_worse", False):
                outs.append(str(args.output)[:-len(".npz")] + ".rejected.npz")   # written if the check rejects it
            check_outputs(outs, overwrite=args.overwrite, option="--output")
        except OutputError as error:
            raise UsageError(str(error)) from None


def run(args) -> int:
    entry = _drive_defaults(args)
    _check(args)
    # deferred: tqdm costs ~40-140 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from tqdm import tqdm

    # deferred: backlash_monitor.classifier.patterns costs ~90 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.patterns import default_library_path
    # deferred: backlash_monitor.classifier.training costs ~720 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.training import NoTrainingWindows, build_library
    out = args.output or default_library_path(args.trigger)
    config = None
    models = []
    if args.model:
        # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from backlash_monitor.workbench.model import ModelError, load_model
        # deferred: backlash_monitor.workbench.retrain costs ~320 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from backlash_monitor.workbench.retrain import training_config
        configs = []
        try:
            for m in args.model:
                models.append(load_model(m))
                cfg, note = training_config(models[-1])
                configs.append(cfg)
                if note:
                    print(f"note: {note}")
        except ModelError as exc:
            raise UsageError(str(exc)) from None
        config = configs[0] if len(configs) == 1 else configs
    t0 = time.time()
    try:
        with tqdm(total=len(args.seeds), desc=f"simulate+window ({args.trigger})", unit="seed",
                  disable=args.no_progress, file=sys.stderr) as bar:
            lib = build_library(args.trigger, args.seeds, epochs=args.epochs, l1=args.l1, l2=args.l2,
                                ridge=args.ridge, duration_s=args.duration, progress=bar.update,
                                window_offset=args.window_offset, config=config)
    except NoTrainingWindows as error:
        model = f"model {', '.join(str(m) for m in args.model)}" if args.model else "the default model"
        raise RunFailure(f"{model} gave no onset window at width {error.width_m * 1e3:.2f} mm, eta_k {error.eta_k:g}, "
                         f"n1 {error.n1:g} in any of its {len(args.seeds)} seeds of {args.duration:g} s: with its "
                         "effects the simulated drive does not cross its backlash there (check the effects' values, "
                         "e.g. an accepted proposal's or partial effect's, in the model file), or give more --seeds or "
                         "a longer --duration; nothing written") from None
    check = None
    rejected = None
    if models and any(m.provenance.get("measurement") for m in models):
        # deferred: backlash_monitor.workbench.retrain costs ~320 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from backlash_monitor.workbench.retrain import check_library
        check = check_library(lib, models, args.previous_library)
        lib.training["check"] = check
        if check["worse"] and not args.keep_worse:
            # never a worse monitor: the previous library goes under the requested name, the retrained one beside it
            # deferred: backlash_monitor.classifier.patterns costs ~90 ms at start-up (python -X importtime, 29 Nov); --help imports every command
            from backlash_monitor.classifier.patterns import load_library
            rejected = lib.save(str(out)[:-len(".npz")] + ".rejected.npz")
            lib = load_library(args.previous_library or default_library_path(args.trigger))
            # (not flagged: it is the library the monitor had; the check says why it was kept)
            lib.training = {**lib.training, "check": {**check, "flagged": False,
                                                      "kept_previous": str(args.previous_library
                                                                           or default_library_path(args.trigger)),
                                                      "rejected": str(rejected)}}
    path = lib.save(out)
    ref_path = None
    if models:
        # the live model watch's reference of the (first) version: the consistency test without simulation
        # deferred: backlash_monitor.workbench.reference costs ~750 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from backlash_monitor.workbench.reference import build as build_reference, reference_path_for_library
        t_ref = time.time()
        try:
            ref_path = build_reference(models[0]).save(reference_path_for_library(path))
        except ValueError as exc:
            # (a model whose simulated drive does not cross its backlash has no events for the watch to test)
            print(f"error: pattern library written: {path}; but the model watch's reference of {args.model[0]} could "
                  f"not be built: {str(exc).splitlines()[0]}; nothing registered (check the model's added terms: "
                  "diagnose it, or add-effect with other values)", file=sys.stderr)
            return 1
        ref_seconds = time.time() - t_ref
    if check is not None:
        _record_monitor_widths(models, check, path, rejected, args.previous_library)
    if entry is not None:
        if rejected is None:
            register(args.registry, entry.hardware_id, model=args.model[0], library=path, watch_reference=ref_path)
            print(f"registry {args.registry}: {entry.hardware_id} is at version {entry.version + 1}: model "
                  f"{args.model[0]}, library {path}, watch reference {ref_path}")
        else:
            print(f"registry {args.registry}: {entry.hardware_id} stays at version {entry.version} (the retrained "
                  "library was worse; nothing registered)")
    fit = lib.training["shape"]["fit"]
    print(f"pattern library written: {path}")
    print(f"  trigger {args.trigger}, seeds {','.join(map(str, args.seeds))}, "
          f"{lib.training['n_onset_windows']} onset windows, window offset "
          f"{lib.settings['window_offset_samples']} samples, epochs {args.epochs}, l1 {args.l1}, l2 {args.l2}")
    print("  shape mode training residual: " + ", ".join(
        f"{s} {v['training_residual_std_m'] * 1e3:.3f} mm" for s, v in fit.items()))
    print(f"  modes: {', '.join(lib.modes)}; plant config {lib.settings['plant_config_hash']}; "
          f"{time.time() - t0:.0f} s")
    if ref_path is not None:
        print(f"model watch reference written: {ref_path} (model {models[0].label()}, {ref_seconds:.0f} s; "
              "model_watch takes it with -p reference:=..., pipeline --watch with --library)")
    if check is not None:
        # deferred: backlash_monitor.workbench.retrain costs ~320 ms at start-up (python -X importtime, 29 Nov); --help imports every command
        from backlash_monitor.workbench.retrain import describe
        for line in describe(check):
            print("  " + line)
        if rejected is not None:
            shown = ("further from the diagnosis than the previous one" if any(c.get("further") for c in check["checked"])
                     else "no closer to the diagnosis than the previous one by its uncertainty, and the diagnosed "
                          "model does not explain its recording")
            print(f"WARNING: the retrained library puts the monitor {shown}: "
                  f"{path} holds the previous library (its training.check says why); the retrained one is {rejected} "
                  "(--keep-worse writes it as --output)", file=sys.stderr)
        elif check["flagged"]:
            print(f"WARNING: the library {path} is FLAGGED (written into it; analyze and the classifier warn when "
                  "they load it): " + "; ".join(check["reasons"]), file=sys.stderr)
    return 0


def _record_monitor_widths(models, check, library, rejected, previous) -> None:
    """The workbench history: the monitor's width on the diagnosed recording with the library written (for the
    version trained on) and with the library in use before (for the version the diagnosis was made against)."""
    # deferred: backlash_monitor.classifier.patterns costs ~90 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.patterns import default_library_path
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import append_history
    by_label = {m.label(): m for m in models}
    for c in check["checked"]:
        m = by_label.get(c.get("model"))
        if m is None or m.path is None or "retrained_width_m" not in c:
            continue
        width = c["packaged_width_m"] if rejected is not None else c["retrained_width_m"]
        common = {"type": "monitor", "measurement": c["measurement"], "diagnosed_width_m": c["diagnosed_width_m"]}
        append_history(m.path, {**common, "model": m.path.name, "name": m.name, "version": m.version,
                                "library": str(library), "width_m": width,
                                "note": "previous library kept (the retrained one was worse)" if rejected else ""})
        parent = (m.provenance or {}).get("diagnosed_model") or {"name": m.name, "version": m.version - 1}
        append_history(m.path, {**common, "model": None, "name": parent["name"], "version": parent["version"],
                                "library": str(previous or default_library_path()), "width_m": c["packaged_width_m"]})
