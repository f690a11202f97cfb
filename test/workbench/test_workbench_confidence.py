"""The confidence step's rule for ties (diagnose.confidence_step): when the recording cannot tell the winner from
other candidates, the IC order among them is the recording's noise; the consistency check decides. These tests
pin the rule on stand-in fits (the check itself, decisions.confident, is tested on recordings elsewhere); the
foreign recording that needs it is in test_workbench_foreign.py."""
from types import SimpleNamespace

import numpy as np

from backlash_monitor.workbench import diagnose as D


def _fit(name, passes, twins=()):
    return SimpleNamespace(effect=name, pred=np.array([float(passes)]), model_mean=f"mean {name}",
                           model_mean_raw=f"raw {name}", indistinguishable_from=list(twins), passes=passes)


def _run(fits):
    return SimpleNamespace(problem=None, base_pred=np.array([0.0]), fits=fits)


def _check(problem, after_pred, base_pred):
    ok = bool(after_pred[0])
    return ok, {"views_made_worse": [] if ok else ["outside"], "consistent_in_every_view": ok}


def test_a_tied_candidate_whose_model_passes_replaces_a_winner_that_fails(monkeypatch):
    monkeypatch.setattr(D, "confident", _check)
    win, twin = _fit("accelerometer_gain[a2]", False, ["load_mass_drift"]), _fit("load_mass_drift", True)
    up = D.confidence_step(_run([win, twin]), D.Update(win, after_pred=win.pred), D.Decision(win, [win, twin]))
    assert up.confident and up.first is twin
    assert up.after_mean == "mean load_mass_drift" and up.after_raw == "raw load_mass_drift"
    # the winner it replaces is named as not distinguishable from it, and why it was replaced is recorded
    assert "accelerometer_gain[a2]" in twin.indistinguishable_from
    assert up.checks["replaced"] == {"effect": "accelerometer_gain[a2]", "views_made_worse": ["outside"],
                                     "consistent_in_every_view": False}


def test_a_candidate_the_recording_tells_apart_does_not_replace_the_winner(monkeypatch):
    """Passing the check is not enough: only a candidate tied with the winner may take its place."""
    monkeypatch.setattr(D, "confident", _check)
    win, other = _fit("accelerometer_gain[a2]", False), _fit("absorber_consistency_drift", True)
    up = D.confidence_step(_run([win, other]), D.Update(win, after_pred=win.pred), D.Decision(win, [win, other]))
    assert not up.confident and up.first is win


def test_a_winner_that_passes_stays_and_a_pair_is_left_as_it_is(monkeypatch):
    monkeypatch.setattr(D, "confident", _check)
    win, twin = _fit("load_mass_drift", True, ["accelerometer_gain[a2]"]), _fit("accelerometer_gain[a2]", True)
    up = D.confidence_step(_run([win, twin]), D.Update(win, after_pred=win.pred), D.Decision(win, [win, twin]))
    assert up.confident and up.first is win
    # a pair (a second effect) that fails is not taken apart here: its members were fitted together
    bad, twin2 = _fit("wheel_coulomb_friction", False, ["working_resistance_drift"]), \
        _fit("working_resistance_drift", True)
    second = _fit("accelerometer_bias[a2]", False)
    up = D.confidence_step(_run([bad, twin2]), D.Update(bad, second=second, after_pred=bad.pred),
                           D.Decision(bad, [bad, twin2]))
    assert not up.confident and up.first is bad


def test_of_several_tied_candidates_the_first_in_ic_order_that_passes_is_taken(monkeypatch):
    monkeypatch.setattr(D, "confident", _check)
    win = _fit("wheel_coulomb_friction", False, ["working_resistance_drift", "mass_force_offset"])
    a, b = _fit("working_resistance_drift", False), _fit("mass_force_offset", True)
    up = D.confidence_step(_run([win, a, b]), D.Update(win, after_pred=win.pred), D.Decision(win, [win, a, b]))
    assert up.first is b and up.confident
    # the same term of the model as the one taken (decisions.IDENTICAL) is named with it
    assert {"wheel_coulomb_friction", "working_resistance_drift"} <= set(b.indistinguishable_from)
