"""The workbench on recordings with hidden effects made by the project's simulator (noise as in the paper).

Hidden: a load mass of 13 kg (model: 10 kg, load_mass_drift +0.3) -> diagnose names load_mass_drift first
(or in the indistinguishable set), the fitted mass within 5 %; after add-effect the new version's residual is
inside the noise band. (A wheel Coulomb friction of 1.5 N*m, named with its torque and retrained away: the
README's loop, test/commands/test_readme_commands.py.) Negatives: clean recordings at two
scenarios give no discovery; an effect outside the catalogue (a constant accelerometer bias on a2, not in
today's catalogue: the rotor resistance) is flagged inconsistent with a 'where' after the entry,
low-frequency (that no catalogue effect is then named is NOT guaranteed: measured, see the test).
(A constant a2 accelerometer bias is NOT a good outside-catalogue case: a spring-stiffness drift explains it
on the event average, 98 % -- measured here; docs/workbench.md.) Recordings are 3 s (12 onset events) to keep the suite short.
"""
import json

import numpy as np
import pytest

from backlash_monitor.__main__ import main
from backlash_monitor.workbench.diagnose import diagnose, public
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.synthetic import hidden_effect_recording

DURATION_S = 3.0
MASS_CHANGE = 0.3           # load_mass_drift.relative_change: 10 kg -> 13 kg
MASS_TOLERANCE = 0.05       # relative error of the fitted mass
NOISE_BAND_RATIO = 1.5      # residual / noise floor of a model that agrees (analysis.INCONSISTENT_RATIO)
# The model's noise ensemble of these diagnoses: 3 seeds (the command line's --ensemble 3), not diagnose's default 6:
# every claim here was measured to hold at 3 as well (29 Nov; a diagnosis 15-30 % less CPU): the hidden mass named
# with +0.304 +- 0.011 (+0.3 within 5 %), its recording's residual 6.8 x the noise floor before (> 3); both clean
# recordings consistent (residual 0.66 and 0.45 x the floor); the rotor resistance inconsistent, nothing explains,
# the residual in the impact phase at level a6.
ENSEMBLE = 3
SEEDS = list(range(ENSEMBLE))


def _save_npz(meas, path):
    np.savez(path, sample_period_s=meas.sample_period_s, **meas.signals)
    return path


@pytest.fixture(scope="module")
def hidden_mass(tmp_path_factory):
    d = tmp_path_factory.mktemp("wb")
    model = load_model(None)
    model.name = "drive"
    model.save(d / "v1.yaml")
    meas = hidden_effect_recording(model, DURATION_S, seed=31, config_overrides={"effects.load_mass_drift": True, "load_mass_drift.relative_change": MASS_CHANGE})
    npz = _save_npz(meas, d / "drive.npz")
    rc = main(["diagnose", str(npz), "--model", str(d / "v1.yaml"), "--json", str(d / "diag.json"),
               "--report", str(d / "report"), "--ensemble", str(ENSEMBLE)])
    assert rc == 0
    return d, json.loads((d / "diag.json").read_text())


@pytest.mark.slow
def test_hidden_mass_is_named_with_its_value(hidden_mass):
    _, diag = hidden_mass
    assert diag["discovery"] == "load_mass_drift" or "load_mass_drift" in diag["indistinguishable"], diag["message"]
    fit = next(r for r in diag["ranked"] if r["effect"] == "load_mass_drift")
    change = fit["parameters"]["relative_change"]
    assert abs((1 + change) - (1 + MASS_CHANGE)) / (1 + MASS_CHANGE) < MASS_TOLERANCE
    assert fit["uncertainty"]["relative_change"] > 0
    for key in ("effect", "parameters", "uncertainty", "delta_ic", "explained_fraction", "indistinguishable_from"):
        assert key in diag["ranked"][0]
    assert set(diag["where"]["per_phase"]) == {"before_entry", "gap_traversal", "impact", "settling"}
    assert diag["fit_percent"]["after"]["a2"] > diag["fit_percent"]["before"]["a2"]


@pytest.mark.slow
def test_add_effect_brings_the_fit_to_the_noise_band(hidden_mass):
    d, diag = hidden_mass
    assert main(["add-effect", str(d / "diag.json"), "--model", str(d / "v1.yaml"), "-o", str(d / "v2.yaml")]) == 0
    v2 = load_model(d / "v2.yaml")
    assert v2.version == 2
    if diag["discovery"] == "load_mass_drift":
        # a drift of a nominal value is the new version's nominal value, not a stacked effect
        assert not v2.effects_added and not v2.plant_config().effects.get("load_mass_drift")
        (update,) = v2.nominal_updates
        assert update["parameter"] == "load.mass_kg" and update["from"] == 10.0
        assert v2.plant_config().load.mass_kg == pytest.approx(10.0 * (1 + MASS_CHANGE), rel=MASS_TOLERANCE)
        assert update["uncertainty"] > 0 and "diag.json" in update["from_diagnosis"]
    else:
        assert v2.effects_added[0]["effect"] == diag["discovery"]
        assert v2.plant_config().effects[diag["discovery"]]
    assert main(["compare", str(d / "drive.npz"), "--model", str(d / "v2.yaml"), "--out-dir", str(d / "cmp2"),
                 "--json", str(d / "cmp2.json")]) == 0
    after = json.loads((d / "cmp2.json").read_text())
    before = diag["residual_over_noise_floor"]["before"]
    assert max(after["residual_over_noise_floor"].values()) < NOISE_BAND_RATIO
    assert max(before.values()) > 2 * NOISE_BAND_RATIO
    assert main(["history", str(d)]) == 0
    hist = [json.loads(line) for line in (d / "workbench_history.jsonl").read_text().splitlines()]
    assert any(h["type"] == "version" and h["version"] == 2 for h in hist)
    assert any(h["type"] == "check" and h["version"] == 2 for h in hist)


@pytest.mark.slow
@pytest.mark.parametrize("scenario,seed", [({"width_m": 0.005}, 41), ({"width_m": 0.0075, "eta_k": 0.0375}, 42)])
def test_clean_recordings_give_no_discovery(scenario, seed):
    model = load_model(None, width_m=scenario["width_m"], eta_k=scenario.get("eta_k"))
    meas = hidden_effect_recording(model, DURATION_S, seed=seed)
    res = public(diagnose(meas, model, seeds=SEEDS, propose=False))
    assert res["discovery"] is None, res["message"]


@pytest.mark.slow
def test_out_of_catalogue_effect_inconsistent_and_where():
    """A rotor resistance of 0.12 p.u. (model: 0.048): a motor parameter no catalogue effect changes. The
    model must be flagged inconsistent, and the residual must sit after the entry (the motor's slip response
    acts when the motor drives the load again), in the lowest wavelet bands (it is slow: tens of ms).
    No confident discovery: the catalogue effect that mimics it inside the candidates' subspace (here the
    clutch damping, 74 %) leaves the residual outside the noise band, or outside the subspace, where the
    model's own noise does not reach (docs/workbench.md, "confident"). Measured: on other recordings it
    is not always so (docs/workbench.md, "Identifiability, measured")."""
    model = load_model(None)
    meas = hidden_effect_recording(model, DURATION_S, seed=43, config_overrides={"motor.r_r_pu": 0.12})
    res = public(diagnose(meas, model, seeds=SEEDS, propose=False))
    assert res["model_inconsistent"], res["residual_over_noise_floor"]
    assert res["discovery"] is None, res["message"]
    assert res["where"]["dominant_phase"] != "before_entry"
    assert res["where"]["dominant_level"] in ("a6", "d6")
