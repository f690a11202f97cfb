"""Scenarios: one simulated drive (backlash width, absorber fluid, noise seed) and the paper's grid."""
from __future__ import annotations

import itertools
from dataclasses import dataclass

# Paper values (SPEC section 3)
K2_WIDTHS_M = (0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01)
ETA_K_VALUES = (0.0125, 0.025, 0.0375, 0.05)          # Pa*s^n
N1_VALUES = (0.89, 0.91, 0.93, 0.95, 0.97)
PATTERN_ETA_K = 0.025                                  # eta_k of the pattern group (paper eq. 13-14, 29-33)


@dataclass(frozen=True)
class Scenario:
    """One drive: backlash width [m], absorber consistency eta_k [Pa*s^n], flow index n1 [-], noise seed."""
    width_m: float
    eta_k: float = PATTERN_ETA_K
    n1: float = 0.89
    seed: int = 0

    def __post_init__(self):
        checks = (("width_m", self.width_m, 0.0, 1.0), ("eta_k", self.eta_k, 0.0, 100.0), ("n1", self.n1, 0.0, 3.0))
        for name, value, lo, hi in checks:
            if isinstance(value, bool) or not isinstance(value, (int, float)) or not (lo < float(value) <= hi):
                raise ValueError(f"Scenario: {name} = {value!r} is out of range; allowed: {lo} < {name} <= {hi}")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ValueError(f"Scenario: seed = {self.seed!r} is not allowed; allowed: integer >= 0")


def grid_scenarios(seeds=(0,), widths_m=K2_WIDTHS_M, eta_k_values=ETA_K_VALUES, n1_values=N1_VALUES) -> list[Scenario]:
    """The paper's grid, eta_k outer, then n1, then width (4 x 5 x 6 = 120 per seed), for each seed."""
    return [Scenario(width_m=w, eta_k=e, n1=n, seed=s)
            for s, e, n, w in itertools.product(seeds, eta_k_values, n1_values, widths_m)]


def pattern_scenarios(seeds=(0,)) -> list[Scenario]:
    """The 30 pattern scenarios: eta_k = 0.025, 5 n1 x 6 widths."""
    return grid_scenarios(seeds=seeds, eta_k_values=(PATTERN_ETA_K,))
