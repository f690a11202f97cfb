"""A user's plug-in effects in the workbench (--effects-file; `effect_files` in the model): fitted as
candidates by diagnose, added by add-effect, kept in the next model version so it loads again.
docs/examples/my_effects.py defines `wheel_drag` (-c*Omega2*|Omega2| on the wheel)."""
from pathlib import Path

import pytest
import yaml

from backlash_monitor.__main__ import main
from backlash_monitor.workbench import plant_adapter
from backlash_monitor.workbench.diagnose import diagnose, public
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.synthetic import hidden_effect_recording

MY_EFFECTS = Path(__file__).resolve().parents[2] / "docs" / "examples" / "my_effects.py"


def test_plugin_is_a_candidate_and_its_version_loads_again(tmp_path, capsys):
    v1 = tmp_path / "v1.yaml"
    load_model(None).save(v1)
    v2 = tmp_path / "models" / "v2.yaml"
    v2.parent.mkdir()
    base = ["add-effect", "wheel_drag", "--value", "coefficient_Nms2_per_rad2=0.02", "--model", str(v1), "-o", str(v2)]
    assert main(base) == 2                                   # without the file: not in the catalogue
    assert "not in the catalogue" in capsys.readouterr().err
    model = load_model(None, effect_files=[MY_EFFECTS])
    assert "wheel_drag" in {c.effect for c in plant_adapter.catalogue(model)}
    assert "wheel_drag" not in {c.effect for c in plant_adapter.catalogue(load_model(None))}   # the model's own
    assert main(base + ["--effects-file", str(MY_EFFECTS)]) == 0
    saved = yaml.safe_load(v2.read_text())
    assert not Path(saved["effect_files"][0]).is_absolute()  # relative to the model file: moves with it
    again = load_model(v2)                                   # the version's own file gives its catalogue
    cfg = again.plant_config()
    assert cfg.effects["wheel_drag"] and cfg.effect_parameter("wheel_drag", "coefficient_Nms2_per_rad2") == 0.02
    assert cfg.catalogue is again.catalogue and "wheel_drag" in again.catalogue


@pytest.mark.slow
def test_diagnose_names_a_hidden_plugin_effect():
    """Hidden quadratic wheel drag c = 0.05 N*m*s^2/rad^2 (Omega2 ~ 7-14 rad/s: 2.5-10 N*m); the fit
    restricted to three candidates (the plug-in, the catalogue's linear wheel friction, a mass drift)
    names the plug-in (or it and the viscous friction as indistinguishable), its value significant
    (more than one uncertainty from 0) and within two of its uncertainties of the truth. Over 7-14
    rad/s a quadratic and a linear wheel drag are nearly collinear: c is determined only to ~60 %."""
    model = load_model(None, effect_files=[MY_EFFECTS])
    meas = hidden_effect_recording(model, 4.0, seed=7301, config_overrides={
        "effects.wheel_drag": True, "wheel_drag.coefficient_Nms2_per_rad2": 0.05})
    pub = public(diagnose(meas, model, effects=["wheel_drag", "wheel_viscous_friction", "load_mass_drift"],
                          second=False))
    named = {pub["discovery"], *pub["indistinguishable"]}
    assert "wheel_drag" in named, pub["message"]
    fit = next(r for r in pub["ranked"] if r["effect"] == "wheel_drag")
    c = fit["parameters"]["coefficient_Nms2_per_rad2"]
    sigma = fit["uncertainty"]["coefficient_Nms2_per_rad2"]
    assert 0 < sigma < c
    assert abs(c - 0.05) <= 2 * sigma
