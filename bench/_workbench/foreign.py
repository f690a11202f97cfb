"""The workbench on foreign drives (issue 20): recordings made by foreign_drives/ (an independent implementation of
the drive's physics, effects in other functional forms, other sensor chains; docs/foreign_drives.md), diagnosed and
looped through the commands exactly as the README runs them:

    diagnose BAG --width-m W --eta-k E --n1 N --json d.json
    add-effect d.json -o v2.yaml                      (refused when there is nothing to add: the monitor stays;
                                                       --accept-partial on a `partial` verdict: the nearer model)
    train --model v2.yaml --out lib.npz --seeds 1000,1001
    analyze BAG --library lib.npz --out after         (before: analyze BAG, the packaged library)

Scoring (per recording, from the diagnosis JSON a user's script reads):
- a *hit* (hidden-effect recordings): a family of the truth is named first -- the discovery, or a candidate the
  diagnosis flags as indistinguishable from it (for two effects: either one);
- a *false discovery* (clean and outside-the-catalogue recordings): verdict "discovery" or "width" (a partial
  explanation is not a discovery; nor is "nothing explains");
- the loop's width error: mean |fused continuous width (a1+a2) - true width| over the onset windows whose fusion is
  full, before and after the loop; *worse*: grown by more than 0.05 mm.
Each command runs as its own process, NUMBA_NUM_THREADS=1; the diagnosis's CPU time is the child's.
"""
from __future__ import annotations

import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
WORSE_MM = 0.05
TRAIN_SEEDS = "1000,1001"        # the README's loop
FUSION_EVENTS = 8


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def _cli(args, cwd) -> tuple[int, str, float, float]:
    """Run ``python -m backlash_monitor ARGS`` in ``cwd``: (exit code, output, wall s, child CPU s)."""
    env = dict(os.environ, NUMBA_NUM_THREADS="1", PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "backlash_monitor", *map(str, args)], cwd=cwd, env=env,
                       capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return p.returncode, p.stdout + p.stderr, wall, cpu


def full_fusions(analyze_doc: dict, signal: str = "a1+a2") -> list:
    """analyze JSON's onset estimates of ``signal`` whose fusion is full and whose fused continuous width is finite."""
    return [e for e in analyze_doc["estimates"]
            if e["signal"] == signal and e.get("entry_kind", "onset") == "onset" and e["fused_events"] >= FUSION_EVENTS
            and e["fused_continuous_width_m"] is not None and np.isfinite(e["fused_continuous_width_m"])]


def fused_width_error_mm(estimates: list, truth_m: float) -> dict:
    """|fused continuous width - truth| over ``estimates`` (full_fusions): mean [mm], median width [mm], count."""
    vals = np.array([e["fused_continuous_width_m"] for e in estimates], dtype=float)
    return {"mean_abs_mm": float(np.mean(np.abs(vals - truth_m)) * 1e3) if vals.size else None,
            "median_width_mm": float(np.median(vals) * 1e3) if vals.size else None, "windows": int(vals.size)}


def monitor_error_mm(analyze_json: Path, truth_m: float, signal: str = "a1+a2") -> dict:
    """The monitor's published fused continuous width (a1+a2; or one signal's) against the truth, from analyze's
    JSON."""
    return fused_width_error_mm(full_fusions(json.loads(analyze_json.read_text()), signal), truth_m)


def score(diag: dict, truth: dict, kind: str) -> dict:
    families = set(truth["families"])
    named_first = set()
    for entry in (diag.get("discovery_parameters"), diag.get("second_effect")):
        if entry:
            named_first |= {entry["effect"]} | {c.split("[")[0] for c in entry.get("indistinguishable_from", [])}
    for alt in diag.get("pair_alternatives") or []:
        named_first |= set(alt["effects"])
    out = {"verdict": diag["verdict"], "discovery": diag["discovery"], "named": sorted(named_first)}
    if kind in ("one", "two"):
        out["hit"] = bool(named_first & families)
        out["all_named"] = bool(families <= named_first)
        out["partial_right_family"] = bool({p["effect"] for p in diag.get("partial_explanation") or []} & families)
    else:
        out["false_discovery"] = diag["verdict"] in ("discovery", "width")
    return out


def run_recording(spec, workdir: Path, loop: bool = True, keep_json: Path | None = None) -> dict:
    """One foreign recording: bag, diagnosis, score; with ``loop`` the whole README loop and the width errors;
    with ``keep_json`` the diagnosis's JSON is kept there as LABEL.json (every candidate's fit, for offline study)."""
    from foreign_drives.files import write_bag
    from foreign_drives.drive import make_recording
    rec = make_recording(spec)
    truth = rec.truth.to_json()
    d = workdir / spec.label
    d.mkdir(parents=True, exist_ok=True)
    bag = d / "drive.mcap"
    write_bag(spec, bag, recording=rec)
    row = {"label": spec.label, "kind": spec.kind, "families": truth["families"], "outside": truth["outside"],
           "true_width_m": truth["true_width_m"], "seed": spec.seed}
    rc, out, wall, cpu = _cli(["diagnose", bag, "--width-m", spec.width_m, "--eta-k", spec.eta_k, "--n1", spec.n1,
                               "--json", d / "d.json", "--no-history"], d)
    if rc != 0:
        row["error"] = out[-2000:]
        return row
    diag = json.loads((d / "d.json").read_text())
    if keep_json is not None:
        keep_json.mkdir(parents=True, exist_ok=True)
        (keep_json / f"{spec.label}.json").write_text((d / "d.json").read_text())
    row.update(score(diag, truth, spec.kind))
    row.update({"message": diag["message"], "seconds": diag["seconds"], "wall_seconds": wall, "cpu_seconds": cpu,
                "additions": [(a["candidate"], a["role"]) for a in diag["additions"]],
                "measured_width_mm": diag["measured_width"]["width_m"] * 1e3})
    if not loop:
        return row
    rc, out, _, _ = _cli(["analyze", bag, "--out", d / "before"], d)
    if rc != 0:
        row["error"] = "analyze before: " + out[-1000:]
        return row
    row["before"] = monitor_error_mm(d / "before.json", truth["true_width_m"])
    # a `partial` verdict: the README's loop takes the nearer model (add-effect --accept-partial)
    partial = ["--accept-partial"] if diag["verdict"] == "partial" else []
    rc, out, _, _ = _cli(["add-effect", d / "d.json", *partial, "-o", d / "v2.yaml"], d)
    row["add_effect_exit"] = rc
    if rc != 0:
        # nothing to add: the monitor keeps its library
        row["after"] = dict(row["before"])
        row["loop"] = "no new version: " + out.strip().splitlines()[-1][:200]
    else:
        rc, out, _, _ = _cli(["train", "--model", d / "v2.yaml", "--output", d / "lib.npz", "--seeds", TRAIN_SEEDS,
                              "--no-progress"], d)
        row["train_check"] = [ln.strip() for ln in out.splitlines() if "check " in ln or "FLAGGED" in ln]
        if rc != 0:
            row["error"] = "train: " + out[-1000:]
            return row
        rc, out, _, _ = _cli(["analyze", bag, "--library", d / "lib.npz", "--out", d / "after"], d)
        if rc != 0:
            row["error"] = "analyze after: " + out[-1000:]
            return row
        row["after"] = monitor_error_mm(d / "after.json", truth["true_width_m"])
        row["loop"] = "retrained"
    b, a = row["before"]["mean_abs_mm"], row["after"]["mean_abs_mm"]
    row["worse"] = bool(a is not None and b is not None and a > b + WORSE_MM)
    return row


def run_suite(name: str = "bench", only=None, loop: bool = True, workdir=None, keep_json=None) -> list:
    sys.path.insert(0, str(ROOT))
    from foreign_drives.suites import suite
    specs = [s for s in suite(name) if not only or s.label in only]
    rows = []
    with tempfile.TemporaryDirectory(dir=workdir) as tmp:
        for i, spec in enumerate(specs):
            row = run_recording(spec, Path(tmp), loop, Path(keep_json) if keep_json else None)
            rows.append(row)
            log(f"[foreign {i + 1}/{len(specs)}] {spec.label}: {row.get('verdict')} {row.get('discovery')} "
                f"(named {row.get('named')}; truth {row['families'] or 'none'})"
                + (f" hit={row['hit']}" if "hit" in row else f" FD={row.get('false_discovery')}")
                + (f"; width {row['before']['mean_abs_mm']} -> {row['after']['mean_abs_mm']} mm" if "after" in row else "")
                + (f"; ERROR {row['error'][:300]}" if "error" in row else "")
                + f" ({row.get('wall_seconds', 0):.0f} s)")
    return rows


def summary(rows: list) -> dict:
    pos = [r for r in rows if r["kind"] in ("one", "two") and "hit" in r]
    neg = [r for r in rows if r["kind"] in ("clean", "outside") and "false_discovery" in r]
    looped = [r for r in rows if "after" in r and r["after"]["mean_abs_mm"] is not None]
    hidden = [r for r in looped if r["kind"] in ("one", "two")]
    return {
        "foreign_recordings": len(rows),
        "foreign_errors": [r["label"] for r in rows if "error" in r],
        "foreign_top1_rate": float(np.mean([r["hit"] for r in pos])) if pos else None,
        "foreign_top1_hits": f"{sum(r['hit'] for r in pos)} of {len(pos)}",
        "foreign_misses": [r["label"] for r in pos if not r["hit"]],
        "foreign_false_discoveries": int(sum(r["false_discovery"] for r in neg)),
        "foreign_false_discovery_labels": [r["label"] for r in neg if r["false_discovery"]],
        "foreign_negatives": len(neg),
        "foreign_loop_width_error_before_mm": float(np.mean([r["before"]["mean_abs_mm"] for r in hidden]))
        if hidden else None,
        "foreign_loop_width_error_after_mm": float(np.mean([r["after"]["mean_abs_mm"] for r in hidden]))
        if hidden else None,
        "foreign_loop_worse_count": int(sum(r.get("worse", False) for r in looped)),
        "foreign_loop_worse_labels": [r["label"] for r in looped if r.get("worse")],
        "foreign_discovery_seconds": float(np.median([r["seconds"] for r in rows if "seconds" in r])) if rows else None,
        "foreign_discovery_seconds_max": float(np.max([r["seconds"] for r in rows if "seconds" in r])) if rows else None,
        "foreign_discovery_cpu_seconds_max": float(np.max([r["cpu_seconds"] for r in rows if "cpu_seconds" in r]))
        if rows else None,
    }


if __name__ == "__main__":
    import argparse
    ap = argparse.ArgumentParser(description="the workbench on the foreign suite (one JSON object on stdout)")
    ap.add_argument("--suite", default="bench")
    ap.add_argument("--only", action="append")
    ap.add_argument("--no-loop", action="store_true")
    ap.add_argument("--keep-json", metavar="DIR", help="keep every diagnosis's JSON as DIR/LABEL.json")
    a = ap.parse_args()
    rows = run_suite(a.suite, a.only, not a.no_loop, keep_json=a.keep_json)
    print(json.dumps({**summary(rows), "per_recording": rows}, default=float))
