"""`python -m backlash_monitor add-effect DIAGNOSIS_OR_EFFECT -o M2`: the next model version.

DIAGNOSIS_OR_EFFECT is a `diagnose --json` file or a catalogue effect's name with its values given by --value NAME=VALUE.

From a diagnosis, the new version is built on the model the diagnosis was made against -- its file, nominal width,
eta_k and n1, --set overrides and effect files, all recorded in the diagnosis's `conditions` -- and takes its
`additions`: the discovered effect (and a second effect, or a torque ripple found in the raw spectrum) with their
fitted values. A backlash width that differs from the model's nominal is the monitor's measurand, never an effect:
the new version's nominal width is set to the measured width instead. A partial explanation (an effect that leaves
part of the residual unexplained) is added only with --accept-partial. The new version records where it came from
(`provenance`), so that `train --model` can check the retrained monitor against the diagnosis. The model's history
(workbench_history.jsonl beside -o) gets a line for it.
"""
from __future__ import annotations

import json
from pathlib import Path
import json as _json
import copy
import datetime as _dt

from backlash_monitor.commands._workbench import (
    add_model_arguments,
    add_overwrite_argument,
    check_outputs,
    load,
    print_table,
    apply_drive,
)
from backlash_monitor.commands import UsageError

NAME = "add-effect"
HELP = "write the next model version with a (diagnosed) effect switched on at its fitted values"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    parser.add_argument("source", metavar="DIAGNOSIS_OR_EFFECT",
                        help="a diagnosis JSON (from diagnose --json) or a catalogue effect name")
    add_model_arguments(parser, measurement=False)
    parser.add_argument("-o", "--output", default=None, metavar="M2.yaml",
                        help="the new model version's file (with --drive, default: DRIVE_vN.yaml beside the registry)")
    parser.add_argument("--value", action="append", default=[], metavar="PARAM=VALUE",
                        help="with an effect name: a parameter's value, e.g. --value mass_kg=12.5 (default: its "
                             "current value); repeatable")
    parser.add_argument("--accept-partial", action="store_true",
                        help="with a diagnosis whose verdict is 'partial': add its effect(s) anyway. They explain "
                             "only part of the residual (the rest is outside the catalogue, or a catalogue effect in "
                             "another form): the new version is a better approximation, not the drive's physics, "
                             "and the monitor retrained on it may still be biased")
    parser.add_argument("--accept-proposal", action="store_true",
                        help="with a diagnosis that proposes a term outside the catalogue (its JSON's 'proposal'): "
                             "write the term as a plug-in file beside -o (M2_proposed_term.py, bounded parameters "
                             "you can read and edit) and add it at its fitted values, with the partial explanation "
                             "it was fitted on top of")
    parser.add_argument("--name", default=None, help="model name (default: the input model's)")
    add_overwrite_argument(parser)


def _model_difference(a, b) -> str | None:
    """How model ``a`` differs from ``b`` in what a diagnosis depends on (nominal values, plant, effect files)."""
    for key in ("width_m", "eta_k", "n1"):
        if abs(float(a.nominal[key]) - float(b.nominal[key])) > 1e-12 * max(abs(float(b.nominal[key])), 1.0):
            return f"nominal {key} {a.nominal[key]:g} (the diagnosis: {b.nominal[key]:g})"
    if _json.dumps(a.plant, sort_keys=True, default=repr) != _json.dumps(b.plant, sort_keys=True, default=repr):
        return "other plant values or effects"
    if {str(Path(f).resolve()) for f in a.effect_files} != {str(Path(f).resolve()) for f in b.effect_files}:
        return "other effect files"
    return None


def _base_from_diagnosis(args, conditions, src):
    """The model the diagnosis was made against (its recorded effective model). Options that name a model
    (--model, --set, --width-m, --eta-k, --n1, --effects-file) must give that same model: the fitted values are
    relative to it."""
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import ModelError, load_model, model_from_dict
    try:
        recorded = load_model(None, base=model_from_dict(conditions.model, base_dir=Path(src).resolve().parent))
    except ModelError as exc:
        raise UsageError(f"the model recorded in {src}: {exc}") from None
    if conditions.model_file and Path(conditions.model_file).is_file():
        recorded.path = Path(conditions.model_file)
    given = (args.model or args.set or args.effects_file
             or any(v is not None for v in (args.width_m, args.eta_k, args.n1)))
    if not given:
        return recorded
    try:
        explicit = load_model(args.model, args.set, args.width_m, args.eta_k, args.n1, effect_files=args.effects_file)
    except ModelError as exc:
        raise UsageError(str(exc)) from None
    diff = _model_difference(explicit, recorded)
    if diff:
        raise UsageError(f"the model given here has {diff}: the diagnosis {src} was made against "
                         f"{conditions.model_file or conditions.model_label}, and its fitted values are relative to "
                         "that model; omit the model options (add-effect then builds on the diagnosed model), or "
                         "diagnose again against this one")
    return explicit


def _take_proposal(diag, src, adds, model, output):
    """(additions, model, note) with a diagnosis's proposed term: its plug-in file written beside ``output`` and put
    into the model's effect files; the additions its proposal was fitted on top of (at their values refitted jointly
    with the term, when the proposal holds them), and the term at its values."""
    # deferred: backlash_monitor.workbench.diagnosis_result costs ~170 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.diagnosis_result import ROLE_SECOND, Addition
    prop = diag.get("proposal")
    if not isinstance(prop, dict) or not prop.get("proposed"):
        why = prop.get("reason") if isinstance(prop, dict) else "its verdict is not partial or nothing_explains"
        raise UsageError(f"diagnosis {src} proposes no term (--accept-proposal): {why}")
    if not prop.get("plugin_source"):
        # the step that remains, by the verdict: the partial effect the term was fitted on, or the discovered effect
        partial = {"partial": " (or take the partial explanation the term was fitted on, the nearer model: "
                              "--accept-partial)",
                   "discovery": " (the discovered effect goes in alone without --accept-proposal: add-effect "
                                f"{src} -o FILE)"}.get(diag.get("verdict"), "")
        raise UsageError(f"diagnosis {src}'s proposed term has no plug-in form (--accept-proposal): {prop.get('law')} "
                         "acts on a sensor's signal through the drive's states or the other channel, or changes with the time "
                         "in the record, not in the drive's physics; "
                         "check that sensor (its mounting, wiring, calibration) instead of adding it to the model"
                         + partial)
    path = output.with_name(output.stem + "_proposed_term.py")
    path.write_text(prop["plugin_source"])
    model = copy.copy(model)
    model.effect_files = list(model.effect_files) + [path.resolve()]
    kept = [a for a in adds if a.effect in prop.get("on_top_of", []) or a.candidate in prop.get("on_top_of", [])]
    # the partial explanation the term was fitted on top of is part of the proposal (the term without it is another
    # model than the one fitted: it goes in without --accept-partial), at its values refitted jointly with the term
    # (proposal._joint_refit) where the proposal holds them, else at diagnose's values of it alone
    joint, joint_unc = prop.get("on_top_values") or {}, prop.get("on_top_uncertainty") or {}
    kept = [Addition(a.effect, a.candidate, dict(joint.get(a.candidate, a.parameters)),
                     dict(joint_unc.get(a.candidate, a.uncertainty)), ROLE_SECOND, a.evidence) for a in kept]
    for effect, values in prop["plugin_values"].items():
        kept.append(Addition(effect, effect, dict(values), {}, "discovery", "proposal"))
    return kept, model, f"proposed term added (--accept-proposal): {prop['law']}; its plug-in file {path}"


def run(args) -> int:
    # deferred: backlash_monitor.workbench.diagnosis_result costs ~170 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.diagnosis_result import ROLE_PARTIAL, read_handoff
    # deferred: backlash_monitor.workbench.model costs ~1300 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.model import append_history
    # deferred: backlash_monitor.workbench.versions costs ~1240 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.workbench.versions import EffectValues, add_effects
    entry = apply_drive(args)
    if args.output is None and entry is None:
        raise UsageError("add-effect needs -o M2.yaml (the new model version's file), or --drive NAME")
    src = Path(args.source)
    additions, nominal, provenance, notes, all_taken = [], {}, {}, [], False
    if src.suffix == ".json" or src.is_file():
        if not src.is_file():
            raise UsageError(f"diagnosis {src} does not exist")
        try:
            diag = json.loads(src.read_text())
            conditions, adds, verdict = read_handoff(diag, str(src))
        except json.JSONDecodeError as exc:
            raise UsageError(f"diagnosis {src} is not JSON: {exc}") from None
        except (ValueError, KeyError, TypeError) as exc:
            raise UsageError(f"diagnosis {src}: {exc}") from None
        model = _base_from_diagnosis(args, conditions, src) if conditions else load(args, measurement=False)[0]
        all_taken = True   # every addition at its fitted values: the diagnosis's fit "after" is this version's
        if args.accept_proposal:
            adds, model, note = _take_proposal(diag, src, adds, model, Path(args.output))
            notes.append(note)
        partial = [a for a in adds if a.role == ROLE_PARTIAL]
        confident = [a for a in adds if a.role != ROLE_PARTIAL]
        width = diag.get("measured_width") or {}
        if partial and not args.accept_partial:
            if not confident and not width.get("differs_from_nominal"):
                raise UsageError(
                    f"diagnosis {src} is partial: {', '.join(a.candidate for a in partial)} explains only part of the "
                    f"residual ({diag.get('message', '')}). Pass --accept-partial to add it anyway: the new version "
                    "is then a better approximation, not the drive's physics")
            notes.append(f"not added: {', '.join(a.candidate for a in partial)} explains only part of the residual "
                         "(--accept-partial adds it)")
            adds = confident
            all_taken = False
        elif partial:
            notes.append(f"partial explanation added on request (--accept-partial): {', '.join(a.candidate for a in partial)} "
                         "explains only part of the residual; the monitor retrained on it may still be biased")
        src_label = f"{src} of {_dt.datetime.fromtimestamp(src.stat().st_mtime, _dt.timezone.utc):%Y-%m-%d %H:%M} UTC"
        additions = [EffectValues(a.effect, a.parameters, a.uncertainty, src_label) for a in adds]
        if width.get("differs_from_nominal"):
            nominal["width_m"] = float(width["width_m"])
            notes.append(f"the backlash width measured {width['width_m'] * 1e3:.3f} mm (nominal "
                         f"{width['nominal_width_m'] * 1e3:.3f} mm): the monitor's measurand, set as the new "
                         "version's nominal width, not added as an effect")
        if not additions and not nominal:
            raise UsageError(f"diagnosis {src} names no effect to add (verdict {verdict or diag.get('discovery')}: "
                             f"{diag.get('message', '')}); nothing to add")
        provenance = {"diagnosis": str(src.resolve()),
                      "diagnosis_time_utc": _dt.datetime.fromtimestamp(src.stat().st_mtime, _dt.timezone.utc)
                      .isoformat(timespec="seconds"),
                      "diagnosed_model": {"name": model.name, "version": model.version}, "measurement": str(Path(conditions.measurement).resolve())
                      if conditions and Path(conditions.measurement).exists() else
                      (conditions.measurement if conditions else diag.get("measurement")),
                      "width_m": float(width.get("width_m", model.nominal["width_m"])),
                      "width_uncertainty_m": width.get("uncertainty_m"), "verdict": verdict}
        if args.accept_proposal:
            # the proposed term taken: whether the model with it explains the recording (train's check reads it)
            provenance["proposal_consistent"] = bool((diag.get("proposal") or {}).get("consistent"))
    else:
        model, _ = load(args, measurement=False)
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
    if entry is not None and model.path is None:
        model.name = entry.model_name
    if args.output is None:
        args.output = str(Path(args.registry).resolve().parent / f"{entry.model_name}_v{model.version + 1}.yaml")
    check_outputs(args, [args.output], "-o")
    try:
        new = add_effects(model, additions, name=args.name, nominal=nominal, provenance=provenance)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    out = Path(args.output)
    if not out.parent.exists():
        raise UsageError(f"-o {out}: directory {out.parent} does not exist")
    new.save(out)
    updates = new.nominal_updates[len(model.nominal_updates):]
    folded = {u["effect"] for u in updates}
    changed = {**{k: {"from": model.nominal[k], "value": v, "uncertainty": provenance.get("width_uncertainty_m")}
                  for k, v in nominal.items()},
               **{u["parameter"]: {"from": u["from"], "value": u["value"], "uncertainty": u["uncertainty"]}
                  for u in updates}}
    additions = [a for a in additions if a.effect not in folded]
    append_history(out, {"type": "version", "model": out.name, "name": new.name, "version": new.version,
                         "parent": new.parent, "added": [a.__dict__ for a in additions],
                         "nominal_changed": changed or None, "provenance": provenance or None})
    if provenance and all_taken:
        # the diagnosis fitted exactly these values on its recording: its fit "after" is this version's fit there
        fp, rr = diag.get("fit_percent") or {}, diag.get("residual_over_noise_floor") or {}
        if fp.get("after") and rr.get("after"):
            append_history(out, {"type": "check", "model": out.name, "name": new.name, "version": new.version,
                                 "measurement": provenance.get("measurement"), "command": "diagnose (fit after)",
                                 "fit_percent": fp["after"], "residual_over_noise_floor": rr["after"]})
    if additions:
        print_table([(a.effect, ", ".join(f"{k}={v:.4g}" for k, v in a.parameters.items()), a.source)
                     for a in additions], ("effect", "values", "from"))
    for u in updates:
        print(f"nominal {u['parameter']}: {u['from']:.4g} -> {u['value']:.4g}"
              + (f" ± {u['uncertainty']:.2g}" if u["uncertainty"] is not None else "")
              + f", from {u['from_diagnosis']} ({u['effect']}: the new nominal value, not an effect)")
    for n in notes:
        print(f"note: {n}")
    print(f"wrote {out}: {new.label()} (parent {new.parent}; nominal width {new.nominal['width_m'] * 1e3:.3f} mm, "
          f"eta_k {new.nominal['eta_k']:g}, n1 {new.nominal['n1']:g})")
    return 0
