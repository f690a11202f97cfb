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

- quantised (stop 59): a quiet signal behind a coarse ADC is not a stuck sensor, a dead one still is. Clean
  recordings quantised to N bits over the accelerometers' ranges (a1 +-50 g, a2 +-4 g): ``quantised_false_stuck``
  counts the signals flagged stuck; and on each of them a2 then a1 made dead three ways (dies in its longest quiet
  run and holds to the end; holds 30 ms from 10 ms before its largest excursion; holds 0.2 s, entered and left by
  one step): ``quantised_dead_detected_rate`` (flagged stuck or at a rail over at least the hold). Development:
  the foreign bench's clean drives and the plant's at 8, 10 and 12 bits (written before the rule, tuned on
  them); **sealed** (``--sealed-quantised``, run once at the end): the outside sets' clean drives and other plant
  seeds at 9 and 11 bits.

- rails behind a 12-bit ADC (stop 59): a1 over +-200 g (the range config/windowing.yaml names: 0.96 m/s^2 steps),
  a2 over +-4 g, and behind 16 bits (a1 +-50 g). ``adc_false_rails``: clean drives read at a rail (development: the
  35 clean drives of the foreign bench and the outside development suites); ``adc_clips_found`` of ``adc_clip_cases``:
  8 of them with a1 or a2 clipped at 50/75/95 % of its peak on both rails or one, then unquantised, 12 or 16 bits.
  Sealed (``--sealed-rails-adc``, run once): the spent outside sealed suites' clean drives, clips at 60/85/90 %.

- rails behind a codec whose step grows with |x| (stop 61): float16 storage, a block floating-point codec (blocks of
  64 samples, 10-bit mantissas), a 12-bit mu-law ADC (a1 +-200 g, a2 +-4 g); ``codec_false_rails`` on the same clean
  drives as the ADC check, ``codec_clips_found`` of ``codec_clip_cases`` alike. Sealed (``--sealed-rails-codec``, run
  once): blocks of 32 with 8-bit mantissas, a 12-bit A-law ADC, bfloat16, on the spent sealed suites' clean drives.

- a rail with noise on it (stop 61): a sensor that saturates in its analog stage and is read with noise after it;
  ``noisy_clips_found`` of ``noisy_clip_cases``, ``noisy_false_flags`` on the same drives unclipped (NOISY_DEV; the
  sealed NOISY_SEALED with ``--sealed-noisy-rails``, run once).

`python bench/_reliability/saturation.py [--sealed | --sealed-quantised | --sealed-rails-adc | --sealed-rails-codec |
--sealed-noisy-rails]` prints the dict as JSON.
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


def _simulated(spec) -> dict:
    """A foreign drive's a1, a2 over DURATION_S."""
    from foreign_drives.drive import make_recording
    rec = make_recording(dataclasses.replace(spec, duration_s=DURATION_S))
    return {s: np.asarray(rec.signals[s], dtype=float) for s in ("a1", "a2")}


def _foreign(label: str) -> dict:
    from foreign_drives.suites import BENCH
    return _simulated(next(s for s in BENCH if s.label == label))


def _count(signals: dict, **overrides) -> dict:
    from backlash_monitor.windowing import DEFAULTS
    from backlash_monitor.windowing.saturation import SaturationCounter, SaturationSettings
    counter = SaturationCounter(("a1", "a2"),
                                SaturationSettings.from_config({**DEFAULTS["saturation"], **overrides}))
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


# the accelerometers' full scales behind an ADC: the bench's own (foreign_drives/suites.py ADC16: a1 +-50 g, a2
# +-4 g) and a high-g a1 (+-200 g, the range config/windowing.yaml names)
FULL_SCALE_M_S2 = {"a1": 50 * 9.81, "a2": 4 * 9.81}
HIGH_G_FULL_SCALE_M_S2 = {"a1": 200 * 9.81, "a2": 4 * 9.81}


def _adc_step(signal: str, bits: int, full_scale: dict = FULL_SCALE_M_S2) -> float:
    """An ADC's step [m/s^2] over a signal's full scale."""
    return 2 * full_scale[signal] / 2 ** bits


def _adc(x: np.ndarray, step: float | None) -> np.ndarray:
    """x behind an undithered ADC of this step (None: unquantised)."""
    return x if step is None else np.round(x / step) * step
QUANTISED_DEV = {"bits": (8, 10, 12), "plant_seeds": (41, 42, 43, 44)}
QUANTISED_SEALED = {"bits": (9, 11), "plant_seeds": (61, 62, 63),
                    "outside_clean": ("od_clean_w6.0_eta0.03_n0.92", "od2_clean_w5.8_eta0.028_n0.91",
                                      "od3_clean_w7.8_eta0.04_n0.95", "od5_clean_w7.2_eta0.0325_n0.92",
                                      "od7_clean_w7.6_eta0.0275_n0.93")}


def _quantised_recordings(sealed: bool) -> dict:
    """{name: {a1, a2}} unquantised: the development or the sealed clean drives."""
    from foreign_drives.suites import BENCH, SUITES
    recs = {}
    if sealed:
        specs = {s.label: s for suite in SUITES.values() for s in suite}
        for label in QUANTISED_SEALED["outside_clean"]:
            recs[f"foreign:{label}"] = _simulated(specs[label])
    else:
        for spec in BENCH:
            if spec.kind == "clean":
                recs[f"foreign:{spec.label}"] = _foreign(spec.label)
    cfg = QUANTISED_SEALED if sealed else QUANTISED_DEV
    specs = [(0.004 + 0.001 * k, 0.02 + 0.01 * k, 0.9 + 0.02 * k, seed) for k, seed in enumerate(cfg["plant_seeds"])]
    for spec, sig in zip(specs, _plant(specs)):
        recs[f"plant:seed{spec[3]}"] = sig
    return recs


def _dead_versions(x: np.ndarray, step: float) -> dict:
    """The signal made dead three ways: {how: (signal, samples held)}."""
    starts = np.concatenate(([0], np.flatnonzero(np.diff(x)) + 1))
    lengths = np.diff(np.concatenate((starts, [x.size])))
    out = {}
    i = int(starts[np.argmax(lengths)])
    if i > x.size - 20_000:
        i = x.size // 2
    held = x.copy()
    held[i:] = x[i]
    out["holds_to_the_end"] = (held, x.size - i)
    peak = int(np.argmax(np.abs(x - np.median(x))))
    i = max(peak - 500, 1)
    held = x.copy()
    held[i:i + 1500] = x[i - 1]
    out["holds_30ms_across_an_event"] = (held, 1500)
    i = x.size // 3
    held = x.copy()
    held[i:i + 10_000] = x[i - 1]
    held[i + 10_000] = x[i - 1] + step
    out["holds_0.2s_left_by_one_step"] = (held, 10_000)
    return out


def _quantised(sealed: bool) -> dict:
    from backlash_monitor.windowing import DEFAULTS
    from backlash_monitor.windowing.saturation import SaturationSettings, assess_signal
    settings = SaturationSettings.from_config(DEFAULTS["saturation"])
    cfg = QUANTISED_SEALED if sealed else QUANTISED_DEV
    false_stuck, before, found_before, clean_rows, dead_rows = 0, 0, 0, [], []
    for name, sig in _quantised_recordings(sealed).items():
        for bits in cfg["bits"]:
            adc = {s: _adc(sig[s], _adc_step(s, bits)) for s in ("a1", "a2")}
            totals = _count(adc)
            flagged = [r.message() for r in totals.values() if r.stuck]
            false_stuck += len(flagged)
            before += sum(bool(r.stuck) for r in _count(adc, stuck_quiet_steps=0).values())
            clean_rows.append({"recording": name, "bits": bits, "stuck": flagged,
                               "rail": [r.message() for r in totals.values() if r.at_rail]})
            if flagged:
                _log("FALSE STUCK", name, bits, flagged)
            for s in ("a2", "a1"):
                for how, (held, n) in _dead_versions(adc[s], _adc_step(s, bits)).items():
                    r = assess_signal(held, s, settings)
                    found = bool(r.stuck + r.at_rail >= n)
                    off = assess_signal(held, s, dataclasses.replace(settings, stuck_quiet_steps=0))
                    found_before += bool(off.stuck + off.at_rail >= n)
                    dead_rows.append({"recording": name, "bits": bits, "signal": s, "how": how, "held": n,
                                      "detected": found, "message": r.message()})
                    if not found:
                        _log("DEAD NOT FOUND", name, bits, s, how, r.message())
    prefix = "sealed_" if sealed else ""
    return {f"{prefix}quantised_false_stuck": false_stuck,
            f"{prefix}quantised_false_stuck_without_quiet_rule": before,
            f"{prefix}quantised_recordings": len(clean_rows),
            f"{prefix}quantised_false_rail": sum(bool(r["rail"]) for r in clean_rows),
            f"{prefix}quantised_dead_detected_rate": sum(r["detected"] for r in dead_rows) / len(dead_rows),
            f"{prefix}quantised_dead_detected_rate_without_quiet_rule": found_before / len(dead_rows),
            f"{prefix}quantised_dead_cases": len(dead_rows),
            "details": {"quantised_clean": clean_rows, "quantised_dead": dead_rows}}


# the chains of the rails check: a high-g a1 behind 12 bits, the bench's own behind 16
RAILS_FULL_SCALE_M_S2 = {12: HIGH_G_FULL_SCALE_M_S2, 16: FULL_SCALE_M_S2}


def _rails_adc(x: np.ndarray, bits: int | None, signal: str) -> np.ndarray:
    return _adc(x, None if bits is None else _adc_step(signal, bits, RAILS_FULL_SCALE_M_S2[bits]))


def _rails_behind_adc(sealed: bool) -> dict:
    from foreign_drives.suites import SEALED_FIRST_SEED, SUITES, suite
    names = ([n for n in SEALED_FIRST_SEED if n.startswith("outside_sealed")] if sealed
             else ["bench"] + [n for n in SUITES if n.startswith("outside_dev")])
    if sealed:      # never an unspent sealed half
        sys.path.insert(0, str(REPO / "bench"))
        from _workbench.outside import UNSPENT_SEALED
        names = [n for n in names if n not in UNSPENT_SEALED]
    recs = {spec.label: _simulated(spec) for n in names for spec in suite(n) if spec.kind == "clean"}
    false = []
    for label, sig in recs.items():
        for bits in (12, 16):
            for r in _count({s: _rails_adc(sig[s], bits, s) for s in ("a1", "a2")}).values():
                if r.at_rail:
                    false.append(f"{label} {bits}-bit: {r.message()}")
    clips = []
    for label in list(recs)[:: max(1, len(recs) // 8)][:8]:
        for s in ("a1", "a2"):
            for fraction in ((0.6, 0.85, 0.9) if sealed else (0.5, 0.75, 0.95)):
                for rails in ("both", "one"):
                    for bits in (None, 12, 16):
                        clipped, _ = _clip(recs[label][s], fraction, rails)
                        adc = {k: _rails_adc(clipped if k == s else recs[label][k], bits, k) for k in ("a1", "a2")}
                        clips.append({"case": f"{label}:{s}:{fraction}:{rails}:{bits or 'float'}",
                                      "found": bool(_count(adc)[s].at_rail > 0)})
    prefix = "sealed_" if sealed else ""
    return {f"{prefix}adc_clean_drives": len(recs), f"{prefix}adc_false_rails": len(false),
            f"{prefix}adc_clips_found": sum(c["found"] for c in clips), f"{prefix}adc_clip_cases": len(clips),
            "details": {"adc_false_rails": false, "adc_clips_missed": [c["case"] for c in clips if not c["found"]]}}


# A codec whose step grows with |x| (stop 61): a recorder that stores a float16, a block floating-point codec (a
# block's samples share one exponent, its largest sets the step), a companding ADC (mu-law, A-law). The step near an
# impact's top is coarse while the signal's smallest change, far from it, is fine. Written before any rule was
# changed for them; the sealed codecs are run once (--sealed-rails-codec).
CODECS_DEV = ("float16", "block_float:64:10", "mu_law:12")
CODECS_SEALED = ("block_float:32:8", "a_law:12", "bfloat16")


def _block_float(x: np.ndarray, block: int, mantissa_bits: int) -> np.ndarray:
    """Blocks of ``block`` samples sharing one exponent: a signed mantissa of ``mantissa_bits`` bits by the block's
    largest |x|."""
    out = np.empty_like(x)
    top = 2 ** (mantissa_bits - 1) - 1
    for k in range(0, x.size, block):
        part = x[k:k + block]
        peak = float(np.abs(part).max())
        if peak == 0.0:
            out[k:k + block] = 0.0
            continue
        step = 2.0 ** (np.floor(np.log2(peak)) + 1 - (mantissa_bits - 1))
        out[k:k + block] = np.clip(np.round(part / step), -top, top) * step
    return out


def _companded(x: np.ndarray, full_scale: float, bits: int, law: str) -> np.ndarray:
    """A companding ADC over +-full_scale: mu-law (mu = 255) or A-law (A = 87.6), ``bits`` bits, expanded back."""
    u = np.clip(np.abs(x) / full_scale, 0.0, 1.0)
    if law == "mu_law":
        y = np.log1p(255.0 * u) / np.log1p(255.0)
    else:
        a = 87.6
        y = np.where(u < 1 / a, a * u / (1 + np.log(a)), (1 + np.log(np.maximum(a * u, 1e-300))) / (1 + np.log(a)))
    levels = 2 ** (bits - 1) - 1
    q = np.round(y * levels) / levels
    if law == "mu_law":
        v = np.expm1(q * np.log1p(255.0)) / 255.0
    else:
        a = 87.6
        t = q * (1 + np.log(a))
        v = np.where(t < 1, t / a, np.exp(t - 1) / a)
    return np.sign(x) * v * full_scale


def _codec(x: np.ndarray, codec: str, signal: str) -> np.ndarray:
    name, *args = codec.split(":")
    if name == "float16":
        return x.astype(np.float16).astype(float)
    if name == "bfloat16":       # float32 with its low 16 bits cut: 8 significant bits
        return (x.astype(np.float32).view(np.uint32) & np.uint32(0xFFFF0000)).view(np.float32).astype(float)
    if name == "block_float":
        return _block_float(x, int(args[0]), int(args[1]))
    return _companded(x, HIGH_G_FULL_SCALE_M_S2[signal], int(args[0]), name)


def _rails_behind_codec(sealed: bool) -> dict:
    """False rails on clean drives behind each codec, and clips found behind it (as _rails_behind_adc)."""
    from foreign_drives.suites import SEALED_FIRST_SEED, SUITES, suite
    names = ([n for n in SEALED_FIRST_SEED if n.startswith("outside_sealed")] if sealed
             else ["bench"] + [n for n in SUITES if n.startswith("outside_dev")])
    if sealed:      # never an unspent sealed half
        sys.path.insert(0, str(REPO / "bench"))
        from _workbench.outside import UNSPENT_SEALED
        names = [n for n in names if n not in UNSPENT_SEALED]
    codecs = CODECS_SEALED if sealed else CODECS_DEV
    recs = {spec.label: _simulated(spec) for n in names for spec in suite(n) if spec.kind == "clean"}
    false, stuck = [], []
    for label, sig in recs.items():
        for codec in codecs:
            for r in _count({s: _codec(sig[s], codec, s) for s in ("a1", "a2")}).values():
                if r.at_rail:
                    false.append(f"{label} {codec}: {r.message()}")
                    _log("FALSE RAIL", false[-1])
                if r.stuck:
                    stuck.append(f"{label} {codec}: {r.message()}")
                    _log("FALSE STUCK", stuck[-1])
    clips = []
    for label in list(recs)[:: max(1, len(recs) // 8)][:8]:
        for s in ("a1", "a2"):
            for fraction in ((0.6, 0.85, 0.9) if sealed else (0.5, 0.75, 0.95)):
                for rails in ("both", "one"):
                    for codec in codecs:
                        clipped, _ = _clip(recs[label][s], fraction, rails)
                        coded = {k: _codec(clipped if k == s else recs[label][k], codec, k) for k in ("a1", "a2")}
                        clips.append({"case": f"{label}:{s}:{fraction}:{rails}:{codec}",
                                      "found": bool(_count(coded)[s].at_rail > 0)})
    prefix = "sealed_" if sealed else ""
    return {f"{prefix}codec_clean_drives": len(recs), f"{prefix}codecs": list(codecs),
            f"{prefix}codec_false_rails": len(false), f"{prefix}codec_false_stuck": len(stuck),
            f"{prefix}codec_clips_found": sum(c["found"] for c in clips), f"{prefix}codec_clip_cases": len(clips),
            "details": {"codec_false_rails": false, "codec_false_stuck": stuck, "codec_clips_missed": [c["case"] for c in clips if not c["found"]]}}


# A sensor that saturates in its analog stage and is read with noise after it (stop 61): its rail is a level with the
# front end's and the ADC's noise on it, not one value repeated. Cases written before any rule for them: a1 or a2
# clipped at c * its peak |x| on both rails, then white noise of n * that peak, then the chain (unquantised, or an ADC;
# sealed: a first-order 5 kHz anti-alias filter before the ADC too). Found: the clipped signal at a rail within
# 4 noise sd + a step of the clip level, the other signal none. False flags: the same drives unclipped through the
# same chains. Sealed (--sealed-noisy-rails): other drives, clip levels and noise, run once.
NOISY_DEV = {"drives": (("plant", 21), ("plant", 22), ("foreign", "clean_w2.5_eta0.05_n0.97"),
                        ("foreign", "clean_w5.0_eta0.025_n0.89"), ("foreign", "clean_w7.1_eta0.0125_n0.97")),
             "fractions": (0.5, 0.75, 0.95), "noise_of_peak": (1e-4, 1e-3, 3e-3), "chains": ("float", "adc16")}
NOISY_SEALED = {"drives": (("plant", 31), ("plant", 32), ("foreign", "clean_w3.1_eta0.0125_n0.89"),
                           ("foreign", "clean_w8.3_eta0.0375_n0.95"), ("foreign", "clean_w10_eta0.05_n0.89")),
                "fractions": (0.6, 0.85, 0.9), "noise_of_peak": (3e-4, 2e-3),
                "chains": ("float", "adc12", "lowpass5k_adc16")}


def _chain(x: np.ndarray, chain: str, signal: str) -> np.ndarray:
    """After the noise: unquantised, an ADC of N bits over the bench's full scale, or a first-order 5 kHz low-pass
    (the anti-alias filter) and then a 16-bit ADC."""
    if chain == "float":
        return x
    if chain.startswith("lowpass5k"):
        a = np.exp(-2 * np.pi * 5000.0 / 50_000.0)
        y = np.empty_like(x)
        acc = x[0]
        for i, v in enumerate(x):          # y[i] = a*y[i-1] + (1-a)*x[i]
            acc = a * acc + (1 - a) * v
            y[i] = acc
        x, chain = y, chain.split("_", 1)[1]
    return _adc(x, _adc_step(signal, int(chain[3:])))


def _noisy_rails(sealed: bool) -> dict:
    cfg = NOISY_SEALED if sealed else NOISY_DEV
    recs = {}
    seeds = [d for src, d in cfg["drives"] if src == "plant"]
    for seed, sig in zip(seeds, _plant([(0.005, 0.025, 0.89, seed) for seed in seeds])):
        recs[("plant", seed)] = sig
    for src, label in cfg["drives"]:
        if src == "foreign":
            recs[(src, label)] = _foreign(label)
    rng = np.random.default_rng(61)
    cases, false = [], []
    for (src, drive), sig in recs.items():
        for noise in cfg["noise_of_peak"]:
            for chain in cfg["chains"]:
                noisy = {s: v + noise * float(np.abs(v).max()) * rng.standard_normal(v.size) for s, v in sig.items()}
                clean = {s: _chain(v, chain, s) for s, v in noisy.items()}
                for r in _count(clean).values():
                    if r.faulty:
                        false.append(f"{src}:{drive}:{noise}:{chain}: {r.message()}")
                        _log("NOISY FALSE FLAG", false[-1])
                for s in ("a1", "a2"):
                    peak = float(np.abs(sig[s]).max())
                    for fraction in cfg["fractions"]:
                        level = fraction * peak
                        x = np.clip(sig[s], -level, level) + noise * peak * rng.standard_normal(sig[s].size)
                        signals = dict(clean)
                        signals[s] = _chain(x, chain, s)
                        totals = _count(signals)
                        other = "a2" if s == "a1" else "a1"
                        tol = 4 * noise * peak + (0.0 if chain == "float" else _adc_step(s, int(chain[-2:])))
                        found = [abs(v) for v in (totals[s].upper_rail, totals[s].lower_rail) if v is not None]
                        ok = bool(totals[s].at_rail > 0 and totals[other].at_rail == 0 and found
                                  and all(abs(v - level) <= tol for v in found))
                        cases.append({"case": f"{src}:{drive}:{s}:{fraction}:{noise}:{chain}", "found": ok,
                                      "message": totals[s].message()})
    # and the clean drives of the ADC check (development: the bench's and the outside development suites'; sealed:
    # the spent sealed suites') with noise of 1e-3 of each signal's peak, unquantised and behind a 16-bit ADC
    from foreign_drives.suites import SEALED_FIRST_SEED, SUITES, suite
    names = ([n for n in SEALED_FIRST_SEED if n.startswith("outside_sealed")] if sealed
             else ["bench"] + [n for n in SUITES if n.startswith("outside_dev")])
    if sealed:
        sys.path.insert(0, str(REPO / "bench"))
        from _workbench.outside import UNSPENT_SEALED
        names = [n for n in names if n not in UNSPENT_SEALED]
    wide = 0
    for spec in (spec for n in names for spec in suite(n) if spec.kind == "clean"):
        sig = _simulated(spec)
        for chain in ("float", "adc16"):
            wide += 1
            noisy = {k: _chain(v + 1e-3 * float(np.abs(v).max()) * rng.standard_normal(v.size), chain, k)
                     for k, v in sig.items()}
            for r in _count(noisy).values():
                if r.faulty:
                    false.append(f"{spec.label}:0.001:{chain}: {r.message()}")
                    _log("NOISY FALSE FLAG", false[-1])
    prefix = "sealed_" if sealed else ""
    return {f"{prefix}noisy_clip_cases": len(cases), f"{prefix}noisy_clips_found": sum(c["found"] for c in cases),
            f"{prefix}noisy_false_flags": len(false), f"{prefix}noisy_clean_chains": len(recs) * len(cfg["noise_of_peak"])
            * len(cfg["chains"]) + wide,
            "details": {"noisy_false_flags": false, "noisy_clips_missed": [c["case"] for c in cases if not c["found"]]}}


def run(sealed: bool = False, sealed_quantised: bool = False, sealed_rails_adc: bool = False,
        sealed_rails_codec: bool = False, sealed_noisy_rails: bool = False) -> dict:
    started = time.perf_counter()
    if sealed_noisy_rails:
        out = _noisy_rails(True)
        out["seconds"] = round(time.perf_counter() - started, 1)
        return out
    if sealed_rails_codec:
        out = _rails_behind_codec(True)
        out["seconds"] = round(time.perf_counter() - started, 1)
        return out
    if sealed_rails_adc:
        out = _rails_behind_adc(True)
        out["seconds"] = round(time.perf_counter() - started, 1)
        return out
    if sealed_quantised:
        out = _quantised(True)
        out["seconds"] = round(time.perf_counter() - started, 1)
        return out
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
        quantised = _quantised(False)
        details.update(quantised.pop("details"))
        out.update(quantised)
        rails = _rails_behind_adc(False)
        details.update(rails.pop("details"))
        out.update(rails)
        codec = _rails_behind_codec(False)
        details.update(codec.pop("details"))
        out.update(codec)
        noisy = _noisy_rails(False)
        details.update(noisy.pop("details"))
        out.update(noisy)
    out["clip_cases"] = len(rows)
    out["seconds"] = round(time.perf_counter() - started, 1)
    out["details"] = details
    return out


if __name__ == "__main__":
    print(json.dumps(run(sealed="--sealed" in sys.argv[1:], sealed_quantised="--sealed-quantised" in sys.argv[1:],
                         sealed_rails_adc="--sealed-rails-adc" in sys.argv[1:],
                         sealed_rails_codec="--sealed-rails-codec" in sys.argv[1:],
                         sealed_noisy_rails="--sealed-noisy-rails" in sys.argv[1:]), indent=1))
