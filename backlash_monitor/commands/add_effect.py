"""`python -m backlash_monitor add-effect DIAGNOSIS_OR_EFFECT --model M -o M2`: the next model version.

DIAGNOSIS_OR_EFFECT is a `diagnose --json` file (its discovery, its second effect if any, and a torque ripple
found in the raw spectrum (`spectral_discovery`, when confident) are added
with their fitted values) or a catalogue effect's name with its values given by --value NAME=VALUE.
The new version records the effect, its values and uncertainties and its source, and the model's
history (workbench_history.jsonl beside -o) gets a line for it.
"""
from __future__ import annotations

import json
from pathlib import Path

NAME = "add-effect"
HELP = "write the next model version with a (diagnosed) effect switched on at its fitted values"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    from backlash_monitor.commands._workbench import add_model_arguments
    parser.add_argument("source", metavar="DIAGNOSIS_OR_EFFECT",
                        help="a diagnosis JSON (from diagnose --json) or a catalogue effect name")
    add_model_arguments(parser, measurement=False)
    parser.add_argument("-o", "--output", required=True, metavar="M2.yaml", help="the new model version's file")
    parser.add_argument("--value", action="append", default=[], metavar="PARAM=VALUE",
                        help="with an effect name: a parameter's value, e.g. --value mass_kg=12.5 (default: its "
                             "current value); repeatable")
    parser.add_argument("--name", default=None, help="model name (default: the input model's)")
    from backlash_monitor.commands._workbench import add_overwrite_argument
    add_overwrite_argument(parser)


def run(args) -> int:
    from backlash_monitor.commands import UsageError
    from backlash_monitor.commands._workbench import check_outputs, load, print_table
    from backlash_monitor.workbench.model import append_history
    from backlash_monitor.workbench.versions import EffectValues, add_effects
    check_outputs(args, [args.output], "-o")
    model, _ = load(args, measurement=False)
    src = Path(args.source)
    additions = []
    if src.suffix == ".json" or src.is_file():
        if not src.is_file():
            raise UsageError(f"diagnosis {src} does not exist")
        try:
            diag = json.loads(src.read_text())
        except json.JSONDecodeError as exc:
            raise UsageError(f"diagnosis {src} is not JSON: {exc}") from None
        if not isinstance(diag, dict) or "discovery" not in diag:
            raise UsageError(f"{src} is not a diagnose --json file (no 'discovery')")
        spectral_fit = diag.get("spectral_discovery")
        spectral_fit = spectral_fit if isinstance(spectral_fit, dict) and spectral_fit.get("confident") else None
        if diag["discovery"] is None and spectral_fit is None:
            raise UsageError(f"diagnosis {src} names no discovery ({diag.get('message', '')}); nothing to add")
        # the event-average discovery (and its second effect) and a ripple found in the raw spectrum
        for entry in (diag.get("discovery_parameters"), diag.get("second_effect"), spectral_fit):
            # a confident ripple is also the discovery or the second effect (diagnose names it there): once
            if entry and all(a.effect != entry["effect"] for a in additions):
                additions.append(EffectValues(entry["effect"], entry["parameters"], entry.get("uncertainty") or {},
                                              str(src)))
    else:
        values = {}
        for text in args.value:
            if "=" not in text:
                raise UsageError(f"--value {text!r}: expected PARAM=VALUE")
            k, v = text.split("=", 1)
            try:
                values[k.strip()] = float(v)
            except ValueError:
                raise UsageError(f"--value {text!r}: {v!r} is not a number") from None
        additions.append(EffectValues(args.source, values, {}, "command line"))
    try:
        new = add_effects(model, additions, name=args.name)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    out = Path(args.output)
    if not out.parent.exists():
        raise UsageError(f"-o {out}: directory {out.parent} does not exist")
    new.save(out)
    append_history(out, {"type": "version", "model": out.name, "name": new.name, "version": new.version,
                         "parent": new.parent, "added": [a.__dict__ for a in additions]})
    print_table([(a.effect, ", ".join(f"{k}={v:.4g}" for k, v in a.parameters.items()), a.source)
                 for a in additions], ("effect", "values", "from"))
    print(f"wrote {out}: {new.label()} (parent {new.parent})")
    return 0
