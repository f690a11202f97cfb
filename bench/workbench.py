"""Model-workbench goals (issue 11) on a hidden-effect suite: one JSON object on stdout, all else on stderr.

Suite: 4 s recordings made by the project's simulator with seeds (9001..) and strengths the tests do not
use: clean drives, one-effect drives, two-effect drives and one effect outside the catalogue. Per recording
`diagnose` (whole catalogue, 6 seeds); for the discoveries the effect is added (versions.add_effects with
the fitted values) and the new version compared (residual over the noise floor). The width check
(width_check): 4 hidden-effect drives, each diagnosed on its own recording, the effect added, the pattern
library retrained on that drive's updated model (`train --model` core), the monitor's widths at 3 widths
before (packaged library) / after (retrained) / control (the same small training on the default model):
mean |continuous width - truth| of the monitor's published (fused) continuous width (the goal's figure,
`width_error_*_mm`), of each window's own continuous width (`width_error_per_window_*_mm`) and the published
fused width's error (`width_fused_error_*_mm`).
NUMBA_NUM_THREADS=1: one core.
top1_rate is strict (strict_top1: every hidden effect named, or a twin flagged as indistinguishable from it;
per-signal effects on the truth's signal and clearly non-zero); top1_rate_loose the former figure (catalogue
names only). `--only LABEL` (repeatable) runs only those suite rows, same seeds, without the width check.
"""
import os
os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import json
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))

from backlash_monitor.workbench import analysis                       # noqa: E402
from backlash_monitor.workbench.diagnose import diagnose, public      # noqa: E402
from backlash_monitor.workbench.model import load_model               # noqa: E402
from backlash_monitor.workbench.synthetic import hidden_effect_recording  # noqa: E402
from backlash_monitor.workbench.diagnosis_result import MEASURAND_EFFECTS  # noqa: E402
from backlash_monitor.workbench.versions import EffectValues, add_effects  # noqa: E402

DURATION_S = 4.0


def on(effect, **params):
    d = {f"effects.{effect}": True}
    d.update({f"{effect}.{k}": v for k, v in params.items()})
    return d


# (label, kind, hidden config overrides, scenario fields, truth {effect: {param: value}})
SUITE = [
    ("clean_w5", "clean", {}, {"width_m": 0.005}, {}),
    ("clean_w7.5", "clean", {}, {}, {}),
    ("clean_w10", "clean", {}, {"width_m": 0.01}, {}),
    ("clean_eta0.0375", "clean", {}, {"eta_k": 0.0375}, {}),
    ("clean_n0.95", "clean", {}, {"n1": 0.95}, {}),
    ("clean_w3.75", "clean", {}, {"width_m": 0.00375}, {}),
    ("wheel_friction_1.0", "one", on("wheel_coulomb_friction", torque_Nm=1.0), {}, {"wheel_coulomb_friction": {"torque_Nm": 1.0}}),
    ("wheel_friction_2.0", "one", on("wheel_coulomb_friction", torque_Nm=2.0), {}, {"wheel_coulomb_friction": {"torque_Nm": 2.0}}),
    ("mass_+0.2", "one", on("load_mass_drift", relative_change=0.2), {}, {"load_mass_drift": {"relative_change": 0.2}}),
    ("mass_+0.4", "one", on("load_mass_drift", relative_change=0.4), {}, {"load_mass_drift": {"relative_change": 0.4}}),
    ("lowpass_a2_600Hz", "one", on("accelerometer_lowpass", a2_time_constant_s=2.65e-4), {},
     {"accelerometer_lowpass": {"a2_time_constant_s": 2.65e-4}}),
    ("clutch_softer_-0.3", "one", on("clutch_contact_stiffness", relative_change=-0.3), {},
     {"clutch_contact_stiffness": {"relative_change": -0.3}}),
    ("mass_force_20N", "one", on("mass_force_offset", force_N=20.0), {}, {"mass_force_offset": {"force_N": 20.0}}),
    ("wheel_inertia_+0.3", "one", on("wheel_inertia_drift", relative_change=0.3), {},
     {"wheel_inertia_drift": {"relative_change": 0.3}}),
    ("pulse_amp_-0.15", "one", on("pulse_amplitude_drift", relative_change=-0.15), {},
     {"pulse_amplitude_drift": {"relative_change": -0.15}}),
    ("absorber_eta_+0.5", "one", on("absorber_consistency_drift", relative_change=0.5), {},
     {"absorber_consistency_drift": {"relative_change": 0.5}}),
    ("mass+gain_a1", "two", {**on("load_mass_drift", relative_change=0.3), **on("accelerometer_gain", a1_relative_change=-0.2)},
     {}, {"load_mass_drift": {"relative_change": 0.3}, "accelerometer_gain": {"a1_relative_change": -0.2}}),
    ("friction+inertia", "two", {**on("wheel_coulomb_friction", torque_Nm=1.0), **on("wheel_inertia_drift", relative_change=0.3)},
     {}, {"wheel_coulomb_friction": {"torque_Nm": 1.0}, "wheel_inertia_drift": {"relative_change": 0.3}}),
    # a hot rotor (200 K over its rated temperature); this row was 'outside' (r_r 2.5x) until the catalogue had the
    # motor's drifts -- same index, same seed
    ("rotor_resistance_+0.8", "one", on("rotor_resistance_drift", relative_change=0.8), {},
     {"rotor_resistance_drift": {"relative_change": 0.8}}),
    ("clean_w9", "clean", {}, {"width_m": 0.009}, {}),
    # a torque ripple (not locked to the events: found in the raw a1 spectrum, workbench/ripple.py); its phase
    # is not identifiable from a spectrum and not scored
    ("torque_ripple_0.25_x6", "one", on("torque_ripple", amplitude_pu=0.25, order=6.0), {},
     {"torque_ripple": {"amplitude_pu": 0.25, "order": 6.0}}),
    ("torque_ripple_0.5_x15", "one", on("torque_ripple", amplitude_pu=0.5, order=15.0), {},
     {"torque_ripple": {"amplitude_pu": 0.5, "order": 15.0}}),
    # outside the catalogue: a motor whose rotor inertia is 40 % more than the model's (a brake disc or a flywheel
    # on the motor shaft; no catalogue effect changes J1)
    ("outside_rotor_inertia_+0.4", "outside", {"motor.mechanical_time_constant_s": 0.86 * 1.4}, {}, {}),
]


def log(*a):
    print(*a, file=sys.stderr, flush=True)


SIGNIFICANCE = 2.0      # "clearly non-zero": the fitted change exceeds 2 of its uncertainties


def _fit_of(pub, cand):
    """(parameters, uncertainty, nominal) the diagnosis reports for a candidate (e.g. accelerometer_gain[a1]):
    the discovery's, the second effect's, else its refined single fit in the ranking; None if not fitted."""
    for f in (pub.get("discovery_parameters"), pub.get("second_effect")):
        if f and f["candidate"] == cand:
            return f
    return next((r for r in pub["ranked"] if r.get("candidate") == cand and r.get("uncertainty")), None)


def strict_top1(pub, truth) -> tuple:
    """Strict scoring: every hidden effect must be named -- as the discovery, the second effect, or a twin the
    diagnosis flags as indistinguishable from one of them (or a member of a pair it flags as indistinguishable
    from the discovered pair) -- and for an effect with per-signal parameters (a1_/a2_: accelerometer gain,
    low-pass, bias) the named candidate must be the truth's signal, fitted clearly non-zero (> 2 uncertainties
    from the model's value) when a fit of it is reported. -> (ok, reason)."""
    if pub["discovery"] is None:
        return False, "no discovery"
    named = []
    for f in (pub.get("discovery_parameters"), pub.get("second_effect")):
        if f:
            named += [f["candidate"]] + list(f["indistinguishable_from"])
    for alt in pub.get("pair_alternatives") or []:
        named += list(alt["candidates"])
    for effect, params in truth.items():
        cands = [c for c in named if c.split("[")[0] == effect]
        if not cands:
            return False, f"{effect} not named (named: {', '.join(dict.fromkeys(named))})"
        signals = {p.split("_", 1)[0] for p in params if p.startswith(("a1_", "a2_"))}
        if not signals:
            continue
        right = [c for c in cands if "[" in c and c.split("[", 1)[1].rstrip("]").split(",")[0] in signals]
        if not right:
            return False, f"{effect}: named {', '.join(cands)}, the truth sets {', '.join(sorted(signals))}"
        fit = _fit_of(pub, right[0])
        if fit is not None:
            for p in params:
                if p in fit["parameters"] and not (abs(fit["parameters"][p] - fit["nominal"][p])
                                                   > SIGNIFICANCE * fit["uncertainty"][p]):
                    return False, f"{right[0]}: {p} = {fit['parameters'][p]:.4g} not clearly non-zero"
    return True, "ok"


def run_suite(only=None):
    rows = []
    for i, (label, kind, hidden, scen, truth) in enumerate(SUITE):
        if only and label not in only:
            continue
        nominal = {k: v for k, v in scen.items()}
        model = load_model(None, width_m=nominal.get("width_m"), eta_k=nominal.get("eta_k"), n1=nominal.get("n1"))
        meas = hidden_effect_recording(model, DURATION_S, seed=9001 + i, config_overrides=hidden)
        t0, c0 = time.perf_counter(), time.process_time()
        res = diagnose(meas, model)
        seconds, cpu_seconds = time.perf_counter() - t0, time.process_time() - c0
        pub = public(res)
        named = set(pub["indistinguishable"]) | ({pub["discovery"]} if pub["discovery"] else set())
        row = {"label": label, "kind": kind, "discovery": pub["discovery"], "named": sorted(named),
               "seconds": seconds, "cpu_seconds": cpu_seconds, "message": pub["message"],
               "simulated_parameter_sets": pub["simulated_parameter_sets"], "pairs_tried": len(pub["pairs_tried"]),
               "ratio_before": pub["residual_over_noise_floor"]["overall_before"]}
        if kind in ("one", "two"):
            # loose (the former figure): any hidden effect's catalogue name among the discovery and its twins
            row["top1_loose"] = bool(pub["discovery"] is not None and named & set(truth))
            row["top1"], row["top1_why"] = strict_top1(pub, truth)
        param_errs = []
        for eff, params in truth.items():
            # the values the diagnosis reports for that effect: the discovery's (a pair's own fit), the second
            # effect's, else its single refined fit in the ranking
            fit = next((r for r in pub["ranked"] if r["effect"] == eff and r.get("uncertainty")), None)
            for alt in pub.get("pair_alternatives") or []:
                # a twin flagged in a pair the diagnosis cannot tell from the discovered one: its values there
                if fit is None and eff in alt["effects"]:
                    fit = {"parameters": {k.split(".", 1)[1]: v for k, v in alt["parameters"].items()
                                          if k.split("[")[0].split(".")[0] == eff}}
            if pub.get("second_effect") and pub["second_effect"]["effect"] == eff:
                fit = pub["second_effect"]
            if pub.get("discovery_parameters") and pub["discovery_parameters"]["effect"] == eff:
                fit = pub["discovery_parameters"]
            if fit is None:
                continue
            for p, v in params.items():
                if p in fit["parameters"]:
                    param_errs.append(abs(fit["parameters"][p] - v) / abs(v))
        row["param_rel_errors"] = param_errs
        adds = [EffectValues(a["effect"], a["parameters"]) for a in pub["additions"] if a["role"] != "partial"]
        if adds:
            m2 = add_effects(model, adds)
            comp = analysis.build_comparison(meas, m2)
            row["ratio_after"] = float(np.sqrt(np.mean(analysis.residual_ratio(comp) ** 2)))
        log(f"[{i + 1}/{len(SUITE)}] {label}: {pub['message']} ({seconds:.1f} s, CPU {cpu_seconds:.1f} s)"
            + (f"; strict top1 {row['top1']} ({row['top1_why']})" if "top1" in row else ""))
        rows.append(row)
    return rows


# Width check (issue 11: "mean |continuous width - truth| of the monitor on those drives, before and after the
# model update and retraining"): hidden-effect drives, each diagnosed on its own 4 s recording at the nominal
# 7.5 mm, the discovered effect(s) added, the library retrained on that drive's updated model; then the
# monitor's widths on 8 s recordings of the same drive at WIDTH_CHECK_WIDTHS_M (the drive wears; the model
# update is about its physics). Seeds 9101.. (the tests use others).
WIDTH_CHECK_DRIVES = [
    ("wheel_friction_1.5", on("wheel_coulomb_friction", torque_Nm=1.5)),
    ("mass_+0.3", on("load_mass_drift", relative_change=0.3)),
    ("clutch_softer_-0.3", on("clutch_contact_stiffness", relative_change=-0.3)),
    ("gain_a2_-0.2", on("accelerometer_gain", a2_relative_change=-0.2)),
]
WIDTH_CHECK_WIDTHS_M = (0.005, 0.0075, 0.009)    # candidate widths: the fused (published) width can be exact
WIDTH_CHECK_SECONDS = 8.0
# the retrained libraries: what `train --model M2` does by default (8 seeds x 2 s); with 2 seeds the regression's
# bias at 9 mm on the friction drive varied by 0.1 mm between trainings, even on the true model
from backlash_monitor.classifier.training import DEFAULT_TRAIN_SEEDS as WIDTH_TRAIN_SEEDS   # noqa: E402
WIDTH_TRAIN_DURATION_S = 2.0


def twins(pub) -> list:
    """EffectValues of every other candidate the diagnosis names as indistinguishable from the discovery, at
    its own fitted values (from the ranked, refined candidates)."""
    out = []
    for name in pub["indistinguishable"]:
        if name == pub["discovery"] or name in MEASURAND_EFFECTS:     # the width is measured, never trained in
            continue
        fit = next((r for r in pub["ranked"] if r["effect"] == name and r.get("uncertainty")), None)
        if fit is not None:
            out.append(EffectValues(name, fit["parameters"]))
    return out


def truth_effects(hidden: dict) -> list:
    """The hidden config overrides {effects.X: True, X.param: v} as EffectValues (the drive's true physics)."""
    names = [k.split(".", 1)[1] for k, v in hidden.items() if k.startswith("effects.") and v]
    return [EffectValues(n, {k.split(".", 1)[1]: v for k, v in hidden.items() if k.startswith(n + ".")})
            for n in names]


def width_check():
    """Per drive: diagnose -> add-effect -> retrain -> the monitor's widths before (packaged library) and after
    (retrained library), and two controls: the same small training on the default model, and on the drive's
    true physics (the oracle: what a perfect model update followed by the same retraining gives)."""
    from backlash_monitor.classifier.training import build_library
    from backlash_monitor.workbench.width import monitor_widths, width_errors
    t0 = time.perf_counter()
    model = load_model(None)
    drives = []
    with tempfile.TemporaryDirectory() as d:
        ctrl = build_library("contact_loss", WIDTH_TRAIN_SEEDS, duration_s=WIDTH_TRAIN_DURATION_S)
        p_ctrl = ctrl.save(os.path.join(d, "control.npz"))
        for i, (label, hidden) in enumerate(WIDTH_CHECK_DRIVES):
            t1 = time.perf_counter()
            meas = hidden_effect_recording(model, DURATION_S, seed=9101 + 10 * i, config_overrides=hidden)
            pub = public(diagnose(meas, model))
            adds = [EffectValues(a["effect"], a["parameters"]) for a in pub["additions"] if a["role"] != "partial"]
            if adds:
                # one model version per candidate the diagnosis cannot tell apart (fitted values of each),
                # the library trained on all of them (train --model V2a --model V2b)
                versions = [add_effects(model, adds)] + [add_effects(model, [t] + adds[1:]) for t in twins(pub)]
                # seeds dealt out over the versions: at least one per version (three twins: 3 seeds)
                pooled_seeds = tuple(range(WIDTH_TRAIN_SEEDS[0], WIDTH_TRAIN_SEEDS[0]
                                           + max(len(WIDTH_TRAIN_SEEDS), len(versions))))
                lib = build_library("contact_loss", pooled_seeds, duration_s=WIDTH_TRAIN_DURATION_S,
                                    config=[v.plant_config() for v in versions])
                p_after = lib.save(os.path.join(d, f"after_{i}.npz"))
                lib_w = build_library("contact_loss", WIDTH_TRAIN_SEEDS, duration_s=WIDTH_TRAIN_DURATION_S,
                                      config=versions[0].plant_config()) if len(versions) > 1 else None
                p_winner = lib_w.save(os.path.join(d, f"winner_{i}.npz")) if lib_w is not None else p_after
            else:
                versions = []
                p_after = p_winner = None     # no model update: the monitor keeps the packaged library
            lib_o = build_library("contact_loss", WIDTH_TRAIN_SEEDS, duration_s=WIDTH_TRAIN_DURATION_S,
                                  config=add_effects(model, truth_effects(hidden)).plant_config())
            p_oracle = lib_o.save(os.path.join(d, f"oracle_{i}.npz"))
            per_width = []
            for j, w in enumerate(WIDTH_CHECK_WIDTHS_M):
                rec = hidden_effect_recording(model, WIDTH_CHECK_SECONDS, seed=9101 + 10 * i + 1 + j,
                                              config_overrides=hidden, scenario={"width_m": w})
                per_width.append({"width_mm": w * 1e3,
                                  "before": width_errors(monitor_widths(rec), w),
                                  "control_same_training": width_errors(monitor_widths(rec, p_ctrl), w),
                                  "after": width_errors(monitor_widths(rec, p_after), w),
                                  # the discovery's model alone (what a library on the winner gives)
                                  "after_winner_only": width_errors(monitor_widths(rec, p_winner), w),
                                  "oracle_true_model": width_errors(monitor_widths(rec, p_oracle), w)})
            row = {"label": label, "hidden": hidden, "discovery": pub["discovery"],
                   "indistinguishable": pub["indistinguishable"],
                   "added": [{"effect": a.effect, "parameters": a.parameters} for a in adds],
                   "trained_on": [[e["effect"] for e in v.effects_added] for v in versions],
                   "per_width": per_width, "seconds": time.perf_counter() - t1}
            for k in ("before", "control_same_training", "after", "after_winner_only", "oracle_true_model"):
                row[f"per_window_mean_abs_mm_{k}"] = float(np.mean([p[k]["per_window_mean_abs_mm"] for p in per_width]))
                row[f"fused_continuous_mean_abs_mm_{k}"] = float(np.mean(
                    [p[k]["fused_continuous_mean_abs_mm"] for p in per_width]))
                row[f"fused_final_abs_mm_{k}"] = float(np.mean([p[k]["fused_final_abs_mm"] for p in per_width]))
                row[f"abs_bias_mm_{k}"] = float(np.mean([abs(p[k]["bias_mm"]) for p in per_width]))
            log(f"[width {i + 1}/{len(WIDTH_CHECK_DRIVES)}] {label}: added {row['added']}; per-window mean |error| "
                f"{row['per_window_mean_abs_mm_before']:.3f} -> {row['per_window_mean_abs_mm_after']:.3f} mm "
                f"(true model: {row['per_window_mean_abs_mm_oracle_true_model']:.3f}), fused continuous "
                f"{row['fused_continuous_mean_abs_mm_before']:.3f} -> {row['fused_continuous_mean_abs_mm_after']:.3f} mm, "
                f"fused {row['fused_final_abs_mm_before']:.3f} -> {row['fused_final_abs_mm_after']:.3f} mm "
                f"({row['seconds']:.0f} s)")
            drives.append(row)

    def mean_of(key):
        return float(np.mean([r[key] for r in drives]))
    return {"widths_mm": [w * 1e3 for w in WIDTH_CHECK_WIDTHS_M], "recording_s": WIDTH_CHECK_SECONDS,
            "training_seeds": list(WIDTH_TRAIN_SEEDS), "training_duration_s": WIDTH_TRAIN_DURATION_S,
            "per_window_mean_abs_mm_before": mean_of("per_window_mean_abs_mm_before"),
            "per_window_mean_abs_mm_after": mean_of("per_window_mean_abs_mm_after"),
            "per_window_mean_abs_mm_control_same_training": mean_of("per_window_mean_abs_mm_control_same_training"),
            "per_window_mean_abs_mm_oracle_true_model": mean_of("per_window_mean_abs_mm_oracle_true_model"),
            "fused_continuous_mean_abs_mm_before": mean_of("fused_continuous_mean_abs_mm_before"),
            "fused_continuous_mean_abs_mm_after": mean_of("fused_continuous_mean_abs_mm_after"),
            "fused_continuous_mean_abs_mm_oracle_true_model": mean_of("fused_continuous_mean_abs_mm_oracle_true_model"),
            "fused_final_abs_mm_before": mean_of("fused_final_abs_mm_before"),
            "fused_final_abs_mm_after": mean_of("fused_final_abs_mm_after"),
            "per_window_mean_abs_mm_after_winner_only": mean_of("per_window_mean_abs_mm_after_winner_only"),
            "abs_bias_mm_after_winner_only": mean_of("abs_bias_mm_after_winner_only"),
            "abs_bias_mm_before": mean_of("abs_bias_mm_before"), "abs_bias_mm_after": mean_of("abs_bias_mm_after"),
            "drives": drives, "seconds": time.perf_counter() - t0}


def parse_args(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--only", action="append", metavar="LABEL", choices=[s[0] for s in SUITE],
                    help="run only this suite row (repeatable; seeds as in the full run: 9001 + its index in "
                         "SUITE) and skip the width check, the foreign suite and the sensor check; the JSON then holds "
                         "only those rows' figures")
    ap.add_argument("--sealed", action="store_true",
                    help="with --parts outside: the sealed outside suite of --set (run once, at the end), not the "
                         "development one")
    ap.add_argument("--set", dest="set_", type=int, default=1, metavar="N",
                    help="with --parts outside: the set of outside mechanisms (bench/_workbench/outside.py SETS; "
                         "the sealed halves not yet run once are its UNSPENT_SEALED, python bench/_workbench/outside.py "
                         "--help names them; default 1)")
    ap.add_argument("--parts", default="own,foreign,sensor,memory", metavar="PART[,PART...]",
                    help="what to run: own (this project's simulator: the suite and the width check), foreign (the "
                         "foreign drives of foreign_drives/ through the README's loop: diagnose, add-effect, train, "
                         "analyze), sensor (the monitor's width against sensor offsets and gains, own and foreign), "
                         "memory (diagnose's peak memory on the README's 4 s recording, in a child process), "
                         "outside (proposing a missing term: bench/_workbench/outside.py, the development suite), "
                         "width (never a confident wrong width, issue 31: the width alarms on every foreign recording "
                         "and the width+effect foreign drives, development and sealed; bench/_workbench/width_caveat.py)")
    return ap.parse_args(argv)


def main(argv=None):
    args = parse_args(argv)
    t0 = time.perf_counter()
    if args.only:
        rows = run_suite(args.only)
        pos = [r for r in rows if "top1" in r]
        print(json.dumps({"only": args.only,
                          "top1_rate": float(np.mean([r["top1"] for r in pos])) if pos else None,
                          "top1_rate_loose": float(np.mean([r["top1_loose"] for r in pos])) if pos else None,
                          "discovery_seconds_max": float(np.max([r["seconds"] for r in rows])),
                          "discovery_cpu_seconds_max": float(np.max([r["cpu_seconds"] for r in rows])),
                          "per_recording": rows, "wall_seconds": time.perf_counter() - t0}))
        return
    parts = {p.strip() for p in args.parts.split(",") if p.strip()}
    unknown = parts - {"own", "foreign", "sensor", "memory", "outside", "width"}
    if unknown:
        log(f"--parts: unknown part {sorted(unknown)[0]!r}; allowed: own, foreign, sensor, memory, outside, width")
        sys.exit(2)
    out = {}
    if "foreign" in parts:
        from _workbench import foreign
        frows = foreign.run_suite("bench")
        out.update(foreign.summary(frows))
        out["foreign_per_recording"] = frows
    if "outside" in parts:
        from _workbench import outside
        if args.set_ not in outside.SETS:
            log(f"--set {args.set_}: unknown set of outside mechanisms; allowed: {', '.join(map(str, outside.SETS))}")
            raise SystemExit(2)
        out.update(outside.summary(*outside.run_all(sealed=args.sealed, set_=args.set_)))
    if "sensor" in parts:
        out.update(sensor_check())
    if "width" in parts:
        from _workbench import width_caveat
        out.update(width_caveat.confident_wrong_width_alarms())
        dev = width_caveat.width_plus_effect(width_caveat.DEVELOPMENT, "width_plus_effect_development_")
        sealed = width_caveat.width_plus_effect(width_caveat.SEALED, "width_plus_effect_sealed_")
        dev2 = width_caveat.width_plus_effect(width_caveat.DEVELOPMENT_2, "width_plus_effect_development2_")
        sealed2 = width_caveat.width_plus_effect(width_caveat.SEALED_2, "width_plus_effect_sealed2_")
        out.update(dev | sealed | dev2 | sealed2)
        rows = [r for part, prefix in ((dev, "development"), (sealed, "sealed"), (dev2, "development2"),
                                       (sealed2, "sealed2"))
                for r in part[f"width_plus_effect_{prefix}_per_recording"]]
        out["width_plus_effect_recordings"] = len(rows)
        ok = [r for r in rows if "error" not in r]
        out["width_plus_effect_named_rate"] = sum(r["other_named"] for r in ok) / len(rows) if rows else None
        out["width_plus_effect_width_error_sigma_max"] = max((r["width_error_sigma"] for r in ok), default=None)
    if "memory" in parts:
        out.update(diagnose_memory())
    if "own" in parts:
        out.update(own_figures(rows_fn=lambda: run_suite(None)))
    out["wall_seconds"] = time.perf_counter() - t0
    print(json.dumps(out, default=float))


# the README's workbench recording ("The model workbench"): 4 s of a drive with a wheel friction of 1.5 N*m
MEMORY_RECORDING = ["simulate", "--widths", "0.0075", "--eta-k", "0.025", "--n1", "0.89", "--seeds", "7",
                    "--duration", "4", "--no-npz", "--set", "effects.wheel_coulomb_friction=true",
                    "--set", "wheel_coulomb_friction.torque_Nm=1.5"]
# run in a child that runs `diagnose` as its own child: RUSAGE_CHILDREN's ru_maxrss is then that one process's peak
_PEAK_OF_CHILD = ("import resource, subprocess, sys; rc = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL)"
                  ".returncode; print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, rc)")


def diagnose_memory() -> dict:
    """diagnose's peak resident memory [MB] on the README's 4 s recording (issue 33's goal: <= 1024 MB), and its
    verdict: `python -m backlash_monitor diagnose REC --json ...` in a child process, ru_maxrss (kB on Linux)."""
    import subprocess
    with tempfile.TemporaryDirectory() as d:
        rc = subprocess.run([sys.executable, "-m", "backlash_monitor", *MEMORY_RECORDING, "--mcap", d + "/rec"],
                            stdout=subprocess.DEVNULL).returncode
        recs = sorted(os.listdir(d + "/rec")) if rc == 0 else []
        if not recs:
            return {"diagnose_peak_rss_mb": None, "diagnose_memory_error": f"simulate exited {rc}"}
        t0 = time.perf_counter()
        out = subprocess.run([sys.executable, "-c", _PEAK_OF_CHILD, sys.executable, "-m", "backlash_monitor",
                              "diagnose", f"{d}/rec/{recs[0]}", "--json", f"{d}/diag.json", "--no-record"],
                             capture_output=True, text=True)
        kb, rc = out.stdout.split()
        diag = json.loads(open(f"{d}/diag.json").read()) if rc == "0" else {}
    log(f"diagnose of the README's 4 s recording: peak {int(kb) / 1024:.0f} MB, verdict {diag.get('verdict')} "
        f"({time.perf_counter() - t0:.0f} s)")
    return {"diagnose_peak_rss_mb": int(kb) / 1024, "diagnose_memory_exit_code": int(rc),
            "diagnose_memory_verdict": diag.get("verdict"), "diagnose_memory_discovery": diag.get("discovery")}


def sensor_check() -> dict:
    """The monitor's width against constant sensor offsets (goal) and gains (reported), own and foreign drives."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    from _workbench import sensor_offset
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite
    extra = []
    for spec in suite("bench"):
        if spec.kind == "clean" and not spec.sensor.any:
            rec = make_recording(spec)
            extra.append({"signals": rec.signals, "sample_period_s": rec.sample_period_s,
                          "true_width_m": rec.truth.true_width_m, "name": "foreign " + spec.label})
    res = sensor_offset.measure(own=True, extra_recordings=extra)
    return {k: v for k, v in res.items()}


def own_figures(rows_fn) -> dict:
    rows = rows_fn()
    width = width_check()
    clean = [r for r in rows if r["kind"] == "clean"]
    pos = [r for r in rows if r["kind"] in ("one", "two")]
    errs = [e for r in rows if r["kind"] in ("one", "two") for e in r["param_rel_errors"]]
    after = [r["ratio_after"] for r in pos if "ratio_after" in r]
    outside = [r for r in rows if r["kind"] == "outside"]
    out = {
        "recordings": len(rows), "duration_s": DURATION_S,
        # strict (strict_top1): every hidden effect named (or a flagged twin), per-signal effects on the right
        # signal and clearly non-zero; loose: any hidden effect's catalogue name named first (the former figure)
        "top1_rate": float(np.mean([r["top1"] for r in pos])),
        "top1_rate_loose": float(np.mean([r["top1_loose"] for r in pos])),
        "false_discovery_rate": float(np.mean([r["discovery"] is not None for r in clean])),
        "outside_catalogue_confident_discoveries": int(sum(r["discovery"] is not None for r in outside)),
        "param_rel_error_median": float(np.median(errs)) if errs else None,
        "fit_after_over_noise_floor": float(np.median(after)) if after else None,
        "fit_after_over_noise_floor_max": float(np.max(after)) if after else None,
        # the goal's figure: mean over drives and widths of |continuous width - truth| of what the monitor
        # publishes for the drive (BacklashEstimate.fused_continuous_width_m: the median of the last 8 windows'
        # continuous widths, what `analyze`, the fleet view and the trend show), per window once the fusion
        # is full
        "width_error_before_mm": width["fused_continuous_mean_abs_mm_before"],
        "width_error_after_mm": width["fused_continuous_mean_abs_mm_after"],
        "width_error_true_model_mm": width["fused_continuous_mean_abs_mm_oracle_true_model"],
        # one onset window's own continuous width (BacklashEstimate.continuous_width_m; the stricter reading,
        # the former headline): window-to-window scatter the model update cannot remove (with the library
        # trained on each drive's TRUE physics it stays near 0.1 mm)
        "width_error_per_window_before_mm": width["per_window_mean_abs_mm_before"],
        "width_error_per_window_after_mm": width["per_window_mean_abs_mm_after"],
        "width_error_per_window_true_model_mm": width["per_window_mean_abs_mm_oracle_true_model"],
        # the published fused (candidate) width's error at the end of each recording
        "width_fused_error_before_mm": width["fused_final_abs_mm_before"],
        "width_fused_error_after_mm": width["fused_final_abs_mm_after"],
        "width_check": width,
        "discovery_seconds": float(np.median([r["seconds"] for r in rows])),
        "discovery_seconds_max": float(np.max([r["seconds"] for r in rows])),
        # CPU time of the process (one numba thread): the one-core cost, independent of other jobs' load
        "discovery_cpu_seconds": float(np.median([r["cpu_seconds"] for r in rows])),
        "discovery_cpu_seconds_max": float(np.max([r["cpu_seconds"] for r in rows])),
        "numba_threads": int(os.environ.get("NUMBA_NUM_THREADS", "0")),
        "per_recording": rows,
    }
    return out


if __name__ == "__main__":
    main()
