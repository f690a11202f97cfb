"""The monitor's width against constant accelerometer offsets and gain errors (issue 20, item 4).

``measure()`` returns a dict with

- ``sensor_offset_width_shift_mm``: the largest change of the monitor's published fused continuous
  width (a1+a2: the median of the last 8 onset windows' continuous widths) when the recording gets a
  constant offset of +-5 m/s^2 on a1 or +-2 m/s^2 on a2 (goal: <= 0.05 mm);
- ``sensor_gain_width_shift_mm``: the same for a gain error of +-10 % on a1 or on a2 (reported);

over every estimate whose fusion is full (8 onset events), each compared with the same window of
the unchanged recording, for the project's own drives (4 s, seeds 9511-9516, which no test uses;
several widths, eta_k and n1) and any ``extra_recordings`` made by another generator.

Own drives: the plant's own sensor effects (``accelerometer_bias``, ``accelerometer_gain``) on the
same scenario and noise as the clean recording (common random numbers: only the sensor differs).
Extra recordings: the perturbation applied to their a1/a2 arrays (a + b, a * (1 + g)), which is
what the plant's effects do to its published samples too.

An extra recording is a mapping: ``signals`` ({"a1", "a2", and "angle_difference" or "omega1" +
"omega2": 1-D arrays [m/s^2, rad, rad/s]}), ``sample_period_s``, ``true_width_m`` and optionally
``name``. The monitor runs as ``analyze`` runs it (backlash_monitor.chain.record.estimate_record: windows
with the sensor offset estimate, sym5 denoising, the packaged contact_loss library, shape mode).

    python bench/_workbench/sensor_offset.py      # one JSON object on stdout (~20 s)
"""
from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Iterable, Mapping

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

SIGNAL = "a1+a2"          # the drive's published width (fleet/trend.py PRIMARY_SIGNAL)
DURATION_S = 4.0
# (width [m], eta_k [Pa s^n], n1, seed): own drives over the grid's range, seeds no test uses
OWN_DRIVES = ((0.0030, 0.0125, 0.91, 9511), (0.0050, 0.0250, 0.95, 9512), (0.0065, 0.0500, 0.89, 9513),
              (0.0075, 0.0250, 0.89, 9514), (0.0090, 0.0375, 0.89, 9515), (0.0100, 0.0375, 0.97, 9516))
OFFSETS_M_S2 = {"a1": (5.0, -5.0), "a2": (2.0, -2.0)}      # the goal's offsets
GAINS = {"a1": (0.10, -0.10), "a2": (0.10, -0.10)}          # relative gain errors (reported)


def _perturbations():
    """(label, kind 'offset'|'gain', signal, value) of every perturbed recording."""
    out = []
    for kind, table in (("offset", OFFSETS_M_S2), ("gain", GAINS)):
        for signal, values in table.items():
            out += [(f"{signal} {kind} {v:+g}", kind, signal, v) for v in values]
    return out


def own_recordings(drives=OWN_DRIVES, duration_s: float = DURATION_S) -> list[dict]:
    """Every own drive clean and with each perturbation, simulated in one batch: per drive a list
    [clean, perturbed...] in the order of _perturbations()."""
    from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
    perturbations = _perturbations()
    config = load_plant_config().with_overrides({"effects.accelerometer_bias": True,
                                                 "effects.accelerometer_gain": True})
    scenarios, params = [], {f"accelerometer_bias.{s}_m_s2": [] for s in ("a1", "a2")}
    params.update({f"accelerometer_gain.{s}_relative_change": [] for s in ("a1", "a2")})
    for width, eta_k, n1, seed in drives:
        for label in [None] + perturbations:
            scenarios.append(Scenario(width_m=width, eta_k=eta_k, n1=n1, seed=seed))
            for s in ("a1", "a2"):
                bias = label[3] if label and label[1] == "offset" and label[2] == s else 0.0
                gain = label[3] if label and label[1] == "gain" and label[2] == s else 0.0
                params[f"accelerometer_bias.{s}_m_s2"].append(bias)
                params[f"accelerometer_gain.{s}_relative_change"].append(gain)
    sim = PlantSimulator(scenarios, config=config, noise=True,
                         parameters={k: np.array(v) for k, v in params.items()},
                         outputs=("a1", "a2", "angle_difference"))
    chunk = sim.run(int(round(duration_s / sim.sample_period_s)))
    per_drive = len(perturbations) + 1
    out = []
    for d, (width, eta_k, n1, seed) in enumerate(drives):
        group = []
        for k in range(per_drive):
            i = d * per_drive + k
            group.append({"name": f"own w{width * 1e3:g}mm eta{eta_k:g} n{n1:g} seed{seed}",
                          "sample_period_s": chunk.sample_period_s, "true_width_m": width,
                          "signals": {s: np.ascontiguousarray(getattr(chunk, s)[i])
                                      for s in ("a1", "a2", "angle_difference")}})
        out.append(group)
    return out


def perturbed(recording: Mapping, kind: str, signal: str, value: float) -> dict:
    """An extra recording with a constant offset (a + value) or a gain error (a * (1 + value))."""
    signals = dict(recording["signals"])
    a = np.asarray(signals[signal], dtype=np.float64)
    signals[signal] = a + value if kind == "offset" else a * (1.0 + value)
    return {**recording, "signals": signals}


def monitor_trace(recording: Mapping, library) -> dict:
    """The monitor's estimates of one recording: per classified onset window (by entry index) the
    fused continuous width and its fused events, and the last sensor offset estimate."""
    from backlash_monitor.chain.record import estimate_record
    from backlash_monitor.estimation import DriveEstimator
    estimator = DriveEstimator(library, mode="shape")
    trace, offsets = {}, {}
    for window, estimates in estimate_record(recording["signals"], recording["sample_period_s"], estimator):
        offsets = dict(getattr(window, "sensor_offsets", {}))
        for e in estimates:
            if e.signal_name == SIGNAL:
                trace[window.entry_sample_index] = (e.fused_continuous_width_m, e.fused_events)
    return {"trace": trace, "sensor_offsets": offsets}


def _shift_mm(reference: dict, other: dict, fusion_events: int, name: str) -> float:
    """Largest |fused continuous width change| [mm] over the windows whose fusion is full in both."""
    shifts = [abs(other[k][0] - w) * 1e3 for k, (w, n) in reference.items()
              if n >= fusion_events and k in other and other[k][1] >= fusion_events]
    if not shifts:
        raise ValueError(f"recording {name!r}: no onset window with a full fusion ({fusion_events} "
                         f"classified onsets; it has {len(reference)}): give recordings of at least "
                         f"{(fusion_events + 1) * 0.25 + 0.1:g} s at 4 load pulses per second")
    return max(shifts)


def measure(own: bool = True, extra_recordings: Iterable[Mapping] = (), library_path=None,
            drives=OWN_DRIVES, duration_s: float = DURATION_S) -> dict:
    """The figures of this module's docstring over the own drives (``own``) and ``extra_recordings``."""
    from backlash_monitor.classifier.patterns import load_library
    from backlash_monitor.estimation import DEFAULT_FUSION_EVENTS
    from backlash_monitor.windowing import default_window_offset
    started = time.perf_counter()
    library = load_library(library_path, trigger="contact_loss",
                           window_offset_samples=default_window_offset("contact_loss"))
    perturbations = _perturbations()
    groups = []          # (name, source, true width, [clean, perturbed...])
    if own:
        for group in own_recordings(drives, duration_s):
            groups.append((group[0]["name"], "own", group[0]["true_width_m"], group))
    for i, rec in enumerate(extra_recordings):
        group = [rec] + [perturbed(rec, kind, signal, value) for _, kind, signal, value in perturbations]
        groups.append((rec.get("name", f"extra {i}"), "extra", float(rec["true_width_m"]), group))
    rows, worst = [], {"offset": (0.0, ""), "gain": (0.0, "")}
    for name, source, truth, group in groups:
        traces = [monitor_trace(r, library) for r in group]
        clean = traces[0]["trace"]
        full = [w for w, n in clean.values() if n >= DEFAULT_FUSION_EVENTS]
        row = {"recording": name, "source": source, "true_width_m": truth,
               "fused_continuous_width_mm": full[-1] * 1e3 if full else math.nan,
               "fused_continuous_error_mm": abs(full[-1] - truth) * 1e3 if full else math.nan,
               "shift_mm": {}, "estimated_offsets_m_s2": {}}
        for (label, kind, signal, value), t in zip(perturbations, traces[1:]):
            shift = _shift_mm(clean, t["trace"], DEFAULT_FUSION_EVENTS, name)
            row["shift_mm"][label] = shift
            if kind == "offset":
                row["estimated_offsets_m_s2"][label] = t["sensor_offsets"].get(signal, math.nan)
            if shift >= worst[kind][0]:
                worst[kind] = (shift, f"{name}: {label}")
        rows.append(row)
    return {
        "sensor_offset_width_shift_mm": worst["offset"][0],
        "sensor_offset_worst": worst["offset"][1],
        "sensor_gain_width_shift_mm": worst["gain"][0],
        "sensor_gain_worst": worst["gain"][1],
        "sensor_offset_goal_mm": 0.05,
        "offsets_m_s2": {s: list(v) for s, v in OFFSETS_M_S2.items()},
        "gains": {s: list(v) for s, v in GAINS.items()},
        "signal": SIGNAL, "recordings": len(groups),
        "what": "largest |change| of the monitor's fused continuous width (median of the last 8 onset "
                "windows' continuous widths, a1+a2) over every estimate with a full fusion, perturbed "
                "recording against the same recording unperturbed",
        "per_recording": rows, "seconds": time.perf_counter() - started,
    }


def main() -> int:
    os.environ.setdefault("NUMBA_NUM_THREADS", "1")
    print(json.dumps(measure(), allow_nan=True))
    return 0


if __name__ == "__main__":
    sys.exit(main())
