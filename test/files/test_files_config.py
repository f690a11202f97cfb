"""files.config.config_file: the one place the packaged config files are found (the windowing,
plant and trend loaders use it): the source tree's config/NAME, else the installed package's."""
from pathlib import Path

from backlash_monitor.files import config as files_config
from backlash_monitor.files.config import config_file

REPO = Path(__file__).resolve().parents[2]


def test_the_source_tree_config_is_found_first():
    for name in ("windowing.yaml", "plant.yaml", "trend.yaml"):
        assert config_file(name) == REPO / "config" / name


def test_the_installed_config_is_found_without_a_source_tree(tmp_path, monkeypatch):
    share = tmp_path / "share" / "config"
    share.mkdir(parents=True)
    (share / "trend.yaml").write_text("warn_growth_m_per_day: 1.0e-5\n")
    monkeypatch.setattr(files_config, "SOURCE_CONFIG_DIR", tmp_path / "no_checkout")
    monkeypatch.setattr(files_config, "_share_config_dir", lambda: share)
    assert config_file("trend.yaml") == share / "trend.yaml"
    # in neither: the source tree's path, which the loaders' errors name
    assert config_file("plant.yaml") == tmp_path / "no_checkout" / "plant.yaml"


def test_every_loader_finds_its_default_through_the_locator():
    from backlash_monitor.fleet import trend
    from backlash_monitor.plant import config as plant_config
    from backlash_monitor.windowing import config as windowing_config

    assert windowing_config.DEFAULT_CONFIG_PATH == config_file("windowing.yaml")
    assert plant_config.DEFAULT_CONFIG_PATH == config_file("plant.yaml")
    assert trend._default_path() == str(config_file("trend.yaml"))
    # and they read those files: a value only the YAML files hold
    assert trend.load_rule().warn_width_m > 0
    assert plant_config.load_plant_config().load.mass_kg > 0
