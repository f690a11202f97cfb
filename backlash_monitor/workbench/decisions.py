"""The decision rules of a diagnosis (docs/workbench.md, "Decisions"), shared by the single-effect steps
(diagnose.py) and the pair search (pairs.py).

- a candidate *qualifies* when its BIC on the events beats the model's by DELTA_IC_STRONG, it explains at least
  MIN_EXPLAINED of the residual, it is not pinned at a bound of its fit range, and its change exceeds the
  model-form tolerance of the parameter it moves (tolerance.py); the width, which has no nominal tolerance (it is
  the measurand), and an effect whose evidence is below DELTA_IC_DECISIVE, must also differ from the nominal by
  SIGNIFICANCE of its own uncertainty: a width within its
  uncertainty of the nominal is no measurement of another width (measured: a clean foreign 8.3 mm drive, just
  outside the event average's band, "measured" 8.44 +- 0.11 mm);
- *the look-elsewhere effect*: the winner is the best of the K candidates screened, so below DELTA_IC_DECISIVE its
  significance is family-wise (Sidak): z above family_significance(K), the z at which the best of K independent null
  candidates passes as rarely as one candidate passes SIGNIFICANCE (two-sided 4.55 %): 2.00 for K = 1, 3.16 for the
  catalogue's 29. Measured on the fifth sealed half's clean drive: the best of 29 screened, a spring stiffness drift
  100 -> 81 +- 8 N/m (z 2.4) at delta_ic -3.9, had been a discovery. Sidak over K is conservative where candidates are
  alike (the low-pass in three section counts); decisive evidence needs no correction: the best of 29 null
  one-parameter candidates reaches delta_ic -10 on 16 events (chi^2 > 12.8) about 1 time in 100;
- a second effect's values must be *significant*: more than SIGNIFICANCE uncertainties from the model's;
- an update is *confident* when the model with it is consistent in every view (consistency.py, with the
  tolerance), or, for a strong effect fitted to >= CONFIDENT_EXPLAINED of the residual, consistent outside the
  candidates' subspace and in its overall residual; and it never makes a view worse (*every view*: an effect must
  not trade the event average for the raw spectra or the record mean).
"""
from __future__ import annotations

import numpy as np
from scipy.special import erfc, ndtri

from . import consistency, tolerance
from .diagnosis_result import MEASURAND_EFFECTS

DELTA_IC_STRONG = 2.0        # "positive" evidence (Kass & Raftery) on E events
DELTA_IC_DECISIVE = 10.0     # below "very strong" evidence (Kass & Raftery) a single effect must also be significant:
                             # its values > SIGNIFICANCE uncertainties from the model's (measured: a clean foreign 8.3 mm
                             # drive just outside the event average's band took a shaft compliance of 2.3e-5 +- 2.3e-5
                             # rad/(N*m) at delta_ic -3.9; strong effects keep the IC alone, their jackknife can be far off)
DELTA_IC_TIE = 2.0           # two candidates closer than this are not distinguishable from the recording
MIN_EXPLAINED = 0.5
MIN_EXPLAINED_SECOND = 0.3
SIGNIFICANCE = 2.0           # a fitted value must differ from the model's by > 2 uncertainties (second effects)
TOLERANCE_FACTOR = 2.0       # a fitted change must exceed 2 x its nominal tolerance
CONFIDENT_EXPLAINED = 0.85   # the model-form tolerance of an effect's own law: explaining this share of the residual in
                             # the fits' whole metric (every view and outside the subspace), what is left is the form in
                             # which the drive writes the effect (docs/workbench.md "Model-form tolerance"; measured on
                             # foreign drives: their catalogue families in other laws 0.89-0.997, outside effects <= 0.79)
COMPLEMENT_EXPLAINED = 0.6   # outside the subspace: within the limit, or this share of the model's T^2 removed
VIEW_WORSE_FACTOR = 1.3      # per signal: residual/noise may not grow beyond max(before, 1) x this (the rms ratio of
                             # a correct model scattered 0.45-1.09 between three recordings of one drive: an effect
                             # whose event-average change is at noise level moves it by that much either way)


def family_significance(n_candidates: int) -> float:
    """The z a value must exceed when it is the best of ``n_candidates`` looked at (Sidak): the two-sided tail
    alpha_K = 1 - (1 - alpha)^(1/K) with alpha the tail of SIGNIFICANCE, so that the best of K independent null
    candidates passes as rarely as one candidate passes SIGNIFICANCE. K = 1: SIGNIFICANCE itself."""
    k = max(int(n_candidates), 1)
    alpha = float(erfc(SIGNIFICANCE / np.sqrt(2.0)))
    alpha_k = -np.expm1(np.log1p(-alpha) / k)
    return float(-ndtri(alpha_k / 2.0))


def significant(fit, threshold: float = SIGNIFICANCE) -> bool:
    """Every fitted value differs from the model's by more than ``threshold`` x its (jackknife) uncertainty; the
    parameters of one of the fit's ``groups`` together (their z above ``threshold``): :func:`smallest_z` above it."""
    return smallest_z(fit) > threshold


def smallest_z(fit) -> float:
    """The smallest of the fitted values' distances from the model's in their (jackknife) uncertainties; a group of
    the fit's ``groups`` counts as one value, its joint z (the quantity :func:`significant` tests)."""
    d = np.abs(np.asarray(fit.values, dtype=float) - np.asarray(fit.nominal, dtype=float))
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(d > 0, d / np.asarray(fit.uncertainty, dtype=float), 0.0)
    z = np.where(np.isnan(z), 0.0, z)
    for start, stop, group_z in getattr(fit, "groups", ()):
        z[start:stop] = group_z
    return float(np.min(z)) if z.size else float("inf")


def refusals(fit, candidate, min_explained: float = MIN_EXPLAINED, n_candidates: int = 1) -> list[str]:
    """Why a fitted candidate does not qualify, in words (empty: it qualifies). ``n_candidates``: how many
    candidates the winner is the best of (diagnose: every one screened and ranked). (No significance test for a
    single effect with decisive evidence: its test is the IC, and the jackknife through the final Jacobian can be far
    off for a strongly nonlinear parameter -- measured: a quadratic wheel drag fitted 0.064 +- 0.040 at delta_ic
    -250. Weaker evidence needs the family-wise significance over the candidates looked at (family_significance);
    the width with decisive evidence SIGNIFICANCE.)"""
    measurand = fit.effect.split("[")[0] in MEASURAND_EFFECTS
    weak = fit.delta_ic > -DELTA_IC_DECISIVE
    threshold = family_significance(n_candidates) if weak else SIGNIFICANCE
    why = []
    if fit.delta_ic > -DELTA_IC_STRONG:
        why.append(f"no evidence on the events (delta_ic {fit.delta_ic:.1f} > {-DELTA_IC_STRONG:.0f})")
    if fit.explained_fraction < min_explained:
        why.append(f"explains less than {min_explained:.0%} of the residual")
    if fit.at_bound:
        why.append("fitted at the bound of its range")
    if not tolerance.beyond_tolerance(fit, candidate, TOLERANCE_FACTOR):
        why.append(f"its change is within {TOLERANCE_FACTOR:g} x the model's nominal tolerance")
    if (measurand or weak) and not significant(fit, threshold):
        z = smallest_z(fit)
        if weak and n_candidates > 1:
            why.append(f"weak evidence (delta_ic {fit.delta_ic:.1f} > {-DELTA_IC_DECISIVE:.0f}) and z {z:.2f} below "
                       f"{threshold:.2f}, the significance of the best of {n_candidates} candidates")
        else:
            why.append(f"its value is {z:.2f} of its uncertainties from the model's, not more than {threshold:.2f}")
    return why


def qualifies(fit, candidate, min_explained: float = MIN_EXPLAINED, n_candidates: int = 1) -> bool:
    """The fitted candidate may be named: :func:`refusals` finds no reason against it."""
    return not refusals(fit, candidate, min_explained, n_candidates)


def views_not_worse(problem, before_pred, after_pred) -> tuple[bool, list]:
    """Every view at least as good after the update as before: a view outside its band must not grow, a view
    inside must stay inside; per signal the event average's residual/noise must not grow beyond
    max(before, 1) x VIEW_WORSE_FACTOR. -> (ok, [names of the views made worse])."""
    b = consistency.test(problem.views, problem.residual(before_pred))
    a = consistency.test(problem.views, problem.residual(after_pred))
    worse = [n for n, v in a.views.items() if v.t2 > max(b.views[n].t2, b.views[n].limit) * (1 + 1e-9)]
    rb = per_signal_ratio(problem, before_pred)
    ra = per_signal_ratio(problem, after_pred)
    worse += [f"event_average_{s}" for s, x, y in zip(("a1", "a2"), rb, ra) if y > max(x, 1.0) * VIEW_WORSE_FACTOR]
    return not worse, worse


def per_signal_ratio(problem, pred) -> np.ndarray:
    """Per signal: rms of the weighted event-average residual (residual / noise floor)."""
    r = problem.event_part(problem.residual(pred)).reshape(2, -1)
    return np.sqrt(np.mean(r ** 2, axis=1))


def confident(problem, after_pred, base_pred) -> tuple[bool, dict]:
    """The model with the discovered effect(s) agrees with the measurement. -> (confident, checks).
    Either the update is consistent in every view and outside the candidates' subspace (within the limit there, or
    COMPLEMENT_EXPLAINED of the model's own T^2 there removed), or it explains CONFIDENT_EXPLAINED of the residual in
    the fits' whole metric (the effect's law differs from the catalogue's; the rest is reported). Always: the
    event-average residual within INCONSISTENT_RATIO of the noise floor, and no view made worse."""
    r = problem.residual(after_pred)
    after = consistency.test(problem.views, r)
    before = consistency.test(problem.views, problem.residual(base_pred))
    explained = problem.explained_share(problem.project(r), problem.fit_residual(base_pred))
    inside = after.consistent
    # outside the candidates' subspace the effect must not leave what the model's noise does not account for
    # (an effect outside the catalogue that a catalogue effect mimics inside the subspace)
    out_a, out_b = after.views[consistency.OUTSIDE], before.views[consistency.OUTSIDE]
    outside_ok = out_a.t2 <= out_a.limit or out_a.t2 <= (1.0 - COMPLEMENT_EXPLAINED) * out_b.t2
    overall_ok = after.residual_over_noise <= consistency.INCONSISTENT_RATIO
    not_worse, worse = views_not_worse(problem, base_pred, after_pred)
    strict = inside and outside_ok
    form = explained >= CONFIDENT_EXPLAINED
    ok = bool(overall_ok and not_worse and (strict or form))
    return ok, {"consistent_in_every_view": bool(inside), "explained": explained, "outside_subspace_ok": bool(outside_ok),
                "overall_ok": bool(overall_ok), "no_view_worse": bool(not_worse), "views_made_worse": worse,
                "within_form_tolerance": bool(form and not strict), "views_after": after.to_json()}


def likelihood_part(fit, n_events: int) -> float:
    """The recording's own evidence of a fit: its delta_ic without the BIC's parameter penalty k ln E. Two candidates
    are indistinguishable when these differ by < DELTA_IC_TIE (a two-parameter law that fits as well as a
    one-parameter one is not told apart by the recording; the penalty only prefers the simpler)."""
    return float(fit.delta_ic - len(fit.values) * np.log(max(n_events, 2)))


# catalogue effects that are the same term of the model (no recording and no sensor tells them apart)
IDENTICAL = (("mass_force_offset", "working_resistance_drift"),)


def identical_to(name: str) -> list:
    return [b if a == name else a for a, b in IDENTICAL if name in (a, b)]
