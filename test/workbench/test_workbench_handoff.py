"""The loop's hand-off (issue 20, "never a worse monitor"): a diagnosis records what it was made against and what
the next version should hold; add-effect builds on exactly that model; the width is measured, never trained in;
train checks the retrained monitor on the diagnosed recording and never hands on a worse library."""
import json
import os

import numpy as np
import pytest
import yaml

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.__main__ import main                               # noqa: E402
from backlash_monitor.classifier.patterns import load_library           # noqa: E402
from backlash_monitor.workbench.diagnosis_result import Addition, Conditions, read_handoff  # noqa: E402
from backlash_monitor.workbench.model import load_model                 # noqa: E402
from backlash_monitor.workbench.retrain import training_config          # noqa: E402
from backlash_monitor.workbench.synthetic import hidden_effect_recording  # noqa: E402
from backlash_monitor.workbench.versions import EffectValues, add_effects  # noqa: E402


def _npz(path, meas):
    np.savez(path, sample_period_s=meas.sample_period_s, **meas.signals)
    return path


@pytest.fixture(scope="module")
def diagnosed_at_other_conditions(tmp_path_factory):
    """A 5 mm drive at eta_k 0.0375, n1 0.93 with 1.5 N*m of wheel friction, diagnosed against the default model
    given those nominal values on the command line (no model file), with a 3-seed ensemble (--ensemble 3: the
    hand-off does not depend on the ensemble's size; a diagnosis ~30 % less CPU than at the default 6)."""
    d = tmp_path_factory.mktemp("handoff")
    model = load_model(None, width_m=0.005, eta_k=0.0375, n1=0.93)
    meas = hidden_effect_recording(model, 3.0, seed=311, config_overrides={
        "effects.wheel_coulomb_friction": True, "wheel_coulomb_friction.torque_Nm": 1.5})
    rec = _npz(d / "drive.npz", meas)
    assert main(["diagnose", str(rec), "--width-m", "0.005", "--eta-k", "0.0375", "--n1", "0.93",
                 "--ensemble", "3", "--json", str(d / "diag.json"), "--no-history"]) == 0
    return d, json.loads((d / "diag.json").read_text())


@pytest.mark.slow
def test_the_diagnosis_records_its_conditions_and_additions(diagnosed_at_other_conditions):
    _, diag = diagnosed_at_other_conditions
    c = diag["conditions"]
    assert c["nominal"] == {"width_m": 0.005, "eta_k": 0.0375, "n1": 0.93}
    assert c["overrides"]["nominal.width_m"] == 0.005 and c["effective_model"]["nominal"]["eta_k"] == 0.0375
    conditions, additions, verdict = read_handoff(diag, "diag.json")
    assert isinstance(conditions, Conditions) and verdict == "discovery"
    assert additions and all(isinstance(a, Addition) for a in additions)
    assert additions[0].role == "discovery" and additions[0].effect == diag["discovery"]


@pytest.mark.slow
def test_add_effect_carries_the_conditions_into_the_next_version(diagnosed_at_other_conditions, capsys):
    d, diag = diagnosed_at_other_conditions
    assert main(["add-effect", str(d / "diag.json"), "-o", str(d / "v2.yaml")]) == 0
    v2 = load_model(d / "v2.yaml")
    assert v2.nominal == {"width_m": 0.005, "eta_k": 0.0375, "n1": 0.93}        # not the default 7.5 mm, 0.025, 0.89
    assert diag["discovery"] in ([e["effect"] for e in v2.effects_added]
                                 + [u["effect"] for u in v2.nominal_updates])
    assert v2.provenance["measurement"].endswith("drive.npz") and v2.provenance["width_m"] == 0.005
    # options that name another model than the diagnosed one are refused, naming the difference
    capsys.readouterr()
    assert main(["add-effect", str(d / "diag.json"), "--width-m", "0.0075", "-o", str(d / "v2b.yaml")]) == 2
    err = capsys.readouterr().err
    assert "nominal width_m" in err and "0.005" in err and not (d / "v2b.yaml").exists()


def test_a_measured_width_becomes_the_nominal_width_never_an_effect(tmp_path, capsys):
    """A diagnosis whose verdict is the width: add-effect writes the next version at the measured width and adds
    no effect; a width drift cannot be added as an effect at all."""
    model = load_model(None, width_m=0.005)
    diag = {"discovery": "backlash_width_drift", "verdict": "width", "message": "the backlash width is 6.2 mm",
            "measurement": "rec.npz", "additions": [],
            "measured_width": {"width_m": 0.0062, "uncertainty_m": 5e-5, "nominal_width_m": 0.005,
                               "differs_from_nominal": True},
            "conditions": Conditions("rec.npz", model.label(), None, dict(model.nominal), {"nominal.width_m": 0.005},
                                     [], model.to_dict(), [0, 1, 2], {}, 16).to_json()}
    (tmp_path / "d.json").write_text(json.dumps(diag))
    assert main(["add-effect", str(tmp_path / "d.json"), "-o", str(tmp_path / "v2.yaml")]) == 0
    v2 = yaml.safe_load((tmp_path / "v2.yaml").read_text())
    assert v2["nominal"]["width_m"] == pytest.approx(0.0062) and v2["effects_added"] == []
    assert "measurand" in capsys.readouterr().out
    with pytest.raises(ValueError, match="measurand"):
        add_effects(model, [EffectValues("backlash_width_drift", {"change": 0.0012})])


def test_training_switches_a_width_drift_off():
    """A model version that holds a width drift (made by hand, or by an older add-effect): training simulates the
    grid's widths themselves -- the labels are the widths the windows are simulated at."""
    m = load_model(None, sets=["effects.backlash_width_drift=true", "backlash_width_drift.change=0.0012"])
    cfg, note = training_config(m)
    assert not cfg.effects.get("backlash_width_drift") and "measurand" in note
    assert training_config(load_model(None))[1] is None


@pytest.mark.slow
def test_train_never_hands_on_a_worse_library(tmp_path, capsys):
    """A version whose added effect is wrong for the drive (4 N*m of wheel friction on a clean 7.5 mm drive): its
    retrained monitor is further from the diagnosed width than the packaged library on the diagnosed recording, so
    --out gets the packaged library (saying why) and the retrained one is kept beside it as .rejected.npz."""
    model = load_model(None)
    meas = hidden_effect_recording(model, 3.0, seed=312, config_overrides={})
    rec = _npz(tmp_path / "clean.npz", meas)
    wrong = add_effects(model, [EffectValues("wheel_coulomb_friction", {"torque_Nm": 4.0})],
                        provenance={"measurement": str(rec), "width_m": 0.0075, "width_uncertainty_m": 5e-5})
    wrong.save(tmp_path / "wrong.yaml")
    assert main(["train", "--model", str(tmp_path / "wrong.yaml"), "--seeds", "1000", "--duration", "1",
                 "--output", str(tmp_path / "lib.npz"), "--no-progress"]) == 0
    out = capsys.readouterr()
    assert "further from the diagnosis" in out.err
    kept = load_library(tmp_path / "lib.npz")
    check = kept.training["check"]
    assert check["worse"] and check["kept_previous"] and not check["flagged"]
    assert kept.settings["plant_config_hash"] == load_library().settings["plant_config_hash"]
    rejected = load_library(tmp_path / "lib.rejected.npz")
    assert rejected.training["check"]["worse"]
    assert rejected.settings["plant_config_hash"] != kept.settings["plant_config_hash"]
