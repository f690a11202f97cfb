"""consistency.ConsistencyViews: the views built once, whole, from a screening's Jacobians and the model's own events
(linear algebra on a toy prediction space: 40 event-average coordinates, 4 spectral, 2 record-mean)."""
import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

from backlash_monitor.workbench import consistency

N_EV, N_SP, N_DC = 40, 4, 2


def _layout(n_events=16, n_seeds=6):
    n = N_EV + N_SP + N_DC
    return SimpleNamespace(event_slice=slice(0, N_EV), spectral_slice=slice(N_EV, N_EV + N_SP),
                           dc_slice=slice(N_EV + N_SP, n), n_event_coords=N_EV, n_events=n_events, n_seeds=n_seeds,
                           target_vec=np.zeros(n), ws=np.ones(N_SP), wdc=np.ones(N_DC), dc_names=("a1", "a2"))


def _candidate(k):
    return SimpleNamespace(bounds=lambda: (-np.ones(k), np.ones(k)),
                           parameters=[SimpleNamespace(key=f"toy.p{i}") for i in range(k)])


def _views(rng, scale=None):
    layout = _layout()
    n = layout.target_vec.size
    jacobians = {"a": rng.normal(size=(n, 2)), "b": rng.normal(size=(n, 1))}
    candidates = {"a": _candidate(2), "b": _candidate(1)}
    scale = np.ones(n) if scale is None else scale
    model_events = rng.normal(size=(6 * 16, n)) * scale[None]          # the model's own events, less its prediction
    return consistency.ConsistencyViews.from_screening(layout, jacobians, candidates, model_events), model_events


def test_the_views_whiten_the_models_own_events_and_the_complement_lies_outside_the_subspace():
    """Each block's whitened coordinates of the model's own events have unit covariance (whatever their scale per
    coordinate); the complement's directions are orthogonal to the event-average block's subspace."""
    rng = np.random.default_rng(7)
    views, model_events = _views(rng, scale=np.linspace(0.5, 3.0, N_EV + N_SP + N_DC))
    names = [name for name, _ in views.blocks]
    assert names == ["event_average", "spectral_shape", "record_mean"]
    for _, sl in views.blocks:
        z = model_events @ views.basis[:, sl]
        assert np.allclose(np.cov(z, rowvar=False), np.eye(sl.stop - sl.start), atol=1e-9)
    ev_dirs = dict(views.candidate_directions)["event_average"][views.event_slice]
    assert np.abs(ev_dirs.T @ views.complement).max() < 1e-9 * np.abs(views.complement).max()
    assert views.fit_basis.shape == (N_EV + N_SP + N_DC, views.basis.shape[1] + views.complement.shape[1])


def test_the_test_in_the_views_flags_a_residual_along_a_candidate_and_passes_the_models_own_mean():
    """The mean of 16 of the model's own events is inside every view; the same shifted along one of the candidates'
    event-average directions by twice one event's noise (8 standard errors of a 16-event mean) is outside the event
    average's."""
    rng = np.random.default_rng(11)
    views, _ = _views(rng)
    own = rng.normal(size=(16, N_EV + N_SP + N_DC)).mean(axis=0)
    assert consistency.test(views, own).consistent
    layout = _layout()
    push = np.zeros(layout.target_vec.size)
    push[views.event_slice] = 2.0 * dict(views.candidate_directions)["event_average"][views.event_slice, 0]
    assert consistency.test(views, own + push).views["event_average"].outside_band


def test_the_views_are_built_whole_and_not_changed_afterwards():
    views, _ = _views(np.random.default_rng(3))
    with pytest.raises(dataclasses.FrozenInstanceError):
        views.basis = None


def test_the_information_criterion_in_the_views_is_the_events_gaussian_per_direction():
    """fitting.Problem.ic in the whitened views: E * sum_j log(mean_e z_ej^2) + k log E, z = (event_e - pred) @ basis
    (docs/workbench.md "Decisions"), with the events' projection kept per views object (a new views object is
    projected anew, not read from the old one's)."""
    from backlash_monitor.workbench import fitting
    rng = np.random.default_rng(3)
    p = object.__new__(fitting.Problem)
    p.event_vecs = rng.normal(size=(16, N_EV + N_SP + N_DC)) + 5.0
    p.n_event_coords = N_EV
    p.views = _views(rng)[0]
    pred = rng.normal(size=p.event_vecs.shape[1])

    def by_hand(views, k):
        z = (p.event_vecs - pred[None]) @ views.basis
        return 16 * np.sum(np.log(np.mean(z ** 2, axis=0))) + k * np.log(16)
    assert p.ic(pred, 3) == pytest.approx(by_hand(p.views, 3), rel=1e-12)
    other = _views(np.random.default_rng(4))[0]
    q = p.with_views(other)
    assert q.ic(pred, 0) == pytest.approx(by_hand(other, 0), rel=1e-12)
    assert p.ic(pred, 0) == pytest.approx(by_hand(p.views, 0), rel=1e-12)
