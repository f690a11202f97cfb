"""`python -m backlash_monitor history [DIR_OR_MODEL]`: the model versions and their errors.

Reads workbench_history.jsonl (written by add-effect, compare and diagnose beside the model files) and
prints one row per version with the checks made against measurements: fit % and residual over the
noise floor per signal.
"""
from __future__ import annotations

import json

NAME = "history"
HELP = "list the workbench model versions with their errors on the measurements they were checked against"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    parser.add_argument("where", nargs="?", default=".", metavar="DIR_OR_MODEL",
                        help="a model file or the folder holding workbench_history.jsonl (default: the current folder)")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="print the history as a table (text) or as JSON")
    from backlash_monitor.commands.vocabulary import deprecated
    deprecated(parser, "--json", "--format json", "format", const="json")


def run(args) -> int:
    from pathlib import Path
    from backlash_monitor.commands import UsageError
    from backlash_monitor.commands._workbench import print_table
    from backlash_monitor.workbench.model import read_history
    if not Path(args.where).exists():
        raise UsageError(f"{args.where} does not exist; give a model file or its directory")
    hist = read_history(args.where)
    if not hist:
        raise UsageError(f"no workbench history at {args.where} (add-effect, compare and diagnose write it)")
    if args.format == "json":
        print(json.dumps(hist, indent=1))
        return 0
    versions = [h for h in hist if h.get("type") == "version"]
    checks = [h for h in hist if h.get("type") == "check"]
    rows = []
    for v in versions:
        rows.append((v["model"], f"v{v['version']}", v.get("parent") or "-",
                     "; ".join(f"{a['effect']}({', '.join(f'{k}={x:.4g}' for k, x in a['parameters'].items())})"
                               for a in v.get("added", [])), "", "", ""))
    for c in checks:
        fp, rr = c.get("fit_percent", {}), c.get("residual_over_noise_floor", {})
        rows.append((c["model"], f"v{c['version']}", c["command"], str(c["measurement"])[-40:],
                     f"{fp.get('a1', float('nan')):.1f}/{fp.get('a2', float('nan')):.1f}",
                     f"{rr.get('a1', float('nan')):.2f}/{rr.get('a2', float('nan')):.2f}", c.get("time_utc", "")))
    print_table(rows, ("model", "version", "parent/cmd", "effects / measurement", "fit % a1/a2",
                       "resid/noise a1/a2", "time"))
    return 0
