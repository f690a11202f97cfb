"""A torque ripple, invisible in the event average, fitted from the raw a1 spectrum (workbench/ripple.py)."""
import os

import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.workbench import analysis                          # noqa: E402
from backlash_monitor.workbench.model import load_model                  # noqa: E402
from backlash_monitor.workbench.ripple import fit_torque_ripple          # noqa: E402
from backlash_monitor.workbench.synthetic import hidden_effect_recording  # noqa: E402


def _ripple(amplitude_pu, order):
    return {"effects.torque_ripple": True, "torque_ripple.amplitude_pu": amplitude_pu,
            "torque_ripple.order": order}


@pytest.mark.slow     # a 3 s recording, the model's comparison and three fit simulations: 4-6 s each
@pytest.mark.parametrize("amplitude_pu, order, seed", [(0.4, 8.0, 71), (0.8, 20.0, 72)])
def test_a_hidden_ripple_is_found_in_the_raw_spectrum_with_its_order_and_amplitude(amplitude_pu, order, seed):
    model = load_model(None)
    meas = hidden_effect_recording(model, 3.0, seed=seed, config_overrides=_ripple(amplitude_pu, order))
    comp = analysis.build_comparison(meas, model)
    fit = fit_torque_ripple(comp)
    assert fit is not None and fit["confident"], fit
    p, u = fit["parameters"], fit["uncertainty"]
    # the line sits at order x the rotation frequency; the order comes back to within a frequency bin
    assert p["order"] == pytest.approx(order, abs=max(0.3, 2 * u["order"]))
    # the amplitude from the line's power: within 10 % and within 3 of its stated uncertainties
    assert p["amplitude_pu"] == pytest.approx(amplitude_pu, rel=0.1)
    assert abs(p["amplitude_pu"] - amplitude_pu) <= 3 * u["amplitude_pu"]
    assert fit["explained_fraction"] > 0.8 and "phase_rad" in fit["not_identifiable"]


@pytest.mark.parametrize("seed", [73, 74, 75])
def test_no_ripple_is_claimed_on_a_drive_without_one(seed):
    model = load_model(None)
    meas = hidden_effect_recording(model, 3.0, seed=seed, config_overrides={})
    assert fit_torque_ripple(analysis.build_comparison(meas, model)) is None


@pytest.mark.slow
def test_diagnose_names_the_ripple_and_add_effect_puts_it_into_the_next_version(tmp_path):
    """End to end: diagnose (the event average finds nothing to add) names the ripple as its discovery, in
    its message and JSON, with the spectral fit's values; add-effect takes it into the next model version
    once; that version's own spectrum has the line (no excess line left in the comparison)."""
    import json

    from backlash_monitor.__main__ import main
    from backlash_monitor.workbench.diagnose import diagnose, public
    model = load_model(None)
    meas = hidden_effect_recording(model, 3.0, seed=76, config_overrides=_ripple(0.5, 10.0))
    # a 3-seed ensemble (diagnose's default: 6): measured to name the ripple as well, confident, amplitude 0.465 p.u.
    # (0.5 hidden), no second effect; the diagnosis ~25 % less CPU
    pub = public(diagnose(meas, model, seeds=[0, 1, 2], propose=False))
    fit = pub["spectral_discovery"]
    assert fit is not None and fit["confident"] and "torque_ripple of order" in pub["message"]
    # named like any discovery (the goal's JSON fields), with the spectral fit's values
    assert pub["discovery"] == "torque_ripple" and pub["indistinguishable"] == ["torque_ripple"]
    assert pub["discovery_parameters"]["parameters"] == fit["parameters"]
    assert pub["discovery_parameters"]["uncertainty"] == fit["uncertainty"] and pub["second_effect"] is None
    diag = tmp_path / "diag.json"
    diag.write_text(json.dumps(pub))
    v1 = model.save(tmp_path / "v1.yaml")
    v2 = tmp_path / "v2.yaml"
    assert main(["add-effect", str(diag), "--model", str(v1), "-o", str(v2)]) == 0
    new = load_model(str(v2))
    assert [a["effect"] for a in new.effects_added] == ["torque_ripple"]      # once, not twice
    cfg = new.plant_config()
    assert "torque_ripple" in {c.name for c in cfg.catalogue.enabled(cfg)}
    assert cfg.effect_parameter("torque_ripple", "amplitude_pu") == pytest.approx(fit["parameters"]["amplitude_pu"])
    assert cfg.effect_parameter("torque_ripple", "order") == pytest.approx(fit["parameters"]["order"])
    after = analysis.spectral_peaks(analysis.spectra(analysis.build_comparison(meas, new)))["a1"]["peaks_hz"]
    assert not any(abs(f - fit["line_hz"]) < 10.0 for f in after), after
