"""Backlash-entry detection and window capture (SPEC section 2 ``windowing``), pure numpy/scipy.

    from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture, BacklashWindower, extract_windows

    det = BacklashEntryDetector(trigger="contact_loss")            # or trigger="paper", width_m=0.005
    cap = WindowCapture(window_length=2048, signals=("a1", "a2"))
    for chunk in stream:                                           # 1-D arrays of one drive
        sig = {"a1": ..., "a2": ..., "angle_difference": ...}      # or "omega1"/"omega2" (integrated)
        windows, discarded = cap.feed(chunk.first_sample_index, sig,
                                      entries=det.feed(chunk.first_sample_index, sig, chunk.sample_period_s),
                                      sample_period_s=chunk.sample_period_s)
    # same in one object:  BacklashWindower(trigger=..., width_m=...).feed(first_index, sig, sample_period_s)
    # offline:             extract_windows(sig, trigger=..., width_m=...) -> list[BacklashWindow]
    #                      extract_windows_batch(sig_2d, width_m=per_row_or_scalar, ...) -> list[list[...]]

Signatures
----------
BacklashEntryDetector(trigger="contact_loss"|"paper", width_m=None|float [m], radius_m=0.15,
    sample_period_s=2e-5, holdoff_samples=2048, angle_source="auto"|"measured"|"integrated",
    integration="trapezoid"|"rectangle", confirm_rad=0.015, reference_tau_s=0.02, settle_samples=100,
    settle_range_rad=1.5e-3, fit_samples=2048, contact_deflection_rad=1.5e-3, initial_contact_side=1,
    rereference_interval_s=0.05);  .feed(first_sample_index, signals, sample_period_s=None) -> [BacklashEntry]
    BacklashEntryDetector.from_config(load_windowing_config()["detector"], **overrides)
BacklashEntry(sample_index, kind "onset"|"return", trigger, confirm_sample_index)
WindowCapture(window_length=2048, signals=("a1","a2"), history_samples=4096, sample_period_s=2e-5,
    window_offset_samples=0)   # window = window_length samples from entry + offset
    default_window_offset(trigger) -> the configured offset (capture.window_offset_samples)
    .feed(first_sample_index, signals, entries=(), sample_period_s=None) -> (windows, discarded); .flush()
BacklashWindow(entry_sample_index, kind, trigger, sample_period_s, signals: dict[str, ndarray], confirm_sample_index)
DiscardedWindow(entry_sample_index, reason in DISCARD_REASONS, kind)

Triggers (docs/windowing.md has the physics and the measured offsets):
- ``paper``: eq. 1, |Delta| < K2/r with Delta = alpha1 - alpha2 measured, or integrated from the speeds
  (eq. 2-3, trapezoid rule by default).  Integrated angles are re-referenced at each settled contact
  to +-(K2/r + contact_deflection_rad), so a speed bias cannot move or lose entries.
- ``contact_loss``: no width.  A causal EMA (reference_tau_s) tracks the contact value of Delta; a
  departure beyond confirm_rad confirms a traverse; a change-point fit (ramp, then an added parabola)
  over the last fit_samples samples finds the departure, and the entry is back-dated to the first
  point after it where Delta is contact_deflection_rad (r*F0/k_c: torque zero) off the contact level
  (mean of the 200 samples before the departure), interpolated to the nearest sample.
  Direction down = onset, up = return.  Drift-immune because it uses only the local departure.
- Both: no new entry before entry + holdoff_samples, and only after the contact has settled again
  (range of Delta over settle_samples <= settle_range_rad), so a bouncing contact cannot re-trigger.
"""
from .config import (DEFAULTS, DEFAULT_CONFIG_PATH, KIND_ONSET, KIND_RETURN, TRIGGERS, default_window_offset,
                     load_windowing_config)
from .detector import BacklashEntry, BacklashEntryDetector, fit_departure, integrate_relative_speed
from .capture import (DISCARD_REASONS, BacklashWindow, BacklashWindower, DiscardedWindow, WindowCapture,
                      extract_windows, extract_windows_batch)

__all__ = ["DEFAULTS", "DEFAULT_CONFIG_PATH", "KIND_ONSET", "KIND_RETURN", "TRIGGERS", "load_windowing_config", "default_window_offset",
           "BacklashEntry", "BacklashEntryDetector", "fit_departure", "integrate_relative_speed",
           "DISCARD_REASONS", "BacklashWindow", "BacklashWindower", "DiscardedWindow", "WindowCapture",
           "extract_windows", "extract_windows_batch"]
