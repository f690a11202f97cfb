"""Sensor saturation as an input fault (issue 34, part 3). `run()` returns

    {"saturation_detected_rate": r, "saturation_false_flags": n, "sealed": {...}, "details": {...}}

- detected: a recording whose a1 or a2 is clipped at +-c * its peak |x| (c = 50-95 %), from our simulator
  (backlash_monitor.plant) and from the foreign generator (foreign_drives, clipped after its own sensor chain),
  counted as the windowing stage, ``analyze``, ``bag-info`` and the workbench count it
  (windowing/saturation.py SaturationCounter, blocks of 1 s): the clipped signal has samples at a rail equal to
  the clip level, and the other signal none. Rate = detected / cases.
- false flags: clean recordings (the 10 clean foreign bench drives, two of them behind an undithered 16-bit ADC,
  one with 14- and one with 16-bit encoders; our simulator over widths, eta_k, n1, noise on and off, and behind
  a 16-bit ADC) with any sample at a rail or stuck: each such signal counts one.
- the case lists were written before the thresholds were tuned (config/windowing.yaml ``saturation``: tuned on
  plant seed 11 and the foreign bench's first ten drives, 2 s, clip levels 0.5/0.75/0.9/0.95). The **sealed**
  half (other clip levels, seeds, drives, one-rail clips) is run with ``--sealed`` once, at the end, and
  reported as it came out: ``sealed_detected_rate``.

`python bench/_reliability/saturation.py [--sealed]` prints the dict as JSON.
"""
from __future__ import annotations

import dataclasses
import json
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
if str(REPO) not in sys.path:
    sys.path.insert(0, str(REPO))

DURATION_S = 4.0
A1_LSB_M_S2 = 2 * 50 * 9.81 / 2 ** 16     # a 16-bit ADC over +-50 g / +-4 g (foreign_drives/suites.py ADC16)
A2_LSB_M_S2 = 2 * 4 * 9.81 / 2 ** 16

# (source, drive, signal, clip fraction of the peak, rails); source plant: drive = plant seed (width 5 mm...)
DEV_CLIP_CASES = [(src, drive, sig, c, "both")
                  for src, drives in (("plant", (21, 22)), ("foreign", ("clean_w2.5_eta0.05_n0.97",
                                                                          "clean_w5.0_eta0.025_n0.89",
                                                                          "clean_w7.1_eta0.0125_n0.97")))
                  for drive in drives for sig in ("a1", "a2") for c in (0.5, 0.75, 0.95)]
SEALED_CLIP_CASES = ([(src, drive, sig, c, rails)
                      for src, drives in (("plant", (31, 32)), ("foreign", ("clean_w3.1_eta0.0125_n0.89",
                                                                              "clean_w8.3_eta0.0375_n0.95",
                                                                              "clean_w10_eta0.05_n0.89",
                                                                              "clean_w4.4_eta0.031_n0.93_adc",
                                                                              "clean_w5.6_eta0.015_n0.96_adc")))
                      for drive in drives for sig in ("a1", "a2") for c in (0.6, 0.85, 0.9)
                      for rails in ("both", "one")])
PLANT_CLEAN = [(w, eta, n1, seed, noise) for (w, eta, n1, seed) in
               ((0.0025, 0.0125, 0.89, 41), (0.005, 0.025, 0.93, 42), (0.0075, 0.05, 0.97, 43),
                (0.01, 0.0375, 0.91, 44)) for noise in (True, False)]


def _log(*args) -> None:
    print("[saturation]", *args, file=sys.stderr, flush=True)


def _plant(seeds_or_specs, noise=True) -> list[dict]:
    from backlash_monitor import plant
    scen = [plant.Scenario(width_m=w, eta_k=eta, n1=n1, seed=seed) for (w, eta, n1, seed) in seeds_or_specs]
    sim = plant.PlantSimulator(scen, config=plant.load_plant_config(), noise=noise)
    chunks = [sim.run(10_000) for _ in range(int(DURATION_S * 50_000) // 10_000)]
    return [{s: np.concatenate([getattr(c, s)[i] for c in chunks]) for s in ("a1", "a2")} for i in range(len(scen))]


def _foreign(label: str) -> dict:
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import BENCH
    spec = next(s for s in BENCH if s.label == label)
    rec = make_recording(dataclasses.replace(spec, duration_s=DURATION_S))
    return {s: np.asarray(rec.signals[s], dtype=float) for s in ("a1", "a2")}


def _count(signals: dict) -> dict:
    from backlash_monitor.windowing import DEFAULTS
    from backlash_monitor.windowing.saturation import SaturationCounter, SaturationSettings
    counter = SaturationCounter(("a1", "a2"), SaturationSettings.from_config(DEFAULTS["saturation"]))
    for k in range(0, len(signals["a1"]), 5000):          # chunks, as a stream comes
        counter.feed({s: v[k:k + 5000] for s, v in signals.items()})
    counter.flush()
    return counter.totals()


def _clip(x: np.ndarray, fraction: float, rails: str) -> tuple[np.ndarray, float]:
    """Both rails at +-fraction * peak |x|; one rail: only the side of the peak."""
    peak = float(np.abs(x).max())
    level = fraction * peak
    if rails == "both":
        return np.clip(x, -level, level), level
    return (np.minimum(x, level) if x.max() >= -x.min() else np.maximum(x, -level)), level


def _clip_cases(cases, recordings) -> tuple[float, list]:
    out = []
    for src, drive, sig, fraction, rails in cases:
        signals = dict(recordings[(src, drive)])
        signals[sig], level = _clip(signals[sig], fraction, rails)
        totals = _count(signals)
        other = "a2" if sig == "a1" else "a1"
        found = [abs(v) for v in (totals[sig].upper_rail, totals[sig].lower_rail) if v is not None]
        ok = bool(totals[sig].at_rail > 0 and totals[other].at_rail == 0 and found
                  and all(abs(v - level) <= 1e-9 * max(level, 1.0) for v in found))
        out.append({"case": f"{src}:{drive}:{sig}:{fraction}:{rails}", "detected": ok,
                    "rail_percent": round(100 * totals[sig].rail_fraction, 3),
                    "clipped_percent": round(100 * float(np.mean(signals[sig] != recordings[(src, drive)][sig])), 3),
                    "message": totals[sig].message()})
        if not ok:
            _log("NOT DETECTED", out[-1])
    return (sum(c["detected"] for c in out) / len(out) if out else float("nan")), out


def _recordings(cases) -> dict:
    recs = {}
    seeds = sorted({d for s, d, *_ in cases if s == "plant"})
    for seed, sig in zip(seeds, _plant([(0.005, 0.025, 0.89, seed) for seed in seeds])):
        recs[("plant", seed)] = sig
    for label in sorted({d for s, d, *_ in cases if s == "foreign"}):
        recs[("foreign", label)] = _foreign(label)
    return recs


def _false_flags() -> tuple[int, list]:
    from foreign_drives.suites import BENCH
    clean = {}
    for spec in BENCH:
        if spec.kind == "clean":
            clean[f"foreign:{spec.label}"] = _foreign(spec.label)
    for noise in (True, False):
        specs = [(w, eta, n1, seed) for (w, eta, n1, seed, nz) in PLANT_CLEAN if nz == noise]
        for spec, sig in zip(specs, _plant(specs, noise=noise)):
            name = f"plant:w{spec[0]}_eta{spec[1]}_n{spec[2]}_seed{spec[3]}_noise{int(noise)}"
            clean[name] = sig
            clean[name + "_adc16"] = {"a1": np.round(sig["a1"] / A1_LSB_M_S2) * A1_LSB_M_S2,
                                      "a2": np.round(sig["a2"] / A2_LSB_M_S2) * A2_LSB_M_S2}
    flags, rows = 0, []
    for name, signals in clean.items():
        totals = _count(signals)
        flagged = [r.message() for r in totals.values() if r.faulty]
        flags += len(flagged)
        rows.append({"recording": name, "flags": flagged})
        if flagged:
            _log("FALSE FLAG", name, flagged)
    return flags, rows


def run(sealed: bool = False) -> dict:
    started = time.perf_counter()
    cases = SEALED_CLIP_CASES if sealed else DEV_CLIP_CASES
    rate, rows = _clip_cases(cases, _recordings(cases))
    _log(f"{'sealed' if sealed else 'dev'} clip cases: {sum(r['detected'] for r in rows)} of {len(rows)} detected")
    out = {("sealed_detected_rate" if sealed else "saturation_detected_rate"): rate}
    details = {"clip_cases": rows}
    if not sealed:
        flags, clean_rows = _false_flags()
        _log(f"clean recordings: {len(clean_rows)}, false flags {flags}")
        out["saturation_false_flags"] = flags
        out["clean_recordings"] = len(clean_rows)
        details["clean"] = clean_rows
    out["clip_cases"] = len(rows)
    out["seconds"] = round(time.perf_counter() - started, 1)
    out["details"] = details
    return out


if __name__ == "__main__":
    print(json.dumps(run(sealed="--sealed" in sys.argv[1:]), indent=1))
