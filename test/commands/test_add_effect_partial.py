"""add-effect on a `partial` diagnosis (README: the loop takes the nearer model with --accept-partial): refused
without the flag, with a message that names it; with it, the partial effect goes in at its fitted value and the new
version says it is an approximation."""
import json

import pytest

from backlash_monitor.__main__ import main
from backlash_monitor.workbench.diagnosis_result import Conditions
from backlash_monitor.workbench.model import load_model


def _partial_diagnosis(tmp_path, change=0.25):
    model = load_model(None)
    cond = Conditions("drive.mcap", model.label(), None, dict(model.nominal), {}, [], model.to_dict(), [1, 2], {}, 16)
    addition = {"effect": "working_resistance_drift", "candidate": "working_resistance_drift",
                "parameters": {"relative_change": change}, "uncertainty": {"relative_change": 0.02},
                "role": "partial", "evidence": "event average"}
    d = {"discovery": None, "verdict": "partial", "message": "partial explanation: working_resistance_drift explains "
         "83% of the residual", "additions": [addition], "conditions": cond.to_json(), "measured_width": {},
         "proposal": {"proposed": False, "reason": "nothing stable"}}
    path = tmp_path / "d.json"
    path.write_text(json.dumps(d))
    return path


def test_a_partial_diagnosis_is_refused_without_the_flag_and_says_which_flag_takes_it(tmp_path, capsys):
    path = _partial_diagnosis(tmp_path)
    out = tmp_path / "v2.yaml"
    assert main(["add-effect", str(path), "-o", str(out)]) != 0
    said = capsys.readouterr()
    assert "--accept-partial" in said.err + said.out
    assert "Traceback" not in said.err
    assert not out.exists()


def test_accept_partial_writes_the_partial_effect_at_its_fitted_value_and_says_it_is_an_approximation(tmp_path,
                                                                                                       capsys):
    path = _partial_diagnosis(tmp_path, change=0.25)
    out = tmp_path / "v2.yaml"
    assert main(["add-effect", str(path), "--accept-partial", "-o", str(out)]) == 0
    said = capsys.readouterr().out
    assert "partial explanation added on request" in said
    f0 = load_model(None).plant_config().load.working_resistance_N
    # a drift is written as the new nominal value: F0 (1 + change)
    assert load_model(out).plant_config().load.working_resistance_N == pytest.approx(f0 * 1.25)


def test_a_sensor_term_proposed_after_a_partial_verdict_is_refused_with_the_partial_step_named(tmp_path, capsys):
    """A proposed term on a sensor's signal has no plug-in form: --accept-proposal refuses it, and on a `partial`
    verdict the refusal names the step that remains (the partial effect: --accept-partial), which then works."""
    path = _partial_diagnosis(tmp_path)
    d = json.loads(path.read_text())
    d["proposal"] = {"proposed": True, "law": "measured a2 += -0.0248 m/s² · a₁/10", "plugin_source": "",
                     "on_top_of": ["working_resistance_drift"], "terms": []}
    path.write_text(json.dumps(d))
    out = tmp_path / "v2.yaml"
    assert main(["add-effect", str(path), "--accept-proposal", "-o", str(out)]) == 2
    said = capsys.readouterr()
    assert "no plug-in form" in said.err and "--accept-partial" in said.err and "Traceback" not in said.err
    assert not out.exists()
    assert main(["add-effect", str(path), "--accept-partial", "-o", str(out)]) == 0
    assert out.exists()


def test_a_sensor_term_proposed_beside_a_discovery_is_refused_with_the_discovery_named(tmp_path, capsys):
    """Beside a discovered catalogue effect a proposal may come too (what the effect left); a sensor's term has no
    plug-in form: --accept-proposal refuses it and names the step that remains, the discovered effect alone
    (add-effect without the flag), which then works and writes the effect."""
    path = _partial_diagnosis(tmp_path, change=0.25)
    d = json.loads(path.read_text())
    d["verdict"] = "discovery"
    d["discovery"] = "working_resistance_drift"
    d["additions"][0]["role"] = "discovery"
    d["proposal"] = {"proposed": True, "law": "measured a2 += +200 m/s² · (a₂/50)³", "plugin_source": "",
                     "on_top_of": ["working_resistance_drift"], "terms": []}
    path.write_text(json.dumps(d))
    out = tmp_path / "v2.yaml"
    assert main(["add-effect", str(path), "--accept-proposal", "-o", str(out)]) == 2
    said = capsys.readouterr()
    assert "no plug-in form" in said.err and "without --accept-proposal" in said.err and "Traceback" not in said.err
    assert "--accept-partial" not in said.err
    assert not out.exists()
    assert main(["add-effect", str(path), "-o", str(out)]) == 0
    f0 = load_model(None).plant_config().load.working_resistance_N
    assert load_model(out).plant_config().load.working_resistance_N == pytest.approx(f0 * 1.25)
