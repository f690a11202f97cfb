"""Candidate-effect fitting on common random numbers, and the ranking on the events as independent units.

The fitted quantity is the event-averaged, sym5-denoised onset segment (a1, a2) of the measurement; the
model's prediction of it is the mean over ``K`` noise seeds of the same quantity in simulated runs. All
parameter sets of all candidates run on the same ``K`` seeds (common random numbers), so the prediction
is smooth in the parameters and differences between candidates are not noise.

Per candidate (docs/workbench.md, "How a candidate is fitted"):
1. screening: one batch with the parameter stepped by ``h`` from the model's value gives the column of
   the Jacobian; a linear least-squares step (clipped to the bounds) estimates the value and the share of
   the residual the effect can explain;
2. the best ``refine`` candidates: ``scipy.optimize.least_squares`` (trust-region, bounds) on the
   simulator itself, the Jacobian by a batched forward difference on the same seeds;
3. uncertainty: delete-one-event jackknife of the measured average (the events are the independent units)
   through the final Jacobian, combined with a delete-one-seed jackknife of the model's mean;
4. information criterion: per event e, L_e = mean of the weighted squared difference between that event's
   denoised segment and the model's mean; IC = E*ln(mean_e L_e) + k*ln(E), with E the number of events
   (BIC with the events as the sample). delta_ic = IC(candidate) - IC(model as is).
"""
from __future__ import annotations

import copy
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.optimize import least_squares, lsq_linear

from . import plant_adapter, spectral
from .events import NoOnsetWindow, concat_ensembles, denoise, ensemble_from_runs


LINEAR_EFFECTS = ("accelerometer_bias", "accelerometer_gain")   # a -> a + b, a -> a (1 + g)
AT_BOUND_FRACTION = 0.01     # of the fit range: a fitted value this close to a bound is 'pinned'
# The simulation batches' memory (Problem.evaluate): a diagnose screens ~50 parameter sets x 6 seeds; simulated in
# one batch their whole records at 50 kHz (4 recorded signals, the motor's load and supply arrays) made a 4 s
# recording's diagnose peak at 3.7 GB. Batches of BATCH_BYTES bound it; a batch of a few sets still runs the
# simulator's scenarios together (its per-batch cost is small against the 200k samples of each scenario)
BATCH_BYTES = 160e6
BATCH_ARRAYS_PER_SCENARIO = 10   # whole-record float64 arrays per scenario: 4 outputs, load, 2 supply, phase, copies


@dataclass
class FitResult:
    effect: str
    parameter_names: list
    units: list
    values: np.ndarray
    uncertainty: np.ndarray
    nominal: np.ndarray
    bounds: tuple
    explained_fraction: float
    delta_ic: float
    ic: float
    model_mean: np.ndarray            # (2, L) denoised mean at the fitted values
    screening_explained: float
    evaluations: int
    balance: str = ""
    description: str = ""
    at_bound: bool = False
    indistinguishable_from: list = field(default_factory=list)
    base: list = field(default_factory=list)   # effects this fit was made on top of
    model_mean_raw: np.ndarray | None = None   # (2, L) raw (not denoised) mean at the fitted values
    pred: np.ndarray | None = None             # the prediction vector at the fitted values (Problem.pred)
    jacobian: np.ndarray | None = None         # (N, k) d pred / d values at the fitted values (forward difference)
    fixed: dict = field(default_factory=dict)  # the candidate's fixed form parameters (e.g. {"a1_sections": 2.0})
    groups: tuple = ()                         # ((start, stop, z), ...): parameters significant together, not one by
    # one (a term locked to a shaft's angle: its harmonics' size over its jackknife uncertainty; a shape parameter of
    # its law, a lift ratio, may sit at its nominal while the term is there: angle_locked.py)

    def to_json(self) -> dict:
        return {"effect": self.effect.split("[")[0], "candidate": self.effect,
                "parameters": {n: float(v) for n, v in zip(self.parameter_names, self.values)} | dict(self.fixed),
                "uncertainty": {n: float(u) for n, u in zip(self.parameter_names, self.uncertainty)},
                "nominal": {n: float(v) for n, v in zip(self.parameter_names, self.nominal)},
                "units": dict(zip(self.parameter_names, self.units)),
                "delta_ic": float(self.delta_ic), "explained_fraction": float(self.explained_fraction),
                "screening_explained_fraction": float(self.screening_explained),
                "indistinguishable_from": list(self.indistinguishable_from), "at_bound": bool(self.at_bound),
                "simulated_parameter_sets": int(self.evaluations), "balance": self.balance,
                "on_top_of": list(self.base), "description": self.description}


@dataclass(frozen=True, eq=False)
class Linearisation:
    """One candidate's screening (:func:`screen`) and its linear estimate (:func:`linear_estimate`): the prediction's
    Jacobian at the model's values and the bounded linear step on it. The prediction is Problem.pred's weighted vector
    (N values, units of each coordinate's noise floor); k: the candidate's parameters."""
    jacobian: np.ndarray          # (N, k): d prediction / d parameter [per parameter unit]: secants of ``step`` on the
                                  # side that explains more; a sine/cosine pair's at x_lin (pair_estimate)
    step: np.ndarray              # (k,): the secants' steps h [parameter units], signed (a pair's: the amplitudes' and
                                  # the phase's, PAIR_PHASE_STEP_RAD); refine's forward differences and x_scale from it
    x_lin: np.ndarray             # (k,): the linear estimate of the parameters [parameter units]
    explained_lin: float          # the share of the residual's excess over the noise it removes (Problem.explained_share)
    delta_ic_lin: float | None = None      # its IC against the model as is (linear_estimate: in the whitened views)
    pred_lin: np.ndarray | None = None     # (N,): the prediction at x_lin, where it is not base + jacobian @ change
                                           # (a sine/cosine pair)
    pair_columns: np.ndarray | None = None  # (N, 2 m): a sine/cosine pair's responses (R0_i, R90_i) per amplitude i
                                            # per unit step (pair_estimate); None for secants

    def linear_pred(self, base_pred: np.ndarray, x0: np.ndarray) -> np.ndarray:
        """(N,): the linearised prediction at x_lin (pred_lin when there is one)."""
        return self.pred_lin if self.pred_lin is not None else base_pred + self.jacobian @ (self.x_lin - x0)


class Problem:
    """The measurement's target and the shared-noise machinery to evaluate the model at parameter sets.

    A *prediction* is one flat vector: the weighted denoised event average (w * m, 2 x L values) followed by
    the weighted spectral-shape features of the raw events (ws * s, workbench/spectral.py) and the weighted
    period means of a1, a2 (wdc * dc, events.period_means: the record-mean view). The measured
    events give the same vector per event; their mean is the target.

    ``views`` (consistency.ConsistencyViews): the whitened views the fits' metric and the IC look in; None before they
    are known (the screening, whose Jacobians they are built from: the identity metric). A problem with them is made
    whole by :meth:`with_views` (diagnose.screen_step)."""

    def __init__(self, model, measured_events, seeds, n_samples, sample_period_s, conditions, weights,
                 spec_weights, dc_weights, spec_noise=None, dc_names=("a1", "a2"), base_sets=None, views=None):
        self.model = model
        self.events = measured_events                         # EventSet (raw)
        self.target = measured_events.mean_denoised()         # (2, L)
        self.event_denoised = denoise(measured_events.raw)    # (E, 2, L)
        self.seeds = list(seeds)
        self.n_samples = int(n_samples)
        self.dt = float(sample_period_s)
        self.conditions = dict(conditions)
        self.w = np.asarray(weights, dtype=float)[:, None]    # per signal 1 / noise-floor rms
        self.ws = np.asarray(spec_weights, dtype=float)       # per spectral feature 1 / its noise floor
        self.wdc = np.asarray(dc_weights, dtype=float)        # per signal 1 / the record mean's noise floor
        self.spec_noise = None if spec_noise is None else np.asarray(spec_noise, dtype=float)  # sensor noise floor
        self.dc_names = tuple(dc_names)                       # the record-mean view's signals
        self.base = dict(base_sets or {})                     # parameter set of effects already added
        self.n_sets_simulated = 0
        self.views = views                                    # consistency.ConsistencyViews, or None
        e = self.event_denoised.shape[0]
        self.n_events = int(e)
        self.n_seeds = len(self.seeds)
        self.n_event_coords = int(self.target.size)
        spec = spectral.event_features(measured_events.raw, self.dt)
        ns = spec.shape[1]
        self.event_slice = slice(0, self.n_event_coords)
        self.spectral_slice = slice(self.n_event_coords, self.n_event_coords + ns)
        self.dc_slice = slice(self.n_event_coords + ns, self.n_event_coords + ns + self.wdc.size)
        self.event_vecs = np.hstack([(self.event_denoised * self.w[None]).reshape(e, -1), spec * self.ws[None],
                                     measured_events.dc * self.wdc[None]])
        self.target_vec = self.event_vecs.mean(axis=0)

    def with_views(self, views) -> "Problem":
        """This problem with the whitened views (consistency.ConsistencyViews of its screening): the fits' metric and
        the IC in them. The measured evidence and the machinery are shared, not copied."""
        out = copy.copy(self)
        out.views = views
        return out

    def _merge(self, sets):
        out = []
        for ps in sets:
            merged = dict(self.base)
            merged.update(ps)
            out.append(merged)
        return out

    def evaluate(self, sets, empty_ok: bool = False):
        """Ensemble (denoised model means per set) of (scenario, config) override sets, in batches of at most
        sets_per_batch sets: each batch's whole records are reduced to its events before the next is simulated
        (the same seeds in every batch: common random numbers hold across them). A set whose simulated drive gives
        no onset window raises events.NoOnsetWindow (its ``sets``: indices into ``sets``), or with ``empty_ok``
        stays with ``n_events`` 0 (ensemble_from_runs)."""
        merged = self._merge(sets)
        per = self.sets_per_batch()
        parts = []
        for i in range(0, len(merged), per):
            runs = plant_adapter.simulate_sets(self.model, merged[i:i + per], self.seeds, self.n_samples,
                                               conditions=self.conditions)
            try:
                parts.append(ensemble_from_runs(runs, self.dt, dc_names=self.dc_names, empty_ok=empty_ok))
            except NoOnsetWindow as error:
                raise NoOnsetWindow([i + j for j in error.sets]) from None
            del runs
        self.n_sets_simulated += len(sets)
        return concat_ensembles(parts)

    def sets_per_batch(self) -> int:
        """Parameter sets simulated in one batch: as many as fit BATCH_BYTES of whole-record samples (every seed,
        BATCH_SIGNALS signals and the simulator's working arrays, float64), at least one."""
        per_set = 8 * BATCH_ARRAYS_PER_SCENARIO * max(self.n_seeds, 1) * max(self.n_samples, 1)
        return max(1, int(BATCH_BYTES // per_set))

    def pred(self, mean_denoised, spec, dc) -> np.ndarray:
        return np.concatenate([(mean_denoised * self.w).ravel(), np.asarray(spec) * self.ws,
                               np.asarray(dc) * self.wdc])

    def pred_of(self, ens, i: int = 0) -> np.ndarray:
        return self.pred(ens.mean_denoised(i), ens.spec_mean(i, self.spec_noise), ens.dc_mean(i))

    def residual(self, pred) -> np.ndarray:
        return self.target_vec - pred

    def event_part(self, r) -> np.ndarray:
        return r[:self.n_event_coords]

    def project(self, r: np.ndarray) -> np.ndarray:
        """Coordinates of a weighted residual (or Jacobian) in the whitened views -- the candidates' subspace and
        the noise directions outside it (``views.fit_basis``; identity before they are known): the generalised-least-
        squares metric of the fits. (Fitted in the subspace alone, a strong effect whose shape at its fitted value
        leaves the secants' subspace was matched inside it while the rest grew outside: measured on a foreign
        eta_k +60 %, 99.8 % explained inside, the outside view made worse.)"""
        return r if self.views is None else self.views.fit_basis.T @ r

    def fit_residual(self, pred) -> np.ndarray:
        return self.project(self.residual(pred))

    def explained_share(self, r_after, r_before) -> float:
        """The share of the residual's *excess over the noise* an update removes, from two projected residuals
        (fit_residual): (R0 - R1) / (R0 - n), R = |r|^2 / c in units of the measured mean's noise, n the metric's
        directions (what R is under a correct model). A weak effect's residual is half noise: measured on a foreign
        +50 % spring (T^2 35 against 20), the right effect removed 50 % of the residual but nearly all of its
        excess. Identity before the views are known."""
        r0 = float(np.sum(np.asarray(r_before) ** 2))
        r1 = float(np.sum(np.asarray(r_after) ** 2))
        if self.views is None:
            return 1.0 - r1 / max(r0, 1e-300)
        c = 1.0 / self.n_events + 1.0 / (self.n_events * max(self.n_seeds, 1))
        noise = float(self.views.fit_basis.shape[1]) * c
        return (r0 - r1) / max(r0 - noise, 1e-3 * r0, 1e-300)

    def events_in_views(self) -> np.ndarray:
        """The measured events' vectors in the whitened views' basis (E, k): taken once per views object, not per
        IC (the fits and the proposal take ~200 ICs of one problem; (E x n) @ (n x k) was a third of a diagnosis)."""
        kept = self.__dict__.get("_events_in_views")
        if kept is None or kept[0] is not self.views:
            kept = (self.views, self.event_vecs @ self.views.basis)
            self._events_in_views = kept
        return kept[1]

    def ic(self, pred, k: int) -> float:
        e = self.event_vecs.shape[0]
        if self.views is not None:
            # whitened candidate subspace: one Gaussian per direction, its variance estimated from the events;
            # (events - pred) @ basis taken as events @ basis (kept) - pred @ basis
            z = self.events_in_views() - (np.asarray(pred) @ self.views.basis)[None]
            return float(e * np.sum(np.log(np.mean(z ** 2, axis=0))) + k * np.log(e))
        d = self.event_vecs - pred[None]
        loss = np.mean(d[:, :self.n_event_coords] ** 2, axis=1)
        return float(e * np.log(np.mean(loss)) + k * np.log(e))


def _step(effect) -> np.ndarray:
    lo, hi = effect.bounds()
    x0 = effect.default_vector()
    h = 0.15 * (hi - lo)
    # step into the interior: away from the nearer bound
    sign = np.where(hi - x0 >= x0 - lo, 1.0, -1.0)
    return sign * h


def _sets_for(effect, values_list):
    return [plant_adapter.apply_values(effect, v) for v in values_list]


def _two_sided(effect, h) -> np.ndarray:
    """Per parameter: True when the model's value has room for a step of |h| on both sides."""
    lo, hi = effect.bounds()
    x0 = effect.default_vector()
    if effect.effect in LINEAR_EFFECTS:        # exactly linear in the parameter: one secant is the derivative
        return np.zeros(len(x0), bool)
    return (x0 - np.abs(h) >= lo) & (x0 + np.abs(h) <= hi)


# A screening step whose simulated drive crosses no backlash (seen: a proposed speed-proportional load stepped 0.3 p.u.
# below its fitted value turned the motor's damping negative and it ran away to 7e4 rad/s) is tried again this much
# shorter, at most STEP_BACK_TRIES times (0.15 of the range -> 0.0375 -> 0.0094 -> 0.0023): a secant is a derivative
# at any length the model stays in its regime at; the screening's other sets are kept
STEP_BACK_FACTOR = 0.25
STEP_BACK_TRIES = 3
# refine's least squares at a point out of that regime: the model's residual as is, this many times (any factor > 1
# is refused by trf's reduction ratio; 10 keeps the cost finite and its gradient meaningless, never used: trf only
# takes Jacobians at points it accepted)
REGIME_WALL = 10.0


def _stepped_predictions(problem: Problem, effects, steps: dict) -> dict:
    """{owner: prediction} of every secant's set (owner: (effect name, parameter index, side); ``steps``: owner ->
    signed step, shortened in place where the model with the step gave no onset window) and of every sine/cosine
    pair's points (owner: (name, point, "pair")), all in one batch first."""
    by_name = {eff.name: eff for eff in effects}
    owners, sets = [], []
    for eff in effects:
        if angle_pair(eff):
            for j, (_, x) in enumerate(pair_points(eff)):
                sets.append(plant_adapter.apply_values(eff, x))
                owners.append((eff.name, j, "pair"))
    pair_count = len(owners)

    def set_of(owner, h):
        eff = by_name[owner[0]]
        x0 = eff.default_vector()
        return plant_adapter.apply_values(eff, x0 + h * np.eye(len(x0))[owner[1]])

    secants = list(steps)
    ens = problem.evaluate(sets + [set_of(o, steps[o]) for o in secants], empty_ok=True)
    empty = (ens.n_events == 0).any(axis=1)
    if empty[:pair_count].any():
        name = owners[int(np.flatnonzero(empty[:pair_count])[0])][0]
        raise NoOnsetWindow(np.flatnonzero(empty[:pair_count]),
                            f"{name}: the model with its sine/cosine pair's amplitude step gives no onset window -- "
                            "the drive does not cross its backlash there; check the term's values in the model file")
    preds = {o: problem.pred_of(ens, j) for j, o in enumerate(owners)}
    retry = []
    for j, o in enumerate(secants):
        if empty[pair_count + j]:
            retry.append(o)
        else:
            preds[o] = problem.pred_of(ens, pair_count + j)
    for _ in range(STEP_BACK_TRIES):
        if not retry:
            break
        for o in retry:
            steps[o] *= STEP_BACK_FACTOR
        ens = problem.evaluate([set_of(o, steps[o]) for o in retry], empty_ok=True)
        empty = (ens.n_events == 0).any(axis=1)
        for j, o in enumerate(retry):
            if not empty[j]:
                preds[o] = problem.pred_of(ens, j)
        retry = [o for j, o in enumerate(retry) if empty[j]]
    if retry:
        name, i, _ = retry[0]
        param = by_name[name].parameters[i]
        raise ScreeningStepError(param.key, float(param.default), float(steps[retry[0]]))
    return preds


class ScreeningStepError(NoOnsetWindow):
    """A parameter whose every screening step (down to STEP_BACK_FACTOR**STEP_BACK_TRIES of the first) leaves the
    model's drive without an onset window: the model at its value is at the edge of a regime it cannot leave."""

    def __init__(self, key: str, value: float, shortest_step: float):
        super().__init__((), f"{key} = {value:.4g}: the model with it stepped by {shortest_step:+.3g} (and by every "
                             "longer step tried) gives no onset window -- the drive does not cross its backlash there; "
                             "check this value in the model file (an accepted proposal's or a plug-in's)")


def screen(problem: Problem, effects, base_pred: np.ndarray, progress=None, two_sided: bool = True):
    """Every effect's parameters stepped by h from the model's values, all in ONE batch (per seed): the
    Jacobian columns and the linear (bounded) estimate of each effect. With ``two_sided``, a parameter with
    room on both sides is stepped by +h and -h (a secant on one side misses an effect that bends the other
    way, e.g. a smaller pulse amplitude); the side whose secants explain more is kept. A step whose model crosses
    no backlash is tried again shorter (STEP_BACK_FACTOR; the Linearisation's ``step`` is the one taken).
    -> {name: Linearisation}."""
    r0 = problem.residual(base_pred)
    out = {}
    steps = {}
    for eff in effects:
        if angle_pair(eff):
            continue
        x0 = eff.default_vector()
        h = _step(eff)
        both = _two_sided(eff, h) if two_sided else np.zeros(len(x0), bool)
        for sign in (1.0, -1.0):
            for i in range(len(x0)):
                if sign < 0 and not both[i]:
                    continue
                steps[(eff.name, i, sign)] = sign * h[i]
    preds = _stepped_predictions(problem, effects, steps)
    lin_r0 = problem.project(r0)
    for eff in effects:
        if angle_pair(eff):
            pts = pair_points(eff)
            h = _pair_steps(eff)
            cols = np.stack([(preds[(eff.name, j, "pair")] - base_pred) / h[i] for j, (i, _) in enumerate(pts)],
                            axis=1)
            out[eff.name] = pair_estimate(problem, eff, cols, h, base_pred, lin_r0)
            if progress is not None:
                progress(1)
            continue
        x0 = eff.default_vector()
        lo, hi = eff.bounds()
        best = None
        for sign in (1.0, -1.0):
            # the other side where a parameter was stepped on it (its room on both sides: the steps made above)
            keys = [(eff.name, i, sign) if (eff.name, i, sign) in steps else (eff.name, i, 1.0)
                    for i in range(len(x0))]
            if sign < 0 and all(k[2] > 0 for k in keys):
                continue
            h = np.array([steps[k] for k in keys])
            cols = [(preds[k] - base_pred) / h[i] for i, k in enumerate(keys)]
            J = np.stack(cols, axis=1)
            jp = problem.project(J)
            # linear bounded step: min ||r0 - J d||, x0 + d within bounds
            d = lsq_linear(jp, lin_r0, bounds=(lo - x0, hi - x0 + 1e-300)).x
            explained = problem.explained_share(lin_r0 - jp @ d, lin_r0)
            if best is None or explained > best.explained_lin:
                best = Linearisation(J, h, x0 + d, explained)
        out[eff.name] = best
        if progress is not None:
            progress(1)
    return out


# ------------------------------------------------------------------ terms locked to a shaft's angle: sine/cosine pairs
PAIR_PHASE_STEP_RAD = 0.5     # the phase's step of the refinement's forward differences and its x_scale


def angle_pair(effect) -> bool:
    """A term locked to a shaft's angle (plant_adapter.angle_phase_index) whose amplitudes are 0 in the model: its
    phase has no derivative there, so it is screened as a sine/cosine pair instead of by secants."""
    k = getattr(effect, "phase_index", -1)
    if k < 0:
        return False
    x0 = effect.default_vector()
    return bool(np.all(np.delete(x0, k) == 0.0)) and len(x0) >= 2


def _pair_steps(effect) -> np.ndarray:
    h = np.abs(_step(effect))
    h[effect.phase_index] = PAIR_PHASE_STEP_RAD
    return h


def _wrap(phase):
    return (np.asarray(phase, float) + np.pi) % (2.0 * np.pi) - np.pi


def pair_points(effect) -> list:
    """(amplitude index, parameter vector) of the pair's simulations: each amplitude stepped by h at the model's
    phase phi0 and at phi0 + pi/2. For a law A*g(alpha + phi) the response to a small amplitude is
    (A/h)*(cos(d)*R0 + sin(d)*R90) with d = phi - phi0: linear in (A cos d, A sin d)."""
    k = effect.phase_index
    x0 = effect.default_vector()
    h = _pair_steps(effect)
    pts = []
    for i in range(len(x0)):
        if i == k:
            continue
        for shift in (0.0, 0.5 * np.pi):
            x = x0.copy()
            x[i] += h[i]
            x[k] = float(_wrap(x0[k] + shift))
            pts.append((i, x))
    return pts


def pair_estimate(problem: Problem, effect, pair_columns: np.ndarray, step: np.ndarray, base_pred: np.ndarray,
                  r0g=None) -> Linearisation:
    """The linear estimate of a sine/cosine pair (unbounded in its coefficients, then the amplitudes clipped to the
    bounds): x_lin, the linear prediction there, the share explained and the Jacobian at x_lin (amplitude columns
    along the fitted phase, the phase column at the fitted amplitude -- at least one step -- so that the views'
    subspace holds both directions)."""
    k = effect.phase_index
    x0 = effect.default_vector()
    lo, hi = effect.bounds()
    h = step
    cols = pair_columns                              # (N, 2 m): (R0_i, R90_i) per amplitude i
    if r0g is None:
        r0g = problem.project(problem.residual(base_pred))
    g = problem.project(cols)
    c = np.linalg.lstsq(g, r0g, rcond=None)[0].reshape(-1, 2)     # (m, 2): per amplitude (cos d, sin d) * A / h
    amp_idx = [i for i in range(len(x0)) if i != k]
    mags = np.hypot(c[:, 0], c[:, 1])
    j = int(np.argmax(mags))
    d = float(np.arctan2(c[j, 1], c[j, 0]))
    x = x0.copy()
    phase = float(_wrap(x0[k] + d))
    x[k] = float(np.clip(phase, lo[k], hi[k]))
    d = x[k] - x0[k]
    for m, i in enumerate(amp_idx):
        # the amplitude along the common phase (a negative projection: the amplitude's lower bound)
        a = h[i] * (c[m, 0] * np.cos(d) + c[m, 1] * np.sin(d))
        x[i] = float(np.clip(x0[i] + a, lo[i], hi[i]))
    r0c, r90c = cols[:, 0::2], cols[:, 1::2]
    amps = np.array([x[i] - x0[i] for i in amp_idx])
    hs = np.array([h[i] for i in amp_idx])
    along = np.cos(d) * r0c + np.sin(d) * r90c                    # (N, m) per unit step h
    shift = along @ (amps / hs)
    J = np.zeros((cols.shape[0], len(x0)))
    for m, i in enumerate(amp_idx):
        J[:, i] = along[:, m] / hs[m]
    J[:, k] = (-np.sin(d) * r0c + np.cos(d) * r90c) @ (np.maximum(np.abs(amps), hs) / hs)
    pred = base_pred + shift
    explained = problem.explained_share(r0g - problem.project(shift), r0g)
    return Linearisation(J, step, x, explained, pred_lin=pred, pair_columns=pair_columns)


def linear_estimate(problem: Problem, effect, screened: Linearisation, base_pred: np.ndarray,
                    base_ic: float) -> Linearisation:
    """The linear estimate of ``effect`` in the problem's (whitened) metric: ``screened`` with x_lin, explained_lin,
    delta_ic_lin from it (diagnose.screen_step, once the views are known). A bounded linear step on the screening's
    secants; a term locked to a shaft's angle as a sine/cosine pair (pair_estimate)."""
    x0 = effect.default_vector()
    if screened.pair_columns is not None:
        out = pair_estimate(problem, effect, screened.pair_columns, screened.step, base_pred)
        return replace(out, delta_ic_lin=problem.ic(out.pred_lin, len(x0)) - base_ic)
    lo, hi = effect.bounds()
    r0g = problem.project(problem.residual(base_pred))
    jg = problem.project(screened.jacobian)
    d = lsq_linear(jg, r0g, bounds=(lo - x0, hi - x0 + 1e-300)).x
    return replace(screened, x_lin=x0 + d, explained_lin=problem.explained_share(r0g - jg @ d, r0g),
                   delta_ic_lin=problem.ic(base_pred + screened.jacobian @ d, len(x0)) - base_ic)


def refine(problem: Problem, effect, start: Linearisation, base_pred: np.ndarray, base_ic: float,
           max_nfev: int = 4) -> FitResult:
    """Bounded least squares on the simulator (shared noise), starting at the linear estimate ``start`` (its x_lin,
    its steps for the forward differences and the scale)."""
    x0 = effect.default_vector()
    lo, hi = effect.bounds()
    cache: dict = {}
    means: dict = {}
    raw: dict = {}

    def preds_at(xs):
        """The predictions at the points xs; None at a point whose simulated drive gives no onset window."""
        todo = list(dict.fromkeys(tuple(np.round(x, 12)) for x in xs if tuple(np.round(x, 12)) not in cache))
        if todo:
            ens = problem.evaluate(_sets_for(effect, [np.array(t) for t in todo]), empty_ok=True)
            for i, t in enumerate(todo):
                if ens.n_events[i].min() == 0:
                    cache[t] = None
                    continue
                cache[t] = problem.pred_of(ens, i)
                means[t] = ens.mean_denoised(i)
                raw[t] = ens.mean_raw(i)
        return [cache[tuple(np.round(x, 12))] for x in xs]

    cache[tuple(np.round(x0, 12))] = base_pred
    h_abs = np.abs(start.step) * 0.5
    # where the model leaves the regime it crosses its backlash in (no onset window: a run-away or a stalled drive)
    # trf meets a wall: a residual REGIME_WALL times the model's as is, a step there is refused and its region shrunk
    wall = REGIME_WALL * problem.fit_residual(base_pred)

    def fun(x):
        pred = preds_at([x])[0]
        return wall if pred is None else problem.fit_residual(pred)

    def jac_pred(x):
        """Forward difference of the prediction (prediction space, not projected); a difference whose point leaves
        the regime is taken on the other side, then shorter (STEP_BACK_FACTOR)."""
        steps = _fd_steps(x, h_abs, hi)
        preds = preds_at(steps)
        for i, m in enumerate(preds):
            if m is not None:
                continue
            h = steps[i][i] - x[i]
            tries = ([-h] if lo[i] <= x[i] - h <= hi[i] else []) + [h * STEP_BACK_FACTOR ** k
                                                                     for k in range(1, STEP_BACK_TRIES + 1)]
            for t in tries:
                point = np.array(x, dtype=float)
                point[i] += t
                m = preds_at([point])[0]
                if m is not None:
                    steps[i], preds[i] = point, m
                    break
            if m is None:
                raise ScreeningStepError(effect.parameters[i].key, float(x[i]), float(tries[-1]))
        return forward_differences(preds_at([x])[0], preds, x, steps)

    last = {}

    def jac(x):
        # residual = target - pred: d residual = -d pred
        last["x"], last["J"] = np.array(x, float), jac_pred(x)
        return -problem.project(last["J"])

    margin = 1e-3 * (hi - lo)   # strictly inside: trf's first trust radius scales with the start's distance
    x_start = np.clip(start.x_lin, lo + margin, hi - margin)
    # a linear estimate outside the regime: back towards the model's values until the drive crosses its backlash
    for _ in range(STEP_BACK_TRIES):
        if preds_at([x_start])[0] is not None:
            break
        x_start = np.clip(x0 + STEP_BACK_FACTOR * (x_start - x0), lo + margin, hi - margin)
    if preds_at([x_start])[0] is None:
        x_start = np.clip(x0, lo + margin, hi - margin)
    res = least_squares(fun, x_start, jac=jac, bounds=(lo, hi + 1e-300), method="trf", max_nfev=max_nfev,
                        x_scale=np.abs(start.step))
    x = res.x
    p = preds_at([x])[0]
    key = tuple(np.round(x, 12))
    m = means.get(key)
    m_raw = raw.get(key)
    # the Jacobian for the uncertainty (and the pair search's linearisation): at x when its steps are simulated
    # already (x is where trf last took one), else the last one trf took -- one accepted step before x, which
    # trf reached on its last allowed evaluation (a step that small changes the uncertainty by a few per cent,
    # not worth n more simulated sets)
    done_here = all(tuple(np.round(s_, 12)) in cache for s_ in _fd_steps(x, h_abs, hi))
    J_pred = jac_pred(x) if done_here or "J" not in last else last["J"]
    J = -problem.project(J_pred)
    unc = jackknife_uncertainty(problem, J, x, effect, m)
    # share of the residual's excess over the noise explained, in the metric of the fit
    explained = problem.explained_share(problem.fit_residual(p), problem.fit_residual(base_pred))
    ic = problem.ic(p, len(x))
    # pinned: within AT_BOUND_FRACTION of the range from a bound the model's value is not on (a fit that
    # stops there is being stretched to mimic something else; measured: motor_load_offset 0.39997 of 0.4
    # on a rotor-resistance recording)
    tol = AT_BOUND_FRACTION * (hi - lo)
    at_bound = bool(np.any(((x - lo <= tol) & (np.abs(x0 - lo) > tol)) | ((hi - x <= tol) & (np.abs(hi - x0) > tol))))
    return FitResult(effect.name, [p_.name for p_ in effect.parameters], [p_.unit for p_ in effect.parameters], x,
                     unc, x0, (lo, hi), explained, ic - base_ic, ic, m, start.explained_lin, len(cache),
                     effect.balance, effect.description, at_bound, model_mean_raw=m_raw, pred=p, jacobian=J_pred,
                     fixed=getattr(effect, "fixed_values", {}))


def forward_differences(p0: np.ndarray, preds, x, steps) -> np.ndarray:
    """(N, k): the prediction's forward differences, column i (preds[i] - p0) / (steps[i][i] - x[i]) for the points
    steps of _fd_steps (one parameter stepped each)."""
    return np.stack([(m - p0) / (s[i] - x[i]) for i, (m, s) in enumerate(zip(preds, steps))], axis=1)


def _fd_steps(x, h_abs, hi) -> list:
    """The forward-difference points of x: one parameter stepped by h_abs (backwards at the upper bound)."""
    steps = []
    for i in range(len(x)):
        e = np.eye(len(x))[i] * h_abs[i]
        steps.append(x + e if x[i] + e[i] <= hi[i] else x - e)
    return steps


def jackknife_uncertainty(problem: Problem, J: np.ndarray, x, effect, m) -> np.ndarray:
    """Standard error of the fitted values: delete-one-event jackknife of the measured average through
    the linearisation J (events = independent units)."""
    ev = problem.event_vecs
    e = ev.shape[0]
    pinv = np.linalg.pinv(J)
    total = ev.sum(axis=0)
    shifts = []
    for i in range(e):
        loo = (total - ev[i]) / (e - 1)
        d = problem.project(loo - problem.target_vec)
        # residual = w(target - m); moving the target by d moves the optimum by pinv(-J) applied to -d
        shifts.append(-(pinv @ d))
    shifts = np.array(shifts)
    se_meas = np.sqrt((e - 1) / e * np.sum((shifts - shifts.mean(axis=0)) ** 2, axis=0))
    # the model mean is itself an average over K seeds x E events: its noise adds ~ se_meas^2 / K
    k = max(len(problem.seeds), 1)
    return se_meas * np.sqrt(1.0 + 1.0 / k)
