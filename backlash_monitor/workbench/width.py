"""The monitor's width estimate on a measurement with a given pattern library (the chain's own stages:
contact_loss windows at the library's window offset, sym5 denoising, DriveEstimator), for the
before/after check of a model update (`train --model M2 --out LIB.npz`)."""
from __future__ import annotations

import numpy as np

from backlash_monitor.chain import denoise_pairs
from backlash_monitor.classifier.patterns import load_library
from backlash_monitor.estimation import DriveEstimator
from backlash_monitor.windowing import default_window_offset, extract_windows


def continuous_widths(meas, library_path=None, signal: str = "a1+a2", mode: str = "shape") -> np.ndarray:
    """Continuous width [m] of every onset window of the measurement (shape mode, ``signal``)."""
    offset = default_window_offset("contact_loss")
    lib = load_library(library_path, trigger="contact_loss", window_offset_samples=offset)
    est = DriveEstimator(lib, mode=mode)
    wins = extract_windows({k: meas.signals[k] for k in ("a1", "a2", "angle_difference")}, trigger="contact_loss",
                           sample_period_s=meas.sample_period_s, window_offset_samples=offset)
    wins = [w for w in wins if w.kind == "onset"]
    if not wins:
        return np.zeros(0)
    den = denoise_pairs([(w.signals["a1"], w.signals["a2"]) for w in wins])
    results = est.estimate_many([(a1, a2, "onset") for a1, a2 in den])
    return np.array([e.continuous_width_m for r in results for e in r if e.signal_name == signal])
