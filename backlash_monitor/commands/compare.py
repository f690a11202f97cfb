"""`python -m backlash_monitor compare MEASUREMENT --model M`: the model against a measurement.

The model runs under the measurement's conditions (its pulse train's phase recovered from the onset
entries) for N noise seeds (--ensemble); the onset segments (contact_loss trigger, on both) are aligned at the entry
and averaged over the events. Per signal: fit % (1 - NRMSE) of the denoised event average against the
ensemble mean, the same for the model's own runs (the noise band), the residual over the noise floor,
the event-to-event spread measured vs modelled; whole-record raw spectra against the ensemble's.
Writes PNGs and JSON into --out-dir; docs/workbench.md.
"""
from __future__ import annotations

import json
from pathlib import Path

from backlash_monitor.commands._workbench import (
    add_model_arguments,
    add_overwrite_argument,
    add_progress_argument,
    COMPARE_FILES,
    check_outputs,
    load,
    print_table,
    write_text_staged,
    history_dir,
)
from backlash_monitor.commands.vocabulary import deprecated
from backlash_monitor.commands import UsageError

NAME = "compare"
HELP = "compare a measurement with a model: event-averaged fit %%, spread and spectra against the model's noise band"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    add_model_arguments(parser)
    parser.add_argument("--out-dir", default="compare_out", metavar="DIR",
                        help="folder for compare.json and the PNGs, created if missing")
    parser.add_argument("--json", default=None, metavar="FILE",
                        help="also write the JSON to FILE (default: only DIR/compare.json)")
    parser.add_argument("--no-history", action="store_true",
                        help="do not add this check to the model's history (workbench_history.jsonl)")
    deprecated(parser, "--no-record", "--no-history", "no_history", const=True)
    add_overwrite_argument(parser)
    add_progress_argument(parser)


def compare_result(meas, model, seeds):
    # deferred: numpy costs ~190 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    import numpy as np
    # deferred: backlash_monitor.workbench.analysis costs ~620 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench import analysis
    # deferred: backlash_monitor.workbench.events costs ~240 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.events import SEGMENT_SIGNALS
    comp = analysis.build_comparison(meas, model, list(range(seeds)))
    fp = analysis.fit_percent(comp.target, comp.model_mean)
    band = analysis.noise_band_fit_percent(comp)
    ratio = analysis.residual_ratio(comp)
    spec = analysis.spectra(comp)
    res = {"measurement": meas.source, "model": model.label(), "conditions": comp.conditions,
           "events": comp.events.n_events, "seeds": comp.seeds,
           "fit_percent": dict(zip(SEGMENT_SIGNALS, map(float, fp))),
           "noise_band_fit_percent": {s: {"min": float(band[:, i].min()), "median": float(np.median(band[:, i])),
                                          "max": float(band[:, i].max())} for i, s in enumerate(SEGMENT_SIGNALS)},
           "residual_over_noise_floor": dict(zip(SEGMENT_SIGNALS, map(float, ratio))),
           "spread": analysis.spread(comp), "spectral_peaks": analysis.spectral_peaks(spec)}
    return res, comp, spec


def run(args) -> int:
    # deferred: tqdm costs ~40-140 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from tqdm import tqdm
    # deferred: backlash_monitor.workbench.report costs ~690 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench import report
    # deferred: backlash_monitor.workbench.analysis costs ~620 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.analysis import ConditionsError
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import record_check
    out = Path(args.out_dir)
    check_outputs(args, [out / f for f in COMPARE_FILES], "--out-dir")
    if args.json:
        check_outputs(args, [args.json], "--json")
    model, meas = load(args)
    out.mkdir(parents=True, exist_ok=True)
    with tqdm(total=1, desc=f"model ensemble ({args.ensemble} seeds)",
              disable=True if args.no_progress else None) as bar:
        try:
            res, comp, spec = compare_result(meas, model, args.ensemble)
        except (ConditionsError, ValueError) as exc:
            raise UsageError(str(exc)) from None
        bar.update(1)
    report.plot_event_average(comp, out / "event_average.png", title=f"{model.label()} vs measurement")
    report.plot_spectra(comp, spec, out / "spectra.png")
    text = json.dumps(res, indent=1, default=float)
    write_text_staged(out / "compare.json", text)
    if args.json:
        write_text_staged(args.json, text)
    if not args.no_history:
        record_check(model, meas.source, "compare", res["fit_percent"], res["residual_over_noise_floor"],
                     directory=history_dir(args, out.parent))
    rows = [(s, f"{res['fit_percent'][s]:.1f}", f"{res['noise_band_fit_percent'][s]['median']:.1f}",
             f"{res['residual_over_noise_floor'][s]:.2f}", f"{res['spread'][s]['measured']:.4g}",
             f"{res['spread'][s]['model_median']:.4g}", ",".join(f"{f:.0f}" for f in res["spectral_peaks"][s]["peaks_hz"])
             or "-") for s in ("a1", "a2")]
    print(f"{model.label()} vs {meas.source}: {res['events']} onset events, {len(res['seeds'])} model seeds")
    print_table(rows, ("signal", "fit %", "band fit %", "resid/noise", "spread meas", "spread model",
                       "peaks > band [Hz]"))
    print(f"wrote {out}/compare.json, event_average.png, spectra.png")
    return 0
