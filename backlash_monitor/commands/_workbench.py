"""Shared options and loading of the workbench commands (compare, diagnose, add-effect, history)."""
from __future__ import annotations

import sys


def add_model_arguments(parser, measurement: bool = True) -> None:
    if measurement:
        parser.add_argument("measurement", help="the drive's recording: an MCAP bag with the project's topics (any "
                                                "namespace), or a CSV/NPZ table (layout: docs/workbench.md)")
        parser.add_argument("--namespace", default=None,
                            help="namespace of the drive's topics in the bag (default: found by the topic names)")
        parser.add_argument("--row", type=int, default=0, help="row of a `simulate` NPZ with several scenarios")
    parser.add_argument("--model", default=None, metavar="M.yaml",
                        help="workbench model file (docs/workbench.md); default: config/plant.yaml at the nominal "
                             "conditions below")
    parser.add_argument("--set", action="append", default=[], metavar="SECTION.KEY=VALUE",
                        help="override one plant config value of the model, e.g. --set load.mass_kg=12; repeatable")
    parser.add_argument("--effects-file", action="append", default=[], metavar="FILE.py",
                        help="a Python file with your own Effect classes (docs/effects.md): registered, fitted as "
                             "candidates by diagnose, usable in --set, and kept in the model add-effect writes; "
                             "repeatable")
    parser.add_argument("--width-m", type=float, default=None, help="the drive's nominal backlash width [m]")
    parser.add_argument("--eta-k", type=float, default=None, help="nominal absorber consistency eta_k [Pa*s^n]")
    parser.add_argument("--n1", type=float, default=None, help="nominal absorber flow index n1 [-]")
    parser.add_argument("--seeds", type=int, default=6, metavar="K",
                        help="noise seeds of the model's ensemble (>= 3; the band and the fits use them)")


def model_overrides(args) -> dict:
    """The overrides given on the command line (--set, --width-m, --eta-k, --n1, --effects-file), as recorded in
    a diagnosis's conditions."""
    out = {}
    for text in getattr(args, "set", []) or []:
        key, _, value = text.partition("=")
        out[key.strip()] = value.strip()
    for key in ("width_m", "eta_k", "n1"):
        v = getattr(args, key, None)
        if v is not None:
            out[f"nominal.{key}"] = v
    for f in getattr(args, "effects_file", []) or []:
        out.setdefault("effects_file", []).append(str(f))
    return out


REPORT_FILES = ("index.html", "event_average.png", "event_residuals.png", "where.png", "ranked.png", "spectra.png")
COMPARE_FILES = ("compare.json", "event_average.png", "spectra.png")


def add_overwrite_argument(parser) -> None:
    parser.add_argument("--overwrite", action="store_true",
                        help="replace output files that exist already (default: refuse, naming the file)")


def check_outputs(args, outputs, option: str) -> None:
    """Before any work: no output may be one of the command's inputs (the measurement, the model
    file), nor an existing file unless --overwrite (backlash_monitor.files.outputs)."""
    from backlash_monitor.commands import UsageError
    from backlash_monitor.files.outputs import OutputError, check_outputs as check
    inputs = [p for p in (getattr(args, "measurement", None), args.model, getattr(args, "source", None)) if p]
    try:
        check(outputs, inputs=inputs, overwrite=args.overwrite, option=option)
    except OutputError as exc:
        raise UsageError(str(exc)) from None


def write_text_staged(path, text: str) -> None:
    """Write ``text`` to ``path`` under its .partial name, renamed once complete."""
    from backlash_monitor.files.outputs import staged_outputs
    with staged_outputs([path]) as (tmp,):
        tmp.write_text(text)


def load(args, measurement: bool = True):
    from backlash_monitor.commands import UsageError
    from backlash_monitor.workbench.measurement import MeasurementError, check_against_model, load_measurement
    from backlash_monitor.workbench.model import ModelError, load_model
    if not 3 <= args.seeds <= 64:
        raise UsageError(f"--seeds {args.seeds}: allowed 3 <= K <= 64")
    try:
        model = load_model(args.model, args.set, args.width_m, args.eta_k, args.n1,
                           effect_files=args.effects_file)
    except ModelError as exc:
        raise UsageError(str(exc)) from None
    if not measurement:
        return model, None
    try:
        meas = load_measurement(args.measurement, args.namespace, args.row)
        check_against_model(meas, model)
    except MeasurementError as exc:
        raise UsageError(str(exc)) from None
    return model, meas


def print_table(rows, header, file=None) -> None:
    file = sys.stdout if file is None else file
    rows = [tuple(str(c) for c in r) for r in rows]
    widths = [max(len(str(h)), *(len(r[i]) for r in rows)) if rows else len(str(h)) for i, h in enumerate(header)]
    print("  ".join(str(h).rjust(w) for h, w in zip(header, widths)), file=file)
    print("  ".join("-" * w for w in widths), file=file)
    for r in rows:
        print("  ".join(c.rjust(w) for c, w in zip(r, widths)), file=file)
