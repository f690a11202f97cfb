"""snapshot_diagnose_agreement: does `diagnose` on the watch's snapshot name what it names on a full recording?

Per effect: `pipeline --watch` runs a 5 mm drive on the default model with the effect switched on mid-run
(--set-at); the model_watch node goes WARN and writes its snapshot. The full recording: `simulate --mcap` of the
same drive with the effect on from the start, 4 s (the workbench's recordings). `diagnose --json` on both (as
processes, as a user runs them); they agree when they name the same effect, or one names the other's as not
distinguishable from it (the workbench bench's scoring of twins).
"""
from __future__ import annotations

import glob
import json
import os
import subprocess
import sys
import tempfile
import time

# (label, the effect's overrides): strengths the workbench bench names (bench/workbench.py's rows)
EFFECTS = [
    ("wheel_coulomb_friction", ["effects.wheel_coulomb_friction=true", "wheel_coulomb_friction.torque_Nm=1.5"]),
    ("load_mass_drift", ["effects.load_mass_drift=true", "load_mass_drift.relative_change=0.3"]),
    ("accelerometer_lowpass", ["effects.accelerometer_lowpass=true",
                               "accelerometer_lowpass.a2_time_constant_s=0.000265"]),
]
WIDTH_M = 0.005
SWITCH_S = 8.0
DURATION_S = 22.0


def _run(cmd, log, timeout=900):
    log("snapshot: " + " ".join(cmd[2:]))
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if p.returncode not in (0, 1):
        raise RuntimeError(f"{' '.join(cmd[2:5])} exited {p.returncode}: {p.stderr[-1500:]}")
    return p


def named(diag: dict) -> tuple[str | None, set]:
    """(the discovery's catalogue effect, the effects named with it: the discovery and its indistinguishable
    twins, diagnose's 'indistinguishable')."""
    d = diag.get("discovery")
    if not d:
        return None, set()
    return d, set(diag.get("indistinguishable") or [d])


def agree(a: dict, b: dict) -> bool:
    na, ta = named(a)
    nb, tb = named(b)
    if na is None or nb is None:
        return na is None and nb is None
    return na == nb or na in tb or nb in ta


def snapshot_agreement(quick: bool = False, log=print) -> dict:
    py = sys.executable
    rows = []
    work = tempfile.mkdtemp(prefix="model_watch_snapshot_")
    for i, (label, sets) in enumerate(EFFECTS[:1] if quick else EFFECTS):
        d = os.path.join(work, label)
        os.makedirs(d)
        t0 = time.perf_counter()
        pipe = _run([py, "-m", "backlash_monitor", "pipeline", "--watch", "--width-m", str(WIDTH_M), "--seed",
                     str(40 + i), "--duration", str(DURATION_S), "--rate-factor", "2", "--snapshot-dir", d,
                     "--set-at", f"{SWITCH_S:g}s", *sets], log)
        snaps = sorted(glob.glob(os.path.join(d, "*.mcap")))
        if not snaps:
            rows.append({"effect": label, "snapshot": None, "agree": False,
                         "note": "no snapshot: the watch did not go WARN", "pipeline_tail": pipe.stdout[-800:]})
            continue
        full_dir = os.path.join(d, "full")
        set_args = [x for s in sets for x in ("--set", s)]
        _run([py, "-m", "backlash_monitor", "simulate", "--widths", str(WIDTH_M), "--eta-k", "0.025", "--n1", "0.89",
              "--seeds", str(60 + i), "--duration", "4", "--no-npz", "--mcap", full_dir, *set_args], log)
        full = sorted(glob.glob(os.path.join(full_dir, "*.mcap")))[0]
        out = {}
        for name, bag in (("snapshot", snaps[0]), ("full", full)):
            js = os.path.join(d, f"{name}.json")
            _run([py, "-m", "backlash_monitor", "diagnose", bag, "--width-m", str(WIDTH_M), "--json", js], log)
            with open(js) as f:
                out[name] = json.load(f)
        ok = agree(out["snapshot"], out["full"])
        rows.append({"effect": label, "snapshot": os.path.basename(snaps[0]),
                     "snapshot_named": named(out["snapshot"])[0], "full_named": named(out["full"])[0],
                     "snapshot_twins": sorted(named(out["snapshot"])[1]), "full_twins": sorted(named(out["full"])[1]),
                     "snapshot_verdict": out["snapshot"].get("verdict"), "full_verdict": out["full"].get("verdict"),
                     "agree": ok, "seconds": round(time.perf_counter() - t0, 1)})
        log(f"snapshot: {label}: snapshot names {rows[-1]['snapshot_named']}, full recording "
            f"{rows[-1]['full_named']}: {'agree' if ok else 'DISAGREE'}")
    n = len(rows)
    return {"snapshot_diagnose_agreement": sum(r["agree"] for r in rows) / n if n else None,
            "snapshot_rows": rows}
