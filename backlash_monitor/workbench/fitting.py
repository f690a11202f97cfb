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

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares, lsq_linear

from . import plant_adapter
from .events import denoise, ensemble_from_runs


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

    def to_json(self) -> dict:
        return {"effect": self.effect.split("[")[0], "candidate": self.effect,
                "parameters": {n: float(v) for n, v in zip(self.parameter_names, self.values)},
                "uncertainty": {n: float(u) for n, u in zip(self.parameter_names, self.uncertainty)},
                "nominal": {n: float(v) for n, v in zip(self.parameter_names, self.nominal)},
                "units": dict(zip(self.parameter_names, self.units)),
                "delta_ic": float(self.delta_ic), "explained_fraction": float(self.explained_fraction),
                "screening_explained_fraction": float(self.screening_explained),
                "indistinguishable_from": list(self.indistinguishable_from), "at_bound": bool(self.at_bound),
                "simulated_parameter_sets": int(self.evaluations), "balance": self.balance,
                "on_top_of": list(self.base), "description": self.description}


class Problem:
    """The measurement's target and the shared-noise machinery to evaluate the model at parameter sets."""

    def __init__(self, model, measured_events, seeds, n_samples, sample_period_s, conditions, weights,
                 base_sets=None):
        self.model = model
        self.events = measured_events                         # EventSet (raw)
        self.target = measured_events.mean_denoised()         # (2, L)
        self.event_denoised = denoise(measured_events.raw)    # (E, 2, L)
        self.seeds = list(seeds)
        self.n_samples = int(n_samples)
        self.dt = float(sample_period_s)
        self.conditions = dict(conditions)
        self.w = np.asarray(weights, dtype=float)[:, None]    # per signal 1 / noise-floor rms
        self.base = dict(base_sets or {})                     # parameter set of effects already added
        self.n_sets_simulated = 0
        self.basis = None      # (2L, q) orthonormal: the directions the candidates act in (set by diagnose)

    def _merge(self, sets):
        out = []
        for ps in sets:
            merged = dict(self.base)
            merged.update(ps)
            out.append(merged)
        return out

    def evaluate(self, sets):
        """Ensemble (denoised model means per set) of (scenario, config) override sets, one batch."""
        runs = plant_adapter.simulate_sets(self.model, self._merge(sets), self.seeds, self.n_samples,
                                           conditions=self.conditions)
        self.n_sets_simulated += len(sets)
        ens = ensemble_from_runs(runs, self.dt)
        return ens

    def residual(self, mean_denoised) -> np.ndarray:
        return ((self.target - mean_denoised) * self.w).ravel()

    def project(self, r: np.ndarray) -> np.ndarray:
        """Coordinates of a weighted residual (or Jacobian) in the whitened candidates' subspace (identity
        before the subspace is known): the generalised-least-squares metric of the fits."""
        return r if self.basis is None else self.basis.T @ r

    def fit_residual(self, mean_denoised) -> np.ndarray:
        return self.project(self.residual(mean_denoised))

    def ic(self, mean_denoised, k: int) -> float:
        d = (self.event_denoised - mean_denoised[None]) * self.w[None]
        e = d.shape[0]
        if self.basis is not None:
            # whitened candidate subspace: one Gaussian per direction, its variance estimated from the events
            z = d.reshape(e, -1) @ self.basis
            return float(e * np.sum(np.log(np.mean(z ** 2, axis=0))) + k * np.log(e))
        loss = np.mean(d ** 2, axis=(1, 2))
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


def screen(problem: Problem, effects, base_mean: np.ndarray, progress=None):
    """Every effect's parameters stepped by h from the model's values, all in ONE batch (per seed): the
    Jacobian columns and the linear (bounded) estimate of each effect. -> dict name -> info."""
    r0 = problem.residual(base_mean)
    out = {}
    sets, owners = [], []
    for eff in effects:
        x0 = eff.default_vector()
        h = _step(eff)
        for i in range(len(x0)):
            sets.append(plant_adapter.apply_values(eff, x0 + h[i] * np.eye(len(x0))[i]))
            owners.append((eff.name, i))
    ens = problem.evaluate(sets)
    means = {o: ens.mean_denoised(j) for j, o in enumerate(owners)}
    for eff in effects:
        x0 = eff.default_vector()
        h = _step(eff)
        cols = [((means[(eff.name, i)] - base_mean) * problem.w).ravel() / h[i] for i in range(len(x0))]
        J = np.stack(cols, axis=1)
        lo, hi = eff.bounds()
        # linear bounded step: min ||r0 - J d||, x0 + d within bounds
        d = lsq_linear(J, r0, bounds=(lo - x0, hi - x0 + 1e-300)).x
        explained = 1.0 - float(np.sum((r0 - J @ d) ** 2) / max(np.sum(r0 ** 2), 1e-300))
        out[eff.name] = {"J": J, "x_lin": x0 + d, "explained_lin": explained, "h": h}
        if progress is not None:
            progress(1)
    return out


def refine(problem: Problem, effect, screening: dict, base_mean: np.ndarray, base_ic: float,
           max_nfev: int = 4) -> FitResult:
    """Bounded least squares on the simulator (shared noise), starting at the linear estimate."""
    x0 = effect.default_vector()
    lo, hi = effect.bounds()
    cache: dict = {}
    raw: dict = {}

    def means_at(xs):
        todo = [tuple(np.round(x, 12)) for x in xs if tuple(np.round(x, 12)) not in cache]
        if todo:
            ens = problem.evaluate(_sets_for(effect, [np.array(t) for t in todo]))
            for i, t in enumerate(todo):
                cache[t] = ens.mean_denoised(i)
                raw[t] = ens.mean_raw(i)
        return [cache[tuple(np.round(x, 12))] for x in xs]

    cache[tuple(np.round(x0, 12))] = base_mean
    h_abs = np.abs(screening["h"]) * 0.5

    def fun(x):
        return problem.fit_residual(means_at([x])[0])

    def jac(x):
        steps = []
        for i in range(len(x)):
            e = np.eye(len(x))[i] * h_abs[i]
            xi = x + e if x[i] + e[i] <= hi[i] else x - e
            steps.append(xi)
        f0 = fun(x)
        ms = means_at(steps)
        return np.stack([(problem.fit_residual(m) - f0) / (s[i] - x[i]) for i, (m, s) in enumerate(zip(ms, steps))],
                        axis=1)

    margin = 1e-3 * (hi - lo)   # strictly inside: trf's first trust radius scales with the start's distance
    start = np.clip(screening["x_lin"], lo + margin, hi - margin)
    res = least_squares(fun, start, jac=jac, bounds=(lo, hi + 1e-300), method="trf", max_nfev=max_nfev,
                        x_scale=np.abs(screening["h"]))
    x = res.x
    m = means_at([x])[0]
    m_raw = raw.get(tuple(np.round(x, 12)))
    J = jac(x)
    unc = jackknife_uncertainty(problem, J, x, effect, m)
    # share of the residual explained, in the metric of the fit (the whitened candidates' subspace)
    r0 = problem.fit_residual(base_mean)
    r1 = problem.fit_residual(m)
    explained = 1.0 - float(np.sum(r1 ** 2) / max(np.sum(r0 ** 2), 1e-300))
    ic = problem.ic(m, len(x))
    at_bound = bool(np.any(np.isclose(x, lo, rtol=0, atol=1e-6 * (hi - lo)) |
                           np.isclose(x, hi, rtol=0, atol=1e-6 * (hi - lo))))
    return FitResult(effect.name, [p.name for p in effect.parameters], [p.unit for p in effect.parameters], x, unc,
                     x0, (lo, hi), explained, ic - base_ic, ic, m, screening["explained_lin"], len(cache),
                     effect.balance, effect.description, at_bound, model_mean_raw=m_raw)


def jackknife_uncertainty(problem: Problem, J: np.ndarray, x, effect, m) -> np.ndarray:
    """Standard error of the fitted values: delete-one-event jackknife of the measured average through
    the linearisation J (events = independent units)."""
    ev = problem.event_denoised
    e = ev.shape[0]
    pinv = np.linalg.pinv(J)
    total = ev.sum(axis=0)
    shifts = []
    for i in range(e):
        loo = (total - ev[i]) / (e - 1)
        d = problem.project(((loo - problem.target) * problem.w).ravel())
        # residual = w(target - m); moving the target by d moves the optimum by pinv(-J) applied to -d
        shifts.append(-(pinv @ d))
    shifts = np.array(shifts)
    se_meas = np.sqrt((e - 1) / e * np.sum((shifts - shifts.mean(axis=0)) ** 2, axis=0))
    # the model mean is itself an average over K seeds x E events: its noise adds ~ se_meas^2 / K
    k = max(len(problem.seeds), 1)
    return se_meas * np.sqrt(1.0 + 1.0 / k)
