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


def test_effect_text_is_the_parameter_lines_and_the_description(model):
    entry = _entry("wheel_coulomb_friction", "torque_Nm", 1.52, 0.04, "N*m", description="dry friction at the wheel")
    assert drive_terms.effect_text(entry, model) == ("wheel_coulomb_friction — friction torque T (torque_Nm): "
                                                     "0 → 1.52 ± 0.04 N·m (dry friction at the wheel)")


N1_CHANGE = 0.05            # the recorded drive's flow index: the model's n1 + this


@pytest.mark.slow
def test_diagnosed_n1_drift_message_reads_in_drive_terms():
    """A drive whose absorber flow index n1 is higher than the model's: the verdict message gives the drift as n1
    moving from the model's value to the fitted one (value and uncertainty from the diagnosis itself), with the
    effect's description, and no unit for the dimensionless n1."""
    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.synthetic import hidden_effect_recording
    model = load_model(None)
    n1 = model.nominal["n1"]
    meas = hidden_effect_recording(model, 3.0, seed=7, scenario={"n1": n1 + N1_CHANGE})
    pub = diagnose(meas, model, effects=["absorber_flow_index_drift"], second=False, propose=False).to_json()
    message = pub["message"]
    assert pub["discovery"] == "absorber_flow_index_drift", message
    disc = pub["discovery_parameters"]
    change, unc = disc["parameters"]["change"], disc["uncertainty"]["change"]
    value, u = drive_terms.significant_digits(n1 + change, unc)
    assert f"missing effect: absorber_flow_index_drift — n1: {n1:.4g} → {value} ± {u} (" in message, message
    assert disc["description"] and disc["description"] in message
    assert " -)" not in message and "change =" not in message
    # the fit finds the drive's n1 (measured: change 0.0479 ± 0.0013 for the recorded 0.05, seed 7)
    assert abs(change - N1_CHANGE) < 0.1 * N1_CHANGE, (change, unc)


def test_an_explained_share_above_one_is_shown_as_all_of_it(model):
    """The share is of the residual's excess over the noise (fitting.Problem.explained_share): a fit into the noise of
    a nearly clean drive scores above 1 (measured 1.20); the message never says "explains 120 %", the JSON keeps it."""
    assert drive_terms.explained_percent(1.2) == "100%"
    assert drive_terms.explained_percent(0.958) == "96%"
    entry = _entry("backlash_width_drift", "change", 1e-4, 1e-4, unit="m", explained_fraction=1.2)
    text = "\n".join(drive_terms.effect_lines(entry, model))
    assert "explains 100% of the residual" in text and "120" not in text
