"""Why a catalogue discovery was confident (issue 31, helper `beyond`): per recording, diagnose's steps, the
confidence checks of its discovery (strict or only within the form tolerance), what the discovery leaves per view and
per signal, its parameter against its fit range and nominal tolerance, and the proposal fitted on top of it
(proposal.propose as for a partial explanation). One JSON line per recording on stdout.

    python bench/_workbench/discovery_probe.py --suite outside_dev --only od_clutch_gap_drag_0.6
    python bench/_workbench/discovery_probe.py --suite bench --kinds clean,one [--every K]
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

import numpy as np  # noqa: E402

from backlash_monitor.workbench import decisions, diagnose as dg, proposal, tolerance  # noqa: E402
from backlash_monitor.workbench.model import load_model  # noqa: E402
from bench._workbench.outside import _measurement  # noqa: E402



def probe(spec) -> dict:
    meas, _ = _measurement(spec)
    model = load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)
    t0 = time.process_time()
    run = dg.prepare(meas, model)
    dg.screen_step(run)
    dg.refine_step(run)
    decision = dg.decide_step(run)
    up = dg.second_effect_step(run, decision, True)
    dg.confidence_step(run, up, decision)
    ripple_fit, spec_ = dg.spectral_step(run)
    result = dg.verdict_step(run, decision, up, ripple_fit, spec_)
    row = {"label": spec.label, "kind": spec.kind, "verdict": result.verdict, "message": result.message[:400],
           "diagnose_cpu_s": time.process_time() - t0, "inconsistent": bool(run.inconsistent),
           "ripple": bool(ripple_fit is not None and ripple_fit.get("confident") and ripple_fit.get("locked")),
           "confident": bool(up.confident)}
    row["views_before"] = {n: [round(v.t2, 1), round(v.limit, 1)] for n, v in run.before.views.items()}
    if up.first is None:
        if result.verdict == "discovery" and run.inconsistent:      # a spectral discovery beside an unexplained average
            prop = proposal.propose(run, up, "nothing_explains")
            j = prop.to_json() if prop is not None else {}
            row["on_top"] = {"proposed": j.get("proposed"), "law": j.get("law"), "reason": (j.get("reason") or "")[:300],
                             "stability": j.get("stability"), "explained_fraction": j.get("explained_fraction"),
                             "consistent": j.get("consistent")}
        return row
    p = run.problem
    ch = dict(up.checks)
    views = ch.pop("views_after", {}).get("views", {})
    row["checks"] = {k: v for k, v in ch.items()}
    row["views_after"] = {n: [round(v["T2"], 1), round(v["T2_limit_p01"], 1)] for n, v in views.items()}
    row["per_signal_after"] = decisions.per_signal_ratio(p, up.after_pred).tolist()
    row["per_signal_before"] = decisions.per_signal_ratio(p, run.base_pred).tolist()
    fits = []
    for f in (up.first, up.second):
        if f is None:
            continue
        c = run.by_name.get(f.effect)
        lo, hi = c.bounds() if c is not None else (None, None)
        sig = tolerance.sigma_of(c) if c is not None else None
        d = np.asarray(f.values) - np.asarray(f.nominal)
        fits.append({"effect": f.effect, "values": list(map(float, f.values)), "nominal": list(map(float, f.nominal)),
                     "uncertainty": list(map(float, f.uncertainty)), "delta_ic": float(f.delta_ic),
                     "explained_fraction": float(f.explained_fraction),
                     "share_of_range": (d / np.maximum(np.asarray(hi) - np.asarray(lo), 1e-300)).tolist()
                     if lo is not None else None,
                     "over_tolerance": (np.abs(d) / np.where(sig > 0, sig, np.nan)).tolist() if sig is not None
                     else None, "balance": f.balance})
    row["fits"] = fits
    # the proposal on top of the update (as for a partial explanation); only where the update is not strict
    if ch.get("consistent_in_every_view") and ch.get("outside_subspace_ok"):
        return row
    t1 = time.process_time()
    prop = proposal.propose(run, up, "partial")
    j = prop.to_json() if prop is not None else {}
    row["on_top"] = {"proposed": j.get("proposed"), "law": j.get("law"), "reason": (j.get("reason") or "")[:300],
                     "stability": j.get("stability"), "selection": j.get("selection"),
                     "explained_fraction": j.get("explained_fraction"), "consistent": j.get("consistent"),
                     "on_top_of": j.get("on_top_of"),
                     "terms": [(t["balance"], t["state"], t["group"]) for t in j.get("terms") or []],
                     "cpu_s": time.process_time() - t1}
    return row


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--suite", required=True)
    ap.add_argument("--only", action="append", default=[])
    ap.add_argument("--kinds", default="")
    ap.add_argument("--every", type=int, default=1)
    ap.add_argument("--start", type=int, default=0)
    a = ap.parse_args()
    if a.suite in ("outside_sealed4",):
        raise SystemExit("never the unspent sealed set 4")
    from foreign_drives.suites import suite
    specs = suite(a.suite)
    if a.kinds:
        specs = [s for s in specs if s.kind in a.kinds.split(",")]
    if a.only:
        specs = [s for s in specs if s.label in a.only]
    for s in specs[a.start::max(1, a.every)]:
        try:
            row = probe(s)
        except Exception as e:  # noqa: BLE001 -- a probe: report and go on
            row = {"label": s.label, "error": repr(e)}
        print(json.dumps(row, default=float), flush=True)


if __name__ == "__main__":
    main()
