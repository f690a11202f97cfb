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

# 6 log-spaced bands from the denoising's edge (~390 Hz) to 6.4 kHz -> 5 shape values per signal. Not higher: above a
# few kHz neither the model (its held disturbance steps, its integrator) nor a real sensor chain (bandwidth, noise,
# quantisation) says anything about the drive's physics -- measured on foreign drives (docs/foreign_drives.md) with
# bands to 20 kHz: clean drives outside the band (T^2 31-586 against 16.8) from the high bands alone
BAND_EDGES_HZ = tuple(float(f) for f in np.geomspace(400.0, 6400.0, 7))


def n_features(n_signals: int = 2) -> int:
    return n_signals * (len(BAND_EDGES_HZ) - 2)


def band_powers(raw: np.ndarray, sample_period_s: float) -> np.ndarray:
    """raw: (E, n_signals, L) raw onset segments -> (E, n_signals, n_bands): per signal, the mean Hann-windowed
    periodogram power |FFT(x w)|^2 in each band (x with its mean removed)."""
    raw = np.asarray(raw, dtype=float)
    e, s, n = raw.shape
    if e == 0:
        return np.zeros((0, s, len(BAND_EDGES_HZ) - 1))
    x = raw - raw.mean(axis=-1, keepdims=True)
    p = np.abs(np.fft.rfft(x * np.hanning(n), axis=-1)) ** 2
    f = np.fft.rfftfreq(n, sample_period_s)
    edges = BAND_EDGES_HZ
    return np.stack([p[..., (f >= lo) & (f < hi)].mean(axis=-1) for lo, hi in zip(edges[:-1], edges[1:])], axis=-1)


def features_from_bands(bands: np.ndarray, noise=None) -> np.ndarray:
    """(E, S, B) band powers -> (E, S * (B - 1)) spectral-shape features; ``noise``: per signal, a white sensor
    noise's power in the same units (noise_power) added to every band first (the model's view of a measurement
    that carries a sensor noise floor), or (S, B) a power per signal and band (a sensor chain with a quantiser:
    sensor_chain)."""
    bands = np.asarray(bands, dtype=float)
    if noise is not None:
        noise = np.asarray(noise, dtype=float)
        bands = bands + (noise[None, :, None] if noise.ndim == 1 else noise[None])
    logp = np.log(np.maximum(bands, 1e-300))
    return np.diff(logp, axis=-1).reshape(bands.shape[0], -1)


def event_features(raw: np.ndarray, sample_period_s: float, noise=None) -> np.ndarray:
    """raw: (E, n_signals, L) raw onset segments -> (E, n_signals * (n_bands - 1)) spectral-shape features:
    per signal, ln P(band b+1) - ln P(band b), P the mean Hann-windowed periodogram power in the band."""
    raw = np.asarray(raw, dtype=float)
    return features_from_bands(band_powers(raw, sample_period_s), noise)


def noisy_event_features(raw: np.ndarray, sample_period_s: float, noise_psd, seed: int = 0,
                         quant_step=None) -> np.ndarray:
    """event_features of ``raw`` with a realisation of white noise of one-sided PSD ``noise_psd`` (per signal)
    added: the model's events as a sensor with that noise floor would record them -- their event-to-event
    spread includes the noise's own (adding only its expected power would not: the features' spread in a
    noise-dominated band would be ~0 and their weights absurd). Seeded: a diagnosis is repeatable.
    ``quant_step``: per signal an ADC's step [m/s^2] (0: none); the noisy events are then quantised at it
    (sensor_chain)."""
    return event_features(_through_chain(raw, sample_period_s, noise_psd, seed, quant_step), sample_period_s)


def _has_quantiser(quant_step) -> bool:
    return quant_step is not None and bool(np.any(np.asarray(quant_step, dtype=float) > 0))


def _through_chain(raw, sample_period_s: float, noise_psd, seed: int, quant_step=None) -> np.ndarray:
    """The model's raw segments as the recording's sensor chain records them: a seeded realisation of the white
    noise floor added, then the ADC's quantiser (quantise) where a signal has a step."""
    raw = np.asarray(raw, dtype=float)
    psd = np.asarray(noise_psd, dtype=float)
    if np.any(psd > 0):
        rng = np.random.default_rng(seed)
        sigma = np.sqrt(psd * 0.5 / sample_period_s)
        raw = raw + rng.standard_normal(raw.shape) * sigma[None, :, None]
    return quantise(raw, quant_step) if _has_quantiser(quant_step) else raw


def quantise(raw: np.ndarray, quant_step) -> np.ndarray:
    """(E, S, L) segments (or (S, L)) with signal s rounded to the lattice k * quant_step[s] (an ADC that rounds;
    0: that signal untouched). The lattice's offset is 0: the model's signal level and the recording's differ by
    more than a step anyway (a bias, the drive's own drift), so an offset would not make the error more like the
    recording's."""
    raw = np.asarray(raw, dtype=float)
    q = np.asarray(quant_step, dtype=float)
    out = raw.copy()
    for s in np.flatnonzero(q > 0):
        out[..., s, :] = np.round(raw[..., s, :] / q[s]) * q[s]
    return out


def sensor_chain(per_seed_raw, sample_period_s: float, noise_psd, quant_step=None) -> tuple[list, np.ndarray]:
    """The model's events through the recording's sensor chain (a white noise floor, then an ADC's quantiser):
    what the spectral-shape view compares a recording with. ``per_seed_raw``: per seed (E_k, S, L) raw onset
    segments of the model's own runs. -> (per seed the events' spectral-shape features, recorded through the chain
    (noisy_event_features, seed = the seed's index): the views' noise; the power the chain adds to each band,
    band_powers' units: the prediction's nuisance term, features_from_bands' ``noise``).

    Without a quantiser the added power is the white floor's expectation, (S,) (noise_power). With one it is
    (S, B): the white floor's plus the power of the quantiser's error on the model's own noisy events, band by band
    (the mean band power of recorded minus noisy: >= 0; the error's correlation with the signal averages out over
    a signal that spans many steps, and its realisation is in the events' features). An undithered ADC's error of a deterministic, slowly varying
    signal is not white (docs/workbench.md, "the sensor chain"): for a 16-bit a2 at 5 mm it carries 5.5x step^2/12
    in the 4.0-6.4 kHz band and 0.26x below, and a foreign drive's a2 through the same ADC 5.4x and 0.26-0.29x,
    where a white step^2/12 put the top band's shape 1.7 off (its T^2 ~100 against a limit of 49)."""
    n_samples = np.asarray(per_seed_raw[0]).shape[-1]
    white = noise_power(noise_psd, n_samples, sample_period_s)
    if not _has_quantiser(quant_step):
        return [noisy_event_features(raw, sample_period_s, noise_psd, seed=k)
                for k, raw in enumerate(per_seed_raw)], white
    feats, error, n = [], 0.0, 0
    for k, raw in enumerate(per_seed_raw):
        noisy = _through_chain(raw, sample_period_s, noise_psd, k)
        recorded = quantise(noisy, quant_step)
        feats.append(event_features(recorded, sample_period_s))
        error = error + band_powers(recorded - noisy, sample_period_s).sum(axis=0)
        n += len(raw)
    return feats, white[:, None] + error / max(n, 1)


def noise_power(noise_psd, n_samples: int, sample_period_s: float) -> np.ndarray:
    """Per signal: the band power (band_powers' units) of a white noise of one-sided PSD ``noise_psd``
    [(m/s^2)^2/Hz] in a segment of ``n_samples``: variance psd * fs / 2 times the Hann window's energy."""
    w = np.hanning(int(n_samples))
    return np.asarray(noise_psd, dtype=float) * (0.5 / sample_period_s) * float(np.sum(w ** 2))
