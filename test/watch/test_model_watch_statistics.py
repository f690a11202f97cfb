"""The statistics under the model watch's alarm rule (docs/model_watch.md, "The alarm rule"): a view whitened by a
covariance *estimated* from the model's own events follows Hotelling's predictive law, not chi^2; the bounded-
influence window mean counts every ordinary event as it is and any single event at most at its radius; the watch's
evaluation with it on a real reference."""
import numpy as np
import pytest
from scipy import stats

from backlash_monitor.watch.alarm import AlarmRule
from backlash_monitor.workbench import consistency, reference, synthetic
from backlash_monitor.workbench.model import load_model
import shared_cache                                             # test/: built by one process, the others wait


def _t2_with_estimated_covariance(rng, n_model: int, q: int, n_window: int) -> float:
    """One window's T^2 as consistency.test forms it: an n_window-event mean against the mean of n_model model
    events, whitened by the model events' sample covariance, c = 1/E + 1/n."""
    model = rng.standard_normal((n_model, q))
    window = rng.standard_normal((n_window, q)).mean(axis=0)
    d = window - model.mean(axis=0)
    s = np.cov(model, rowvar=False)
    return float(d @ np.linalg.solve((1.0 / n_window + 1.0 / n_model) * s, d))


def test_a_view_whitened_by_the_models_own_events_follows_hotellings_law_not_chi2():
    """Gaussian events, the covariance estimated from n = 48 model events (dof 47), q = 6: the predictive law's
    5 % point is exceeded 5 % of the time (binomial 99.9 % band over 4000 windows); chi^2's 5 % point ~2x as often.
    With n = 96 and q = 7 (the watch's event average) the laws' 1e-6 points are 53.0 vs 40.5: at chi^2's, the
    predictive law's chance is 33x the intended one."""
    rng = np.random.default_rng(7)
    n, q, e = 48, 6, 16
    t2 = np.array([_t2_with_estimated_covariance(rng, n, q, e) for _ in range(4000)])
    rate = np.mean(t2 > consistency.predictive_t2_isf(0.05, q, n - 1))
    band = stats.binom.interval(0.999, 4000, 0.05)
    assert band[0] / 4000 <= rate <= band[1] / 4000, rate
    assert np.mean(t2 > stats.chi2.isf(0.05, q)) > 1.5 * 0.05
    assert consistency.predictive_t2_isf(1e-6, 7, 95) == pytest.approx(53.01, abs=0.01)
    assert consistency.predictive_p(stats.chi2.isf(1e-6, 7), 7, 95) == pytest.approx(3.3e-5, rel=0.01)
    # the law's own round trip, and its limit: a known covariance (dof -> inf) is chi^2
    assert consistency.predictive_p(consistency.predictive_t2_isf(1e-4, 9, 95), 9, 95) == pytest.approx(1e-4)
    assert consistency.predictive_t2_isf(1e-3, 7, 10 ** 7) == pytest.approx(stats.chi2.isf(1e-3, 7), rel=1e-4)


def test_the_clipped_mean_is_the_mean_of_ordinary_events_and_bounds_any_single_one():
    rng = np.random.default_rng(3)
    u = rng.standard_normal((16, 7))
    radius = 6.0
    assert np.all(np.linalg.norm(u, axis=1) < radius)
    mean, w = consistency.clipped_mean(u, radius)
    assert np.array_equal(w, np.ones(16)) and np.allclose(mean, u.mean(axis=0), rtol=0, atol=1e-15)
    odd = u.copy()
    odd[5] = 1000.0 * np.ones(7)                       # one event 2600 sigma out
    mean_odd, w = consistency.clipped_mean(odd, radius)
    # it counts along its own direction at the radius: the mean moves by radius / E at most
    assert np.linalg.norm(mean_odd - consistency.clipped_mean(np.delete(u, 5, 0), radius)[0] * 15 / 16) \
        == pytest.approx(radius / 16)
    assert w[5] == pytest.approx(radius / np.linalg.norm(odd[5])) and np.all(np.delete(w, 5) == 1.0)


@pytest.fixture(scope="module")
def model():
    return load_model(None, width_m=0.005)


@pytest.fixture(scope="module")
def ref(model):
    return reference.load(shared_cache.watch_reference(model).path)


def test_clipping_changes_nothing_where_no_event_is_odd_and_bounds_an_odd_one(model, ref):
    """On the watch's reference: with a radius no event reaches the clipped evaluation is the plain one (diagnose's
    test, every view's T^2 to 1e-9); one event made odd (its a1 and a2 tripled) puts the plain event average far
    outside the rule's limit but moves the clipped one by no more than its bound; 2.5 N*m of wheel friction is
    outside the limit clipped or not."""
    rule = AlarmRule().check()
    dof = ref.view_dof()
    meas = synthetic.hidden_effect_recording(model, 5.0, seed=37)
    ev = reference.evidence_from_measurement(meas, ref, last_n=16, significant_noise=True)
    plain = ref.evaluate(ev, where=False)
    wide = ref.evaluate(ev, where=False, clip_p=1e-300)          # a radius far beyond every event
    for name, v in plain.result.views.items():
        assert wide.result.views[name].t2 == pytest.approx(v.t2, rel=1e-9), name
    odd = reference.Evidence(ev.raw.copy(), ev.dc, ev.spec, ev.noise_psd, ev.entries, ev.dc_names)
    odd.raw[7] *= 3.0
    limit = rule.limit("event_average", plain.result.views["event_average"].dimension, dof)
    assert ref.evaluate(odd, where=False).result.views["event_average"].t2 > 3 * limit
    clipped = ref.evaluate(odd, where=False, clip_p=rule.event_clip_p)
    assert not rule.exceeds(clipped, dof)[0], {n: v.t2 for n, v in clipped.result.views.items()}
    # the bound: one event moves the whitened mean by at most its radius / E, so sqrt(T^2) by radius / sqrt(E c E)
    radius = ref.clip_radius(ref.for_window(ev.noise_psd, 16, ev.dc_names).views, rule.event_clip_p)["event_average"]
    c = consistency.noise_scale(16, len(ref.seeds))
    bound = np.sqrt(ref.evaluate(reference.Evidence(np.delete(ev.raw, 7, 0), ev.dc[np.arange(16) != 7],
                                                    ev.spec[np.arange(16) != 7], ev.noise_psd, ev.entries[:15],
                                                    ev.dc_names), where=False).result.views["event_average"]
                    .t2_without_tolerance) + 2 * radius / 16 / np.sqrt(c)
    assert np.sqrt(clipped.result.views["event_average"].t2_without_tolerance) < bound
    bad = synthetic.hidden_effect_recording(model, 5.0, seed=38, config_overrides={
        "effects.wheel_coulomb_friction": True, "wheel_coulomb_friction.torque_Nm": 2.5})
    ev_bad = reference.evidence_from_measurement(bad, ref, last_n=16, significant_noise=True)
    assert rule.exceeds(ref.evaluate(ev_bad, where=False, clip_p=rule.event_clip_p), dof)[0]
