"""The plant simulator's physics core (SPEC section 3): pure numpy (+ optional numba), no ROS.

    from backlash_monitor.plant import load_plant_config, Scenario, PlantSimulator, grid_scenarios
    sim = PlantSimulator(grid_scenarios(), config=load_plant_config(), noise=True)
    chunk = sim.run(5000)        # 0.1 s of every scenario at 50 kHz

Equations and measured figures: docs/model.md.

The names below are loaded on first use (PEP 562): the simulator pulls in numba and scipy.optimize (~1 s at
start-up, python -X importtime, 29 Nov), which a command's --help or the paper's grid constants
(``plant.scenarios``) do not need.
"""
from __future__ import annotations

import importlib

# public name -> the module of this package that holds it
_HOME = {
    "PlantConfig": "config", "load_plant_config": "config", "config_from_dict": "config",
    "DEFAULT_CONFIG_PATH": "config",
    "BALANCES": "effects", "Effect": "effects", "Parameter": "effects",
    "EffectCatalogue": "catalogue", "builtin_catalogue": "catalogue",
    "K2_WIDTHS_M": "scenarios", "ETA_K_VALUES": "scenarios", "N1_VALUES": "scenarios",
    "PATTERN_ETA_K": "scenarios", "Scenario": "scenarios", "grid_scenarios": "scenarios",
    "pattern_scenarios": "scenarios",
    "PlantSimulator": "simulate", "SimulationChunk": "simulate", "simulate_batch": "simulate",
    "find_entries": "simulate", "ENTRY_ONSET": "simulate", "ENTRY_RETURN": "simulate",
}

__all__ = list(_HOME)


def __getattr__(name: str):
    home = _HOME.get(name)
    if home is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{home}"), name)
    globals()[name] = value          # the next lookup is a plain attribute
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
