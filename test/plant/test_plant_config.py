"""Config loading and validation: bad values give a ValueError naming the key and the allowed range."""
import pytest

from backlash_monitor.plant import PlantConfig, Scenario, load_plant_config
from backlash_monitor.plant.config import DEFAULT_CONFIG_PATH


def test_defaults_file_matches_the_spec():
    cfg = load_plant_config()
    assert isinstance(cfg, PlantConfig)
    assert cfg.motor.w_pu == pytest.approx(0.374)
    assert cfg.motor.rotor_inertia_kgm2 == pytest.approx(0.1095, abs=1e-4)
    assert cfg.motor.base_mechanical_speed_rad_s == pytest.approx(157.08, abs=1e-2)
    assert cfg.load.absorber_area_m2 == 0.00311565 and cfg.load.absorber_gap_m == 1e-6
    assert cfg.clutch.contact_stiffness_Nm_per_rad == 3000 and cfg.clutch.contact_damping_Nms_per_rad == 20
    assert cfg.pulse_load.amplitude_pu == 1.6 and cfg.simulation.window_samples == 2048
    assert all(getattr(cfg.effects, n) for n in ("backlash_clutch", "spring", "absorber_power_law",
                                                  "working_resistance", "pulse_load", "gaussian_disturbance",
                                                  "pulse_disturbance"))


@pytest.mark.parametrize("overrides, key, allowed", [
    ({"motor.r_s_pu": -0.1}, "motor.r_s_pu", "0.0 < value <= 1.0"),
    ({"load.mass_kg": 0}, "load.mass_kg", "0.0 < value"),
    ({"clutch.contact_stiffness_Nm_per_rad": "stiff"}, "clutch.contact_stiffness_Nm_per_rad", "allowed"),
    ({"simulation.backend": "cuda"}, "simulation.backend", "'auto', 'numba', 'numba-scalar', 'numpy'"),
    ({"effects.spring": "yes"}, "effects.spring", "true or false"),
    ({"motor.pole_pairs": 2.5}, "motor.pole_pairs", "integer"),
    ({"disturbances.gaussian_hold_s": 1.1e-5}, "disturbances.gaussian_hold_s", "sample period"),
    ({"pulse_load.duration_s": 0.5}, "pulse_load.duration_s", "duration_s <= period_s"),
    ({"motor.x_m_pu": 1.95}, "motor.x_m_pu", "x_s_pu*x_r_pu"),
    ({"load.colour": 3}, "load.colour", "allowed keys"),
])
def test_bad_values_name_key_and_range(overrides, key, allowed):
    with pytest.raises(ValueError) as err:
        load_plant_config(overrides=overrides)
    assert key in str(err.value) and allowed in str(err.value)


def test_bad_file_and_yaml(tmp_path):
    with pytest.raises(ValueError, match="does not exist"):
        load_plant_config(tmp_path / "none.yaml")
    bad = tmp_path / "bad.yaml"
    bad.write_text("motor: [1, 2\n")
    with pytest.raises(ValueError, match="not valid YAML"):
        load_plant_config(bad)
    ok = tmp_path / "ok.yaml"
    ok.write_text(DEFAULT_CONFIG_PATH.read_text().replace("absorber_gap_m: 1.0e-6", "absorber_gap_m: 2e-6"))
    assert load_plant_config(ok).load.absorber_gap_m == 2e-6      # YAML "2e-6" (a string in YAML 1.1) accepted


def test_scenario_validation():
    with pytest.raises(ValueError, match="width_m"):
        Scenario(width_m=-1.0)
    with pytest.raises(ValueError, match="seed"):
        Scenario(0.005, seed=-3)
