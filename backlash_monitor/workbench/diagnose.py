"""``diagnose``: where the model fails on a measurement, and which catalogue effect is missing.

Evidence: the weighted denoised event average and the raw events' spectral shape (workbench/spectral.py),
each in its own whitened block of the candidates' subspace; the events are the units. Decision rules
(docs/workbench.md, "Decisions"):
- the model is *inconsistent* when T^2 of either block exceeds its 1 % limit or the event-average residual
  exceeds INCONSISTENT_RATIO times the noise floor;
- a candidate is a *discovery* when the model is inconsistent, its delta_ic <= -DELTA_IC_STRONG (BIC on
  the events), it explains >= MIN_EXPLAINED of the residual and it is not pinned at a bound (a second
  effect's values must also be significant: > SIGNIFICANCE uncertainties from the model's);
- two candidates are *indistinguishable* when both qualify and their IC differ by < DELTA_IC_TIE; every
  screened candidate whose linearised IC may tie is refined before this comparison;
- after a discovery whose model is still inconsistent, pairs (one of the best singles + any other) are
  fitted linearly; the best with no member in common refined in order until one passes (<= PAIR_REFINE),
  then its members' single-effect twins substituted and the pairs whose linearised IC may tie (<= PAIR_EXTRA)
  refined; pairs within DELTA_IC_TIE of the best are named as indistinguishable (the rule of singles);
- *confident*: the model with the effect(s) is consistent, also outside the candidates' subspace.
"""
from __future__ import annotations

import copy
import time

import numpy as np
from scipy import stats

from . import analysis, fitting, plant_adapter, ripple, separation, spectral
from .events import SEGMENT_SIGNALS, denoise

DELTA_IC_STRONG = 2.0     # "positive" evidence (Kass & Raftery) on E events; docs/workbench.md
DELTA_IC_TIE = 2.0
MIN_EXPLAINED = 0.5
MIN_EXPLAINED_SECOND = 0.3
PAIR_MAX_NFEV = 4            # as a single effect (measured: 6 converged to the same values on a pair)
PAIR_REFINE = 3              # pairs (no member in common) refined on the simulator until one passes
PAIR_EXTRA = 1               # more pairs refined when their linearised IC may tie with the best refined pair
                             # (besides its members' single-effect twins substituted; measured: 6 pairs within
                             # reach on a friction + inertia recording, each refinement ~9 simulated sets)
PAIR_FIRST = 6               # pairs: the first effect among the best 6 screened singles, the second any
REFINE_TOP = 3               # singles refined first: the best 3 by explained share (model inconsistent)
REFINE_EXTRA = 3            # more candidates refined when their linearised IC may tie with the winner
LINEAR_IC_MARGIN = 2.0     # how far the linearised IC may be off the refined one (docs/workbench.md)
SUBSPACE_ENERGY = 0.99       # share of the candidates' reach the subspace keeps
SUBSPACE_MAX_DIM = 12
SPECTRAL_MAX_DIM = 6          # of the spectral-shape block's 10 features (workbench/spectral.py)


def significant(fit) -> bool:
    """Every fitted value differs from the model's by more than SIGNIFICANCE x its (jackknife) uncertainty."""
    d = np.abs(np.asarray(fit.values) - np.asarray(fit.nominal))
    return bool(np.all(d > SIGNIFICANCE * np.asarray(fit.uncertainty)))


def _overall(problem, r) -> float:
    """rms of the weighted event-average residual (residual / noise floor over a1 and a2)."""
    return float(np.sqrt(np.mean(problem.event_part(r) ** 2)))


def _inconsistent(comp, problem, r) -> bool:
    """The weighted residual r beyond the noise band: overall, or in a block of the candidates' subspace."""
    if _overall(problem, r) > analysis.INCONSISTENT_RATIO:
        return True
    return any(t2 > limit for t2, limit in hotelling_blocks(comp, problem, r).values())


CONFIDENT_EXPLAINED = 0.9
SIGNIFICANCE = 2.0           # a fitted value must differ from the model's by > 2 uncertainties
COMPLEMENT_DIM = 20          # noise directions outside the candidates' subspace checked after a fit
COMPLEMENT_EXPLAINED = 0.6   # ... where the fit must stay within the 1 % limit or remove this share


def _confident(comp, problem, after_pred, base_pred) -> bool:
    """The model with the discovered effect(s) agrees with the measurement: overall residual/noise within
    INCONSISTENT_RATIO, and either T^2 in the subspace within its limit or >= CONFIDENT_EXPLAINED of the
    (whitened) residual explained (a strong effect fitted to 98 % can leave a T^2 above the limit from the
    fit's own finite accuracy)."""
    r = problem.residual(after_pred)
    if _overall(problem, r) > analysis.INCONSISTENT_RATIO:
        return False
    within = all(t2 <= limit for t2, limit in hotelling_blocks(comp, problem, r).values())
    r0g = problem.fit_residual(base_pred)
    explained = 1 - float(np.sum(problem.project(r) ** 2) / max(np.sum(r0g ** 2), 1e-300))
    if not (within or explained >= CONFIDENT_EXPLAINED):
        return False
    # outside the candidates' subspace: the effect must not leave there what the model's noise does not
    # account for (an effect outside the catalogue that a catalogue effect mimics inside the subspace)
    t2c, limit_c = complement_t2(comp, problem, r)
    t2c0, _ = complement_t2(comp, problem, problem.residual(base_pred))
    return bool(t2c <= limit_c or t2c <= (1.0 - COMPLEMENT_EXPLAINED) * t2c0)


def model_event_vectors(comp, problem) -> np.ndarray:
    """The model's own events (all seeds of the ensemble) as prediction-space vectors minus the model's
    prediction: (K*E, N), the sample of the noise the whitening and the per-block limits are taken from."""
    base = problem.pred(comp.model_mean, comp.ensemble.spec_mean(0))
    out = []
    for raw in comp.ensemble.per_event:
        v = np.hstack([(denoise(raw) * comp.weights[None, :, None]).reshape(raw.shape[0], -1),
                       spectral.event_features(raw, problem.dt) * problem.ws[None]])
        out.append(v - base[None])
    return np.vstack(out)


def whiten(blocks, comp, problem) -> tuple[np.ndarray, list]:
    """Per block (event average, spectral shape): basis @ C^(-1/2), C the covariance of the model's own
    events in that block's subspace: the projected event residuals then have unit variance per direction.
    -> (N, q) basis, [(block name, column slice)]."""
    z_all = model_event_vectors(comp, problem)
    cols, names, q0 = [], [], 0
    for name, basis in blocks:
        if basis.shape[1] == 0:
            continue
        z = z_all @ basis
        cov = np.cov(z, rowvar=False).reshape(basis.shape[1], basis.shape[1])
        vals, vecs = np.linalg.eigh(cov)
        vals = np.maximum(vals, 1e-12 * vals.max())
        cols.append(basis @ (vecs / np.sqrt(vals)[None, :]) @ vecs.T)
        names.append((name, slice(q0, q0 + basis.shape[1])))
        q0 += basis.shape[1]
    return np.hstack(cols), names


def hotelling_blocks(comp, problem, r) -> dict:
    """Per block: T^2 of the measured average's residual in the whitened subspace (E events, the model
    mean's own noise from K seeds included) and its 1 % limit (chi-square, q dof of the block)."""
    e = comp.events.n_events
    k = len(comp.seeds)
    z = problem.basis.T @ r
    out = {}
    for name, sl in problem.blocks:
        zb = z[sl]
        out[name] = (float(np.sum(zb ** 2) / (1.0 / e + 1.0 / (e * k))), float(stats.chi2.ppf(0.99, zb.size)))
    return out


def complement_basis(comp, problem) -> np.ndarray:
    """The COMPLEMENT_DIM strongest directions of the model's own event noise in the event average that lie
    outside the candidates' subspace, whitened: (n_event_coords, P)."""
    ne = problem.n_event_coords
    z = model_event_vectors(comp, problem)[:, :ne]
    q, _ = np.linalg.qr(problem.basis[:ne, problem.blocks[0][1]])
    zc = z - (z @ q) @ q.T
    _, sv, vt = np.linalg.svd(zc, full_matrices=False)
    p = min(COMPLEMENT_DIM, len(sv))
    return vt[:p].T / np.maximum(sv[:p] / np.sqrt(max(z.shape[0] - 1, 1)), 1e-300)[None]


def complement_t2(comp, problem, r) -> tuple[float, float]:
    """T^2 of the event-average residual in the complement directions and its 1 % limit."""
    e = comp.events.n_events
    k = len(comp.seeds)
    z = problem.complement.T @ problem.event_part(r)
    return float(np.sum(z ** 2) / (1.0 / e + 1.0 / (e * k))), float(stats.chi2.ppf(0.99, z.size))


def hotelling(comp, problem, r) -> tuple[float, float]:
    """T^2 and its 1 % limit of the event-average block (the first block)."""
    return hotelling_blocks(comp, problem, r)["event_average"]


def candidate_basis(scr: dict, by_name: dict, n_event: int) -> list:
    """Orthonormal bases of the directions the candidates move the prediction in, per block (the weighted
    event average; the spectral shape of the raw events): SVD of their Jacobian columns scaled by their fit
    ranges, keeping SUBSPACE_ENERGY of each block's energy. -> [(name, (N, q_block))]."""
    cols = []
    for n, info in scr.items():
        lo, hi = by_name[n].bounds()
        cols.append(info["J"] * (hi - lo)[None, :])
    s_mat = np.hstack(cols)
    out = []
    for name, sl, max_dim in (("event_average", slice(0, n_event), SUBSPACE_MAX_DIM),
                              ("spectral_shape", slice(n_event, s_mat.shape[0]), SPECTRAL_MAX_DIM)):
        part = s_mat[sl]
        basis = np.zeros((s_mat.shape[0], 0))
        if part.shape[0] > 0 and np.any(part):
            u, sv, _ = np.linalg.svd(part, full_matrices=False)
            energy = np.cumsum(sv ** 2) / max(np.sum(sv ** 2), 1e-300)
            q = int(min(max_dim, part.shape[0], np.searchsorted(energy, SUBSPACE_ENERGY) + 1))
            basis = np.zeros((s_mat.shape[0], q))
            basis[sl] = u[:, :q]
        out.append((name, basis))
    return out


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
                              comp.conditions, comp.weights, comp.spec_weights)
    base_pred = problem.pred(base_mean, comp.ensemble.spec_mean(0))
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
    scr = fitting.screen(problem, catalogue, base_pred, progress=progress)
    # the candidates' subspace: what the catalogue can change in the event average and in the raw events'
    # spectral shape (from the model's Jacobians over the fit ranges, before any fit to the measurement);
    # the IC and the consistency gates are taken in it, so the events' noise in directions no candidate
    # moves does not drown the evidence
    by_name = {c.name: c for c in catalogue}
    problem.basis, problem.blocks = whiten(candidate_basis(scr, by_name, problem.n_event_coords), comp, problem)
    problem.complement = complement_basis(comp, problem)
    base_ic = problem.ic(base_pred, 0)
    r0 = problem.residual(base_pred)
    gates = hotelling_blocks(comp, problem, r0)
    t2, t2_limit = gates["event_average"]
    sub_ratio = float(np.sqrt(t2 / max(problem.blocks[0][1].stop, 1)))
    inconsistent = inconsistent or any(v[0] > v[1] for v in gates.values())
    # the linear estimates again, in the whitened subspace (generalised least squares), and their IC
    r0g = problem.project(r0)
    for n, info in scr.items():
        eff = by_name[n]
        x0 = eff.default_vector()
        lo, hi = eff.bounds()
        jg = problem.project(info["J"])
        d = fitting.lsq_linear(jg, r0g, bounds=(lo - x0, hi - x0 + 1e-300)).x
        info["x_lin"] = x0 + d
        info["explained_lin"] = 1.0 - float(np.sum((r0g - jg @ d) ** 2) / max(np.sum(r0g ** 2), 1e-300))
        info["delta_ic_lin"] = problem.ic(base_pred + info["J"] @ d, len(x0)) - base_ic
    order = sorted(scr, key=lambda k: -scr[k]["explained_lin"])
    if inconsistent:
        # the best REFINE_TOP by explained share; the candidates that may tie or still qualify follow below (by
        # the reach rule). (Measured: the best 2 by linearised IC + the best by share instead missed the wheel
        # friction's tie on a 2 N*m recording: a dry friction's linearised IC is far worse than its refined one)
        first_refined = order[:REFINE_TOP]
    else:
        # the model agrees with the measurement: nothing can be discovered; the best candidate is fitted for
        # the report (its value and uncertainty say how far it could be off)
        first_refined = order[:1]
    fits = [fitting.refine(problem, by_name[n], scr[n], base_pred, base_ic) for n in first_refined]

    def qualifies(f, min_expl):
        # (no significance test here: the IC is the test of a single effect, and the jackknife through the
        # final Jacobian can be far off for a strongly nonlinear parameter -- measured: a quadratic wheel drag
        # fitted 0.064 +- 0.040 at delta_ic -250; the significance test guards the second effect of a pair)
        return f.delta_ic <= -DELTA_IC_STRONG and f.explained_fraction >= min_expl and not f.at_bound

    # a candidate that screens lower may still tie with the winner (the same physics seen through another
    # parameter): every screened candidate whose linearised fit comes within the tie margin of the best
    # refined IC is refined too, so the indistinguishability rule compares all that might tie
    if inconsistent:
        ok = [f.delta_ic for f in fits if qualifies(f, MIN_EXPLAINED)]
        # with a qualifying winner: what may tie with it; without one: what may still qualify (delta_ic <=
        # -DELTA_IC_STRONG after refinement); the tie margin is about a winner, so it applies only with one
        reach = (min(ok) + DELTA_IC_TIE if ok else -DELTA_IC_STRONG) + LINEAR_IC_MARGIN
        extra = sorted((n for n in order if n not in first_refined and scr[n]["delta_ic_lin"] <= reach),
                       key=lambda n: scr[n]["delta_ic_lin"])[:REFINE_EXTRA]
        fits += [fitting.refine(problem, by_name[n], scr[n], base_pred, base_ic) for n in extra]
    refined = {f.effect for f in fits}
    fits.sort(key=lambda f: f.delta_ic)

    qual = [f for f in fits if qualifies(f, MIN_EXPLAINED)] if inconsistent else []
    discovery = qual[0] if qual else None
    if discovery is not None:
        for f in qual[1:]:
            if f.delta_ic - discovery.delta_ic < DELTA_IC_TIE:
                discovery.indistinguishable_from.append(f.effect)
                f.indistinguishable_from.append(discovery.effect)
    unrefined = [n for n in order if n not in refined]
    ranked = [f.to_json() | {"delta_ic_linearised": float(scr[f.effect]["delta_ic_lin"])} for f in fits] + [
        {"effect": n, "parameters": {p.name: float(v) for p, v in zip(by_name[n].parameters, scr[n]["x_lin"])},
         "uncertainty": None, "delta_ic": None, "explained_fraction": float(scr[n]["explained_lin"]),
         "indistinguishable_from": [], "screening_only": True, "balance": by_name[n].balance,
         "delta_ic_linearised": float(scr[n]["delta_ic_lin"])}
        for n in unrefined]
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
        ne = problem.n_event_coords
        reach_ev = float(np.max(np.sqrt(np.mean(span[:ne] ** 2, axis=0))))
        reach_sp = float(np.max(np.sqrt(np.mean(span[ne:] ** 2, axis=0)))) if span.shape[0] > ne else 0.0
        reach = max(reach_ev, reach_sp)
        identifiability[n] = {"range_effect_over_noise_floor": reach,
                              "event_average_over_noise_floor": reach_ev,
                              "spectral_shape_over_noise_floor": reach_sp,
                              "identifiable": reach >= 1.0}
    after_mean = discovery.model_mean if discovery is not None else base_mean
    after_pred = discovery.pred if discovery is not None else base_pred
    after_raw = discovery.model_mean_raw if discovery is not None else None
    second_fit = None
    pair = None
    pairs_tried: list = []
    pair_alternatives: list = []     # pairs not distinguishable from the discovered pair
    if discovery is not None and second:
        # the single-effect twins (qualifying candidates within the tie margin of each other): a pair's member
        # is also tried with each of its twins in its place
        twins_of = {f.effect: [g.effect for g in qual if g is not f and abs(g.delta_ic - f.delta_ic) < DELTA_IC_TIE]
                    for f in qual}
        pair = _second_effect(comp, problem, model, discovery, by_name, scr, order, base_pred, base_ic,
                              pairs_tried, twins_of, fits)
        if pair is not None:
            fit2, a, b, ties = pair
            after_mean = fit2.model_mean
            after_pred = fit2.pred
            after_raw = fit2.model_mean_raw
            # the pair replaces the single winner: split it into its two effects
            na = len(by_name[a].parameters)
            first = _part(fit2, by_name[a], slice(0, na), [])
            second_fit = _part(fit2, by_name[b], slice(na, None), [a])
            # pairs that tie with it (the same rule as singles): one member in common -> the other is
            # indistinguishable from the member it replaces; no member in common -> an alternative pair
            for f2, c, d in ties:
                if {c, d} & {a, b} and {c, d} != {a, b}:
                    keep = ({c, d} & {a, b}).pop()
                    other = c if d == keep else d
                    (second_fit if keep == a else first).indistinguishable_from.append(other)
                pair_alternatives.append({
                    "effects": [c.split("[")[0], d.split("[")[0]], "candidates": [c, d],
                    "parameters": {f"{c}.{n}": float(v) for n, v in zip(f2.parameter_names[:len(by_name[c].parameters)],
                                                                        f2.values)}
                    | {f"{d}.{n}": float(v) for n, v in zip(f2.parameter_names[len(by_name[c].parameters):],
                                                            f2.values[len(by_name[c].parameters):])},
                    "delta_ic": float(f2.delta_ic), "delta_ic_from_winner": float(f2.delta_ic - fit2.delta_ic)})
            discovery = first
        else:
            second_fit = _greedy_second(comp, problem, model, discovery, by_name, scr, order)
            if second_fit is not None:
                after_mean = second_fit.model_mean
                after_pred = second_fit.pred
                after_raw = second_fit.model_mean_raw
    ratio_after = analysis.residual_ratio(comp, after_mean)
    best = fits[0] if fits else None
    partial = None
    if discovery is not None and not _confident(comp, problem, after_pred, base_pred):
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
            by_place: dict = {}          # twins acting at one place share one separating measurement
            for t in twins:
                by_place.setdefault(_where_acts(t), []).append(t.effect)
            message += "".join(
                ". To tell them apart: " + separation.separating_measurement(
                    discovery.effect, _where_acts(discovery), " and ".join(names), place)
                for place, names in by_place.items())
        if second_fit is not None:
            message += f"; a second effect on top: {second_fit.effect} ({second_fit.values[0]:.4g})"
            if second_fit.indistinguishable_from:
                message += (" (not distinguishable from this recording from "
                            + ", ".join(second_fit.indistinguishable_from) + ")")
            if pair_alternatives:
                message += ("; the pair is not distinguishable from this recording from "
                            + ", ".join(" + ".join(p["candidates"]) for p in pair_alternatives))
    fit_before = analysis.fit_percent(comp.target, base_mean)
    fit_after = analysis.fit_percent(comp.target, after_mean)
    band = analysis.noise_band_fit_percent(comp)
    # the catalogue effect the event average cannot see: a ripple locked to the motor angle, from the raw spectrum
    spec = analysis.spectra(comp)
    ripple_fit = ripple.fit_torque_ripple(comp, spec)
    ripple_entry = None
    if ripple_fit is not None and ripple_fit["confident"]:
        message += "; " + ripple.describe(ripple_fit)
        # a confident ripple is named like any other discovery: the winner when the event average found
        # nothing, else the second effect when there is none (add-effect takes it once)
        ripple_entry = ripple.as_discovery(ripple_fit)
        if discovery is None:
            message = message.replace("nothing to discover", "nothing to discover in the event average", 1)
    winner = discovery.to_json() if discovery is not None else ripple_entry
    result = {
        "measurement": meas.source, "model": model.label(),
        "model_file": str(model.path) if model.path else None,
        "conditions": comp.conditions, "seeds": comp.seeds, "events": comp.events.n_events,
        "discovery": None if winner is None else winner["effect"],
        "discovery_candidate": None if winner is None else winner["candidate"],
        "discovery_parameters": winner,
        "indistinguishable": [] if winner is None else [e.split("[")[0] for e in
                                                        [winner["candidate"]] + winner["indistinguishable_from"]],
        "second_effect": (second_fit.to_json() if second_fit is not None
                          else ripple_entry if discovery is not None else None),
        "pairs_tried": pairs_tried,
        "pair_alternatives": pair_alternatives if second_fit is not None and discovery is not None else [],
        "partial_explanation": None if partial is None else [f.to_json() for f in partial if f is not None],
        "message": message,
        "model_inconsistent": bool(inconsistent),
        "subspace": {"dimension": int(problem.blocks[0][1].stop), "T2": t2, "T2_limit_p01": t2_limit,
                     "residual_over_noise": sub_ratio,
                     "blocks": {name: {"dimension": int(sl.stop - sl.start), "T2": gates[name][0],
                                       "T2_limit_p01": gates[name][1]} for name, sl in problem.blocks}},
        "spectral_shape": {"bands_hz": list(spectral.BAND_EDGES_HZ),
                           "measured_minus_model": dict(zip(
                               [f"{s}_{lo:.0f}-{hi:.0f}_vs_{hi:.0f}-{hh:.0f}_Hz" for s in SEGMENT_SIGNALS
                                for lo, hi, hh in zip(spectral.BAND_EDGES_HZ[:-2], spectral.BAND_EDGES_HZ[1:-1],
                                                      spectral.BAND_EDGES_HZ[2:])],
                               map(float, (problem.target_vec - base_pred)[problem.n_event_coords:] /
                                   problem.ws))),
                           "units": "ln(power ratio of adjacent bands), mean over the events"},
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
        "spectral_peaks": analysis.spectral_peaks(spec),
        "spectral_discovery": ripple_fit,
        "information_criterion": "BIC on the events: IC = E*ln(mean_e L_e) + k*ln(E), E onset events, L_e the "
                                 "weighted mean squared difference of event e's denoised segment from the model "
                                 "mean",
        "simulated_parameter_sets": problem.n_sets_simulated + 1,
        "seconds": time.perf_counter() - t0,
    }
    result["_arrays"] = {"comparison": comp, "after_mean": after_mean, "fits": fits, "problem": problem,
                         "base_pred": base_pred, "scr": scr}
    return result


def _combined(a, b):
    """One candidate holding the parameters of two (they act on different keys, so values apply together)."""
    return plant_adapter.CandidateEffect(f"{a.name}+{b.name}", f"{a.effect}+{b.effect}", a.balance,
                                         f"{a.description}; {b.description}",
                                         tuple(a.parameters) + tuple(b.parameters))


def _pair_key(a, b, order):
    """A pair's canonical order: the member that screened better first (as the linear pair search names it)."""
    return (a, b) if order.index(a) <= order.index(b) else (b, a)


def _second_effect(comp, problem, model, first, by_name, scr, order, base_pred, base_ic, tried=None,
                   twins_of=None, singles=None):
    """Two effects at once. Every pair (one of the best PAIR_FIRST screened singles + any other candidate) is
    fitted linearly together on the screening Jacobians (cheap, no simulation) and ranked by its linearised
    IC. Then on the simulator (bounded least squares, common random numbers):
    A member refined as a single effect is linearised at its fitted values (simulated prediction and Jacobian
    there), any other at the model's values (screening secant): the pairs' start values and linearised ICs.
    1. the best pairs with no member in common, in that order, until one passes (at most PAIR_REFINE);
    2. the pairs that may tie with the best passing one: each member replaced by its single-effect twins
       (the candidates the single-effect analysis calls indistinguishable from it), and any other pair whose
       linearised IC comes within DELTA_IC_TIE + LINEAR_IC_MARGIN of the best refined IC (the singles' rule;
       at most PAIR_EXTRA, best first).
    A pair passes when it beats the single winner by DELTA_IC_STRONG, is not pinned, its values are
    significant, its second effect explains >= MIN_EXPLAINED_SECOND of what the first left, and the model with
    both is confident. -> (fit of the best pair, a, b, [(fit, c, d) of the passing pairs within DELTA_IC_TIE of
    it]) or None."""
    r1 = problem.residual(first.pred)
    if not _inconsistent(comp, problem, r1):
        return None
    r0 = problem.project(problem.residual(base_pred))
    r1g = problem.project(r1)
    single = 1 - float(np.sum(r1g ** 2) / max(np.sum(r0 ** 2), 1e-300))
    twins_of = twins_of or {}
    lin: dict = {}           # (a, b) -> (explained, x_lin, h, linearised IC)

    singles = {f.effect: f for f in (singles or []) if f.jacobian is not None}

    def expansion(n):
        """Where a member's linear model is taken: at its refined single-effect fit when there is one (its
        simulated prediction and forward-difference Jacobian there: exact at that value, and the pair's value
        of a member is usually near it), else at the model's value with the screening secant."""
        f = singles.get(n)
        if f is not None:
            return np.asarray(f.values, float), f.pred - base_pred, f.jacobian
        return by_name[n].default_vector(), np.zeros_like(base_pred), scr[n]["J"]

    def linear(a, b):
        key = _pair_key(a, b, order)
        if key not in lin:
            a, b = key
            (xa, da, ja), (xb, db, jb) = expansion(a), expansion(b)
            Jf = np.hstack([ja, jb])
            J = problem.project(Jf)
            ea, eb = by_name[a], by_name[b]
            xe = np.concatenate([xa, xb])
            lo = np.concatenate([ea.bounds()[0], eb.bounds()[0]])
            hi = np.concatenate([ea.bounds()[1], eb.bounds()[1]])
            shift = da + db
            rr = r0 - problem.project(shift)
            res = fitting.lsq_linear(J, rr, bounds=(lo - xe, hi - xe + 1e-300))
            expl = 1 - float(np.sum((rr - J @ res.x) ** 2) / np.sum(r0 ** 2))
            ic = problem.ic(base_pred + shift + Jf @ res.x, len(xe))
            lin[key] = (expl, xe + res.x, np.concatenate([scr[a]["h"], scr[b]["h"]]), ic)
        return key

    # every pair (linear, on the screening Jacobians: cheap): the first of the best PAIR_FIRST singles, the
    # second any other candidate -- a second effect need not screen well on its own (measured: wheel friction
    # 1.0 N*m + wheel inertia +30 % screened 12th alone)
    for i, a in enumerate(order[:PAIR_FIRST]):
        for b in order:
            if b != a and b not in order[:i]:
                linear(a, b)
    ranked = sorted((k for k, v in lin.items() if v[0] > single), key=lambda k: lin[k][3])
    tried = [] if tried is None else tried
    done: dict = {}          # (a, b) -> (fit, passed)

    def run(key):
        a, b = key
        expl, x_lin, h, _ = lin[key]
        pair = _combined(by_name[a], by_name[b])
        fit = fitting.refine(problem, pair, {"x_lin": x_lin, "h": h, "explained_lin": expl}, base_pred, base_ic,
                             max_nfev=PAIR_MAX_NFEV)
        left = 1 - float(np.sum(problem.fit_residual(fit.pred) ** 2) / max(np.sum(r1g ** 2), 1e-300))
        checks = {"beats_first_by_2": bool(fit.delta_ic <= first.delta_ic - DELTA_IC_STRONG),
                  "not_pinned": not fit.at_bound, "significant": significant(fit),
                  "second_explains_30pc_of_what_first_left": bool(left >= MIN_EXPLAINED_SECOND),
                  "confident": _confident(comp, problem, fit.pred, base_pred)}
        ok = all(checks.values())
        tried.append({"pair": [a, b], "parameters": [float(v) for v in fit.values],
                      "delta_ic": float(fit.delta_ic), "delta_ic_linearised": float(lin[key][3] - base_ic),
                      "checks": checks, "passed": ok})
        done[key] = (fit, ok)
        return ok

    # 1. many pairs fit about equally well linearly (measured: the 12 best pairs of a friction + inertia
    # recording within 3 of each other's linearised IC; the right one 8th), and only the simulator tells them
    # apart: the best disjoint pairs are refined in order until one passes
    used: set = set()
    for key in ranked:
        if key[0] in used or key[1] in used:
            continue
        used |= set(key)
        if run(key) or len(done) == PAIR_REFINE:
            break
    passed = [k for k, (f, ok) in done.items() if ok]
    if not passed:
        return None
    best = min(passed, key=lambda k: done[k][0].delta_ic)
    # 2. what may tie with it: its members' single-effect twins substituted (a heavier mass for a lower a2
    # gain), then the pairs within reach of its refined IC by their linearised IC
    subs = [linear(t, best[1]) for t in twins_of.get(best[0], []) if t != best[1]]
    subs += [linear(best[0], t) for t in twins_of.get(best[1], []) if t != best[0]]
    reach = done[best][0].ic + DELTA_IC_TIE + LINEAR_IC_MARGIN
    subs = [k for k in dict.fromkeys(subs) if k not in done]
    near = [k for k in ranked if lin[k][3] <= reach and k not in done and k not in subs]
    for key in subs + near[:PAIR_EXTRA]:
        run(key)
    passed = sorted((k for k, (f, ok) in done.items() if ok), key=lambda k: done[k][0].delta_ic)
    fit, (a, b) = done[passed[0]][0], passed[0]
    ties = [(done[k][0], k[0], k[1]) for k in passed[1:] if done[k][0].delta_ic - fit.delta_ic < DELTA_IC_TIE]
    return fit, a, b, ties


def _greedy_second(comp, problem, model, first, by_name, scr, order):
    """Every other candidate fitted on top of the first effect (fixed at its fitted values)."""
    r1 = problem.residual(first.pred)
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
    p2 = copy.copy(problem)
    p2.base = dict(base_sets)
    p2.n_sets_simulated = 0
    base_ic = first.ic + len(first.values) * 0.0
    eff = by_name[name]
    s2 = fitting.screen(p2, [eff], first.pred, two_sided=False)
    f2 = fitting.refine(p2, eff, s2[name], first.pred, base_ic)
    problem.n_sets_simulated += p2.n_sets_simulated
    f2.base = [first.effect]
    if (f2.delta_ic <= -DELTA_IC_STRONG and f2.explained_fraction >= MIN_EXPLAINED_SECOND and not f2.at_bound
            and significant(f2)):
        return f2
    return None



def _part(fit, effect, sl, base):
    f = fitting.FitResult(effect.name, fit.parameter_names[sl], fit.units[sl], fit.values[sl], fit.uncertainty[sl],
                          fit.nominal[sl], (fit.bounds[0][sl], fit.bounds[1][sl]), fit.explained_fraction,
                          fit.delta_ic, fit.ic, fit.model_mean, fit.screening_explained, fit.evaluations,
                          effect.balance, effect.description, fit.at_bound, [], list(base), fit.model_mean_raw,
                          fit.pred)
    return f


def public(result: dict) -> dict:
    return {k: v for k, v in result.items() if not k.startswith("_")}
