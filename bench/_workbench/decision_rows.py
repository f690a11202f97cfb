"""Diagnoses of chosen rows of the foreign suites, each recording's diagnosis JSON kept whole (every screened and
refined candidate: delta_ic, values, uncertainty, explained share), to study offline which decisions a rule of
decisions.py moves (docs/workbench.md, "Decisions"):

    python bench/_workbench/decision_rows.py --out DIR SUITE[:LABEL,...] ... [--propose] [--reseed N]

Each row is diagnosed in this process at the drive's nominal values (as outside.py does, NUMBA_NUM_THREADS=1);
without ``--propose`` no term is proposed (the decision among the catalogue's candidates is what is studied). One
line of JSON per row on stdout: label, verdict, discovery, the diagnosis's message; DIR/SUITE__LABEL__SEED.json the whole
diagnosis. ``--reseed N``: each row also N times with other noise seeds (seed + 10007 i, i = 1..N; the same drive,
other noise: whether a decision is the drive's or the noise's). Never an unspent sealed half (outside.UNSPENT_SEALED).
"""
from __future__ import annotations

import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

from _workbench.outside import _measurement                       # noqa: E402

from backlash_monitor.workbench.diagnose import diagnose          # noqa: E402
from backlash_monitor.workbench.model import load_model           # noqa: E402


def rows_of(arg: str) -> tuple[str, list]:
    from foreign_drives.suites import suite
    name, _, labels = arg.partition(":")
    if name.endswith("6"):
        raise SystemExit(f"{name}: the sixth set is not to be read or run here")
    wanted = [x for x in labels.split(",") if x]
    specs = [s for s in suite(name) if not wanted or s.label in wanted]
    missing = set(wanted) - {s.label for s in specs}
    if missing:
        raise SystemExit(f"{name}: no rows {sorted(missing)}")
    return name, specs


def main(argv=None) -> int:
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("suites", nargs="+", metavar="SUITE[:LABEL,...]")
    ap.add_argument("--out", required=True, type=Path)
    ap.add_argument("--propose", action="store_true", help="propose a term when the verdict calls for one")
    ap.add_argument("--reseed", type=int, default=0, metavar="N", help="each row also with N other noise seeds")
    ap.add_argument("--reseeded-only", action="store_true", help="with --reseed: not the row's own seed")
    a = ap.parse_args(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    for arg in a.suites:
        name, specs = rows_of(arg)
        from dataclasses import replace
        specs = [replace(s, seed=s.seed + 10007 * i) if i else s for s in specs for i in range(a.reseed + 1)
                 if i or not a.reseeded_only]
        for spec in specs:
            meas, _ = _measurement(spec)
            model = load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)
            t0 = time.process_time()
            d = diagnose(meas, model, propose=a.propose).to_json()
            cpu = time.process_time() - t0
            (a.out / f"{name}__{spec.label}__{spec.seed}.json").write_text(json.dumps(d, default=float))
            prop = d.get("proposal") or {}
            print(json.dumps({"suite": name, "label": spec.label, "seed": spec.seed, "kind": spec.kind, "verdict": d["verdict"],
                              "discovery": d.get("discovery"), "proposed": bool(prop.get("proposed")),
                              "law": prop.get("law"), "cpu_seconds": cpu, "message": d["message"]}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
