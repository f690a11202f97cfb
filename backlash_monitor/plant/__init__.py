"""The plant simulator's physics core (SPEC section 3): pure numpy (+ optional numba), no ROS.

    from backlash_monitor.plant import load_plant_config, Scenario, PlantSimulator, grid_scenarios
    sim = PlantSimulator(grid_scenarios(), config=load_plant_config(), noise=True)
    chunk = sim.run(5000)        # 0.1 s of every scenario at 50 kHz

Equations and measured figures: docs/model.md.
"""
from .config import PlantConfig, load_plant_config, config_from_dict, DEFAULT_CONFIG_PATH
from .effects import BALANCES, Effect, Parameter
from .catalogue import EffectCatalogue, builtin_catalogue
from .scenarios import (K2_WIDTHS_M, ETA_K_VALUES, N1_VALUES, PATTERN_ETA_K, Scenario, grid_scenarios,
                        pattern_scenarios)
from .simulate import PlantSimulator, SimulationChunk, simulate_batch, find_entries, ENTRY_ONSET, ENTRY_RETURN

__all__ = ["PlantConfig", "load_plant_config", "config_from_dict", "DEFAULT_CONFIG_PATH", "BALANCES",
           "Effect", "Parameter", "EffectCatalogue", "builtin_catalogue", "K2_WIDTHS_M", "ETA_K_VALUES",
           "N1_VALUES", "PATTERN_ETA_K", "Scenario", "grid_scenarios",
           "pattern_scenarios", "PlantSimulator", "SimulationChunk", "simulate_batch", "find_entries",
           "ENTRY_ONSET", "ENTRY_RETURN"]
