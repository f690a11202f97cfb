"""The consistency test: is a recording's evidence inside the model's noise band, allowing for the model-form
tolerance? The same test serves ``diagnose`` (before and after an update) and the live model watch.

Evidence (a prediction vector, fitting.Problem): the weighted denoised event average and the raw events' spectral
shape, and the record's mean acceleration (workbench/record_mean.py). The test looks at it in *views*:
- ``event_average``: the whitened candidates' subspace of the event average (the q <= 12 directions in which the
  catalogue can move it, whitened by the covariance of the model's own events);
- ``spectral_shape``: the same for the raw events' spectral shape (<= 6 of its 10 features);
- ``record_mean``: the record's mean a1, a2 (a constant sensor offset shows here and nowhere else);
- ``outside``: the event average in the strongest directions of the model's own noise *outside* the subspace.
Per view, T^2 = z' (c I + T)^-1 z with z the whitened residual of the measured mean, c = (1 + 1/K)/E the noise of
an E-event mean against a K-seed model mean (the events are the independent units), and T the model-form tolerance
in that view (tolerance.py: the spread of the model's nominal parameters, linearised); the limit is chi^2_q's
1 % point. The model is *inconsistent* when a view exceeds its limit or the event-average residual exceeds
INCONSISTENT_RATIO times the noise floor.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from scipy.special import gammaincinv     # chi^2's ppf as scipy.stats.chi2.ppf computes it (scipy.stats: ~1 s to import)
from scipy.special import fdtri, fdtrc

from . import tolerance
from .events import dc_block_deviations, denoise

SUBSPACE_ENERGY = 0.99       # share of the candidates' reach the subspace keeps
SUBSPACE_MAX_DIM = 12
SPECTRAL_MAX_DIM = 6         # of the spectral-shape block's 10 features (workbench/spectral.py)
COMPLEMENT_DIM = 20          # noise directions outside the candidates' subspace
LIMIT_P = 0.99               # the views' limits: chi^2 1 % points
INCONSISTENT_RATIO = 2.0     # event-average residual / noise floor above which the model is inconsistent (clean
                             # 4 s recordings measured up to 1.78; the views' T^2 are the finer gate)
OUTSIDE = "outside"


@dataclass(frozen=True)
class ViewResult:
    name: str
    t2: float
    limit: float
    dimension: int
    t2_without_tolerance: float

    @property
    def outside_band(self) -> bool:
        return self.t2 > self.limit

    def to_json(self) -> dict:
        return {"T2": self.t2, "T2_limit_p01": self.limit, "dimension": self.dimension,
                "T2_without_tolerance": self.t2_without_tolerance, "outside_band": self.outside_band}


@dataclass(frozen=True)
class ConsistencyResult:
    views: dict                   # name -> ViewResult (event_average, spectral_shape, record_mean, outside)
    residual_over_noise: float    # rms over a1, a2 of the weighted event-average residual

    @property
    def consistent(self) -> bool:
        return self.residual_over_noise <= INCONSISTENT_RATIO and not any(
            v.outside_band for n, v in self.views.items() if n != OUTSIDE)

    @property
    def consistent_everywhere(self) -> bool:
        """Also outside the candidates' subspace."""
        return self.consistent and not self.views[OUTSIDE].outside_band

    def to_json(self) -> dict:
        return {"consistent": self.consistent, "residual_over_noise": self.residual_over_noise,
                "views": {n: v.to_json() for n, v in self.views.items()}}


def model_event_vectors(comp, problem) -> np.ndarray:
    """The model's own events (all seeds of the ensemble) as prediction-space vectors minus the model's
    prediction: (K*E, N), the sample of the noise the whitening and the views' limits are taken from. The
    record-mean coordinates are the model's own per-period means (record_mean.py)."""
    base = problem.pred_of(comp.ensemble, 0)
    out = []
    for k, raw in enumerate(comp.ensemble.per_event):
        v = np.hstack([(denoise(raw) * comp.weights[None, :, None]).reshape(raw.shape[0], -1),
                       comp.model_event_spec[k] * problem.ws[None], np.zeros((raw.shape[0], problem.wdc.size))])
        v = v - base[None]
        # the record-mean coordinates: block means (events.dc_block_deviations), not single periods
        v[:, problem.dc_slice] = dc_block_deviations(comp.ensemble.dc_samples(k)) * problem.wdc[None]
        out.append(v)
    return np.vstack(out)


def candidate_basis(jacobian_spans: list, problem) -> list:
    """Orthonormal bases of the directions the candidates move the prediction in, per block: SVD of their
    Jacobian columns, each scaled to unit length in that block (every candidate parameter counts alike: scaled by
    its fit range instead, one wide range -- a sensor offset of +-10 m/s^2 moves a2 by 20 noise floors per
    m/s^2 -- took 99 % of the energy and left the event average 2 directions), keeping SUBSPACE_ENERGY of each
    block's energy. ``jacobian_spans``: (N, k) each. -> [(name, (N, q_block))]."""
    s_mat = np.hstack(jacobian_spans)
    out = []
    for name, sl, max_dim in (("event_average", problem.event_slice, SUBSPACE_MAX_DIM),
                              ("spectral_shape", problem.spectral_slice, SPECTRAL_MAX_DIM),
                              ("record_mean", problem.dc_slice, problem.dc_slice.stop - problem.dc_slice.start)):
        part = s_mat[sl]
        norms = np.linalg.norm(part, axis=0)
        keep = norms > 1e-9 * max(float(norms.max()), 1e-300) if part.size else np.zeros(0, bool)
        basis = np.zeros((s_mat.shape[0], 0))
        if part.shape[0] > 0 and np.any(keep):
            u, sv, _ = np.linalg.svd(part[:, keep] / norms[keep][None, :], full_matrices=False)
            energy = np.cumsum(sv ** 2) / max(np.sum(sv ** 2), 1e-300)
            q = int(min(max_dim, part.shape[0], np.searchsorted(energy, SUBSPACE_ENERGY) + 1))
            basis = np.zeros((s_mat.shape[0], q))
            basis[sl] = u[:, :q]
        out.append((name, basis))
    return out


def whiten(blocks, z_all, more_rows: dict | None = None) -> tuple[np.ndarray, list]:
    """Per block: basis @ C^(-1/2), C the covariance of the model's own events (``z_all``: (K*E, N)) in that
    block's subspace: the projected event residuals then have unit variance per direction. ``more_rows``: per block
    name, (column slice, rows (M, slice width)): more samples of the model's noise, zero outside that slice, that only
    that block's covariance is estimated from too (the watch's record-mean seeds, reference.RECORD_MEAN_SEEDS).
    -> (N, q) basis, [(block name, column slice)]."""
    cols, names, q0 = [], [], 0
    for name, basis in blocks:
        if basis.shape[1] == 0:
            continue
        z = z_all @ basis
        if more_rows and name in more_rows:
            part, rows = more_rows[name]
            z = np.vstack([z, rows @ basis[part]])
        cov = np.cov(z, rowvar=False).reshape(basis.shape[1], basis.shape[1])
        vals, vecs = np.linalg.eigh(cov)
        vals = np.maximum(vals, 1e-12 * max(vals.max(), 1e-300))
        cols.append(basis @ (vecs / np.sqrt(vals)[None, :]) @ vecs.T)
        names.append((name, slice(q0, q0 + basis.shape[1])))
        q0 += basis.shape[1]
    return np.hstack(cols), names


def complement_basis(z_all, n_event_coords: int, basis: np.ndarray, blocks) -> np.ndarray:
    """The COMPLEMENT_DIM strongest directions of the model's own event noise in the event average that lie
    outside the candidates' subspace (the first of ``blocks``' columns of ``basis``), whitened: (n_event_coords, P)."""
    ne = n_event_coords
    z = z_all[:, :ne]
    q, _ = np.linalg.qr(basis[:ne, blocks[0][1]])
    zc = z - (z @ q) @ q.T
    _, sv, vt = np.linalg.svd(zc, full_matrices=False)
    p = min(COMPLEMENT_DIM, len(sv))
    return vt[:p].T / np.maximum(sv[:p] / np.sqrt(max(z.shape[0] - 1, 1)), 1e-300)[None]


def fit_basis(views: "ConsistencyViews") -> np.ndarray:
    """(N, q + P): the fits' metric -- every view's whitened basis with its model-form tolerance folded in
    (basis_b (I + Z_b Z_b' / c)^(-1/2): generalised least squares with the noise and the tolerance, so a fit does not
    bend to explain what the tolerance allows) and the complement's directions."""
    c = noise_scale(views.n_events, views.n_seeds)
    cols = []
    for _, sl in views.blocks:
        b = views.basis[:, sl]
        z = views.tolerance_z[sl]
        if not np.any(z):
            cols.append(b)
            continue
        vals, vecs = np.linalg.eigh(np.eye(z.shape[0]) + z @ z.T / c)
        cols.append(b @ (vecs / np.sqrt(vals)[None, :]) @ vecs.T)
    outside = np.zeros((views.basis.shape[0], views.complement.shape[1]))
    outside[views.event_slice] = views.complement
    return np.hstack(cols + [outside])


@dataclass(frozen=True, eq=False)
class ConsistencyViews:
    """The views the consistency test looks in, for one evidence layout (fitting.Problem's prediction vector: event
    average, spectral shape, record mean) and one number of events E against K model seeds: built once, whole, from a
    screening (:meth:`from_screening`). diagnose builds it per recording (screen_step), the model watch's reference per
    window's noise floor and E (reference.WindowReference). N: the prediction vector's length; q: the views'
    directions; P: the complement's; m: the model-form tolerance's."""
    candidate_directions: tuple   # ((block name, (N, q_b)), ...): the candidates' orthonormal directions per block,
                                  # before whitening (candidate_basis; a block without any: q_b 0)
    basis: np.ndarray             # (N, q): the whitened directions the views look in (whiten)
    blocks: tuple                 # ((view name, slice of basis' columns), ...): event_average, spectral_shape,
                                  # record_mean (those with directions)
    complement: np.ndarray        # (n_event_coords, P): whitened noise directions outside the subspace
    tolerance_directions: np.ndarray   # (N, m): the model-form tolerance in the prediction space (tolerance.py)
    n_events: int                 # E: the evidence's onset events (the noise of its mean)
    n_seeds: int                  # K: the model mean's noise seeds
    n_event_coords: int           # the event average's share of the prediction vector (its first coordinates)

    @classmethod
    def from_screening(cls, layout, jacobians: dict, candidates: dict, model_events: np.ndarray,
                       more_rows: dict | None = None, complement: np.ndarray | None = None) -> "ConsistencyViews":
        """The views of a screening: the candidates' subspace spanned by every screened candidate's Jacobian over its
        fit range (candidate_basis), whitened by the model's own events (whiten), the complement's noise directions
        (complement_basis) and the model-form tolerance from the screening's Jacobians (tolerance.directions).
        ``layout``: the prediction vector's slices and weights (fitting.Problem, reference.WindowReference);
        ``jacobians``: the screening's, {candidate name: (N, k) d prediction / d parameter} (fitting.Linearisation's
        jacobian); ``candidates``: {name: plant_adapter.CandidateEffect}
        (their fit ranges and tolerances); ``model_events``: (K*E, N) the model's own events less its prediction
        (model_event_vectors); ``more_rows``: whiten's; ``complement``: the complement when the caller has it for
        this layout's number of events (the reference computes it once per E)."""
        spans = []
        for name, jacobian in jacobians.items():
            lo, hi = candidates[name].bounds()
            spans.append(jacobian * (hi - lo)[None, :])
        directions = candidate_basis(spans, layout)
        basis, blocks = whiten(directions, model_events, more_rows)
        if complement is None:
            complement = complement_basis(model_events, layout.n_event_coords, basis, blocks)
        return cls(tuple(directions), basis, tuple(blocks), complement,
                   tolerance.directions(layout, jacobians, candidates), int(layout.n_events), int(layout.n_seeds),
                   int(layout.n_event_coords))

    @cached_property
    def tolerance_z(self) -> np.ndarray:
        """(q, m): the model-form tolerance in the basis' coordinates."""
        return self.basis.T @ self.tolerance_directions

    @cached_property
    def fit_basis(self) -> np.ndarray:
        """(N, q + P): the fits' metric (fit_basis; fitting.Problem.project)."""
        return fit_basis(self)

    @property
    def event_slice(self) -> slice:
        return slice(0, self.n_event_coords)

    def event_part(self, r) -> np.ndarray:
        return r[:self.n_event_coords]


def predictive_t2_isf(p: float, dimension: int, dof: int) -> float:
    """The T^2 a view exceeds with probability ``p`` when its whitening is *estimated* from the model's own events
    (``dof`` degrees of freedom of that covariance) and the recording is the model's: Hotelling's predictive law,
    T^2 ~ q dof / (dof - q + 1) F(q, dof - q + 1) -- not chi^2_q, whose far tail is 1e2-1e4 times too thin at
    dof 95 (docs/model_watch.md). ``dof`` <= q: no such law (inf)."""
    q, d2 = int(dimension), int(dof) - int(dimension) + 1
    if d2 < 1:
        return math.inf
    return float(q * dof / d2 * fdtri(q, d2, 1.0 - p))


def predictive_p(t2: float, dimension: int, dof: int) -> float:
    """The chance of a T^2 at least this large under :func:`predictive_t2_isf`'s law."""
    q, d2 = int(dimension), int(dof) - int(dimension) + 1
    if d2 < 1:
        return 1.0
    return float(fdtrc(q, d2, max(float(t2), 0.0) * d2 / (q * dof)))


@lru_cache(maxsize=None)
def chi2_limit(dimension: int) -> float:
    """A view's limit: chi^2's LIMIT_P point at its dimension (cached: stats.chi2.ppf costs ~0.6 ms a call, four
    per test -- 7 % of the live watch's work when computed every time)."""
    return float(2.0 * gammaincinv(dimension / 2.0, LIMIT_P))


def noise_scale(n_events: int, n_seeds: int) -> float:
    """Variance, per whitened direction, of an E-event mean against a K-seed model mean (units: one event)."""
    return 1.0 / n_events + 1.0 / (n_events * n_seeds)


def _t2(z: np.ndarray, c: float, tol: np.ndarray | None) -> float:
    if tol is None or tol.size == 0:
        return float(np.sum(z ** 2) / c)
    cov = c * np.eye(z.size) + tol @ tol.T
    return float(z @ np.linalg.solve(cov, z))


def clipped_mean(u: np.ndarray, radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Huber's bounded-influence mean of per-event whitened deviations ``u`` (E, q): every event whose deviation
    is longer than ``radius`` counts with its direction at that length. -> (the mean (q,), each event's weight
    min(1, radius / |u_i|) (E,)). Events inside the radius count as they are (then it is the plain mean)."""
    norms = np.sqrt(np.sum(u * u, axis=1))
    weights = np.minimum(1.0, radius / np.maximum(norms, 1e-300))
    return (weights[:, None] * u).mean(axis=0), weights


def test(views: ConsistencyViews, r: np.ndarray, with_tolerance: bool = True,
         event_residuals: np.ndarray | None = None, clip_radius: dict | None = None,
         event_coords: dict | None = None) -> ConsistencyResult:
    """The consistency of the weighted residual ``r`` (prediction space) in every view of ``views``.

    ``event_residuals`` (E, N), whose mean is ``r``, with ``clip_radius`` {view: radius}: in those views the
    residual is :func:`clipped_mean` of the events' whitened deviations instead of their mean (the live model
    watch: one odd event must not decide a window; docs/model_watch.md), and the event-average residual ratio is
    taken with the event-average view's weights. Without them (diagnose) the plain mean. ``event_coords``: {view:
    (E, q) event_residuals @ that view's basis columns} when the caller has projected them already (the same
    product, not made twice)."""
    c = noise_scale(views.n_events, views.n_seeds)
    z = views.basis.T @ r
    event_weights = None
    if event_residuals is not None and clip_radius:
        for name, sl in views.blocks:
            if name in clip_radius:
                u = event_coords.get(name) if event_coords else None
                if u is None:
                    u = event_residuals @ views.basis[:, sl]
                z[sl], w = clipped_mean(u, clip_radius[name])
                if name == "event_average":
                    event_weights = w
    if event_weights is not None and np.any(event_weights < 1.0):
        r = (event_weights[:, None] * event_residuals).mean(axis=0)
    tol = views.tolerance_z if with_tolerance else None
    results = {}
    for name, sl in views.blocks:
        tb = None if tol is None else tol[sl]
        results[name] = ViewResult(name, _t2(z[sl], c, tb), chi2_limit(sl.stop - sl.start),
                                   sl.stop - sl.start, _t2(z[sl], c, None))
    # outside the candidates' subspace: no tolerance (the nominal parameters move the prediction inside it; what
    # lies outside is what no catalogue effect and no nominal error makes)
    zc = views.complement.T @ views.event_part(r)
    t2c = _t2(zc, c, None)
    results[OUTSIDE] = ViewResult(OUTSIDE, t2c, chi2_limit(int(zc.size)), int(zc.size), t2c)
    return ConsistencyResult(results, float(np.sqrt(np.mean(views.event_part(r) ** 2))))
