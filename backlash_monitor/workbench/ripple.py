"""A torque ripple from the raw spectra: the catalogue effect the event average cannot see.

``torque_ripple`` is a load moment A*sin(order*alpha1 + phase) locked to the motor angle, not to the
backlash events: it averages out of the event average (plant_adapter.NOT_EVENT_LOCKED), but it puts a
line into the raw a1 spectrum at order x the motor's rotation frequency. This module fits it there:

1. the line: the strongest frequency where the measured a1 PSD (Welch, whole record, raw) exceeds the
   model ensemble's largest by ``LINE_FACTOR`` (analysis.spectral_peaks);
2. the order: line frequency / rotation frequency (the model ensemble's mean omega1 / 2 pi under the
   measurement's conditions); a line outside the effect's orders (``ORDER_RANGE``) is not a ripple;
3. the amplitude: the line's *excess* power (band power over the ensemble mean in the band around the
   line, the band as wide as the speed's spread smears the line) scales with A^2, so a simulation at
   ``REF_AMPLITUDE_PU`` (the same seeds: common random numbers) gives A = A_ref * sqrt(excess / excess_ref),
   and one more at that A corrects it (a strong ripple is not quite linear: it moves the speed);
4. the check: the model with the fitted ripple, simulated, must reproduce the line: its excess within the
   measurement's own uncertainty. The independent units: the seeds of the ensemble for the band's noise
   (the line counts only when its excess is ``MIN_Z`` of their spreads above the ensemble mean), and
   ``BLOCKS`` time blocks of the record for the measured line power's own uncertainty.

The phase is not identifiable from a power spectrum (reported as such). Docs: docs/workbench.md
"Torque ripple: the spectral fit".
"""
from __future__ import annotations

import math

import numpy as np

from . import analysis, plant_adapter

EFFECT = "torque_ripple"
REF_AMPLITUDE_PU = 0.3
LINE_FACTOR = 2.0              # the measured PSD over the ensemble's largest: a line
MIN_Z = 5.0                    # the line's excess over the band's spread across the model's seeds
ORDER_RANGE = (0.5, 50.0)      # the effect's orders (bounds 0..50; below 0.5 the line is at DC)
REF_SEEDS = 3                  # seeds of the reference and check simulations (common random numbers)
BLOCKS = 4                     # time blocks of the record for the measured line power's uncertainty


def _band_power(f, psd, lo_hz, hi_hz) -> np.ndarray:
    sel = (f >= lo_hz) & (f <= hi_hz)
    return psd[..., sel].sum(axis=-1)


def _block_spread(a1, fs, lo_hz, hi_hz) -> float:
    """Relative standard error of the record's band power from its BLOCKS time blocks' band powers."""
    x = np.asarray(a1, dtype=float)
    n = len(x) // BLOCKS
    f, p = analysis.welch_psd(x[:n * BLOCKS].reshape(BLOCKS, n), fs)
    band = _band_power(f, p, lo_hz, hi_hz)
    return float(band.std(ddof=1) / max(band.mean(), 1e-300) / math.sqrt(BLOCKS))


def fit_torque_ripple(comp, spec: dict | None = None) -> dict | None:
    """The ripple explaining the strongest excess line of the raw a1 spectrum, or None (no line, or a line
    no ripple order can make). ``comp``: analysis.Comparison; ``spec``: analysis.spectra(comp) if done."""
    spec = spec if spec is not None else analysis.spectra(comp)
    peaks = analysis.spectral_peaks({"a1": spec["a1"]}, factor=LINE_FACTOR)["a1"]["peaks_hz"]
    rec = comp.ensemble.raw_records or {}
    if not peaks or "omega1" not in rec:
        return None
    f, meas_psd, ens_psd = spec["a1"]["f"], spec["a1"]["measured"], spec["a1"]["ensemble"]
    omega = np.asarray(rec["omega1"], dtype=float)
    f_rot = float(np.mean(omega)) / (2.0 * math.pi)
    if not (math.isfinite(f_rot) and f_rot > 0):
        return None
    peak_hz = float(peaks[0])
    # the line is smeared by the speed's variation over the record (load pulses): the band covers
    # +-2 standard deviations of the speed at that order, and at least 3 frequency bins
    df = float(f[1] - f[0])
    half = max(3.0 * df, 2.0 * peak_hz * float(np.std(omega)) / max(float(np.mean(omega)), 1e-12))
    # the line's frequency between the bins: the centroid of the excess power over the model's mean
    sel = (f >= peak_hz - half) & (f <= peak_hz + half)
    w = np.maximum(meas_psd[sel] - ens_psd[:, sel].mean(axis=0), 0.0)
    line_hz = float(np.sum(f[sel] * w) / np.sum(w)) if np.sum(w) > 0 else peak_hz
    order = line_hz / f_rot
    if not ORDER_RANGE[0] <= order <= ORDER_RANGE[1]:
        return None
    lo, hi = line_hz - half, line_hz + half
    ens_band = _band_power(f, ens_psd, lo, hi)                 # one value per model seed
    base, noise = float(ens_band.mean()), float(ens_band.std(ddof=1))
    excess = float(_band_power(f, meas_psd, lo, hi)) - base
    z = excess / max(noise, 1e-300)
    if z < MIN_Z:
        return None
    fs = 1.0 / comp.meas.sample_period_s
    seeds = list(comp.seeds)[:REF_SEEDS]
    switch = {**comp.conditions, f"effects.{EFFECT}": True}

    def line_excess(amplitude_pu: float) -> np.ndarray:
        runs = plant_adapter.simulate_sets(
            comp.model, [{f"{EFFECT}.amplitude_pu": amplitude_pu, f"{EFFECT}.order": order}], seeds,
            comp.meas.n_samples, conditions=switch, signals=("a1",))
        return _band_power(f, analysis.welch_psd(runs["a1"][0], fs)[1], lo, hi) - ens_band[:len(seeds)]

    # A from the A^2 scaling of the line's power, from the reference; then once more from a simulation at
    # that A (the drive's response is not exactly linear in A: a strong ripple moves the speed)
    amplitude = REF_AMPLITUDE_PU
    for _ in range(2):
        ref = line_excess(amplitude)
        ref_mean = float(ref.mean())
        if not ref_mean > 0:
            return None
        amplitude = min(amplitude * math.sqrt(excess / ref_mean), 2.0)
    # uncertainty, propagated through A ~ sqrt(excess / ref): the measured line power's own uncertainty,
    # from its spread over BLOCKS time blocks of the record (the blocks as the independent units: the line's
    # power moves with the speed profile over the record, more than the model's seeds show), the band's
    # noise (its spread over the model's seeds) and the reference mean's spread over its seeds
    ref_rel = float(ref.std(ddof=1)) / ref_mean
    block_rel = _block_spread(comp.meas.signals["a1"], fs, lo, hi)
    rel = 0.5 * math.sqrt(block_rel ** 2 + (noise / excess) ** 2 + ref_rel ** 2 / len(ref))
    check = line_excess(amplitude)
    explained = 1.0 - abs(excess - float(check.mean())) / excess
    # confident: the fitted ripple reproduces the line within two of its uncertainties, inside the bounds
    tolerance = 2.0 * math.sqrt((block_rel * excess) ** 2 + noise ** 2 + float(check.var(ddof=1)))
    confident = bool(abs(excess - float(check.mean())) <= tolerance and amplitude < 2.0)
    return {"effect": EFFECT,
            "parameters": {"amplitude_pu": amplitude, "order": order},
            "uncertainty": {"amplitude_pu": amplitude * rel,
                            "order": 0.5 * df / f_rot},          # half a frequency bin of the line
            "not_identifiable": ["phase_rad"],
            "line_hz": line_hz, "rotation_hz": f_rot, "band_hz": [lo, hi],
            "line_over_model": float(excess / max(base, 1e-300)) + 1.0, "line_z": z,
            "explained_fraction": float(explained), "confident": confident,
            "method": "raw a1 spectrum (Welch), the line's excess power over the model ensemble; amplitude "
                      "from its A^2 scaling (a reference simulation and one correction, common random "
                      "numbers), order = line frequency (excess centroid) / rotation frequency; independent "
                      "units: the model's seeds for the band's noise, 4 time blocks of the record for the "
                      "line's own power"}


def as_discovery(fit: dict) -> dict:
    """The ripple fit in the form of diagnose's fitted candidates (``discovery_parameters``,
    ``second_effect``): effect, candidate, parameters, uncertainty, nominal, units, explained_fraction,
    indistinguishable_from, ... (nominal values, units and description: the catalogue effect's own).
    ``delta_ic`` is None: its evidence is the spectral line (``line_z``), not the event-average
    information criterion."""
    from backlash_monitor.plant import effects as plant_effects
    effect = plant_effects.catalogue()[EFFECT]
    fitted = [p for p in effect.parameters if p.name in fit["parameters"]]
    return {"effect": EFFECT, "candidate": EFFECT,
            "parameters": dict(fit["parameters"]), "uncertainty": dict(fit["uncertainty"]),
            "nominal": {p.name: float(p.default) for p in fitted}, "units": {p.name: p.unit for p in fitted},
            "delta_ic": None, "explained_fraction": fit["explained_fraction"], "indistinguishable_from": [],
            "at_bound": False, "not_identifiable": list(fit["not_identifiable"]),
            "evidence": "raw a1 spectrum", "line_hz": fit["line_hz"], "line_z": fit["line_z"],
            "description": effect.description}


def describe(fit: dict) -> str:
    p, u = fit["parameters"], fit["uncertainty"]
    return (f"the raw a1 spectrum has a line at {fit['line_hz']:.0f} Hz ({fit['line_over_model']:.1f} x the "
            f"model's power there, {fit['line_z']:.0f} x its seed-to-seed spread) that the event average "
            f"cannot show: {EFFECT} of order {p['order']:.2f} (x the {fit['rotation_hz']:.1f} Hz rotation) with "
            f"amplitude_pu = {p['amplitude_pu']:.3g} +- {u['amplitude_pu']:.2g} explains "
            f"{100 * fit['explained_fraction']:.0f} % of it (its phase is not identifiable from a spectrum)")
