"""`python -m backlash_monitor history [DIR_OR_MODEL]`: the model versions and their errors.

Reads workbench_history.jsonl (written by diagnose, compare, add-effect and train beside the model files, or for
the default model beside the diagnosis) and prints one row per version: where it came from (the diagnosis and its
date), what changed, its fit % and residual over the noise floor per signal on the recording it was last checked
against, the monitor's width with the library trained on it, and its date. A version never checked says so.
--plot writes the error per version as a PNG, --report an HTML page with the table and the plot.
"""
from __future__ import annotations

import json
from pathlib import Path

from backlash_monitor.commands.vocabulary import deprecated
from backlash_monitor.commands._workbench import add_drive_arguments, add_overwrite_argument, print_table, drive_entry
from backlash_monitor.commands import UsageError
from backlash_monitor.files.outputs import OutputError, check_outputs
from backlash_monitor.workbench.history import HEADER, plot_history, version_rows, write_html

NAME = "history"
HELP = "list the workbench model versions with their errors on the measurements they were checked against"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    parser.add_argument("where", nargs="?", default=".", metavar="DIR_OR_MODEL",
                        help="a model file or the folder holding workbench_history.jsonl (default: the current folder)")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="print the history as a table (text) or as JSON")
    deprecated(parser, "--json", "--format json", "format", const="json")
    parser.add_argument("--plot", default=None, metavar="PNG", help="write the error per version as a PNG (default: no plot)")
    parser.add_argument("--report", default=None, metavar="DIR",
                        help="write an HTML page (index.html, history.png) with the table and the plot into DIR, created if "
                             "missing (default: no page)")
    add_overwrite_argument(parser)
    add_drive_arguments(parser)


def run(args) -> int:
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import read_history
    entry = drive_entry(args)
    names = None
    if entry is not None:
        names = {entry.model_name}
        if entry.model is not None:
            # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
            from backlash_monitor.workbench.model import ModelError, load_model
            try:
                names.add(load_model(entry.model).name)
            except ModelError as exc:
                raise UsageError(f"drive {entry.hardware_id}: {exc}") from None
        args.where = str(entry.model.parent if entry.model is not None else Path(args.registry).resolve().parent)
    if not Path(args.where).exists():
        raise UsageError(f"{args.where} does not exist; give a model file or its directory")
    if args.plot and not str(args.plot).lower().endswith(".png"):
        raise UsageError(f"--plot {args.plot}: the plot is a PNG; give a name ending in .png")
    try:
        if args.plot:
            check_outputs([args.plot], overwrite=args.overwrite, option="--plot")
        if args.report:
            check_outputs([Path(args.report) / f for f in ("index.html", "history.png")], overwrite=args.overwrite,
                          option="--report")
    except OutputError as exc:
        raise UsageError(str(exc)) from None
    hist = read_history(args.where)
    if not hist:
        raise UsageError(f"no workbench history at {args.where} (diagnose, compare, add-effect and train write it "
                         "beside the model file, or beside the diagnosis for the default model)")
    if args.format == "json":
        print(json.dumps(hist, indent=1))
        return 0
    rows = version_rows(hist)
    if names is not None:
        rows = [r for r in rows if r.name in names]
        if not rows:
            raise UsageError(f"no workbench history of drive {entry.hardware_id} at {args.where} (diagnose --drive "
                             f"{args.drive} writes it)")
        print(f"drive {entry.hardware_id} ({args.registry}): version {entry.version}, model "
              f"{entry.model or 'default at its nominal'}, library {entry.library or 'packaged'}, watch reference "
              f"{entry.watch_reference or 'default'}")
    print_table([r.cells() for r in rows], HEADER)
    if args.plot:
        print(f"wrote {plot_history(rows, args.plot)}")
    if args.report:
        print(f"wrote {write_html(rows, args.report)}")
    return 0
