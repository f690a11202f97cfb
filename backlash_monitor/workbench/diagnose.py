"""``diagnose``: where the model fails on a measurement, and which catalogue effect is missing.

Decision rules (docs/workbench.md, "Decisions"):
- the model is *inconsistent* with the measurement when the residual of the event average exceeds
  INCONSISTENT_RATIO times the noise floor (the model's own leave-one-seed-out deviation);
- a candidate is a *discovery* when the model is inconsistent, its delta_ic <= -DELTA_IC_STRONG (BIC on
  the events), it explains >= MIN_EXPLAINED of the residual and its value is not pinned at a bound;
- two candidates are *indistinguishable* when both qualify and their IC differ by < DELTA_IC_TIE;
- after a discovery whose model is still inconsistent, every other candidate is fitted on top of it and
  reported as a second effect by the same rules (delta_ic against the one-effect model).
"""
from __future__ import annotations

import time

import numpy as np
from scipy import stats

from . import analysis, fitting, plant_adapter, separation
from .events import SEGMENT_SIGNALS, denoise

DELTA_IC_STRONG = 2.0     # "positive" evidence (Kass & Raftery) on E events; docs/workbench.md
DELTA_IC_TIE = 2.0
MIN_EXPLAINED = 0.5
MIN_EXPLAINED_SECOND = 0.3
REFINE_TOP = 3
SUBSPACE_ENERGY = 0.99       # share of the candidates' reach the subspace keeps
SUBSPACE_MAX_DIM = 12


def _inconsistent(comp, problem, r) -> bool:
    """The weighted residual r beyond the noise band: overall, or in the candidates' subspace."""
    if np.sqrt(np.mean(r ** 2)) > analysis.INCONSISTENT_RATIO:
        return True
    t2, limit = hotelling(comp, problem, r)
    return bool(t2 > limit)


CONFIDENT_EXPLAINED = 0.9


def _confident(comp, problem, after_mean, base_mean) -> bool:
    """The model with the discovered effect(s) agrees with the measurement: overall residual/noise within
    INCONSISTENT_RATIO, and either T^2 in the subspace within its limit or >= CONFIDENT_EXPLAINED of the
    (whitened) residual explained (a strong effect fitted to 98 % can leave a T^2 above the limit from the
    fit's own finite accuracy)."""
    r = problem.residual(after_mean)
    if np.sqrt(np.mean(r ** 2)) > analysis.INCONSISTENT_RATIO:
        return False
    t2, limit = hotelling(comp, problem, r)
    r0g = problem.fit_residual(base_mean)
    explained = 1 - float(np.sum(problem.project(r) ** 2) / max(np.sum(r0g ** 2), 1e-300))
    return bool(t2 <= limit or explained >= CONFIDENT_EXPLAINED)


def whiten(basis: np.ndarray, comp) -> np.ndarray:
    """basis @ C^(-1/2), C the covariance of the model's own events in the subspace (all seeds' events,
    minus the model mean): the projected event residuals then have unit variance per direction."""
    m = comp.model_mean
    z = []
    for raw in comp.ensemble.per_event:
        d = (denoise(raw) - m[None]) * comp.weights[None, :, None]
        z.append(d.reshape(d.shape[0], -1) @ basis)
    z = np.vstack(z)
    cov = np.cov(z, rowvar=False).reshape(basis.shape[1], basis.shape[1])
    vals, vecs = np.linalg.eigh(cov)
    vals = np.maximum(vals, 1e-12 * vals.max())
    return basis @ (vecs / np.sqrt(vals)[None, :]) @ vecs.T


def hotelling(comp, problem, r) -> tuple[float, float]:
    """T^2 of the measured event average's residual in the whitened subspace (E events, the model mean's own
    noise from K seeds included) and its 1 % limit (chi-square, q dof)."""
    e = comp.events.n_events
    k = len(comp.seeds)
    z = problem.basis.T @ r
    t2 = float(np.sum(z ** 2) / (1.0 / e + 1.0 / (e * k)))
    return t2, float(stats.chi2.ppf(0.99, problem.basis.shape[1]))


def candidate_basis(scr: dict, by_name: dict) -> np.ndarray:
    """Orthonormal basis of the directions the candidates move the weighted event average in: SVD of
    their Jacobian columns scaled by their fit ranges, keeping SUBSPACE_ENERGY of the energy."""
    cols = []
    for n, info in scr.items():
        lo, hi = by_name[n].bounds()
        cols.append(info["J"] * (hi - lo)[None, :])
    s_mat = np.hstack(cols)
    u, sv, _ = np.linalg.svd(s_mat, full_matrices=False)
    energy = np.cumsum(sv ** 2) / max(np.sum(sv ** 2), 1e-300)
    q = int(min(SUBSPACE_MAX_DIM, np.searchsorted(energy, SUBSPACE_ENERGY) + 1))
    return u[:, :q]


def _where_acts(fit) -> str:
    """Where a fitted candidate acts on the drive (separation.location), drifts by their target."""
    from backlash_monitor.plant import effects as plant_effects
    cls = plant_effects.catalogue().get(fit.effect.split("[")[0])
    return separation.location(fit.effect, fit.balance, getattr(cls, "target", None))


def _separating_measurement(a, b) -> str:
    """What recording or sensor would tell two candidates apart, from where each acts."""
    return separation.separating_measurement(a.effect, _where_acts(a), b.effect, _where_acts(b))


def diagnose(meas, model, seeds=None, effects=None, progress=None, second: bool = True) -> dict:
    """Full diagnosis; returns a dict with the JSON fields and, under "_arrays", the data for the report."""
    t0 = time.perf_counter()
    comp = analysis.build_comparison(meas, model, seeds)
    base_mean = comp.model_mean
    problem = fitting.Problem(model, comp.events, comp.seeds, meas.n_samples, meas.sample_period_s,
                              comp.conditions, comp.weights)
    ratio_before = analysis.residual_ratio(comp)
    overall_before = float(np.sqrt(np.mean(ratio_before ** 2)))
    inconsistent = overall_before > analysis.INCONSISTENT_RATIO
    catalogue = plant_adapter.catalogue(model)
    if effects:
        unknown = [e for e in effects if e not in {c.name for c in catalogue} | {c.effect for c in catalogue}]
        if unknown:
            raise ValueError(f"effect {unknown[0]!r} is not in the catalogue; allowed: "
                             + ", ".join(c.name for c in catalogue))
        catalogue = [c for c in catalogue if c.name in effects or c.effect in effects]
    where_before = analysis.where(comp)
    scr = fitting.screen(problem, catalogue, base_mean, progress=progress)
    # the candidates' subspace: what the catalogue can change in the event average (from the model's
    # Jacobians over the fit ranges, before any fit to the measurement); the IC and the consistency gate
    # are taken in it, so the events' noise in directions no candidate moves does not drown the evidence
    problem.basis = whiten(candidate_basis(scr, by_name := {c.name: c for c in catalogue}), comp)
    base_ic = problem.ic(base_mean, 0)
    r0 = problem.residual(base_mean)
    t2, t2_limit = hotelling(comp, problem, r0)
    sub_ratio = float(np.sqrt(t2 / problem.basis.shape[1]))
    inconsistent = inconsistent or t2 > t2_limit
    # the linear estimates again, in the whitened subspace (generalised least squares)
    r0g = problem.project(r0)
    for n, info in scr.items():
        eff = by_name[n]
        x0 = eff.default_vector()
        lo, hi = eff.bounds()
        jg = problem.project(info["J"])
        d = fitting.lsq_linear(jg, r0g, bounds=(lo - x0, hi - x0 + 1e-300)).x
        info["x_lin"] = x0 + d
        info["explained_lin"] = 1.0 - float(np.sum((r0g - jg @ d) ** 2) / max(np.sum(r0g ** 2), 1e-300))
    order = sorted(scr, key=lambda k: -scr[k]["explained_lin"])
    fits = [fitting.refine(problem, by_name[n], scr[n], base_mean, base_ic) for n in order[:REFINE_TOP]]
    fits.sort(key=lambda f: f.delta_ic)

    def qualifies(f, min_expl):
        return f.delta_ic <= -DELTA_IC_STRONG and f.explained_fraction >= min_expl and not f.at_bound

    qual = [f for f in fits if qualifies(f, MIN_EXPLAINED)] if inconsistent else []
    discovery = qual[0] if qual else None
    if discovery is not None:
        for f in qual[1:]:
            if f.delta_ic - discovery.delta_ic < DELTA_IC_TIE:
                discovery.indistinguishable_from.append(f.effect)
                f.indistinguishable_from.append(discovery.effect)
    ranked = [f.to_json() for f in fits] + [
        {"effect": n, "parameters": {p.name: float(v) for p, v in zip(by_name[n].parameters, scr[n]["x_lin"])},
         "uncertainty": None, "delta_ic": None, "explained_fraction": float(scr[n]["explained_lin"]),
         "indistinguishable_from": [], "screening_only": True, "balance": by_name[n].balance}
        for n in order[REFINE_TOP:]]
    for r in ranked:
        if discovery is not None and r["effect"] in discovery.indistinguishable_from:
            r["separating_measurement"] = _separating_measurement(discovery, next(f for f in fits
                                                                                 if f.effect == r["effect"]))
    # identifiability: how far the whole fit range moves the event average, in noise floors (linearised)
    identifiability = {}
    for n in order:
        eff = by_name[n]
        lo, hi = eff.bounds()
        span = scr[n]["J"] * (hi - lo)[None, :]
        reach = float(np.max(np.sqrt(np.mean(span ** 2, axis=0))))
        identifiability[n] = {"range_effect_over_noise_floor": reach,
                              "identifiable": reach >= 1.0}
    after_mean = discovery.model_mean if discovery is not None else base_mean
    after_raw = discovery.model_mean_raw if discovery is not None else None
    second_fit = None
    pair = None
    if discovery is not None and second:
        pair = _second_effect(comp, problem, model, discovery, by_name, scr, order, base_mean, base_ic)
        if pair is not None:
            fit2, a, b = pair
            after_mean = fit2.model_mean
            after_raw = fit2.model_mean_raw
            # the pair replaces the single winner: split it into its two effects
            na = len(by_name[a].parameters)
            first = _part(fit2, by_name[a], slice(0, na), [])
            second_fit = _part(fit2, by_name[b], slice(na, None), [a])
            if discovery.effect not in (a, b):
                first.indistinguishable_from = []
            discovery = first
        else:
            second_fit = _greedy_second(comp, problem, model, discovery, by_name, scr, order)
            if second_fit is not None:
                after_mean = second_fit.model_mean
                after_raw = second_fit.model_mean_raw
    ratio_after = analysis.residual_ratio(comp, after_mean)
    best = fits[0] if fits else None
    partial = None
    if discovery is not None and not _confident(comp, problem, after_mean, base_mean):
        # the effect(s) leave the residual outside the noise band: a partial explanation, not a discovery
        partial = (discovery, second_fit)
        discovery, second_fit, after_mean, after_raw = None, None, base_mean, None
        ratio_after = analysis.residual_ratio(comp, after_mean)
    if discovery is None and partial is not None:
        wb = where_before
        p1, p2 = partial
        message = (f"no confident discovery: {p1.effect}" + (f" + {p2.effect}" if p2 is not None else "")
                   + f" explains {(p2 or p1).explained_fraction:.0%} of the residual but leaves it outside the "
                   f"noise band (an effect outside the catalogue?); the residual sits in the "
                   f"{wb['dominant_phase'].replace('_', ' ')} phase and wavelet level {wb['dominant_level']}")
    elif discovery is None:
        if not inconsistent:
            message = (f"the model agrees with the measurement within its noise band (residual "
                       f"{overall_before:.2f} x the noise floor): nothing to discover")
        else:
            wb = where_before
            message = (f"nothing in the catalogue explains the residual (best: {best.effect}, explains "
                       f"{best.explained_fraction:.0%}, delta_ic {best.delta_ic:.1f}"
                       + (", at the bound of its range" if best.at_bound else "") + "); the residual sits in the "
                       f"{wb['dominant_phase'].replace('_', ' ')} phase and wavelet level {wb['dominant_level']}")
    else:
        vals = ", ".join(f"{n} = {v:.4g} ± {u:.2g} {unit}" for n, v, u, unit in
                         zip(discovery.parameter_names, discovery.values, discovery.uncertainty, discovery.units))
        message = (f"missing effect: {discovery.effect} ({vals}), explains {discovery.explained_fraction:.0%} of "
                   f"the residual, delta_ic {discovery.delta_ic:.1f}")
        if discovery.indistinguishable_from:
            message += ("; not distinguishable from this recording from " + ", ".join(discovery.indistinguishable_from))
            twins = [f for f in fits if f.effect in discovery.indistinguishable_from]
            message += "".join(f". To tell them apart: {_separating_measurement(discovery, t)}" for t in twins)
        if second_fit is not None:
            message += f"; a second effect on top: {second_fit.effect} ({second_fit.values[0]:.4g})"
    fit_before = analysis.fit_percent(comp.target, base_mean)
    fit_after = analysis.fit_percent(comp.target, after_mean)
    band = analysis.noise_band_fit_percent(comp)
    result = {
        "measurement": meas.source, "model": model.label(),
        "model_file": str(model.path) if model.path else None,
        "conditions": comp.conditions, "seeds": comp.seeds, "events": comp.events.n_events,
        "discovery": None if discovery is None else discovery.effect.split("[")[0],
        "discovery_candidate": None if discovery is None else discovery.effect,
        "discovery_parameters": None if discovery is None else discovery.to_json(),
        "indistinguishable": [] if discovery is None else [e.split("[")[0] for e in
                                                           [discovery.effect] + discovery.indistinguishable_from],
        "second_effect": None if second_fit is None else second_fit.to_json(),
        "partial_explanation": None if partial is None else [f.to_json() for f in partial if f is not None],
        "message": message,
        "model_inconsistent": bool(inconsistent),
        "subspace": {"dimension": int(problem.basis.shape[1]), "T2": t2, "T2_limit_p01": t2_limit,
                     "residual_over_noise": sub_ratio},
        "ranked": ranked,
        "where": where_before,
        "where_after": (analysis.where(comp, after_mean, after_raw) if discovery is not None and after_raw is not None
                        else None),
        "fit_percent": {"before": dict(zip(SEGMENT_SIGNALS, map(float, fit_before))),
                        "after": dict(zip(SEGMENT_SIGNALS, map(float, fit_after))),
                        "noise_band_median": dict(zip(SEGMENT_SIGNALS, map(float, np.median(band, axis=0))))},
        "residual_over_noise_floor": {"before": dict(zip(SEGMENT_SIGNALS, map(float, ratio_before))),
                                      "after": dict(zip(SEGMENT_SIGNALS, map(float, ratio_after))),
                                      "overall_before": overall_before,
                                      "overall_after": float(np.sqrt(np.mean(ratio_after ** 2)))},
        "identifiability": identifiability,
        "not_identifiable": [n for n, v in identifiability.items() if not v["identifiable"]],
        "whiteness": analysis.whiteness(comp),
        "input_correlation": analysis.input_correlation(comp),
        "spectral_peaks": analysis.spectral_peaks(analysis.spectra(comp)),
        "information_criterion": "BIC on the events: IC = E*ln(mean_e L_e) + k*ln(E), E onset events, L_e the "
                                 "weighted mean squared difference of event e's denoised segment from the model "
                                 "mean",
        "simulated_parameter_sets": problem.n_sets_simulated + 1,
        "seconds": time.perf_counter() - t0,
    }
    result["_arrays"] = {"comparison": comp, "after_mean": after_mean, "fits": fits}
    return result


def _combined(a, b):
    """One candidate holding the parameters of two (they act on different keys, so values apply together)."""
    return plant_adapter.CandidateEffect(f"{a.name}+{b.name}", f"{a.effect}+{b.effect}", a.balance,
                                         f"{a.description}; {b.description}",
                                         tuple(a.parameters) + tuple(b.parameters))


def _second_effect(comp, problem, model, first, by_name, scr, order, base_mean, base_ic):
    """Two effects at once: every pair of the best screened candidates is fitted linearly together (the
    screening Jacobians); the best pair is refitted on the simulator. Returned when it beats the single
    winner by DELTA_IC_STRONG and its second effect explains >= MIN_EXPLAINED_SECOND of what the first
    left. -> (fit of the pair, name of the second effect) or None."""
    r1 = problem.residual(first.model_mean)
    if not _inconsistent(comp, problem, r1):
        return None
    r0 = problem.project(problem.residual(base_mean))
    top = order[:6]
    best = None
    for i, a in enumerate(top):
        for b in top[i + 1:]:
            J = problem.project(np.hstack([scr[a]["J"], scr[b]["J"]]))
            ea, eb = by_name[a], by_name[b]
            x0 = np.concatenate([ea.default_vector(), eb.default_vector()])
            lo = np.concatenate([ea.bounds()[0], eb.bounds()[0]])
            hi = np.concatenate([ea.bounds()[1], eb.bounds()[1]])
            res = fitting.lsq_linear(J, r0, bounds=(lo - x0, hi - x0 + 1e-300))
            expl = 1 - float(np.sum((r0 - J @ res.x) ** 2) / np.sum(r0 ** 2))
            if best is None or expl > best[0]:
                best = (expl, a, b, x0 + res.x, np.concatenate([scr[a]["h"], scr[b]["h"]]))
    r1g = problem.project(r1)
    if best is None or best[0] <= 1 - float(np.sum(r1g ** 2) / max(np.sum(r0 ** 2), 1e-300)):
        return None
    _, a, b, x_lin, h = best
    pair = _combined(by_name[a], by_name[b])
    fit = fitting.refine(problem, pair, {"x_lin": x_lin, "h": h, "explained_lin": best[0]}, base_mean, base_ic)
    if fit.delta_ic > first.delta_ic - DELTA_IC_STRONG or fit.at_bound:
        return None
    left = 1 - float(np.sum(problem.fit_residual(fit.model_mean) ** 2) / max(np.sum(r1g ** 2), 1e-300))
    if left < MIN_EXPLAINED_SECOND:
        return None
    return fit, a, b


def _greedy_second(comp, problem, model, first, by_name, scr, order):
    """Every other candidate fitted on top of the first effect (fixed at its fitted values)."""
    r1 = problem.residual(first.model_mean)
    if not _inconsistent(comp, problem, r1):
        return None
    eff1 = by_name[first.effect]
    base_sets = plant_adapter.apply_values(eff1, first.values)
    # linear screening on the first fit's residual with the Jacobians at the model (cheap), then refine the best
    cands = []
    for n in order:
        if n == first.effect:
            continue
        J = problem.project(scr[n]["J"])
        r1g = problem.project(r1)
        eb = by_name[n]
        d = fitting.lsq_linear(J, r1g, bounds=(eb.bounds()[0] - eb.default_vector(),
                                              eb.bounds()[1] - eb.default_vector() + 1e-300)).x
        cands.append((1 - float(np.sum((r1g - J @ d) ** 2) / max(np.sum(r1g ** 2), 1e-300)), n))
    cands.sort(reverse=True)
    if not cands or cands[0][0] < MIN_EXPLAINED_SECOND:
        return None
    name = cands[0][1]
    p2 = fitting.Problem(model, comp.events, comp.seeds, problem.n_samples, problem.dt, problem.conditions,
                         comp.weights[:], base_sets=base_sets)
    p2.w = problem.w
    p2.basis = problem.basis
    base_ic = first.ic + len(first.values) * 0.0
    eff = by_name[name]
    s2 = fitting.screen(p2, [eff], first.model_mean)
    f2 = fitting.refine(p2, eff, s2[name], first.model_mean, base_ic)
    problem.n_sets_simulated += p2.n_sets_simulated
    f2.base = [first.effect]
    if f2.delta_ic <= -DELTA_IC_STRONG and f2.explained_fraction >= MIN_EXPLAINED_SECOND and not f2.at_bound:
        return f2
    return None



def _part(fit, effect, sl, base):
    f = fitting.FitResult(effect.name, fit.parameter_names[sl], fit.units[sl], fit.values[sl], fit.uncertainty[sl],
                          fit.nominal[sl], (fit.bounds[0][sl], fit.bounds[1][sl]), fit.explained_fraction,
                          fit.delta_ic, fit.ic, fit.model_mean, fit.screening_explained, fit.evaluations,
                          effect.balance, effect.description, fit.at_bound, [], list(base), fit.model_mean_raw)
    return f


def public(result: dict) -> dict:
    return {k: v for k, v in result.items() if not k.startswith("_")}
