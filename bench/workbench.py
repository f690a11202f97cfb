"""Model-workbench goals (issue 11) on a hidden-effect suite: one JSON object on stdout, all else on stderr.

Suite: 4 s recordings made by the project's simulator with seeds (9001..) and strengths the tests do not
use: clean drives, one-effect drives, two-effect drives and one effect outside the catalogue. Per recording
`diagnose` (whole catalogue, 6 seeds); for the discoveries the effect is added (versions.add_effects with
the fitted values) and the new version compared (residual over the noise floor). The width check retrains
the pattern library on the updated model (`train --model` core) and on the default model with the same
seeds (control), and reports the monitor's mean |continuous width - truth| before/after.
NUMBA_NUM_THREADS=1: one core.
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
    ("outside_rotor_resistance", "outside", {"motor.r_r_pu": 0.12}, {}, {}),
    ("clean_w9", "clean", {}, {"width_m": 0.009}, {}),
]


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def run_suite():
    rows = []
    for i, (label, kind, hidden, scen, truth) in enumerate(SUITE):
        nominal = {k: v for k, v in scen.items()}
        model = load_model(None, width_m=nominal.get("width_m"), eta_k=nominal.get("eta_k"), n1=nominal.get("n1"))
        meas = hidden_effect_recording(model, DURATION_S, seed=9001 + i, config_overrides=hidden)
        t0 = time.perf_counter()
        res = diagnose(meas, model)
        seconds = time.perf_counter() - t0
        pub = public(res)
        named = set(pub["indistinguishable"]) | ({pub["discovery"]} if pub["discovery"] else set())
        row = {"label": label, "kind": kind, "discovery": pub["discovery"], "named": sorted(named),
               "seconds": seconds, "message": pub["message"],
               "ratio_before": pub["residual_over_noise_floor"]["overall_before"]}
        if kind in ("one", "two"):
            row["top1"] = bool(pub["discovery"] is not None and named & set(truth))
        param_errs = []
        for eff, params in truth.items():
            fit = next((r for r in pub["ranked"] if r["effect"] == eff and r.get("uncertainty")), None)
            if pub.get("second_effect") and pub["second_effect"]["effect"] == eff:
                fit = pub["second_effect"]
            if fit is None:
                continue
            for p, v in params.items():
                if p in fit["parameters"]:
                    param_errs.append(abs(fit["parameters"][p] - v) / abs(v))
        row["param_rel_errors"] = param_errs
        if pub["discovery"] is not None:
            adds = [EffectValues(pub["discovery_parameters"]["effect"], pub["discovery_parameters"]["parameters"])]
            if pub.get("second_effect"):
                adds.append(EffectValues(pub["second_effect"]["effect"], pub["second_effect"]["parameters"]))
            m2 = add_effects(model, adds)
            comp = analysis.build_comparison(meas, m2)
            row["ratio_after"] = float(np.sqrt(np.mean(analysis.residual_ratio(comp) ** 2)))
        log(f"[{i + 1}/{len(SUITE)}] {label}: {pub['message']} ({seconds:.1f} s)")
        rows.append(row)
    return rows


def width_check():
    """Hidden wheel friction 1.5 N*m at 7.5 mm (the issue's example): monitor width before/after retraining."""
    from backlash_monitor.classifier.training import build_library
    from backlash_monitor.workbench.width import continuous_widths
    model = load_model(None)
    hidden = on("wheel_coulomb_friction", torque_Nm=1.5)
    meas = hidden_effect_recording(model, 8.0, seed=9101, config_overrides=hidden)
    t0 = time.perf_counter()
    pub = public(diagnose(meas, model))
    adds = [EffectValues(pub["discovery_parameters"]["effect"], pub["discovery_parameters"]["parameters"])]
    m2 = add_effects(model, adds)
    seeds = (1000, 1001)
    with tempfile.TemporaryDirectory() as d:
        lib_after = build_library("contact_loss", seeds, duration_s=2.0, config=m2.plant_config())
        p_after = lib_after.save(os.path.join(d, "after.npz"))
        lib_ctrl = build_library("contact_loss", seeds, duration_s=2.0)
        p_ctrl = lib_ctrl.save(os.path.join(d, "control.npz"))
        truth = model.nominal["width_m"]
        w_before = continuous_widths(meas)                 # the packaged library (default model)
        w_ctrl = continuous_widths(meas, p_ctrl)
        w_after = continuous_widths(meas, p_after)
    return {"width_truth_mm": truth * 1e3, "added": pub["discovery_parameters"],
            "width_error_before_mm": float(np.mean(np.abs(w_before - truth)) * 1e3),
            "width_error_control_same_training_mm": float(np.mean(np.abs(w_ctrl - truth)) * 1e3),
            "width_error_after_mm": float(np.mean(np.abs(w_after - truth)) * 1e3),
            "width_bias_before_mm": float((np.mean(w_before) - truth) * 1e3),
            "width_bias_after_mm": float((np.mean(w_after) - truth) * 1e3),
            "onset_windows": int(len(w_after)), "seconds": time.perf_counter() - t0,
            "training_seeds": list(seeds)}


def main():
    t0 = time.perf_counter()
    rows = run_suite()
    width = width_check()
    clean = [r for r in rows if r["kind"] == "clean"]
    pos = [r for r in rows if r["kind"] in ("one", "two")]
    errs = [e for r in rows if r["kind"] in ("one", "two") for e in r["param_rel_errors"]]
    after = [r["ratio_after"] for r in pos if "ratio_after" in r]
    outside = [r for r in rows if r["kind"] == "outside"]
    out = {
        "recordings": len(rows), "duration_s": DURATION_S,
        "top1_rate": float(np.mean([r["top1"] for r in pos])),
        "false_discovery_rate": float(np.mean([r["discovery"] is not None for r in clean])),
        "outside_catalogue_confident_discoveries": int(sum(r["discovery"] is not None for r in outside)),
        "param_rel_error_median": float(np.median(errs)) if errs else None,
        "fit_after_over_noise_floor": float(np.median(after)) if after else None,
        "fit_after_over_noise_floor_max": float(np.max(after)) if after else None,
        "width_error_before_mm": width["width_error_before_mm"],
        "width_error_after_mm": width["width_error_after_mm"],
        "width_check": width,
        "discovery_seconds": float(np.median([r["seconds"] for r in rows])),
        "discovery_seconds_max": float(np.max([r["seconds"] for r in rows])),
        "numba_threads": int(os.environ.get("NUMBA_NUM_THREADS", "0")),
        "per_recording": rows,
        "wall_seconds": time.perf_counter() - t0,
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
