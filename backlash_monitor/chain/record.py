"""Offline: the whole chain over one drive's record held in arrays (no bag, no DDS) -- the windows
and the estimates the live graph publishes for it.
"""
from __future__ import annotations

import numpy as np

from backlash_monitor.chain.joiner import JoinedRange
from backlash_monitor.chain.stage import WindowingStage
from backlash_monitor.denoise import denoise_pairs


def estimate_record(signals, sample_period_s: float, estimator, trigger: str = "contact_loss",
                    width_m: float | None = None, window_offset_samples: int | None = None,
                    first_sample_index: int = 0):
    """The chain over one drive's record held in arrays (no bag, no DDS): windowing (with its
    sensor offset estimate), denoising, ``estimator`` (a DriveEstimator; its fusion goes on from
    its state). ``signals``: 1-D arrays of one length, a1, a2 and angle_difference (measured
    angles) or omega1 and omega2 (integrated). Returns [(window, [WidthEstimate, ...])] for every
    window in stream order ([] for the ones not classified: returns, the first onset)."""
    angle = "measured" if "angle_difference" in signals else "integrated"
    stage = WindowingStage(trigger=trigger, width_m=width_m, angle_source=angle,
                           window_offset_samples=window_offset_samples)
    arrays = {name: np.ascontiguousarray(signals[name], dtype=np.float64)
              for name in stage.input_signals}
    windows, _ = stage.feed(JoinedRange(int(first_sample_index), float(sample_period_s), arrays))
    onsets = [w for w in windows if estimator.classifies(w.kind)]
    denoised = denoise_pairs([(w.signals["a1"], w.signals["a2"]) for w in onsets])
    results = estimator.estimate_many([(a1, a2, w.kind, w.sample_period_s, w.sensor_offsets)
                                       for w, (a1, a2) in zip(onsets, denoised)])
    by_window = {id(w): r for w, r in zip(onsets, results)}
    return [(w, by_window.get(id(w), [])) for w in windows]
