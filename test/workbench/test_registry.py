"""The drive registry (files/registry.py, docs/registry.md): one YAML that is also the fleet file; the workbench
commands find a drive's model there (--drive), train registers a new version, the fleet takes library and
reference from it. Fast: no simulation."""
import pytest
import yaml

from backlash_monitor.__main__ import main
from backlash_monitor.files import registry
from backlash_monitor.fleet.drives import load_drives
from backlash_monitor.workbench.model import load_model

REGISTRY = {"defaults": {"n1": 0.89, "eta_k": 0.025},
            "lines": {"line1": {"drive01": {"width_m": 0.0025, "seed": 1},
                                "drive02": {"width_m": 0.006, "eta_k": 0.05, "n1": 0.93, "seed": 2,
                                            "model": "m/drive02_v3.yaml", "library": "m/drive02_v3.npz",
                                            "watch_reference": "m/drive02_v3.watch.npz",
                                            "versions": [{"version": 1, "model": None, "library": None,
                                                          "watch_reference": None}]}},
                      "line2": {"drive01": {"width_m": 0.005, "seed": 3}}}}


@pytest.fixture
def reg(tmp_path):
    p = tmp_path / "drives.yaml"
    p.write_text(yaml.safe_dump(REGISTRY))
    return p


def test_entries_find_and_match(reg, tmp_path):
    drives = registry.entries(reg)
    assert [d.hardware_id for d in drives] == ["line1/drive01", "line1/drive02", "line2/drive01"]
    d2 = registry.find(reg, "drive02")
    assert d2.nominal == {"width_m": 0.006, "eta_k": 0.05, "n1": 0.93} and d2.version == 2
    assert d2.model == tmp_path / "m" / "drive02_v3.yaml" and d2.library == tmp_path / "m" / "drive02_v3.npz"
    assert registry.find(reg, "/line2/drive01").parameters["width_m"] == 0.005
    with pytest.raises(registry.RegistryError, match="2 drives of that name.*line1/drive01"):
        registry.find(reg, "drive01")
    with pytest.raises(registry.RegistryError, match="no such drive.*allowed: line1/drive01"):
        registry.find(reg, "drive09")
    assert registry.match(drives, namespace="/line1/drive02").name == "drive02"
    assert registry.match(drives, drive_name="line2/drive01").line == "line2"
    assert registry.match(drives, namespace="/plant", drive_name="") is None


def test_register_keeps_the_versions_before(reg, tmp_path):
    (tmp_path / "m").mkdir()
    entry = registry.register(reg, "line1/drive02", model=tmp_path / "m" / "v4.yaml", library=tmp_path / "m" / "v4.npz",
                              watch_reference=tmp_path / "m" / "v4.watch.npz")
    assert entry.version == 3 and entry.model == tmp_path / "m" / "v4.yaml"
    assert entry.versions[-1]["model"] == "m/drive02_v3.yaml" and entry.versions[-1]["until_utc"]
    data = yaml.safe_load(reg.read_text())
    assert data["lines"]["line1"]["drive02"]["library"] == "m/v4.npz"
    assert data["lines"]["line1"]["drive01"] == REGISTRY["lines"]["line1"]["drive01"]   # the others untouched


def test_the_fleet_reads_the_registry_as_its_fleet_file(reg, tmp_path):
    drives = {d.hardware_id: d for d in load_drives(str(reg))}
    params = drives["line1/drive02"].node_parameters()
    assert params["classifier"]["library"] == str(tmp_path / "m" / "drive02_v3.npz")
    assert params["model_watch"]["reference"] == str(tmp_path / "m" / "drive02_v3.watch.npz")
    assert params["model_watch"]["n1"] == 0.93
    assert "library" not in drives["line1/drive01"].node_parameters()["classifier"]


def test_add_effect_and_history_with_drive(reg, tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["add-effect", "wheel_coulomb_friction", "--value", "torque_Nm=1.2", "--drive", "line2/drive01"]) == 0
    v2 = load_model(tmp_path / "line2_drive01_v2.yaml")
    assert v2.name == "line2_drive01" and v2.nominal["width_m"] == 0.005 and v2.version == 2
    assert main(["history", "--drive", "line2/drive01"]) == 0
    out = capsys.readouterr().out
    assert "line2_drive01 v2" in out and "not checked" in out
    assert main(["history", "--drive", "nobody", "--registry", str(reg)]) == 2
    assert "no such drive" in capsys.readouterr().err
    assert main(["history", "--drive", "line1/drive01", "--registry", str(tmp_path / "missing.yaml")]) == 2


def test_analyze_holds_each_bag_against_its_own_drive(reg, tmp_path):
    """analyze FOLDER --registry: a bag is matched by its namespace or drive name; its reference is its drive's
    (or the default model's at the drive's nominal conditions); a bag of no drive falls back and is named."""
    import argparse

    from backlash_monitor.commands.analyze import registry_drives
    from backlash_monitor.fleet.folder_analysis import WatchOptions, reference_for_bag, registered_drive
    from backlash_monitor.offline.bag_analysis import AnalyzeOptions
    from backlash_monitor.workbench import reference
    watch = WatchOptions(drives=registry_drives(argparse.Namespace(registry=str(reg))))
    opts = AnalyzeOptions()
    row2 = {"drive": "whatever", "namespace": "/line1/drive02"}
    assert registered_drive(watch, row2)[0] == "line1/drive02"
    assert reference_for_bag(opts, watch, 0.006, row2) == str(tmp_path / "m" / "drive02_v3.watch.npz")
    row1 = {"drive": "line2/drive01", "namespace": ""}
    own = reference.cache_path(load_model(None, width_m=0.005, eta_k=0.025, n1=0.89))
    assert reference_for_bag(opts, watch, 0.0071, row1) == str(own)
    stranger = {"drive": "press7", "namespace": "/press7"}
    assert registered_drive(watch, stranger) is None
    assert reference_for_bag(opts, watch, 0.005, stranger) == reference_for_bag(opts, WatchOptions(), 0.005, stranger)


def test_pipeline_takes_the_drive_from_the_registry(reg, tmp_path):
    import argparse

    from backlash_monitor.nodes import pipeline
    parser = argparse.ArgumentParser()
    pipeline.add_arguments(parser)
    args = parser.parse_args(["--watch", "--drive", "line1/drive02", "--registry", str(reg)])
    pipeline.apply_registry(args)
    assert (args.width_m, args.eta_k, args.n1) == (0.006, 0.05, 0.93) and args.drive_name == "line1/drive02"
    assert args.library == str(tmp_path / "m" / "drive02_v3.npz") and args.model == str(tmp_path / "m" / "drive02_v3.yaml")
    assert pipeline.watch_reference(args) == str(tmp_path / "m" / "drive02_v3.watch.npz")
    node = pipeline.node_parameters(args)
    assert node["classifier"]["library"] == args.library and node["plant_simulator"]["width_m"] == 0.006


def test_train_drive_defaults_and_refusals(reg, tmp_path, capsys):
    import argparse

    from backlash_monitor.commands import train
    parser = argparse.ArgumentParser()
    train.add_arguments(parser)
    args = parser.parse_args(["--drive", "line1/drive02", "--registry", str(reg)])
    entry = train._drive_defaults(args)
    assert entry.hardware_id == "line1/drive02" and args.model == [str(tmp_path / "m" / "drive02_v3.yaml")]
    assert args.output == str(tmp_path / "m" / "drive02_v3.npz")
    assert args.previous_library == str(tmp_path / "m" / "drive02_v3.npz")
    # a drive without a model file needs --model (the version to register)
    assert main(["train", "--drive", "line2/drive01", "--registry", str(reg)]) == 2
    assert "has no model file" in capsys.readouterr().err
