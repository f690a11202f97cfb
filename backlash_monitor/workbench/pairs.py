"""The second effect: two catalogue effects at once, when the best single one leaves the model inconsistent
(docs/workbench.md, "a second effect"). Pairs are fitted linearly on the screening Jacobians (cheap), then the best
disjoint pairs are refined on the simulator until one passes; what may tie with it is refined too; pairs within
DELTA_IC_TIE of the best are named as indistinguishable (the rule of singles). Greedy fallback: every other
candidate on top of the fixed winner.
"""
from __future__ import annotations

import copy

import numpy as np

from . import consistency, fitting, plant_adapter, tolerance
from .decisions import (DELTA_IC_STRONG, DELTA_IC_TIE, MIN_EXPLAINED_SECOND, TOLERANCE_FACTOR, confident,
                        significant)

PAIR_MAX_NFEV = 4            # as a single effect (measured: 6 converged to the same values on a pair)
PAIR_REFINE = 3              # pairs (no member in common) refined on the simulator until one passes
PAIR_EXTRA = 1               # more pairs refined when their linearised IC may tie with the best refined pair
                             # (besides its members' single-effect twins substituted; measured: 6 pairs within
                             # reach on a friction + inertia recording, each refinement ~9 simulated sets)
MEASURAND_SUBSTITUTES = 2    # then the width beside the best 2 other candidates, linearised at the width of its best
                             # refined pair (measured, 29 Nov: a 1.5 N*m wheel friction beside 7.5 -> 8.3 mm, the
                             # friction 7th alone and not refined; width + mass force refined -298.7, width + wheel
                             # Coulomb friction -309.5: the truth, 8.32 mm and 1.58 N*m)
PAIR_FIRST = 6               # pairs: the first effect among the best 6 screened singles, the second any
LINEAR_IC_MARGIN = 2.0       # how far the linearised IC may be off the refined one
MEASURAND_PARTNERS = 3       # the width refined beside each of the best 3 qualifying singles (by their refined IC),
                             # whatever the linear ranking says: the width is the measurand, it may have moved on any
                             # drive, and its pairs' linearisation is far off (measured on four foreign width + effect
                             # drives, 29 Nov: the right pair's linearised IC -190, -173 (not among the best 15), -219
                             # against refined -260, -210, -283; each passed once refined, none had been refined)


def combined(a, b):
    """One candidate holding the parameters of two (they act on different keys, so values apply together)."""
    return plant_adapter.CandidateEffect(f"{a.name}+{b.name}", f"{a.effect}+{b.effect}", a.balance,
                                         f"{a.description}; {b.description}",
                                         tuple(a.parameters) + tuple(b.parameters), fixed=a.fixed + b.fixed)


def pair_key(a, b, order):
    """A pair's canonical order: the member that screened better first (as the linear pair search names it)."""
    return (a, b) if order.index(a) <= order.index(b) else (b, a)


def best_pair(problem, first, by_name, scr, order, base_pred, base_ic, tried=None, twins_of=None,
              singles=None, refine_pair=None, event_locked=(), measurand=None, partners=(), fits=None):
    """Two effects at once. Every pair (one of the best PAIR_FIRST screened singles + any other candidate) is
    fitted linearly together on the screening Jacobians (cheap, no simulation) and ranked by its linearised
    IC. Then on the simulator (bounded least squares, common random numbers):
    A member refined as a single effect is linearised at its fitted values (simulated prediction and Jacobian
    there), any other at the model's values (screening secant): the pairs' start values and linearised ICs.
    1. the best pairs with no member in common, in that order, until one passes (at most PAIR_REFINE); and the
       ``measurand`` (the width) beside each of ``partners`` (the best MEASURAND_PARTNERS qualifying singles but the
       measurand itself): the width may have moved on any drive, and a pair with it is linearised badly (the width is
       strongly nonlinear: the gap times the impacts), so the ranking cannot be trusted to reach it;
    2. the pairs that may tie with the best passing one: each member replaced by its single-effect twins
       (the candidates the single-effect analysis calls indistinguishable from it), and any other pair whose
       linearised IC comes within DELTA_IC_TIE + LINEAR_IC_MARGIN of the best refined IC (the singles' rule;
       at most PAIR_EXTRA, best first).
    A pair passes when it beats the single winner by DELTA_IC_STRONG, is not pinned, its values are
    significant, its second effect explains >= MIN_EXPLAINED_SECOND of what the first left, and the model with
    both is confident. -> (fit of the best pair, a, b, [(fit, c, d) of the passing pairs within DELTA_IC_TIE of
    it]) or None. ``fits``: a list that receives every refined pair as (fit, a, b) (the measured width's model
    average, diagnose.width_measurement). ``refine_pair(a, b)``: a pair's own fit where it has one (a term locked to a shaft's angle fitted
    event by event beside the other: angle_locked.fit_pair), else None: refined on the event average. ``event_locked``:
    those terms (names); the first effect's pair with each of them is refined besides the ranked ones (the event
    average's linearisation cannot rank it: the term washes out there)."""
    r1 = problem.residual(first.pred)
    if consistency.test(problem.views, r1).consistent:
        return None
    r0 = problem.project(problem.residual(base_pred))
    r1g = problem.project(r1)
    single = problem.explained_share(r1g, r0)
    twins_of = twins_of or {}
    lin: dict = {}           # (a, b) -> (explained, x_lin, h, linearised IC, Jacobian (N, k_a + k_b))

    singles = {f.effect: f for f in (singles or []) if f.jacobian is not None}

    def expansion(n):
        """Where a member's linear model is taken: at its refined single-effect fit when there is one (its
        simulated prediction and forward-difference Jacobian there: exact at that value, and the pair's value
        of a member is usually near it), else at the model's value with the screening secant."""
        f = singles.get(n)
        if f is not None:
            return np.asarray(f.values, float), f.pred - base_pred, f.jacobian
        return by_name[n].default_vector(), np.zeros_like(base_pred), scr[n].jacobian

    def linear(a, b):
        key = pair_key(a, b, order)
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
            expl = problem.explained_share(rr - J @ res.x, r0)
            ic = problem.ic(base_pred + shift + Jf @ res.x, len(xe))
            lin[key] = (expl, xe + res.x, np.concatenate([scr[a].step, scr[b].step]), ic, Jf)
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
        expl, x_lin, h, _, jacobian = lin[key]
        fit = refine_pair(a, b) if refine_pair is not None else None
        if fit is None:
            fit = fitting.refine(problem, combined(by_name[a], by_name[b]), fitting.Linearisation(jacobian, h, x_lin, expl),
                                 base_pred, base_ic, max_nfev=PAIR_MAX_NFEV)
        left = problem.explained_share(problem.fit_residual(fit.pred), r1g)
        na = len(by_name[a].parameters)
        checks = {"beats_first_by_2": bool(fit.delta_ic <= first.delta_ic - DELTA_IC_STRONG),
                  "not_pinned": not fit.at_bound, "significant": significant(fit),
                  "beyond_tolerance": bool(tolerance.beyond_tolerance(part(fit, by_name[a], slice(0, na), []),
                                                                      by_name[a], TOLERANCE_FACTOR)
                                           and tolerance.beyond_tolerance(part(fit, by_name[b], slice(na, None), []),
                                                                          by_name[b], TOLERANCE_FACTOR)),
                  "second_explains_30pc_of_what_first_left": bool(left >= MIN_EXPLAINED_SECOND),
                  "confident": confident(problem, fit.pred, base_pred)[0]}
        ok = all(checks.values())
        tried.append({"pair": [a, b], "parameters": [float(v) for v in fit.values],
                      "delta_ic": float(fit.delta_ic), "delta_ic_linearised": float(lin[key][3] - base_ic),
                      "checks": checks, "passed": ok})
        done[key] = (fit, ok)
        if fits is not None:
            fits.append((fit, a, b))
        return ok

    def substitutes(m):
        """The pairs of ``m`` not refined yet, ranked by their IC linearised at m's value in its best refined pair (the
        other member removed linearly): a strongly nonlinear member (the width) is linearised where it is, not at the
        nominal or its single fit. Their lin entries are replaced by that linearisation."""
        mine = [k for k in done if m in k and done[k][0].jacobian is not None]
        if not mine:
            return []
        k0 = min(mine, key=lambda k: done[k][0].delta_ic)
        fit = done[k0][0]
        other = k0[1] if k0[0] == m else k0[0]
        na = len(by_name[k0[0]].parameters)
        im, io = (slice(0, na), slice(na, None)) if k0[0] == m else (slice(na, None), slice(0, na))
        jm = fit.jacobian[:, im]
        xm = np.asarray(fit.values[im], float)
        pred_m = fit.pred - fit.jacobian[:, io] @ (np.asarray(fit.values[io], float) - by_name[other].default_vector())
        rr = problem.project(problem.residual(pred_m))
        scored = []
        for n in order:
            key = pair_key(m, n, order)
            if n == m or key in done:
                continue
            first_m = key[0] == m
            em, en = by_name[m], by_name[n]
            parts = [(jm, xm, em.bounds(), scr[m].step), (scr[n].jacobian, en.default_vector(), en.bounds(), scr[n].step)]
            if not first_m:
                parts.reverse()
            Jf = np.hstack([q[0] for q in parts])
            xe = np.concatenate([q[1] for q in parts])
            lo = np.concatenate([q[2][0] for q in parts])
            hi = np.concatenate([q[2][1] for q in parts])
            # the prediction at xe is pred_m (the candidate at its nominal)
            res = fitting.lsq_linear(problem.project(Jf), rr, bounds=(lo - xe, hi - xe + 1e-300))
            expl = problem.explained_share(rr - problem.project(Jf) @ res.x, r0)
            ic = problem.ic(pred_m + Jf @ res.x, len(xe))
            scored.append((ic, key, (expl, np.clip(xe + res.x, lo, hi), np.concatenate([q[3] for q in parts]), ic, Jf)))
        scored.sort(key=lambda t: t[0])
        for _, key, entry in scored:
            lin[key] = entry
        return [key for _, key, _ in scored]

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
    # the width beside the best qualifying singles (measured, 29 Nov: a 10 N rail friction beside 6.0 -> 6.9 mm, the
    # width first at -153.9; width + mass force linearised -190, 5th, behind width + motor load at -207; refined
    # -260.4, 99 % explained and consistent in every view, never refined: the width's one disjoint pair was the other)
    if measurand is not None and measurand in order:
        for n in [n for n in partners if n != measurand and n in order][:MEASURAND_PARTNERS]:
            key = linear(measurand, n)
            if key not in done:
                run(key)
        for key in substitutes(measurand)[:MEASURAND_SUBSTITUTES]:
            run(key)
    # the first effect with a term locked to a shaft's angle: fitted event by event (refine_pair), measured: a crank
    # pump beside a width change, the width + crank pair not among the ranked (one disjoint pair per member)
    for n in event_locked:
        if refine_pair is not None and n != first.effect and n in order and first.effect in order:
            key = linear(first.effect, n)
            if key not in done:
                run(key)
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


def greedy_second(problem, first, by_name, scr, order):
    """Every other candidate fitted on top of the first effect (fixed at its fitted values)."""
    r1 = problem.residual(first.pred)
    if consistency.test(problem.views, r1).consistent:
        return None
    eff1 = by_name[first.effect]
    base_sets = plant_adapter.apply_values(eff1, first.values)
    # linear screening on the first fit's residual with the Jacobians at the model (cheap), then refine the best
    cands = []
    for n in order:
        if n == first.effect:
            continue
        J = problem.project(scr[n].jacobian)
        r1g = problem.project(r1)
        eb = by_name[n]
        d = fitting.lsq_linear(J, r1g, bounds=(eb.bounds()[0] - eb.default_vector(),
                                              eb.bounds()[1] - eb.default_vector() + 1e-300)).x
        cands.append((problem.explained_share(r1g - J @ d, r1g), n))
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
            and significant(f2) and tolerance.beyond_tolerance(f2, eff, TOLERANCE_FACTOR)):
        return f2
    return None


def part(fit, effect, sl, base):
    f = fitting.FitResult(effect.name, fit.parameter_names[sl], fit.units[sl], fit.values[sl], fit.uncertainty[sl],
                          fit.nominal[sl], (fit.bounds[0][sl], fit.bounds[1][sl]), fit.explained_fraction,
                          fit.delta_ic, fit.ic, fit.model_mean, fit.screening_explained, fit.evaluations,
                          effect.balance, effect.description, fit.at_bound, [], list(base), fit.model_mean_raw,
                          fit.pred, fixed=dict(effect.fixed_values))
    return f
