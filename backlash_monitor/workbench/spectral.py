"""The raw-signal spectral block of the workbench's evidence: the spectral shape of every onset event.

The event average is sym5-denoised (details d1..d6 removed, i.e. everything above ~390 Hz at 50 kHz), so an
effect that acts only there -- a sensor roll-off of a few hundred hertz and up -- is invisible in it. This
block looks at the raw (not denoised) a1/a2 of each onset segment (the same segments as the event average):
per event, per signal, the log of the Hann-windowed periodogram's mean power in log-spaced bands between
BAND_EDGES_HZ[0] and BAND_EDGES_HZ[-1]; the feature is the *difference of adjacent bands* (the spectral
shape: a roll-off tilts it, while a gain or a heavier mass that scales the whole band only shifts the level,
which the differences drop; measured: a per-recording level of a1's noise differs between noise seeds by
more than its events' spread, the shape does not).

The independent units are the events (as for the event average): the measured feature is the mean over the
recording's events; its covariance is estimated from the model's own events (K seeds x E events). Docs:
docs/workbench.md, "Raw spectral block".
"""
from __future__ import annotations

import numpy as np

BAND_EDGES_HZ = tuple(float(f) for f in np.geomspace(400.0, 20000.0, 7))   # 6 bands -> 5 shape values per signal


def n_features(n_signals: int = 2) -> int:
    return n_signals * (len(BAND_EDGES_HZ) - 2)


def event_features(raw: np.ndarray, sample_period_s: float) -> np.ndarray:
    """raw: (E, n_signals, L) raw onset segments -> (E, n_signals * (n_bands - 1)) spectral-shape features:
    per signal, ln P(band b+1) - ln P(band b), P the mean Hann-windowed periodogram power in the band."""
    raw = np.asarray(raw, dtype=float)
    e, s, n = raw.shape
    if e == 0:
        return np.zeros((0, n_features(s)))
    x = raw - raw.mean(axis=-1, keepdims=True)
    p = np.abs(np.fft.rfft(x * np.hanning(n), axis=-1)) ** 2
    f = np.fft.rfftfreq(n, sample_period_s)
    edges = BAND_EDGES_HZ
    bands = np.stack([p[..., (f >= lo) & (f < hi)].mean(axis=-1) for lo, hi in zip(edges[:-1], edges[1:])],
                     axis=-1)                                    # (E, S, B)
    logp = np.log(np.maximum(bands, 1e-300))
    return np.diff(logp, axis=-1).reshape(e, -1)
