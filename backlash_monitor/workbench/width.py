"""The monitor's width estimate on a measurement with a given pattern library (the chain's own stages:
contact_loss windows at the library's window offset, sym5 denoising, DriveEstimator), for the
before/after check of a model update (`train --model M2 --out LIB.npz`).

Two figures per drive, as the monitor publishes them per onset window (classifier node / `analyze`):
- the *continuous width* of each window (shape mode, a1+a2): ``continuous_width_m``;
- the *fused width*: the candidate width (one of the library's grid widths) of the fusion of the last
  ``fusion_events`` windows' B vectors: ``fused_width_m``;
- the *fused continuous width*: the median of the same windows' continuous widths:
  ``fused_continuous_width_m``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from backlash_monitor.denoise import denoise_pairs
from backlash_monitor.classifier.patterns import load_library
from backlash_monitor.estimation import DEFAULT_FUSION_EVENTS, DriveEstimator
from backlash_monitor.windowing import default_window_offset, extract_windows
from backlash_monitor.windowing.a1_chain import A1ChainCheck


@dataclass
class WidthTrace:
    """Per onset window (in recording order) of one signal: the published widths [m]."""
    continuous_m: np.ndarray
    fused_m: np.ndarray
    fused_events: np.ndarray
    fused_continuous_m: np.ndarray


def monitor_widths(meas, library_path=None, signal: str = "a1+a2", mode: str = "shape",
                   fusion_events: int = DEFAULT_FUSION_EVENTS) -> WidthTrace:
    """What the monitor publishes for every onset window of the measurement with that library (a path, None for
    the packaged one, or a PatternLibrary object)."""
    offset = default_window_offset("contact_loss")
    lib = (library_path if hasattr(library_path, "shape_arrays") else
           load_library(library_path, trigger="contact_loss", window_offset_samples=offset))
    est = DriveEstimator(lib, mode=mode, fusion_events=fusion_events)
    wins = extract_windows({k: meas.signals[k] for k in ("a1", "a2", "angle_difference")}, trigger="contact_loss",
                           sample_period_s=meas.sample_period_s, window_offset_samples=offset)
    wins = [w for w in wins if w.kind == "onset"]
    if not wins:
        return WidthTrace(np.zeros(0), np.zeros(0), np.zeros(0, dtype=int), np.zeros(0))
    den = denoise_pairs([(w.signals["a1"], w.signals["a2"]) for w in wins])
    chain = a1_chain_of(meas)
    results = est.estimate_many([(a1, a2, "onset", None, w.sensor_offsets, chain) for w, (a1, a2) in zip(wins, den)])
    mine = [e for r in results for e in r if e.signal_name == signal]
    return WidthTrace(np.array([e.continuous_width_m for e in mine]), np.array([e.fused_width_m for e in mine]),
                      np.array([e.fused_events for e in mine], dtype=int),
                      np.array([e.fused_continuous_width_m for e in mine]))


def a1_chain_of(meas):
    """a1 checked against the measurement's motor speed over the whole record (windowing/a1_chain.py; ``analyze``
    checks as the samples come, so its windows before the first 2 s span are not checked); None without the motor
    speed."""
    if "omega1" not in meas.signals:
        return None
    check = A1ChainCheck()
    check.feed(0, meas.signals["a1"], meas.signals["omega1"], meas.sample_period_s)
    return check.result()


def continuous_widths(meas, library_path=None, signal: str = "a1+a2", mode: str = "shape") -> np.ndarray:
    """Continuous width [m] of every onset window of the measurement (shape mode, ``signal``)."""
    return monitor_widths(meas, library_path, signal, mode).continuous_m


def width_errors(trace: WidthTrace, truth_m: float, fusion_events: int = DEFAULT_FUSION_EVENTS) -> dict:
    """Errors [mm] of one drive against its true width:
    ``per_window_mean_abs_mm``  mean over the onset windows of |continuous width - truth| (one window's own);
    ``bias_mm``                 mean continuous width - truth;
    ``fused_final_abs_mm``      |last published fused width - truth| (the drive's answer at the end);
    ``fused_mean_abs_mm``       mean |fused width - truth| over the windows whose fusion is full;
    ``fused_continuous_mean_abs_mm``  mean |fused continuous width - truth| over those windows (what the
                                      monitor publishes as the drive's continuous width)."""
    c = np.asarray(trace.continuous_m, dtype=float)
    if c.size == 0:
        raise ValueError("the measurement has no onset window: no width to check")
    full = np.asarray(trace.fused_events) >= fusion_events
    fused = np.asarray(trace.fused_m, dtype=float)
    return {"per_window_mean_abs_mm": float(np.mean(np.abs(c - truth_m)) * 1e3),
            "bias_mm": float((np.mean(c) - truth_m) * 1e3),
            "per_window_std_mm": float(np.std(c) * 1e3),
            "fused_final_mm": float(fused[-1] * 1e3),
            "fused_final_abs_mm": float(abs(fused[-1] - truth_m) * 1e3),
            "fused_mean_abs_mm": float(np.mean(np.abs(fused[full] - truth_m)) * 1e3) if full.any() else None,
            "fused_continuous_mean_abs_mm": _mean_abs_mm(np.asarray(trace.fused_continuous_m, dtype=float)[full]
                                                         - truth_m) if full.any() else None,
            "onset_windows": int(c.size)}


def _mean_abs_mm(error_m: np.ndarray):
    """Mean |error| [mm] over the finite entries; None when there is none (a mode without continuous widths)."""
    e = error_m[np.isfinite(error_m)]
    return float(np.mean(np.abs(e)) * 1e3) if e.size else None
