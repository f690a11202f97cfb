"""Which decisions a qualification rule moves, read off kept diagnosis JSONs (foreign.py --keep-json, decision_rows.py),
without re-running a diagnosis (docs/workbench.md, "Decisions"):

    python bench/_workbench/decision_offline.py DIR [DIR ...] [--json]

Per recording: the verdict; K, the candidates screened and ranked; the best linearised delta_ic of the K and how many
reach delta_ic_lin <= -2 (on a clean recording: what the look-elsewhere effect looks like); every refined candidate
with weak evidence (-10 < delta_ic <= -2): its z (the smallest |value - nominal| / uncertainty of its parameters)
and whether it qualifies under the single test (z > SIGNIFICANCE) and under the family-wise one
(decisions.family_significance(K)); *moves*: the model inconsistent and the set of qualifying candidates differs.
The other conditions of decisions.qualifies (explained share, bound, nominal tolerance) are evaluated as there; a
term locked to a shaft's angle is judged by its parameters one by one (its groups are not in the JSON).
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))

from backlash_monitor.workbench import plant_adapter, tolerance                     # noqa: E402
from backlash_monitor.workbench.decisions import (DELTA_IC_DECISIVE, DELTA_IC_STRONG, MIN_EXPLAINED,  # noqa: E402
                                                  SIGNIFICANCE, TOLERANCE_FACTOR, family_significance)
from backlash_monitor.workbench.diagnosis_result import MEASURAND_EFFECTS           # noqa: E402
from backlash_monitor.workbench.model import load_model                             # noqa: E402

CATALOGUE = {c.name: c for c in plant_adapter.catalogue(load_model(None))}


def z_of(r: dict) -> float:
    v, u, n = r["parameters"], r["uncertainty"] or {}, r.get("nominal") or {}
    zs = [abs(v[p] - n.get(p, 0.0)) / u[p] if u.get(p) else np.inf for p in u]
    return float(min(zs)) if zs else float("nan")


def qualifies(r: dict, threshold_weak: float) -> bool:
    cand = CATALOGUE.get(r["candidate"])
    if cand is not None:
        vals = np.array([r["parameters"][p.name] for p in cand.parameters])
        nom = np.array([(r.get("nominal") or {}).get(p.name, 0.0) for p in cand.parameters])
        beyond = tolerance.beyond_tolerance(type("F", (), {"values": vals, "nominal": nom}), cand, TOLERANCE_FACTOR)
    else:
        beyond = True               # a user's plug-in: no nominal tolerance
    weak = r["delta_ic"] > -DELTA_IC_DECISIVE
    measurand = r["effect"] in MEASURAND_EFFECTS
    thr = threshold_weak if weak else SIGNIFICANCE
    return bool(r["delta_ic"] <= -DELTA_IC_STRONG and r["explained_fraction"] >= MIN_EXPLAINED and not r["at_bound"]
                and beyond and (not (weak or measurand) or z_of(r) > thr))


def row(path: Path) -> dict:
    d = json.loads(path.read_text())
    ranked = d["ranked"]
    k = len(ranked)
    lin = [r["delta_ic_linearised"] for r in ranked if r.get("delta_ic_linearised") is not None]
    refined = [r for r in ranked if r.get("delta_ic") is not None]
    inconsistent = bool(d.get("model_inconsistent"))
    old = [r["candidate"] for r in refined if qualifies(r, SIGNIFICANCE)]
    new = [r["candidate"] for r in refined if qualifies(r, family_significance(k))]
    weak = [{"candidate": r["candidate"], "delta_ic": round(r["delta_ic"], 2), "z": round(z_of(r), 2),
             "explained": round(r["explained_fraction"], 3), "at_bound": r["at_bound"],
             "single": qualifies(r, SIGNIFICANCE), "family": qualifies(r, family_significance(k))}
            for r in refined if -DELTA_IC_DECISIVE < r["delta_ic"] <= -DELTA_IC_STRONG]
    disc = d.get("discovery_parameters") or {}
    return {"file": path.name, "verdict": d["verdict"], "discovery": d.get("discovery"),
            "discovery_delta_ic": disc.get("delta_ic"), "discovery_z": z_of(disc) if disc.get("uncertainty") else None,
            "model_inconsistent": inconsistent, "K": k, "z_family": round(family_significance(k), 3),
            "best_delta_ic_lin": min(lin) if lin else None, "n_lin_below_-2": int(sum(x <= -2 for x in lin)),
            "weak_refined": weak, "qualifying_single": old, "qualifying_family": new,
            "moves": bool(inconsistent and old != new)}


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="+", type=Path)
    ap.add_argument("--json", action="store_true", help="one JSON object per recording")
    a = ap.parse_args(argv)
    for d in a.dirs:
        for p in sorted(d.glob("*.json")):
            r = row(p)
            if a.json:
                print(json.dumps(r, default=float))
                continue
            print(f"{r['file'][:60]:60s} {r['verdict']:16s} {str(r['discovery'])[:26]:26s} "
                  f"ic={r['discovery_delta_ic'] if r['discovery_delta_ic'] is None else round(r['discovery_delta_ic'], 1)} "
                  f"z={r['discovery_z'] if r['discovery_z'] is None else round(r['discovery_z'], 2)} K={r['K']} "
                  f"lin_best={r['best_delta_ic_lin']:.1f} n_lin<=-2={r['n_lin_below_-2']} "
                  f"incons={r['model_inconsistent']} MOVES={r['moves']} weak={r['weak_refined']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
