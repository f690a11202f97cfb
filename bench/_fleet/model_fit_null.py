"""bench/fleet.py's part model_fit_null: the folder model fit's false-WARN rate on healthy drives (docs/registry.md,
"The folder's rule").

``analyze FOLDER`` judges each bag's model fit once: one evaluation of the reference on the bag's last 16 onset
events (watch/core.evaluate_recording), WARN when the rule's test exceeds. Its rule (config/folder_model_fit.yaml)
is sized for one test per bag. This part measures what that rule says on healthy drives, with the events as the
units: long clean recordings are cut into disjoint pieces of ``PIECE_S`` (each piece a bag of its own: its own
noise floor, its own last 16 events; no event in two pieces), so every piece is one independent test.

- own simulator (the project's PlantSimulator, the paper's noise generators), ``own_s`` per nominal condition;
- foreign drives (foreign_drives/, an independent simulator with its own sensor chains), the bench's healthy
  rows' conditions and sensor chains, on other seeds, ``foreign_s`` per condition;

each against the default model's reference at the drive's nominal (the registry's reference for a drive with no
version of its own). Per piece: each alarm view's T^2, dimension and p-value, the residual ratio, and the same for
each of the 16 leave-one-out windows, so that any rule of watch/alarm.py's form can be applied to the same
evaluations (``apply_rule``): the statistic does not depend on the rule.
"""
from __future__ import annotations

import math
import time
from types import SimpleNamespace

import numpy as np

PIECE_S = 4.5            # s: 18 pulses of the paper's 4 Hz train, >= 16 complete onset events after the edges
OWN_SKIP_S = 1.0         # s: the own simulator's start (its state settles from rest; a bag starts mid-run)
WINDOW_EVENTS = 16       # the evaluation's events (evaluate_recording's window)


def _pieces(signals: dict, sample_period_s: float, skip_s: float, source: str):
    from backlash_monitor.workbench.measurement import Measurement
    n = int(round(PIECE_S / sample_period_s))
    start = int(round(skip_s / sample_period_s))
    total = len(signals["a1"])
    k = 0
    while start + n <= total:
        yield Measurement(f"{source}[piece {k}]", sample_period_s,
                          {s: np.ascontiguousarray(v[start:start + n]) for s, v in signals.items()})
        start += n
        k += 1


def evaluate_piece(meas, ref, clip_p: float | None) -> dict:
    """The evaluation evaluate_recording makes (its last 16 events, the noise floor as the watch takes it), with
    every alarm view's T^2 and the leave-one-out windows' kept: {views: {name: [t2, dim]}, ratio, loo: [...]}."""
    from backlash_monitor.watch.alarm import ALARM_VIEWS
    from backlash_monitor.workbench.reference import evidence_from_measurement
    evidence = evidence_from_measurement(meas, ref, last_n=WINDOW_EVENTS, significant_noise=True)
    ev = ref.evaluate(evidence, clip_p=clip_p, where=False)

    def pack(result):
        return {"views": {n: [float(v.t2), int(v.dimension)] for n, v in result.views.items() if n in ALARM_VIEWS},
                "ratio": float(result.residual_over_noise)}
    # the views the rule does not judge (the noise directions outside the candidates' subspace): kept to see where
    # an effect lies, not used by apply_rule
    other = {n: [float(v.t2), int(v.dimension)] for n, v in ev.result.views.items() if n not in ALARM_VIEWS}
    out = pack(ev.result)
    out["events"] = int(evidence.n_events)
    out["other_views"] = other
    out["loo"] = [pack(r) for r in ref.leave_one_out(evidence, ev, clip_p=clip_p)]
    return out


def _result(packed: dict):
    return SimpleNamespace(views={n: SimpleNamespace(t2=t2, dimension=d) for n, (t2, d) in packed["views"].items()},
                           residual_over_noise=packed["ratio"])


def apply_rule(piece: dict, rule, dof: dict) -> bool:
    """Whether ``rule`` (watch/alarm.AlarmRule) says WARN on the piece: evaluate_recording's decision, on the kept
    statistics (the same AlarmRule.result_exceeds)."""
    exceeding, _ = rule.result_exceeds(_result(piece), dof)
    if exceeding and rule.robust and piece["loo"]:
        exceeding = all(rule.result_exceeds(_result(r), dof)[0] for r in piece["loo"])
    return bool(exceeding)


def p_min(piece: dict, rule, dof: dict) -> float:
    """The smallest alarm view p-value under ``rule``'s law."""
    return min(rule.p_value(n, t2, d, dof) for n, (t2, d) in piece["views"].items())


def own_pieces(conditions, reference_for, own_s: float, clip_p, seed0: int = 91_000, log=print) -> list:
    """Own simulator: per nominal condition one clean drive of ``own_s`` (+ OWN_SKIP_S) cut into pieces."""
    from backlash_monitor.workbench.model import load_model
    from backlash_monitor.workbench.synthetic import hidden_effect_recording
    rows = []
    for i, (w, e, n1) in enumerate(conditions):
        ref, dof = reference_for(w, e, n1)
        model = load_model(None, width_m=w, eta_k=e, n1=n1)
        t0 = time.perf_counter()
        meas = hidden_effect_recording(model, own_s + OWN_SKIP_S, seed0 + i)
        for piece in _pieces(meas.signals, meas.sample_period_s, OWN_SKIP_S, f"own {w * 1e3:g} mm"):
            rows.append({"source": "own", "condition": [w, e, n1], "dof": dof, **evaluate_piece(piece, ref, clip_p)})
        log(f"model_fit_null: own {w * 1e3:g} mm / {e:g} / {n1:g}: {time.perf_counter() - t0:.0f} s")
    return rows


def foreign_pieces(specs, reference_for, foreign_s: float, clip_p, seed0: int = 92_000, log=print) -> list:
    """Foreign drives: each healthy spec (its condition and sensor chain) on another seed for ``foreign_s``."""
    import dataclasses
    from foreign_drives.drive import make_recording
    rows = []
    for i, s in enumerate(specs):
        ref, dof = reference_for(s.width_m, s.eta_k, s.n1)
        t0 = time.perf_counter()
        dur = round(math.floor(foreign_s / PIECE_S) * PIECE_S, 6)
        spec = dataclasses.replace(s, seed=seed0 + i, duration_s=dur).check()
        rec = make_recording(spec)
        for piece in _pieces(rec.signals, rec.sample_period_s, 0.0, f"foreign {s.label}"):
            rows.append({"source": "foreign", "condition": [s.width_m, s.eta_k, s.n1], "label": s.label, "dof": dof,
                         **evaluate_piece(piece, ref, clip_p)})
        del rec
        log(f"model_fit_null: foreign {s.label}: {time.perf_counter() - t0:.0f} s")
    return rows


def upper_95(k: int, n: int) -> float:
    """The one-sided 95 % upper bound of a rate seen k times in n independent trials (Clopper-Pearson)."""
    from scipy.stats import beta
    return 1.0 if n == 0 else float(beta.ppf(0.95, k + 1, n - k)) if k < n else 1.0


def summarize(rows: list, rule, watch_rule) -> dict:
    """Per source: pieces, the folder rule's WARNs (and the live watch's rule's, for comparison), the rate's 95 %
    upper bound, and the null distribution of the smallest view p-value and the residual ratio."""
    out = {}
    for source in ("own", "foreign"):
        sel = [r for r in rows if r["source"] == source]
        if not sel:
            continue
        warn = [r for r in sel if apply_rule(r, rule, r["dof"])]
        pm = np.array([p_min(r, rule, r["dof"]) for r in sel])
        ratio = np.array([r["ratio"] for r in sel])
        out[source] = {
            "pieces": len(sel), "folder_rule_warns": len(warn),
            "folder_rule_false_warn_rate_upper_95": round(upper_95(len(warn), len(sel)), 4),
            "watch_rule_warns": sum(apply_rule(r, watch_rule, r["dof"]) for r in sel),
            # the p-values' calibration: the share below 1e-2 and 1e-3 (the law: 3 views x that, at most)
            "p_min_share_below_1e-2": round(float(np.mean(pm < 1e-2)), 4),
            "p_min_share_below_1e-3": round(float(np.mean(pm < 1e-3)), 4),
            "p_min_smallest": float(pm.min()),
            "ratio_quantiles_50_90_99_max": [round(float(np.quantile(ratio, q)), 3) for q in (0.5, 0.9, 0.99)]
                                            + [round(float(ratio.max()), 3)],
            "warned": [{"condition": r["condition"], "label": r.get("label", ""), "ratio": round(r["ratio"], 3),
                        "p_min": p_min(r, rule, r["dof"])} for r in warn]}
    if len(out) == 2:
        n, k = sum(v["pieces"] for v in out.values()), sum(v["folder_rule_warns"] for v in out.values())
        out["all"] = {"pieces": n, "folder_rule_warns": k, "folder_rule_false_warn_rate_upper_95": round(upper_95(k, n), 4)}
    return out
