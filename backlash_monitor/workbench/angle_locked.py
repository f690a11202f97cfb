"""A user's term locked to a shaft's angle, fitted event by event (issue 31; docs/workbench.md, "A term locked to a
shaft's angle").

A plug-in f(alpha; p) of one shaft's angle (a wheel's cam, an unbalance, a crank, a mesh; plant_adapter.
angle_phase_index finds its phase parameter) changes every backlash event differently, because every event starts
at another angle: its event average washes out, and a fit on the average sees almost nothing (measured: the exact
law of an 8 N*m wheel torque fitted at 7e-20 N*m, 0 % explained). Here it is fitted on the events themselves:

1. **the law's harmonics.** The term is evaluated on numpy over one revolution: f(alpha; p) = a_0(p) +
   sum_k [b_k(p) sin(k alpha) + a_k(p) cos(k alpha)], orders 1..MAX_ORDER (``law_orders``: those the law has).
2. **the response to each harmonic, on the simulator.** A probe c sin(k alpha) per order, and a constant c, in the
   term's balance (``harmonics_file``: a generated plug-in), each at a small amplitude beside the model without it,
   on the same seeds (common random numbers). Each simulated event's change of its vector is regressed on
   cos(k psi), sin(k psi) of that event's own simulated angle at entry psi: the response to sin(k alpha) is
   cos(k psi) U_k + sin(k psi) V_k, to cos(k alpha) = sin(k alpha + pi/2) it is cos(k psi) V_k - sin(k psi) U_k.
3. **lined up with the recording.** The recording gives its angle up to a constant: theta(t) = the integral of its
   speed from sample 0 (event_design.recorded_angles). Event e's predicted change is sum_k b_k(p) (cos k theta_e U_k
   + sin k theta_e V_k) + a_k(p) (cos k theta_e V_k - sin k theta_e U_k) + a_0(p) R_0; p is fitted by bounded least
   squares over every event's vector in the whitened views (the fitted phase is the law's phase in that angle),
   from starts around the phase circle.
4. **a secant, then the whole law.** A torque of the working torque's size changes the crossing it acts on: the
   probes are simulated again at the fitted harmonics' own amplitudes (up to SECANT_ITERATIONS times). Then the law
   itself is simulated at the fitted values (``law_prediction``), at phase_steps phases around the circle (the
   model's events enter at nearly the same angles on every seed: one phase samples only an arc), each simulated
   event's change regressed on the harmonics of its own (shifted) angle and evaluated at the recorded angles. What
   the linear probes miss is a defect; the fit is redone with it taken off the events, and a step is kept only when
   the law simulated at its values lowers the events' error (``law_steps``). The model's per-event prediction is
   that of the whole law. (Measured on a foreign 6 N*m wheel unbalance: linear 6.09 +- 0.03 N*m, the event average
   left outside the band in the view outside the candidates' subspace, 17 -> 53; with the law's defect 5.93 +- 0.34,
   every view inside its limit.)
5. **uncertainty** -- the jackknife over the recorded events (their noise; the events are the independent units)
   and, in quadrature, over the simulated seeds (the responses' regression on the model's own runs).
6. **the model with it.** Its event average is the change of the recorded events at their own angles; its spectral
   shape (a power: phase-free, of second order) is simulated at the fitted values; its evidence (the IC) is the
   events' own likelihood about their per-event predictions, the same formula as the model's without it.

The result is a fitting.FitResult like any refined candidate: the diagnosis ranks, decides and tests it as it does
the others. A term that reads another state besides its angle is not fitted here (its harmonics depend on that
state).
"""
from __future__ import annotations

import copy
import hashlib
import os
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

from backlash_monitor.plant import effects as plant_effects
from backlash_monitor.plant.mathlib import NUMPY_NAMESPACE

from . import candidate_terms, event_design, fitting, plant_adapter
from .proposal import gram

MAX_ORDER = 4              # the largest harmonic of the angle a law is fitted with (per revolution)
ORDER_SHARE = 0.05         # a harmonic of the law whose amplitude is under this share of its largest is left out
GRID = 256                 # points of one revolution the law is evaluated on
SECANT_ITERATIONS = 2      # re-simulations of the responses at the fitted values
SECANT_TOLERANCE = 0.05    # stop when no parameter moves by more than this share of its range
PARSEVAL_SHARE = 0.95      # the law's orders up to MAX_ORDER hold at least this share of its power, else not fitted here
MAX_CONCENTRATION = 0.95   # the events' angles at entry: |mean exp(i k angle)| under this on every order (measured: a
                           # crank pump on the motor, its events at 0.87 on order 1, fitted within 1 uncertainty)
RECORDED_CONCENTRATION = 0.99  # the same for the recorded events: their vectors tell sine from cosine by the responses'
                           # shapes too (U_k, V_k differ), and the jackknife says how well (measured: a crank pump beside
                           # a width change, 16 events at 0.97 on order 1: left to the event average, 0.06 p.u. for 0.25)
LAW_ITERATIONS = 4         # the whole law simulated at the fitted values, the fit redone with its defect (at most)
LAW_TOLERANCE = 1e-3      # stop when no parameter moves by more than this share of its range
SHIFT_TOLERANCE = 1e-3     # a phase step is a shift of the law's angle when the shifted law matches to this share
BESIDE_ITERATIONS = 2      # a pair's shared effect linearised again at the pair's value (at most; each len(x) + 1 sets)
BESIDE_TOLERANCE = 0.5     # stop when the shared effect moved by less than this many of its uncertainties
BESIDE_SEARCH_STEP = 1.5    # a pair's shared effect searched on the whole law at -+ this many of its jackknife spread
PHASE_STARTS = 8           # starts of the fit around the phase circle
REF_HARMONIC = 4.0         # the probes' amplitude: this many of the balance's small step (candidate_terms.BALANCES:
                           # 2 N*m on the wheel, 0.08 p.u. on the motor): small, so that the response is linear in it
                           # (measured: the cam's own law as the probe, at 13 N*m in its first harmonic, fitted 0.13
                           # N*m for 4)


def angle_variable(model, effect) -> str | None:
    """"alpha1" or "alpha2": the shaft angle a candidate's term reads when it reads nothing else but its parameters,
    else None."""
    if getattr(effect, "phase_index", -1) < 0 or not fitting.angle_pair(effect):
        return None
    try:
        args = plant_effects.term_arguments(model.catalogue[effect.effect])
    except (KeyError, ValueError, TypeError, OSError, SyntaxError):
        return None
    names = {q.name for q in effect.parameters}
    angles = [a for a in args if a in plant_adapter.ANGLE_VARIABLES]
    others = [a for a in args if a not in names and a not in plant_adapter.ANGLE_VARIABLES]
    return angles[0] if len(angles) == 1 and not others else None


class Law:
    """A term f(alpha; p) on numpy: its harmonics' coefficients at any parameter vector."""

    def __init__(self, model, effect, var: str):
        cls = model.catalogue[effect.effect]
        ns = dict(NUMPY_NAMESPACE)
        exec(compile(plant_effects.term_source(cls), "<angle-locked term>", "exec"), ns)  # noqa: S102
        self._fn = ns[f"_t_{cls.name}"]
        self._args = plant_effects.term_arguments(cls)
        self._names = [q.name for q in effect.parameters]
        self._var = var
        self._grid = np.arange(GRID) * (2.0 * np.pi / GRID)

    def values(self, x) -> np.ndarray:
        """f over one revolution (GRID points) at the parameter vector x."""
        args = [self._grid if a == self._var else float(x[self._names.index(a)]) for a in self._args]
        return np.broadcast_to(np.asarray(self._fn(*args), dtype=float), self._grid.shape)

    def harmonics(self, x) -> tuple[float, np.ndarray, np.ndarray]:
        """(a_0, b (MAX_ORDER,), a (MAX_ORDER,)): f = a_0 + sum_k b_k sin(k alpha) + a_k cos(k alpha)."""
        c = np.fft.rfft(self.values(x)) / GRID
        return float(c[0].real), -2.0 * c[1:MAX_ORDER + 1].imag, 2.0 * c[1:MAX_ORDER + 1].real


def law_orders(law: Law, x) -> tuple:
    """The harmonics the law has at x: orders whose amplitude is at least ORDER_SHARE of the largest; () when the
    law is not such a sum (its orders up to MAX_ORDER hold less than PARSEVAL_SHARE of its power: a mesh at 20 per
    revolution, a law not periodic in one revolution) or is not finite."""
    v = law.values(x)
    a0, b, a = law.harmonics(x)
    amp = np.hypot(a, b)
    if not (np.all(np.isfinite(v)) and np.all(np.isfinite(amp))) or amp.max() <= 0.0:
        return ()
    power = float(np.mean(v ** 2))
    if a0 ** 2 + 0.5 * float(np.sum(amp ** 2)) < PARSEVAL_SHARE * power:
        return ()
    return tuple(int(k) + 1 for k in np.flatnonzero(amp >= ORDER_SHARE * amp.max()))


def spread_enough(angles: np.ndarray, orders, limit: float = MAX_CONCENTRATION) -> bool:
    """The events' angles at entry cover each order's circle: |mean exp(i k angle)| below ``limit`` (events that all
    enter at one angle -- a pulse locked to the shaft -- cannot tell the harmonics' sine from their cosine)."""
    angles = np.asarray(angles, dtype=float)
    return bool(len(angles) > 0 and all(abs(np.mean(np.exp(1j * k * angles))) < limit for k in orders))


@dataclass(frozen=True)
class Responses:
    """Per order k of ``orders``, in the prediction space per unit amplitude: an event entering at the angle psi
    changes by cos(k psi) U_k + sin(k psi) V_k under sin(k alpha) in the balance; R0 (N,) its change under a constant."""
    orders: tuple
    U: np.ndarray
    V: np.ndarray
    R0: np.ndarray


@dataclass(frozen=True)
class Beside:
    """A shared effect fitted together with an angle-locked term (a pair): its linear model about ``x`` -- the
    prediction there ``shift`` (N,) over the model's, and its Jacobian (N, k), the same on every event."""
    effect: object
    x: np.ndarray
    shift: np.ndarray
    jacobian: np.ndarray


def harmonics_file(balance: str, var: str, orders) -> Path:
    """A plug-in file (in the proposals' cache, named by its content) with the probes of the responses: c * sin(k var)
    for each order and a constant c, in ``balance``."""
    parts = ['"""The probes of an angle-locked term\'s responses (workbench/angle_locked.py), generated."""\n'
             + candidate_terms.HEADER]
    param = "Parameter('coefficient', '-', 0.0, (-1e6, 1e6), 'c')"
    for k in orders:
        arg = var if k == 1 else f"{k} * {var}"
        parts.append(candidate_terms._class_source(f"Probe{k}", probe_name(balance, var, k), balance,
                                                   f"c * sin({arg})", [param], [var, "coefficient"],
                                                   f"coefficient * sin({arg})"))
    parts.append(candidate_terms._class_source("Probe0", probe_name(balance, var, 0), balance, "c", [param],
                                               [var, "coefficient"], f"coefficient * (1.0 + 0.0 * {var})"))
    src = "\n\n".join(parts)
    path = candidate_terms.cache_dir() / f"angle_probes_{hashlib.sha256(src.encode()).hexdigest()[:16]}.py"
    if not path.exists():
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(src)
        os.replace(tmp, path)
    return path


def probe_name(balance: str, var: str, k: int) -> str:
    return f"probe_{balance}_{var}_{'const' if k == 0 else f'sin{k}'}"


def _probe_problem(p, balance, var, orders):
    """A copy of the problem whose model holds the probes (harmonics_file)."""
    q = copy.copy(p)
    q.model = copy.copy(p.model)
    q.model.effect_files = list(p.model.effect_files) + [harmonics_file(balance, var, orders)]
    return q


def _probe_amplitudes(balance, orders, coef=None) -> dict:
    """Per order (0: the constant) the probe's amplitude: REF_HARMONIC of the balance's small step, or the fitted
    harmonic's own amplitude (a secant) when that is larger."""
    step = candidate_terms.BALANCES.get(balance, (None, 1.0))[1]
    out = {}
    for j, k in enumerate((0,) + tuple(orders)):
        a = REF_HARMONIC * step
        if coef is not None:
            size = abs(coef[0]) if k == 0 else float(np.hypot(coef[2 * j - 1], coef[2 * j]))
            a = max(a, size)
        out[k] = a
    return out


def _solve_responses(changes, amps, var, orders, drop_seed=None) -> Responses | None:
    """The responses per unit of each probe (the constant first, then sin k alpha per order): each simulated event's
    change regressed on 1, cos k psi, sin k psi of its own angle at entry -> U_k, V_k (and R0: the constant probe's
    mean change)."""
    n = None
    U, V, R0 = [], [], None
    for (D, a), k in zip(changes, (0,) + tuple(orders)):
        if D is None:
            return None
        keep = np.ones(len(D), bool) if drop_seed is None else np.asarray(a["seed"]) != drop_seed
        if keep.sum() < event_design.MIN_MATCHED:
            return None
        Dk = D[keep] / amps[k]
        if not np.all(np.isfinite(Dk)):
            return None
        if k > 0 and not spread_enough(a[var][keep], (k,)):
            return None
        if k == 0:
            R0 = Dk.mean(axis=0)
            continue
        X = event_design.fourier_basis(a[var][keep] * k, (1,))
        C, *_ = np.linalg.lstsq(X, Dk, rcond=None)
        n = C.shape[1]
        U.append(C[1])
        V.append(C[2])
    return Responses(tuple(orders), np.asarray(U).reshape(len(orders), n), np.asarray(V).reshape(len(orders), n), R0)


def angle_shift(law: Law, x, k_phase: int, phase: float) -> float | None:
    """tau [rad] with f(alpha; x at ``phase``) = f(alpha + tau; x) (modulo the law's own period), or None when that
    phase is not a shift of the law's angle (a phase that also changes the law's shape)."""
    xs = np.array(x, dtype=float)
    xs[k_phase] = phase
    f0, f1 = np.fft.rfft(law.values(x))[1:MAX_ORDER + 1], np.fft.rfft(law.values(xs))[1:MAX_ORDER + 1]
    ks = np.arange(1, MAX_ORDER + 1)
    amp = np.abs(f0)
    if not np.all(np.isfinite(f1)) or amp.max() <= 0.0:
        return None
    g = int(ks[np.argmax(amp >= ORDER_SHARE * amp.max())])          # the lowest order the law has
    scale = float(np.sqrt(np.sum(amp ** 2)))
    for m in range(g):                                                # its rotation gives tau up to 2 pi / g
        tau = (float(np.angle(f1[g - 1] / f0[g - 1])) + 2.0 * np.pi * m) / g
        if np.sqrt(np.sum(np.abs(f1 - f0 * np.exp(1j * ks * tau)) ** 2)) <= SHIFT_TOLERANCE * scale:
            return tau
    return None


def phase_steps(orders) -> int:
    """How many phases the whole law is simulated at: the smallest prime above the largest order over their common
    divisor (at least 3), so that every order's circle is stepped to that many distinct points."""
    g = int(np.gcd.reduce(np.asarray(orders, dtype=int)))
    n = max(3, max(orders) // g + 1)
    while any(n % d == 0 for d in range(2, int(np.sqrt(n)) + 1)):
        n += 1
    return n


def law_prediction(p, effect, law: Law, x, var: str, theta: np.ndarray, orders, extra=None) -> np.ndarray | None:
    """(E, N): each recorded event's change under the whole law at ``x``, at its recorded angle ``theta``, from the
    simulator -- not linearised. The law is simulated at phase_steps phases around the circle (common random numbers):
    the model's events enter at nearly the same angles on every seed (its speeds are the same), so one phase would
    sample the law's effect on an arc, and the recording's events may enter elsewhere (measured: a foreign 6 N*m
    wheel unbalance, its 16 events at 1.7-4.4 rad, the model's at -1.0-1.3 rad). A phase step is a shift of the law's
    angle (angle_shift): each simulated event's change is taken at its angle plus that shift, regressed on the
    harmonics of the law's orders' common divisor up to its largest order, and evaluated at the recorded angles.
    ``extra``: values of other effects simulated with it (a shared effect beside it). None when too few events
    matched or their angles do not cover the circle."""
    k = effect.phase_index
    lo, hi = effect.bounds()
    x = np.asarray(x, dtype=float)
    n = phase_steps(orders)
    sets, shifts = [], []
    for j in range(n):
        ph = lo[k] + (x[k] + 2.0 * np.pi * j / n - lo[k]) % (2.0 * np.pi)
        tau = angle_shift(law, x, k, ph) if ph <= hi[k] else None
        if tau is None:
            continue
        xs = np.array(x)
        xs[k] = ph
        sets.append(plant_adapter.apply_values(effect, xs) | dict(extra or {}))
        shifts.append(tau)
    if not sets:
        return None
    D, psi = [], []
    for tau, (d, a) in zip(shifts, event_design.matched_changes(p, sets)):
        if d is not None:
            D.append(d)
            psi.append(a[var] + tau)
    g = int(np.gcd.reduce(np.asarray(orders, dtype=int)))
    fit_orders = tuple(range(g, max(orders) + 1, g))
    if not D or sum(len(d) for d in D) < max(event_design.MIN_MATCHED, 4 * (1 + 2 * len(fit_orders))):
        return None
    D, psi = np.vstack(D), np.concatenate(psi)
    if not (np.all(np.isfinite(D)) and spread_enough(psi, fit_orders)):
        return None
    C, *_ = np.linalg.lstsq(event_design.fourier_basis(psi, fit_orders), D, rcond=None)
    return event_design.fourier_basis(theta, fit_orders) @ C


def _columns(resp: Responses, theta: np.ndarray) -> np.ndarray:
    """(E, N, 1 + 2K): each recorded event's change per unit a_0, then per order b_k, a_k."""
    const = np.broadcast_to(resp.R0[None, :, None], (len(theta), resp.R0.size, 1))
    return np.concatenate([const] + [event_design.rotated_columns(resp.U[j], resp.V[j], k * theta)   # sin, cos(k a)
                                     for j, k in enumerate(resp.orders)], axis=-1)


def _coefficients(law, x, orders) -> np.ndarray:
    a0, b, a = law.harmonics(x)
    return np.concatenate([[a0]] + [[b[k - 1], a[k - 1]] for k in orders])


def _fit_values(law, orders, A, bvec, x_start, lo, hi, k_phase, multi: bool, coef=None) -> np.ndarray:
    """The parameter vector minimising c(x)' A c(x) - 2 b' c(x) (the events' squared error in the whitened views) in
    the bounds; from ``x_start`` and, with ``multi``, from PHASE_STARTS phases around the circle. ``coef``: c(x) when
    it is not the law's coefficients alone (a shared effect beside it)."""
    coef = coef or (lambda xv: _coefficients(law, xv, orders))
    w, Q = np.linalg.eigh(0.5 * (A + A.T))
    w = np.maximum(w, 1e-12 * max(float(w.max()), 1e-300))
    L = Q * np.sqrt(w)[None]                                          # A = L L'
    target = (Q / np.sqrt(w)[None]).T @ bvec                           # L^-1 b

    def res(x):
        return L.T @ coef(x) - target
    starts = [np.clip(x_start, lo, hi)]
    if multi:
        for ph in np.linspace(-np.pi, np.pi, PHASE_STARTS, endpoint=False):
            v = np.array(starts[0])
            v[k_phase] = float(np.clip(ph, lo[k_phase], hi[k_phase]))
            starts.append(v)
    best = None
    span = np.maximum(hi - lo, 1e-12)
    for x0 in starts:
        r = least_squares(res, np.clip(x0, lo + 1e-9 * span, hi - 1e-9 * span), bounds=(lo, np.maximum(hi, lo + span)),
                          x_scale=span, method="trf")
        if best is None or r.cost < best.cost:
            best = r
    return best.x


def law_steps(x, predict, refit, error, span, iterations: int = LAW_ITERATIONS):
    """Defect correction of a linearised fit: ``predict(x)`` the whole law's per-event prediction (None: not
    available), ``error(P)`` the events' error about it, ``refit(x, P)`` the linear fit redone with the defect at x
    taken off. A step is kept only when it lowers the error (the law simulated at the new values), else it is halved;
    at most ``iterations`` predictions, until no parameter moves by LAW_TOLERANCE of ``span``. -> (x, P) of the lowest error
    seen, or None when the law cannot be predicted at the start."""
    best = None
    x = np.asarray(x, dtype=float)
    for _ in range(iterations):
        P = predict(x)
        if P is None:
            break
        err = error(P)
        if best is not None and err >= best[2]:
            x = best[0] + 0.5 * (x - best[0])          # the step overshot (or went the wrong way): half of it
        else:
            best = (x, P, err)
            x = np.asarray(refit(x, P), dtype=float)
        if np.max(np.abs(x - best[0]) / np.maximum(span, 1e-12)) <= LAW_TOLERANCE:
            break
    return None if best is None else best[:2]


def whole_law_search(x, P, err, predict, error, indices, h, lo, hi):
    """A parabola's step on the whole law along each parameter of ``indices``: its error (``error(predict(x))``) at
    x -+ h[i], and at the vertex of the parabola through the three (within 2 h[i]); the lowest error seen is kept.
    -> (x, P, err): the inputs themselves when no point lowered the error (or h[i] is 0)."""
    best = (np.asarray(x, dtype=float), P, float(err))
    for i in indices:
        if not h[i] > 0.0:
            continue
        x0, e0 = best[0], best[2]
        tried = []
        for s in (-1.0, 1.0):
            xs = np.array(x0)
            xs[i] = float(np.clip(x0[i] + s * h[i], lo[i], hi[i]))
            if xs[i] != x0[i]:
                Ps = predict(xs)
                if Ps is not None:
                    tried.append((xs, Ps, error(Ps)))
        if len(tried) == 2:
            (xm, _, em), (xp, _, ep) = tried
            dm, dp = xm[i] - x0[i], xp[i] - x0[i]
            # the parabola through (dm, em), (0, e0), (dp, ep): its vertex, when it opens upwards
            curv = ((ep - e0) / dp - (em - e0) / dm) / (dp - dm)
            slope = (ep - e0) / dp - curv * dp
            if curv > 0.0:
                xv = np.array(x0)
                xv[i] = float(np.clip(x0[i] - slope / (2.0 * curv), max(lo[i], x0[i] - 2.0 * h[i]),
                                      min(hi[i], x0[i] + 2.0 * h[i])))
                Pv = predict(xv)
                if Pv is not None:
                    tried.append((xv, Pv, error(Pv)))
        for t in tried:
            if t[2] < best[2]:
                best = t
    return best


def _jackknife(rows: np.ndarray) -> np.ndarray:
    n = len(rows)
    return np.sqrt((n - 1) / n * np.sum((rows - rows.mean(axis=0)) ** 2, axis=0))


def _unwrap_phase(rows: np.ndarray, k: int, ref: float) -> np.ndarray:
    rows = np.array(rows, dtype=float)
    rows[:, k] = ref + fitting._wrap(rows[:, k] - ref)
    return rows


def fit(run, effect, beside: Beside | None = None) -> fitting.FitResult | None:
    """:func:`fit_event_by_event`, or None when a user's term does not run on numpy arrays, gives values that are not
    finite, or its responses cannot be solved (its candidate is then refined on the event average as any other)."""
    try:
        return fit_event_by_event(run, effect, beside)
    except (TypeError, ValueError, ArithmeticError, NameError, AttributeError, np.linalg.LinAlgError):
        return None


def fit_pair(run, a: str, b: str) -> fitting.FitResult | None:
    """The pair (a, b) when exactly one of them is a term locked to a shaft's angle that the diagnosis fitted event by
    event: that term fitted event by event beside the other, a shared effect, linearised at its single-effect fit when
    there is one (else at the model's values, on its screening secant). Its parameters in the order a's, b's (as
    pairs.combined holds them); its evidence the events' own likelihood about their per-event predictions, as the
    term's alone (comparable with it); the shared effect's value then searched on the whole law (whole_law_search).
    None when it does not apply (the pair is then refined on the event average)."""
    locked = [n for n in (a, b) if n in run.event_fits]
    if len(locked) != 1:
        return None
    name = locked[0]
    other = b if name == a else a
    eff = run.by_name[other]
    single = next((f for f in run.fits if f.effect == other and f.jacobian is not None and f.pred is not None), None)
    if single is not None:
        beside = Beside(eff, np.asarray(single.values, float), single.pred - run.base_pred, single.jacobian)
    else:
        beside = Beside(eff, eff.default_vector(), np.zeros_like(run.base_pred), run.screening[other].jacobian)
    nl = len(run.by_name[name].parameters)
    f = fit(run, run.by_name[name], beside)
    # the shared effect linearised again where the pair put it: a width moves every crossing's timing, and its
    # linearisation at its single fit is off at the pair's value (measured, 29 Nov: a crank pump beside a width
    # grown 4.0 -> 5.0 mm, the pair at +0.885 mm and 0.17 p.u. linearised at the single fit's +0.784 mm)
    for _ in range(BESIDE_ITERATIONS):
        if f is None or other not in run.screening:
            break
        xb = np.asarray(f.values[nl:], float)
        moved = np.abs(xb - beside.x)
        if np.all(moved <= np.maximum(BESIDE_TOLERANCE * np.abs(np.asarray(f.uncertainty[nl:], float)), 1e-300)):
            break
        beside = relinearised(run, eff, xb)
        f_next = fit(run, run.by_name[name], beside)
        if f_next is None:
            break
        f = f_next
    if f is None or name == a:
        return f
    perm = np.r_[np.arange(nl, len(f.values)), np.arange(nl)]
    return replace(f, effect=f"{other}+{name}", parameter_names=[f.parameter_names[i] for i in perm],
                   units=[f.units[i] for i in perm], values=f.values[perm], uncertainty=f.uncertainty[perm],
                   nominal=f.nominal[perm], bounds=(f.bounds[0][perm], f.bounds[1][perm]),
                   jacobian=f.jacobian[:, perm], balance=eff.balance,
                   groups=tuple((len(f.values) - nl + a0, len(f.values) - nl + b0, z) for a0, b0, z in f.groups))


def relinearised(run, eff, x: np.ndarray) -> Beside:
    """The shared effect ``eff``'s linear model about ``x``: its prediction there and forward differences of the
    screening's half steps (as fitting.refine takes them), simulated on the diagnosis's seeds (len(x) + 1 sets)."""
    lo, hi = eff.bounds()
    h_abs = np.abs(run.screening[eff.name].step) * 0.5
    steps = fitting._fd_steps(x, h_abs, hi)
    ens = run.problem.evaluate(fitting._sets_for(eff, [x] + steps))
    p0 = run.problem.pred_of(ens, 0)
    J = fitting.forward_differences(p0, [run.problem.pred_of(ens, i + 1) for i in range(len(steps))], x, steps)
    return Beside(eff, np.asarray(x, float), p0 - run.base_pred, J)


def fit_event_by_event(run, effect, beside: Beside | None = None) -> fitting.FitResult | None:
    """The event-by-event fit of ``effect`` (a CandidateEffect locked to one shaft's angle: angle_variable) on the
    diagnosis ``run``; None when it does not apply (not such a term, no recorded speed, too few events, a law with no
    harmonic at its reference). ``beside``: a shared effect fitted together with it (its parameters after the
    term's; pairs.py's second effect)."""
    p = run.problem
    var = angle_variable(run.model, effect)
    if var is None or p.n_events < 6:
        return None
    angles = event_design.recorded_angles(run.meas.signals, p.dt)
    if var not in angles:
        return None
    law = Law(run.model, effect, var)
    theta = angles[var][np.asarray(p.events.entries)]
    k = effect.phase_index
    x0 = effect.default_vector()
    lo, hi = effect.bounds()
    x_start = x0 + np.where(np.arange(len(x0)) == k, 0.0, fitting._step(effect))   # 15 % into the range
    orders = law_orders(law, x_start)
    nl = len(x0)
    if beside is not None:
        x0 = np.concatenate([x0, beside.effect.default_vector()])
        lo = np.concatenate([lo, beside.effect.bounds()[0]])
        hi = np.concatenate([hi, beside.effect.bounds()[1]])
        x_start = np.concatenate([x_start, beside.x])

    def coef(xv):
        c = _coefficients(law, xv[:nl], orders)
        return c if beside is None else np.concatenate([c, xv[nl:] - beside.x])

    def joint(Gl):
        """(E, N, M [+ k_S]): the law's columns, and the shared effect's Jacobian the same on every event."""
        if beside is None:
            return Gl
        return np.concatenate([Gl, np.broadcast_to(beside.jacobian[None], (Gl.shape[0],) + beside.jacobian.shape)],
                              axis=-1)

    def extra(xv):
        return {} if beside is None else plant_adapter.apply_values(beside.effect, xv[nl:])
    if not orders or not spread_enough(theta, orders, RECORDED_CONCENTRATION):
        return None
    base = run.base_pred
    shift = 0.0 if beside is None else beside.shift                    # the shared effect at its expansion point
    Y0 = p.project((p.event_vecs - base[None]).T).T                    # (E, D)
    Y = Y0 - (0.0 if beside is None else p.project(shift)[None])
    q = _probe_problem(p, effect.balance, var, orders)
    q_before = q.n_sets_simulated
    n_before = p.n_sets_simulated
    probes = (0,) + tuple(orders)
    keys = {o: f"{probe_name(effect.balance, var, o)}.coefficient" for o in probes}
    amps = _probe_amplitudes(effect.balance, orders)
    x = None
    for it in range(1 + SECANT_ITERATIONS):
        changes = event_design.matched_changes(q, [{keys[o]: amps[o]} for o in probes])
        resp_new = _solve_responses(changes, amps, var, orders)
        if resp_new is None:
            break
        resp, used = resp_new, (changes, dict(amps))
        G = joint(_columns(resp, theta))                               # (E, N, M)
        Gp = np.stack([p.project(G[..., c].T).T for c in range(G.shape[-1])], axis=-1)
        GG, Gy, _ = gram(Gp, Y)
        A, bvec = GG.sum(axis=0), Gy.sum(axis=0)
        x_new = _fit_values(law, orders, A, bvec, x_start if x is None else x, lo, hi, k, multi=x is None, coef=coef)
        moved = x is None or np.max(np.abs(x_new - x) / np.maximum(hi - lo, 1e-12)) > SECANT_TOLERANCE
        x = x_new
        if not moved or it == SECANT_ITERATIONS:
            break
        # the next responses at the fitted harmonics' own amplitudes (a secant)
        new_amps = _probe_amplitudes(effect.balance, orders, _coefficients(law, x[:nl], orders))
        if all(abs(new_amps[o] - amps[o]) <= SECANT_TOLERANCE * amps[o] for o in amps):
            break
        amps = new_amps
    if x is None:
        return None
    # the law as a whole at the fitted values, simulated (law_prediction): what the linear probes miss (a torque of
    # the working torque's size, its harmonics acting together) is a defect, and the fit is redone with it taken off
    # the events (law_steps: a step is kept only when the law simulated at its values lowers the events' error)
    def defect_of(xv, P):
        return p.project((P - shift - G @ coef(xv)).T).T

    def refit(xv, P):
        GGd, Gyd, _ = gram(Gp, Y - defect_of(xv, P))
        return _fit_values(law, orders, GGd.sum(axis=0), Gyd.sum(axis=0), xv, lo, hi, k, multi=False, coef=coef)

    def predict(xv):
        return law_prediction(p, effect, law, xv[:nl], var, theta, orders, extra(xv))

    def error(P):
        return float(np.sum((Y0 - p.project(P.T).T) ** 2))
    stepped = law_steps(x, predict, refit, error, hi - lo)
    if stepped is None:
        per_event, defect = shift + G @ coef(x), np.zeros_like(Y)    # the linear prediction, lined up
    else:
        x, per_event = stepped
        defect = defect_of(x, per_event)
        GG, Gy, _ = gram(Gp, Y - defect)
        A, bvec = GG.sum(axis=0), Gy.sum(axis=0)
        if beside is not None:
            # the shared effect searched on the whole law itself: its linear column (even linearised again where the
            # pair put it, with or without the term on) leaves the defect correction's fixed point off the whole
            # law's least error (measured: a crank pump beside a width grown 4.0 -> 5.0 mm stopped at +0.903 mm,
            # error 1314.7, the whole law's least error along the width at +0.997 mm, 1276.4)
            loo = [_fit_values(law, orders, A - GG[i], bvec - Gy[i], x, lo, hi, k, multi=False, coef=coef)
                   for i in range(len(GG))]
            h = np.zeros_like(x)
            h[nl:] = BESIDE_SEARCH_STEP * _jackknife(np.array(loo))[nl:]
            x_s, per_s, _ = whole_law_search(x, per_event, error(per_event), predict, error, range(nl, len(x)), h,
                                             lo, hi)
            if per_s is not per_event:
                x, per_event = x_s, per_s
                defect = defect_of(x, per_event)
                GG, Gy, _ = gram(Gp, Y - defect)
                A, bvec = GG.sum(axis=0), Gy.sum(axis=0)
    # the uncertainty: leave-one-event-out and leave-one-seed-out refits from the fitted values
    loo = [_fit_values(law, orders, A - GG[i], bvec - Gy[i], x, lo, hi, k, multi=False, coef=coef)
           for i in range(len(GG))]

    def size(xv):                                     # the law's harmonics' size (its balance's unit)
        return float(np.sqrt(np.sum(_coefficients(law, xv[:nl], orders) ** 2)))
    size_spread = _jackknife(np.array([[size(v)] for v in loo]))[0]
    spread = _jackknife(_unwrap_phase(np.array(loo), k, x[k]))
    by_seed = []
    for s in range(len(p.seeds)):
        rs = _solve_responses(used[0], used[1], var, orders, drop_seed=s)
        if rs is None:
            continue
        Gs = joint(_columns(rs, theta))
        GGs, Gys, _ = gram(np.stack([p.project(Gs[..., c].T).T for c in range(Gs.shape[-1])], axis=-1),
                           Y - defect)
        by_seed.append(_fit_values(law, orders, GGs.sum(axis=0), Gys.sum(axis=0), x, lo, hi, k, multi=False,
                                   coef=coef))
    if len(by_seed) >= 2:
        spread = np.hypot(spread, _jackknife(_unwrap_phase(np.array(by_seed), k, x[k])))
        size_spread = float(np.hypot(size_spread, _jackknife(np.array([[size(v)] for v in by_seed]))[0]))
    size_z = size(x) / max(size_spread, 1e-300)
    # the model after: the recorded events' own change on average; the spectral shape simulated at the fitted values
    ens = p.evaluate([plant_adapter.apply_values(effect, x[:nl]) | extra(x)])
    pred = base + per_event.mean(axis=0)
    sp = p.spectral_slice
    pred[sp] = p.pred_of(ens, 0)[sp]
    explained = p.explained_share(p.fit_residual(pred), p.fit_residual(base))
    ic = _event_ic(p, base[None] + per_event, len(x0))
    # the Jacobian (prediction space) at the fitted values, by differences of the law's coefficients
    c_fit = coef(x)
    J = np.zeros((len(base), len(x0)))
    for i in range(len(x0)):
        hstep = 1e-4 * max(hi[i] - lo[i], 1e-12)
        xs = np.array(x)
        xs[i] = xs[i] + hstep if xs[i] + hstep <= hi[i] else xs[i] - hstep
        J[:, i] = (G @ ((coef(xs) - c_fit) / (xs[i] - x[i]))).mean(axis=0)
    p.n_sets_simulated += q.n_sets_simulated - q_before        # the probes' runs count in the diagnosis's total
    tol = fitting.AT_BOUND_FRACTION * (hi - lo)
    at_bound = bool(np.any([(x[i] - lo[i] <= tol[i] and abs(x0[i] - lo[i]) > tol[i])
                            or (hi[i] - x[i] <= tol[i] and abs(hi[i] - x0[i]) > tol[i])
                            for i in range(len(x0)) if i != k]))
    members = [effect] if beside is None else [effect, beside.effect]
    name = effect.name if beside is None else f"{effect.name}+{beside.effect.name}"
    return fitting.FitResult(name, [q.name for e in members for q in e.parameters],
                             [q.unit for e in members for q in e.parameters],
                             x, spread, x0, (lo, hi), explained, ic - run.base_ic, ic, ens.mean_denoised(0), explained,
                             p.n_sets_simulated - n_before, effect.balance, effect.description, at_bound,
                             model_mean_raw=ens.mean_raw(0), pred=pred, jacobian=J,
                             fixed={k: v for e in members for k, v in getattr(e, "fixed_values", {}).items()},
                             groups=((0, nl, float(size_z)),))


def _event_ic(p, per_event_pred: np.ndarray, k: int) -> float:
    """fitting.Problem.ic with a prediction per event (E, N): the events' likelihood in the whitened candidate
    subspace about their own predictions (the same formula as the model's IC about its one mean)."""
    d = p.event_vecs - per_event_pred
    e = d.shape[0]
    z = d @ p.views.basis
    return float(e * np.sum(np.log(np.mean(z ** 2, axis=0))) + k * np.log(e))
