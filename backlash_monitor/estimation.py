"""One drive's width estimation from denoised windows: the core behind the classifier node and
``python -m backlash_monitor analyze`` (no rclpy), so that live and offline estimates are identical.

    library = load_library()                                   # backlash_monitor/data/patterns.npz
    estimator = DriveEstimator(library, mode="shape", n1=0.89)
    for estimate in estimator.estimate(a1, a2, entry_kind="onset"):   # one per signal
        estimate.width_m, estimate.b_vector, estimate.fused_width_m, ...

Only onset windows are classified (SPEC section 3: the return entries' windows follow another
transient); a return window gives no estimate. Each signal keeps its own fusion of the last
``fusion_events`` onset events (backlash_monitor.classifier.fusion).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from backlash_monitor.classifier.cpn import CPN_VARIANTS, b_margin
from backlash_monitor.classifier.fusion import WidthFusion
from backlash_monitor.classifier.patterns import PatternLibrary
from backlash_monitor.classifier.shape import SHAPE, SHAPE_SIGNALS, ShapeModel

MODES = tuple(CPN_VARIANTS) + (SHAPE,)
DEFAULT_MODE = SHAPE
DEFAULT_FUSION_EVENTS = 8


@dataclass
class WidthEstimate:
    signal_name: str
    mode: str
    candidate_widths_m: np.ndarray
    b_vector: np.ndarray
    width_index: int
    width_m: float
    b_margin: float
    continuous_width_m: float
    fused_width_m: float
    fused_events: int


def default_signals(mode: str) -> tuple[str, ...]:
    return ("a1", "a2", "a1+a2") if mode == SHAPE else ("a1", "a2")


class DriveEstimator:
    """Classifies one drive's denoised onset windows in ``mode`` for each of ``signals``."""

    def __init__(self, library: PatternLibrary, mode: str = DEFAULT_MODE, n1: float = 0.89,
                 signals: tuple[str, ...] | None = None,
                 fusion_events: int = DEFAULT_FUSION_EVENTS):
        if mode not in MODES:
            raise ValueError(f"mode {mode!r} is unknown; allowed: {', '.join(MODES)}")
        if mode not in library.modes:
            raise ValueError(f"mode {mode!r} has no patterns in {library.path}; the library has: "
                             f"{', '.join(library.modes)}")
        self.mode = mode
        self.signals = tuple(signals) if signals else default_signals(mode)
        allowed = SHAPE_SIGNALS if mode == SHAPE else ("a1", "a2")
        for signal in self.signals:
            if signal not in allowed:
                raise ValueError(f"signal {signal!r} is not allowed in mode {mode}; allowed: "
                                 f"{', '.join(allowed)}")
        self.widths_m = np.asarray(library.widths_m, dtype=float)
        if mode == SHAPE:
            arrays = {f"shape/{k}": v for k, v in library.shape_arrays().items()}
            self.models = {s: ShapeModel.from_arrays(arrays, s, self.widths_m) for s in self.signals}
        else:
            self.models = {s: library.cpn(mode, s, n1) for s in self.signals}
        self.fusion = {s: WidthFusion(self.widths_m, window_events=fusion_events)
                       for s in self.signals}

    def reset(self) -> None:
        """Forget the fused history (a new drive, or the drive was repaired)."""
        for fusion in self.fusion.values():
            fusion.reset()

    def _b(self, signal: str, a1: np.ndarray, a2: np.ndarray) -> tuple[np.ndarray, float]:
        model = self.models[signal]
        if self.mode == SHAPE:
            b, w = model.b(a1=a1[None, :], a2=a2[None, :])
            return b[0], float(w[0])
        return model.b({"a1": a1, "a2": a2}[signal]), math.nan

    def estimate(self, a1, a2, entry_kind: str = "onset") -> list[WidthEstimate]:
        """Estimates of one denoised window (a1, a2: equal-length float arrays); [] for non-onsets."""
        if entry_kind != "onset":
            return []
        a1 = np.asarray(a1, dtype=float)
        a2 = np.asarray(a2, dtype=float)
        out = []
        for signal in self.signals:
            b, continuous = self._b(signal, a1, a2)
            index = int(np.argmin(b))
            fused = self.fusion[signal].add(b, kind="onset")
            out.append(WidthEstimate(
                signal_name=signal, mode=self.mode, candidate_widths_m=self.widths_m,
                b_vector=np.asarray(b, dtype=float), width_index=index,
                width_m=float(self.widths_m[index]), b_margin=float(b_margin(b)),
                continuous_width_m=continuous, fused_width_m=fused.width_m,
                fused_events=fused.events))
        return out
