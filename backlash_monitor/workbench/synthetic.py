"""Recordings with hidden effects, made by the project's simulator (for the tests, the bench and the docs)."""
from __future__ import annotations

from typing import Mapping

import numpy as np

from backlash_monitor.plant import PlantSimulator, Scenario

from .measurement import Measurement


def hidden_effect_recording(model, duration_s: float, seed: int, config_overrides: Mapping | None = None,
                            scenario: Mapping | None = None, noise: bool = True) -> Measurement:
    """One drive recorded from ``model`` with extra ``config_overrides`` (the hidden effects) and
    scenario fields (width_m, eta_k, n1) changed; noise as in the paper (the model's generators)."""
    cfg = model.plant_config(config_overrides or {})
    fields = dict(model.nominal)
    fields.update(scenario or {})
    sim = PlantSimulator([Scenario(width_m=fields["width_m"], eta_k=fields["eta_k"], n1=fields["n1"],
                                   seed=int(seed))], config=cfg, noise=noise,
                         outputs=("a1", "a2", "omega1", "omega2", "angle_difference"))
    n = int(round(duration_s * cfg.simulation.sample_rate_hz))
    ch = sim.run(n)
    sig = {s: np.ascontiguousarray(getattr(ch, s)[0]) for s in ("a1", "a2", "omega1", "omega2", "angle_difference")}
    return Measurement(f"simulated(seed={seed}, hidden={dict(config_overrides or {})}, scenario={dict(scenario or {})})",
                       ch.sample_period_s, sig)
