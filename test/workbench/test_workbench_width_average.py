"""The measured width when the model does not hold (issue 31): averaged over the plausible models that hold it, with
the unconditional standard error (workbench/model_average.py, Burnham & Anderson 2002 ch. 4). The estimator's own
properties first (pure numpy), then on drives of the independent simulator (foreign_drives/): a width change beside
an effect whose law the catalogue does not have, and a width change alone."""
import math

import numpy as np
import pytest

from backlash_monitor.workbench.model_average import PLAUSIBLE_IC_MARGIN, Member, average, weights


def test_one_model_keeps_its_own_value_and_error():
    a = average([Member(1.0e-3, 0.1e-3, 500.0)])
    assert a.value == pytest.approx(1.0e-3) and a.sd == pytest.approx(0.1e-3) and a.weights == (1.0,)


def test_two_equally_supported_models_that_disagree_widen_the_error_by_their_spread():
    """Two models with the same evidence that put the width 0.4 mm apart: the average lies between them, and its
    error covers both (each one's own 0.1 mm would leave the other 2 of them off)."""
    a = average([Member(1.0e-3, 0.1e-3, 300.0), Member(1.4e-3, 0.1e-3, 300.0)])
    assert a.value == pytest.approx(1.2e-3)
    assert a.sd == pytest.approx(math.sqrt(0.1e-3 ** 2 + 0.2e-3 ** 2))
    assert abs(a.value - 1.0e-3) <= a.sd * 1.0 + 1e-12 and abs(a.value - 1.4e-3) <= a.sd + 1e-12


def test_a_model_far_behind_on_the_events_takes_no_part():
    far = PLAUSIBLE_IC_MARGIN + 1.0
    a = average([Member(1.0e-3, 0.1e-3, 300.0), Member(3.0e-3, 0.1e-3, 300.0 + far)])
    assert len(a.members) == 1 and a.value == pytest.approx(1.0e-3) and a.sd == pytest.approx(0.1e-3)


def test_a_misfit_spreads_the_weight_as_quasi_likelihood_does():
    """Under a misfit (T^2 per dimension c > 1) the events' IC overstates the evidence by c: a model 20 behind is out
    at c = 1, in at c = 4 with the weight of 5 behind."""
    w1 = weights([100.0, 120.0], 1.0)
    w4 = weights([100.0, 120.0], 4.0)
    assert w1[1] == 0.0
    assert w4[1] == pytest.approx(math.exp(-2.5) / (1 + math.exp(-2.5)))


def test_no_model_or_a_scale_below_one_is_refused_in_one_line():
    with pytest.raises(ValueError, match="at least one fitted model"):
        weights([], 1.0)
    with pytest.raises(ValueError, match="allowed >= 1"):
        weights([1.0], 0.5)


def test_the_average_covers_a_biased_model_in_repeated_samples():
    """Coverage by simulation: the truth 1.0; model A unbiased (error 0.1), model B biased by +0.4 (a missing effect
    taken up by the width) with the same evidence on average (each IC +-2). The best model's own error covers the truth
    at 2 sigma about half the time (B wins half the time); the average's unconditional error far more often (measured
    with this seed: 83 % against 48 %), though not at the nominal 95 %: the weights follow the IC's own noise."""
    rng = np.random.default_rng(3)
    hit_avg = hit_best = 0
    n = 2000
    for _ in range(n):
        a, b = 1.0 + 0.1 * rng.standard_normal(), 1.4 + 0.1 * rng.standard_normal()
        ica, icb = 100.0 + 2.0 * rng.standard_normal(), 100.0 + 2.0 * rng.standard_normal()
        avg = average([Member(a, 0.1, ica), Member(b, 0.1, icb)])
        best = a if ica < icb else b
        hit_avg += abs(avg.value - 1.0) <= 2 * avg.sd
        hit_best += abs(best - 1.0) <= 2 * 0.1
    assert hit_avg / n > 0.75 and hit_best / n < 0.55, (hit_avg / n, hit_best / n)


@pytest.mark.slow
def test_a_width_change_beside_a_fan_load_is_measured_within_its_stated_uncertainty():
    """A foreign drive (its own simulator) whose width grew 6.0 -> 6.8 mm and whose motor drives a fan (a load torque
    rising with the square of the speed, 2.5 N*m at 151.4 rad/s: a law the catalogue does not have; seed 7801, no
    bench row uses it). The width is not the verdict (it does not explain alone), and the measured width lies within 3
    of its stated uncertainties of the truth (the issue's goal); where the model does not hold, the uncertainty is
    the model average's (averaged_over lists the models)."""
    from foreign_drives.drive import make_recording
    from foreign_drives.spec import EffectSpec as E
    from foreign_drives.spec import RecordingSpec

    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    from backlash_monitor.workbench.model import load_model
    spec = RecordingSpec(label="width_fan", kind="two", width_m=0.006, eta_k=0.03, n1=0.9, seed=7801, duration_s=4.0,
                         effects=(E("drift_width", {"change": 0.0008}),
                                  E("motor_fan_load", {"torque_Nm": 2.5, "reference_speed_rad_s": 151.4}))).check()
    rec = make_recording(spec)
    meas = Measurement("foreign:width_fan", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    d = diagnose(meas, load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1), propose=False).to_json()
    w = d["measured_width"]
    assert d["verdict"] != "width", d["message"]
    assert abs(w["width_m"] - rec.truth.true_width_m) <= 3 * w["uncertainty_m"], (w, rec.truth.true_width_m)
    if d["verdict"] in ("partial", "nothing_explains"):
        assert len(w["averaged_over"]) >= 1 and not w["differs_from_nominal"], w
