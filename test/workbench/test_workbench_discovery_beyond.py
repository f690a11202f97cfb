"""A catalogue discovery on a drive whose mechanism the catalogue does not have (issue 31): when the proposal runs
after a ``discovery`` verdict (diagnose.proposal_basis). The rule on stand-in updates; the class it is for on a
recording that foreign_drives made (an independent simulator: no inverse crime)."""
import os
from types import SimpleNamespace

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.workbench import diagnose as D                        # noqa: E402


def _views(ratio_ea: float, ratio_out: float = 0.5) -> dict:
    """The consistency views a model leaves: T^2 at these multiples of the limits."""
    return {"views": {"event_average": {"T2": 20.0 * ratio_ea, "T2_limit_p01": 20.0,
                                        "outside_band": ratio_ea > 1},
                      "outside": {"T2": 37.6 * ratio_out, "T2_limit_p01": 37.6, "outside_band": ratio_out > 1}}}


def _update(confident, strict=False, ratio_ea=0.5, first=True):
    fit = SimpleNamespace(effect="accelerometer_bias[a1]") if first else None
    checks = {"consistent_in_every_view": strict, "outside_subspace_ok": strict,
              "within_form_tolerance": confident and not strict, "explained": 0.93,
              "views_after": _views(ratio_ea)}
    return D.Update(fit, confident=confident, checks=checks if first else {})


def test_the_proposal_runs_on_its_own_verdicts_and_never_after_a_consistent_model_or_a_width():
    run = SimpleNamespace(inconsistent=True)
    assert D.proposal_basis(run, D.Update(None), "partial") == "partial"
    assert D.proposal_basis(run, D.Update(None), "nothing_explains") == "nothing_explains"
    assert D.proposal_basis(SimpleNamespace(inconsistent=False), D.Update(None), "consistent") is None
    assert D.proposal_basis(run, _update(True, strict=True), "width") is None


def test_a_discovery_consistent_in_every_view_leaves_nothing_to_propose():
    """The model with the effect agrees with the recording in every view and outside the candidates' subspace: no
    recording-level test tells the effect from a mechanism it mimics (measured: a ratchet pawl on the wheel read as
    viscous wheel friction, every view within its limit) -- nothing is proposed on top."""
    assert D.proposal_basis(SimpleNamespace(inconsistent=True), _update(True, strict=True), "discovery") is None


def test_a_spectral_discovery_beside_an_unexplained_event_average_gets_the_proposal():
    """A torque ripple from the raw a1 spectrum makes the verdict a discovery, but the event average is still outside
    its band: the proposal is fitted to it -- on top of its partial explanation when there is one."""
    run = SimpleNamespace(inconsistent=True)
    assert D.proposal_basis(run, D.Update(None), "discovery") == "nothing_explains"
    assert D.proposal_basis(run, _update(False, ratio_ea=14.0), "discovery") == "partial"
    # the ripple alone on a model the event average agrees with: nothing to propose
    assert D.proposal_basis(SimpleNamespace(inconsistent=False), D.Update(None), "discovery") is None


def test_a_discovery_within_the_form_tolerance_gets_the_proposal_only_when_it_leaves_a_view_far_outside():
    run = SimpleNamespace(inconsistent=True)
    far = _update(True, ratio_ea=D.FORM_LEFT_T2_RATIO * 8)
    near = _update(True, ratio_ea=D.FORM_LEFT_T2_RATIO * 0.8)
    assert D.proposal_basis(run, far, "discovery") == "partial"
    assert D.proposal_basis(run, near, "discovery") is None
    assert D.form_left_ratio(far) == pytest.approx(D.FORM_LEFT_T2_RATIO * 8)


@pytest.mark.heavy      # make test-all (CI time); bench/_workbench/discovery_probe.py measures the rows one by one
@pytest.mark.slow
def test_a_rotating_accelerometer_read_as_a_torque_ripple_gets_its_sensor_term_proposed():
    """foreign_drives' od_a1_rotating_gravity (a1 on the motor's rim sweeps through gravity: a1 += 9.81 m/s^2 *
    sin(alpha1 + 0.9)): the raw a1 spectrum's 24 Hz line reads as a torque ripple, the event average stays outside its
    band. The proposal is fitted to it and names a term of the a1 sensor at the motor's angle, the size of g."""
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite

    from backlash_monitor.workbench.measurement import Measurement
    from backlash_monitor.workbench.model import load_model
    spec = next(s for s in suite("outside_dev") if s.label == "od_a1_rotating_gravity")
    rec = make_recording(spec)
    meas = Measurement(f"foreign:{spec.label}", rec.sample_period_s,
                       {k: np.asarray(v) for k, v in rec.signals.items()})
    d = D.diagnose(meas, load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)).to_json()
    prop = d["proposal"]
    assert d["verdict"] == "discovery" and prop is not None and prop["proposed"], d["message"]
    assert "nothing to discover in the event average" not in d["message"]
    term = prop["terms"][0]
    assert term["balance"] == "sensor_a1_m_s2" and term["state"] == "alpha1"
    assert term["amplitude"] == pytest.approx(9.81, rel=0.25)
    assert prop["consistent"]
