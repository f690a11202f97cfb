"""sym5 wavelet denoising of backlash windows (paper section 3, SPEC section 2 ``denoise``).

Pure numpy/PyWavelets core, no ROS.  The paper removes details d1..d6 of a level-6 symlet-5
decomposition from every captured window (a1 and a2 alike); what is left is the level-6
approximation a6, i.e. roughly the 0 .. fs/2**7 band (0 .. 390 Hz at fs = 50 kHz).

API
---
``denoise_sym5(window, level=6, details_removed=(1, 2, 3, 4, 5, 6), mode=DEFAULT_MODE,
wavelet="sym5", axis=-1) -> np.ndarray``
    ``window``: one window (n,) or a batch (..., n); the transform runs along ``axis`` and every
    other axis is an independent window (vectorised: the batch result equals the per-window
    result).  ``details_removed``: which detail levels to zero (1 = finest); ``()`` reconstructs
    the input (perfect reconstruction).  Output: float64, same shape as the input (the
    reconstruction is trimmed to the input length).

``denoise_sym5_window(window: BacklashWindow-like, signals=None, **kw)``
    convenience: applies ``denoise_sym5`` to every array of a window's ``signals`` dict and returns
    a dict of denoised arrays.

The chain's window helpers (the denoise node's core and ``analyze``'s), with ``DENOISE_DEFAULTS``:
``check_window_pair(a1, a2)`` the reason a window cannot be denoised, or None;
``denoise_checked(a1, a2)`` ``((a1, a2), None)`` or ``(None, reason)``; ``denoise_pair(a1, a2)`` a
window's a1 and a2 in one call (as the node does); ``denoise_pairs(pairs)`` many windows in one
batch, bit for bit the same; ``denoising_label(level, details_removed, mode)`` the text the nodes
report.

Boundary mode
-------------
A window is not periodic (the entry at its start, the far-side impact or the settling at its
end), so ``periodization``/``periodic`` wrap the end onto the start and put an artificial step into
the approximation (measured: 2-3x the edge error of the extension modes).  ``smooth`` and
``antireflect`` extrapolate the end slope and are best for pure trends, but they inject the
window's high-frequency content at the ends (a 10 kHz tone keeps 63 % / 27 % of its RMS), i.e. the
noise the stage must remove.  ``DEFAULT_MODE = "symmetric"`` (half-sample mirror, PyWavelets'
default) is continuous at both ends, keeps every tone above 780 Hz below 10 % and has within 5 %
the smallest error on low-frequency signal + held noise; see docs/denoising.md and
``boundary_mode_error`` for the measurement.
"""
from __future__ import annotations

from typing import Iterable, Mapping

import numpy as np
import pywt

__all__ = [
    "DEFAULT_MODE",
    "ALLOWED_MODES",
    "denoise_sym5",
    "denoise_sym5_window",
    "DENOISE_DEFAULTS",
    "check_window_pair",
    "denoise_checked",
    "denoise_pair",
    "denoise_pairs",
    "denoising_label",
    "max_level",
    "boundary_mode_error",
]

DEFAULT_WAVELET = "sym5"
DEFAULT_LEVEL = 6
DEFAULT_DETAILS_REMOVED = (1, 2, 3, 4, 5, 6)
DEFAULT_MODE = "symmetric"
ALLOWED_MODES = tuple(pywt.Modes.modes)
_DISCRETE_WAVELETS = frozenset(pywt.wavelist(kind="discrete"))   # looked up once (~50 us a call)


def max_level(n_samples: int, wavelet: str = DEFAULT_WAVELET) -> int:
    """Deepest useful decomposition level for a window of ``n_samples`` (pywt.dwt_max_level)."""
    return pywt.dwt_max_level(int(n_samples), pywt.Wavelet(wavelet).dec_len)


def _check_params(n: int, level, details_removed, mode: str, wavelet: str) -> tuple[int, tuple[int, ...]]:
    if wavelet not in _DISCRETE_WAVELETS:
        raise ValueError(f"wavelet={wavelet!r}: must be a discrete PyWavelets wavelet, e.g. 'sym5'")
    if mode not in ALLOWED_MODES:
        raise ValueError(f"mode={mode!r}: allowed values are {ALLOWED_MODES}")
    if isinstance(level, bool) or not isinstance(level, (int, np.integer)) or level < 1:
        raise ValueError(f"level={level!r}: must be a positive int")
    level = int(level)
    if n < 1:
        raise ValueError("window: must have at least one sample along the transform axis")
    lmax = max_level(n, wavelet)
    if level > lmax:
        raise ValueError(
            f"level={level}: too deep for a window of {n} samples with {wavelet} "
            f"(allowed 1..{lmax}, pywt.dwt_max_level)"
        )
    try:
        removed = tuple(sorted(set(int(d) for d in details_removed)))
    except TypeError as exc:
        raise ValueError(f"details_removed={details_removed!r}: must be an iterable of ints") from exc
    bad = [d for d in removed if d < 1 or d > level]
    if bad:
        raise ValueError(f"details_removed={details_removed!r}: every entry must be in 1..level={level}")
    return level, removed


def denoise_sym5(
    window,
    level: int = DEFAULT_LEVEL,
    details_removed: Iterable[int] = DEFAULT_DETAILS_REMOVED,
    mode: str = DEFAULT_MODE,
    wavelet: str = DEFAULT_WAVELET,
    axis: int = -1,
) -> np.ndarray:
    """Decompose to ``level`` with ``wavelet``, zero the listed details, reconstruct, trim.

    ``details_removed`` counts from the finest detail: d1 = cD1 (fs/4..fs/2), d6 = cD6.
    Raises ValueError naming the parameter for a bad level, mode, wavelet or detail list.
    """
    x = np.asarray(window, dtype=np.float64)
    if x.ndim == 0:
        raise ValueError("window: must be an array with at least one axis")
    x = np.moveaxis(x, axis, -1)
    n = x.shape[-1]
    level, removed = _check_params(n, level, details_removed, mode, wavelet)
    coeffs = pywt.wavedec(x, wavelet, mode=mode, level=level, axis=-1)
    # coeffs = [cA_level, cD_level, ..., cD_1]; detail d is at index level - d + 1
    for d in removed:
        coeffs[level - d + 1] = np.zeros_like(coeffs[level - d + 1])
    y = pywt.waverec(coeffs, wavelet, mode=mode, axis=-1)[..., :n]
    return np.moveaxis(np.ascontiguousarray(y), -1, axis)


def denoise_sym5_window(window, signals: Iterable[str] | None = None, **kwargs) -> dict[str, np.ndarray]:
    """Denoise the arrays of a window (an object with a ``signals`` mapping, or a mapping itself)."""
    data: Mapping[str, np.ndarray] = getattr(window, "signals", window)
    names = list(data) if signals is None else list(signals)
    missing = [s for s in names if s not in data]
    if missing:
        raise ValueError(f"signals={names!r}: not in the window (it has {sorted(data)})")
    return {s: denoise_sym5(data[s], **kwargs) for s in names}


# What the denoise node and ``analyze`` apply to every window (the paper's: d1..d6 of level 6 removed).
DENOISE_DEFAULTS = dict(level=DEFAULT_LEVEL, details_removed=DEFAULT_DETAILS_REMOVED, mode=DEFAULT_MODE)


def check_window_pair(a1, a2, level: int = DENOISE_DEFAULTS["level"],
                      window_length: int | None = None) -> str | None:
    """The reason a window's (a1, a2) cannot be denoised (or classified), or None: both 1-D of one
    length (``window_length`` when given), long enough for ``level``, finite (input_faults.REASONS)."""
    try:
        a1 = np.asarray(a1, dtype=np.float64)
        a2 = np.asarray(a2, dtype=np.float64)
    except (TypeError, ValueError):
        return "non_finite_samples"
    if a1.ndim != 1 or a2.ndim != 1:
        return "bad_shape"
    if a1.size != a2.size:
        return "length_mismatch"
    if window_length is not None and a1.size != window_length:
        return "wrong_window_length"
    if a1.size == 0 or max_level(a1.size) < level:
        return "wrong_window_length"
    if not (np.isfinite(a1).all() and np.isfinite(a2).all()):
        return "non_finite_samples"
    return None


def denoise_checked(a1, a2, **options):
    """``((a1, a2), None)`` denoised, or ``(None, reason)``: the window is checked first
    (:func:`check_window_pair`) and a result that is not finite (finite samples near the float
    limit can overflow the transform) is refused as ``denoise_failed``. The denoise node's core."""
    level = options.get("level", DENOISE_DEFAULTS["level"])
    reason = check_window_pair(a1, a2, level=level)
    if reason is not None:
        return None, reason
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            clean = denoise_pair(a1, a2, **options)
    except ValueError:
        return None, "denoise_failed"
    if not (np.isfinite(clean[0]).all() and np.isfinite(clean[1]).all()):
        return None, "denoise_failed"
    return clean, None


def denoise_pair(a1, a2, **options):
    """sym5 denoising of a window's a1 and a2 in one call; returns (a1, a2)."""
    clean = denoise_sym5(np.stack([np.asarray(a1, dtype=np.float64),
                                   np.asarray(a2, dtype=np.float64)]),
                         **{**DENOISE_DEFAULTS, **options})
    return clean[0], clean[1]


def denoise_pairs(pairs, **options) -> list[tuple[np.ndarray, np.ndarray]]:
    """:func:`denoise_pair` of many windows' (a1, a2) in one batched transform (offline).

    pywt transforms every row of a 2-D batch with the same 1-D routine, so each result is bit for
    bit the window's own ``denoise_pair`` (test/denoise/test_denoise_pairs.py); windows of unequal
    lengths are denoised pair by pair."""
    pairs = [(np.asarray(a1, dtype=np.float64), np.asarray(a2, dtype=np.float64))
             for a1, a2 in pairs]
    shapes = {a.shape for pair in pairs for a in pair}
    if len(pairs) < 2 or len(shapes) != 1 or len(next(iter(shapes))) != 1:
        return [denoise_pair(a1, a2, **options) for a1, a2 in pairs]
    rows = np.stack([a for pair in pairs for a in pair])          # a1, a2, a1, a2, ...
    clean = denoise_sym5(rows, **{**DENOISE_DEFAULTS, **options})
    return [(clean[2 * i], clean[2 * i + 1]) for i in range(len(pairs))]


def denoising_label(level: int, details_removed, mode: str) -> str:
    return (f"sym5 level {level}, details {','.join(map(str, details_removed))} removed, "
            f"mode {mode}")


def boundary_mode_error(
    clean_long: np.ndarray,
    window_length: int = 2048,
    modes: Iterable[str] = ("smooth", "symmetric", "reflect", "antireflect", "constant", "zero",
                            "periodic", "periodization"),
    edge: int = 128,
    **kwargs,
) -> dict[str, dict[str, float]]:
    """Edge error of each boundary mode, the measurement behind ``DEFAULT_MODE``.

    ``clean_long``: (n_windows, L) noise-free records, L >= 3*window_length.  The reference is the
    approximation of the long record (the window's middle third, where no boundary reaches); each
    mode denoises the cut window alone.  Returns per mode the RMS error over the first and last
    ``edge`` samples and over the whole window, relative to the reference RMS.
    """
    clean_long = np.atleast_2d(np.asarray(clean_long, dtype=np.float64))
    w = int(window_length)
    if clean_long.shape[-1] < 3 * w:
        raise ValueError("clean_long: records must be at least 3*window_length long")
    lo = w
    ref = denoise_sym5(clean_long, mode="symmetric", **kwargs)[..., lo:lo + w]
    cut = clean_long[..., lo:lo + w]
    scale = np.sqrt(np.mean(ref ** 2)) + 1e-300
    out: dict[str, dict[str, float]] = {}
    for m in modes:
        y = denoise_sym5(cut, mode=m, **kwargs)
        e = y - ref
        out[m] = {
            "start": float(np.sqrt(np.mean(e[..., :edge] ** 2)) / scale),
            "end": float(np.sqrt(np.mean(e[..., -edge:] ** 2)) / scale),
            "whole": float(np.sqrt(np.mean(e ** 2)) / scale),
        }
    return out
