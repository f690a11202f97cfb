"""bench/fleet.py's part registry_loop: a live fleet picks up one drive's new model version (docs/registry.md).

A fleet of ``n_drives`` simulated drives (layout process) runs from a registry file in a temporary folder. Before
the fleet starts: ``add-effect wheel_coulomb_friction --value torque_Nm=1.2 --drive line1/drive05`` writes the
drive's version 2 (an effect given on the command line, no diagnosis: the part measures the pickup, not the
workbench), and ``train --model line1_drive05_v2.yaml -o line1_drive05_v2.npz`` (one seed of 0.5 s: a small
library; ~2 min, most of it the watch reference) writes its library and watch reference without registering them.
While the fleet runs, 10 s after every drive streams, the loop's registering step: ``files.registry.register`` of
that model, library and reference as the drive's new version (what ``train --drive`` does once its library is
accepted). The fleet sees the registry change and swaps that drive's chain.

``live_train=True`` runs the real ``train --drive line1/drive05 --model line1_drive05_v2.yaml`` live instead (niced,
beside the fleet); the stream must outlast it: on 29 Nov at load 16 it took 533 s and a 420 s stream ended first
(``registry_loop_live_train_end_before_stream_end_s``), so it is not the default.

registry_loop_pickup_s: the registry file written (its mtime) -> the drive's classifier status on /diagnostics
  says model_version 2 (the fleet monitor's wall clock; the classifier publishes its status once a second).
registry_loop_changed_drives: the drives the fleet swapped (must be exactly line1/drive05).
registry_loop_other_drives_missed_onsets: over the other drives, onset windows classifiable but not estimated, plus
  their chain restarts (goal 0); with whether each kept its library, reference and version in the registry.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import threading
import time

DRIVE = "line1/drive05"
MODEL = "line1_drive05_v2.yaml"
TRAIN = ["--seeds", "1000", "--duration", "0.5", "--no-progress"]   # one seed of 1 s per grid point: a small
                                                                    # library; the pickup does not depend on it


def log(*args):
    print(*args, file=sys.stderr, flush=True)


def command(args, cwd, nice=0, timeout=1800):
    started = time.perf_counter()
    proc = subprocess.run((["nice", "-n", str(nice)] if nice else []) + [sys.executable, "-m", "backlash_monitor", *args],
                          cwd=cwd, capture_output=True, text=True, timeout=timeout)
    seconds = time.perf_counter() - started
    if proc.returncode != 0:
        log(proc.stdout[-2000:], proc.stderr[-2000:])
        raise RuntimeError(f"{' '.join(args[:3])} ... exited {proc.returncode}")
    return proc, seconds


def versions_of(reg):
    from backlash_monitor.files import registry
    return {d.hardware_id: (str(d.model or ""), str(d.library or ""), str(d.watch_reference or ""), d.version)
            for d in registry.entries(reg)}


def registry_loop(workdir, n_drives=8, stream_s=60.0, live_train=False):
    import yaml
    folder = os.path.join(workdir, "registry_loop")
    os.makedirs(folder, exist_ok=True)
    reg = os.path.join(folder, "drives.yaml")
    with open(reg, "w") as f:
        yaml.safe_dump({"lines": {"line1": {f"drive{i:02d}": {"seed": i, "width_m": (0.005, 0.0075)[i % 2]}
                                            for i in range(1, n_drives + 1)}}}, f)
    # before the fleet: the new version's model file (no diagnosis: an effect given on the command line)
    _, add_s = command(["add-effect", "wheel_coulomb_friction", "--value", "torque_Nm=1.2", "--drive", DRIVE,
                        "--registry", reg], folder)
    prepared_s = None
    if not live_train:
        _, prepared_s = command(["train", "--model", MODEL, "-o", MODEL.replace(".yaml", ".npz"), *TRAIN], folder)
    log(f"registry_loop: add-effect {add_s:.1f} s, train before the fleet {prepared_s} s; the fleet of {n_drives} "
        f"drives streams {stream_s:g} s")
    before = versions_of(reg)
    duration_s = stream_s
    summary = os.path.join(folder, "summary.json")
    fleet = subprocess.Popen([sys.executable, "-m", "backlash_monitor", "fleet", "--config", reg,
                              "--duration", str(duration_s), "--view-period", "0", "--json", summary],
                             cwd=folder, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines, streaming = [], threading.Event()

    def read():
        for line in fleet.stderr:
            lines.append(line)
            if "drives streaming" in line:
                streaming.set()
    threading.Thread(target=read, daemon=True).start()
    train = {}
    try:
        if not streaming.wait(300):
            raise RuntimeError("the fleet did not start streaming: " + "".join(lines[-10:]))
        streaming_at = time.time()
        if live_train:
            proc, train["seconds"] = command(["train", "--drive", DRIVE, "--registry", reg, "--model", MODEL,
                                              *TRAIN], folder, nice=10)
            train["printed"] = [x for x in proc.stdout.splitlines() if x.startswith("registry")]
        else:
            from backlash_monitor.files import registry
            time.sleep(10.0)
            base = os.path.join(folder, MODEL[:-len(".yaml")])
            t0 = time.perf_counter()
            entry = registry.register(reg, DRIVE, model=base + ".yaml", library=base + ".npz",
                                      watch_reference=base + ".watch.npz")
            train["seconds"] = time.perf_counter() - t0
            train["printed"] = [f"registered {entry.hardware_id} version {entry.version}"]
        train["registered_wall_s"] = os.stat(reg).st_mtime
        train["ended_before_stream_end_s"] = streaming_at + duration_s - time.time()
        log(f"registry_loop: the registering step took {train['seconds']:.1f} s; waiting for the fleet's end")
        fleet.wait(timeout=duration_s * 3 + 300)
    finally:
        if fleet.poll() is None:
            fleet.kill()
            fleet.wait()
    result = json.load(open(summary))
    rows = {r["drive"]: r for r in result["drives"]}
    after = versions_of(reg)
    swapped = sorted({e["drive"] for e in result["registry_events"] if e["event"] == "swapped"})
    others = [h for h in rows if h != DRIVE]
    missed = {h: max(0, rows[h]["onset_windows"] - rows[h]["onsets_before_offset"] - rows[h]["onsets_estimated"])
              for h in others}
    seen = rows[DRIVE]["versions_seen_wall_s"].get("2")
    swap = [e for e in result["registry_events"] if e["drive"] == DRIVE]
    started = next((e["wall_s"] for e in swap if e["event"] == "swap started"), None)
    done = next((e["wall_s"] for e in swap if e["event"] == "swapped"), None)
    return {
        "registry_loop_pickup_s": None if seen is None else seen - train["registered_wall_s"],
        "registry_loop_changed_drives": swapped,
        "registry_loop_other_drives_missed_onsets": sum(missed.values()),
        "registry_loop_other_drives_chain_restarts": sum(rows[h]["chain_restarts"] for h in others),
        "registry_loop_other_drives_registry_unchanged": all(after[h] == before[h] for h in others),
        "registry_loop_other_drives_version": sorted({rows[h]["model_version"] for h in others}),
        "registry_loop_other_drives_realtime": sum(rows[h]["realtime"] for h in others),
        "registry_loop_other_drives_all_chunks": all(rows[h]["chunks"] == rows[h]["expected_chunks"] for h in others),
        "registry_loop_drive": DRIVE,
        "registry_loop_drive_version": rows[DRIVE]["model_version"],
        "registry_loop_drive_library": os.path.basename(rows[DRIVE]["library"]),
        "registry_loop_drive_registry": {"before": before[DRIVE], "after": after[DRIVE]},
        "registry_loop_swap_s": None if started is None or done is None else done - started,
        "registry_loop_detection_s": None if started is None else started - train["registered_wall_s"],
        "registry_loop_drives": len(rows), "registry_loop_layout": result["layout"],
        "registry_loop_stream_s": duration_s,
        "registry_loop_registering_s": train["seconds"], "registry_loop_live_train": live_train,
        "registry_loop_train_before_fleet_s": prepared_s,
        "registry_loop_live_train_end_before_stream_end_s": train["ended_before_stream_end_s"],
        "registry_loop_train_said": train["printed"],
        "registry_loop_events": result["registry_events"],
        "registry_loop_fleet_said": [x.strip() for x in lines if x.startswith("fleet:")][:20],
        "registry_loop_missed_onsets_by_drive": missed,
        "registry_loop_by_drive": {h: {k: r.get(k) for k in (
            "chunks", "expected_chunks", "joined_at_sample", "onset_windows", "onsets_before_offset", "onsets_estimated",
            "lag_ms_median", "lag_ms_max", "realtime", "cpu_percent", "model_version", "chain_restarts")}
            for h, r in rows.items()},
        "registry_loop_fleet_wall_s": result.get("wall_s"),
        "registry_loop_what_ran": (
            f"before the fleet: add-effect wheel_coulomb_friction --value torque_Nm=1.2 --drive {DRIVE} (no diagnosis)"
            + (f"; live, when every drive streamed: nice -n 10 train --drive {DRIVE} --model {MODEL} {' '.join(TRAIN)} "
               "(trains, builds the watch reference, registers)" if live_train else
               f", train --model {MODEL} -o {MODEL[:-5]}.npz {' '.join(TRAIN)} (library + watch reference, not "
               f"registered); live, 10 s after every drive streamed: files.registry.register({DRIVE}, model, library, "
               "watch reference), train --drive's registering step")),
    }
