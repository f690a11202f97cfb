"""The workbench commands never destroy data: no output over an input (the measurement, the model),
none over an existing file without --overwrite; refused before any work, with exit code 2."""
import numpy as np
import yaml

from backlash_monitor.__main__ import main
from backlash_monitor.workbench.model import load_model


def _model(tmp_path):
    m = load_model(None)
    m.name = "drive"
    return m.save(tmp_path / "v1.yaml")


def test_add_effect_refuses_to_replace_its_own_model(tmp_path, capsys):
    v1 = _model(tmp_path)
    before = v1.read_text()
    rc = main(["add-effect", "wheel_coulomb_friction", "--value", "torque_Nm=1.5", "--model", str(v1), "-o", str(v1)])
    assert rc == 2
    assert "is the input" in capsys.readouterr().err
    assert v1.read_text() == before


def test_add_effect_existing_output_needs_overwrite(tmp_path, capsys):
    v1 = _model(tmp_path)
    v2 = tmp_path / "v2.yaml"
    v2.write_text("mine\n")
    args = ["add-effect", "wheel_coulomb_friction", "--value", "torque_Nm=1.5", "--model", str(v1), "-o", str(v2)]
    assert main(args) == 2
    assert "--overwrite" in capsys.readouterr().err and v2.read_text() == "mine\n"
    assert main(args + ["--overwrite"]) == 0
    written = yaml.safe_load(v2.read_text())
    assert written["version"] == 2


def test_diagnose_and_compare_refuse_existing_outputs_before_any_work(tmp_path, capsys):
    meas = tmp_path / "drive.npz"
    np.savez(meas, a1=np.zeros(10))             # never read: the refusal comes first
    taken = tmp_path / "diag.json"
    taken.write_text("{}")
    assert main(["diagnose", str(meas), "--json", str(taken)]) == 2
    assert "exists already" in capsys.readouterr().err and taken.read_text() == "{}"
    assert main(["diagnose", str(meas), "--json", str(meas)]) == 2
    assert "is the input" in capsys.readouterr().err
    out = tmp_path / "cmp"
    out.mkdir()
    (out / "compare.json").write_text("{}")
    assert main(["compare", str(meas), "--out-dir", str(out)]) == 2
    assert "exists already" in capsys.readouterr().err and (out / "compare.json").read_text() == "{}"
