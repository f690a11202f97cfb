"""Proposing the missing term: when no catalogue effect explains a recording, a sparse sum of generic candidate terms
(candidate_terms.py) fitted to the residual that is left, selected honestly on the events (docs/workbench.md,
"Proposing a missing term").

1. **the per-event design** (event_design.py): the model (with the partial explanation, when diagnose found one)
   and every plain candidate term at a small coefficient in its balance, one batch on the diagnosis's seeds (common
   random numbers): the column of each term's effect on the prediction (event average, spectral shape, record mean),
   whitened in the diagnosis's views, the same for every event; a term locked to a shaft's angle by its per-event
   response, lined up with the recording's own angle at each event; a sensor's term and a slow change computed on
   the recorded events;
2. **selection on the events**: forward selection of groups of terms (a harmonic's sine and cosine are one group) by
   leave-one-event-out cross-validation: a group enters only when it lowers the held-out events' error by more than
   ``CV_Z`` of that gain's standard error over the events (the events are the independent units, never the
   samples), at most ``MAX_GROUPS``;
3. **stability**: the selection repeated on ``BOOTSTRAP`` resamples of the events; a group is proposed only when it
   is selected in at least ``STABILITY`` of them and on the whole recording;
4. **fit and test like a catalogue effect**: the selected coefficients by least squares on every event's design, their
   uncertainty the jackknife over the events; the model with the simulated terms at those values (and the recorded
   ones by their linear change) tested by diagnose's consistency test (consistency.test) in every view;
5. **outputs**: the law in words and symbols, a plug-in file in the ``--effects-file`` form with the fitted values
   (bounded parameters, neutral defaults), and what add-effect --accept-proposal makes of it (the next version).
"""
from __future__ import annotations

import copy
import time
from dataclasses import dataclass, field

import numpy as np

from backlash_monitor.plant.integrator import first_call_cpu_seconds

from . import candidate_terms, consistency, drive_terms, event_design, fitting, plant_adapter

NO_PLUGIN_NOTE = ("; no plug-in form (a sensor's term of the drive's states or of the other channel, or one of the "
                  "time in the record)")   # the reason's tail; a channel's own cube is a plug-in sensor stage

VERDICTS = ("partial", "nothing_explains")
CV_Z = 3.0             # a group enters when its held-out gain is CV_Z standard errors (over the events) above 0
MAX_GROUPS = 3         # at most this many groups of terms in one proposal (a sparse law)
BOOTSTRAP = 60         # resamples of the events for the stability
STABILITY = 0.6        # share of the resamples a proposed group must be selected in (stability selection)
MIN_EVENTS = 6         # fewer events: no honest cross-validation
ALIKE_COSINE = 0.95    # two groups whose per-event columns span (almost) the same directions: the cosine of the
                       # smallest principal angle between them over every event's whitened coordinates. The data cannot
                       # tell them apart (the two shafts' angles differ by at most the gap; a speed's sign is 1 on a
                       # drive that never reverses), so they share their votes in the stability and are reported as one
MIN_EXPLAINED_SHARE = 0.0   # a proposal must lower the event average's residual once in the model (share > 0)
BOOTSTRAP_SEED = 31    # the resampling's seed: a diagnosis is reproducible
# The terms with a memory (candidate_terms.memory_terms: first-order lags of the speeds, the penetration and the load
# input) in a SECOND pass, run only when the library without them proposes nothing: in one pass with the rest they
# took the selection from terms that were right (outside_dev3's a2 deadband, outside_dev6's torque limiter; docs/
# workbench.md "Terms with memory"), and they cost every recording 9-18 s; a second pass cannot change a proposal the
# first one made, and costs only the recordings where nothing was proposed
MEMORY_SECOND_PASS = True
BATCH_SETS = 6         # parameter sets simulated per batch (memory: a 4 s recording's set is ~0.2 GB over 8 seeds)


@dataclass
class Proposal:
    proposed: bool
    reason: str
    law: str = ""
    pieces: list = field(default_factory=list)       # [candidate_terms.ProposedPiece]
    stability: dict = field(default_factory=dict)    # group -> share of the resamples selecting it
    cv: list = field(default_factory=list)           # the selection's steps: group, held-out gain, its z
    explained_fraction: float | None = None
    delta_ic: float | None = None
    consistent: bool | None = None
    views_after: dict | None = None
    plugin_source: str = ""
    finding: str = ""          # what was proposed and how well it explains, without the reason's no-plug-in tail
    plugin_values: dict = field(default_factory=dict)
    on_top_of: list = field(default_factory=list)   # the partial explanation the terms were fitted on top of
    cpu_seconds: float = 0.0
    simulated_sets: int = 0
    form: dict = field(default_factory=dict)   # the form stage (_form_stage): the hinges screened, their selection
    joint: dict = field(default_factory=dict)  # the partial explanation refitted jointly with the terms (_joint_refit)
    on_top_values: dict = field(default_factory=dict)       # candidate -> {parameter: value}: the partial explanation's
    on_top_uncertainty: dict = field(default_factory=dict)  # values beside the terms (what --accept-proposal writes)
    selection_ran: bool = False   # the selection on the events was reached (not stopped by a precondition)
    memory_pass: dict = field(default_factory=dict)   # the second pass with the terms with a memory, when it ran
    first_call_cpu_seconds: float = 0.0   # of cpu_seconds, the one-time first call of the library's kernel in this
                                          # process (its compile on a cold cache; plant.integrator.first_call_cpu_seconds)

    def to_json(self) -> dict:
        return {"proposed": self.proposed, "reason": self.reason, "law": self.law,
                "terms": [{"balance": p.balance, "state": p.state(), "group": p.terms[0].group,
                           "alike": [{"balance": t.balance, "state": t.state, "group": t.group} for t in p.alike],
                           "terms": [t.name for t in p.terms], "symbols": [t.symbol for t in p.terms],
                           "coefficients": [float(c) for c in p.coefficients],
                           "uncertainty": [float(u) for u in p.uncertainties], "law": p.law(),
                           **({"amplitude": p.amplitude_phase()[0], "phase_rad": p.amplitude_phase()[1],
                               "amplitude_uncertainty": p.amplitude_phase()[2]} if p.harmonic else {})}
                          for p in self.pieces],
                "stability": self.stability, "selection": self.cv,
                "explained_fraction": self.explained_fraction, "delta_ic": self.delta_ic,
                "consistent": self.consistent, "consistency_after": self.views_after,
                "plugin_source": self.plugin_source, "plugin_values": self.plugin_values,
                "on_top_of": self.on_top_of, "cpu_seconds": self.cpu_seconds, "simulated_sets": self.simulated_sets,
                "form_stage": self.form, "joint_refit": self.joint, "memory_pass": self.memory_pass,
                "on_top_values": self.on_top_values, "on_top_uncertainty": self.on_top_uncertainty,
                "kernel_first_call_cpu_seconds": self.first_call_cpu_seconds,
                "per_recording_cpu_seconds": self.cpu_seconds - self.first_call_cpu_seconds,
                "method": "forward selection of generic terms by leave-one-event-out cross-validation, stable under "
                          f"{BOOTSTRAP} resamples of the events (>= {STABILITY:.0%}), refined on the simulator"}


def sensor_fault_gate(saturation: dict) -> Proposal | None:
    """No term is proposed from a recording whose accelerometer sat at its rail or stuck at one value
    (``saturation``: measurement.saturation_of, the diagnosis's ``input_saturation``): the residual there is the
    sensor's fault, which no term of the drive's states reproduces (a sensor term adds to the signal; a clipped or
    held signal has lost it). -> the Proposal that says so, or None (the recording's sensors are sound: propose)."""
    if not saturation or not saturation.get("saturated"):
        return None
    faults = "; ".join(saturation.get("messages") or []) or "an accelerometer clipped or stuck"
    return Proposal(False, f"not proposed: {faults}. The residual is read off a faulty sensor, not a missing "
                           "physical term: repair or replace the sensor (or cut the faulty samples from the "
                           "recording) and diagnose again")


# ------------------------------------------------------------------------------------------ selection (pure numpy)
def _per_event(G: np.ndarray, e: int) -> np.ndarray:
    """(E, D, M): a design the same for every event (D, M) repeated, or one per event as given."""
    G = np.asarray(G, dtype=float)
    return np.broadcast_to(G[None], (e,) + G.shape) if G.ndim == 2 else G


def gram(G: np.ndarray, Y: np.ndarray) -> tuple:
    """The events' normal equations: (G_e' G_e (E, M, M), G_e' Y_e (E, M), |Y_e|^2 (E,)). G: (D, M) shared by the
    events or (E, D, M) one per event (event_design.py); Y: (E, D) the events' whitened residuals."""
    Y = np.asarray(Y, dtype=float)
    Ge = _per_event(G, Y.shape[0])
    return np.einsum("edm,edn->emn", Ge, Ge), np.einsum("edm,ed->em", Ge, Y), np.sum(Y ** 2, axis=1)


def _loo_coefficients(GG, Gy, cols):
    """Per event e: the least-squares coefficients of ``cols`` on the other events (E, m)."""
    A = GG[:, cols][:, :, cols]
    b = Gy[:, cols]
    Ao = A.sum(axis=0)[None] - A
    bo = b.sum(axis=0)[None] - b
    ridge = 1e-10 * np.trace(A.sum(axis=0)) / len(cols) + 1e-300
    return np.linalg.solve(Ao + ridge * np.eye(len(cols))[None], bo[..., None])[..., 0], A, b


def cv_errors_gram(GG, Gy, yy, cols) -> np.ndarray:
    """Per event e: |Y_e - G_e c_(-e)|^2, c_(-e) fitted on the other events (from gram())."""
    if not cols:
        return yy
    c, A, b = _loo_coefficients(GG, Gy, list(cols))
    return yy - 2.0 * np.einsum("em,em->e", c, b) + np.einsum("em,emn,en->e", c, A, c)


def cv_errors(G: np.ndarray, Y: np.ndarray, cols) -> np.ndarray:
    """Per event e: |Y_e - G_e c_(-e)|^2, c_(-e) the least-squares coefficients on the other events.
    G: (D, M) or (E, D, M) whitened sensitivities; Y: (E, D) the events' whitened residuals."""
    return cv_errors_gram(*gram(G, Y), cols)


def _forward_gram(GG, Gy, yy, groups: list, z: float, max_groups: int, alike: list | None = None,
                  start: list | None = None, candidates: list | None = None):
    """forward_select on the events' normal equations; ``alike`` (alike_groups): a group the data cannot tell from
    one already selected is the same term and does not enter beside it (two of them together fit their small
    difference, a term of another shape: measured, sin α₂ and sin α₁ on a2 at opposite coefficients). ``start``:
    groups already chosen (the form stage: the hinges enter on top of them, ``candidates`` the only ones tried); the
    returned selection holds the added groups only, ``max_groups`` counts the start's too."""
    start = list(start or [])
    sel: list = []
    cols: list = [c for g in start for c in groups[g]]
    allowed = None if candidates is None else set(candidates)
    err = cv_errors_gram(GG, Gy, yy, cols)
    steps = []
    e = yy.shape[0]
    taken: set = set()
    for g in start:
        taken |= set(alike[g]) if alike is not None else {g}
    while len(start) + len(sel) < max_groups:
        best = None
        for gi, g in enumerate(groups):
            if gi in sel or gi in taken or (allowed is not None and gi not in allowed):
                continue
            d = err - cv_errors_gram(GG, Gy, yy, cols + list(g))
            m, s = float(d.mean()), float(d.std(ddof=1)) / np.sqrt(e)
            zz = m / s if s > 0 else (np.inf if m > 0 else 0.0)
            if zz > z and (best is None or m > best[1]):
                best = (gi, m, zz)
        if best is None:
            break
        sel.append(best[0])
        taken |= set(alike[best[0]]) if alike is not None else set()
        cols += list(groups[best[0]])
        err = cv_errors_gram(GG, Gy, yy, cols)
        steps.append(best)
    return sel, steps


def forward_select(G: np.ndarray, Y: np.ndarray, groups: list, z: float = CV_Z, max_groups: int = MAX_GROUPS):
    """Groups (lists of column indices) entered one by one while the best one's held-out gain over the events is
    ``z`` standard errors above 0. G: (D, M) or per event (E, D, M). -> ([group index], [(group index, mean gain,
    z)])."""
    return _forward_gram(*gram(G, Y), groups, z, max_groups)


def alike_groups(G: np.ndarray, groups: list, cosine: float = ALIKE_COSINE) -> list:
    """Per group, the indices of the groups the data cannot tell from it (itself included): the largest cosine of
    the principal angles between their column spaces, every event's coordinates stacked, above ``cosine``."""
    Ge = np.asarray(G, dtype=float)
    flat = Ge.reshape(-1, Ge.shape[-1]) if Ge.ndim == 3 else Ge
    bases = []
    for g in groups:
        q, r = np.linalg.qr(flat[:, list(g)])
        keep = np.abs(np.diag(r)) > 1e-12 * max(float(np.abs(r).max()), 1e-300)
        bases.append(q[:, keep])
    out = []
    for i, qi in enumerate(bases):
        row = []
        for j, qj in enumerate(bases):
            if i == j:
                row.append(j)
            elif qi.shape[1] and qj.shape[1] and np.linalg.svd(qi.T @ qj, compute_uv=False)[0] > cosine:
                row.append(j)
        out.append(row)
    return out


def stability(G: np.ndarray, Y: np.ndarray, groups: list, n: int = BOOTSTRAP, seed: int = BOOTSTRAP_SEED,
              alike: list | None = None) -> np.ndarray:
    """Share of ``n`` resamples of the events (with replacement) in which each group is selected -- or, with
    ``alike`` (alike_groups), one of the groups the data cannot tell from it."""
    return _stability_gram(*gram(G, Y), groups, n, seed, alike)


def _stability_gram(GG, Gy, yy, groups: list, n: int = BOOTSTRAP, seed: int = BOOTSTRAP_SEED,
                    alike: list | None = None, start: list | None = None, candidates: list | None = None) -> np.ndarray:
    """stability on the events' normal equations (gram()); ``start``, ``candidates``: as _forward_gram's (the groups
    added on top of ``start`` in each resample)."""
    rng = np.random.default_rng(seed)
    e = yy.shape[0]
    counts = np.zeros(len(groups))
    for _ in range(n):
        idx = rng.integers(0, e, e)
        if len(np.unique(idx)) < 3:
            continue
        sel, _ = _forward_gram(GG[idx], Gy[idx], yy[idx], groups, CV_Z, MAX_GROUPS, alike, start, candidates)
        hit = np.zeros(len(groups), dtype=bool)
        hit[sel] = True
        if alike is not None:
            hit = np.array([hit[a].any() for a in alike])
        counts[hit] += 1
    return counts / n


# ------------------------------------------------------------------------------------------ the proposal of a run
def _library_model(model, memory: bool = False):
    lib = copy.copy(model)
    lib.effect_files = list(model.effect_files) + [candidate_terms.library_file(memory)]
    lib.effects_added = list(model.effects_added)
    return lib


SECANT_ITERATIONS = 3  # re-estimations of an angle-locked pair's response at its fitted amplitude
SECANT_TOLERANCE = 0.05  # stop when no coefficient moves by more than this share of the largest
MIN_COEFFICIENT_Z = 2.0  # a proposed group's largest coefficient over its jackknife uncertainty, at least
# Gauss-Newton steps of the plain terms' coefficients on the simulator after the per-event fit, the Jacobian corrected by
# each step's own change (secant: a motor load of the motor's own size moves its slip and speed, and the tangent at the
# small screening step no longer holds -- measured on the spent outside rows: a particle brake's 0.9 p.u. load, pinned at
# the bound by the fixed tangent with the record mean's speed 12.5x its limit, came to 0.89 p.u. and a model consistent
# in every view; the five proposals consistent before stayed so), each refused step tried at half and a quarter
REFIT_ITERATIONS = 5
REFIT_SCALES = (1.0, 0.5, 0.25)
JOINT_REFIT = True       # after a partial verdict: the partial effect's parameters refitted jointly with the terms (below)
PAIR_VARIANT = False     # a third selection variant after a partial verdict: on top of the partial explanation with its
                         # tangent columns free in every held-out fit (a pair against a term alone). Off: measured
                         # (30 Nov, 6dbd39a) on the three rows proposed instead of their partial, it lost the held-out
                         # error to "instead" on each (od6 PWM brake 5604 vs 4427, idler rattle 998 vs 971, os7
                         # hold-down 1281 vs 1243): nothing changed (docs/workbench.md "The partial explanation
                         # refitted jointly")
JOINT_ITERATIONS = 2     # its Gauss-Newton steps; each one simulated set, or up to three when refused (the step halved
                         # twice), + the partial's tangents when diagnose's fit has none (one set per parameter); a step
                         # is kept only when it lowers the residual


def _fit(GG, Gy, cols) -> tuple:
    """The least-squares coefficients of ``cols`` over every event and their jackknife standard errors over the
    events (from the leave-one-out fits)."""
    A, b = GG[:, cols][:, :, cols].sum(axis=0), Gy[:, cols].sum(axis=0)
    coef = np.linalg.lstsq(A, b, rcond=None)[0]
    c_loo, _, _ = _loo_coefficients(GG, Gy, cols)
    e = GG.shape[0]
    return coef, np.sqrt((e - 1) / e * np.sum((c_loo - c_loo.mean(axis=0)) ** 2, axis=0))


def _evaluate_each(p, sets) -> list:
    """The prediction of every parameter set, in batches (a batch's raw runs are sets x seeds x samples); a set whose
    simulated runs give no onset window (a term at its step that stops the drive crossing its backlash) -> None; a
    batch the simulator refuses (a value out of a parameter's range: ValueError) again one set at a time."""
    preds: list = []
    for i in range(0, len(sets), BATCH_SETS):
        batch = sets[i:i + BATCH_SETS]
        try:
            ens = p.evaluate(batch, empty_ok=True)
            preds += [p.pred_of(ens, j) if ens.n_events[j].all() else None for j in range(len(batch))]
        except ValueError:
            for one in batch:
                try:
                    preds.append(p.pred_of(p.evaluate([one]), 0))
                except ValueError:
                    preds.append(None)
    return preds


def kept_gauss_newton(x0, lo, hi, J: np.ndarray, residual_at, r0: np.ndarray, iterations: int,
                      scales=(1.0, 0.5, 0.25), secant: bool = False) -> tuple:
    """Bounded Gauss-Newton steps of x on a Jacobian J (d prediction / d x, in the metric of the residual
    r = target - prediction), each kept only when the residual it leaves, ``residual_at(x)`` (which may raise
    ValueError: no prediction there), is smaller than the one kept; a step refused is tried again shorter (``scales``
    of it) before the iterations stop: the residual never grows. J is fixed, or with ``secant`` corrected after every
    trial by the change it saw (Broyden's rank-one update: J += ((r - r_trial) - J dx) dx^T / |dx|^2), for a response
    that bends away from its tangent over the step; a step the bounds leave at x ends the iterations.
    -> (x, r, |r|^2, the trials' |r|^2, None where ``residual_at`` raised)."""
    x, r = np.asarray(x0, dtype=float).copy(), np.asarray(r0, dtype=float)
    J = np.array(J, dtype=float)
    norm, trials = float(r @ r), []
    for _ in range(iterations):
        step = np.linalg.lstsq(J, r, rcond=None)[0]
        kept = False
        for scale in scales:
            trial = np.clip(x + scale * step, lo, hi)
            if secant and np.array_equal(trial, x):
                break
            try:
                r_trial = np.asarray(residual_at(trial), dtype=float)
            except ValueError:
                trials.append(None)
                continue
            n_trial = float(r_trial @ r_trial)
            trials.append(n_trial)
            if secant:
                dx = trial - x
                J = J + np.outer((r - r_trial) - J @ dx, dx) / float(dx @ dx)
            if n_trial < norm:
                x, r, norm, kept = trial, r_trial, n_trial, True
                break
        if not kept:
            break
    return x, r, norm, trials


def _partial_fits(run, up) -> list:
    """The fits of the partial explanation the terms go on top of (_base_sets' order)."""
    return [f for f in (getattr(up, "first", None), getattr(up, "second", None))
            if f is not None and f.effect in run.by_name]


def _partial_set(run, fits, x) -> dict:
    """The parameter set of the partial fits at the values ``x`` (their parameters one after another)."""
    out, i = {}, 0
    for f in fits:
        n = len(f.values)
        out.update(plant_adapter.apply_values(run.by_name[f.effect], x[i:i + n]))
        i += n
    return out


def _base_sets(run, up) -> tuple[dict, list]:
    """The parameter set of the partial explanation the terms go on top of (diagnose's update), and its names."""
    fits = _partial_fits(run, up)
    values = np.concatenate([np.asarray(f.values, dtype=float) for f in fits]) if fits else np.zeros(0)
    return _partial_set(run, fits, values), [f.effect for f in fits]


def running_integral(x: np.ndarray, dt_s: float) -> np.ndarray:
    """∫x dt from sample 0 (trapezoid) [unit of x * s], its mean and linear trend over the record removed
    (candidate_terms._sensor_dynamics: a high-passed channel has no DC; a ramp is an offset's, not the filter's)."""
    x = np.asarray(x, dtype=float)
    y = np.zeros_like(x)
    y[1:] = np.cumsum(0.5 * (x[1:] + x[:-1])) * float(dt_s)
    t = np.linspace(-1.0, 1.0, len(x))
    A = np.column_stack([np.ones_like(t), t])
    return y - A @ np.linalg.lstsq(A, y, rcond=None)[0]


def _sensor_shape(term, angles: dict, signals: dict, n: int, dt_s: float | None = None) -> np.ndarray | None:
    """The whole-record shape a sensor term adds to its signal (per unit coefficient), from the recording's states."""
    kind = term.recorded[2]
    if kind[0] == "integral":
        x = signals.get(kind[1])
        return None if x is None or dt_s is None else running_integral(x, dt_s) / (
            candidate_terms.INTEGRAL_TIME_SCALE_S * candidate_terms.CHANNEL_SCALE_M_S2)
    if kind[0] == "harmonic":
        _, var, k, fn = kind
        if var not in angles:
            return None
        return (np.sin if fn == "sin" else np.cos)(k * angles[var])
    if kind[0] == "cubic":
        x = signals.get(kind[1])
        return None if x is None else (np.asarray(x, dtype=float) / candidate_terms.CUBIC_SCALE_M_S2) ** 3
    if kind[0] == "channel":
        x = signals.get(kind[1])
        return None if x is None else np.asarray(x, dtype=float) / candidate_terms.CHANNEL_SCALE_M_S2
    if kind[0] == "speed":
        w = signals.get(kind[1])
        if w is None:
            return None
        w = np.asarray(w, dtype=float)
        return (w - w.mean()) / candidate_terms.REL_SPEED_SCALE_RAD_S
    return np.arange(n, dtype=float) / n


@dataclass
class Design:
    """The proposal's columns: ``terms`` in column order, ``G`` (E, D, M) per event in the whitened views, ``mean_cols``
    (N, M) each column's change of the mean prediction (unprojected, for the consistency test after the fit), and
    ``groups`` (name -> column indices)."""
    terms: list
    G: np.ndarray
    mean_cols: np.ndarray
    groups: dict
    angles: dict          # the recording's shaft angles from its speeds (event_design.recorded_angles)


def design(p, run, terms, steps, S, ref) -> Design:
    """The per-event design of the library (event_design.py): the simulated terms' shared secants ``S`` (N, M_s) of the
    event-averaged prediction, the angle-locked pairs lined up with the recording's angles, the sensor's terms and
    the slow changes computed on the recorded events."""
    e = p.n_events
    entries = np.asarray(p.events.entries)
    shared = [t for t in terms if t.simulated and t.harmonic is None]
    Gs = p.project(S)                                   # (D, M_s)
    cols_pe, cols_mean, names = [], [], []
    for j, t in enumerate(shared):
        cols_pe.append(np.broadcast_to(Gs[:, j][None], (e, Gs.shape[0])))
        cols_mean.append(S[:, j])
        names.append(t)
    # angle-locked pairs: the responses on the simulator, the phases from the recording
    angles = event_design.recorded_angles(run.meas.signals, p.dt)
    sin_terms = [t for t in terms if t.simulated and t.harmonic is not None and t.harmonic[2] == "sin"
                 and t.harmonic[0] in angles]
    resp = event_design.angle_responses(p, sin_terms, steps, p.project)
    by = candidate_terms.by_name()
    for t in sin_terms:
        r = resp.get(t.name)
        if r is None:
            continue
        var, k, _ = t.harmonic
        psi = k * angles[var][entries]
        cols = event_design.angle_columns(r, psi, p.project)            # (E, D, 2)
        # the change of the events' mean: the recorded events' own angles, lined up (the model's runs have theirs)
        mean = event_design.angle_columns(r, psi).mean(axis=0)        # (N, 2)
        cos_t = by[t.name.replace(f"_sin{k}", f"_cos{k}")]
        for c, term in enumerate((t, cos_t)):
            cols_pe.append(cols[..., c])
            cols_mean.append(mean[:, c])
            names.append(term)
    # the recorded terms: a sensor's (computed on the recorded events), a balance's constant changing with time
    recorded = candidate_terms.recorded_terms()
    shapes = {}
    for t in recorded:
        if t.recorded[0] == "sensor":
            shape = _sensor_shape(t, angles, run.meas.signals, p.n_samples, p.dt)
            if shape is not None:
                shapes[t.name] = (t.recorded[1], shape)
    sens = event_design.sensor_columns(p, shapes, p.project, unprojected=True)
    t_rel = entries / float(p.n_samples)
    const_index = {t.name: j for j, t in enumerate(shared)}
    for t in recorded:
        if t.name in sens:
            pe, mean = sens[t.name]
            cols_pe.append(pe)
            cols_mean.append(mean)
            names.append(t)
        elif t.recorded[0] == "time" and t.recorded[1] in const_index:
            j = const_index[t.recorded[1]]
            cols_pe.append(t_rel[:, None] * Gs[:, j][None])
            cols_mean.append(float(t_rel.mean()) * S[:, j])
            names.append(t)
    G = np.stack(cols_pe, axis=-1)
    groups: dict = {}
    for i, t in enumerate(names):
        groups.setdefault(t.group, []).append(i)
    return Design(names, G, np.stack(cols_mean, axis=-1), groups, angles)


TIE_SHARE = 0.05       # alike groups within this share of the best's held-out gain are tied: a simulated term's per-event
                       # columns carry the noise of their regression on the model's runs, a recorded term's none, which
                       # costs the simulated one a few per cent of its gain (measured: 1.5 % on a 6 N*m wheel-angle torque)
# the states of the body each balance acts on (its own speed and angle: the shaft driving it, for a harmonic): among terms the events cannot tell apart, a
# load on a body that depends on that body's own motion is the simpler physical hypothesis (a pump, a fan, a brake on
# the motor shaft reads the motor's speed, not the carriage's); measured on a speed relay loading the motor: ẋ/(rΩ_mb)
# and t_e chosen over Ω₁ that fitted the events as well
# the own-state preference picks the state within the balance of the tied set's largest gain; it does not move the term
# to another body (alike groups of several balances explain the events alike; the best gain is the one hint the events
# give at the balance). Measured (docs/workbench.md "The sixth set's misses"): a PWM wheel brake named in the wheel on
# its speed (before: a mass force on xdot|xdot|), a wheel phase-lock trim in the wheel; 14 other proposing rows the same
TIE_KEEPS_BALANCE = True
OWN_STATES = {"motor_load_moment_pu": ("omega1", "alpha1"), "wheel_torque_Nm": ("omega2", "alpha2"),
              "mass_force_N": ("xdot", "alpha2"), "clutch_torque_Nm": ("penetration", "penetration rate"),
              "rim_mass_force_N": ("z", "v"), "coupling_torque_Nm": ("rel_speed", "delta")}


def _preferred(GG, Gy, yy, groups: list, chosen: list, alike: list, terms: list) -> list:
    """The selected groups, each replaced by the one of its alike groups (alike_groups) that the events cannot tell
    from the best (its held-out gain, with the others selected, less than one standard error of the paired
    difference below the best's) and that comes first in: a term the simulator runs before a sensor's or a slow
    change's (it has the model's physics and a plug-in form); a harmonic of its balance's own shaft's angle or a term
    of the own body's state (OWN_STATES); the larger gain. The others stay named as alike."""
    out = list(chosen)
    for pos, g in enumerate(chosen):
        rest = [c for h in out if h != g for c in groups[h]]
        base = cv_errors_gram(GG, Gy, yy, rest)
        gains = {a: base - cv_errors_gram(GG, Gy, yy, rest + list(groups[a])) for a in alike[g]
                 if a == g or a not in out}
        best = max(gains, key=lambda a: gains[a].mean())

        def tied(a):
            d = gains[best] - gains[a]
            return a == best or d.mean() < max(d.std(ddof=1) / np.sqrt(len(d)), TIE_SHARE * gains[best].mean())

        def rank(a):
            t = terms[groups[a][0]]
            own = t.state in OWN_STATES.get(t.balance, ())      # a harmonic's state is its angle
            same = t.balance == terms[groups[best][0]].balance if TIE_KEEPS_BALANCE else True
            return (t.simulated, same, own, float(gains[a].mean()))
        out[pos] = max((a for a in gains if tied(a)), key=rank)
    return out


# the form stage: hinges of the selected groups' own states (candidate_terms.hinge_terms), selected by the same rule on
# top of the chosen groups; off by default (candidate_terms.HINGES_IN_PROPOSAL: its measurement there and in
# docs/workbench.md "The proposed term's form")


def _event_samples(p) -> np.ndarray:
    """The sample indices of the recording's events (each event's segment from its entry)."""
    L = int(np.asarray(p.events.raw).shape[-1])
    idx = (np.asarray(p.events.entries, dtype=int)[:, None] + np.arange(L)[None]).ravel()
    return np.unique(idx[(idx >= 0) & (idx < p.n_samples)])


def _state_samples(p, run, states) -> dict:
    """{state: its values over the recording's events} for the hinges' knots: the recorded speeds (Ω₁, Ω₂, Ω₁ − Ω₂),
    the carriage's ẋ/r from the recorded a2 (its running integral about r·mean Ω₂: the carriage runs at the wheel's
    rim speed on average); the contact's penetration and its rate -- which no sensor records -- from the model's own
    run without noise (in contact: the transmitted torque non-zero; β the least |Δ| there), as a speed the recording
    lacks."""
    states = set(states)
    idx = _event_samples(p)
    sig = run.meas.signals
    out = {}
    for v in ("omega1", "omega2"):
        if v in states and v in sig:
            out[v] = np.asarray(sig[v], dtype=float)[idx]
    if "rel_speed" in states and "omega1" in sig and "omega2" in sig:
        out["rel_speed"] = (np.asarray(sig["omega1"], dtype=float) - np.asarray(sig["omega2"], dtype=float))[idx]
    if "xdot" in states and "omega2" in sig and "a2" in sig:
        r = float(plant_adapter._plant_config(run.model).load.wheel_radius_m)
        xr = float(np.mean(np.asarray(sig["omega2"], dtype=float))) + running_integral(sig["a2"], p.dt) / r
        out["xdot"] = xr[idx]
    missing = states - set(out)
    if missing:
        sim = plant_adapter.simulate_sets(p.model, [dict(p.base)], p.seeds[:1], p.n_samples,
                                          conditions=p.conditions, noise=False,
                                          signals=("omega1", "omega2", "angle_difference", "transmitted_torque_Nm"))
        w1, w2 = sim["omega1"][0, 0], sim["omega2"][0, 0]
        dl, tc = sim["angle_difference"][0, 0], sim["transmitted_torque_Nm"][0, 0]
        touch = np.abs(tc) > 0.0
        inside = idx[touch[idx]]
        if inside.size:
            beta = float(np.min(np.abs(dl[touch])))
            sim_states = {"penetration": np.abs(dl[inside]) - beta,
                          "approach_speed": (np.sign(dl) * (w1 - w2))[inside]}
        else:
            sim_states = {}
        sim_states.update({"omega1": w1[idx], "omega2": w2[idx], "rel_speed": (w1 - w2)[idx]})
        out.update({v: sim_states[v] for v in missing if v in sim_states})
    return out


def hinge_alike(hinges: list, g0: int) -> list:
    """Per hinge (its group index g0 + j), the hinges of the same side of the same state at the other knots: the
    alternatives of one form (one of them enters; they share their votes in the stability, as alike groups do)."""
    family: dict = {}
    for j, t in enumerate(hinges):
        family.setdefault((t.knot, t.name[:-1]), []).append(g0 + j)
    return [family[(t.knot, t.name[:-1])] for t in hinges]


def select_on_top(G, Y, groups: list, start: list, candidates: list, alike: list) -> tuple:
    """The form stage's selection (pure numpy): ``candidates`` entered by forward selection on top of the groups
    ``start`` (leave-one-event-out CV_Z standard errors, at most MAX_GROUPS in all), kept when stable in STABILITY of
    BOOTSTRAP resamples of the events. -> ([added group], [(group, held-out gain, z)], the resamples' shares)."""
    GG, Gy, yy = gram(G, Y)
    sel, steps = _forward_gram(GG, Gy, yy, groups, CV_Z, MAX_GROUPS, alike, list(start), list(candidates))
    freq = _stability_gram(GG, Gy, yy, groups, alike=alike, start=list(start), candidates=list(candidates))
    return [g for g in sel if freq[g] >= STABILITY], steps, freq


def _form_stage(p, run, d, Y, groups, group_names, stable, alike, key, steps):
    """Hinges of the stable groups' states, screened on the simulator (one batch, the same seeds: common random numbers)
    and entered by the selection's own rule on top of them: leave-one-event-out CV_Z standard errors, stable in
    STABILITY of the event resamples, at most MAX_GROUPS in all; the knots of one side of a state are alternatives
    (one of them enters; they share their votes). -> (design, groups, group names, alike, [added group], knots {term
    name: knot}, report) or None (no state to refine)."""
    states = []
    for g in stable:
        for c in groups[g]:
            states += [v for v in candidate_terms.hinge_states_of(d.terms[c]) if v not in states]
    if not states:
        return None
    knots = candidate_terms.hinge_knots(_state_samples(p, run, states))
    hinges = [t for t in candidate_terms.hinges_for(states) if t.knot in knots]
    if not hinges:
        return None
    knot_of = {t.name: knots[t.knot][candidate_terms.hinge_slot(t)] for t in hinges}
    p.base = {**p.base, **{candidate_terms.knot_key(t): knot_of[t.name] for t in hinges}}
    for t in hinges:
        key[t.name] = f"{t.name}.{candidate_terms.coefficient_name(t)}"
        steps[t.name] = candidate_terms.BALANCES[t.balance][1]
    preds = _evaluate_each(p, [{}] + [{key[t.name]: float(steps[t.name])} for t in hinges])
    if preds[0] is None:
        return None
    S = np.stack([np.zeros_like(preds[0]) if preds[j + 1] is None else (preds[j + 1] - preds[0]) / steps[t.name]
                  for j, t in enumerate(hinges)], axis=1)
    e = d.G.shape[0]
    Gh = p.project(S)
    m0 = d.G.shape[-1]
    d2 = Design(list(d.terms) + hinges, np.concatenate([d.G, np.broadcast_to(Gh[None], (e,) + Gh.shape)], axis=-1),
                np.concatenate([d.mean_cols, S], axis=-1), {**d.groups, **{t.group: [m0 + j] for j, t in
                                                                            enumerate(hinges)}}, d.angles)
    g0 = len(groups)
    groups2 = list(groups) + [[m0 + j] for j in range(len(hinges))]
    names2 = list(group_names) + [t.group for t in hinges]
    alike2 = [list(a) for a in alike] + hinge_alike(hinges, g0)
    cand = list(range(g0, len(groups2)))
    added, steps_sel, freq = select_on_top(d2.G, Y, groups2, list(stable), cand, alike2)
    report = {"states": states, "knots": knots, "screened": len(hinges),
              "selection": [{"group": names2[g], "held_out_gain": m, "z": z} for g, m, z in steps_sel],
              "stability": {names2[g]: float(freq[g]) for g in cand if freq[g] > 0},
              "added": [names2[g] for g in added]}
    return d2, groups2, names2, alike2, added, knot_of, report


def _joint_refit(p, run, fits, coef, cols, plain_cols, lo, d, pred_after, model_after, ref) -> tuple:
    """The partial explanation's parameters (``fits``, diagnose's) and the plain terms' coefficients refitted jointly
    (kept_gauss_newton on the events' mean in the views' metric, JOINT_ITERATIONS steps). The partial's tangent
    columns: diagnose's forward differences at its values (FitResult.jacobian), else one simulated set per parameter
    at the model with the terms. The partial's uncertainty: the delete-one-event jackknife of the mean through the
    joint linearisation (fitting.jackknife_uncertainty; the terms keep their per-event jackknife).
    -> (the report, coef, pred_after)."""
    n_sets = p.n_sets_simulated
    x0 = np.concatenate([np.asarray(f.values, dtype=float) for f in fits])
    lo_b = np.concatenate([np.asarray(f.bounds[0], dtype=float) for f in fits])
    hi_b = np.concatenate([np.asarray(f.bounds[1], dtype=float) for f in fits])
    names = [f"{f.effect}.{n}" for f in fits for n in f.parameter_names]
    report = {"refitted": [f.effect for f in fits], "parameters": names,
              "values_before": {f.effect: dict(zip(f.parameter_names, map(float, f.values))) for f in fits},
              "uncertainty_alone": {f.effect: dict(zip(f.parameter_names, map(float, f.uncertainty))) for f in fits}}
    tangents, sources, i0 = [], [], 0
    try:
        for f in fits:
            if f.jacobian is not None and np.shape(f.jacobian) == (len(ref), len(f.values)):
                tangents.append(np.asarray(f.jacobian, dtype=float))
                sources.append(f"{f.effect}: diagnose's forward differences at its values")
            else:
                sources.append(f"{f.effect}: simulated at the model with the terms")
                lin = run.screening.get(f.effect)
                for j in range(len(f.values)):
                    i = i0 + j
                    h = (0.5 * abs(float(lin.step[j])) if lin is not None and len(lin.step) == len(f.values)
                         else 0.05 * (hi_b[i] - lo_b[i]))
                    h = h if x0[i] + h <= hi_b[i] else -h
                    x = x0.copy()
                    x[i] += h
                    tangents.append(((model_after(coef, x) - pred_after) / h)[:, None])
            i0 += len(f.values)
    except ValueError as error:
        report["skipped"] = f"a tangent step stops the model crossing its backlash ({str(error).splitlines()[0]})"
        report["simulated_sets"] = p.n_sets_simulated - n_sets
        return report, coef, pred_after
    k = len(x0)
    plain = [cols[i] for i in plain_cols]
    J = p.project(np.hstack(tangents + [d.mean_cols[:, plain]]))
    lo_all = np.concatenate([lo_b, lo[plain_cols] * 0.999])
    hi_all = np.concatenate([hi_b, -lo[plain_cols] * 0.999])
    preds: dict = {}

    def residual_at(x):
        c = coef.copy()
        c[plain_cols] = x[k:]
        preds[tuple(x)] = model_after(c, x[:k])
        return p.project(p.residual(preds[tuple(x)]))

    r0 = p.project(p.residual(pred_after))
    x_start = np.concatenate([x0, coef[plain_cols]])
    first_step = np.linalg.lstsq(J, r0, rcond=None)[0]
    report["first_step"] = dict(zip(names + [f"term {i}" for i in range(len(plain))], map(float, first_step)))
    x, _, norm, trials = kept_gauss_newton(x_start, lo_all, hi_all, J, residual_at, r0, JOINT_ITERATIONS)
    moved = norm < float(r0 @ r0)
    r_ref = p.project(p.residual(ref))
    report.update({"residual_before": float(r0 @ r0), "residual_after": norm, "trials": trials, "moved": moved,
                   "explained_before": float(p.explained_share(r0, r_ref)),
                   "consistent_before": bool(consistency.test(p.views, p.residual(pred_after)).consistent),
                   "tangents": sources})
    if moved:
        coef = coef.copy()
        coef[plain_cols] = x[k:]
        pred_after = preds[tuple(x)]
    unc = fitting.jackknife_uncertainty(p, -J, x, None, None)[:k]
    values, uncertainty, i = {}, {}, 0
    for f in fits:
        n = len(f.values)
        values[f.effect] = dict(zip(f.parameter_names, map(float, x[i:i + n]))) | dict(f.fixed)
        uncertainty[f.effect] = dict(zip(f.parameter_names, map(float, unc[i:i + n])))
        i += n
    report.update({"values_after": values, "uncertainty": uncertainty,
                   "simulated_sets": p.n_sets_simulated - n_sets})
    return report, coef, pred_after


def _pair_variant(p, run, up, d, Y, groups, alike):
    """The selection on top of the partial explanation with its tangent columns (diagnose's forward differences,
    shared by the events) free in every fit: the events' normal equations of the library extended by them, the
    partial's columns a start group (not counted among the terms). -> (the held-out error's sum, [group], steps, the
    extended normal equations for the stability), or None when a partial fit has no tangent."""
    fits = _partial_fits(run, up)
    if not fits or any(f.jacobian is None or np.shape(f.jacobian)[1] != len(f.values) for f in fits):
        return None
    J = p.project(np.hstack([np.asarray(f.jacobian, dtype=float) for f in fits]))       # (D, k)
    Ge = _per_event(d.G, Y.shape[0])                                                      # (E, D, M)
    E, _, M = Ge.shape
    k = J.shape[1]
    G_ext = np.concatenate([Ge, np.broadcast_to(J[None], (E,) + J.shape)], axis=2)
    GG, Gy, yy = gram(G_ext, Y)
    start = len(groups)
    groups_ext = list(groups) + [list(range(M, M + k))]
    alike_ext = list(alike) + [[start]]
    sel, steps = _forward_gram(GG, Gy, yy, groups_ext, CV_Z, MAX_GROUPS + 1, alike_ext, [start])
    cols = list(range(M, M + k)) + [c for g in sel for c in groups_ext[g]]
    return float(cv_errors_gram(GG, Gy, yy, cols).sum()), sel, steps, (GG, Gy, yy, groups_ext, alike_ext, start)


def _joint_text(joint: dict) -> str:
    """The partial values before and after the joint refit, in words."""
    parts = []
    for effect, before in joint["values_before"].items():
        after = joint["values_after"][effect]
        unc = joint["uncertainty"][effect]
        parts += [f"{effect}.{n} {v:.4g} -> {after[n]:.4g} ± {unc[n]:.2g}" for n, v in before.items()]
    return ", ".join(parts)


def propose(run, up, verdict: str) -> Proposal | None:
    """The proposal for a diagnosis (diagnose.Run and Update, its verdict); None when the verdict is not one of
    VERDICTS (a consistent model or a catalogue effect that explains: nothing to propose). Its ``cpu_seconds`` holds
    the library kernel's first call in this process, named apart (``first_call_cpu_seconds``): on a cold kernel cache
    its compile, ~40 s of one core once after a change of the library or of the plant's generator (the gated
    library kernel: bench/results.json proposal_cpu_first_call)."""
    c0 = first_call_cpu_seconds()
    sensitivities: dict = {}
    out = _propose(run, up, verdict, sensitivities=sensitivities)
    if (MEMORY_SECOND_PASS and not candidate_terms.MEMORY_IN_LIBRARY and out is not None and not out.proposed
            and out.selection_ran):
        first = out
        again = _propose(run, up, verdict, memory=True, sensitivities=sensitivities)
        if again.proposed:
            out = again
            out.reason += f" (with the terms with a memory, after the library without them: {first.reason})"
        else:
            out.reason += f" (with the terms with a memory as well: {again.reason})"
        out.memory_pass = {"proposed": again.proposed, "reason": again.reason, "cpu_seconds": again.cpu_seconds}
        out.cpu_seconds = first.cpu_seconds + again.cpu_seconds
        out.simulated_sets = first.simulated_sets + again.simulated_sets
    if out is not None:
        out.first_call_cpu_seconds = first_call_cpu_seconds() - c0
    return out


REUSE_TOLERANCE = 1e-9   # the second pass's reference against the first's (relative, its largest sample): the same
                         # model at zero coefficients, so the same runs; beyond it the first pass's columns are not used


def _shared_predictions(p, shared: list, key: dict, steps: dict, sensitivities: dict) -> list:
    """The reference's and every plain term's prediction at its step ([ref, term 1, ...]; None where the term stops
    the drive crossing its backlash). ``sensitivities`` ({} on a first pass) holds a pass's predictions by term;
    a later pass on a library with more terms simulates the reference and the terms it has not, and takes the
    others from it when its reference is the same (it is: the same model at zero coefficients, common random
    numbers; a reference that is not -- another kernel's rounding -- simulates them all)."""
    known = sensitivities.get("by_term", {})
    new = [t for t in shared if t.name not in known]
    preds = _evaluate_each(p, [{}] + [{key[t.name]: float(steps[t.name])} for t in new])
    ref, by = preds[0], dict(zip((t.name for t in new), preds[1:]))
    old_ref = sensitivities.get("ref")
    if known and (ref is None or old_ref is None
                  or np.max(np.abs(ref - old_ref)) > REUSE_TOLERANCE * max(float(np.max(np.abs(old_ref))), 1e-300)):
        rest = [t for t in shared if t.name not in by]
        by.update(zip((t.name for t in rest), _evaluate_each(p, [{key[t.name]: float(steps[t.name])} for t in rest])))
    else:
        by.update({name: pred for name, pred in known.items() if name not in by})
    if ref is not None and "ref" not in sensitivities:
        sensitivities.update(ref=ref, by_term=dict(by))
    return [ref] + [by[t.name] for t in shared]


def _propose(run, up, verdict: str, memory: bool = False, sensitivities: dict | None = None) -> Proposal | None:
    """One pass of the proposal on the library (with the terms with a memory or without); ``sensitivities``: see
    _shared_predictions."""
    if verdict not in VERDICTS:
        return None
    t0 = time.process_time()
    p0 = run.problem
    if p0.n_events < MIN_EVENTS:
        return Proposal(False, f"{p0.n_events} events: too few for a cross-validation over the events "
                               f"(at least {MIN_EVENTS})")
    p = copy.copy(p0)
    p.model = _library_model(run.model, memory)
    base_sets, on_top = _base_sets(run, up) if verdict == "partial" else ({}, [])
    terms = list(candidate_terms.library(memory=memory))
    # the speed-deviation terms' operating point: the recording's mean speeds (candidate_terms._speed_deviations)
    centers = candidate_terms.centers(run.meas.signals)
    center_sets = {candidate_terms.center_key(t): centers[t.center] for t in terms if t.center in centers}
    p.base = {**p0.base, **base_sets, **center_sets}
    n_before = p.n_sets_simulated
    shared = [t for t in terms if t.harmonic is None]
    key = {t.name: f"{t.name}.{candidate_terms.coefficient_name(t)}" for t in terms}
    steps = {t.name: candidate_terms.BALANCES[t.balance][1] for t in terms}
    # 1. the shared sensitivities: the reference and every plain term at a small coefficient (common random numbers)
    preds = _shared_predictions(p, shared, key, steps, {} if sensitivities is None else sensitivities)
    if preds[0] is None:
        return Proposal(False, "the model (with the partial explanation) gives no onset window in a simulated run: "
                               "nothing to fit a term to", cpu_seconds=time.process_time() - t0)
    ref = preds[0]
    S = np.stack([np.zeros_like(ref) if preds[j + 1] is None else (preds[j + 1] - ref) / steps[t.name]
                  for j, t in enumerate(shared)], axis=1)
    Y = p.project((p.event_vecs - ref[None]).T).T
    d = design(p, run, terms, steps, S, ref)
    group_names = list(d.groups)
    groups = [d.groups[g] for g in group_names]
    # 2-3. selection on the events, and its stability under their resampling. After a partial explanation, the terms
    # are selected on top of it and, the same design, instead of it (a catalogue effect can take up part of a
    # mechanism it is not: measured, a band brake on the wheel read as 82 % wheel inertia); the one whose selection
    # leaves the smaller held-out error over the events is kept
    alike = alike_groups(d.G, groups)
    variants = [(Y, ref, on_top)]
    if on_top:
        variants.append((p.project((p.event_vecs - run.base_pred[None]).T).T, run.base_pred, []))
    best = None
    for Yv, refv, top in variants:
        GGv, Gyv, yyv = gram(d.G, Yv)
        selv, stepsv = _forward_gram(GGv, Gyv, yyv, groups, CV_Z, MAX_GROUPS, alike)
        score = float(cv_errors_gram(GGv, Gyv, yyv, [c for g in selv for c in groups[g]]).sum())
        if best is None or (selv and score < best[0]):
            best = (score, Yv, refv, top, GGv, Gyv, yyv, selv, stepsv)
    pair_note, pair_gram = None, None
    if PAIR_VARIANT and on_top:
        pair = _pair_variant(p, run, up, d, variants[0][0], groups, alike)
        if pair is not None:
            pair_note = {"score": pair[0], "selected": [group_names[g] for g in pair[1]],
                         "scores_of_the_others": float(best[0])}
            if pair[1] and pair[0] < best[0]:
                GGv, Gyv, yyv = gram(d.G, variants[0][0])
                best = (pair[0], variants[0][0], variants[0][1], on_top, GGv, Gyv, yyv, pair[1], pair[2])
                pair_note["chosen"] = True
                pair_gram = pair[3]
    _, Y, ref, top, GG, Gy, yy, sel, cv_steps = best
    replaced = [] if top else on_top
    if replaced:
        on_top = []
        p.base = {**p0.base, **center_sets}
    if pair_gram is None:
        freq = _stability_gram(GG, Gy, yy, groups, alike=alike)
    else:       # the pair variant: the groups' stability with the partial's columns free in every resample
        GGx, Gyx, yyx, groups_x, alike_x, start_x = pair_gram
        freq = _stability_gram(GGx, Gyx, yyx, groups_x, alike=alike_x, start=[start_x])[:len(groups)]
    stab = {group_names[i]: float(freq[i]) for i in np.argsort(-freq) if freq[i] > 0}
    cv = [{"group": group_names[g], "held_out_gain": m, "z": z} for g, m, z in cv_steps]
    stable = _preferred(GG, Gy, yy, groups, [g for g in sel if freq[g] >= STABILITY], alike, d.terms)
    out = Proposal(False, "", stability=stab, cv=cv, on_top_of=on_top, selection_ran=True)
    if pair_note is not None:
        out.joint = {"pair_variant": pair_note}
    if not stable:
        out.reason = ("no candidate term lowers the held-out events' error stably: "
                      + (", ".join(f"{group_names[g]} selected in {freq[g]:.0%} of the resamples" for g in sel)
                         if sel else f"none gains {CV_Z:g} standard errors over the events"))
        out.cpu_seconds = time.process_time() - t0
        out.simulated_sets = p.n_sets_simulated - n_before
        return out
    # 3b. the form: hinges of the chosen groups' own states (a cap, a deadband, a limit), on top of them, by the same rule
    knot_of: dict = {}
    form_added: list = []
    if candidate_terms.HINGES_IN_PROPOSAL and len(stable) < MAX_GROUPS:
        form = _form_stage(p, run, d, Y, groups, group_names, stable, alike, key, steps)
        if form is not None:
            d, groups, group_names, alike, form_added, knot_of, out.form = form
            stable = list(stable) + form_added
            GG, Gy, yy = gram(d.G, Y)
    # the form stage refines a law, it must not cost one: when the fitted terms with the hinges stop the model crossing
    # its backlash (a hinge fitted past the mechanism it stands for: measured, the od6 torque limiter), the law is
    # fitted again without them (the design without the hinges' columns)
    attempts = [stable] + ([[g for g in stable if g not in form_added]] if form_added else [])
    for attempt, stable in enumerate(attempts):
        cols = [c for g in stable for c in groups[g]]
        # 4. the coefficients on every event (least squares of the per-event design), their uncertainty the jackknife
        # over the events (the leave-one-out fits the selection made); an angle-locked pair's response re-estimated at
        # its fitted amplitude (a secant: a torque of the working torque's size changes the crossing it acts on, its
        # response is not the tangent's at amplitude 0: measured, 8 N*m on the wheel fitted as 5.4 on the tangent)
        coef, unc = _fit(GG, Gy, cols)
        angles = d.angles
        entries = np.asarray(p.events.entries)
        for _ in range(SECANT_ITERATIONS):
            moved = False
            for g in stable:
                sin_t = d.terms[groups[g][0]]
                if not (sin_t.simulated and sin_t.harmonic is not None) or sin_t.harmonic[0] not in angles:
                    continue
                i0 = cols.index(groups[g][0])
                amp = float(np.hypot(coef[i0], coef[i0 + 1]))
                if amp < 2.0 * steps[sin_t.name]:
                    continue
                resp = event_design.angle_responses(p, [sin_t], {sin_t.name: amp}, p.project).get(sin_t.name)
                if resp is None:
                    continue
                var, k, _ = sin_t.harmonic
                psi = k * angles[var][entries]
                d.G[..., groups[g]] = event_design.angle_columns(resp, psi, p.project)
                d.mean_cols[:, groups[g]] = event_design.angle_columns(resp, psi).mean(axis=0)
                moved = True
            if not moved:
                break
            GG, Gy, yy = gram(d.G, Y)
            before = coef
            coef, unc = _fit(GG, Gy, cols)
            if np.max(np.abs(coef - before)) < SECANT_TOLERANCE * max(float(np.max(np.abs(coef))), 1e-12):
                break
        # a group whose fitted coefficients are all within MIN_COEFFICIENT_Z of their uncertainty from 0 leaves the
        # proposal (it entered beside a term whose response was still the tangent's)
        keep = [g for g in stable if np.max(np.abs(coef[[cols.index(c) for c in groups[g]]])
                                            / np.maximum(unc[[cols.index(c) for c in groups[g]]], 1e-300)) >= MIN_COEFFICIENT_Z]
        if keep and len(keep) < len(stable):
            stable = keep
            cols = [c for g in stable for c in groups[g]]
            coef, unc = _fit(GG, Gy, cols)
        chosen = [d.terms[c] for c in cols]
        lo = np.array([-candidate_terms.BALANCES[t.balance][2] for t in chosen])
        coef = np.clip(coef, lo * 0.999, -lo * 0.999)
        # the model after: the plain terms simulated at their fitted values; a term locked to an angle by its change of
        # the recorded events' mean at their own angles (the model's runs cross their entries at other angles: their
        # average of it is another draw of the same noise); the recorded ones by their linear change
        # -- except in the spectral shape, a power: there the angle-locked terms are simulated at their fitted values too
        # (the shape does not depend on the phase; its change is of second order in the amplitude, which no secant at
        # amplitude 0 holds)
        rec_cols = [i for i, t in enumerate(chosen) if not t.simulated]
        harm_cols = [i for i, t in enumerate(chosen) if t.simulated and t.harmonic is not None]
        plain_cols = [i for i, t in enumerate(chosen) if t.simulated and t.harmonic is None]

        def model_after(coef, x_partial=None):
            sim_set = {key[chosen[i].name]: float(coef[i]) for i in plain_cols}
            if x_partial is not None:      # the partial explanation at other values than diagnose's (the joint refit)
                sim_set.update(_partial_set(run, partial_fits, x_partial))
            harm_set = {key[chosen[i].name]: float(coef[i]) for i in harm_cols}
            sets_after = ([sim_set] if sim_set else []) + ([{**sim_set, **harm_set}] if harm_set else [])
            ens = p.evaluate(sets_after) if sets_after else None
            pred = p.pred_of(ens, 0) if sim_set else ref.copy()
            if rec_cols:
                pred = pred + d.mean_cols[:, [cols[i] for i in rec_cols]] @ coef[rec_cols]
            if harm_cols:
                lined_up = d.mean_cols[:, [cols[i] for i in harm_cols]] @ coef[harm_cols]
                lined_up[p.spectral_slice] = 0.0
                pred = pred + lined_up
                sp = p.spectral_slice
                pred[sp] += p.pred_of(ens, len(sets_after) - 1)[sp] - (p.pred_of(ens, 0)[sp] if sim_set else ref[sp])
            return pred
        try:
            pred_after = model_after(coef)
            break
        except ValueError as error:        # the terms at these values stop the drive crossing its backlash
            if attempt + 1 < len(attempts):
                out.form["dropped"] = ("the fitted terms with the hinges stop the model crossing its backlash "
                                       f"({str(error).splitlines()[0]}): fitted again without them")
                continue
            out.reason = ("the fitted terms stop the model crossing its backlash "
                          f"({str(error).splitlines()[0]}): nothing proposed")
            out.cpu_seconds = time.process_time() - t0
            out.simulated_sets = p.n_sets_simulated - n_before
            return out
    # the plain terms' coefficients refined on the simulator (Gauss-Newton on the events' mean in the views' metric,
    # the tangent columns as the Jacobian): the per-event fit holds each term's change at its small screening step, a
    # term of the balance's own size bends it (a brake that slows the crossing it acts on). A step is kept only when
    # it lowers the mean's residual; the jackknife uncertainty stays the per-event fit's
    if plain_cols:
        J = p.project(d.mean_cols[:, [cols[i] for i in plain_cols]])
        tried: dict = {}

        def refit_residual(x):
            c = coef.copy()
            c[plain_cols] = x
            tried[tuple(x)] = (c, model_after(c))
            return p.project(p.residual(tried[tuple(x)][1]))
        r0 = p.project(p.residual(pred_after))
        x, _, norm, _ = kept_gauss_newton(coef[plain_cols], lo[plain_cols] * 0.999, -lo[plain_cols] * 0.999, J,
                                          refit_residual, r0, REFIT_ITERATIONS, scales=REFIT_SCALES, secant=True)
        if norm < float(r0 @ r0):
            coef, pred_after = tried[tuple(x)]
    # 5. the partial explanation refitted jointly with the terms: diagnose fitted it alone, where it took up part of
    # the mechanism the terms now hold, so its values are no longer the best beside them (measured: the model with both
    # outside the noise band). Its parameters (tangents: diagnose's forward differences at its values, or one set per
    # parameter at the model with the terms) and the plain terms' coefficients, Gauss-Newton on the events' mean in
    # the views' metric, within the partial's fit range and the terms' bounds, each step kept only when it lowers the
    # residual
    joint: dict = {}
    partial_fits = _partial_fits(run, up) if (JOINT_REFIT and on_top) else []
    if partial_fits:
        joint, coef, pred_after = _joint_refit(p, run, partial_fits, coef, cols, plain_cols, lo, d, pred_after,
                                               model_after, ref)
    r_before, r_after = p.project(p.residual(ref)), p.project(p.residual(pred_after))
    explained = p.explained_share(r_after, r_before)
    k = len(cols)
    delta_ic = p.ic(pred_after, k) - p.ic(ref, 0)
    after = consistency.test(p.views, p.residual(pred_after))
    pieces = []
    i = 0
    for g in stable:
        n = len(groups[g])
        pieces.append(candidate_terms.ProposedPiece(tuple(candidate_terms.with_knot(candidate_terms.with_center(
                                                        d.terms[c], centers.get(d.terms[c].center, 0.0)),
                                                        knot_of.get(d.terms[c].name, 0.0)) for c in groups[g]),
                                                    tuple(float(v) for v in coef[i:i + n]),
                                                    tuple(float(u) for u in unc[i:i + n]),
                                                    tuple(d.terms[groups[a][0]] for a in alike[g] if a != g)))
        i += n
    if explained <= MIN_EXPLAINED_SHARE:
        # stable over the resampled events, yet once in the model it does not lower the events' mean residual: the
        # terms fit the events one by one (a column built from each event's own recorded signal), not what they share
        out.reason = (f"{candidate_terms.proposal_law(pieces)} was selected in the resampled events but explains "
                      f"{100 * explained:.0f} % of the event average once in the model: nothing proposed")
        out.explained_fraction = float(explained)
        out.cpu_seconds = time.process_time() - t0
        out.simulated_sets = p.n_sets_simulated - n_before
        return out
    src, values = candidate_terms.proposal_source(pieces)
    out.proposed = True
    out.pieces = pieces
    out.law = candidate_terms.proposal_law(pieces)
    out.explained_fraction = float(explained)
    out.delta_ic = float(delta_ic)
    out.consistent = bool(after.consistent)
    out.views_after = after.to_json()
    out.plugin_source, out.plugin_values = src, values
    out.joint = {**out.joint, **joint}
    if joint.get("moved"):        # the partial explanation's values beside the terms: what --accept-proposal writes
        out.on_top_values = joint["values_after"]
        out.on_top_uncertainty = joint["uncertainty"]
    also = "".join(x.alike_text() for x in pieces)
    out.finding = (f"{out.law}{also}: explains {drive_terms.explained_percent(explained)} of the residual"
                   + (f" left by {' + '.join(on_top)}" if on_top else "")
                   + (f" (refitted with it: {_joint_text(joint)})" if joint.get("moved") else "")
                   + (f", instead of {' + '.join(replaced)} (the events' held-out error is smaller without it)"
                      if replaced else "")
                   + (", the model with it consistent in every view" if after.consistent
                      else ", the model with it still outside the noise band"))
    out.reason = out.finding + ("" if src else NO_PLUGIN_NOTE)
    out.cpu_seconds = time.process_time() - t0
    out.simulated_sets = p.n_sets_simulated - n_before
    return out
