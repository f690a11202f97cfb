"""The proposed term refitted jointly with the partial explanation it sits on (issue 31: the proposed term "fitted,
tested and ranked like a catalogue effect", the second member of a pair): the Gauss-Newton steps, kept only when they
lower the residual, and add-effect writing the partial effect at its jointly fitted values."""
import json
import os

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.workbench import candidate_terms, proposal   # noqa: E402


def _design(seed=3, n=200):
    """Two columns of a linear model of the events' mean: u, a catalogue effect's response per unit of its
    parameter, and v, a missing term's per unit of its coefficient, v partly along u (cosine ~0.6)."""
    rng = np.random.default_rng(seed)
    u = rng.normal(size=n)
    v = 0.6 * u + 0.8 * rng.normal(size=n)
    return u, v


def test_the_joint_refit_moves_a_partial_effect_that_took_part_of_the_term_back_to_its_truth():
    u, v = _design()
    a_true, c_true = 1.0, 2.0
    y = a_true * u + c_true * v
    # diagnose: the partial effect fitted alone takes up the term's share along u
    a_alone = float(u @ y / (u @ u))
    assert a_alone > a_true + 0.5
    # the proposal: the term fitted on top of the partial effect held at a_alone
    c_top = float(v @ (y - a_alone * u) / (v @ v))
    J = np.stack([u, v], axis=1)

    def residual_at(x):
        return y - J @ x

    r0 = residual_at(np.array([a_alone, c_top]))
    x, r, norm, trials = proposal.kept_gauss_newton([a_alone, c_top], [-10.0, -10.0], [10.0, 10.0], J, residual_at,
                                                    r0, 2)
    assert abs(x[0] - a_true) < 0.05 * abs(a_alone - a_true)
    assert abs(x[1] - c_true) < 0.05 * abs(c_top - c_true)
    assert norm < 1e-6 * float(r0 @ r0)
    assert norm == pytest.approx(float(r @ r))


def test_the_joint_refit_never_raises_the_residual_with_a_wrong_tangent_or_a_failing_model():
    u, v = _design(seed=5)
    y = 1.0 * np.tanh(u) + 2.0 * v              # the response is not linear in the partial effect's parameter

    def residual_at(x):
        return y - x[0] * np.tanh(u) - x[1] * v

    x0 = np.array([1.8, 1.2])
    r0 = residual_at(x0)
    for J in (np.stack([u, v], axis=1),                   # a tangent at another point (tanh bent away)
              np.stack([-u, 3 * v], axis=1),              # a tangent of the wrong sign: every step is refused
              np.stack([u, v], axis=1) * 50.0):           # a tangent 50 times too large: steps too small, still kept
        x, r, norm, trials = proposal.kept_gauss_newton(x0, [-10, -10], [10, 10], J, residual_at, r0, 3)
        assert norm <= float(r0 @ r0)
        assert np.allclose(r, residual_at(x))
    # the bounds hold: the partial's fit range, the terms' bounds
    x, _, _, _ = proposal.kept_gauss_newton(x0, [1.5, -10], [10, 10], np.stack([np.tanh(u), v], axis=1), residual_at,
                                            r0, 3)
    assert x[0] >= 1.5

    def fails(x):
        raise ValueError("no onset window")
    x, r, norm, trials = proposal.kept_gauss_newton(x0, [-10, -10], [10, 10], np.stack([u, v], axis=1), fails, r0, 3)
    assert np.array_equal(x, x0) and norm == pytest.approx(float(r0 @ r0)) and trials == [None] * 3


def test_add_effect_writes_the_partial_effect_at_the_values_refitted_with_the_proposed_term(tmp_path):
    from backlash_monitor.__main__ import main
    from backlash_monitor.workbench.diagnosis_result import Conditions
    from backlash_monitor.workbench.model import load_model
    by = candidate_terms.by_name()
    pieces = [candidate_terms.ProposedPiece((by["cand_wheel_omega2_1"],), (-1.5,), (0.1,))]
    src, values = candidate_terms.proposal_source(pieces)
    model = load_model(None)
    cond = Conditions("drive.mcap", model.label(), None, dict(model.nominal), {}, [], model.to_dict(), [1, 2], {}, 16)
    alone, joint = 0.30, 0.12     # the working resistance drift fitted alone, and beside the term
    prop = {"proposed": True, "reason": "test", "law": candidate_terms.proposal_law(pieces), "plugin_source": src,
            "plugin_values": values, "on_top_of": ["working_resistance_drift"],
            "on_top_values": {"working_resistance_drift": {"relative_change": joint}},
            "on_top_uncertainty": {"working_resistance_drift": {"relative_change": 0.02}}}
    addition = {"effect": "working_resistance_drift", "candidate": "working_resistance_drift",
                "parameters": {"relative_change": alone}, "uncertainty": {"relative_change": 0.01},
                "role": "partial", "evidence": "event average"}
    d = {"discovery": None, "verdict": "partial", "message": "partial", "additions": [addition],
         "conditions": cond.to_json(), "measured_width": {}, "proposal": prop}
    path = tmp_path / "d.json"
    path.write_text(json.dumps(d))
    out = tmp_path / "v2.yaml"
    # the partial the term sits on goes in with it (no --accept-partial needed: the term was fitted beside it)
    assert main(["add-effect", str(path), "-o", str(out), "--accept-proposal"]) == 0
    f0 = load_model(None).plant_config().load.working_resistance_N
    # a drift is written as the new nominal value: F0 (1 + change)
    assert load_model(out).plant_config().load.working_resistance_N == pytest.approx(f0 * (1 + joint))
    # without the joint values (a proposal of before), diagnose's value of the partial alone
    del prop["on_top_values"], prop["on_top_uncertainty"]
    path.write_text(json.dumps(d))
    out3 = tmp_path / "v3.yaml"
    assert main(["add-effect", str(path), "-o", str(out3), "--accept-proposal"]) == 0
    assert load_model(out3).plant_config().load.working_resistance_N == pytest.approx(f0 * (1 + alone))


@pytest.mark.heavy      # make test-all (CI time); ~2 min CPU
@pytest.mark.slow
def test_a_torque_limiters_term_refitted_with_the_drift_it_sits_on_gives_back_what_the_drift_took():
    """foreign_drives' torque limiter (the sixth development half: the clutch's contact torque capped at 40 N·m).
    diagnose calls it partial, a working-resistance drift fitted alone standing in for part of it (measured +0.60).
    The true drive has no drift: with the proposed clutch term in, the joint refit moves the drift back toward 0 and
    lowers the events' mean residual; it never raises it."""
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite

    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    from backlash_monitor.workbench.model import load_model
    spec = next(s for s in suite("outside_dev6") if s.label == "od6_clutch_torque_limiter")
    rec = make_recording(spec)
    meas = Measurement("foreign:limiter", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    d = diagnose(meas, load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)).to_json()
    prop = d["proposal"]
    assert prop and prop["proposed"] and prop["on_top_of"] == ["working_resistance_drift"], d["message"]
    joint = prop["joint_refit"]
    assert joint["residual_after"] <= joint["residual_before"]
    assert joint["moved"], joint
    before = joint["values_before"]["working_resistance_drift"]["relative_change"]
    after = prop["on_top_values"]["working_resistance_drift"]["relative_change"]
    assert 0.0 <= after < before, (before, after)
    assert prop["explained_fraction"] > joint["explained_before"]
