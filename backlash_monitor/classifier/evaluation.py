"""Identification figures over simulated windows (the core of ``evaluate`` and bench/identification.py).

Protocol: the library's patterns/models (trained on its own seeds) classify the onset windows of the
evaluation seeds (default 0-4, never training seeds) over the full grid. Paper modes use the patterns of
the window's n1 (the paper's protocol: n1 known, eta_k unknown); the shape mode ignores n1.
Fusion: per drive (one seed x scenario), the onset events in order, the mode's rule of fusion.py
(``default_fusion_rule``: trimmed normalised sum for shape, normalised sum for the paper modes) over the last
``window_events`` events; a fused estimate is counted once the buffer is full.
"""
from __future__ import annotations

import numpy as np

from ..plant import K2_WIDTHS_M
from .cpn import CPN_VARIANTS, CounterPropagationNetwork, b_margin, continuous_width_from_b
from .dataset import WindowSet
from .fusion import DEFAULT_WINDOW_EVENTS, default_fusion_rule, fused_indices
from .patterns import PatternLibrary
from .shape import SHAPE, SHAPE_SIGNALS, ShapeModel
from .training import pattern_means, pattern_windows, M3_N1

MODES = tuple(CPN_VARIANTS) + (SHAPE,)
EVAL_SIGNALS = {"paper": ("a1", "a2"), "paper_corrected": ("a1", "a2"), SHAPE: SHAPE_SIGNALS}
UNSEEN_WIDTHS_M = (0.003, 0.0045, 0.006, 0.0085)

# The paper's Tables 1 (a1) and 2 (a2): (signal, width, eta_k, n1, epochs, l1, l2, B as printed)
PAPER_TABLE_CASES = (
    ("a1", 0.009, 0.0125, 0.91, 30, 0.1, 0.09, (1.5895, 0.9248, 0.2620, 0.4710, 0.0025, 0.8902)),
    ("a1", 0.009, 0.0125, 0.91, 30, 0.1, 0.01, (0.0859, 0.0500, 0.0142, 0.0255, 0.0001, 0.0481)),
    ("a1", 0.0025, 0.05, 0.95, 30, 0.1, 0.09, (0.2949, 0.9600, 1.6225, 2.3551, 1.8860, 0.9922)),
    ("a1", 0.0025, 0.05, 0.95, 30, 0.9, 0.01, (0.0165, 0.0538, 0.0910, 0.1321, 0.1058, 0.0557)),
    ("a1", 0.005, 0.0375, 0.97, 20, 0.1, 0.09, (0.5442, 0.2718, 0.0003, 0.2998, 0.1076, 0.2585)),
    ("a1", 0.005, 0.0375, 0.97, 40, 0.1, 0.09, (3.18481, 0.5904, 0.0019, 1.7545, 0.6297, 1.5130)),
    ("a2", 0.009, 0.0125, 0.93, 30, 0.1, 0.09, (0.6245, 0.4992, 0.3698, 0.1376, 0.0002, 0.0868)),
    ("a2", 0.009, 0.0125, 0.93, 30, 0.1, 0.01, (0.0517, 0.0413, 0.0306, 0.0114, 1.5565e-5, 0.0072)),
    ("a2", 0.00375, 0.05, 0.89, 30, 0.1, 0.09, (0.1256, 0.0003, 0.1292, 0.3613, 0.4988, 0.5857)),
    ("a2", 0.00375, 0.05, 0.89, 30, 0.9, 0.01, (0.2931, 0.0006, 0.3016, 0.8434, 1.1643, 1.3672)),
    ("a2", 0.0025, 0.0375, 0.91, 20, 0.1, 0.09, (0.0001, 0.0761, 0.1550, 0.2963, 0.3800, 0.4330)),
    ("a2", 0.0025, 0.0375, 0.91, 40, 0.1, 0.09, (0.0003, 0.1799, 0.3663, 0.7003, 0.8980, 1.0231)),
)


def classify_windows(lib: PatternLibrary, ws: WindowSet, mode: str, signal: str):
    """(B (n, 6), continuous width (n,)) of every window of ``ws``."""
    widths = np.asarray(lib.widths_m, dtype=float)
    if mode == SHAPE:
        arrays = {f"shape/{k}": v for k, v in lib.shape_arrays().items()}
        model = ShapeModel.from_arrays(arrays, signal, widths)
        b, w = model.b(ws.a1, ws.a2)
        return b, w
    b = np.empty((len(ws), widths.size))
    n1 = ws.col("n1")
    x = ws.signal(signal)
    for v in np.unique(n1):
        sel = n1 == v
        b[sel] = lib.cpn(mode, signal, float(v)).b(x[sel])
    return b, continuous_width_from_b(b, widths)


def drive_keys(ws: WindowSet) -> np.ndarray:
    return ws.col("seed") * 100000 + ws.col("scenario")


def fused_correct(ws: WindowSet, b: np.ndarray, truth_index: np.ndarray,
                  window_events: int = DEFAULT_WINDOW_EVENTS, rule: str = "sum_normalised_b"):
    """(n correct fused estimates, n fused estimates, n drives wrong at least once)."""
    keys = drive_keys(ws)
    ok = n = bad = 0
    for k in np.unique(keys):
        s = np.flatnonzero(keys == k)
        s = s[np.argsort(ws.col("event")[s])]
        fi = fused_indices(b[s], window_events, rule)
        c = int((fi == truth_index[s[0]]).sum())
        ok += c
        n += fi.size
        bad += int(c < fi.size)
    return ok, n, bad


def confusion(truth: np.ndarray, pred: np.ndarray, k: int) -> np.ndarray:
    m = np.zeros((k, k), dtype=int)
    np.add.at(m, (truth, pred), 1)
    return m


def evaluate_mode(lib: PatternLibrary, ws: WindowSet, mode: str, signal: str,
                  window_events: int = DEFAULT_WINDOW_EVENTS) -> dict:
    widths = np.asarray(lib.widths_m, dtype=float)
    truth = np.array([int(np.argmin(np.abs(widths - w))) for w in ws.width_m])
    b, w = classify_windows(lib, ws, mode, signal)
    pred = np.argmin(b, axis=1)
    marg = b_margin(b)
    fin = np.isfinite(marg)
    ok, n, bad = fused_correct(ws, b, truth, window_events, default_fusion_rule(mode))
    return {
        "mode": mode, "signal": signal, "n_windows": int(len(ws)),
        "accuracy": float((pred == truth).mean()),
        "accuracy_per_width": [float((pred[truth == i] == i).mean()) for i in range(widths.size)],
        "confusion": confusion(truth, pred, widths.size).tolist(),
        "b_margin_median": float(np.median(marg[fin])) if fin.any() else float("inf"),
        "b_margin_p10": float(np.percentile(marg[fin], 10)) if fin.any() else float("inf"),
        "b_margin_median_correct": float(np.median(marg[fin & (pred == truth)])) if (fin & (pred == truth)).any() else None,
        "b_margin_median_wrong": float(np.median(marg[fin & (pred != truth)])) if (fin & (pred != truth)).any() else None,
        "fused_accuracy": ok / n if n else float("nan"), "fused_estimates": int(n), "fused_drives_wrong": int(bad),
        "continuous_abs_error_median_m": float(np.median(np.abs(w - ws.width_m))),
        "_b": b, "_pred": pred, "_truth": truth, "_w": w,
    }


def paper_miss_explanation(train: WindowSet, ws: WindowSet, result: dict, signal: str) -> dict:
    """How much of the paper mode's decision is the nearest pattern-window *mean* (the mean-only
    consequence), and how much the window means of neighbouring widths overlap over eta_k."""
    widths = np.asarray(K2_WIDTHS_M)
    m2 = ws.signal(signal).mean(axis=1)
    n1 = ws.col("n1")
    pred, truth = result["_pred"], result["_truth"]
    nn_mean = np.empty_like(pred)
    for v in np.unique(n1):
        sel = n1 == v
        pm = pattern_windows(train, signal, float(v), widths).mean(axis=1)
        nn_mean[sel] = np.argmin(np.abs(m2[sel, None] - pm[None, :]), axis=1)
    overlap = []
    for i in range(widths.size - 1):
        a, c = m2[truth == i], m2[truth == i + 1]
        lo, hi = max(a.min(), c.min()), min(a.max(), c.max())
        overlap.append(float(np.mean((a >= lo) & (a <= hi))) if hi > lo else 0.0)
    return {
        "decision_equals_nearest_pattern_mean": float((nn_mean == pred).mean()),
        "misses": int((pred != truth).sum()),
        "misses_explained_by_mean": int(((pred != truth) & (nn_mean == pred)).sum()),
        "window_mean_spread_within_over_between_widths": float(
            np.mean([m2[truth == i].std() for i in range(widths.size)]) /
            np.std([m2[truth == i].mean() for i in range(widths.size)])),
        "fraction_of_windows_inside_next_width_mean_range": overlap,
    }


def paper_table_rows(train: WindowSet, test: WindowSet, widths_m=K2_WIDTHS_M) -> list[dict]:
    """The paper's Tables 1-2 cases with the same width, eta_k, n1, epochs, l1, l2 (paper mode):
    patterns from the training windows, B of every evaluation window of the case."""
    rows = []
    widths = np.asarray(widths_m)
    for signal, width, eta, n1, epochs, l1, l2, paper_b in PAPER_TABLE_CASES:
        m3 = pattern_means(pattern_windows(train, signal, M3_N1, widths))
        net = CounterPropagationNetwork(m3, epochs=epochs, l1=l1, l2=l2)
        net.fit_patterns(pattern_windows(train, signal, n1, widths))
        sel = np.isclose(test.width_m, width) & np.isclose(test.col("eta_k"), eta) & np.isclose(test.col("n1"), n1)
        b = net.b(test.signal(signal)[sel])
        truth = int(np.argmin(np.abs(widths - width)))
        pb = np.asarray(paper_b)
        rows.append({
            "signal": signal, "width_m": width, "eta_k": eta, "n1": n1, "epochs": epochs, "l1": l1, "l2": l2,
            "paper_b": pb.tolist(), "paper_index": int(np.argmin(pb)), "true_index": truth,
            "ours_b_mean": b.mean(axis=0).tolist(), "ours_b_first_window": b[0].tolist(),
            "ours_index_of_mean_b": int(np.argmin(b.mean(axis=0))),
            "ours_accuracy": float((np.argmin(b, axis=1) == truth).mean()), "ours_windows": int(len(b)),
        })
    return rows


def continuous_error(lib: PatternLibrary, unseen: WindowSet, mode: str, signal: str) -> dict:
    _, w = classify_windows(lib, unseen, mode, signal)
    err = w - unseen.width_m
    per = {f"{x:g}": {"mean_estimate_m": float(w[np.isclose(unseen.width_m, x)].mean()),
                      "std_m": float(w[np.isclose(unseen.width_m, x)].std())}
           for x in np.unique(unseen.width_m)}
    return {"mae_m": float(np.mean(np.abs(err))), "rmse_m": float(np.sqrt(np.mean(err ** 2))),
            "median_abs_m": float(np.median(np.abs(err))), "bias_m": float(err.mean()), "per_width": per,
            "n_windows": int(len(w))}
