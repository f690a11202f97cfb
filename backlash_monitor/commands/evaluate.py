"""`python -m backlash_monitor evaluate`: identification figures of every classifier mode over the grid.

Writes into --out-dir: evaluation.json (every figure), confusion_<trigger>.png, windows_<trigger>.png
(raw vs denoised onset windows per width), continuous_<trigger>.png, and prints a summary table.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from backlash_monitor.commands import UsageError
from backlash_monitor.commands._args import seed_list
from backlash_monitor.files.outputs import OutputError, check_outputs, staged_outputs

NAME = "evaluate"
HELP = "identification accuracy, confusion, B margin, fusion, continuous width and the paper's tables, per mode"
DESCRIPTION = (
    "Classify the denoised onset windows of the full grid (6 widths x 4 eta_k x 5 n1) for the evaluation noise "
    "seeds (never the library's training seeds) with every mode (paper, paper_corrected, shape) and signal, "
    "for each trigger, using the pattern library of that trigger. Reports per-window accuracy, confusion "
    "matrices, B margins (second-smallest over smallest B), fused accuracy over the drive's last onset events, "
    "the continuous-width error on widths the patterns never saw, and the paper's Tables 1-2 cases side by side "
    "with the printed values. Writes PNGs and evaluation.json into --out-dir.")

TRIGGERS = ("paper", "contact_loss")


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--out-dir", default="out/evaluate", metavar="DIR",
                        help="directory for evaluation.json and the PNGs (created); existing files "
                             "there are an error unless --overwrite")
    parser.add_argument("--overwrite", action="store_true",
                        help="replace evaluation.json and the PNGs in --out-dir (each is replaced "
                             "only once the whole evaluation has completed)")
    parser.add_argument("--trigger", action="append", choices=TRIGGERS, default=None,
                        help="trigger(s) to evaluate; repeat for several (default: both, paper and contact_loss)")
    parser.add_argument("--seeds", type=seed_list, default=[0, 1, 2, 3, 4], metavar="S[,S...]",
                        help="evaluation noise seeds; each is the full 120-scenario grid with 8 onset windows per "
                             "scenario; must not overlap the library's training seeds")
    parser.add_argument("--library", action="append", default=None, metavar="TRIGGER=FILE.npz",
                        help="pattern library per trigger, e.g. paper=/tmp/p.npz (default: the packaged library "
                             "of each trigger)")
    parser.add_argument("--fusion-events", type=int, default=8, metavar="N",
                        help="onset events fused into one estimate (the drive's last N), 1 <= N <= 8 "
                             "(the 2 s drives have 8 onset events)")
    parser.add_argument("--unseen-seeds", type=seed_list, default=[0], metavar="S[,S...]",
                        help="seeds for the continuous-width check on widths the patterns never saw "
                             "(0.003, 0.0045, 0.006, 0.0085 m over all eta_k and n1)")
    parser.add_argument("--no-plots", action="store_true", help="skip the PNGs")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


def _libraries(args) -> dict:
    # deferred: backlash_monitor.classifier.patterns costs ~90 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.patterns import default_library_path
    triggers = args.trigger or list(TRIGGERS)
    paths = {t: default_library_path(t) for t in triggers}
    for item in args.library or []:
        if "=" not in item:
            raise UsageError(f"--library {item!r}: give TRIGGER=FILE.npz with TRIGGER one of {', '.join(TRIGGERS)}")
        t, f = item.split("=", 1)
        if t not in TRIGGERS:
            raise UsageError(f"--library {item!r}: unknown trigger {t!r}; allowed: {', '.join(TRIGGERS)}")
        paths[t] = Path(f)
    return {t: paths[t] for t in triggers}


def _check(args) -> None:
    if not 1 <= args.fusion_events <= 8:
        raise UsageError(f"--fusion-events {args.fusion_events}: out of range, allowed 1..8")


def _public(r: dict) -> dict:
    return {k: v for k, v in r.items() if not k.startswith("_")}


def run(args) -> int:
    _check(args)
    # deferred: backlash_monitor.classifier.patterns costs ~90 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.patterns import PatternLibraryError, load_library

    libs = {}
    for trig, path in _libraries(args).items():
        try:
            libs[trig] = load_library(path, trigger=trig)
            if libs[trig].settings.get("window_offset_samples") is None:
                raise PatternLibraryError(f"pattern library {path} has no window_offset_samples setting "
                                          "(made by an older version); retrain it")
        except (PatternLibraryError, ValueError) as error:
            raise UsageError(str(error)) from None
        train_seeds = set(libs[trig].training.get("seeds") or [])
        clash = sorted(train_seeds & set(args.seeds))
        if clash:
            raise UsageError(f"--seeds {','.join(map(str, args.seeds))}: seed(s) {','.join(map(str, clash))} trained "
                             f"the {trig} library {path}; evaluate on other seeds")
    out_dir = Path(args.out_dir)
    outputs = [out_dir / "evaluation.json"] + ([] if args.no_plots else [
        out_dir / f"{kind}_{trig}.png" for trig in libs
        for kind in ("confusion", "windows", "continuous")])
    try:
        check_outputs(outputs, overwrite=args.overwrite, option="--out-dir")
    except OutputError as error:
        raise UsageError(str(error)) from None
    with staged_outputs(outputs) as temps:   # renamed onto their names only when all are written
        staged = dict(zip(outputs, temps))
        report = _evaluate(args, libs, out_dir, staged)
    _summary(report)
    print(f"\nfigures: {out_dir / 'evaluation.json'}" + ("" if args.no_plots else f", PNGs in {out_dir}"))
    return 0


def _evaluate(args, libs, out_dir, staged) -> dict:
    # deferred: tqdm costs ~40-140 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from tqdm import tqdm

    # deferred: backlash_monitor.classifier.dataset costs ~880 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.dataset import collect_windows
    # deferred: backlash_monitor.classifier.evaluation costs ~740 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.evaluation import (EVAL_SIGNALS, MODES, UNSEEN_WIDTHS_M, continuous_error,
                                                        evaluate_mode, paper_miss_explanation, paper_table_rows)
    t0 = time.time()
    triggers = list(libs)
    n_steps = len(triggers) * (len(args.seeds) + 1 + len(args.unseen_seeds)) + len(triggers) * 7
    report = {"seeds": args.seeds, "fusion_events": args.fusion_events, "triggers": {}}
    with tqdm(total=n_steps, desc="evaluate", unit="step", disable=args.no_progress, file=sys.stderr) as bar:
        for trig in triggers:
            lib = libs[trig]
            bar.set_postfix_str(f"{trig}: simulate")
            off = int(lib.settings["window_offset_samples"])   # windows as the library's were cut
            test = collect_windows(args.seeds, trig, progress=bar.update, window_offset=off)
            train = collect_windows(lib.training["seeds"], trig, window_offset=off)
            bar.update(1)
            unseen = collect_windows(args.unseen_seeds, trig, widths_m=UNSEEN_WIDTHS_M, progress=bar.update,
                                     window_offset=off)
            res, tab = {}, {}
            for mode in MODES:
                for sig in EVAL_SIGNALS[mode]:
                    bar.set_postfix_str(f"{trig}: {mode} {sig}")
                    r = evaluate_mode(lib, test, mode, sig, args.fusion_events)
                    r["continuous_unseen"] = continuous_error(lib, unseen, mode, sig)
                    if mode == "paper":
                        r["mean_only"] = paper_miss_explanation(train, test, r, sig)
                    res[(mode, sig)] = r
                    bar.update(1)
            tab = paper_table_rows(train, test)
            report["triggers"][trig] = {
                "library": lib.path, "library_settings": lib.settings, "n_windows": len(test),
                "results": {f"{m}/{s}": _public(r) for (m, s), r in res.items()}, "paper_tables": tab}
            if not args.no_plots:
                _plots(out_dir, trig, lib, test, unseen, res, staged)
    report["elapsed_s"] = round(time.time() - t0, 1)
    staged[out_dir / "evaluation.json"].write_text(json.dumps(report, indent=1, default=float))
    return report


def _summary(report: dict) -> None:
    print(f"\n{'trigger':13s} {'mode':16s} {'signal':6s} {'acc':>7s} {'fused':>7s} {'margin':>7s} "
          f"{'cont.err':>9s}   accuracy per width (0.0025 ... 0.01 m)")
    for trig, t in report["triggers"].items():
        for key, r in t["results"].items():
            mode, sig = key.split("/")
            print(f"{trig:13s} {mode:16s} {sig:6s} {r['accuracy']:7.4f} {r['fused_accuracy']:7.4f} "
                  f"{r['b_margin_median']:7.2f} {r['continuous_unseen']['mae_m'] * 1e3:6.3f} mm   "
                  + " ".join(f"{a:.3f}" for a in r["accuracy_per_width"]))
    for trig, t in report["triggers"].items():
        print(f"\nThe paper's Tables 1-2 cases (paper mode), trigger {trig}: index of min B (1-based), paper vs ours")
        for row in t["paper_tables"]:
            print(f"  {row['signal']} width {row['width_m']:<7g} eta {row['eta_k']:<6g} n1 {row['n1']:<4g} "
                  f"ep {row['epochs']:2d} l1 {row['l1']:<3g} l2 {row['l2']:<4g}: paper {row['paper_index'] + 1}, "
                  f"ours {row['ours_index_of_mean_b'] + 1} (true {row['true_index'] + 1}; "
                  f"{row['ours_accuracy'] * 100:.0f} % of {row['ours_windows']} windows)  "
                  f"paper B {' '.join(f'{v:.4g}' for v in row['paper_b'])} | ours mean B "
                  f"{' '.join(f'{v:.4g}' for v in row['ours_b_mean'])}")


def _plots(out_dir: Path, trig: str, lib, test, unseen, res: dict, staged: dict) -> None:
    # deferred: matplotlib costs ~180 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    import matplotlib
    matplotlib.use("Agg")
    # deferred: matplotlib.pyplot costs ~450 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    import matplotlib.pyplot as plt
    widths = np.asarray(lib.widths_m)
    keys = list(res)
    ncol = 4
    nrow = math.ceil(len(keys) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.9 * nrow))
    for ax, key in zip(axes.flat, keys):
        r = res[key]
        cm = np.asarray(r["confusion"], dtype=float)
        cmn = cm / np.maximum(cm.sum(axis=1, keepdims=True), 1)
        ax.imshow(cmn, vmin=0, vmax=1, cmap="Blues")
        for i in range(cm.shape[0]):
            for j in range(cm.shape[1]):
                if cm[i, j]:
                    ax.text(j, i, f"{int(cm[i, j])}", ha="center", va="center", fontsize=7,
                            color="white" if cmn[i, j] > 0.5 else "black")
        ax.set_title(f"{key[0]} {key[1]}: {r['accuracy'] * 100:.1f} %", fontsize=9)
        ax.set_xticks(range(widths.size), [f"{w * 1e3:g}" for w in widths], fontsize=7)
        ax.set_yticks(range(widths.size), [f"{w * 1e3:g}" for w in widths], fontsize=7)
        ax.set_xlabel("identified width [mm]", fontsize=8)
        ax.set_ylabel("true width [mm]", fontsize=8)
    for ax in list(axes.flat)[len(keys):]:
        ax.axis("off")
    fig.suptitle(f"Confusion matrices, trigger {trig}, {len(test)} onset windows")
    fig.tight_layout()
    fig.savefig(staged[out_dir / f"confusion_{trig}.png"], dpi=90, format="png")
    plt.close(fig)

    fig, axes = plt.subplots(2, 2, figsize=(13, 8), sharex=True)
    t_ms = np.arange(test.a1.shape[1]) * test.sample_period_s * 1e3
    colors = plt.cm.viridis(np.linspace(0, 1, widths.size))
    for i, w in enumerate(widths):
        sel = np.flatnonzero(np.isclose(test.width_m, w) & np.isclose(test.col("eta_k"), 0.025)
                             & np.isclose(test.col("n1"), 0.89))[:1]
        for k in sel:
            axes[0, 0].plot(t_ms, test.raw_a1[k], color=colors[i], lw=0.4, label=f"{w * 1e3:g} mm")
            axes[1, 0].plot(t_ms, test.a1[k], color=colors[i], lw=1.2)
            axes[0, 1].plot(t_ms, test.raw_a2[k], color=colors[i], lw=0.6)
            axes[1, 1].plot(t_ms, test.a2[k], color=colors[i], lw=1.2)
    for ax, title in zip(axes.flat, ("a1 raw", "a2 raw",
                                     "a1 denoised (sym5, d1-d6 removed), sensor offset removed",
                                     "a2 denoised, sensor offset removed (the classifier's input)")):
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3)
    axes[1, 0].set_xlabel("time after the window start (entry + the trigger's offset) [ms]")
    axes[1, 1].set_xlabel("time after the window start (entry + the trigger's offset) [ms]")
    axes[0, 0].set_ylabel("a1 [m/s^2]")
    axes[0, 1].set_ylabel("a2 [m/s^2]")
    axes[0, 0].legend(fontsize=7)
    fig.suptitle(f"One onset window per width (eta_k 0.025, n1 0.89), trigger {trig}")
    fig.tight_layout()
    fig.savefig(staged[out_dir / f"windows_{trig}.png"], dpi=90, format="png")
    plt.close(fig)

    # deferred: backlash_monitor.classifier.evaluation costs ~740 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.classifier.evaluation import classify_windows
    fig, ax = plt.subplots(1, 3, figsize=(14, 4.2))
    for a, sig in zip(ax, ("a1", "a2", "a1+a2")):
        _, w_hat = classify_windows(lib, unseen, "shape", sig)
        _, w_seen = classify_windows(lib, test, "shape", sig)
        a.plot(test.width_m * 1e3 + np.random.default_rng(0).normal(0, 0.04, len(test)), w_seen * 1e3, ".",
               ms=1.5, alpha=0.3, label="grid widths (evaluation seeds)")
        a.plot(unseen.width_m * 1e3 + np.random.default_rng(1).normal(0, 0.04, len(unseen)), w_hat * 1e3, ".",
               ms=2, alpha=0.5, color="C3", label="unseen widths")
        a.plot([2, 11], [2, 11], "k--", lw=0.8)
        a.set_title(f"shape {sig}: continuous width", fontsize=10)
        a.set_xlabel("true width [mm]")
        a.set_ylabel("estimated width [mm]")
        a.grid(alpha=0.3)
    ax[0].legend(fontsize=7, markerscale=5)
    fig.tight_layout()
    fig.savefig(staged[out_dir / f"continuous_{trig}.png"], dpi=90, format="png")
    plt.close(fig)
