"""Counter-propagation network of the paper (section 4, eq. 9-33), no rclpy.

Two variants, both named and measured (SPEC section 4):

``paper``
    The equations exactly as written: eq. 12 divides the window by the *sum of squares* (not by the
    norm eq. 11 asks for) and eq. 23 moves the Grossberg weights *away* from the target Z1
    (``W2 += l2 (Y2 - Z1) X2``).
``paper_corrected``
    Unit-norm input (eq. 11: ``X1 = x / ||x||``) and the textbook outstar sign
    (``W2 += l2 (Z1 - Y2) X2``). Everything else identical.

For every tested window the network starts afresh from the pattern weights (W1 from M3, W2 = m1) and
is processed for ``epochs`` epochs on that one window; W4 (eq. 28) is the result. Patterns W5 are
the W4 of the six pattern windows (eta_k = 0.025, same n1); B(i) = sum_j |W6(j) - W5(i, j)| (eq. 31).

Consequence measured in ``docs/classifier.md`` and proved in ``test/classifier/test_classifier_mean_only.py``:
every E1(i) is a function of (m2, M3) times the common factor 1/sum(x^2) (paper) resp. of
(m2 / rms, M3) (corrected), so the winner sequence, and with it W2, W4 and B, depend on the window
only through its mean m2 (paper) -- ``paper_w4_from_mean`` computes them from m2 alone.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PAPER = "paper"
PAPER_CORRECTED = "paper_corrected"
CPN_VARIANTS = (PAPER, PAPER_CORRECTED)

DEFAULT_EPOCHS = 30
DEFAULT_L1 = 0.1
DEFAULT_L2 = 0.09

_CHUNK = 256  # windows processed together in process_batch (memory: chunk x 6 x 2048 x 8 B)


def check_variant(variant: str) -> str:
    if variant not in CPN_VARIANTS:
        raise ValueError(f"unknown counter-propagation variant {variant!r}; allowed: {', '.join(CPN_VARIANTS)}")
    return variant


# ---------------------------------------------------------------- the equations, one function each
def normalise_input(x: np.ndarray, variant: str = PAPER) -> np.ndarray:
    """Eq. 11-12 on the last axis. ``paper``: x / sum(x^2) (eq. 12 as printed); corrected: x / ||x||."""
    x = np.asarray(x, dtype=float)
    ss = np.sum(x * x, axis=-1, keepdims=True)
    if np.any(ss == 0.0):
        raise ValueError("cannot normalise an all-zero window (eq. 12 divides by its sum of squares)")
    if check_variant(variant) == PAPER:
        return x / ss
    return x / np.sqrt(ss)


def pattern_means(m2: np.ndarray) -> np.ndarray:
    """Eq. 14: M3(i) = mean of row i of M2 (M2: 6 pattern windows x samples)."""
    return np.asarray(m2, dtype=float).mean(axis=-1)


def initial_w1(m3: np.ndarray, n_inputs: int) -> np.ndarray:
    """Eq. 13: W1(i, j) = M3(i), shape (len(M3), n_inputs)."""
    m3 = np.asarray(m3, dtype=float)
    return np.repeat(m3[:, None], n_inputs, axis=1)


def initial_w2(m3: np.ndarray) -> np.ndarray:
    """Eq. 20-21: W2(i, j) = m1 = mean(M3), shape (len(M3), len(M3))."""
    m3 = np.asarray(m3, dtype=float)
    return np.full((m3.size, m3.size), m3.mean())


def kohonen_step(w1: np.ndarray, x1: np.ndarray, l1: float, inplace: bool = False) -> tuple[np.ndarray, np.ndarray, int | np.ndarray]:
    """Eq. 15-18 (batched on leading axes): E1 = W1 X1, t = argmax E1, Y1 = one-hot(t),
    W1(t, :) += l1 (X1 - W1(t, :)). Returns (new W1, Y1, t). Ties go to the first (lowest) index.
    ``inplace``: update w1 itself (the batch loop) instead of a copy."""
    e1 = np.einsum("...ij,...j->...i", w1, x1)
    t = np.argmax(e1, axis=-1)
    y1 = np.zeros(e1.shape)
    np.put_along_axis(y1, np.asarray(t)[..., None], 1.0, axis=-1)
    if not inplace:
        w1 = w1.copy()
    ti = np.asarray(t)[..., None, None]
    row = np.take_along_axis(w1, ti, axis=-2)                  # only the winner's row changes (eq. 18)
    np.put_along_axis(w1, ti, row + l1 * (x1[..., None, :] - row), axis=-2)
    return w1, y1, t


def grossberg_step(w2: np.ndarray, x2: np.ndarray, z1: np.ndarray, l2: float, variant: str = PAPER) -> np.ndarray:
    """Eq. 22-23 (batched): Y2 = W2 X2; ``paper``: W2(i, j) += l2 (Y2(i) - Z1(i)) X2(j);
    corrected (textbook outstar): W2(i, j) += l2 (Z1(i) - Y2(i)) X2(j)."""
    y2 = np.einsum("...ij,...j->...i", w2, x2)
    err = (y2 - z1) if check_variant(variant) == PAPER else (z1 - y2)
    return w2 + l2 * err[..., :, None] * x2[..., None, :]


def w4_from_w2(w2: np.ndarray) -> np.ndarray:
    """Eq. 26-28: T2 = max W2, W3 = the (first) row holding T2, W4 = W3 sorted descending."""
    n = w2.shape[-1]
    flat = w2.reshape(w2.shape[:-2] + (-1,))
    d = np.argmax(flat, axis=-1) // n
    w3 = np.take_along_axis(w2, d[..., None, None], axis=-2)[..., 0, :]
    return -np.sort(-w3, axis=-1)


def b_vector(w6: np.ndarray, w5: np.ndarray) -> np.ndarray:
    """Eq. 31: B(i) = sum_j |W6(j) - W5(i, j)|. w6 (..., 6), w5 (6, 6) -> (..., 6)."""
    return np.abs(np.asarray(w6)[..., None, :] - np.asarray(w5)).sum(axis=-1)


def b_margin(b: np.ndarray) -> np.ndarray:
    """Second-smallest over smallest B (>= 1; inf when the smallest is 0 and the second is not)."""
    s = np.sort(np.asarray(b, dtype=float), axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        m = s[..., 1] / s[..., 0]
    return np.where(s[..., 1] == s[..., 0], 1.0, m)


# ---------------------------------------------------------------- the network
@dataclass
class CPNResult:
    w1: np.ndarray        # (..., 6, L) Kohonen weights after the epochs
    w2: np.ndarray        # (..., 6, 6) Grossberg weights after the epochs
    w4: np.ndarray        # (..., 6) eq. 28
    winners: np.ndarray   # (..., epochs) winner index t of each epoch


class CounterPropagationNetwork:
    """The paper's two-layer network for one signal and one creep index n1.

    ``m3``: the six pattern-window means (eq. 14). ``process(window)`` runs the epochs on one denoised
    window (eq. 9-28) and returns W4; ``fit_patterns(pattern_windows)`` stores W5 (eq. 29);
    ``b(window)`` gives B (eq. 31); ``classify(window)`` -> (index, B) (eq. 32-33, index 0-based).
    """

    def __init__(self, m3, *, variant: str = PAPER, epochs: int = DEFAULT_EPOCHS,
                 l1: float = DEFAULT_L1, l2: float = DEFAULT_L2, w5=None):
        self.m3 = np.asarray(m3, dtype=float)
        if self.m3.ndim != 1:
            raise ValueError("m3 must be a 1-D vector of pattern-window means")
        self.variant = check_variant(variant)
        if int(epochs) < 1:
            raise ValueError(f"epochs must be >= 1, got {epochs}")
        self.epochs = int(epochs)
        self.l1 = float(l1)
        self.l2 = float(l2)
        self.w5 = None if w5 is None else np.asarray(w5, dtype=float)

    @classmethod
    def from_pattern_windows(cls, pattern_windows, **kw) -> "CounterPropagationNetwork":
        """M2 = pattern windows (6 x L): M3 from eq. 14, W5 from processing each row (eq. 29)."""
        pattern_windows = np.asarray(pattern_windows, dtype=float)
        net = cls(pattern_means(pattern_windows), **kw)
        net.fit_patterns(pattern_windows)
        return net

    def fit_patterns(self, pattern_windows) -> np.ndarray:
        self.w5 = self.process_batch(np.asarray(pattern_windows, dtype=float)).w4
        return self.w5

    def process_batch(self, windows: np.ndarray, keep_w1: bool = False) -> CPNResult:
        """Eq. 9-28 for each window of ``windows`` (n, L) (each one processed from fresh weights)."""
        windows = np.atleast_2d(np.asarray(windows, dtype=float))
        n, length = windows.shape
        k = self.m3.size
        w2_out = np.empty((n, k, k))
        winners = np.empty((n, self.epochs), dtype=int)
        w1_out = np.empty((n, k, length)) if keep_w1 else None
        w1_0 = initial_w1(self.m3, length)
        w2_0 = initial_w2(self.m3)
        for s in range(0, n, _CHUNK):
            x = windows[s:s + _CHUNK]
            x1 = normalise_input(x, self.variant)                       # eq. 9, 11-12
            z1 = np.repeat(x.mean(axis=-1)[:, None], k, axis=1)         # eq. 24-25: Z1(i) = m2
            w1 = np.broadcast_to(w1_0, (len(x), k, length)).copy()
            w2 = np.broadcast_to(w2_0, (len(x), k, k)).copy()
            for e in range(self.epochs):
                w1, y1, t = kohonen_step(w1, x1, self.l1, True)             # eq. 15-18
                w2 = grossberg_step(w2, y1, z1, self.l2, self.variant)  # eq. 19, 22-23 (X2 = Y1)
                winners[s:s + _CHUNK, e] = t
            w2_out[s:s + _CHUNK] = w2
            if keep_w1:
                w1_out[s:s + _CHUNK] = w1
        return CPNResult(w1=w1_out, w2=w2_out, w4=w4_from_w2(w2_out), winners=winners)

    def process(self, window) -> CPNResult:
        r = self.process_batch(np.asarray(window, dtype=float)[None, :], keep_w1=True)
        return CPNResult(w1=r.w1[0], w2=r.w2[0], w4=r.w4[0], winners=r.winners[0])

    def b(self, windows) -> np.ndarray:
        """B vectors (eq. 31) for one window (L,) -> (6,) or many (n, L) -> (n, 6)."""
        if self.w5 is None:
            raise RuntimeError("no patterns W5: call fit_patterns() or pass w5=")
        windows = np.asarray(windows, dtype=float)
        w6 = self.process_batch(windows).w4
        out = b_vector(w6, self.w5)
        return out[0] if windows.ndim == 1 else out

    def classify(self, window):
        """Eq. 32-33: (0-based index of the identified width, B)."""
        b = self.b(window)
        return int(np.argmin(b)), b


def paper_w4_from_mean(m2: float, m3, n_samples: int, *, rms: float | None = None, variant: str = PAPER,
                       epochs: int = DEFAULT_EPOCHS, l1: float = DEFAULT_L1, l2: float = DEFAULT_L2) -> np.ndarray:
    """W4 computed from the window's mean alone, without the window (the mean-only proof).

    After n updates the winner row of W1 is a M3(t) + (1 - a) X1 with a = (1 - l1)^n; every other row
    is still M3(i). ``paper``: sum X1 = L m2 / S and X1.X1 = 1/S (S = sum x^2), so
    E1(i) = (a_i M3(i) L m2 + 1 - a_i) / S: the common factor 1/S does not move the argmax, and the
    winner sequence -- hence W2, W4, B -- is a function of m2 alone. ``paper_corrected``: sum X1 =
    sqrt(L) m2 / rms and X1.X1 = 1, so E1(i) = a_i M3(i) sqrt(L) m2 / rms + 1 - a_i: the winners
    depend on m2 / rms (``rms`` must be given), the Grossberg target on m2.
    W2 then evolves column by column from m1 with Z1 = m2 (eq. 22-24).
    """
    m3 = np.asarray(m3, dtype=float)
    k = m3.size
    if check_variant(variant) == PAPER:
        gain = float(n_samples) * float(m2)
    else:
        if rms is None:
            raise ValueError("the corrected variant needs the window's rms as well")
        gain = np.sqrt(float(n_samples)) * float(m2) / float(rms)
    n_upd = np.zeros(k)
    w2 = initial_w2(m3)
    z1 = np.full(k, float(m2))
    for _ in range(int(epochs)):
        a = (1.0 - l1) ** n_upd
        t = int(np.argmax(a * m3 * gain + (1.0 - a)))
        n_upd[t] += 1
        x2 = np.zeros(k)
        x2[t] = 1.0
        w2 = grossberg_step(w2, x2, z1, l2, variant)
    return w4_from_w2(w2)


def continuous_width_from_b(b, widths_m) -> np.ndarray:
    """A width between the candidates from a B vector (any mode): the winner i and its better neighbour j
    share the step in proportion to their B, w = K2(i) + (K2(j) - K2(i)) B(i) / (B(i) + B(j)).
    For the paper mode (B ~ |m2 - m2_i| times a common gain) this is linear interpolation of the window
    mean between the two nearest pattern means. b (k,) or (n, k) -> (n,)."""
    b = np.atleast_2d(np.asarray(b, dtype=float))
    k = np.asarray(widths_m, dtype=float)
    i = np.argmin(b, axis=1)
    rows = np.arange(len(b))
    left = np.where(i > 0, b[rows, np.maximum(i - 1, 0)], np.inf)
    right = np.where(i < k.size - 1, b[rows, np.minimum(i + 1, k.size - 1)], np.inf)
    j = np.where(left <= right, i - 1, i + 1)
    j = np.clip(j, 0, k.size - 1)
    bi, bj = b[rows, i], b[rows, j]
    with np.errstate(divide="ignore", invalid="ignore"):
        frac = np.where(bi + bj > 0, bi / (bi + bj), 0.0)
    frac = np.where(j == i, 0.0, frac)
    out = k[i] + (k[j] - k[i]) * frac
    return out
