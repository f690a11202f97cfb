"""The model reference: everything the workbench's consistency test needs for one model version, precomputed, so
that the live model watch simulates nothing (docs/model_watch.md).

``diagnose`` builds its comparison per recording: the model's K-seed noise ensemble under the recording's
conditions, the weights, the views (consistency.py: the whitened candidates' subspace of the event average, the raw
events' spectral shape, the record mean, and the noise directions outside the subspace) and the model-form
tolerance. A reference does the same once, when the model version is trained, with the workbench's own steps
(``diagnose.prepare`` and ``diagnose.screen_step`` on a recording the model makes of itself), and keeps what the
test needs:

- the model's own onset events of the ensemble (raw segments, period means): the whitening and the views' noise;
- the screening Jacobians of every catalogue candidate (the directions the subspace is spanned by, and the
  model-form tolerance), the spectral block's as band powers of every stepped set;
- the model's prediction at a grid of backlash widths (``backlash_width_drift`` over its fit range, common
  random numbers): the width is the monitor's measurand, so a drive whose clutch wears is compared with the model
  at the width it has (profiled: the width that fits best in the fits' metric), not read as "the model no longer
  explains the drive";
- the model's whole-record spectrum above 12 kHz (the recording's sensor noise floor is read off against it) and
  its leave-one-seed-out deviations (where the residual sits: phase, wavelet level).

Two things depend on the recording and are applied when a reference is evaluated: the number of events E (the
noise of an E-event mean; the weights scale with sqrt(E)) and the sensor noise floor (the spectral block's
prediction and whitening include it, as diagnose's do). ``for_window(noise_psd, n_events)`` builds the views for them
as diagnose does (consistency.ConsistencyViews.from_screening on the stored screening Jacobians and the model's own
events); ``evaluate(evidence)`` runs ``consistency.test``.

File: ``LIB.watch.npz`` beside a pattern library (``train --model``), or the cache (.cache/watch/) for the default
model at a drive's nominal conditions. FORMAT_VERSION counts the layout; a file of another version is refused
with the command that rebuilds it.
"""
from __future__ import annotations

import hashlib
import json
import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from types import SimpleNamespace

import numpy as np
from scipy.special import chdtrc

from . import analysis, consistency, spectral, tolerance
from .events import (DC_BLOCKS, PRE_SAMPLES, POST_SAMPLES, SEGMENT_SIGNALS, Ensemble, EventSet, dc_block_deviations,
                     denoise, ensemble_from_runs, event_set)
from .events import dc_signals
from backlash_monitor.classifier.patterns import config_hash

FORMAT_VERSION = 4                 # 2: the record mean of a1, a2 and omega1 (diagnose's record-mean view on wb);
                                   # 3: the model's own events at every grid width (width-local whitening);
                                   # 4: the record mean's noise from RECORD_MEAN_SEEDS more seeds (3 is read too)
READ_VERSIONS = (3, 4)
RECORD_MEAN_SEEDS = 24             # more noise seeds of the model at its nominal width, for the record mean's noise
                                   # alone: its whitening is estimated from 6 seeds x (DC_BLOCKS - 1) = 18 degrees of
                                   # freedom in diagnose's ensemble, and the watch's alarm at p 1e-6 on 18 dof is T^2
                                   # 98.6 at 3 dimensions (chi^2 30.7); with 30 seeds, 90 dof: 37.3. ~1 s more
                                   # per build (docs/model_watch.md, "The record mean's noise")
RECORD_MEAN_SEED0 = 1_000_000      # their seeds: RECORD_MEAN_SEED0 + i (not the ensemble's 0..K-1 nor BUILD_SEED)
SUFFIX = ".watch.npz"              # LIB.npz -> LIB.watch.npz
BUILD_DURATION_S = 4.0             # the model's own recording the views are built on: 16 onset events per seed, the
                                   # 4 s recordings the workbench is measured on (docs/model_watch.md)
BUILD_SEED = 424_242               # its noise seed (not one of the ensemble's 0..K-1)
WIDTH_STEP = 0.025                 # the width grid's step, relative to the nominal width (docs/model_watch.md)
WIDTH_RANGE = 0.4                  # +-, relative: the fit range of backlash_width_drift (plant_adapter.FIT_RANGES)
WIDTH_EFFECT = "backlash_width_drift"
WIDTH_KEY = "backlash_width_drift.change"
CLIPPED_VIEWS = ("event_average",)     # evaluate(clip_p=...): the view whose odd single events decide windows of
                                       # the model's own drives (docs/model_watch.md). Not the record mean (its
                                       # units are blocks of events), nor the spectral shape: an effect there lies
                                       # along the model-form tolerance, and a bound set in the noise's metric
                                       # capped a 600 Hz a2 low-pass at T^2 14 (222 unclipped; never detected)
NOISE_SIGNIFICANT = 10.0           # the watch's sensor noise floor: measured noise-band level / the model's own (noise_floor)


class ReferenceError(ValueError):
    """A reference file that cannot be used (names the problem and the command that rebuilds it)."""


def reference_path_for_library(library_path) -> Path:
    """Where ``train --model ... --out LIB.npz`` writes the library's reference: LIB.watch.npz."""
    p = Path(library_path)
    name = p.name[:-4] if p.name.endswith(".npz") else p.name
    return p.with_name(name + SUFFIX)


# ------------------------------------------------------------------------------------------------ evidence

@dataclass
class Evidence:
    """The onset events a reference is evaluated on: raw segments (E, 2, L), their period means (E, 2), their raw
    spectral-shape features (E, n_features), the recording's sensor noise floor per signal [(m/s^2)^2/Hz], and the
    entries' sample indices (E,)."""
    raw: np.ndarray
    dc: np.ndarray
    spec: np.ndarray
    noise_psd: np.ndarray
    entries: np.ndarray
    dc_names: tuple = SEGMENT_SIGNALS     # the record-mean view's signals (events.dc_signals of the recording)
    denoised: np.ndarray | None = None    # (E, 2, L) each raw segment sym5-denoised (events.denoise), when the caller
                                          # has them (the live watch keeps each event's); else made when needed
    quant_step: np.ndarray | None = None  # per signal the recording's ADC step [m/s^2] (analysis.quantisation_step;
                                          # 0 or None: not quantised): the model's events are quantised at it

    @property
    def n_events(self) -> int:
        return int(len(self.entries))


def evidence_from_measurement(meas, reference: "ModelReference", last_n: int | None = None,
                              significant_noise: bool = False) -> Evidence:
    """The evidence of a recording as diagnose takes it (events.event_set, spectral.event_features, the sensor noise
    floor from the whole record's Welch spectrum against the model's); ``last_n``: only the last n events (the
    watch's window at the end of the recording); ``significant_noise``: the noise floor as the watch takes it
    (ModelReference.noise_floor)."""
    names = tuple(n for n in dc_signals(meas.signals) if n in reference.dc_names)
    ev = event_set(meas.signals, meas.sample_period_s, names)
    if ev.n_events == 0:
        raise ValueError(f"measurement {meas.source}: no complete onset event")
    sel = slice(None) if last_n is None else slice(max(ev.n_events - int(last_n), 0), None)
    quant = analysis.quantisation_steps(meas.signals)
    noise = reference.noise_floor({s: analysis.welch_psd(meas.signals[s], 1.0 / meas.sample_period_s)[1]
                                   for s in SEGMENT_SIGNALS}, significant=significant_noise, quant_step=quant)
    raw = ev.raw[sel]
    return Evidence(raw, ev.dc[sel], spectral.event_features(raw, meas.sample_period_s), noise, ev.entries[sel],
                    names, quant_step=quant if np.any(quant > 0) else None)


# ------------------------------------------------------------------------------------------------ evaluation

@dataclass
class Evaluation:
    """One evaluation of a reference on evidence (E events)."""
    result: consistency.ConsistencyResult      # at the profiled width (the test diagnose runs)
    width_m: float                             # the profiled backlash width (the measurand)
    residual_over_noise: dict                  # per signal: rms(measured mean - model mean) / the E-event noise floor
    where: dict | None                         # analysis.where: per phase and wavelet level; dominant_phase/_level
    n_events: int
    noise_psd: np.ndarray
    nominal_width_m: float
    model_mean: np.ndarray | None = field(default=None, repr=False)   # (2, L) at width_m, denoised
    model_raw: np.ndarray | None = field(default=None, repr=False)    # (2, L) raw
    weights: np.ndarray | None = field(default=None, repr=False)      # (2,) the E-event weights
    position: float | None = None          # the width's fractional index in the grid (None: the nominal width)

    @property
    def consistent(self) -> bool:
        return self.result.consistent

    def p_values(self) -> dict:
        """Per view: the chance of a T^2 this large from the model's own noise (chi^2 of the view's dimension)."""
        return {n: float(chdtrc(v.dimension, v.t2)) for n, v in self.result.views.items()}

    def to_json(self) -> dict:
        return {"consistent": self.consistent, "n_events": self.n_events, "width_m": self.width_m,
                "nominal_width_m": self.nominal_width_m,
                "residual_over_noise": dict(self.residual_over_noise),
                "residual_over_noise_overall": self.result.residual_over_noise,
                "views": {n: v.to_json() | {"p": p} for (n, v), p in
                          zip(self.result.views.items(), self.p_values().values())},
                "noise_psd_m2_s4_per_hz": dict(zip(SEGMENT_SIGNALS, map(float, self.noise_psd))),
                "where": None if self.where is None else {"dominant_phase": self.where["dominant_phase"],
                                                          "dominant_level": self.where["dominant_level"]}}


class WindowReference:
    """The reference for one window's (noise floor, number of events): what fitting.Problem is to diagnose -- the
    prediction vector's slices and weights, the model's predictions at the width grid -- and the views the
    consistency test looks in (``views``: consistency.ConsistencyViews, built from the reference's screening as
    diagnose's screen_step builds them). Made by ModelReference.for_window."""

    def __init__(self, ref: "ModelReference", noise_psd, n_events: int, dc_names=SEGMENT_SIGNALS, quant_step=None):
        self.noise_psd = np.asarray(noise_psd, dtype=float)
        self.quant_step = None if quant_step is None or not np.any(np.asarray(quant_step) > 0) \
            else np.asarray(quant_step, dtype=float)
        self.dc_names = tuple(dc_names)                     # the record-mean view's signals (the evidence's)
        try:
            dc_idx = [ref.dc_names.index(n) for n in self.dc_names]
        except ValueError:
            raise ValueError(f"record-mean signals {self.dc_names}; this reference has "
                             f"{', '.join(ref.dc_names)}") from None
        seed_dc = [np.asarray(d)[:, dc_idx] for d in ref.seed_dc]
        more_dc = [np.asarray(d)[:, dc_idx] for d in ref.record_mean_dc]     # the record-mean seeds' (none: diagnose's)
        self.n_events = int(n_events)
        self.n_seeds = len(ref.seeds)
        self.n_event_coords = int(ref.base_mean.size)
        ns = spectral.n_features(len(SEGMENT_SIGNALS))
        self.event_slice = slice(0, self.n_event_coords)
        self.spectral_slice = slice(self.n_event_coords, self.n_event_coords + ns)
        self.dc_slice = slice(self.n_event_coords + ns, self.n_event_coords + ns + len(self.dc_names))
        dt = ref.sample_period_s
        scale = math.sqrt(self.n_events / ref.build_events)
        self.w = ref.weights * scale                            # 1 / the E-event noise floor of the event average
        self.floor_rms = 1.0 / self.w
        # the model's events through the recording's sensor chain (its white floor, its ADC's quantiser): diagnose's
        # (analysis.build_comparison)
        model_event_spec, chain = spectral.sensor_chain(ref.seed_events, dt, self.noise_psd, self.quant_step)
        feats = np.vstack(model_event_spec)
        self.ws = 1.0 / np.maximum(feats.std(axis=0) / math.sqrt(self.n_events), 1e-12)
        # the record mean's noise floor: diagnose's estimate (analysis.record_mean_floor) on the ensemble's seeds and
        # the record-mean seeds
        self.wdc = 1.0 / np.maximum(analysis.record_mean_floor(seed_dc + more_dc, self.n_events), 1e-12)
        self.spec_noise = chain if self.quant_step is not None \
            else spectral.noise_power(self.noise_psd, PRE_SAMPLES + POST_SAMPLES, dt)
        # the model's prediction at the nominal width and at every width of the grid
        self.base = self._pred(ref.base_mean, ref.base_bands, np.asarray(ref.base_dc)[dc_idx])
        self.grid = np.stack([self._pred(m, b, d[dc_idx])
                              for m, b, d in zip(ref.grid_mean, ref.grid_bands, ref.grid_dc)])
        self.target_vec = np.zeros_like(self.base)        # (its size: what tolerance.directions reads of it)
        # the screening Jacobians in this weighting: event and record-mean parts scale, the spectral part is taken
        # from the stepped sets' band powers with this noise floor
        base_spec = spectral.features_from_bands(ref.base_bands, self.spec_noise).mean(axis=0)
        cols = []
        for j in range(ref.jac_event.shape[0]):
            spec = (spectral.features_from_bands(ref.jac_bands[j], self.spec_noise).mean(axis=0) - base_spec) \
                / ref.jac_step[j]
            cols.append(np.concatenate([(ref.jac_event[j].reshape(self.w.size, -1) * self.w[:, None]).ravel(),
                                        spec * self.ws, ref.jac_dc[j][dc_idx] * self.wdc]))
        jac = np.stack(cols, axis=1)
        jacobians = {cand["name"]: jac[:, cand["columns"]] for cand in ref.candidates}
        comp = SimpleNamespace(ensemble=SimpleNamespace(per_event=ref.seed_events,
                                                        dc_samples=lambda k: seed_dc[k]),
                               weights=self.w, model_event_spec=model_event_spec)
        z_all = consistency.model_event_vectors(comp, self)
        # the record-mean seeds' block deviations: rows (in the record-mean coordinates) for that view's whitening only
        more = {"record_mean": (self.dc_slice, np.vstack([dc_block_deviations(d) for d in more_dc]) * self.wdc[None])
                } if more_dc else None
        # the noise directions outside the subspace come from the event average alone (not from the noise floor,
        # which only the spectral block sees): computed once per number of events (an SVD of K*E x 4596: ~0.5 s)
        self.views = consistency.ConsistencyViews.from_screening(self, jacobians, ref.candidate_objects(), z_all, more,
                                                                 ref._complements.get(self.n_events))
        ref._complements.setdefault(self.n_events, self.views.complement)
        # the noise realisation's effect on each model event's spectral features (noisy minus the noise's power
        # only): added to the events of the other widths, whose raw segments the reference does not keep
        f0 = spectral.features_from_bands(ref.base_bands, self.spec_noise) * self.ws - self.base[self.spectral_slice]
        self.realisation = z_all[:, self.spectral_slice] - f0
        self.ref = ref
        self._local: dict = {}
        self.grid_fit = self.grid @ self.views.fit_basis        # (G, q + P): the grid in the fits' metric
        self.profile_curves: dict = {}     # profile_width: per grid width g the cubic's points around it (81, q + P)

    def local_views(self, g: int) -> consistency.ConsistencyViews:
        """The views whitened by the model's own events at grid width ``g`` (the subspace and the complement's
        directions stay the nominal width's): what consistency.test reads, for a drive whose width moved. The
        whitening is consistency.whiten on the width's events projected on each block's directions (it is linear
        in the basis: whitening the coordinates is whitening the basis)."""
        out = self._local.get(g)
        if out is not None:
            return out
        ref, views = self.ref, self.views
        if ref.local_zev is None:
            return views
        scale = math.sqrt(self.n_events / ref.build_events)
        n = views.basis.shape[0]
        cols, blocks, q0 = [], [], 0
        for name, b in views.candidate_directions:
            q = b.shape[1]
            if q == 0:
                continue
            if name == "event_average":
                b = np.zeros((n, ref.local_event_basis.shape[1]))
                b[self.event_slice] = ref.local_event_basis
                q = b.shape[1]
                z = ref.local_zev[g] * scale
            elif name == "spectral_shape":
                feats = spectral.features_from_bands(ref.grid_bands[g], self.spec_noise) * self.ws \
                    - self.grid[g][self.spectral_slice]
                feats = feats + self.realisation[np.arange(len(feats)) % len(self.realisation)]
                z = feats @ b[self.spectral_slice]
            else:           # the record mean: the width barely moves its noise; the nominal whitening
                cols.append(views.basis[:, dict(views.blocks)[name]])
                blocks.append((name, slice(q0, q0 + q)))
                q0 += q
                continue
            t, _ = consistency.whiten([(name, np.eye(q))], z)
            cols.append(b @ t)
            blocks.append((name, slice(q0, q0 + q)))
            q0 += q
        basis = np.hstack(cols)
        tc, _ = consistency.whiten([("outside", np.eye(ref.local_complement.shape[1]))], ref.local_zc[g] * scale)
        out = consistency.ConsistencyViews(views.candidate_directions, basis, tuple(blocks),
                                           ref.local_complement @ tc, views.tolerance_directions, self.n_events,
                                           self.n_seeds, self.n_event_coords)
        if len(self._local) >= 8:
            self._local.pop(next(iter(self._local)))
        self._local[g] = out
        return out

    def _pred(self, mean_denoised, bands, dc) -> np.ndarray:
        return np.concatenate([(np.asarray(mean_denoised) * self.w[:, None]).ravel(),
                               spectral.features_from_bands(bands, self.spec_noise).mean(axis=0) * self.ws,
                               np.asarray(dc) * self.wdc])

    # what consistency.model_event_vectors reads of a fitting.Problem
    def pred_of(self, ens, i: int = 0) -> np.ndarray:
        return self.base

    def denoised_events(self, evidence: Evidence) -> np.ndarray:
        """(E, 2, L) every event's denoised segment (the evidence's own, else denoised here)."""
        if evidence.denoised is not None:
            return evidence.denoised
        return denoise(evidence.raw)

    def event_targets(self, evidence: Evidence) -> np.ndarray:
        """(E, N): each event's own measured vector; their mean is :meth:`target` (the denoising is linear). The
        weighted segments are written into the result (the same products, no (E, 2, L) temporary)."""
        dens = self.denoised_events(evidence)
        e, n = dens.shape[0], self.n_event_coords
        out = np.empty((e, self.dc_slice.stop))
        np.multiply(dens, self.w[None, :, None], out=np.reshape(out[:, :n], dens.shape, copy=False))
        np.multiply(evidence.spec, self.ws[None], out=out[:, self.spectral_slice])
        np.multiply(evidence.dc, self.wdc[None], out=out[:, self.dc_slice])
        return out

    def target(self, evidence: Evidence, denoised_mean: np.ndarray | None = None) -> np.ndarray:
        """The measured vector: the weighted denoised event average (``denoised_mean``: mean_denoised(evidence) when
        the caller has it), the mean spectral shape and record mean."""
        if denoised_mean is None:
            denoised_mean = mean_denoised(evidence)
        return np.concatenate([(denoised_mean * self.w[:, None]).ravel(),
                               evidence.spec.mean(axis=0) * self.ws, evidence.dc.mean(axis=0) * self.wdc])


@dataclass
class ModelReference:
    """A model version's precomputed reference (see the module doc). Arrays in SI units; weights per signal are
    1 / the noise floor of a ``build_events``-event average [(m/s^2)^-1]."""
    meta: dict                      # model label and content, seeds, conditions, build settings, candidates
    sample_period_s: float
    seeds: list
    build_events: int               # events per seed of the build recording (E_ref)
    weights: np.ndarray             # (2,) 1 / the event-average noise floor at build_events
    seed_events: list               # per seed: (E_k, 2, L) raw onset segments of the model's own runs
    seed_dc: list                   # per seed: (E_k, D) their period means of dc_names [m/s^2, rad/s]
    seed_means: np.ndarray          # (K, 2, L) raw event average per seed (noise floor, where)
    base_mean: np.ndarray           # (2, L) the model's denoised event average at the nominal width
    base_raw: np.ndarray            # (2, L) raw
    base_bands: np.ndarray          # (K*E, 2, n_bands) band powers of every model event (spectral.band_powers)
    base_dc: np.ndarray             # (D,) mean period means
    jac_event: np.ndarray           # (n_cols, 2*L) d(denoised event average)/d(parameter), unweighted
    jac_dc: np.ndarray              # (n_cols, D) d(record mean)/d(parameter)
    jac_bands: list                 # per column: (E_j, 2, n_bands) band powers at the stepped set
    jac_step: np.ndarray            # (n_cols,) the step [parameter unit]
    candidates: list                # [{name, effect, keys, lower, upper, default, columns}]
    widths_m: np.ndarray            # (G,) the width grid [m]
    grid_mean: np.ndarray           # (G, 2, L) denoised event average per width
    grid_raw: np.ndarray            # (G, 2, L) raw
    grid_bands: list                # per width: (E_g, 2, n_bands)
    grid_dc: np.ndarray             # (G, D)
    noise_band_psd: np.ndarray      # (2, F) the model's whole-record Welch PSD (mean over seeds)
    noise_band_f: np.ndarray        # (F,) its frequencies [Hz]
    # the model's own events at every grid width, projected on the nominal views' directions (width-local
    # whitening, WindowReference.local_views): the event-average block's directions (N_ev, q), the complement's unit
    # directions (N_ev, P), per width the events' coordinates in them (weights of build_events)
    local_event_basis: np.ndarray | None = None
    local_complement: np.ndarray | None = None
    local_zev: list | None = None
    local_zc: list | None = None
    record_mean_dc: list = field(default_factory=list)   # per extra seed (RECORD_MEAN_SEEDS): (E_k, D) the model's
                                                         # period means at the nominal width, for the record mean's
                                                         # noise (its floor and whitening) beside seed_dc's
    path: Path | None = None
    _windows: dict = field(default_factory=dict, repr=False)
    _complements: dict = field(default_factory=dict, repr=False)
    _profile_points: dict = field(default_factory=dict, repr=False)   # profile_width's positions per grid width

    # -------------------------------------------------------------------------------------------- identity
    @property
    def model_label(self) -> str:
        return self.meta["model_label"]

    @property
    def nominal_width_m(self) -> float:
        return float(self.meta["nominal"]["width_m"])

    @property
    def pulse_period_samples(self) -> int:
        return int(self.meta["pulse_period_samples"])

    @property
    def dc_names(self) -> tuple:
        """The record-mean view's signals of the build recording (a1, a2 and omega1: the model records them all);
        a window's evidence uses those of them it has (diagnose: events.dc_signals of the recording)."""
        return tuple(self.meta.get("dc_names", SEGMENT_SIGNALS))

    def candidate_objects(self) -> dict:
        """The candidates as plant_adapter.CandidateEffect (what tolerance.py reads)."""
        # deferred: the simulator (numba, scipy.optimize) costs ~600 ms at start-up (python -X importtime, 29 Nov)
        from .plant_adapter import CandidateEffect, EffectParameter
        out = {}
        for c in self.candidates:
            params = tuple(EffectParameter(k.split(".", 1)[1], "", d, lo, hi, k)
                           for k, d, lo, hi in zip(c["keys"], c["default"], c["lower"], c["upper"]))
            out[c["name"]] = CandidateEffect(c["name"], c["effect"], "", "", params)
        return out

    # -------------------------------------------------------------------------------------------- views
    def noise_floor(self, measured_psd: dict, significant: bool = False, quant_step=None) -> np.ndarray:
        """The sensor noise floor per signal from measured whole-record Welch PSDs ({signal: PSD on
        analysis.welch_psd's bins}) against the model's: analysis.sensor_noise_floor (diagnose's estimate). With
        ``significant`` (the watch) a signal's floor counts only where the measured level in the noise band is
        NOISE_SIGNIFICANT times the model's own: below that the excess is the model's own level wandering from
        recording to recording (measured on clean own drives: a2's excess 1e-15..2.5e-15 (m/s^2)^2/Hz against a
        model level of ~3e-15 at 10 mm, and the spectral view at T^2 66 against its limit 16.8 when it was taken
        as a sensor's; a real sensor chain's floor is orders above: a 16-bit ADC over +-4 g alone 5e-12)."""
        spectra = {s: {"f": self.noise_band_f, "measured": np.asarray(measured_psd[s], dtype=float),
                       "ensemble": self.noise_band_psd[i][None]} for i, s in enumerate(SEGMENT_SIGNALS)}
        # ``quant_step``: per signal the ADC's step (analysis.quantisation_steps): the floor is the white noise before
        # the quantiser (analysis.sensor_noise_floor)
        floor = analysis.sensor_noise_floor(spectra, None, self.sample_period_s, quant_step)
        if significant:
            sel = (self.noise_band_f >= analysis.NOISE_BAND_HZ[0]) & (self.noise_band_f <= analysis.NOISE_BAND_HZ[1])
            model = np.median(self.noise_band_psd[:, sel], axis=1)
            floor = np.where(floor > (NOISE_SIGNIFICANT - 1.0) * model, floor, 0.0)
        return floor

    def for_window(self, noise_psd, n_events: int, dc_names=SEGMENT_SIGNALS, quant_step=None) -> WindowReference:
        """The reference for a window's sensor noise floor (per signal [(m/s^2)^2/Hz]), number of events, record-mean
        signals and ADC steps (cached: the last 8)."""
        quant = () if quant_step is None or not np.any(np.asarray(quant_step) > 0) \
            else tuple(float(x) for x in np.asarray(quant_step, dtype=float))
        key = (tuple(float(x) for x in np.asarray(noise_psd, dtype=float)), int(n_events), tuple(dc_names), quant)
        v = self._windows.get(key)
        if v is None:
            if len(self._windows) >= 8:
                self._windows.clear()
            v = self._windows[key] = WindowReference(self, noise_psd, n_events, dc_names, quant or None)
        return v

    # -------------------------------------------------------------------------------------------- evaluation
    def profile_width(self, window: WindowReference, target: np.ndarray) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
        """The width whose prediction fits the target best in the fits' metric (fitting.Problem.project: the
        whitened subspace and the noise outside it), the predictions cubic between the grid's widths (Lagrange
        through the four nearest: the event average moves with the width by a shift of the far-side impact, ~17
        samples per 2.5 % at 5 mm; linear interpolation left T^2 of 27 against 4-9 at the grid points around a
        5.8 mm drive). -> (width [m], prediction, denoised model mean (2, L), raw model mean (2, L))."""
        t = window.views.fit_basis.T @ target
        grid = window.grid_fit
        n = len(self.widths_m)
        cost = np.einsum("ij,ij->i", t[None, :] - grid, t[None, :] - grid)
        g = int(np.argmin(cost))
        # the cubic between the neighbours of the best grid width, on 1/40 of a step (0.06 % of the nominal
        # width), then a parabola through the best three of those
        points = self._profile_points.get((g, n))
        if points is None:          # depend on g and the grid only: made once per grid width
            xs = np.linspace(max(g - 1, 0), min(g + 1, n - 1), 81)
            points = self._profile_points[(g, n)] = (xs, *_lagrange_many(xs, n))    # (81, 4) each
        xs, idx, w = points
        curve = window.profile_curves.get(g)
        if curve is None:           # the grid's predictions at those points: per window and g, not per target
            curve = window.profile_curves[g] = np.einsum("xk,xkq->xq", w, grid[idx])
        r = t[None, :] - curve
        costs = np.einsum("xq,xq->x", r, r)
        i = int(np.argmin(costs))
        best = float(xs[i])
        if 0 < i < len(xs) - 1:
            c0, c1, c2 = costs[i - 1:i + 2]
            den = c0 - 2 * c1 + c2
            if den > 0:
                best += 0.5 * (c0 - c2) / den * (xs[1] - xs[0])
        self._last_position = best
        idx, w = _lagrange(best, n)
        return (float(w @ self.widths_m[idx]), w @ window.grid[idx], np.tensordot(w, self.grid_mean[idx], 1),
                np.tensordot(w, self.grid_raw[idx], 1))

    def view_dof(self) -> dict:
        """Per view: the degrees of freedom of the covariance its whitening is estimated from (the model's K x E
        own events; the record mean's from its K (+ the record-mean seeds) x DC_BLOCKS block means less the seeds'
        means) -- what
        consistency.predictive_t2_isf needs for the view's honest tail."""
        n = len(self.seeds) * self.build_events
        return {"event_average": n - 1, "spectral_shape": n - 1, "outside": n - 1,
                "record_mean": (len(self.seeds) + len(self.record_mean_dc)) * (DC_BLOCKS - 1)}

    def clip_radius(self, views: consistency.ConsistencyViews, clip_p: float) -> dict:
        """Per clipped view: the length of one event's whitened deviation that the model's own events exceed with
        probability ``clip_p`` (consistency.predictive_t2_isf of one event against the n-event model mean)."""
        dof = self.view_dof()
        n = len(self.seeds) * self.build_events
        return {name: math.sqrt((1.0 + 1.0 / n) * consistency.predictive_t2_isf(clip_p, sl.stop - sl.start,
                                                                                  dof[name]))
                for name, sl in views.blocks if name in CLIPPED_VIEWS}

    def evaluate(self, evidence: Evidence, profile_width: bool = True, where: bool = True,
                 clip_p: float | None = None) -> Evaluation:
        """The consistency test (consistency.test: diagnose's) of ``evidence`` against the model; with
        ``profile_width`` at the width that fits best (the measurand), else at the model's nominal width.

        ``clip_p`` (the live watch): in the event average (CLIPPED_VIEWS) each event's whitened deviation counts at
        most at the length the model's own events exceed with that probability (consistency.clipped_mean:
        Huber's bounded influence; docs/model_watch.md, "The alarm rule"); when that clips an event the width is
        profiled again on the clipped evidence. None: the plain mean, diagnose's test to the last digit."""
        if evidence.n_events < 1:
            raise ValueError("no onset event to evaluate")
        window = self.for_window(evidence.noise_psd, evidence.n_events, evidence.dc_names, evidence.quant_step)
        plain_mean = mean_denoised(evidence)          # the target's, and the residual ratio's when nothing is clipped
        target = window.target(evidence, plain_mean)
        if profile_width:
            width, pred, mean, raw = self.profile_width(window, target)
            position = self._last_position
            tested = window.local_views(int(round(position)))     # whitened by the model's events at that width
        else:
            width, pred, mean, raw = self.nominal_width_m, window.base, self.base_mean, self.base_raw
            position = None
            tested = window.views
        residuals, radius, weights, coords = None, None, None, None
        if clip_p is not None:
            events = window.event_targets(evidence)
            radius = self.clip_radius(tested, clip_p)
            residuals = events - pred[None]
            weights, coords = _event_weights(tested, residuals, radius)
            if profile_width and np.any(weights < 1.0):
                # the width the clipped evidence fits (an odd event pulls the plain mean's width too)
                width, pred, mean, raw = self.profile_width(window, pred + (weights[:, None] * residuals).mean(0))
                position = self._last_position
                tested = window.local_views(int(round(position)))
                radius = self.clip_radius(tested, clip_p)
                residuals = events - pred[None]
                weights, coords = _event_weights(tested, residuals, radius)
        # the events' event-average coordinates _event_weights projected are the test's (same residuals, same basis)
        result = consistency.test(tested, target - pred, event_residuals=residuals, clip_radius=radius,
                                  event_coords=coords)
        if weights is not None and np.any(weights < 1.0):
            dens = window.denoised_events(evidence)
            measured = mean + (weights[:, None, None] * (dens - mean[None])).mean(axis=0)
        else:
            measured = plain_mean
        ratio = np.sqrt(np.mean((measured - mean) ** 2, axis=-1)) / window.floor_rms
        out = Evaluation(result, width, dict(zip(SEGMENT_SIGNALS, map(float, ratio))), None, evidence.n_events,
                         np.asarray(evidence.noise_psd, dtype=float), self.nominal_width_m, mean, raw, window.w,
                         position)
        if where:
            out.where = self.where(evidence, out)
        return out

    def leave_one_out(self, evidence: Evidence, evaluation: Evaluation, clip_p: float | None = None) -> list:
        """consistency.test of the window without each one of its events in turn (E - 1 events), each at the width
        that fits it (an odd event moves the width too): [ConsistencyResult] per left-out event. The watch's alarm
        asks that the evidence not hinge on one event (watch/alarm.py: one odd event stays in N consecutive
        windows)."""
        n = evidence.n_events
        if n < 4:
            return []
        out = []
        for e in range(n):
            keep = np.arange(n) != e
            sub = Evidence(evidence.raw[keep], evidence.dc[keep], evidence.spec[keep], evidence.noise_psd,
                           evidence.entries[keep], evidence.dc_names,
                           None if evidence.denoised is None else evidence.denoised[keep], evidence.quant_step)
            out.append(self.evaluate(sub, profile_width=evaluation.position is not None, where=False,
                                     clip_p=clip_p).result)
        return out

    def where(self, evidence: Evidence, evaluation: Evaluation) -> dict:
        """Where the residual of an evaluation sits (per phase and sym5 level): analysis.where on a comparison made
        of the reference (the model's seeds) and the evidence, at the evaluation's width."""
        k = self.seed_means.shape[0]
        ens = Ensemble(self.seed_means[None], np.full((1, k), self.build_events), [])
        comp = analysis.Comparison(None, SimpleNamespace(sample_period_s=self.sample_period_s), {}, list(self.seeds),
                                   EventSet(evidence.raw, evidence.entries), ens, evaluation.weights,
                                   1.0 / evaluation.weights)
        return analysis.where(comp, evaluation.model_mean, evaluation.model_raw)

    # -------------------------------------------------------------------------------------------- files
    def save(self, path) -> Path:
        """Write the reference (npz, no pickles); an existing file is replaced only once the new one is complete."""
        p = Path(path)
        arrays = {"format_version": np.array(FORMAT_VERSION), "meta": np.array(json.dumps(self.meta)),
                  "sample_period_s": np.array(self.sample_period_s), "seeds": np.array(self.seeds),
                  "build_events": np.array(self.build_events), "weights": self.weights,
                  "seed_means": self.seed_means, "base_mean": self.base_mean, "base_raw": self.base_raw,
                  "base_bands": self.base_bands, "base_dc": self.base_dc, "jac_event": self.jac_event,
                  "jac_dc": self.jac_dc, "jac_step": self.jac_step, "widths_m": self.widths_m,
                  "grid_mean": self.grid_mean, "grid_raw": self.grid_raw, "grid_dc": self.grid_dc,
                  "noise_band_psd": self.noise_band_psd, "noise_band_f": self.noise_band_f}
        arrays["local_event_basis"] = self.local_event_basis
        arrays["local_complement"] = self.local_complement
        for name, parts in (("seed_events", self.seed_events), ("seed_dc", self.seed_dc),
                            ("jac_bands", self.jac_bands), ("grid_bands", self.grid_bands),
                            ("local_zev", self.local_zev), ("local_zc", self.local_zc),
                            ("record_mean_dc", self.record_mean_dc)):
            if not parts:
                arrays[name] = np.zeros((0, len(self.dc_names)))
                arrays[name + "_counts"] = np.zeros(0, dtype=int)
                continue
            arrays[name] = np.concatenate(parts, axis=0)
            arrays[name + "_counts"] = np.array([len(x) for x in parts])
        tmp = p.with_name(p.name + f".partial{os.getpid()}")
        with open(tmp, "wb") as f:
            np.savez_compressed(f, **arrays)
        os.replace(tmp, p)
        self.path = p
        return p


def mean_denoised(evidence: Evidence) -> np.ndarray:
    """(2, L) the denoised event average: the mean of the events' own denoised segments where the evidence has them
    (the live watch denoises each event once; the denoising is linear, so this is the denoised mean to rounding),
    else the denoised mean of the raw segments (diagnose's)."""
    if evidence.denoised is not None:
        return evidence.denoised.mean(axis=0)
    return denoise(evidence.raw.mean(axis=0))


def _event_weights(problem, residuals: np.ndarray, radius: dict) -> tuple[np.ndarray, dict]:
    """Each event's weight in the event-average view's clipped mean (consistency.clipped_mean): 1 inside the
    radius; and the events' coordinates it is computed from ({"event_average": (E, q)}: consistency.test's
    ``event_coords``)."""
    sl = dict(problem.blocks)["event_average"]
    u = residuals @ problem.basis[:, sl]
    return consistency.clipped_mean(u, radius["event_average"])[1], {"event_average": u}


def _lagrange(position: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(indices, weights) of the cubic Lagrange interpolation at fractional grid ``position`` through the four
    nearest of ``n`` equally spaced points (three or two at a short grid's edge)."""
    k = min(max(int(math.floor(position)) - 1, 0), max(n - 4, 0))
    idx = np.arange(k, min(k + 4, n))
    x = position - idx
    w = np.array([np.prod([(position - j) / (i - j) for j in idx if j != i]) for i in idx])
    return idx, w if np.all(np.isfinite(w)) else (x == 0).astype(float)


def _lagrange_many(positions: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """_lagrange for many positions at once: (indices (m, 4), weights (m, 4)); a grid of n >= 4 points."""
    pos = np.asarray(positions, dtype=float)
    k = np.clip(np.floor(pos).astype(int) - 1, 0, n - 4)
    idx = k[:, None] + np.arange(4)[None, :]
    w = np.ones_like(idx, dtype=float)
    for i in range(4):
        for j in range(4):
            if i != j:
                w[:, i] *= (pos - idx[:, j]) / (idx[:, i] - idx[:, j])
    return idx, w


def _split(arr: np.ndarray, counts: np.ndarray) -> list:
    return np.split(arr, np.cumsum(counts)[:-1]) if len(counts) else []


def load(path) -> ModelReference:
    """A reference file; ReferenceError (naming the file, the problem and the rebuild command) when it cannot be
    used."""
    p = Path(path)
    rebuild = ("rebuild it with `python -m backlash_monitor train --model M.yaml --out LIB.npz` (writes "
               "LIB.watch.npz) or `python -m backlash_monitor watch-reference`")
    if not p.is_file():
        raise ReferenceError(f"model reference {str(p)!r} does not exist; {rebuild}")
    try:
        with np.load(p, allow_pickle=False) as z:
            version = int(z["format_version"]) if "format_version" in z.files else None
            if version not in READ_VERSIONS:
                raise ReferenceError(f"model reference {p} has format version {version}; this code reads "
                                     f"{', '.join(map(str, READ_VERSIONS))}; {rebuild}")
            d = {k: z[k] for k in z.files}
    except ReferenceError:
        raise
    except (OSError, ValueError, KeyError) as exc:
        raise ReferenceError(f"model reference {p} cannot be read ({exc}); {rebuild}") from None
    meta = json.loads(str(d["meta"]))
    return ModelReference(
        meta=meta, sample_period_s=float(d["sample_period_s"]), seeds=[int(s) for s in d["seeds"]],
        build_events=int(d["build_events"]), weights=d["weights"],
        seed_events=_split(d["seed_events"], d["seed_events_counts"]),
        seed_dc=_split(d["seed_dc"], d["seed_dc_counts"]), seed_means=d["seed_means"], base_mean=d["base_mean"],
        base_raw=d["base_raw"], base_bands=d["base_bands"], base_dc=d["base_dc"], jac_event=d["jac_event"],
        jac_dc=d["jac_dc"], jac_bands=_split(d["jac_bands"], d["jac_bands_counts"]), jac_step=d["jac_step"],
        candidates=meta["candidates"], widths_m=d["widths_m"], grid_mean=d["grid_mean"], grid_raw=d["grid_raw"],
        grid_bands=_split(d["grid_bands"], d["grid_bands_counts"]), grid_dc=d["grid_dc"],
        noise_band_psd=d["noise_band_psd"], noise_band_f=d["noise_band_f"],
        local_event_basis=d["local_event_basis"], local_complement=d["local_complement"],
        local_zev=_split(d["local_zev"], d["local_zev_counts"]), local_zc=_split(d["local_zc"], d["local_zc_counts"]),
        record_mean_dc=(_split(d["record_mean_dc"], d["record_mean_dc_counts"]) if "record_mean_dc" in d else []),
        path=p)


# ------------------------------------------------------------------------------------------------ build

BUILT_BY = ("diagnose.py", "analysis.py", "events.py", "spectral.py", "fitting.py", "plant_adapter.py",
            "synthetic.py", "model.py")      # what a reference's arrays come from (the views are made at load time)


def source_hash() -> str:
    """Hash of the code a reference's arrays are made by (plant, windowing, denoising, the workbench modules of
    BUILT_BY): a cached reference made by other code is not reused."""
    # deferred: classifier.dataset (the simulator) costs ~600 ms at start-up (python -X importtime, 29 Nov)
    from backlash_monitor.classifier.dataset import source_hash as plant_source_hash
    h = hashlib.sha256(plant_source_hash().encode())
    here = Path(__file__).resolve().parent
    for f in (here / n for n in BUILT_BY):
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def cache_path(model) -> Path:
    """Where the cached reference of ``model`` lives: .cache/watch/<name>_v<version>_<key>.watch.npz, the key a
    hash of the model's plant config and nominal conditions, the build settings and the code (source_hash)."""
    # deferred: classifier.dataset (the simulator) costs ~600 ms at start-up (python -X importtime, 29 Nov)
    from backlash_monitor.classifier.dataset import CACHE_DIR
    parts = {"plant": config_hash(model.plant_config()), "nominal": dict(model.nominal), "label": model.label(),
             "format": FORMAT_VERSION, "record_mean_seeds": RECORD_MEAN_SEEDS, "duration_s": BUILD_DURATION_S, "seed": BUILD_SEED, "width_step": WIDTH_STEP,
             "width_range": WIDTH_RANGE, "code": source_hash()}
    key = hashlib.sha256(json.dumps(parts, sort_keys=True, default=repr).encode()).hexdigest()[:16]
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in f"{model.name}_v{model.version}")
    return Path(CACHE_DIR) / "watch" / f"{safe}_{key}{SUFFIX}"


def cached(model, progress=None, log=None) -> ModelReference:
    """The reference of ``model`` from the cache, built (and cached) when missing (~30 s of one core);
    ``log(text)`` is told when it is built."""
    p = cache_path(model)
    if p.is_file():
        try:
            return load(p)
        except ReferenceError:
            pass                         # a damaged cache entry: build it again
    if log is not None:
        log(f"building the model watch's reference for {model.label()} at width "
            f"{model.nominal['width_m'] * 1e3:g} mm, eta_k {model.nominal['eta_k']:g}, n1 {model.nominal['n1']:g} "
            f"(once; cached in {p.parent})")
    ref = build(model, progress=progress)
    p.parent.mkdir(parents=True, exist_ok=True)
    ref.save(p)
    return ref


def _width_grid(nominal_width_m: float, step: float = WIDTH_STEP) -> np.ndarray:
    n = int(round(WIDTH_RANGE / step))
    return nominal_width_m * step * np.arange(-n, n + 1)       # the drift's change [m]


def build(model, duration_s: float = BUILD_DURATION_S, seeds=None, progress=None,
          width_step: float = WIDTH_STEP, recording=None, record_mean_seeds: int = RECORD_MEAN_SEEDS) -> ModelReference:
    """The reference of ``model`` (a WorkbenchModel): diagnose's prepare and screening on a recording the model
    makes of itself (``duration_s``, noise seed BUILD_SEED), plus the width grid (``width_step`` of the nominal
    width over +-WIDTH_RANGE) on the same seeds. ``recording``: build on this measurement instead (its conditions
    and length: then the reference evaluated on it is diagnose's test on it, to the last digit -- the tests check
    it, with ``record_mean_seeds`` 0). ``record_mean_seeds``: more noise seeds at the nominal width whose period means
    the record mean's noise is estimated from too (RECORD_MEAN_SEEDS)."""
    # deferred: workbench.diagnose (the simulator) costs ~580 ms at start-up (python -X importtime, 29 Nov)
    from . import diagnose, synthetic
    t0 = time.perf_counter()
    meas = recording if recording is not None else synthetic.hidden_effect_recording(model, duration_s, BUILD_SEED)
    run = diagnose.prepare(meas, model, seeds)
    p = run.problem
    captured = []                    # every simulated set: (parameter set, its ensemble)
    evaluate = p.evaluate

    def capturing(sets, **kwargs):
        ens = evaluate(sets, **kwargs)
        captured.extend((dict(s), ens, i) for i, s in enumerate(sets) if ens.n_events[i].all())
        return ens
    p.evaluate = capturing
    try:
        diagnose.screen_step(run, progress=progress)
        changes = _width_grid(float(model.nominal["width_m"]), width_step)
        # the width grid: the ensemble (as Problem.evaluate makes it) and every run's own events
        sets = [{WIDTH_KEY: float(c)} for c in changes]
        # deferred: the simulator (numba, scipy.optimize) costs ~600 ms at start-up (python -X importtime, 29 Nov)
        from . import plant_adapter   # the simulator (numba): not imported by a watch that only evaluates
        runs = plant_adapter.simulate_sets(model, p._merge(sets), p.seeds, p.n_samples, conditions=p.conditions)
        p.n_sets_simulated += len(sets)
        grid_ens = ensemble_from_runs(runs, p.dt, dc_names=p.dc_names)
        grid_events = [[event_set({name: runs[name][i, k] for name in runs}, p.dt) for k in range(len(p.seeds))]
                       for i in range(len(sets))]
        del runs
        # the record-mean seeds: the nominal set (as the ensemble's set 0) on other noise seeds, their period means
        more_seeds = [RECORD_MEAN_SEED0 + i for i in range(int(record_mean_seeds))]
        record_mean_dc = []
        if more_seeds:
            runs = plant_adapter.simulate_sets(model, p._merge([{}]), more_seeds, p.n_samples, conditions=p.conditions)
            record_mean_dc = [event_set({name: runs[name][0, k] for name in runs}, p.dt, p.dc_names).dc
                              for k in range(len(more_seeds))]
            del runs
    finally:
        p.evaluate = evaluate
    comp = run.comp
    w = comp.weights
    n_sig = len(SEGMENT_SIGNALS)
    base_bands = np.concatenate(comp.ensemble.seed_bands[0], axis=0)

    def set_of(parameter_set):
        for s, ens, i in captured:
            if s == parameter_set:
                return ens, i
        raise RuntimeError(f"screening set {parameter_set} was not simulated")   # pragma: no cover

    # deferred: the simulator (numba, scipy.optimize) costs ~600 ms at start-up (python -X importtime, 29 Nov)
    from .plant_adapter import apply_values
    candidates, jac_event, jac_dc, jac_bands, jac_step = [], [], [], [], []
    for name, lin in run.screening.items():
        cand = run.by_name[name]
        x0 = cand.default_vector()
        cols = []
        for i, h in enumerate(np.atleast_1d(lin.step)):
            ens, j = set_of(apply_values(cand, x0 + h * np.eye(len(x0))[i]))
            J = lin.jacobian[:, i]
            cols.append(len(jac_step))
            jac_event.append((J[p.event_slice].reshape(n_sig, -1) / w[:, None]).ravel())
            jac_dc.append(J[p.dc_slice] / p.wdc)
            jac_bands.append(np.concatenate(ens.seed_bands[j], axis=0))
            jac_step.append(float(h))
        lo, hi = cand.bounds()
        candidates.append({"name": name, "effect": cand.effect, "keys": [q.key for q in cand.parameters],
                           "default": [float(v) for v in x0], "lower": [float(v) for v in lo],
                           "upper": [float(v) for v in hi], "columns": cols})
    spectra = comp.record_spectra
    nominal = dict(model.nominal)
    meta = {"model_label": model.label(), "model": model.to_dict(), "nominal": nominal,
            "model_path": str(model.path) if model.path else None, "conditions": dict(comp.conditions),
            "build_duration_s": float(duration_s), "build_seed": BUILD_SEED, "width_step": float(width_step),
            "pulse_period_samples": int(round(model.plant_config().pulse_load.period_s / meas.sample_period_s)),
            "candidates": candidates, "tolerance_scale": float(tolerance.SCALE),
            "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()), "source_hash": source_hash(),
            "build_seconds": None, "format_version": FORMAT_VERSION,
            # diagnose's own consistency test on the build recording (screen_step's): provenance, and what a
            # reference built on a recording must reproduce on it (test_model_watch_core.py)
            "build_consistency": run.before.to_json(), "build_events_measured": int(p.n_events),
            "dc_names": list(p.dc_names), "record_mean_seeds": more_seeds}
    ref = ModelReference(
        meta=meta, sample_period_s=float(meas.sample_period_s), seeds=list(comp.seeds),
        build_events=int(round(float(np.mean(comp.ensemble.n_events[0])))), weights=np.asarray(w, dtype=float),
        seed_events=[np.asarray(x) for x in comp.ensemble.per_event],
        seed_dc=[np.asarray(x) for x in comp.ensemble.per_event_dc], seed_means=comp.ensemble.seed_means[0],
        base_mean=comp.ensemble.mean_denoised(0), base_raw=comp.ensemble.mean_raw(0), base_bands=base_bands,
        base_dc=comp.ensemble.dc_mean(0), jac_event=np.array(jac_event), jac_dc=np.array(jac_dc),
        jac_bands=jac_bands, jac_step=np.array(jac_step), candidates=candidates,
        widths_m=float(model.nominal["width_m"]) + changes,
        grid_mean=np.stack([grid_ens.mean_denoised(i) for i in range(len(changes))]),
        grid_raw=np.stack([grid_ens.mean_raw(i) for i in range(len(changes))]),
        grid_bands=[np.concatenate(grid_ens.seed_bands[i], axis=0) for i in range(len(changes))],
        grid_dc=np.stack([grid_ens.dc_mean(i) for i in range(len(changes))]),
        noise_band_psd=np.stack([spectra[s]["ensemble"].mean(axis=0) for s in SEGMENT_SIGNALS]),
        noise_band_f=np.asarray(spectra[SEGMENT_SIGNALS[0]]["f"]), record_mean_dc=record_mean_dc)
    _add_local(ref, grid_events)
    ref.meta["build_seconds"] = time.perf_counter() - t0
    return ref


def _add_local(ref: ModelReference, grid_events: list) -> None:
    """The width-local whitening's data (WindowReference.local_views): the model's own events at every grid width on
    the nominal views' event-average and complement directions."""
    v0 = WindowReference(ref, np.zeros(len(SEGMENT_SIGNALS)), ref.build_events)
    b_ev = dict(v0.views.candidate_directions)["event_average"][v0.event_slice]
    comp = v0.views.complement / np.linalg.norm(v0.views.complement, axis=0)[None, :]
    zev, zc = [], []
    for g, per_seed in enumerate(grid_events):
        raw = np.concatenate([ev.raw for ev in per_seed], axis=0)
        vec = (denoise(raw) * v0.w[None, :, None]).reshape(raw.shape[0], -1) - v0.grid[g][v0.event_slice][None]
        zev.append(vec @ b_ev)
        zc.append(vec @ comp)
    ref.local_event_basis, ref.local_complement = b_ev, comp
    ref.local_zev, ref.local_zc = zev, zc
