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

5. locked to the motor angle (`locking`): only a line that is an integer order of the rotation, within its
   uncertainty, and that follows the rotation speed through the record is a torque ripple. The record is resampled
   at equal steps of the motor angle (alpha1 = the integral of omega1: computed order tracking); in that angle
   domain a locked line is one sharp line at an integer order, while a line at a fixed frequency (a structural
   vibration, another machine) lands at a non-integer order and is smeared by the speed's variation; the
   concentration of the line's excess power in the angle domain is compared with the time domain's.

The phase is not identifiable from a power spectrum (reported as such). Docs: docs/workbench.md
"Torque ripple: the spectral fit".
"""
from __future__ import annotations

import math

import numpy as np

from . import analysis, plant_adapter
from backlash_monitor.plant.catalogue import builtin_catalogue

EFFECT = "torque_ripple"
REF_AMPLITUDE_PU = 0.3
LINE_FACTOR = 2.0              # the measured PSD over the ensemble's largest: a line
MIN_Z = 5.0                    # the line's excess over the band's spread across the model's seeds
ORDER_RANGE = (0.5, 50.0)      # the effect's orders (bounds 0..50; below 0.5 the line is at DC)
REF_SEEDS = 3                  # seeds of the reference and check simulations (common random numbers)
BLOCKS = 4                     # time blocks of the record for the measured line power's uncertainty
SAMPLES_PER_REV = 2048         # the angle domain's resampling (about the samples of one revolution at 50 kHz)
ORDER_TOLERANCE = 0.02         # an integer order within max(this, 3 uncertainties) (measured on own ripples of
                               # orders 1-15: within 0.003 of the integer; fixed lines 107/148/250 Hz: 0.15-0.44 off)
LINE_BAND = 0.03               # the line's band for the concentration: +-3 % of its order (the speed's spread +-1 %)
CONCENTRATION_MARGIN = 0.05    # locked: the angle domain's concentration >= the time domain's - this


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
    lock = locking(comp, line_hz, f_rot)
    line = {"line_hz": line_hz, "rotation_hz": f_rot, "band_hz": [lo, hi],
            "line_over_model": float(excess / max(base, 1e-300)) + 1.0, "line_z": z, "locking": lock,
            "locked": bool(lock["locked"])}
    if not lock["locked"]:
        return {"effect": EFFECT, "parameters": None, "uncertainty": None, "confident": False,
                "explained_fraction": 0.0, "order_time_domain": order, **line}
    order = float(lock["integer_order"])
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
            "uncertainty": {"amplitude_pu": amplitude * rel, "order": float(lock["order_uncertainty"])},
            "not_identifiable": ["phase_rad"], **line,
            "explained_fraction": float(explained), "confident": confident,
            "method": "raw a1 spectrum (Welch), the line's excess power over the model ensemble; amplitude "
                      "from its A^2 scaling (a reference simulation and one correction, common random "
                      "numbers), order = the integer order of the line in the angle domain (computed order "
                      "tracking on omega1); independent units: the model's seeds for the band's noise, 4 time "
                      "blocks of the record for the line's own power and its order"}


def _angle_spectrum(a1, omega1, fs):
    """Order spectrum of a1 resampled at equal steps of the motor angle: (orders, power, revolutions)."""
    om = np.asarray(omega1, dtype=float)
    alpha = np.concatenate([[0.0], np.cumsum(0.5 * (om[1:] + om[:-1]) / fs)])
    if not np.all(np.diff(alpha) > 0):
        return None
    grid = np.arange(0.0, alpha[-1], 2.0 * math.pi / SAMPLES_PER_REV)
    y = np.interp(grid, alpha, np.asarray(a1, dtype=float))
    y = y - y.mean()
    p = np.abs(np.fft.rfft(y * np.hanning(len(y)))) ** 2
    return np.fft.rfftfreq(len(y), 1.0 / SAMPLES_PER_REV), p, alpha[-1] / (2.0 * math.pi)


def _time_spectrum(a1, fs):
    x = np.asarray(a1, dtype=float)
    x = x - x.mean()
    return np.fft.rfftfreq(len(x), 1.0 / fs), np.abs(np.fft.rfft(x * np.hanning(len(x)))) ** 2


def _concentration(xx, p, p_model, centre):
    """Share of the line's excess power (over the model's) in +-LINE_BAND of ``centre`` that lies within 2 bins
    of its largest bin; and the excess centroid."""
    sel = (xx > centre * (1 - LINE_BAND)) & (xx < centre * (1 + LINE_BAND))
    ex = np.maximum(p[sel] - p_model[sel], 0.0)
    if not np.any(ex > 0):
        return 0.0, float(centre)
    k = int(np.argmax(ex))
    return float(ex[max(k - 2, 0):k + 3].sum() / ex.sum()), float(np.sum(xx[sel] * ex) / ex.sum())


def locking(comp, line_hz: float, f_rot: float) -> dict:
    """Is the line at ``line_hz`` locked to the motor angle? Its order in the angle domain (the excess centroid
    over the model's runs, resampled alike) and that order's uncertainty from BLOCKS time blocks; its
    concentration in the angle and in the time domain. Locked: an integer order within max(ORDER_TOLERANCE,
    3 uncertainties), and the angle domain at least as concentrated as the time domain (a line that follows the
    speed is sharp in the angle domain; one at a fixed frequency is sharp in time)."""
    fs = 1.0 / comp.meas.sample_period_s
    sig = comp.meas.signals
    if "omega1" not in sig:
        return {"locked": False, "why": "the recording has no motor speed (omega1): the line's locking to the motor "
                                        "angle cannot be checked"}
    rec = comp.ensemble.raw_records
    meas_a = _angle_spectrum(sig["a1"], sig["omega1"], fs)
    if meas_a is None:
        return {"locked": False, "why": "the motor angle does not increase through the record"}
    o, pa, revs = meas_a
    model_a = [_angle_spectrum(a, w, fs) for a, w in zip(rec["a1"], rec["omega1"])]
    pa_m = np.mean([np.interp(o, m[0], m[1]) for m in model_a if m is not None], axis=0)
    f, pt = _time_spectrum(sig["a1"], fs)
    pt_m = np.mean([np.interp(f, *_time_spectrum(a, fs)) for a in rec["a1"]], axis=0)
    conc_a, order = _concentration(o, pa, pa_m, line_hz / f_rot)
    conc_t, _ = _concentration(f, pt, pt_m, line_hz)
    # the order's uncertainty: its spread over the record's time blocks (each resampled alike)
    n = len(sig["a1"]) // BLOCKS
    blocks = []
    for b in range(BLOCKS):
        sl = slice(b * n, (b + 1) * n)
        mb = _angle_spectrum(sig["a1"][sl], sig["omega1"][sl], fs)
        mm = [_angle_spectrum(a[sl], w[sl], fs) for a, w in zip(rec["a1"], rec["omega1"])]
        if mb is None or any(m is None for m in mm):
            continue
        pm = np.mean([np.interp(mb[0], m[0], m[1]) for m in mm], axis=0)
        blocks.append(_concentration(mb[0], mb[1], pm, order)[1])
    unc = float(np.std(blocks, ddof=1) / math.sqrt(len(blocks))) if len(blocks) > 1 else float("nan")
    k = int(round(order))
    tol = max(ORDER_TOLERANCE, 3.0 * unc) if math.isfinite(unc) else ORDER_TOLERANCE
    integer = k >= 1 and abs(order - k) <= tol
    follows = conc_a >= conc_t - CONCENTRATION_MARGIN
    why = ("locked: integer order" if integer and follows else
           f"order {order:.3f} is not an integer within {tol:.3f}" if not integer else
           f"the line does not follow the rotation speed (its power is more concentrated in time, {conc_t:.2f}, "
           f"than in the motor angle, {conc_a:.2f})")
    return {"locked": bool(integer and follows), "order_angle_domain": order, "order_uncertainty": unc,
            "integer_order": k, "order_tolerance": tol, "concentration_angle_domain": conc_a,
            "concentration_time_domain": conc_t, "revolutions": float(revs), "why": why}


def as_discovery(fit: dict) -> dict:
    """The ripple fit in the form of diagnose's fitted candidates (``discovery_parameters``,
    ``second_effect``): effect, candidate, parameters, uncertainty, nominal, units, explained_fraction,
    indistinguishable_from, ... (nominal values, units and description: the catalogue effect's own).
    ``delta_ic`` is None: its evidence is the spectral line (``line_z``), not the event-average
    information criterion."""
    effect = builtin_catalogue()[EFFECT]          # a built-in effect: in every model's catalogue
    fitted = [p for p in effect.parameters if p.name in fit["parameters"]]
    return {"effect": EFFECT, "candidate": EFFECT,
            "parameters": dict(fit["parameters"]), "uncertainty": dict(fit["uncertainty"]),
            "nominal": {p.name: float(p.default) for p in fitted}, "units": {p.name: p.unit for p in fitted},
            "delta_ic": None, "explained_fraction": fit["explained_fraction"], "indistinguishable_from": [],
            "at_bound": False, "not_identifiable": list(fit["not_identifiable"]),
            "evidence": "raw a1 spectrum", "line_hz": fit["line_hz"], "line_z": fit["line_z"],
            "description": effect.description}


def describe_not_locked(fit: dict) -> str:
    """A line in the raw a1 spectrum that is not a torque ripple: why, and what it may be."""
    lock = fit.get("locking") or {}
    return (f"the raw a1 spectrum has a line at {fit['line_hz']:.0f} Hz ({fit['line_over_model']:.1f} x the model's "
            f"power there) that is not locked to the motor angle ({lock.get('why', 'not checked')}): not a torque "
            "ripple -- an effect outside the catalogue (a vibration at a fixed frequency?)")


def describe(fit: dict) -> str:
    p, u = fit["parameters"], fit["uncertainty"]
    return (f"the raw a1 spectrum has a line at {fit['line_hz']:.0f} Hz ({fit['line_over_model']:.1f} x the "
            f"model's power there, {fit['line_z']:.0f} x its seed-to-seed spread) that the event average "
            f"cannot show: {EFFECT} of order {p['order']:.2f} (x the {fit['rotation_hz']:.1f} Hz rotation) with "
            f"amplitude_pu = {p['amplitude_pu']:.3g} +- {u['amplitude_pu']:.2g} explains "
            f"{100 * fit['explained_fraction']:.0f} % of it (its phase is not identifiable from a spectrum)")
