"""Shared options and loading of the workbench commands (compare, diagnose, add-effect, history)."""
from __future__ import annotations

import sys
from pathlib import Path

from backlash_monitor.files.registry import DEFAULT_REGISTRY, RegistryError, find
from backlash_monitor.commands import UsageError
from backlash_monitor.commands.vocabulary import deprecated
from backlash_monitor.files.outputs import OutputError, check_outputs as check, staged_outputs
from backlash_monitor.errors import out_of_range


def add_drive_arguments(parser) -> None:
    """--drive NAME and --registry PATH: the drive registry (docs/registry.md) gives the drive's model version,
    library and watch reference."""
    parser.add_argument("--drive", default=None, metavar="NAME",
                        help="a drive of the registry (LINE/DRIVE, or DRIVE when unique): its current model version "
                             "(or the default model at its nominal width, eta_k, n1), library and watch reference")
    parser.add_argument("--registry", default=DEFAULT_REGISTRY, metavar="PATH",
                        help=f"the drive registry YAML (docs/registry.md; default: ./{DEFAULT_REGISTRY})")


def drive_entry(args):
    """The registry's entry of --drive (None without --drive); a UsageError naming the problem."""
    if not getattr(args, "drive", None):
        return None
    try:
        return find(args.registry, args.drive)
    except RegistryError as exc:
        raise UsageError(str(exc)) from None


def apply_drive(args):
    """With --drive: the drive's model file as --model (unless one is given), or the default model at the
    drive's nominal conditions (where --width-m/--eta-k/--n1 give none). -> the entry or None."""
    entry = drive_entry(args)
    if entry is None:
        return None
    if getattr(args, "model", None) is None and entry.model is not None:
        args.model = str(entry.model)
    elif getattr(args, "model", None) is None:
        for key, value in entry.nominal.items():
            if getattr(args, key, None) is None:
                setattr(args, key, value)
    return entry


def history_dir(args, default):
    """Where a check of an unsaved model goes: beside the registry with --drive, else ``default``."""
    return Path(args.registry).resolve().parent if getattr(args, "drive", None) else default


def add_model_arguments(parser, measurement: bool = True) -> None:
    if measurement:
        parser.add_argument("measurement", help="the drive's recording: an MCAP bag with the project's topics (any "
                                                "namespace), or a CSV/NPZ table (layout: docs/workbench.md)")
        parser.add_argument("--namespace", default=None,
                            help="namespace of the drive's topics in the bag (default: the one drive the bag holds, "
                                 "found by the topic names)")
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
    parser.add_argument("--width-m", type=float, default=None, metavar="M",
                        help="the drive's nominal backlash width [m] (default: the model's nominal; "
                             f"without --model: {_nominal('width_m'):g})")
    parser.add_argument("--eta-k", type=float, default=None,
                        help="nominal absorber consistency eta_k [Pa*s^n] (default: the model's nominal; "
                             f"without --model: {_nominal('eta_k'):g})")
    parser.add_argument("--n1", type=float, default=None,
                        help="nominal absorber flow index n1 [-] (default: the model's nominal; "
                             f"without --model: {_nominal('n1'):g})")
    parser.add_argument("--ensemble", type=int, default=6, metavar="N",
                        help="size of the model's noise ensemble: seeds 0..N-1, 3 <= N <= 64 (the band and the fits "
                             "use them)")
    deprecated(parser, "--seeds", "--ensemble", "ensemble", type=int, metavar="N")
    add_drive_arguments(parser)


def add_progress_argument(parser) -> None:
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


# The default model's nominal values (workbench/model.py DEFAULT_NOMINAL, which imports the plant: seconds at
# start-up), shown as the defaults of --width-m, --eta-k, --n1; test_cli_vocabulary checks they are the same.
DEFAULT_NOMINAL_SHOWN = {"width_m": 0.0075, "eta_k": 0.025, "n1": 0.89}


def _nominal(key: str) -> float:
    return DEFAULT_NOMINAL_SHOWN[key]


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
    inputs = [p for p in (getattr(args, "measurement", None), args.model, getattr(args, "source", None)) if p]
    try:
        check(outputs, inputs=inputs, overwrite=args.overwrite, option=option)
    except OutputError as exc:
        raise UsageError(str(exc)) from None


def write_text_staged(path, text: str) -> None:
    """Write ``text`` to ``path`` under its .partial name, renamed once complete."""
    with staged_outputs([path]) as (tmp,):
        tmp.write_text(text)


def load(args, measurement: bool = True):
    # deferred: backlash_monitor.workbench.measurement costs ~340 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.measurement import MeasurementError, check_against_model, load_measurement
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import NOMINAL_RANGES, ModelError, load_model
    if not 3 <= args.ensemble <= 64:
        raise out_of_range("--ensemble", args.ensemble, 3, 64)
    for key, unit in (("width_m", "m"), ("eta_k", "Pa*s^n"), ("n1", "")):
        value, (low, high) = getattr(args, key, None), NOMINAL_RANGES[key]
        if value is not None and not low < value <= high:
            raise UsageError(f"--{key.replace('_', '-')} {value:g}: out of range, allowed {low:g}..{high:g}"
                             f"{' ' + unit if unit else ''}, above {low:g}")
    entry = apply_drive(args)
    try:
        model = load_model(args.model, args.set, args.width_m, args.eta_k, args.n1,
                           effect_files=args.effects_file)
    except ModelError as exc:
        raise UsageError(str(exc)) from None
    if entry is not None and model.path is None:
        model.name = entry.model_name      # the drive's versions carry its name in the history
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
