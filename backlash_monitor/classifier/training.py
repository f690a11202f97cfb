"""Building the pattern library from simulated windows (the core of ``python -m backlash_monitor train``).

Paper modes (eq. 13-14, 29): the pattern window of (n1, width) -- a row of M2 -- is the mean of the
denoised onset windows at eta_k = 0.025 of that n1 and width over the training seeds' events (one
simulated window per width, as the paper had, would put one event's ~1 ms traversal jitter into the
patterns). M3 = the row means of M2 for n1 = 0.89 (eq. 14 as written, for every n1); W5(n1) = W4 of
each width's pattern window processed from that M3 (eq. 29).

Shape mode: one ridge regression per signal (a1, a2, a1+a2) on every training window of the whole
grid (all eta_k and n1; n1 is not an input), see shape.py.
"""
from __future__ import annotations

import datetime as _dt

import numpy as np

from ..plant import ETA_K_VALUES, K2_WIDTHS_M, N1_VALUES, PATTERN_ETA_K
from .cpn import CPN_VARIANTS, DEFAULT_EPOCHS, DEFAULT_L1, DEFAULT_L2, CounterPropagationNetwork, pattern_means
from .dataset import DEFAULT_DURATION_S, WindowSet, collect_windows
from .patterns import SIGNALS, PatternLibrary
from .training_defaults import DEFAULT_TRAIN_SEEDS
from .shape import (A1_JUMP, A1_OFFSETS, A2_DROP, A2_OFFSETS, DEFAULT_RIDGE, SHAPE, SHAPE_SIGNALS, ShapeModel)

M3_N1 = 0.89                                      # eq. 14: M3 from the n1 = 0.89 group


class NoTrainingWindows(ValueError):
    """A condition of the training grid at which the simulated drive gave no onset window in any seed (a model whose
    effects stop it crossing its backlash there)."""

    def __init__(self, width_m: float, eta_k: float, n1: float):
        super().__init__(f"no training windows for width {width_m} m, eta_k {eta_k}, n1 {n1}")
        self.width_m, self.eta_k, self.n1 = width_m, eta_k, n1


def pattern_windows(ws: WindowSet, signal: str, n1: float, widths_m=K2_WIDTHS_M,
                    eta_k: float = PATTERN_ETA_K) -> np.ndarray:
    """M2 for one n1: (6, L), row i = mean of the denoised onset windows of width i at eta_k, n1."""
    x = ws.signal(signal)
    rows = []
    for w in widths_m:
        sel = (np.isclose(ws.width_m, w)) & np.isclose(ws.col("eta_k"), eta_k) & np.isclose(ws.col("n1"), n1)
        if not sel.any():
            raise NoTrainingWindows(w, eta_k, n1)
        rows.append(x[sel].mean(axis=0))
    return np.array(rows)


def paper_networks(ws: WindowSet, variant: str, signal: str, *, epochs: int = DEFAULT_EPOCHS,
                   l1: float = DEFAULT_L1, l2: float = DEFAULT_L2, n1_values=N1_VALUES,
                   widths_m=K2_WIDTHS_M) -> tuple[np.ndarray, np.ndarray]:
    """(m3 (n_n1, 6), w5 (n_n1, 6, 6)) of one variant and signal."""
    m3 = pattern_means(pattern_windows(ws, signal, M3_N1, widths_m))
    m3s, w5s = [], []
    for n1 in n1_values:
        net = CounterPropagationNetwork(m3, variant=variant, epochs=epochs, l1=l1, l2=l2)
        w5s.append(net.fit_patterns(pattern_windows(ws, signal, n1, widths_m)))
        m3s.append(m3)
    return np.array(m3s), np.array(w5s)


def _collect(seeds, trigger, duration_s, progress, window_offset, config) -> WindowSet:
    configs = list(config) if isinstance(config, (list, tuple)) else [config]
    if len(configs) == 1:
        return collect_windows(seeds, trigger, duration_s=duration_s, progress=progress,
                               window_offset=window_offset, config=configs[0])
    seeds = [int(s) for s in seeds]
    if len(seeds) < len(configs):
        raise ValueError(f"{len(configs)} plant configs need at least {len(configs)} training seeds "
                         f"(one per config at least), got {len(seeds)}")
    parts = [collect_windows(seeds[k::len(configs)], trigger, duration_s=duration_s, progress=progress,
                             window_offset=window_offset, config=c) for k, c in enumerate(configs)]
    ws = WindowSet.concat(parts)
    ws.info = dict(parts[0].info, seeds=seeds,
                   plant_config_hash="+".join(str(p.info.get("plant_config_hash")) for p in parts),
                   seeds_per_config=[p.info.get("seeds") for p in parts])
    return ws


def build_library(trigger: str = "contact_loss", seeds=DEFAULT_TRAIN_SEEDS, *, epochs: int = DEFAULT_EPOCHS,
                  l1: float = DEFAULT_L1, l2: float = DEFAULT_L2, ridge: float = DEFAULT_RIDGE,
                  duration_s: float = DEFAULT_DURATION_S, windows: WindowSet | None = None,
                  progress=None, window_offset: int | None = None, config=None) -> PatternLibrary:
    """Simulate (or take ``windows``), then fit every mode. ``progress(n)`` is called per seed simulated.
    ``config``: the plant config of the training drives (default: config/plant.yaml; the workbench passes a
    model version's config, ``train --model``), or a list of configs: the training seeds are dealt out
    round-robin (seed k -> config k mod n) and the windows pooled -- for a drive whose diagnosis names
    physically indistinguishable effects, train on every candidate model (docs/workbench.md)."""
    ws = windows if windows is not None else _collect(seeds, trigger, duration_s, progress, window_offset, config)
    widths = np.asarray(K2_WIDTHS_M, dtype=float)
    arrays = {}
    for variant in CPN_VARIANTS:
        for signal in SIGNALS:
            m3, w5 = paper_networks(ws, variant, signal, epochs=epochs, l1=l1, l2=l2)
            arrays[f"{variant}/{signal}/m3"] = m3
            arrays[f"{variant}/{signal}/w5"] = w5
    shape_fit = {}
    for signal in SHAPE_SIGNALS:
        model = ShapeModel.fit(signal, widths, ws.width_m, ws.a1, ws.a2, ws.sample_period_s, ridge=ridge)
        arrays.update(model.to_arrays())
        shape_fit[signal] = {"training_residual_std_m": model.sigma_m, "n_features": int(model.mu.size)}
    info = ws.info
    settings = {"trigger": trigger, "epochs": int(epochs), "l1": float(l1), "l2": float(l2),
                "denoising": info.get("denoising"), "window_length": int(ws.a1.shape[1]),
                "window_offset_samples": info.get("window_offset_samples"),
                "sample_period_s": float(ws.sample_period_s), "plant_config_hash": info.get("plant_config_hash"),
                "sensor_offset": info.get("sensor_offset")}
    training = {
        "seeds": info.get("seeds"), "duration_s": info.get("duration_s"), "widths_m": info.get("widths_m"),
        "eta_k_values": info.get("eta_k_values", list(ETA_K_VALUES)), "n1_values": info.get("n1_values"),
        "n_onset_windows": int(len(ws)), "code_hash": info.get("code_hash"),
        "paper_patterns": f"M2 row = mean of the denoised onset windows at eta_k = {PATTERN_ETA_K} of that n1 and "
                          f"width over the training seeds; M3 from n1 = {M3_N1} (eq. 14) for every n1; "
                          "W5 = W4 of each pattern window (eq. 29)",
        "shape": {"model": "ridge regression of the width on quadratic shape features, nearest candidate; "
                           "B(i) = ((w_hat - K2(i)) / sigma)^2",
                  "data": "every training onset window of the grid (all eta_k and n1)", "ridge": float(ridge),
                  "a1_jump_m_s2": A1_JUMP, "a2_drop_m_s2": A2_DROP, "a1_offsets": list(A1_OFFSETS),
                  "a2_offsets": list(A2_OFFSETS), "fit": shape_fit},
    }
    if info.get("seeds_per_config"):
        training["seeds_per_config"] = info["seeds_per_config"]    # several plant configs pooled
    return PatternLibrary(settings=settings, widths_m=widths, n1_values=np.asarray(N1_VALUES, dtype=float),
                          arrays=arrays, training=training, shape_meta={"mode": SHAPE},
                          created_utc=_dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"))
