"""config/windowing.yaml and the code defaults agree; unknown keys are rejected."""
import pytest

from backlash_monitor.windowing import DEFAULT_CONFIG_PATH, DEFAULTS, BacklashEntryDetector, load_windowing_config


def test_yaml_matches_defaults():
    assert DEFAULT_CONFIG_PATH.is_file()
    cfg = load_windowing_config(DEFAULT_CONFIG_PATH)
    assert cfg == {sec: dict(v) for sec, v in DEFAULTS.items()}


def test_from_config_builds_detector():
    det = BacklashEntryDetector.from_config(load_windowing_config()["detector"], trigger="paper", width_m=0.005)
    assert det.beta == pytest.approx(0.005 / 0.15)


def test_unknown_key_rejected(tmp_path):
    p = tmp_path / "w.yaml"
    p.write_text("detector:\n  confirm_radd: 1\n")
    with pytest.raises(ValueError, match="confirm_radd"):
        load_windowing_config(p)
