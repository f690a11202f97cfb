"""A measurand's value and uncertainty averaged over the models that may hold (docs/workbench.md, "The measured
width when the model does not hold").

When no fitted model explains the recording, the width fitted inside any one of them carries that model's bias: a
missing effect is taken up by the width as far as their directions overlap, and a fit's own standard error covers
its variance, not that bias. The width is then measured in every plausible model -- the width fitted alone and
beside each second effect that was fitted with it -- and averaged with the models' weights on the events' information
criterion; its uncertainty is the *unconditional* standard error (Burnham & Anderson 2002, *Model Selection and
Multimodel Inference*, ch. 4, the unconditional variance):

    theta_bar = sum_i w_i theta_i
    se(theta_bar) = sum_i w_i sqrt(var_i + (theta_i - theta_bar)^2)
    w_i = exp(-Delta_i / (2 c)) / sum_j exp(-Delta_j / (2 c)),   Delta_i = IC_i - min_j IC_j

IC the BIC on the events (fitting.Problem.ic), c >= 1 the best model's misfit scale (T^2 per dimension over every
view: diagnose.misfit_scale), the quasi-likelihood correction for a model that leaves more than noise (Burnham &
Anderson ch. 6, QAIC): under a misfit the events' IC overstates the evidence between two models by that factor.
A model is plausible when Delta_i / c <= PLAUSIBLE_IC_MARGIN. Pure numpy.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PLAUSIBLE_IC_MARGIN = 10.0   # Delta_i / c beyond which a model takes no part (Burnham & Anderson ch. 2: Delta > 10,
                             # "essentially no support"; Kass & Raftery: "very strong" evidence against it; its weight
                             # would be < exp(-5) = 0.7 % of the best's). Fixed 29 Nov 2026 before any width figure was
                             # looked at.


@dataclass(frozen=True)
class Member:
    """One fitted model that holds the measurand: its value, its own standard error (the fit's), its IC."""
    value: float
    sd: float
    ic: float
    label: str = ""


@dataclass(frozen=True)
class Average:
    """The model average: the value, its unconditional standard error, the members that took part and their
    weights (same order)."""
    value: float
    sd: float
    members: tuple
    weights: tuple


def weights(ics, misfit_scale: float = 1.0, margin: float = PLAUSIBLE_IC_MARGIN) -> np.ndarray:
    """IC weights of models (0 beyond ``margin`` of the best, on Delta / misfit_scale)."""
    ic = np.asarray(ics, dtype=float)
    if ic.size == 0:
        raise ValueError("model average of no model: give at least one fitted model")
    if not misfit_scale >= 1.0:
        raise ValueError(f"misfit scale {misfit_scale}: allowed >= 1 (T^2 per dimension, 1 for a model that holds)")
    d = (ic - np.min(ic)) / misfit_scale
    w = np.where(d <= margin, np.exp(-0.5 * d), 0.0)
    return w / np.sum(w)


def average(members, misfit_scale: float = 1.0, margin: float = PLAUSIBLE_IC_MARGIN) -> Average:
    """The model-averaged value and its unconditional standard error (module docstring) over ``members``."""
    members = [m for m in members if np.isfinite(m.value) and np.isfinite(m.sd) and np.isfinite(m.ic)]
    w = weights([m.ic for m in members], misfit_scale, margin)
    v = np.array([m.value for m in members])
    sd = np.array([m.sd for m in members])
    bar = float(np.sum(w * v))
    se = float(np.sum(w * np.sqrt(sd ** 2 + (v - bar) ** 2)))
    keep = w > 0
    return Average(bar, se, tuple(m for m, k in zip(members, keep) if k), tuple(float(x) for x in w[keep]))
