"""`python -m backlash_monitor diagnose MEASUREMENT --model M`: where the model fails, which effect is missing.

The residual of the event average per phase (before entry, gap traversal, impact, settling), per sym5
level, its spectral peaks, whiteness (Ljung-Box at the noise's decorrelation spacing) and correlation
with the inputs, each against the model ensemble's band; then every catalogue effect fitted (bounded
least squares on common random numbers), ranked by BIC on the events (the independent units), the
winner with its values ± uncertainty and explained share, indistinguishable pairs, a second effect on
top. docs/workbench.md has the method and the decision rules.
"""
from __future__ import annotations

import argparse
import json
from pathlib import Path

from backlash_monitor.commands._workbench import (
    add_model_arguments,
    add_overwrite_argument,
    add_progress_argument,
    REPORT_FILES,
    check_outputs,
    load,
    print_table,
    write_text_staged,
    history_dir,
    model_overrides,
)
from backlash_monitor.errors import DeprecatedSpelling
from backlash_monitor.commands.vocabulary import deprecated
from backlash_monitor.commands import UsageError

NAME = "diagnose"
HELP = "find where the model fails on a measurement and which catalogue effect is missing (JSON + HTML report)"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    add_model_arguments(parser)
    parser.add_argument("--json", default=None, metavar="FILE", help="write the diagnosis JSON to FILE "
                        "(default: diagnosis.json in --report, or ./diagnosis.json)")
    parser.add_argument("--report", default=None, metavar="DIR",
                        help="also write the HTML report (index.html) and its PNGs into DIR, created if missing "
                             "(default: no report)")
    parser.add_argument("--candidates", default=None, metavar="NAME[,NAME...]",
                        help="fit only these catalogue effects as candidates (default: the whole catalogue; "
                             "your own effects from a file: --effects-file)")
    parser.add_argument("--effects", dest="candidates", action=DeprecatedSpelling, new="--candidates",
                        metavar="NAME[,NAME...]", help=argparse.SUPPRESS)
    parser.add_argument("--no-second", action="store_true", help="do not try a second effect on top")
    parser.add_argument("--no-history", action="store_true",
                        help="do not add this check to the model's history (workbench_history.jsonl)")
    deprecated(parser, "--no-record", "--no-history", "no_history", const=True)
    add_overwrite_argument(parser)
    add_progress_argument(parser)


def run(args) -> int:
    # deferred: tqdm costs ~40-140 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from tqdm import tqdm
    # deferred: backlash_monitor.workbench.report costs ~690 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench import drive_terms, plant_adapter, report
    # deferred: backlash_monitor.workbench.analysis costs ~620 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.analysis import ConditionsError
    # deferred: backlash_monitor.workbench.diagnose costs ~1310 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.diagnose import diagnose
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import record_check
    effects = [e.strip() for e in args.candidates.split(",") if e.strip()] if args.candidates else None
    files = [e for e in effects or [] if e.endswith(".py")]
    if files:
        raise UsageError(f"--candidates {','.join(files)}: names catalogue effects; a Python file of "
                         f"your own effects is given with --effects-file {files[0]}")
    json_path = Path(args.json) if args.json else (Path(args.report) / "diagnosis.json" if args.report
                                                   else Path("diagnosis.json"))
    check_outputs(args, [json_path], "--json" if args.json or not args.report else "--report")
    if args.report:
        check_outputs(args, [Path(args.report) / f for f in REPORT_FILES], "--report")
    model, meas = load(args)
    n = len(effects) if effects else len(plant_adapter.catalogue(model))
    with tqdm(total=n, desc="screening candidate effects", unit="effect", disable=True if args.no_progress else None) as bar:
        try:
            result = diagnose(meas, model, seeds=list(range(args.ensemble)), effects=effects, progress=bar.update,
                              second=not args.no_second, overrides=model_overrides(args))
        except (ConditionsError, ValueError) as exc:
            raise UsageError(str(exc)) from None
    json_path.parent.mkdir(parents=True, exist_ok=True)
    pub = result.to_json()
    write_text_staged(json_path, json.dumps(pub, indent=1, default=float))
    if args.report:
        page = report.write_report(result, args.report, json_path=json_path)
        print(f"report: {page}")
    if not args.no_history:
        where = record_check(model, meas.source, "diagnose", pub["fit_percent"]["before"],
                             pub["residual_over_noise_floor"]["before"],
                             directory=history_dir(args, json_path.parent))
        print(f"history: this check of {model.label()} added to {where} (`history` lists it)")
    rows = []
    for r in pub["ranked"]:
        unc = r.get("uncertainty") or {}
        vals = ", ".join(f"{k}={v:.4g}" + (f"±{unc[k]:.2g}" if k in unc else "") for k, v in r["parameters"].items())
        rows.append((r["effect"], vals, "screened" if r["delta_ic"] is None else f"{r['delta_ic']:.1f}",
                     f"{r['explained_fraction']:.0%}"))
    print_table(rows, ("effect", "fitted", "delta IC", "explained"))
    fp = pub["fit_percent"]
    print("fit %: " + ", ".join(f"{s} {fp['before'][s]:.1f} -> {fp['after'][s]:.1f} (band {fp['noise_band_median'][s]:.1f})"
                                for s in ("a1", "a2")))
    print(f"verdict: {pub['verdict']}: {pub['message']}")
    print()
    for line in drive_terms.summary_lines(pub, model):
        print(line)
    if pub["additions"]:
        print("for the next model version (add-effect " + str(json_path) + "): " + ", ".join(
            f"{a['candidate']} ({a['role']})" for a in pub["additions"]))
    print(f"wrote {json_path} ({pub['seconds']:.1f} s)")
    return 0
