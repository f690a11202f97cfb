"""Proposing the missing term: when no catalogue effect explains a recording, a sparse sum of generic candidate terms
(candidate_terms.py) fitted to the residual that is left, selected honestly on the events (docs/workbench.md,
"Proposing a missing term").

1. **sensitivities**: the model (with the partial explanation, when diagnose found one) and every candidate term at a
   small coefficient in its balance, one batch on the diagnosis's seeds (common random numbers): the column of each
   term's effect on the prediction (event average, spectral shape, record mean), whitened in the diagnosis's views;
2. **selection on the events**: forward selection of groups of terms (a harmonic's sine and cosine are one group) by
   leave-one-event-out cross-validation: a group enters only when it lowers the held-out events' error by more than
   ``CV_Z`` of that gain's standard error over the events (the events are the independent units, never the
   samples), at most ``MAX_GROUPS``;
3. **stability**: the selection repeated on ``BOOTSTRAP`` resamples of the events; a group is proposed only when it
   is selected in at least ``STABILITY`` of them and on the whole recording;
4. **fit and test like a catalogue effect**: the selected coefficients refined by bounded least squares on the
   simulator (fitting.refine: the same metric, the same jackknife uncertainty over the events), the model with them
   tested by diagnose's consistency test (consistency.test) in every view;
5. **outputs**: the law in words and symbols, a plug-in file in the ``--effects-file`` form with the fitted values
   (bounded parameters, neutral defaults), and what add-effect --accept-proposal makes of it (the next version).
"""
from __future__ import annotations

import copy
import time
from dataclasses import dataclass, field

import numpy as np

from . import candidate_terms, consistency, fitting, plant_adapter

VERDICTS = ("partial", "nothing_explains")
CV_Z = 3.0             # a group enters when its held-out gain is CV_Z standard errors (over the events) above 0
MAX_GROUPS = 3         # at most this many groups of terms in one proposal (a sparse law)
BOOTSTRAP = 60         # resamples of the events for the stability
STABILITY = 0.6        # share of the resamples a proposed group must be selected in (stability selection)
MIN_EVENTS = 6         # fewer events: no honest cross-validation
REFINE_NFEV = 5        # least-squares evaluations of the refinement on the simulator
BOOTSTRAP_SEED = 31    # the resampling's seed: a diagnosis is reproducible
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
    plugin_values: dict = field(default_factory=dict)
    on_top_of: list = field(default_factory=list)   # the partial explanation the terms were fitted on top of
    cpu_seconds: float = 0.0
    simulated_sets: int = 0

    def to_json(self) -> dict:
        return {"proposed": self.proposed, "reason": self.reason, "law": self.law,
                "terms": [{"balance": p.balance, "state": p.state(), "group": p.terms[0].group,
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
                "method": "forward selection of generic terms by leave-one-event-out cross-validation, stable under "
                          f"{BOOTSTRAP} resamples of the events (>= {STABILITY:.0%}), refined on the simulator"}


# ------------------------------------------------------------------------------------------ selection (pure numpy)
def cv_errors(G: np.ndarray, Y: np.ndarray, cols) -> np.ndarray:
    """Per event e: |Y_e - G c_(-e)|^2, c_(-e) the least-squares coefficients on the mean of the other events.
    G: (D, M) whitened sensitivities; Y: (E, D) the events' whitened residuals."""
    e = Y.shape[0]
    if not cols:
        return np.sum(Y ** 2, axis=1)
    ga = G[:, list(cols)]
    loo = (Y.sum(axis=0)[None] - Y) / (e - 1)
    c = loo @ np.linalg.pinv(ga).T
    return np.sum((Y - c @ ga.T) ** 2, axis=1)


def forward_select(G: np.ndarray, Y: np.ndarray, groups: list, z: float = CV_Z, max_groups: int = MAX_GROUPS):
    """Groups (lists of column indices) entered one by one while the best one's held-out gain over the events is
    ``z`` standard errors above 0. -> ([group index], [(group index, mean gain, z)])."""
    sel: list = []
    cols: list = []
    err = cv_errors(G, Y, cols)
    steps = []
    e = Y.shape[0]
    while len(sel) < max_groups:
        best = None
        for gi, g in enumerate(groups):
            if gi in sel:
                continue
            d = err - cv_errors(G, Y, cols + list(g))
            m, s = float(d.mean()), float(d.std(ddof=1)) / np.sqrt(e)
            zz = m / s if s > 0 else (np.inf if m > 0 else 0.0)
            if zz > z and (best is None or m > best[1]):
                best = (gi, m, zz)
        if best is None:
            break
        sel.append(best[0])
        cols += list(groups[best[0]])
        err = cv_errors(G, Y, cols)
        steps.append(best)
    return sel, steps


def stability(G: np.ndarray, Y: np.ndarray, groups: list, n: int = BOOTSTRAP, seed: int = BOOTSTRAP_SEED) -> np.ndarray:
    """Share of ``n`` resamples of the events (with replacement) in which each group is selected."""
    rng = np.random.default_rng(seed)
    e = Y.shape[0]
    counts = np.zeros(len(groups))
    for _ in range(n):
        idx = rng.integers(0, e, e)
        if len(np.unique(idx)) < 3:
            continue
        sel, _ = forward_select(G, Y[idx], groups)
        counts[sel] += 1
    return counts / n


# ------------------------------------------------------------------------------------------ the proposal of a run
def _library_model(model):
    lib = copy.copy(model)
    lib.effect_files = list(model.effect_files) + [candidate_terms.library_file()]
    lib.effects_added = list(model.effects_added)
    return lib


def _term_effect(term, lower_upper=None) -> plant_adapter.CandidateEffect:
    unit, _, bound = candidate_terms.BALANCES[term.balance]
    key = f"{term.name}.{candidate_terms.coefficient_name(term)}"
    lo, hi = lower_upper or (-bound, bound)
    return plant_adapter.CandidateEffect(term.name, term.name, term.balance, term.symbol,
                                         (plant_adapter.EffectParameter(term.name, unit, 0.0, lo, hi, key),))


def _base_sets(run, up) -> tuple[dict, list]:
    """The parameter set of the partial explanation the terms go on top of (diagnose's update), and its names."""
    sets, names = {}, []
    for f in (getattr(up, "first", None), getattr(up, "second", None)):
        if f is None or f.effect not in run.by_name:
            continue
        sets.update(plant_adapter.apply_values(run.by_name[f.effect], f.values))
        names.append(f.effect)
    return sets, names


def propose(run, up, verdict: str) -> Proposal | None:
    """The proposal for a diagnosis (diagnose.Run and Update, its verdict); None when the verdict is not one of
    VERDICTS (a consistent model or a catalogue effect that explains: nothing to propose)."""
    if verdict not in VERDICTS:
        return None
    t0 = time.process_time()
    p0 = run.problem
    if p0.n_events < MIN_EVENTS:
        return Proposal(False, f"{p0.n_events} events: too few for a cross-validation over the events "
                               f"(at least {MIN_EVENTS})")
    p = copy.copy(p0)
    p.model = _library_model(run.model)
    base_sets, on_top = _base_sets(run, up) if verdict == "partial" else ({}, [])
    p.base = {**p0.base, **base_sets}
    n_before = p.n_sets_simulated
    terms = candidate_terms.library()
    keys = [f"{t.name}.{candidate_terms.coefficient_name(t)}" for t in terms]
    steps = np.array([candidate_terms.BALANCES[t.balance][1] for t in terms])
    # 1. sensitivities: the reference and every term at a small coefficient, one batch (common random numbers)
    sets = [{}] + [{k: float(h)} for k, h in zip(keys, steps)]
    preds = []
    for i in range(0, len(sets), BATCH_SETS):        # in batches: a batch's raw runs are sets x seeds x samples
        ens = p.evaluate(sets[i:i + BATCH_SETS])
        preds += [p.pred_of(ens, j) for j in range(len(sets[i:i + BATCH_SETS]))]
        del ens
    ref = preds[0]
    S = np.stack([(preds[j + 1] - ref) / steps[j] for j in range(len(terms))], axis=1)
    G = p.project(S)
    Y = p.project((p.event_vecs - ref[None]).T).T
    names = [t.name for t in terms]
    group_names = list(candidate_terms.groups())
    groups = [[names.index(n) for n in candidate_terms.groups()[g]] for g in group_names]
    # 2-3. selection on the events, and its stability under their resampling
    sel, cv_steps = forward_select(G, Y, groups)
    freq = stability(G, Y, groups)
    stab = {group_names[i]: float(freq[i]) for i in np.argsort(-freq) if freq[i] > 0}
    cv = [{"group": group_names[g], "held_out_gain": m, "z": z} for g, m, z in cv_steps]
    stable = [g for g in sel if freq[g] >= STABILITY]
    out = Proposal(False, "", stability=stab, cv=cv, on_top_of=on_top)
    if not stable:
        out.reason = ("no candidate term lowers the held-out events' error stably: "
                      + (", ".join(f"{group_names[g]} selected in {freq[g]:.0%} of the resamples" for g in sel)
                         if sel else f"none gains {CV_Z:g} standard errors over the events"))
        out.cpu_seconds = time.process_time() - t0
        out.simulated_sets = p.n_sets_simulated - n_before
        return out
    cols = [c for g in stable for c in groups[g]]
    # 4. the coefficients: linear estimate on the whole recording, then refined on the simulator
    c_lin = np.linalg.lstsq(G[:, cols], Y.mean(axis=0), rcond=None)[0]
    chosen = [terms[c] for c in cols]
    effs = [_term_effect(t) for t in chosen]
    cand = plant_adapter.CandidateEffect("proposal", "proposal", chosen[0].balance, "proposed terms",
                                         tuple(e.parameters[0] for e in effs))
    lo, hi = cand.bounds()
    c_lin = np.clip(c_lin, lo * 0.999, hi * 0.999)
    ref_ic = p.ic(ref, 0)
    lin_expl = p.explained_share(p.project(p.residual(ref + S[:, cols] @ c_lin)), p.project(p.residual(ref)))
    fit = fitting.refine(p, cand, fitting.Linearisation(S[:, cols], steps[cols], c_lin, lin_expl), ref, ref_ic,
                         max_nfev=REFINE_NFEV)
    after = consistency.test(p.views, p.residual(fit.pred))
    pieces = []
    i = 0
    for g in stable:
        n = len(groups[g])
        pieces.append(candidate_terms.ProposedPiece(tuple(terms[c] for c in groups[g]),
                                                    tuple(float(v) for v in fit.values[i:i + n]),
                                                    tuple(float(u) for u in fit.uncertainty[i:i + n])))
        i += n
    src, values = candidate_terms.proposal_source(pieces)
    out.proposed = True
    out.pieces = pieces
    out.law = candidate_terms.proposal_law(pieces)
    out.explained_fraction = float(fit.explained_fraction)
    out.delta_ic = float(fit.delta_ic)
    out.consistent = bool(after.consistent)
    out.views_after = after.to_json()
    out.plugin_source, out.plugin_values = src, values
    out.reason = (f"{out.law}: explains {fit.explained_fraction:.0%} of the residual"
                  + (f" left by {' + '.join(on_top)}" if on_top else "")
                  + (", the model with it consistent in every view" if after.consistent
                     else ", the model with it still outside the noise band"))
    out.cpu_seconds = time.process_time() - t0
    out.simulated_sets = p.n_sets_simulated - n_before
    return out
