"""The improved ``shape`` mode: a physics-guided regression of the backlash width from the window's shape.

Why (docs/classifier.md has the numbers): the far-side impact time T alone varies by ~1 ms from event
to event because the disturbances act on the motor's load moment, while adjacent widths' impacts are
only ~2 ms apart. During the gap traversal the relative rim displacement is

    2 b ~= v0 T + double integral of the relative acceleration over [0, T]
         ~= T (v0 + v_impact) / 2,

and the window shows both factors: T (a1's jump / a2's kink), the double integral of a1 (the motor's
actual deceleration, disturbance included) and the impact strength (a1's jump height, the depth of
a2's drop after the impact, which grows with v_impact). A ridge regression on these few features and
their pairwise products gives a continuous width estimate ``w_hat``; the B-like distance vector is

    B(i) = ((w_hat - K2(i)) / sigma)^2          (sigma: the training residual std)

so the identified width is the nearest candidate, the margin and fusion work as for the paper mode,
and ``w_hat`` is the continuous width.

Signals: ``a1`` (a1's features only), ``a2`` (a2's only), ``a1+a2`` (both). One model per signal and
trigger, trained on noisy windows of every eta_k and n1 of the grid (n1 is not needed at run time).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

CONTINUOUS_TOP_FACTOR = 2.0   # w_hat is clipped to [0, 2 x the widest pattern width] (20 mm for the paper's 10 mm): a
                              # regression beyond its training range is extrapolation, and a window whose features
                              # are far off (another mechanism, a broken sensor) must not read as any width at all


def continuous_top_m(widths_m) -> float:
    """The top [m] of the continuous width's range: CONTINUOUS_TOP_FACTOR x the widest pattern width. A window
    clipped there says only that the width is at least this (fusion.fused_width_uncertainty_m)."""
    return CONTINUOUS_TOP_FACTOR * float(np.max(np.asarray(widths_m, dtype=float)))

SHAPE = "shape"
SHAPE_SIGNALS = ("a1", "a2", "a1+a2")

# Feature-extraction constants (samples at 50 kHz; documented in docs/classifier.md)
BASE_A1 = (0, 500)          # a1's pre-impact level: median over the first 10 ms
A1_JUMP = 40.0              # a1 impact: first sample 40 m/s^2 above that level (after SEARCH_FROM)
BASE_A2 = (0, 200)          # a2's pre-impact line: least squares over the first 4 ms
A2_DROP = 0.1               # a2 impact: first sample 0.1 m/s^2 below that line
SEARCH_FROM = 100
EDGE = 40                   # a2's kink is not searched in the last 40 samples (denoising edge)
A1_OFFSETS = (25, 50, 100, 150, 200)           # a1 - level at T + offset (impact strength)
A2_OFFSETS = (-50, 0, 50, 100, 150, 200, 300, 400)   # a2 - line at T + offset (depth of the drop)
A2_SCALE_OFFSET = 200       # the drop depth at T + 4 ms normalises a2's profile (scale-free form)
A2_LOG_FLOOR = 1e-3         # m/s^2 (or /s^3): floor under the logarithms of a2's levels


def _first_crossing(x: np.ndarray, thr: float, start: int) -> np.ndarray:
    """Fractional index of the first sample >= thr at or after ``start`` (len-1 when none)."""
    n = x.shape[-1]
    above = x[:, start:] >= thr
    ok = above.any(axis=1)
    idx = np.argmax(above, axis=1) + start
    i0 = np.maximum(idx - 1, 0)
    x0 = np.take_along_axis(x, i0[:, None], 1)[:, 0]
    x1 = np.take_along_axis(x, idx[:, None], 1)[:, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.clip(np.where(x1 != x0, (thr - x0) / (x1 - x0), 1.0), 0.0, 1.0)
    return np.where(ok, i0 + frac, float(n - 1))


def _at(x: np.ndarray, pos: np.ndarray) -> np.ndarray:
    """Linear interpolation of each row of x at fractional positions pos (n, k), clipped to the window."""
    n = x.shape[-1]
    pos = np.clip(pos, 0.0, n - 1.000001)
    i = np.floor(pos).astype(int)
    f = pos - i
    return np.take_along_axis(x, i, 1) * (1 - f) + np.take_along_axis(x, i + 1, 1) * f


def _integrals(x: np.ndarray, t_imp: np.ndarray, dt: float):
    """Single and double integral of each row from 0 to its impact index (fractional)."""
    k = np.arange(x.shape[-1])[None, :]
    w1 = np.clip(t_imp[:, None] - k, 0.0, 1.0)             # sample weights of [0, T)
    w2 = np.clip(t_imp[:, None] - k, 0.0, None)            # (T - k) for k < T
    return (w1 * x).sum(1) * dt, (w2 * x).sum(1) * dt * dt


def a1_features(a1: np.ndarray, dt: float) -> np.ndarray:
    """(n, L) denoised a1 -> (n, 8): T [s], v-change and displacement to T, jump profile, level."""
    a1 = np.atleast_2d(np.asarray(a1, dtype=float))
    level = np.median(a1[:, BASE_A1[0]:BASE_A1[1]], axis=1)
    x = a1 - level[:, None]
    t = _first_crossing(x, A1_JUMP, SEARCH_FROM)
    s1, i1 = _integrals(a1, t, dt)
    prof = _at(x, t[:, None] + np.array(A1_OFFSETS)[None, :])
    return np.column_stack([t * dt, s1, i1, prof, level])


def a2_features(a2: np.ndarray, dt: float) -> np.ndarray:
    """(n, L) denoised a2 -> (n, 26): T [s], integrals, drop profile, pre-impact line (level, slope),
    kink sharpness, log(drop depth, |level|, sharpness, |slope|), drop profile / drop depth.

    The impact is a2's sharpest downward kink: the most negative second difference after SEARCH_FROM
    and before the last EDGE samples (the zone entry's kink is far weaker; with the contact-loss
    trigger it lies inside the window). The pre-impact line is fitted over [T - 150, T - 50].
    """
    a2 = np.atleast_2d(np.asarray(a2, dtype=float))
    n_s = a2.shape[1]
    d2 = np.full(a2.shape, np.inf)
    d2[:, 1:-1] = a2[:, 2:] - 2 * a2[:, 1:-1] + a2[:, :-2]
    d2[:, :SEARCH_FROM] = np.inf
    d2[:, n_s - EDGE:] = np.inf
    kink = np.argmin(d2, axis=1).astype(float)
    strength = -np.min(d2, axis=1) / dt ** 2 * 1e-6       # kink sharpness [m/s^4 * 1e-6]
    lo = np.clip(kink - 150, 0, None).astype(int)
    k = lo[:, None] + np.arange(100)[None, :]
    seg = np.take_along_axis(a2, k, 1)
    kc = np.arange(100) - 49.5
    slope = (seg * kc).sum(1) / (kc * kc).sum()
    level = seg.mean(1) - slope * (lo + 49.5)          # the line's value at sample 0
    line = level[:, None] + slope[:, None] * np.arange(n_s)[None, :]
    x = a2 - line
    t = _first_crossing(-x, A2_DROP, SEARCH_FROM)
    t = np.where(t < kink - 100, kink, t)
    s2, i2 = _integrals(a2, t, dt)
    prof = _at(x, t[:, None] + np.array(A2_OFFSETS)[None, :])
    # Scale-free part: the absorber (c = eta_k S1 / h^n1, ~12x over the grid) scales a2's level, slope
    # and drop depth; the drop's *form* (profile / its depth at T + 4 ms) and the logarithms of the
    # levels (a multiplicative c becomes an additive term the regression can cancel) carry v_impact
    # with far less eta_k/n1 bias at 9-10 mm (docs/classifier.md).
    depth = np.abs(prof[:, A2_OFFSETS.index(A2_SCALE_OFFSET)]) + A2_LOG_FLOOR
    logs = np.log(np.column_stack([depth, np.abs(level) + A2_LOG_FLOOR, strength + 1e-6,
                                   np.abs(slope / dt) + A2_LOG_FLOOR]))
    return np.column_stack([t * dt, s2, i2, prof, level, slope / dt, strength, logs, prof / depth[:, None]])


def window_features(signal: str, a1=None, a2=None, dt: float = 2e-5) -> np.ndarray:
    if signal not in SHAPE_SIGNALS:
        raise ValueError(f"unknown signal {signal!r} for the shape mode; allowed: {', '.join(SHAPE_SIGNALS)}")
    parts = []
    if signal in ("a1", "a1+a2"):
        if a1 is None:
            raise ValueError(f"the shape mode on {signal} needs the a1 window")
        parts.append(a1_features(a1, dt))
    if signal in ("a2", "a1+a2"):
        if a2 is None:
            raise ValueError(f"the shape mode on {signal} needs the a2 window")
        parts.append(a2_features(a2, dt))
    return np.column_stack(parts)


DEFAULT_RIDGE = 1e-5   # ridge penalty per training window on the standardised expanded features
Z_CLIP = 8.0   # standardised features are clipped to +-8 (a window unlike any training window)


def _expand(z: np.ndarray) -> np.ndarray:
    """Standardised features (clipped to +-Z_CLIP) -> [z, z_i z_j (i <= j)]."""
    z = np.clip(z, -Z_CLIP, Z_CLIP)
    iu = np.triu_indices(z.shape[1])
    return np.column_stack([z, (z[:, :, None] * z[:, None, :])[:, iu[0], iu[1]]])


@dataclass
class ShapeModel:
    """Ridge regression of the width on quadratic shape features of one signal ("a1", "a2", "a1+a2")."""
    signal: str
    widths_m: np.ndarray
    mu: np.ndarray          # feature means
    sd: np.ndarray          # feature stds
    coef: np.ndarray        # regression coefficients of the expanded features
    intercept: float
    sigma_m: float          # training residual std [m]
    sample_period_s: float
    ridge: float = 1e-5

    @classmethod
    def fit(cls, signal: str, widths_m, y_m, a1=None, a2=None, sample_period_s: float = 2e-5,
            ridge: float = DEFAULT_RIDGE) -> "ShapeModel":
        f = window_features(signal, a1, a2, sample_period_s)
        mu, sd = f.mean(0), f.std(0)
        sd[sd == 0] = 1.0
        z = _expand((f - mu) / sd)
        y = np.asarray(y_m, dtype=float)
        zm = z.mean(0)
        zc = z - zm
        coef = np.linalg.solve(zc.T @ zc + ridge * len(y) * np.eye(z.shape[1]), zc.T @ (y - y.mean()))
        intercept = float(y.mean() - zm @ coef)
        resid = z @ coef + intercept - y
        return cls(signal, np.asarray(widths_m, dtype=float), mu, sd, coef, intercept,
                   float(np.std(resid)), float(sample_period_s), float(ridge))

    def continuous_width(self, a1=None, a2=None) -> np.ndarray:
        f = window_features(self.signal, a1, a2, self.sample_period_s)
        w = _expand((f - self.mu) / self.sd) @ self.coef + self.intercept
        return np.clip(w, 0.0, continuous_top_m(self.widths_m))

    def b(self, a1=None, a2=None) -> tuple[np.ndarray, np.ndarray]:
        """(B (n, 6), continuous width (n,)) for windows (n, L) (or one window (L,): B (1, 6))."""
        w = self.continuous_width(a1, a2)
        return ((w[:, None] - self.widths_m[None, :]) / self.sigma_m) ** 2, w

    # -------- storage in the pattern library (arrays under shape/<signal>/...)
    def to_arrays(self) -> dict:
        p = f"shape/{self.signal}/"
        return {p + "mu": self.mu, p + "sd": self.sd, p + "coef": self.coef,
                p + "scalars": np.array([self.intercept, self.sigma_m, self.sample_period_s, self.ridge])}

    @classmethod
    def from_arrays(cls, arrays: dict, signal: str, widths_m) -> "ShapeModel":
        p = f"shape/{signal}/"
        if p + "coef" not in arrays:
            raise KeyError(f"no shape model for {signal}")
        intercept, sigma, dt, ridge = arrays[p + "scalars"]
        return cls(signal, np.asarray(widths_m, dtype=float), arrays[p + "mu"], arrays[p + "sd"],
                   arrays[p + "coef"], float(intercept), float(sigma), float(dt), float(ridge))
