"""The workbench history per model version, and add-effect's nominal updates.

Fast: the rows folded from a history's entries (a version never checked says so; no blank cell), the plot; a drift
of a nominal value becomes the next version's nominal value (with its uncertainty and source), an effect stays an
effect, old model files (a stacked drift) still load and are folded when diagnosed again.
The README's own loop ending in `history` (every version's figures, no cell blank) is run by
test/commands/test_readme_commands.py.
"""
import json

import pytest
import yaml

from backlash_monitor.__main__ import main
from backlash_monitor.workbench.history import HEADER, NOT_CHECKED, version_rows
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.versions import EffectValues, add_effects


def _entries():
    return [
        {"type": "check", "model": "(unsaved)", "name": "default", "version": 1, "measurement": "/r/rec.mcap",
         "command": "diagnose", "fit_percent": {"a1": 44.2, "a2": 77.7},
         "residual_over_noise_floor": {"a1": 3.46, "a2": 3.52}, "time_utc": "2026-11-28T22:13:00+00:00"},
        {"type": "version", "model": "v2.yaml", "name": "default", "version": 2, "parent": "default v1 (unsaved)",
         "added": [{"effect": "wheel_viscous_friction", "parameters": {"damping_Nms_per_rad": 0.0086}}],
         "nominal_changed": {"n1": {"from": 0.89, "value": 0.9104, "uncertainty": 0.0004}},
         "provenance": {"diagnosis": "/r/diag.json", "diagnosis_time_utc": "2026-11-28T22:12:00+00:00"},
         "time_utc": "2026-11-28T22:14:00+00:00"},
        {"type": "version", "model": "v3.yaml", "name": "default", "version": 3, "parent": "v2.yaml",
         "added": [{"effect": "torque_ripple", "parameters": {"order": 6.0}}], "time_utc": "2026-11-28T22:20:00"},
        {"type": "monitor", "model": "v2.yaml", "name": "default", "version": 2, "library": "/r/lib_v2.npz",
         "width_m": 0.00739},
        {"type": "monitor", "model": None, "name": "default", "version": 1, "library": "/p/patterns.npz",
         "width_m": 0.00694},
    ]


def test_one_row_per_version_with_its_figures_and_a_never_checked_version_says_so(tmp_path):
    rows = version_rows(_entries())
    assert [(r.name, r.version) for r in rows] == [("default", 1), ("default", 2), ("default", 3)]
    v1, v2, v3 = (dict(zip(HEADER, r.cells())) for r in rows)
    assert v1["fit % a1/a2"] == "44.2/77.7" and v1["monitor width mm"].startswith("6.940")
    assert v2["from diagnosis"] == "diag.json of 2026-11-28 22:12"
    assert "n1 0.89 -> 0.9104 ± 0.0004" in v2["changes"] and "wheel_viscous_friction" in v2["changes"]
    assert v2["monitor width mm"].startswith("7.390") and v2["fit % a1/a2"] == NOT_CHECKED
    assert v3["fit % a1/a2"] == NOT_CHECKED and v3["resid/noise a1/a2"] == NOT_CHECKED
    assert v3["monitor width mm"] == "not trained"
    assert all(c.strip() for r in rows for c in r.cells())


def test_history_command_table_plot_and_report(tmp_path, capsys):
    (tmp_path / "workbench_history.jsonl").write_text("\n".join(json.dumps(e) for e in _entries()) + "\n")
    assert main(["history", str(tmp_path), "--plot", str(tmp_path / "h.png"), "--report", str(tmp_path / "rep")]) == 0
    out = capsys.readouterr().out
    assert "default v3" in out and NOT_CHECKED in out
    assert (tmp_path / "h.png").stat().st_size > 1000 and (tmp_path / "rep" / "history.png").is_file()
    assert "diag.json of 2026-11-28 22:12" in (tmp_path / "rep" / "index.html").read_text()
    assert main(["history", str(tmp_path), "--plot", str(tmp_path / "h.png")]) == 2     # exists: refused
    assert main(["history", str(tmp_path / "empty_dir_missing")]) == 2


def test_a_drift_of_a_nominal_value_becomes_the_nominal_value(tmp_path):
    m1 = load_model(None)
    m2 = add_effects(m1, [EffectValues("absorber_flow_index_drift", {"change": 0.02}, {"change": 0.0004},
                                       "diag.json of 2026-11-28 22:12 UTC"),
                          EffectValues("load_mass_drift", {"relative_change": 0.3}, {"relative_change": 0.01}, "d"),
                          EffectValues("wheel_coulomb_friction", {"torque_Nm": 1.5}, {"torque_Nm": 0.2}, "d")])
    m2.save(tmp_path / "v2.yaml")
    v2 = load_model(tmp_path / "v2.yaml")
    assert v2.nominal["n1"] == pytest.approx(0.91)
    cfg = v2.plant_config()
    assert cfg.load.mass_kg == pytest.approx(13.0)
    assert not cfg.effects.get("absorber_flow_index_drift") and not cfg.effects.get("load_mass_drift")
    assert cfg.effects["wheel_coulomb_friction"]                    # an added effect stays an effect
    assert [a["effect"] for a in v2.effects_added] == ["wheel_coulomb_friction"]
    n1, mass = v2.nominal_updates
    assert (n1["parameter"], n1["from"], n1["uncertainty"]) == ("n1", 0.89, pytest.approx(0.0004))
    assert n1["from_diagnosis"].startswith("diag.json")
    assert (mass["parameter"], mass["from"], mass["uncertainty"]) == ("load.mass_kg", 10.0, pytest.approx(0.1))
    # the next round moves it again from the new nominal, not from the first one
    m3 = add_effects(v2, [EffectValues("absorber_flow_index_drift", {"change": -0.01}, {}, "d2")])
    assert m3.nominal["n1"] == pytest.approx(0.90) and len(m3.nominal_updates) == 3
    # a drift with no nominal value in the config stays an effect
    m4 = add_effects(m1, [EffectValues("supply_voltage_drift", {"relative_change": -0.05})])
    assert m4.plant_config().effects["supply_voltage_drift"] and not m4.nominal_updates


def test_an_old_model_with_a_stacked_drift_still_loads_and_is_folded(tmp_path):
    old = {"workbench_model": 1, "name": "drive", "version": 2, "parent": "v1.yaml",
           "nominal": {"width_m": 0.0075, "eta_k": 0.025, "n1": 0.89},
           "plant": {"effects": {"absorber_flow_index_drift": True}, "absorber_flow_index_drift": {"change": 0.02}},
           "effects_added": [{"effect": "absorber_flow_index_drift", "parameters": {"change": 0.02}}]}
    (tmp_path / "old.yaml").write_text(yaml.safe_dump(old))
    m = load_model(tmp_path / "old.yaml")
    assert m.plant_config().effects["absorber_flow_index_drift"] and m.nominal_updates == []
    # diagnosed again: the fitted change replaces the model's own drift (a candidate's value overrides it)
    m3 = add_effects(m, [EffectValues("absorber_flow_index_drift", {"change": 0.025}, {}, "d")])
    assert m3.nominal["n1"] == pytest.approx(0.915)
    assert not m3.plant_config().effects.get("absorber_flow_index_drift")
