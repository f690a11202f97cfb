"""The comparison of one measurement with a model: conditions, the model's noise ensemble, fit %, spread,
spectra, and where the residual sits (phase, wavelet level, spectral peaks, whiteness, inputs).

All figures are against the model's own noise ensemble (``K`` seeds, the measurement's length and
conditions): a measurement from a correct model lies inside that band.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pywt
from scipy.special import chdtrc     # chi^2's sf, as scipy.stats.chi2.sf computes it (scipy.stats: ~1 s to import)
from scipy import fft as scipy_fft

from . import spectral
from .events import (DC_BLOCKS, IMPACT_SETTLE_S, POST_SAMPLES, PRE_SAMPLES, SEGMENT_SIGNALS, Ensemble, EventSet,
                     dc_block_deviations, dc_signals, denoise, ensemble_from_runs, event_set, onset_entries)

DEFAULT_SEEDS = 6
PHASES = ("before_entry", "gap_traversal", "impact", "settling")
LEVELS = ("d1", "d2", "d3", "d4", "d5", "d6", "a6")
from .consistency import INCONSISTENT_RATIO  # noqa: E402,F401  (kept here for its users)


class ConditionsError(ValueError):
    pass


def recover_conditions(meas, model) -> dict:
    """The pulse train's timing of the recording: its phase from the onset entries (period checked
    against the model's). -> config overrides {"pulse_load.first_s": ...}."""
    cfg = model.plant_config()
    fs = cfg.simulation.sample_rate_hz
    period = int(round(cfg.pulse_load.period_s * fs))
    entries = onset_entries(meas.signals, meas.sample_period_s)
    if len(entries) < 3:
        raise ConditionsError(f"measurement {meas.source}: only {len(entries)} onset entries found; "
                              "allowed: >= 3 (a longer recording, or a drive that crosses its backlash)")
    spacing = float(np.median(np.diff(entries)))
    if abs(spacing - period) > 0.03 * period:
        raise ConditionsError(f"measurement {meas.source}: onset entries every {spacing / fs * 1e3:.1f} ms, the "
                              f"model's pulse period is {period / fs * 1e3:.1f} ms; allowed: within 3 % "
                              f"(--set pulse_load.period_s={round(spacing) / fs:g})")
    # the model's delay from pulse start to onset entry (noise-free, nominal timing)
    # deferred: the simulator (numba, scipy.optimize) costs ~700 ms at start-up (python -X importtime, 29 Nov)
    from . import plant_adapter      # the simulator (numba): imported where a model is simulated, not to evaluate
    runs = plant_adapter.simulate_sets(model, [{}], [0], int(round(1.0 * fs)), noise=False)
    sim_entries = onset_entries({k: v[0, 0] for k, v in runs.items()}, 1.0 / fs)
    first = int(round(cfg.pulse_load.first_s * fs))
    if len(sim_entries) == 0:
        raise ConditionsError("the model (noise-free) gives no onset entry in 1 s; it cannot be compared")
    delay = float(np.median((sim_entries - first) % period))
    phase = np.angle(np.mean(np.exp(2j * np.pi * ((entries - delay) % period) / period)))
    start = int(round((phase / (2 * np.pi)) * period)) % period
    return {"pulse_load.first_s": start / fs}


@dataclass
class Comparison:
    model: object
    meas: object
    conditions: dict
    seeds: list
    events: EventSet
    ensemble: Ensemble
    weights: np.ndarray          # per signal 1/noise floor rms (denoised)
    floor_rms: np.ndarray        # per signal, rms of the leave-one-seed-out deviation
    spec_weights: np.ndarray | None = None   # per spectral-shape feature 1/its noise floor (workbench/spectral.py)
    dc_weights: np.ndarray | None = None     # per signal 1/the noise floor of the mean of its period means
    noise_psd: np.ndarray | None = None      # per signal: the recording's white sensor-noise floor [(m/s^2)^2/Hz]
                                             # (beyond its ADC's quantiser, when it has one: sensor_noise_floor)
    record_spectra: dict | None = None       # spectra(): the whole-record Welch PSDs (measured, ensemble)
    model_event_spec: list | None = None     # per seed: the model's events' spectral features with the noise floor
    dc_names: tuple = ("a1", "a2")           # the record-mean view's signals (events.dc_signals)
    quant_step: np.ndarray | None = None     # per signal: the recording's ADC step [m/s^2], 0 = not quantised
    chain_power: np.ndarray | None = None    # the sensor chain's power per signal (S,) or per signal and band (S, B)
                                             # in the spectral block's band-power units (spectral.sensor_chain)

    @property
    def segment_noise(self) -> np.ndarray:
        """The sensor chain's power in the spectral block's band-power units: the white floor's (spectral.noise_power)
        or, with an ADC's quantiser, per band (spectral.sensor_chain)."""
        if self.chain_power is not None:
            return self.chain_power
        return spectral.noise_power(self.noise_psd, PRE_SAMPLES + POST_SAMPLES, self.meas.sample_period_s)

    @property
    def noise_psd_white_equivalent(self) -> np.ndarray:
        """Per signal: the white floor plus the quantiser's step^2/12 as a white PSD (the whole-record spectra's
        nuisance, analysis.spectra; what the recording's noise band reads)."""
        return self.noise_psd + quantisation_psd(self.quant_step, self.meas.sample_period_s)

    @property
    def target(self):
        return self.events.mean_denoised()

    @property
    def model_mean(self):
        return self.ensemble.mean_denoised()


def build_comparison(meas, model, seeds=None) -> Comparison:
    seeds = list(range(DEFAULT_SEEDS)) if seeds is None else list(seeds)
    if len(seeds) < 3:
        raise ValueError("the ensemble needs >= 3 seeds")
    conditions = recover_conditions(meas, model)
    dc_names = dc_signals(meas.signals)
    ev = event_set(meas.signals, meas.sample_period_s, dc_names)
    # deferred: the simulator (numba, scipy.optimize) costs ~700 ms at start-up (python -X importtime, 29 Nov)
    from . import plant_adapter
    runs = plant_adapter.simulate_sets(model, [{}], seeds, meas.n_samples, conditions=conditions,
                                       signals=("a1", "a2", "omega1", "omega2", "angle_difference"))
    ens = ensemble_from_runs(runs, meas.sample_period_s, keep_records=True, dc_names=dc_names)
    loo = ens.loo_deviation()
    floor = np.sqrt(np.mean(loo ** 2, axis=(0, 2)))
    record_spectra = _welch_all(meas, ens)
    quant = quantisation_steps(meas.signals)
    noise_psd = sensor_noise_floor(record_spectra, meas.signals, meas.sample_period_s, quant)
    # the spectral-shape features' floor: their event-to-event spread in the model's own events (recorded through
    # the recording's sensor chain: its noise floor and its ADC's quantiser) over the square root of the
    # measurement's number of events (the noise of the measured events' mean)
    model_event_spec, chain = spectral.sensor_chain(ens.per_event, meas.sample_period_s, noise_psd, quant)
    feats = np.vstack(model_event_spec)
    spec_floor = feats.std(axis=0) / np.sqrt(max(ev.n_events, 1))
    # the record-mean view's floor: the same for the events' period means (events.period_means)
    dc_floor = record_mean_floor(ens.per_event_dc, ev.n_events)
    return Comparison(model, meas, conditions, seeds, ev, ens, 1.0 / floor, floor,
                      1.0 / np.maximum(spec_floor, 1e-12), 1.0 / np.maximum(dc_floor, 1e-12), noise_psd,
                      record_spectra, model_event_spec, dc_names, quant,
                      chain if np.any(quant > 0) else None)


def record_mean_floor(per_seed_dc, n_events: int) -> np.ndarray:
    """The record-mean view's noise floor for an ``n_events`` recording: the spread of the model's events' block
    deviations (events.dc_block_deviations, per seed; the blocks' means are the degrees of freedom lost) over the
    square root of the number of events. ``per_seed_dc``: per seed (E_k, n_dc) period means."""
    dcs = np.vstack([dc_block_deviations(d) for d in per_seed_dc])
    return np.sqrt(np.sum(dcs ** 2, axis=0) / max(dcs.shape[0] - len(per_seed_dc) * DC_BLOCKS, 1)) \
        / np.sqrt(max(n_events, 1))


def fit_percent(target, model_mean) -> np.ndarray:
    """Per signal: 100 * (1 - ||y - m|| / ||y - mean(y)||)."""
    num = np.linalg.norm(target - model_mean, axis=-1)
    den = np.linalg.norm(target - target.mean(axis=-1, keepdims=True), axis=-1)
    return 100.0 * (1.0 - num / den)


def residual_ratio(c: Comparison, model_mean=None) -> np.ndarray:
    """Per signal: rms(measured average - model mean) / noise floor (1 = as good as the model's own runs)."""
    m = c.model_mean if model_mean is None else model_mean
    return np.sqrt(np.mean((c.target - m) ** 2, axis=-1)) / c.floor_rms


def noise_band_fit_percent(c: Comparison) -> np.ndarray:
    """(n_seeds, 2): fit % of each seed's own average against the mean of the other seeds."""
    x = c.ensemble.seed_denoised()
    k = x.shape[0]
    others = (x.sum(axis=0)[None] - x) / (k - 1)
    return np.array([fit_percent(x[i], others[i]) for i in range(k)])


def spread(c: Comparison) -> dict:
    """Event-to-event spread (rms over the segment of the per-sample std across events), measured vs model."""
    meas = denoise(c.events.raw).std(axis=0).mean(axis=-1) if c.events.n_events > 1 else np.full(2, np.nan)
    mod = np.array([denoise(p).std(axis=0).mean(axis=-1) for p in c.ensemble.per_event if len(p) > 1])
    return {s: {"measured": float(meas[i]), "model_median": float(np.median(mod[:, i])),
                "model_min": float(mod[:, i].min()), "model_max": float(mod[:, i].max())}
            for i, s in enumerate(SEGMENT_SIGNALS)}


SPECTRUM_NPERSEG = 8192     # Welch segment of the whole-record spectra (6.1 Hz bins at 50 kHz)


def welch_psd(x, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """(f, PSD) of one record or of each row of (n, samples): the workbench's one spectrum estimate, so that
    every spectrum it compares has the same segment and bins. ``scipy.signal.welch(x, fs, nperseg=min(8192,
    samples))`` to the last bit (test_analysis_welch.py), computed here with numpy and scipy.fft in the order of
    operations scipy's ShortTimeFFT uses: the segments' mean removed, times the periodic Hann window scaled to a
    density, the one-sided FFT's squared magnitude, the inner bins doubled, the mean over the segments. Not
    scipy.signal itself: importing it costs ~0.35 s per process (a `analyze FOLDER` worker's model fit, the
    watch node's start), and its welch rebuilt the window at every call (the live watch's spectrum of an onset
    period, two 8192-sample segments of a1 and a2 every 4th event, cost 1.8 ms with scipy's welch)."""
    x = np.asarray(x, dtype=float)
    n = x.shape[-1] if x.ndim else 0
    if x.ndim == 0 or x.size == 0:
        # deferred: scipy.signal costs ~1100 ms at start-up (python -X importtime, 29 Nov)
        from scipy import signal as sps     # scipy's own answer (and errors) for what has no segment
        return sps.welch(x, fs=fs, nperseg=min(SPECTRUM_NPERSEG, max(n, 1)), axis=-1)
    nperseg = min(SPECTRUM_NPERSEG, n)
    win, f = _welch_plan(nperseg, float(fs))
    hop = nperseg - nperseg // 2
    n_segments = (n - nperseg // 2) // hop
    segments = np.lib.stride_tricks.sliding_window_view(x, nperseg, axis=-1)[..., :n_segments * hop:hop, :]
    segments = segments - np.mean(segments, axis=-1, keepdims=True)
    spectrum = scipy_fft.rfft(segments * win, n=nperseg, axis=-1)          # (..., segment, bin)
    pxx = spectrum.real ** 2 + spectrum.imag ** 2
    pxx[..., 1:-1 if nperseg % 2 == 0 else None] *= 2
    pxx = np.ascontiguousarray(np.moveaxis(pxx, -2, -1))                    # (..., bin, segment), as scipy sums
    pxx = pxx.mean(axis=-1) if n_segments > 1 else np.reshape(pxx, pxx.shape[:-1])
    return f, pxx


_WELCH_PLANS: dict = {}


def _welch_plan(nperseg: int, fs: float) -> tuple[np.ndarray, np.ndarray]:
    """(window, bin frequencies in Hz) of welch_psd for (nperseg, fs), built once: scipy's periodic Hann window
    (``get_window('hann', nperseg)``: the symmetric one of nperseg + 1 points without its last, as a sum of
    cosines on linspace(-pi, pi)) scaled to a density, 1 / sqrt(sum(w^2) * fs) with the sum taken in order as
    ShortTimeFFT.fac_psd does."""
    plan = _WELCH_PLANS.get((nperseg, fs))
    if plan is None:
        if len(_WELCH_PLANS) >= 16:
            _WELCH_PLANS.clear()
        if nperseg <= 1:
            win = np.ones(nperseg)
        else:
            angle = np.linspace(-np.pi, np.pi, nperseg + 1)
            win = np.zeros(nperseg + 1)
            for k, a in enumerate(np.asarray([0.5, 0.5])):
                win += a * np.cos(k * angle)
            win = win[:-1]
        win = win * (1 / np.sqrt(sum(win ** 2) / (1 / fs)))
        plan = _WELCH_PLANS[(nperseg, fs)] = (win, scipy_fft.rfftfreq(nperseg, 1 / fs))
    return plan


NOISE_BAND_HZ = (12000.0, 24000.0)   # where a sensor's white noise floor is read off (the model's a1 has 1e-4,
                                     # its a2 1e-15..1e-13 (m/s^2)^2/Hz there; a MEMS sensor's floor is 1e-9..1e-6)


def _welch_all(meas, ens) -> dict:
    fs = 1.0 / meas.sample_period_s
    out = {}
    for s in SEGMENT_SIGNALS:
        f, pm = welch_psd(meas.signals[s], fs)
        out[s] = {"f": f, "measured": pm, "ensemble": welch_psd(ens.raw_records[s], fs)[1]}
    return out


def quantisation_step(x: np.ndarray) -> float:
    """The ADC step of a recorded signal [its unit], 0 when it is not quantised: the values lie on a grid (the
    distinct values' spacings are whole multiples of the smallest, and far fewer distinct values than samples)."""
    u = np.unique(np.asarray(x, dtype=float))
    if len(u) < 3 or len(u) > 0.5 * len(x):
        return 0.0
    d = np.diff(u)
    step = float(d.min())
    if not step > 0:
        return 0.0
    k = d / step
    return step if np.all(np.abs(k - np.round(k)) < 1e-3 * np.maximum(k, 1.0)) else 0.0


def quantisation_steps(signals: dict) -> np.ndarray:
    """Per signal (SEGMENT_SIGNALS): the ADC step of the recording's samples [their unit], 0 = not quantised
    (quantisation_step)."""
    return np.array([quantisation_step(signals[s]) for s in SEGMENT_SIGNALS])


def quantisation_psd(quant_step, sample_period_s: float) -> np.ndarray:
    """Per signal: an ADC step's step^2/12 as a white one-sided PSD [(m/s^2)^2/Hz] (0 without a step)."""
    q = np.zeros(len(SEGMENT_SIGNALS)) if quant_step is None else np.asarray(quant_step, dtype=float)
    return q ** 2 / 12.0 * 2.0 * sample_period_s


def sensor_noise_floor(record_spectra: dict, signals: dict | None = None,
                       sample_period_s: float | None = None, quant_step=None) -> np.ndarray:
    """Per signal: the white noise floor the recording's sensor chain adds [(m/s^2)^2/Hz, one-sided]: the median
    of the measured PSD over NOISE_BAND_HZ minus the model's there, >= 0. A real accelerometer always has one (and
    an ADC its quantisation); the model has none. It is a nuisance, not an effect: the spectral views compare the
    measurement with the model recorded through the sensor chain (an effect must explain what is left).

    A quantised signal (an ADC; its step from ``quant_step`` or read off ``signals``: quantisation_step) is
    modelled as the white floor *then* the quantiser (spectral.sensor_chain quantises the model's events): the
    floor returned is the white noise before it, the noise band's excess less the step^2/12 a dithered
    quantiser leaves there, >= 0. An undithered ADC's error is not white (its level above 12 kHz measured 2.3x
    under step^2/12 on a foreign drive with a 16-bit a2), so a drive with no other noise gets a floor of 0 and its
    quantiser alone; a noisy one (noise >> step) its noise, the quantiser adding ~step^2/12 on top as it does."""
    out = []
    if quant_step is None and signals is not None and sample_period_s is not None:
        quant_step = quantisation_steps(signals)
    quant = np.zeros(len(SEGMENT_SIGNALS)) if quant_step is None or sample_period_s is None \
        else quantisation_psd(quant_step, sample_period_s)
    for i, s in enumerate(SEGMENT_SIGNALS):
        d = record_spectra[s]
        sel = (d["f"] >= NOISE_BAND_HZ[0]) & (d["f"] <= NOISE_BAND_HZ[1])
        excess = float(np.median(d["measured"][sel]) - np.median(d["ensemble"].mean(axis=0)[sel]))
        out.append(max(excess - quant[i], 0.0))
    return np.array(out)


def spectra(c: Comparison) -> dict:
    """Whole-record raw spectra (Welch) of the measurement and every ensemble run, the runs with the recording's
    sensor noise floor added (sensor_noise_floor; an ADC's quantiser as its white step^2/12)."""
    out = {}
    noise = c.noise_psd if c.quant_step is None else c.noise_psd_white_equivalent
    for i, s in enumerate(SEGMENT_SIGNALS):
        d = c.record_spectra[s]
        out[s] = {"f": d["f"], "measured": d["measured"], "ensemble": d["ensemble"] + noise[i]}
    return out


def spectral_peaks(spec: dict, n_peaks: int = 5, factor: float = 2.0) -> dict:
    """Frequencies where the measured PSD exceeds the ensemble's maximum by ``factor`` (strongest first)."""
    out = {}
    for s, d in spec.items():
        hi = d["ensemble"].max(axis=0)
        mean = d["ensemble"].mean(axis=0)
        ratio = d["measured"] / np.maximum(mean, 1e-300)
        idx = np.flatnonzero((d["measured"] > factor * hi) & (d["f"] > 0))
        idx = idx[np.argsort(-ratio[idx])][:n_peaks]
        low = d["measured"] < d["ensemble"].min(axis=0) / factor
        band_ratio = {}
        for lo_f, hi_f in ((0, 50), (50, 200), (200, 1000), (1000, 5000), (5000, 25000)):
            sel = (d["f"] >= lo_f) & (d["f"] < hi_f)
            if sel.any():
                band_ratio[f"{lo_f}-{hi_f} Hz"] = float(d["measured"][sel].sum() / max(mean[sel].sum(), 1e-300))
        out[s] = {"peaks_hz": [float(d["f"][i]) for i in idx], "peak_ratio": [float(ratio[i]) for i in idx],
                  "fraction_below_band": float(low[1:].mean()), "power_ratio_per_band": band_ratio}
    return out


def impact_sample(c: Comparison) -> int:
    """Index in the segment of the far-side impact: the largest |a1| of the model's mean after the entry."""
    a1 = c.ensemble.mean_raw()[0]
    return PRE_SAMPLES + int(np.argmax(np.abs(a1[PRE_SAMPLES:])))


def phase_slices(c: Comparison) -> dict:
    L = c.target.shape[-1]
    imp = impact_sample(c)
    settle = imp + int(round(IMPACT_SETTLE_S / c.meas.sample_period_s))
    return {"before_entry": slice(0, PRE_SAMPLES), "gap_traversal": slice(PRE_SAMPLES, imp),
            "impact": slice(imp, min(settle, L)), "settling": slice(min(settle, L), L)}


def where(c: Comparison, model_mean=None, raw_model_mean=None) -> dict:
    """Share of the (weighted) residual per phase and per sym5 level, each with the noise's share and the
    ratio residual energy / noise energy there (1 = inside the band)."""
    m = c.model_mean if model_mean is None else model_mean
    w = c.weights[:, None]
    r = (c.target - m) * w
    loo = c.ensemble.loo_deviation() * w[None]
    total = float(np.sum(r ** 2))
    noise_total = float(np.mean(np.sum(loo ** 2, axis=(1, 2))))
    per_phase = {}
    for name, sl in phase_slices(c).items():
        e = float(np.sum(r[:, sl] ** 2))
        n = float(np.mean(np.sum(loo[:, :, sl] ** 2, axis=(1, 2))))
        per_phase[name] = {"share": e / max(total, 1e-300), "noise_share": n / max(noise_total, 1e-300),
                           "over_noise": e / max(n, 1e-300),
                           "per_signal_over_noise": {s: float(np.sum(r[i, sl] ** 2) /
                                                              max(np.mean(np.sum(loo[:, i, sl] ** 2, axis=1)), 1e-300))
                                                     for i, s in enumerate(SEGMENT_SIGNALS)}}
    # wavelet levels on the raw (not denoised) averages: the denoising removes d1..d6
    rm = c.ensemble.mean_raw() if raw_model_mean is None else raw_model_mean
    rr = (c.events.mean_raw() - rm) * w
    raw_loo = c.ensemble.loo_deviation(denoised=False) * w[None]
    lv_e = np.zeros(len(LEVELS))
    lv_n = np.zeros(len(LEVELS))
    for i in range(len(SEGMENT_SIGNALS)):
        coeffs = pywt.wavedec(rr[i], "sym5", level=6)      # [a6, d6, ..., d1]
        for j, cf in enumerate(coeffs):
            lv_e[_level_index(j)] += np.sum(cf ** 2)
        for k in range(raw_loo.shape[0]):
            for j, cf in enumerate(pywt.wavedec(raw_loo[k, i], "sym5", level=6)):
                lv_n[_level_index(j)] += np.sum(cf ** 2) / raw_loo.shape[0]
    per_level = {name: {"share": float(lv_e[i] / max(lv_e.sum(), 1e-300)),
                        "noise_share": float(lv_n[i] / max(lv_n.sum(), 1e-300)),
                        "over_noise": float(lv_e[i] / max(lv_n[i], 1e-300))} for i, name in enumerate(LEVELS)}
    return {"per_phase": per_phase, "per_level": per_level,
            "dominant_phase": max(per_phase, key=lambda k: per_phase[k]["over_noise"]),
            "dominant_level": max(per_level, key=lambda k: per_level[k]["over_noise"] * per_level[k]["share"])}


def _level_index(j: int) -> int:
    # coeffs index j: 0 = a6, 1 = d6, ..., 6 = d1 -> LEVELS index: d1..d6 = 0..5, a6 = 6
    return 6 if j == 0 else 6 - j


def ljung_box(x: np.ndarray, lags: int = 10) -> tuple[float, float]:
    x = np.asarray(x, dtype=float) - np.mean(x)
    n = len(x)
    lags = min(lags, n - 2)
    if lags < 1:
        return float("nan"), float("nan")
    d = np.sum(x ** 2)
    q = n * (n + 2) * sum((np.sum(x[k:] * x[:-k]) / d) ** 2 / (n - k) for k in range(1, lags + 1))
    return float(q), float(chdtrc(lags, q))


def decorrelation_lag(loo: np.ndarray) -> int:
    """Samples after which the noise's autocorrelation falls below 1/e (mean over seeds and signals)."""
    lags = []
    for k in range(loo.shape[0]):
        for i in range(loo.shape[1]):
            x = loo[k, i] - loo[k, i].mean()
            ac = np.correlate(x, x, "full")[len(x) - 1:]
            ac = ac / max(ac[0], 1e-300)
            below = np.flatnonzero(ac < 1 / np.e)
            lags.append(int(below[0]) if below.size else len(x))
    return max(1, int(np.median(lags)))


def whiteness(c: Comparison, model_mean=None) -> dict:
    """Ljung-Box on the residual of the event average, sampled every decorrelation length of the noise
    (the honest unit: about one independent value per lag), against the same test on the ensemble's own
    leave-one-out deviations."""
    m = c.model_mean if model_mean is None else model_mean
    loo = c.ensemble.loo_deviation()
    lag = decorrelation_lag(loo)
    out = {"decorrelation_samples": lag}
    for i, s in enumerate(SEGMENT_SIGNALS):
        q, p = ljung_box((c.target[i] - m[i])[::lag])
        band = [ljung_box(loo[k, i, ::lag])[1] for k in range(loo.shape[0])]
        out[s] = {"Q": q, "p_value": p, "n": int(len(c.target[i][::lag])),
                  "ensemble_p_min": float(np.nanmin(band)), "ensemble_p_median": float(np.nanmedian(band))}
    return out


def _event_correlations(events_raw, entries, omega1, m, weights, cfg, fs):
    ev = denoise(events_raw)
    period = cfg.pulse_load.period_s * fs
    inputs = {"pulse_phase": ((entries - cfg.pulse_load.first_s * fs) % period) / period}
    if omega1 is not None:
        inputs["motor_speed"] = np.array([omega1[k - PRE_SAMPLES:k + ev.shape[-1] - PRE_SAMPLES].mean()
                                          for k in entries])
    out = {}
    for i, s in enumerate(SEGMENT_SIGNALS):
        resid = ((ev[:, i] - m[i]) * weights[i]).mean(axis=-1)
        for name, x in inputs.items():
            ok = len(x) > 3 and np.std(x) > 0 and np.std(resid) > 0
            out[f"{s}_vs_{name}"] = float(np.corrcoef(resid, x)[0, 1]) if ok else 0.0
    return out


def input_correlation(c: Comparison, model_mean=None) -> dict:
    """Per event: the mean weighted residual of a1 and a2 over the segment vs the motor speed (omega1,
    mean over the segment) and the pulse phase at the entry; the band is the same correlation in each of
    the model's own seeds (against the model mean): a correlation the physics makes anyway (a faster motor
    crosses the gap harder) is inside it."""
    m = c.model_mean if model_mean is None else model_mean
    fs = 1.0 / c.meas.sample_period_s
    cfg = c.model.plant_config(c.conditions)
    out = {"events": c.events.n_events}
    if c.events.n_events < 4:
        return out
    meas = _event_correlations(c.events.raw, c.events.entries, c.meas.signals.get("omega1"), m, c.weights, cfg, fs)
    band = []
    rec = c.ensemble.raw_records or {}
    for k, (raw, ent) in enumerate(zip(c.ensemble.per_event, c.ensemble.per_event_entries or [])):
        om = rec["omega1"][k] if "omega1" in rec else None
        band.append(_event_correlations(raw, ent, om, m, c.weights, cfg, fs))
    for key, r in meas.items():
        vals = [b[key] for b in band if key in b]
        lo, hi = (min(vals), max(vals)) if vals else (-2 / np.sqrt(c.events.n_events), 2 / np.sqrt(c.events.n_events))
        out[key] = {"r": r, "ensemble_min": lo, "ensemble_max": hi, "outside_band": bool(r < lo or r > hi)}
    return out
