"""diagnose speaks drive terms (workbench/drive_terms.py): a parameter drift is shown as the drive quantity it moves
(the model's value → the fitted one ± its uncertainty, in that quantity's unit), any other parameter by its
description and unit, the width in mm with its uncertainty, near-ties with what separates them, and ΔIC, T² and
the unitless quantities explained."""
import pytest

from backlash_monitor.workbench import drive_terms
from backlash_monitor.workbench.model import load_model


@pytest.fixture(scope="module")
def model():
    return load_model(None)


def _entry(effect, pname, value, unc, unit="-", nominal=0.0, **extra):
    return {"effect": effect, "candidate": effect, "parameters": {pname: value}, "uncertainty": {pname: unc},
            "nominal": {pname: nominal}, "units": {pname: unit}, "delta_ic": -50.0, "explained_fraction": 0.99,
            "indistinguishable_from": [], "description": "", **extra}


@pytest.mark.parametrize("value, unc, text", [(0.91039, 0.00041, ("0.9104", "0.0004")),
                                              (7.4213, 0.0512, ("7.42", "0.05")),
                                              (13.02, 0.13, ("13.02", "0.13")),
                                              (1523.0, 41.0, ("1520", "40"))])
def test_value_to_the_uncertainty_digit(value, unc, text):
    assert drive_terms.significant_digits(value, unc) == text


def test_absolute_drift_is_the_quantity_it_moves(model):
    n1 = model.nominal["n1"]
    line, = drive_terms.parameter_lines(_entry("absorber_flow_index_drift", "change", 0.02039, 0.00041), model)
    assert line == f"n1: {n1:.4g} → {n1 + 0.02039:.4f} ± 0.0004"


def test_relative_drift_applies_to_the_model_value(model):
    mass = model.plant_config().load.mass_kg
    line, = drive_terms.parameter_lines(_entry("load_mass_drift", "relative_change", 0.3, 0.01), model)
    v, u = drive_terms.significant_digits(mass * 1.3, mass * 0.01)
    assert line == f"mass m: {mass:.4g} → {v} ± {u} kg"


def test_width_drift_in_mm(model):
    w = model.nominal["width_m"]
    line, = drive_terms.parameter_lines(_entry("backlash_width_drift", "change", -0.0008, 0.00005, "m"), model)
    assert line.startswith(f"backlash width: {w * 1e3:.4g} → ") and line.endswith(" mm")


def test_effect_parameter_by_its_description_and_unit(model):
    line, = drive_terms.parameter_lines(_entry("wheel_coulomb_friction", "torque_Nm", 1.52, 0.04, "N*m"), model)
    assert line == "friction torque T (torque_Nm): 0 → 1.52 ± 0.04 N·m"


def test_summary_width_near_tie_and_legend(model):
    disc = _entry("absorber_flow_index_drift", "change", 0.02, 0.0004, description="drift of the flow index")
    diag = {"verdict": "discovery", "discovery_parameters": disc, "second_effect": None, "partial_explanation": None,
            "measured_width": {"width_m": 0.00742, "uncertainty_m": 0.00005, "nominal_width_m": 0.0075,
                               "differs_from_nominal": True},
            "ranked": [disc],
            "near_ties": [{"effect": "absorber_consistency_drift", "candidate": "absorber_consistency_drift",
                           "description": "drift of eta_k", "explained_fraction": 1.0, "delta_ic": -46.1,
                           "ic_behind": 3.9, "separating_measurement": "a recording at another motor speed"}]}
    lines = drive_terms.summary_lines(diag, model)
    text = "\n".join(lines)
    assert "backlash width 7.42 ± 0.05 mm" in text
    assert "drift of the flow index" in text
    assert ("near-tie: absorber_consistency_drift also explains 100%, 3.9 IC behind" in text
            and "a recording at another motor speed" in text)
    assert drive_terms.DELTA_IC_LINE in lines and drive_terms.T2_LINE in lines
    assert not any(line.rstrip().endswith(" -") or " -)" in line for line in lines)     # no bare unit "-"
