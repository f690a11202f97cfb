"""``diagnose``: where the model fails on a recording, and which catalogue effect is missing.

One recording, followed through the named steps (docs/workbench.md, "Diagnose: the steps"):

1. **screen** (`screen_step`): the model's noise ensemble under the recording's conditions; every candidate's
   parameters stepped on common random numbers (the Jacobians); the views the consistency test looks in
   (consistency.py: the candidates' subspace of the event average, the raw events' spectral shape, the record
   mean, and outside the subspace), whitened by the model's own events; the model-form tolerance (tolerance.py);
   the linear fit of every candidate; the consistency of the model as it is.
2. **refine** (`refine_step`): bounded least squares on the simulator for the best candidates and every one
   that may tie with them.
3. **decide** (`decide_step`): the winner among the qualifying candidates (decisions.qualifies, its weak evidence
   significant family-wise over the candidates screened: the look-elsewhere effect) and the ones not
   distinguishable from it.
4. **second effect** (`second_effect_step`, pairs.py): when the winner leaves the model inconsistent.
5. **confidence** (`confidence_step`): the model with the effect(s) must be consistent in every view, without
   making any view worse (decisions.confident); a torque ripple from the raw a1 spectrum (ripple.py) must be
   locked to the motor angle.
6. **verdict** (`verdict_step`): consistent / discovery / width (the measurand) / partial / nothing explains and
   the additions for the next model version (`decide_verdict`); the message (`verdict_message`); the report's
   fields (report.diagnosis_report). -> diagnosis.Diagnosis.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from . import (analysis, angle_locked, consistency, drive_terms, fitting, model_average, pairs, plant_adapter,
               proposal, report, ripple, separation, tolerance)
from .decisions import (DELTA_IC_DECISIVE, DELTA_IC_STRONG, DELTA_IC_TIE, MIN_EXPLAINED, confident, identical_to,
                        likelihood_part, qualifies, refusals, significant)
from .diagnosis_result import (CONSISTENT, DISCOVERY, MEASURAND, MEASURAND_EFFECTS, NOTHING_EXPLAINS, PARTIAL,
                        ROLE_DISCOVERY, ROLE_PARTIAL, ROLE_SECOND, Addition, Conditions, Diagnosis,
                        WidthMeasurement)
from .measurement import Measurement, saturation_of
from .model import WorkbenchModel

REFINE_TOP = 3               # singles refined first: the best 3 by explained share (model inconsistent)
REFINE_EXTRA = 4             # more candidates refined when they may tie with the winner (the rim-force twins of a wheel
                             # friction are three: working resistance, a force on the mass, a viscous drag)
LINEAR_IC_MARGIN = pairs.LINEAR_IC_MARGIN
# the balances whose candidates are laws of one torque or force (refine_step refines them beside the best one);
# sensor effects and parameter drifts are told apart by their signal and their linearisation holds. The rim balance
# (spring, absorber) is not among them: the own and foreign suites were measured without it
LAW_BALANCES = ("wheel_torque_Nm", "mass_force_N", "motor_load_moment_pu", "clutch_torque_Nm")
WIDTH_CANDIDATE = next(iter(MEASURAND_EFFECTS))   # the catalogue's candidate of the measurand: the width drift


@dataclass
class Run:
    """The state of one diagnosis as it goes through the steps. The prediction vectors (N values) are
    fitting.Problem's: weighted, in units of each coordinate's noise floor."""
    meas: Measurement
    model: WorkbenchModel
    comp: analysis.Comparison                     # the recording against the model's noise ensemble
    problem: fitting.Problem                      # with the views once screened (screen_step)
    catalogue: list[plant_adapter.CandidateEffect]
    by_name: dict[str, plant_adapter.CandidateEffect]
    base_pred: np.ndarray                         # (N,): the model's prediction as it is
    overrides: dict                               # the command line's overrides the model was loaded with
    t0: float                                     # time.perf_counter() at the start [s]
    screening: dict[str, fitting.Linearisation] = field(default_factory=dict)   # every screened candidate's
    order: list[str] = field(default_factory=list)      # the ranked candidates, by their linear explained share
    base_ic: float = 0.0                          # the IC of the model as it is (in the views)
    before: consistency.ConsistencyResult | None = None  # the model as it is, in the views
    fits: list[fitting.FitResult] = field(default_factory=list)   # the refined candidates, best delta_ic first
    views: consistency.ConsistencyViews | None = None     # the views of the screening (screen_step)
    event_fits: dict[str, fitting.FitResult] = field(default_factory=dict)   # the terms locked to a shaft's angle,
                                                  # fitted event by event (angle_locked.py) in place of refine
    events_evidence: str | None = None            # such a term whose evidence on the events contradicts a model the
                                                  # views call consistent (screen_step)

    @property
    def inconsistent(self) -> bool:
        return not self.before.consistent or self.events_evidence is not None

    @property
    def n_candidates(self) -> int:
        """How many candidates the winner is the best of: every one screened and ranked (decisions.qualifies)."""
        return len(self.order)

    def qualifies(self, fit) -> bool:
        """decisions.qualifies, honest about the candidates looked at (the look-elsewhere effect)."""
        return qualifies(fit, self.by_name[fit.effect], n_candidates=self.n_candidates)

    def refusals(self, fit) -> list[str]:
        """Why ``fit`` does not qualify, in words (decisions.refusals; empty when it does)."""
        return refusals(fit, self.by_name[fit.effect], n_candidates=self.n_candidates)


@dataclass
class Decision:
    winner: fitting.FitResult | None
    qualifying: list


@dataclass
class Update:
    """The model update a diagnosis arrives at: the effect(s), the model mean and prediction with them."""
    first: fitting.FitResult | None
    second: fitting.FitResult | None = None
    pairs_tried: list = field(default_factory=list)
    pair_fits: list = field(default_factory=list)   # every pair refined on the simulator: (fit, a, b)
    greedy: bool = False                          # the second effect fitted on top of the fixed first (greedy_second)
    pair_alternatives: list = field(default_factory=list)
    after_mean: np.ndarray | None = None
    after_pred: np.ndarray | None = None
    after_raw: np.ndarray | None = None
    confident: bool = False
    checks: dict = field(default_factory=dict)


# -------------------------------------------------------------------------------------------------- steps

def prepare(meas, model, seeds=None, effects=None, overrides=None) -> Run:
    """The comparison (conditions, the model's noise ensemble) and the fit problem; the candidate catalogue."""
    comp = analysis.build_comparison(meas, model, seeds)
    problem = fitting.Problem(model, comp.events, comp.seeds, meas.n_samples, meas.sample_period_s,
                              comp.conditions, comp.weights, comp.spec_weights, comp.dc_weights, comp.segment_noise,
                              comp.dc_names)
    base_pred = problem.pred_of(comp.ensemble, 0)
    catalogue = plant_adapter.catalogue(model)
    if effects:
        known = {c.name for c in catalogue} | {c.effect for c in catalogue}
        unknown = [e for e in effects if e not in known]
        if unknown:
            raise ValueError(f"effect {unknown[0]!r} is not in the catalogue; allowed: "
                             + ", ".join(c.name for c in catalogue))
    return Run(meas, model, comp, problem, catalogue, {c.name: c for c in catalogue}, base_pred,
               dict(overrides or {}), time.perf_counter())


def screen_step(run: Run, effects=None, progress=None) -> None:
    """Every candidate stepped on common random numbers (its Jacobian); the views and the tolerance from them
    (measurement-independent: the model's sensitivities and its own events); the linear fits; the model's
    consistency as it is."""
    p = run.problem
    allowed = [c.name for c in run.catalogue if not effects or c.name in effects or c.effect in effects]
    # the requested candidates and those that carry a nominal tolerance (the null hypothesis needs them)
    screened = [c for c in run.catalogue if c.name in allowed or (tolerance.SCALE > 0
                                                                   and np.any(tolerance.sigma_of(c) > 0))]
    screening = fitting.screen(p, screened, run.base_pred, progress=progress)
    run.views = consistency.ConsistencyViews.from_screening(p, {n: s.jacobian for n, s in screening.items()},
                                                            run.by_name, consistency.model_event_vectors(run.comp, p))
    p = run.problem = p.with_views(run.views)
    run.base_ic = p.ic(run.base_pred, 0)
    run.before = consistency.test(run.views, p.residual(run.base_pred))
    # the linear estimates in the whitened views (generalised least squares), and their IC; a term locked to a
    # shaft's angle as a sine/cosine pair
    run.screening = {n: fitting.linear_estimate(p, run.by_name[n], s, run.base_pred, run.base_ic)
                     for n, s in screening.items()}
    # a term locked to a shaft's angle, fitted on the events at the recording's own angles (its event average washes
    # out): its screening's estimate is that fit's. It is fitted even when the views call the model consistent: they
    # look at the event average, where such a term washes out, and the events' own evidence may still be decisive
    # (measured: a foreign 5 N*m torque at twice the wheel angle, the model consistent, the exact law fitted event by
    # event 4.69 +- 0.29 N*m at delta_ic -104); the model is then inconsistent with its events.
    for n in allowed:
        f = angle_locked.fit(run, run.by_name[n]) if angle_locked.angle_variable(run.model, run.by_name[n]) else None
        if f is not None:
            run.event_fits[n] = f
            run.screening[n] = replace(run.screening[n], x_lin=f.values, explained_lin=f.explained_fraction,
                                       pred_lin=f.pred, delta_ic_lin=f.delta_ic)
    run.events_evidence = events_evidence(run.event_fits.values()) if run.before.consistent else None
    run.order = sorted(allowed, key=lambda k: -run.screening[k].explained_lin)


def events_evidence(event_fits) -> str | None:
    """The term locked to a shaft's angle whose event-by-event fit is decisive evidence on the events (delta_ic <=
    -DELTA_IC_DECISIVE and its size significant: decisions.significant), the best one; None when there is none (on a
    clean foreign recording the exact law of a torque at twice the wheel angle fitted 0.6 +- 0.3 N*m, delta_ic +3.9)."""
    decisive = [f for f in event_fits if f.delta_ic <= -DELTA_IC_DECISIVE and significant(f)]
    return min(decisive, key=lambda f: f.delta_ic).effect if decisive else None


def refine_step(run: Run) -> list:
    """Bounded least squares on the simulator: the best REFINE_TOP by explained share (only the best one when the
    model is consistent: its value and uncertainty for the report), then every screened candidate whose
    linearised IC may tie with the best qualifying one (or, without one, may still qualify)."""
    p, scr = run.problem, run.screening
    first = run.order[:REFINE_TOP] if run.inconsistent else run.order[:1]
    fits = [_refined(run, n) for n in first]
    if run.inconsistent:
        # in the recording's evidence (the IC without its parameter penalty): a two-parameter law may tie with a
        # one-parameter one that fits as well (decisions.likelihood_part); with the best's misfit scale
        lnE = np.log(max(p.n_events, 2))
        ok = [f for f in fits if run.qualifies(f)]
        best = min(ok, key=lambda f: f.delta_ic) if ok else None
        reach = ((likelihood_part(best, p.n_events) + DELTA_IC_TIE * misfit_scale(p, best)) if best is not None
                 else -DELTA_IC_STRONG) + LINEAR_IC_MARGIN

        def lin_part(n):
            return scr[n].delta_ic_lin - len(run.by_name[n].parameters) * lnE

        def lin_distance(n):
            pred = scr[n].linear_pred(run.base_pred, run.by_name[n].default_vector())
            return prediction_distance(p, best.pred, pred) / misfit_scale(p, best) if best is not None else np.inf

        near = {n for n in run.order if n not in first and lin_distance(n) < 4 * DELTA_IC_TIE}
        # the laws of the best one's own balance (a wheel torque: Coulomb, viscous, Stribeck) differ only in how
        # they depend on the state they act on; where that state moves little (the wheel never reverses) they
        # are one torque, and the linearisation at the nominal misses that for a strong effect (measured: a
        # 2 N*m wheel Coulomb friction, linear delta_ic -246, refined -273.8 against the viscous law's -274.0)
        if best is not None and best.balance in LAW_BALANCES:
            near |= {n for n in run.order if n not in first and run.by_name[n].balance == best.balance}
        extra = sorted((n for n in run.order if n not in first and (lin_part(n) <= reach or n in near)),
                       key=lambda n: (n not in near, lin_part(n)))[:REFINE_EXTRA]
        fits += [_refined(run, n) for n in extra]
    fits.sort(key=lambda f: f.delta_ic)
    run.fits = fits
    return fits


def _refined(run: Run, name: str) -> fitting.FitResult:
    """A candidate's fit on the simulator (fitting.refine), or its event-by-event fit (angle_locked.py)."""
    if name in run.event_fits:
        return run.event_fits[name]
    return fitting.refine(run.problem, run.by_name[name], run.screening[name], run.base_pred, run.base_ic)


def misfit_scale(problem, fit) -> float:
    """The a-posteriori variance factor of a fit: its T^2 per dimension over every view (>= 1). Where the drive's
    law differs from the catalogue's the fit leaves more than noise, and the recording's evidence between two
    candidates is overstated by this factor (generalised least squares with an unknown scale)."""
    return misfit_scale_of(problem, fit.pred)


def prediction_distance(problem, pred_a, pred_b) -> float:
    """How far two fitted models' predictions lie apart, in units of the measured mean's noise over every view (the
    fits' metric): the IC difference a recording would show between them on average were one of them right. Two
    candidates closer than DELTA_IC_TIE x the misfit scale cannot be told apart by this recording, whatever their
    ICs on it (measured on a foreign 12 N force on the mass: the four rim-force twins' fits within 5.3 of each
    other, their ICs 9.5 apart: under a misfit the events' IC magnifies tiny differences)."""
    d = problem.project(pred_a - pred_b)
    return float(np.sum(d ** 2) / consistency.noise_scale(problem.n_events, problem.n_seeds))


def _ties(problem, a, b, scale: float) -> bool:
    e = problem.n_events
    return (abs(likelihood_part(a, e) - likelihood_part(b, e)) / scale < DELTA_IC_TIE
            or prediction_distance(problem, a.pred, b.pred) / scale < DELTA_IC_TIE)


def decide_step(run: Run) -> Decision:
    """The winner: the best qualifying candidate (only when the model is inconsistent); the qualifying ones that tie
    with it -- their evidence (decisions.likelihood_part) or their fitted prediction (prediction_distance) within
    DELTA_IC_TIE of it, both divided by the winner's misfit_scale -- are not distinguishable from it, and so is a
    candidate that is the same term of the model as it or as one of those (decisions.IDENTICAL)."""
    qual = [f for f in run.fits if run.qualifies(f)] if run.inconsistent else []
    winner = qual[0] if qual else None
    if winner is not None:
        scale = misfit_scale(run.problem, winner)
        for f in qual[1:]:
            if _ties(run.problem, winner, f, scale) or f.effect in identical_to(winner.effect):
                winner.indistinguishable_from.append(f.effect)
                f.indistinguishable_from.append(winner.effect)
        for name in [winner.effect] + list(winner.indistinguishable_from):
            for twin in identical_to(name):
                if twin in run.by_name and twin != winner.effect and twin not in winner.indistinguishable_from:
                    winner.indistinguishable_from.append(twin)
    return Decision(winner, qual)


def second_effect_step(run: Run, decision: Decision, second: bool = True) -> Update:
    """The winner alone, or with a second effect when it leaves the model inconsistent (pairs.py)."""
    win = decision.winner
    anchor_only = False
    if win is None and second and run.inconsistent:
        # no single effect explains enough: two together may (measured: +30 % load mass with a -20 % a1 gain; the
        # best single, the a1 gain at delta_ic -88.7, explained 13 % of the residual's excess). The pair search
        # starts from the best decisively evidenced single; the pair must then explain MIN_EXPLAINED itself.
        anchors = [f for f in run.fits if f.delta_ic <= -DELTA_IC_DECISIVE and not f.at_bound and significant(f)
                   and f.effect.split("[")[0] not in MEASURAND_EFFECTS]
        win, anchor_only = (anchors[0], True) if anchors else (None, False)
    if win is None:
        return Update(None)
    up = Update(win, after_mean=win.model_mean, after_pred=win.pred, after_raw=win.model_mean_raw)
    if not second:
        return up
    twins_of = {f.effect: [g.effect for g in decision.qualifying
                           if g is not f and _ties(run.problem, f, g, misfit_scale(run.problem, f))]
                for f in decision.qualifying}
    found = pairs.best_pair(run.problem, win, run.by_name, run.screening, run.order, run.base_pred, run.base_ic,
                            up.pairs_tried, twins_of, run.fits,
                            refine_pair=(lambda a, b: angle_locked.fit_pair(run, a, b)) if run.event_fits else None,
                            event_locked=list(run.event_fits), measurand=WIDTH_CANDIDATE,
                            partners=[f.effect for f in decision.qualifying] or [win.effect], fits=up.pair_fits)
    if found is not None and anchor_only and found[0].explained_fraction < MIN_EXPLAINED:
        found = None
    if found is None and anchor_only:
        return Update(None, pairs_tried=up.pairs_tried, pair_fits=up.pair_fits)
    if found is not None:
        fit2, a, b, ties = found
        na = len(run.by_name[a].parameters)
        first = pairs.part(fit2, run.by_name[a], slice(0, na), [])
        sec = pairs.part(fit2, run.by_name[b], slice(na, None), [a])
        for f2, c, d in ties:
            # one member in common: the other is not distinguishable from the member it replaces
            if {c, d} & {a, b} and {c, d} != {a, b}:
                keep = ({c, d} & {a, b}).pop()
                other = c if d == keep else d
                (sec if keep == a else first).indistinguishable_from.append(other)
            nc = len(run.by_name[c].parameters)
            up.pair_alternatives.append({
                "effects": [c.split("[")[0], d.split("[")[0]], "candidates": [c, d],
                "parameters": {f"{c}.{n}": float(v) for n, v in zip(f2.parameter_names[:nc], f2.values[:nc])}
                | {f"{d}.{n}": float(v) for n, v in zip(f2.parameter_names[nc:], f2.values[nc:])},
                "delta_ic": float(f2.delta_ic), "delta_ic_from_winner": float(f2.delta_ic - fit2.delta_ic)})
        # a member's single-effect twins (and the same terms of the model) are not distinguishable from it in the pair
        for member, fit in ((a, first), (b, sec)):
            for t in twins_of.get(member, []) + [x for y in [member] + twins_of.get(member, []) for x in identical_to(y)]:
                if t not in (a, b) and t in run.by_name and t not in fit.indistinguishable_from:
                    fit.indistinguishable_from.append(t)
        up.first, up.second = first, sec
        up.after_mean, up.after_pred, up.after_raw = fit2.model_mean, fit2.pred, fit2.model_mean_raw
        return up
    sec = pairs.greedy_second(run.problem, win, run.by_name, run.screening, run.order)
    if sec is not None:
        up.second, up.greedy = sec, True
        up.after_mean, up.after_pred, up.after_raw = sec.model_mean, sec.pred, sec.model_mean_raw
    return up


def confidence_step(run: Run, up: Update, decision: Decision | None = None) -> Update:
    """The model with the effect(s) at their fitted values: consistent in every view, none made worse.

    A single winner that fails this check is not the last word when the recording cannot tell it from other
    candidates (decide_step's ties: their evidence or their predictions within DELTA_IC_TIE): among those, the
    IC order is the recording's noise, and the check is further evidence. The first tied candidate (in IC order)
    whose fitted model passes takes the winner's place, the winner named as not distinguishable from it. Measured
    on a foreign drive with +30 % load mass (docs/workbench.md): the a2 gain (delta_ic -346.1) left the view
    outside the candidates' subspace at T^2 40.8 (limit 37.6, made worse from 39.9); the load mass, 2.8 behind
    it, 38.7 (better, and 99.5 % explained: within the form tolerance): the truth, a discovery, not a partial."""
    if up.first is None:
        return up
    up.confident, up.checks = confident(run.problem, up.after_pred, run.base_pred)
    win = decision.winner if decision is not None else None
    if up.confident or up.second is not None or win is None or up.first is not win:
        return up
    for f in decision.qualifying:
        if f is win or f.effect not in win.indistinguishable_from:
            continue
        ok, checks = confident(run.problem, f.pred, run.base_pred)
        if ok:
            if win.effect not in f.indistinguishable_from:
                f.indistinguishable_from.append(win.effect)
            for t in win.indistinguishable_from:
                if t != f.effect and t not in f.indistinguishable_from and _ties_or_identical(run, f, t):
                    f.indistinguishable_from.append(t)
            worse = up.checks.get("views_made_worse") or []
            checks["replaced"] = {"effect": win.effect, "views_made_worse": worse,
                                  "consistent_in_every_view": up.checks.get("consistent_in_every_view")}
            up.first, up.confident, up.checks = f, True, checks
            up.after_mean, up.after_pred, up.after_raw = f.model_mean, f.pred, f.model_mean_raw
            break
    return up


def _ties_or_identical(run: Run, f, name: str) -> bool:
    """``name`` (a fitted candidate) is not distinguishable from ``f``: tied with it, or the same term."""
    g = next((x for x in run.fits if x.effect == name), None)
    if name in identical_to(f.effect):
        return True
    return g is not None and _ties(run.problem, f, g, misfit_scale(run.problem, f))


def spectral_step(run: Run) -> tuple[dict | None, dict]:
    """A torque ripple from the raw a1 spectrum (ripple.py): the fit, or None; and the spectra."""
    spec = analysis.spectra(run.comp)
    return ripple.fit_torque_ripple(run.comp, spec), spec


def width_measurement(run: Run, up: Update) -> WidthMeasurement:
    """The backlash width the recording shows, with an uncertainty that includes the model-form tolerance
    (tolerance.measurand_form_sigma: how far the width moves when the nominal values are off by their sigma):
    - the nominal plus the width drift a confident update holds (its fitted uncertainty, with the form's), when
      the width explains the recording alone or beside a found effect (_width_alone_explains): no averaging;
    - the nominal (the width direction's linear standard error, with the form's) where the update (or the model as it
      is) leaves the recording consistent;
    - else, the model does not hold: the width averaged over the plausible models that hold it (width_models: the
      width fitted alone, beside each second effect fitted with it, and on top of the update), its uncertainty the
      unconditional standard error over them (model_average.py: it covers what a missing effect moves the width by
      between the models, not only each fit's variance), with the form's; ``drift_found`` False (issue 31: 5.0 +-
      0.024 mm reported on a 6.2 mm drive with an a2 offset)."""
    nominal = float(run.model.nominal["width_m"])
    width_lin = run.screening.get(WIDTH_CANDIDATE)
    form = (tolerance.measurand_form_sigma(run.problem, {n: s.jacobian for n, s in run.screening.items()},
                                           run.by_name, width_lin.jacobian[:, 0])
            if width_lin is not None else 0.0)
    held = next((f for f in (up.first, up.second) if up.confident and _is_measurand(f)), None)
    width_only = held is not None and all(_is_measurand(f) for f in (up.first, up.second) if f is not None)
    if held is not None and (not width_only or _width_alone_explains(up)):
        return WidthMeasurement(nominal + float(held.values[0]), float(np.hypot(held.uncertainty[0], form)), nominal,
                                True, form)
    if width_lin is None:
        return WidthMeasurement(nominal, float("nan"), nominal, False)
    p = run.problem
    jz = p.project(width_lin.jacobian[:, 0])
    se = float(np.sqrt(consistency.noise_scale(p.n_events, p.n_seeds) / max(float(jz @ jz), 1e-300)))
    pred = _update_pred(run, up)
    if held is None and consistency.test(p.views, p.residual(pred)).consistent:
        return WidthMeasurement(nominal, float(np.hypot(se, form)), nominal, False, form)
    members = width_models(run, up)
    best_pred = min(members, key=lambda m: m[0].ic)[1]
    avg = model_average.average([m for m, _ in members], misfit_scale_of(p, best_pred))
    over = tuple({"model": m.label, "width_m": nominal + m.value, "uncertainty_m": m.sd, "weight": w}
                 for m, w in zip(avg.members, avg.weights))
    return WidthMeasurement(nominal + avg.value, float(np.hypot(avg.sd, form)), nominal, False, form, over)


def _update_pred(run: Run, up: Update) -> np.ndarray:
    """The prediction of the model with the update's effects, or the model's own when the update holds none."""
    return up.after_pred if up.first is not None and up.after_pred is not None else run.base_pred


def misfit_scale_of(problem, pred) -> float:
    """misfit_scale of a prediction (T^2 per dimension over every view, >= 1)."""
    c = consistency.test(problem.views, problem.residual(pred))
    return max(1.0, sum(v.t2 for v in c.views.values()) / max(sum(v.dimension for v in c.views.values()), 1))


def width_models(run: Run, up: Update) -> list:
    """The fitted models that hold the width (the measurand), each as (model_average.Member of the width change [m],
    its prediction): the width refined alone (refine_step); every pair with the width refined on the simulator (the
    pair search); a greedy second effect that is the width (fitted on top of the first); and, where the update holds
    no width, the width's linear fit on top of the update (Gauss-Newton from it, its error scaled by the residual's
    Birge ratio sqrt(T^2 / dimension): the excess is not the noise the error comes from; also when no other model
    holds the width). Fits pinned at a bound of their range are left out (their error is no fit's error)."""
    p, lnE = run.problem, np.log(max(run.problem.n_events, 2))
    out, seen = [], set()

    def add(value, sd, ic, pred, label):
        if ic not in seen:
            seen.add(ic)
            out.append((model_average.Member(float(value), float(sd), float(ic), label), pred))

    for f in run.fits:
        if _is_measurand(f) and not f.at_bound:
            add(f.values[0], f.uncertainty[0], f.ic, f.pred, f.effect)
    for fit, a, b in up.pair_fits:
        if WIDTH_CANDIDATE in (a, b) and not fit.at_bound:
            i = 0 if a == WIDTH_CANDIDATE else len(run.by_name[a].parameters)
            add(fit.values[i], fit.uncertainty[i], fit.ic, fit.pred, f"{a}+{b}")
    if up.greedy and _is_measurand(up.second) and not up.second.at_bound:
        # a greedy second effect (pairs.greedy_second): its IC counted the first effect's parameters as fixed
        add(up.second.values[0], up.second.uncertainty[0], up.second.ic + len(up.first.values) * lnE, up.second.pred,
            f"{up.first.effect}+{up.second.effect}")
    inside = next((f for f in (up.first, up.second) if _is_measurand(f)), None)
    if (inside is None and up.first is not None) or not out:
        # (a width in the update that took no part -- pinned -- is the start: the step measures only the rest)
        start = float(inside.values[0]) if inside is not None else 0.0
        width_lin = run.screening[WIDTH_CANDIDATE]
        pred = _update_pred(run, up)
        j = width_lin.jacobian[:, 0]
        jz = p.project(j)
        jj = max(float(jz @ jz), 1e-300)
        c = consistency.noise_scale(p.n_events, p.n_seeds)
        rz = p.project(p.residual(pred))
        lo, hi = run.by_name[WIDTH_CANDIDATE].bounds()
        change = float(np.clip(start + (jz @ rz) / jj, lo[0], hi[0]))
        birge = float(np.sqrt(max(1.0, float(rz @ rz) / c / max(rz.size, 1))))
        k = sum(len(f.values) for f in (up.first, up.second) if f is not None) + (inside is None)
        after = pred + j * (change - start)
        label = "+".join([f.effect for f in (up.first, up.second) if f is not None] + ["width (linear)"])
        add(change, np.sqrt(c / jj) * birge, p.ic(after, k), after, label)
    return out


# -------------------------------------------------------------------------------------------------- verdict

def _where_acts(fit, catalogue) -> str:
    """Where a fitted candidate acts on the drive (separation.location), drifts by their target; ``catalogue``:
    the model's EffectCatalogue."""
    name = fit.effect.split("[")[0]
    cls = catalogue[name] if name in catalogue else None
    return separation.location(fit.effect, fit.balance, getattr(cls, "target", None))


def _separating_measurement(a, b, catalogue) -> str:
    return separation.separating_measurement(a.effect, _where_acts(a, catalogue), b.effect, _where_acts(b, catalogue))


def _is_measurand(fit) -> bool:
    return fit is not None and fit.effect.split("[")[0] in MEASURAND_EFFECTS


def _left_where(run: Run, up: Update) -> str:
    """What an update leaves: the views still outside their band, and where the residual sits."""
    views = up.checks.get("views_after", {}).get("views", {})
    out = [n.replace("_", " ") for n, v in views.items() if v["outside_band"]]
    wb = analysis.where(run.comp, up.after_mean, up.after_raw) if up.after_mean is not None else None
    where = (f"the residual sits in the {wb['dominant_phase'].replace('_', ' ')} phase and wavelet level "
             f"{wb['dominant_level']}") if wb else ""
    worse = up.checks.get("views_made_worse") or []
    text = ("left outside the noise band: " + ", ".join(out) if out else "")
    if worse:
        text += ("; " if text else "") + "made worse: " + ", ".join(w.replace("_", " ") for w in worse)
    return "; ".join(t for t in (text, where) if t)


def _width_alone_explains(up: Update) -> bool:
    """The model at the fitted width is consistent in every view and outside the candidates' subspace: the width
    alone explains the recording. (An effect's update may pass within the model-form tolerance of its own law,
    decisions.confident; the width has no law of its own to be off in -- it is the measurand -- so a width that
    explains only CONFIDENT_EXPLAINED of the residual leaves room for a second effect it took up.)"""
    return bool(up.checks.get("consistent_in_every_view") and up.checks.get("outside_subspace_ok"))


@dataclass
class Verdict:
    """What verdict_step decides: the verdict, the effects in their roles, the additions for the next model
    version, and the ripple from the raw a1 spectrum."""
    verdict: str
    discovery: fitting.FitResult | None
    second: fitting.FitResult | None
    partial: list
    effects: list
    additions: list
    ripple_entry: dict | None
    line_not_locked: bool
    after_mean: np.ndarray


def decide_verdict(run: Run, up: Update, ripple_fit) -> Verdict:
    """The verdict (consistent / discovery / width / partial / nothing explains), the effects in their roles and
    the additions for the next model version."""
    comp = run.comp
    discovery = second = None
    partial: list = []
    additions: list = []
    ripple_ok = ripple_fit is not None and ripple_fit["confident"] and ripple_fit["locked"]
    line_not_locked = ripple_fit is not None and not ripple_fit["locked"]
    ripple_entry = ripple.as_discovery(ripple_fit) if ripple_ok else None
    after_mean = comp.model_mean
    if up.first is not None and up.confident:
        discovery, second = up.first, up.second
        after_mean = up.after_mean
    elif up.first is not None:
        partial = [f for f in (up.first, up.second) if f is not None]
    if discovery is not None and all(_is_measurand(f) for f in (discovery, second) if f is not None) \
            and not _width_alone_explains(up):
        # the width is the verdict only when it alone explains the recording (issue 31): confident only within the
        # model-form tolerance of an effect's law, it may have taken up an effect beside it -- a partial explanation
        # (its measured width: width_measurement's, with the error scaled by what is left)
        discovery, second, partial, after_mean = None, None, [up.first], comp.model_mean
    # the roles: the width is the measurand (reported, never added); the rest are model effects
    effects = [f for f in (discovery, second) if f is not None and not _is_measurand(f)]
    for role, f in zip((ROLE_DISCOVERY, ROLE_SECOND), effects):
        additions.append(Addition(f.effect.split("[")[0], f.effect,
                                  dict(zip(f.parameter_names, map(float, f.values))) | dict(f.fixed),
                                  dict(zip(f.parameter_names, map(float, f.uncertainty))), role))
    for f in partial:
        if not _is_measurand(f):
            additions.append(Addition(f.effect.split("[")[0], f.effect,
                                      dict(zip(f.parameter_names, map(float, f.values))) | dict(f.fixed),
                                      dict(zip(f.parameter_names, map(float, f.uncertainty))), ROLE_PARTIAL))
    if ripple_entry is not None and not any(a.effect == ripple.EFFECT for a in additions):
        role = ROLE_DISCOVERY if not additions or all(a.role == ROLE_PARTIAL for a in additions) else ROLE_SECOND
        additions.insert(0 if role == ROLE_DISCOVERY else len(additions),
                         Addition(ripple.EFFECT, ripple.EFFECT, dict(ripple_entry["parameters"]),
                                  dict(ripple_entry["uncertainty"]), role, "raw a1 spectrum"))

    if discovery is not None and not effects:
        verdict = MEASURAND
    elif discovery is not None or ripple_entry is not None:
        verdict = DISCOVERY
    elif partial:
        verdict = PARTIAL
    elif run.inconsistent or line_not_locked:
        verdict = NOTHING_EXPLAINS
    else:
        verdict = CONSISTENT
    return Verdict(verdict, discovery, second, partial, effects, additions, ripple_entry, line_not_locked,
                   after_mean)


def verdict_message(run: Run, up: Update, v: Verdict, width: WidthMeasurement, ripple_fit,
                    overall_before: float) -> str:
    """The verdict in one message: what the recording shows, and what tells near-ties apart."""
    comp = run.comp
    verdict, discovery, second, partial = v.verdict, v.discovery, v.second, v.partial
    best = run.fits[0] if run.fits else None
    wb = analysis.where(comp)
    where_text = (f"the residual sits in the {wb['dominant_phase'].replace('_', ' ')} phase and wavelet level "
                  f"{wb['dominant_level']}")
    if verdict == CONSISTENT:
        message = (f"the model agrees with the measurement within its noise band and model-form tolerance "
                   f"(residual {overall_before:.2f} x the noise floor): nothing to discover")
    elif verdict == NOTHING_EXPLAINS and not run.inconsistent:
        message = (f"the model agrees with the event average within its noise band and model-form tolerance "
                   f"(residual {overall_before:.2f} x the noise floor), but not with the raw spectrum")
    elif verdict == NOTHING_EXPLAINS:
        why = run.refusals(best)
        message = (f"nothing in the catalogue explains the residual (best: {best.effect}, explains "
                   f"{drive_terms.explained_percent(best.explained_fraction)}, delta_ic {best.delta_ic:.1f}"
                   + (f"; not taken: {'; '.join(why)}" if why else "") + f"); {where_text}")
    elif verdict == PARTIAL:
        names = " + ".join(f.effect for f in partial)
        message = (f"partial explanation, no confident discovery: {names} explains "
                   f"{drive_terms.explained_percent(up.checks.get('explained', partial[-1].explained_fraction))} of the residual but "
                   f"{_left_where(run, up) or 'leaves it outside the noise band'} (an effect outside the catalogue, "
                   "or a catalogue effect in another form?); add-effect --accept-partial takes it as the nearer "
                   "model, the loop's next step when nothing is proposed")
    else:
        parts = []
        if discovery is not None:
            caveat = separation.motor_side_note(discovery.effect, discovery.indistinguishable_from)
            if _is_measurand(discovery):
                parts.append(f"the backlash width is {width.width_m * 1e3:.3f} ± {width.uncertainty_m * 1e3:.2f} mm "
                             f"(model nominal {width.nominal_width_m * 1e3:.3f} mm): the width is what the monitor "
                             "measures, not a missing effect")
            elif run.before.consistent:           # seen on the events only (screen_step's events_evidence)
                parts.append(f"missing effect: {drive_terms.effect_text(discovery.to_json(), run.model)}, seen in the "
                             "events at their own shaft angles (the event average is within its noise band: the term "
                             f"washes out there), delta_ic {discovery.delta_ic:.1f}")
            else:
                parts.append(f"missing effect: {drive_terms.effect_text(discovery.to_json(), run.model)}, explains "
                             f"{drive_terms.explained_percent(discovery.explained_fraction)} of the residual, delta_ic {discovery.delta_ic:.1f}")
            if discovery.indistinguishable_from:
                parts[-1] += ("; not distinguishable from this recording from "
                              + ", ".join(discovery.indistinguishable_from))
                same = [t for t in discovery.indistinguishable_from if t in identical_to(discovery.effect)]
                twins = [f for f in run.fits if f.effect in discovery.indistinguishable_from and f.effect not in same]
                if same:
                    parts[-1] += (f". {', '.join(same)} is the same term of the model as {discovery.effect} (no "
                                  "recording and no sensor separates them)")
                by_place: dict = {}
                for t in twins:
                    by_place.setdefault(_where_acts(t, run.model.catalogue), []).append(t.effect)
                parts[-1] += "".join(
                    ". To tell them apart: " + separation.separating_measurement(
                        discovery.effect, _where_acts(discovery, run.model.catalogue), " and ".join(names), place)
                    for place, names in by_place.items())
            if caveat:
                parts[-1] += ". Or " + caveat
            if second is not None:
                if _is_measurand(second):
                    parts.append(f"at a backlash width of {width.width_m * 1e3:.3f} mm (nominal "
                                 f"{width.nominal_width_m * 1e3:.3f} mm: the measurand, not an effect)")
                else:
                    parts.append(f"a second effect on top: {drive_terms.effect_text(second.to_json(), run.model)}"
                                 + (" (not distinguishable from this recording from "
                                    + ", ".join(second.indistinguishable_from) + ")"
                                    if second.indistinguishable_from else ""))
                if up.pair_alternatives:
                    parts[-1] += ("; the pair is not distinguishable from this recording from "
                                  + ", ".join(" + ".join(a["candidates"]) for a in up.pair_alternatives))
        elif v.ripple_entry is not None and run.inconsistent:
            # the spectral line is explained, the event average not (proposal_basis: the proposal runs on it)
            parts.append("the event average is not explained by a catalogue effect"
                         + (f" ({' + '.join(f.effect for f in partial)} explains "
                            f"{drive_terms.explained_percent(up.checks.get('explained', partial[-1].explained_fraction))} of it but "
                            f"{_left_where(run, up) or 'leaves it outside the noise band'})" if partial else
                            f" (best: {best.effect}, explains {drive_terms.explained_percent(best.explained_fraction)})" if best is not None
                            else ""))
        elif v.ripple_entry is not None:
            parts.append("nothing to discover in the event average")
        if v.ripple_entry is not None:
            parts.append(ripple.describe(ripple_fit))
        message = "; ".join(parts)
    if v.line_not_locked:
        message += "; " + ripple.describe_not_locked(ripple_fit)
    return message


def verdict_step(run: Run, decision: Decision, up: Update, ripple_fit, spec) -> Diagnosis:
    """The verdict (decide_verdict), its message (verdict_message) and the report (report.diagnosis_report)
    -> diagnosis.Diagnosis."""
    comp = run.comp
    overall_before = float(np.sqrt(np.mean(analysis.residual_ratio(comp) ** 2)))
    width = width_measurement(run, up)
    v = decide_verdict(run, up, ripple_fit)
    message = verdict_message(run, up, v, width, ripple_fit, overall_before)
    saturation = saturation_of(run.meas.signals)
    message = saturated_first(message, saturation)
    discovery, second, partial, ripple_entry = v.discovery, v.second, v.partial, v.ripple_entry
    # the JSON's candidate entries: a confident ripple is the discovery when the event average has none, else
    # the second effect when there is none
    disc_json = discovery.to_json() if discovery is not None else ripple_entry
    second_json = (second.to_json() if second is not None
                   else ripple_entry if discovery is not None and ripple_entry is not None else None)
    ranked = _ranked(run, discovery)
    after_view = (consistency.test(run.views, run.problem.residual(up.after_pred)) if discovery is not None
                  else run.before)
    report_dict = report.diagnosis_report(run, up, v, ripple_fit, spec, overall_before, _identifiability(run))
    report_dict["input_saturation"] = saturation
    report_dict["near_ties"] = _near_ties(run, discovery)
    conditions = Conditions(run.meas.source, run.model.label(),
                            str(run.model.path) if run.model.path else None, dict(run.model.nominal),
                            dict(run.overrides), [str(f) for f in run.model.effect_files],
                            run.model.to_dict(), list(comp.seeds), dict(comp.conditions), comp.events.n_events)
    views = {"before": run.before.to_json(), "after": after_view.to_json()}
    return Diagnosis(conditions, v.verdict, message, disc_json, second_json,
                     [f.to_json() for f in partial], v.additions, width, ranked, views, report_dict, comp,
                     up.after_mean if discovery is not None else None)


def saturated_first(message: str, saturation: dict) -> str:
    """A recording with a sensor at its rail (or stuck) says so before any effect is named: a clipped
    accelerometer changes the event average as an effect would."""
    if not saturation["saturated"]:
        return message
    railed = any("at its rail" in m for m in saturation["messages"])
    what = "the recording is saturated" if railed else "a sensor of the recording is stuck"
    return f"{what}: {'; '.join(saturation['messages'])}; what follows is read off those samples: {message}"


def _near_ties(run: Run, discovery) -> list:
    """Fitted candidates that the decision told apart from the discovery, but only just: they explain at least
    MIN_EXPLAINED of the residual and trail it by less than DELTA_IC_DECISIVE; each with the measurement that would
    separate them (separation.py)."""
    if discovery is None:
        return []
    out = []
    for f in run.fits:
        if (f is discovery or f.effect == discovery.effect or f.effect in discovery.indistinguishable_from
                or f.explained_fraction < MIN_EXPLAINED or f.delta_ic - discovery.delta_ic >= DELTA_IC_DECISIVE):
            continue
        out.append({"effect": f.effect.split("[")[0], "candidate": f.effect, "description": f.description,
                    "explained_fraction": float(f.explained_fraction), "delta_ic": float(f.delta_ic),
                    "ic_behind": float(f.delta_ic - discovery.delta_ic),
                    "separating_measurement": _separating_measurement(discovery, f, run.model.catalogue)})
    return out


def _ranked(run: Run, discovery) -> list:
    scr, by_name = run.screening, run.by_name
    refined = {f.effect for f in run.fits}
    ranked = [f.to_json() | {"delta_ic_linearised": float(scr[f.effect].delta_ic_lin)} for f in run.fits] + [
        {"effect": n, "candidate": n,
         "parameters": {pp.name: float(v) for pp, v in zip(by_name[n].parameters, scr[n].x_lin)},
         "uncertainty": None, "delta_ic": None, "explained_fraction": float(scr[n].explained_lin),
         "indistinguishable_from": [], "screening_only": True, "balance": by_name[n].balance,
         "delta_ic_linearised": float(scr[n].delta_ic_lin)}
        for n in run.order if n not in refined]
    for r in ranked:
        if discovery is not None and r["effect"] in discovery.indistinguishable_from:
            twin = next((f for f in run.fits if f.effect == r["effect"]), None)
            r["separating_measurement"] = (_separating_measurement(discovery, twin, run.model.catalogue)
                                           if twin is not None else
                                           "none: the same term of the model (decisions.IDENTICAL)")
    return ranked


def _identifiability(run: Run) -> dict:
    """How far each candidate's whole fit range moves the evidence, in noise floors (linearised)."""
    p = run.problem
    out = {}
    for n in run.order:
        lo, hi = run.by_name[n].bounds()
        span = run.screening[n].jacobian * (hi - lo)[None, :]
        reach_ev = float(np.max(np.sqrt(np.mean(span[p.event_slice] ** 2, axis=0))))
        reach_sp = float(np.max(np.sqrt(np.mean(span[p.spectral_slice] ** 2, axis=0))))
        reach_dc = float(np.max(np.sqrt(np.mean(span[p.dc_slice] ** 2, axis=0))))
        reach = max(reach_ev, reach_sp, reach_dc)
        out[n] = {"range_effect_over_noise_floor": reach, "event_average_over_noise_floor": reach_ev,
                  "spectral_shape_over_noise_floor": reach_sp, "record_mean_over_noise_floor": reach_dc,
                  "identifiable": reach >= 1.0}
    return out


def diagnose(meas, model, seeds=None, effects=None, progress=None, second: bool = True,
             overrides=None, propose: bool = True) -> Diagnosis:
    """The whole diagnosis of ``meas`` against ``model`` (a WorkbenchModel): the steps above, in order.
    ``effects``: only these candidates are ranked (the views and the tolerance use the whole catalogue);
    ``overrides``: the command-line overrides the model was loaded with (recorded in the conditions);
    ``propose``: when nothing in the catalogue explains (partial, nothing explains), propose a term from the
    generic library (proposal.py; the JSON's ``proposal``)."""
    run = prepare(meas, model, seeds, effects, overrides)
    screen_step(run, effects, progress)
    refine_step(run)
    decision = decide_step(run)
    up = second_effect_step(run, decision, second)
    confidence_step(run, up, decision)
    ripple_fit, spec = spectral_step(run)
    result = verdict_step(run, decision, up, ripple_fit, spec)
    if propose:
        basis = proposal_basis(run, up, result.verdict)
        # a sensor at its rail or stuck: its residual is the fault's, no term is fitted to it
        gated = proposal.sensor_fault_gate(result.report.get("input_saturation")) if basis is not None else None
        found = gated or (proposal.propose(run, up, basis) if basis is not None else None)
        if gated is not None:
            result.message += "; no term proposed: the residual is read off a faulty sensor (fix it, then diagnose again)"
        result.report["proposal"] = None if found is None else found.to_json()
        result.report["proposal_after"] = None if basis is None else PROPOSAL_AFTER[(result.verdict, basis)]
        if found is not None and found.proposed:
            lead = ("; proposed term outside the catalogue: " if result.verdict == basis else
                    f"; {up.first.effect}" + (f" + {up.second.effect}" if up.second is not None else "")
                    + f" explains {drive_terms.explained_percent(up.checks.get('explained', 0.0))} of the residual only within the model-form "
                    "tolerance of its law (its model is outside the noise band in "
                    + ", ".join(n.replace("_", " ") for n, v in up.checks.get("views_after", {}).get("views", {}).items()
                                if v.get("outside_band")) + "); what is left is proposed as a term outside the "
                    "catalogue: " if basis == PARTIAL and up.confident else
                    "; the event average is not explained by the spectral discovery: proposed term outside the "
                    "catalogue: ")
            # the finding without the reason's no-plug-in note: the message ends with what to do instead
            result.message += (f"{lead}{found.finding} "
                               + ("(add-effect --accept-proposal)" if found.plugin_source else
                                  "(a sensor's term or a change in time: check the sensor, nothing to add to the model)"))
    return result


# why the proposal ran, by (verdict, the residual it was fitted to): the JSON's ``proposal_after``
PROPOSAL_AFTER = {(PARTIAL, PARTIAL): "partial", (NOTHING_EXPLAINS, NOTHING_EXPLAINS): "nothing_explains",
                  (DISCOVERY, PARTIAL): "discovery_within_form_tolerance_or_spectral_beside_a_partial",
                  (DISCOVERY, NOTHING_EXPLAINS): "spectral_discovery_beside_an_unexplained_event_average"}


def proposal_basis(run: Run, up: Update, verdict: str) -> str | None:
    """The residual the proposal (proposal.propose) is fitted to, as one of proposal.VERDICTS, or None (nothing to
    propose: the model is consistent, or a catalogue effect explains the recording):
    - ``partial`` / ``nothing_explains``: the verdict's own;
    - a ``discovery`` made in the raw a1 spectrum alone (a torque ripple, ripple.py) while the event average stays
      unexplained (the model inconsistent, no confident update): the event average's residual, on top of its partial
      explanation when there is one (measured on od_a1_rotating_gravity, an a1 sensor turning through gravity: the
      ripple explained the 24 Hz line, the a1 gain 64 % of the event average at T^2 302 over its limit 21.7; the
      proposal, a1 += 9.5 m/s^2 sin(alpha1 + 2.36), consistent in every view);
    - a ``discovery`` confident only within the model-form tolerance of its law (decisions.confident's
      ``within_form_tolerance``) whose model leaves a view FORM_LEFT_T2_RATIO x its limit or more: on top of it,
      as on a partial explanation (docs/workbench.md "A discovery within the form tolerance")."""
    if verdict in proposal.VERDICTS:
        return verdict
    if verdict != DISCOVERY:
        return None
    if not up.confident and run.inconsistent:
        return PARTIAL if up.first is not None else NOTHING_EXPLAINS
    if up.confident and up.checks.get("within_form_tolerance") and form_left_ratio(up) >= FORM_LEFT_T2_RATIO:
        return PARTIAL
    return None


FORM_LEFT_T2_RATIO = 5.0     # a discovery within the form tolerance that leaves a view at this multiple of its limit or
                             # more gets the proposal on top. The form tolerance is a share of the residual (85 %); on a
                             # strong mechanism what it leaves can be many times the noise. Measured (discovery_probe.py,
                             # 29 Nov 2026): the foreign bench's catalogue families in other laws that pass only by the
                             # form tolerance leave at most 2.48 (a 4th-order Butterworth on a1, spectral shape; a
                             # Hunt-Crossley contact 1.05, +30 % mass 1.03, a fan load 1.22, a rail friction 2.25 -- and
                             # on 3 of them a generic term WOULD be selected on top: the law's difference, not a missing
                             # mechanism); an a1 solenoid pickup outside the catalogue, read as a1 bias + gain at 93 %,
                             # left the event average at 26.2 x its limit


def form_left_ratio(up: Update) -> float:
    """The largest T^2 over its limit among the views (outside the subspace included) that a discovery's model leaves."""
    views = up.checks.get("views_after", {}).get("views", {})
    return max((v["T2"] / v["T2_limit_p01"] for v in views.values()), default=0.0)


def public(result) -> dict:
    """The JSON of a diagnosis (Diagnosis.to_json); kept for the callers of the former dict result."""
    return result.to_json() if isinstance(result, Diagnosis) else {k: v for k, v in result.items()
                                                                    if not k.startswith("_")}
