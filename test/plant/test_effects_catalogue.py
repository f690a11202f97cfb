"""The effect catalogue as an object (plant/catalogue.py): the built-in one never changes, a user's plug-ins
go into a copy that the config carries, and generated kernels are shared by term source, not by catalogue."""
import copy
import pickle
from pathlib import Path

import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.catalogue import EffectCatalogue, builtin_catalogue
from backlash_monitor.plant.codegen import HAVE_NUMBA
from backlash_monitor.plant.effects import CATALOGUE, NOMINAL
from backlash_monitor.plant.simulate import check_runtime_change

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "my_effects.py"
QUADRATIC = """from backlash_monitor.plant.effects import Effect, Parameter
from backlash_monitor.plant.mathlib import fabs

class WheelDrag(Effect):
    name = "wheel_drag"
    balance = "wheel_torque_Nm"
    description = "drag on the wheel, -c*Omega2*|Omega2|"
    parameters = (Parameter("c", "N*m*s^2/rad^2", 0.0, (0.0, 1.0), "drag coefficient"),)

    @staticmethod
    def term(omega2, c):
        return -c * omega2 * fabs(omega2)
"""
LINEAR = QUADRATIC.replace("return -c * omega2 * fabs(omega2)", "return -c * omega2").replace(
    '"drag on the wheel, -c*Omega2*|Omega2|"', '"drag on the wheel, -c*Omega2"')
ON = {"simulation.run_in_s": 0.0, "effects.wheel_drag": True, "wheel_drag.c": 1e-3}


def _file(directory: Path, name: str, text: str) -> Path:
    directory.mkdir(parents=True, exist_ok=True)
    p = directory / name
    p.write_text(text)
    return p


def test_builtin_catalogue_holds_nominal_and_catalogue_and_never_changes(tmp_path):
    base = builtin_catalogue()
    assert base.names[:len(NOMINAL) + len(CATALOGUE)] == tuple(c.name for c in NOMINAL + CATALOGUE)
    assert base.frozen and builtin_catalogue() is base
    with pytest.raises(ValueError, match="cannot change .*; allowed: .*copy"):
        base.register(CATALOGUE[0], replace=True)
    with pytest.raises(ValueError, match="cannot change"):
        base.load_effects_file(EXAMPLE)
    mine = base.with_files([EXAMPLE])
    assert {"wheel_drag", "my_viscous_wheel"} <= set(mine) and "wheel_drag" not in base
    assert mine.names[:len(base)] == base.names               # the built-in order first, plug-ins after
    assert base.with_files([]) is base


def test_config_carries_the_catalogue_it_was_validated_against():
    mine = builtin_catalogue().with_files([EXAMPLE])
    with pytest.raises(ValueError, match=r"unknown key effects\.wheel_drag .*--effects-file"):
        load_plant_config(overrides={"effects.wheel_drag": True})       # the built-in catalogue has no wheel_drag
    cfg = load_plant_config(overrides={"effects.wheel_drag": True}, catalogue=mine)
    assert cfg.catalogue is mine and load_plant_config().catalogue is builtin_catalogue()
    again = cfg.with_overrides({"wheel_drag.coefficient_Nms2_per_rad2": 0.5})
    assert again.catalogue is mine and again.effect_parameter("wheel_drag", "coefficient_Nms2_per_rad2") == 0.5
    assert cfg.effects["my_viscous_wheel"] is False           # known to this config's catalogue, switched off
    with pytest.raises(KeyError):
        load_plant_config().effects["my_viscous_wheel"]       # unknown to the built-in one
    assert [c.name for c in mine.enabled(cfg, "term")][-1] == "wheel_drag"
    with pytest.raises(ValueError, match="not in this catalogue"):
        builtin_catalogue().enabled(cfg)
    for other in (copy.deepcopy(cfg), pickle.loads(pickle.dumps(cfg))):
        assert other == cfg and other.catalogue.names == mine.names
        assert other.catalogue["wheel_drag"] is mine["wheel_drag"]


def test_file_rules_same_file_twice_and_a_taken_name(tmp_path):
    mine = builtin_catalogue().copy()
    assert mine.load_effects_file(EXAMPLE) == mine.load_effects_file(EXAMPLE)   # the same file twice: no error
    n = len(mine)
    other = _file(tmp_path, "other.py", QUADRATIC)
    with pytest.raises(ValueError, match="'wheel_drag' is already registered .*allowed: a new name"):
        mine.load_effects_file(other)                          # another wheel_drag (another parameter)
    assert len(mine) == n                                      # all or none
    with pytest.raises(ValueError, match="unknown effect 'wheel_drg' \\(nearest: 'wheel_drag'\\); allowed: "):
        mine.get("wheel_drg")
    with pytest.raises(ValueError, match="does not exist"):
        mine.load_effects_file(tmp_path / "missing.py")


def test_catalogues_share_a_kernel_by_term_source_and_same_names_do_not_collide(tmp_path):
    """Two catalogues from one file hold the same classes (one kernel); the same file content under two paths
    gives other classes but the same generated source (one kernel file and module); another term under the
    same name gives another kernel and other signals."""
    quad_a = _file(tmp_path / "a", "drag.py", QUADRATIC)
    quad_b = _file(tmp_path / "b", "drag.py", QUADRATIC)
    lin = _file(tmp_path / "c", "drag.py", LINEAR)
    cats = {k: builtin_catalogue().with_files([p]) for k, p in
            (("quad_a", quad_a), ("quad_a_again", quad_a), ("quad_b", quad_b), ("lin", lin))}
    assert cats["quad_a"] is not cats["quad_a_again"]
    assert cats["quad_a"]["wheel_drag"] is cats["quad_a_again"]["wheel_drag"]
    assert cats["quad_a"]["wheel_drag"] is not cats["quad_b"]["wheel_drag"]
    scen = [Scenario(0.005, seed=3)]
    sims = {k: PlantSimulator(scen, config=load_plant_config(overrides=ON, catalogue=c), noise=True, backend="numpy")
            for k, c in cats.items()}
    assert sims["quad_a"].kernel is sims["quad_a_again"].kernel
    if HAVE_NUMBA:
        assert sims["quad_b"].kernel.path == sims["quad_a"].kernel.path
        assert sims["quad_b"].kernel.module is sims["quad_a"].kernel.module
        assert sims["lin"].kernel.path != sims["quad_a"].kernel.path
    out = {k: s.run(1000) for k, s in sims.items()}      # 20 ms: the drags differ by ~22 N*m (below)
    assert np.array_equal(out["quad_a"].a1, out["quad_b"].a1)
    # Omega2 ~ 150 rad/s: c*Omega2*|Omega2| ~ 22 N*m against c*Omega2 ~ 0.15 N*m, so the wheel runs otherwise
    assert not np.allclose(out["lin"].omega2, out["quad_a"].omega2, rtol=1e-6)


def test_runtime_change_refuses_another_class_under_the_same_name(tmp_path):
    quad = builtin_catalogue().with_files([_file(tmp_path / "a", "drag.py", QUADRATIC)])
    lin = builtin_catalogue().with_files([_file(tmp_path / "b", "drag.py", LINEAR)])
    running = load_plant_config(overrides=ON, catalogue=quad)
    check_runtime_change(running, running.with_overrides({"wheel_drag.c": 0.5}))
    with pytest.raises(ValueError, match="'wheel_drag' is another class"):
        check_runtime_change(running, load_plant_config(overrides=ON, catalogue=lin))


def test_a_catalogue_of_ones_own_classes():
    """A catalogue built by hand: the default config/plant.yaml names the built-in catalogue's effects, so a
    catalogue without them refuses it by name; with them it gives the built-in model."""
    nominal_only = EffectCatalogue(NOMINAL)
    assert nominal_only.names == tuple(c.name for c in NOMINAL) and not nominal_only.frozen
    with pytest.raises(ValueError, match="unknown key effects.wheel_coulomb_friction"):
        load_plant_config(catalogue=nominal_only)
    own = EffectCatalogue(NOMINAL + CATALOGUE)
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0}, catalogue=own)
    assert cfg.catalogue is own and [c.name for c in own.enabled(cfg)] == [c.name for c in NOMINAL if c.nominal]
    scen = [Scenario(0.005, seed=4)]
    ref = PlantSimulator(scen, config=load_plant_config(overrides={"simulation.run_in_s": 0.0}), noise=True,
                         backend="numpy").run(500)
    mine = PlantSimulator(scen, config=cfg, noise=True, backend="numpy").run(500)
    assert np.array_equal(ref.a1, mine.a1) and np.array_equal(ref.a2, mine.a2)
