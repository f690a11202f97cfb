"""The per-event design of a proposal: how each candidate term would change *each* recorded event's vector, not only
their average (docs/workbench.md, "Proposing a missing term").

Three kinds of column, each (E, N) in the diagnosis's weighted prediction space (fitting.Problem's ``event_vecs``):

- **shared** -- a term of the drive's states whose effect is the same on every event: the simulator's secant of the
  event-averaged prediction (proposal.py), repeated for every event;
- **angle-locked** -- a term A sin(k α + φ) of a shaft's angle. An event starts at a different angle each time, so
  its average washes out and a secant at amplitude 0 has no phase column (issue 31). Linear in its sine and cosine
  coefficients, its effect on an event that starts at the angle ψ_e = k α(t_e) is cos ψ_e U + sin ψ_e V: U, V are
  the responses to a torque sin(k Ω τ) and cos(k Ω τ) started at the entry. They are estimated on the simulator by
  regressing each simulated event's change (the term at a small coefficient against none, on common random numbers)
  on the cosine and sine of that event's own simulated angle at its entry. The recording gives its angle up to a
  constant: θ(t) = ∫ω dt from sample 0 (the model's angles start at 0 at sample 0 too), so the recorded events get
  the columns at ψ_e = k θ(t_e), and the fitted phase is the law's phase in that angle;
- **recorded** -- a term the sensor adds to a1 or a2 (a function of the recorded speeds and angles), or a term that
  changes slowly with the time in the record: computed on each recorded event directly (a sensor term does not go
  through the dynamics) or as the shared column of a constant times the event's time in the record.

Plain numpy on the workbench's objects; the simulator is called through fitting.Problem / plant_adapter.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import spectral
from .candidate_terms import coefficient_name
from .events import denoise, event_set, period_means, SEGMENT_SIGNALS, PRE_SAMPLES, POST_SAMPLES

MATCH_SAMPLES = 50        # a simulated event of a set matches the reference set's event within 1 ms (same seed)
MIN_MATCHED = 12          # fewer matched events over the seeds: the angle-locked responses are not estimated


@dataclass(frozen=True)
class AngleResponse:
    """The per-event response to h * sin(k * angle) of one term, per unit coefficient, in the weighted prediction
    space: an event that starts at k * angle = psi changes by cos(psi) U + sin(psi) V (+ W, the part that does not
    depend on the phase). ``n_events``: simulated events the regression used; ``r2``: the share of the simulated
    changes' energy the two columns explain (a term the linear picture does not describe has a low one)."""
    U: np.ndarray
    V: np.ndarray
    W: np.ndarray
    n_events: int
    r2: float


def recorded_angles(signals: dict, sample_period_s: float) -> dict:
    """{"alpha1": θ1(t), "alpha2": θ2(t)} [rad]: the shaft angles integrated from the recorded speeds from sample 0
    (trapezoid; the wheel's from omega2 when recorded, else from omega1 and the angle difference)."""
    out = {}
    dt = float(sample_period_s)

    def integrate(w):
        w = np.asarray(w, dtype=float)
        a = np.empty_like(w)
        a[0] = 0.0
        a[1:] = np.cumsum(0.5 * (w[1:] + w[:-1])) * dt
        return a
    if "omega1" in signals:
        out["alpha1"] = integrate(signals["omega1"])
    if "omega2" in signals:
        out["alpha2"] = integrate(signals["omega2"])
    elif "alpha1" in out and "angle_difference" in signals:
        d = np.asarray(signals["angle_difference"], dtype=float)
        out["alpha2"] = out["alpha1"] - (d - d[0])
    return out


def event_vectors(problem, raw: np.ndarray, dc: np.ndarray, with_noise: bool = True) -> np.ndarray:
    """(E, N): events' vectors in the problem's weighted prediction space (the same as fitting.Problem.event_vecs
    for the recording; for simulated events the model's view of them, its sensor noise floor added to the band
    powers as Problem.pred_of does)."""
    raw = np.asarray(raw, dtype=float)
    e = raw.shape[0]
    den = denoise(raw) * problem.w[None]
    noise = problem.spec_noise if with_noise else None
    spec = spectral.features_from_bands(spectral.band_powers(raw, problem.dt), noise) * problem.ws[None]
    return np.hstack([den.reshape(e, -1), spec, np.asarray(dc, dtype=float) * problem.wdc[None]])


def _match(ref_entries: np.ndarray, entries: np.ndarray) -> list:
    """Pairs (i_ref, i) of events whose entries lie within MATCH_SAMPLES."""
    out = []
    if len(entries) == 0:
        return out
    for i, k in enumerate(ref_entries):
        j = int(np.argmin(np.abs(entries - k)))
        if abs(int(entries[j]) - int(k)) <= MATCH_SAMPLES:
            out.append((i, j))
    return out


ANGLE_SIGNALS = ("alpha1", "alpha2")


def matched_changes(problem, sets: list) -> list:
    """Per parameter set of ``sets`` (each merged over ``problem.base``): (D (n, N) each matched simulated event's change
    of its vector against the reference's same event, {"alpha1", "alpha2": (n,)} the set's own simulated shaft angles
    at that event's entry, and "seed": (n,) the index of the seed it was simulated on). The reference (``problem.base`` alone) and the sets run on the problem's seeds (common random numbers); a
    set's event matches the reference's within MATCH_SAMPLES. A set whose runs give no matched event -> (None, None)."""
    # deferred: the simulator (numba) is loaded only when a proposal or an angle-locked fit simulates
    from . import plant_adapter
    base = dict(problem.base)
    merged = [{**base, **s} for s in sets]
    signals = ("a1", "a2", "omega1", "angle_difference") + ANGLE_SIGNALS
    seg_signals = ("a1", "a2", "omega1", "angle_difference")
    out = [([], {v: [] for v in ANGLE_SIGNALS + ("seed",)}) for _ in sets]
    per_batch = max(1, problem.sets_per_batch())
    refs = []                                        # per seed: (the reference's events, their vectors)
    order = [None] + list(range(len(sets)))          # the reference first, simulated once
    for b in range(0, len(order), per_batch):
        chunk = order[b:b + per_batch]
        runs = plant_adapter.simulate_sets(problem.model, [base if i is None else merged[i] for i in chunk],
                                           problem.seeds, problem.n_samples, conditions=problem.conditions,
                                           signals=signals)
        problem.n_sets_simulated += len(chunk)
        for c, i in enumerate(chunk):
            for j in range(len(problem.seeds)):
                ev = event_set({s: runs[s][c, j] for s in seg_signals}, problem.dt, problem.dc_names)
                if i is None:
                    refs.append((ev, event_vectors(problem, ev.raw, ev.dc) if ev.n_events else None))
                    continue
                ref, ref_vec = refs[j]
                pairs = _match(ref.entries, ev.entries) if ref.n_events else []
                if not pairs:
                    continue
                vec = event_vectors(problem, ev.raw, ev.dc)
                for a, k in pairs:
                    out[i][0].append(vec[k] - ref_vec[a])
                    for v in ANGLE_SIGNALS:
                        out[i][1][v].append(float(runs[v][c, j][int(ev.entries[k])]))
                    out[i][1]["seed"].append(j)
        del runs
    return [(np.asarray(d), {v: np.asarray(x) for v, x in a.items()}) if d else (None, None) for d, a in out]


def angle_responses(problem, terms: list, steps: dict, project) -> dict:
    """{term name: AngleResponse} for the ``terms`` (candidate_terms.Term with ``harmonic`` = (angle, k, "sin")), each
    simulated at its ``steps[name]`` coefficient beside the reference on the problem's seeds (common random numbers),
    with the simulated angles recorded. The responses are in the prediction space (unprojected); ``project`` (the
    map to the selection's whitened coordinates) weighs the regression's share explained."""
    keys = {t.name: f"{t.name}.{_coefficient_key(t)}" for t in terms}
    out = {}
    changes = matched_changes(problem, [{keys[t.name]: float(steps[t.name])} for t in terms])
    for t, (D, a) in zip(terms, changes):
        if D is None or len(D) < MIN_MATCHED:
            continue
        var, k, _ = t.harmonic
        psi = k * a[var]
        D = D / float(steps[t.name])
        X = np.column_stack([np.cos(psi), np.sin(psi), np.ones(len(psi))])
        coef, *_ = np.linalg.lstsq(X, D, rcond=None)
        Dp, fitp = project(D.T).T, project((X @ coef).T).T
        r2 = 1.0 - float(np.sum((Dp - fitp) ** 2)) / max(float(np.sum(Dp ** 2)), 1e-300)
        out[t.name] = AngleResponse(coef[0], coef[1], coef[2], len(D), r2)
    return out


def fourier_basis(theta: np.ndarray, orders) -> np.ndarray:
    """(n, 1 + 2 len(orders)): 1, cos kθ, sin kθ for each order k."""
    theta = np.asarray(theta, dtype=float)
    cols = [np.ones_like(theta)]
    for k in orders:
        cols += [np.cos(k * theta), np.sin(k * theta)]
    return np.column_stack(cols)


def angle_columns(resp: AngleResponse, psi: np.ndarray, project=None) -> np.ndarray:
    """(E, D, 2): per recorded event (its k * angle at entry ``psi``), the columns of c_s sin(kθ) and c_c cos(kθ):
    sin(kθ) -> cos ψ U + sin ψ V; cos(kθ) = sin(kθ + π/2) -> -sin ψ U + cos ψ V (``project`` applied to U and V
    first; without it, in U and V's own space)."""
    U, V = (resp.U, resp.V) if project is None else (project(resp.U), project(resp.V))
    return rotated_columns(U, V, psi)


def rotated_columns(U: np.ndarray, V: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """(E, D, 2): the responses U (to sin θ) and V (to cos θ) of a term locked to an angle, rotated by each event's
    angle ``psi`` at entry: the columns of sin(θ + ψ) = cos ψ sin θ + sin ψ cos θ -> cos ψ U + sin ψ V, and of
    cos(θ + ψ) -> -sin ψ U + cos ψ V."""
    c, s = np.cos(psi)[:, None], np.sin(psi)[:, None]
    col_s = c * U[None] + s * V[None]
    col_c = -s * U[None] + c * V[None]
    return np.stack([col_s, col_c], axis=-1)


def sensor_columns(problem, shapes: dict, project, unprojected: bool = False) -> dict:
    """{name: (E, D)}: the change of each recorded event's projected vector per unit coefficient when the sensor adds
    ``shapes[name]`` = (signal "a1"/"a2", a whole-record array) to that accelerometer. The denoised segment and the
    period means change linearly; the spectral shape (a log of band powers) by its secant at the record's own events
    (the shape scaled to SENSOR_STEP_M_S2). ``unprojected``: {name: ((E, D), (N,) the change of the events' mean
    vector)}."""
    ev = problem.events
    entries = np.asarray(ev.entries)
    n = problem.n_samples
    base = event_vectors(problem, ev.raw, ev.dc, with_noise=False)
    out = {}
    for name, (signal, shape) in shapes.items():
        j = SEGMENT_SIGNALS.index(signal)
        seg = np.zeros_like(ev.raw)
        for i, k in enumerate(entries):
            lo, hi = int(k) - PRE_SAMPLES, int(k) + POST_SAMPLES
            if lo >= 0 and hi <= n:
                seg[i, j] = shape[lo:hi]
        scale = SENSOR_STEP_M_S2 / max(float(np.max(np.abs(seg))), 1e-12)
        dc = np.array(ev.dc, dtype=float, copy=True)
        if signal in problem.dc_names:
            d = period_means({signal: shape, "a1": shape}, entries, entries, (signal,))[:, 0]
            dc[:, problem.dc_names.index(signal)] += scale * d
        change = (event_vectors(problem, ev.raw + scale * seg, dc, with_noise=False) - base) / scale
        pe = np.stack([project(v) for v in change])
        out[name] = (pe, change.mean(axis=0)) if unprojected else pe
    return out


SENSOR_STEP_M_S2 = 0.5     # the secant's size of a sensor column: a small share of a1/a2's event swing (~10-50 m/s^2)


def _coefficient_key(term) -> str:
    return coefficient_name(term)
