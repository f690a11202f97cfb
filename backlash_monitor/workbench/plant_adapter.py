"""The workbench's one door to the plant simulator: the candidate catalogue and batched, shared-noise runs.

Everything the workbench needs from ``backlash_monitor.plant`` goes through this module, so that moving
to the plug-in effects API (issue 10: ``plant.effects.catalogue()``, ``PlantSimulator(parameters=...,
noise_seed=...)``) changes this file only.

Today's bridge (until that API is on this branch):

- the catalogue holds the effects today's config can express: drifts of the model's parameters
  (scenario fields width/eta_k/n1, config keys such as ``load.mass_kg``) and the built-in switchable
  ``constant_motor_load`` term as ``motor_load_offset``;
- a parameter set that changes a config key needs its own ``PlantSimulator`` (the config is global to a
  simulator); sets that only change scenario fields share one batch;
- common random numbers: today each scenario's noise seed is derived from its width, eta_k and n1, so
  two candidate widths would get different noise. :func:`_shared_noise` replaces that derivation, for
  the duration of one batch, by one that uses the scenario's seed only (the effects API's
  ``noise_seed=`` does this properly; this is the only place that reaches into plant internals).
"""
from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from backlash_monitor.plant import PlantSimulator, Scenario
from backlash_monitor.plant import simulate as _plant_simulate

SIGNALS = ("a1", "a2", "omega1", "omega2", "angle_difference")


@dataclass(frozen=True)
class EffectParameter:
    name: str          # short name, e.g. "mass_kg"
    unit: str
    default: float     # the model's current value (the effect "off" = this value for a drift)
    lower: float
    upper: float
    target: str        # "scenario.<field>" or "config.<section.key>" (where the value goes today)


@dataclass(frozen=True)
class CandidateEffect:
    name: str
    balance: str
    description: str
    parameters: tuple[EffectParameter, ...]
    switch: str | None = None          # config key switched on with the effect (None: a drift)
    identifiable_note: str = ""

    def full_names(self) -> list[str]:
        return [f"{self.name}.{p.name}" for p in self.parameters]

    def default_vector(self) -> np.ndarray:
        return np.array([p.default for p in self.parameters])

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([p.lower for p in self.parameters]), np.array([p.upper for p in self.parameters])


def _drift(name, balance, desc, pname, unit, target, value, lo_factor, hi_factor, lo_abs=None, hi_abs=None):
    lo = value * lo_factor if lo_abs is None else lo_abs
    hi = value * hi_factor if hi_abs is None else hi_abs
    return CandidateEffect(name, balance, desc, (EffectParameter(pname, unit, float(value), float(lo), float(hi),
                                                                 target),))


def catalogue(model) -> list[CandidateEffect]:
    """The candidate effects the workbench can fit on ``model`` (a WorkbenchModel), defaults = its values."""
    cfg = model.plant_config()
    n = model.nominal
    return [
        _drift("backlash_width", "clutch_torque_Nm", "drift of the backlash width (the gap the clutch crosses)",
               "width_m", "m", "scenario.width_m", n["width_m"], 0.6, 1.4),
        _drift("absorber_consistency", "rim_mass_force_N", "drift of the absorber fluid's consistency eta_k",
               "eta_k", "Pa*s^n", "scenario.eta_k", n["eta_k"], 0.4, 2.5),
        _drift("absorber_flow_index", "rim_mass_force_N", "drift of the absorber fluid's flow index n1",
               "n1", "-", "scenario.n1", n["n1"], 0.0, 0.0, lo_abs=max(0.8, n["n1"] - 0.1),
               hi_abs=min(1.1, n["n1"] + 0.1)),
        _drift("spring_stiffness", "rim_mass_force_N", "drift of the load spring's stiffness k",
               "stiffness_N_per_m", "N/m", "config.load.spring_stiffness_N_per_m",
               cfg.load.spring_stiffness_N_per_m, 0.25, 4.0),
        _drift("load_mass", "mass_force_N", "drift of the load mass m", "mass_kg", "kg", "config.load.mass_kg",
               cfg.load.mass_kg, 0.5, 2.0),
        _drift("wheel_inertia", "wheel_torque_Nm", "drift of the load wheel's inertia J2", "inertia_kgm2", "kg*m^2",
               "config.load.wheel_inertia_kgm2", cfg.load.wheel_inertia_kgm2, 0.5, 2.0),
        _drift("working_resistance", "mass_force_N", "drift of the constant working resistance F0 on the mass",
               "force_N", "N", "config.load.working_resistance_N", cfg.load.working_resistance_N, 0.0, 0.0,
               lo_abs=0.0, hi_abs=max(3.0 * cfg.load.working_resistance_N, 30.0)),
        _drift("pulse_amplitude", "motor_load_moment_pu", "drift of the system load's pulse amplitude",
               "amplitude_pu", "p.u.", "config.pulse_load.amplitude_pu", cfg.pulse_load.amplitude_pu, 0.7, 1.3),
        _drift("clutch_contact_stiffness", "clutch_torque_Nm", "drift of the clutch's contact stiffness k_c",
               "stiffness_Nm_per_rad", "N*m/rad", "config.clutch.contact_stiffness_Nm_per_rad",
               cfg.clutch.contact_stiffness_Nm_per_rad, 0.5, 2.0),
        _drift("clutch_contact_damping", "clutch_torque_Nm", "drift of the clutch's contact damping d_c",
               "damping_Nms_per_rad", "N*m*s/rad", "config.clutch.contact_damping_Nms_per_rad",
               cfg.clutch.contact_damping_Nms_per_rad, 0.25, 4.0),
        CandidateEffect("motor_load_offset", "motor_load_moment_pu",
                        "a constant extra load moment on the motor (e.g. bearing drag)",
                        (EffectParameter("load_pu", "p.u.", float(cfg.constant_motor_load_pu
                                                                  if cfg.effects.constant_motor_load else 0.0),
                                         -0.4, 0.4, "config.constant_motor_load_pu"),),
                        switch="effects.constant_motor_load"),
    ]


def effect_by_name(model, name: str) -> CandidateEffect:
    effects = {e.name: e for e in catalogue(model)}
    if name not in effects:
        raise ValueError(f"effect {name!r} is not in the catalogue; allowed: {', '.join(effects)}")
    return effects[name]


def apply_values(effect: CandidateEffect, values) -> tuple[dict, dict]:
    """(scenario field overrides, config overrides) that put ``values`` (one per parameter) into a model."""
    scen, conf = {}, {}
    for p, v in zip(effect.parameters, np.atleast_1d(values)):
        kind, key = p.target.split(".", 1)
        (scen if kind == "scenario" else conf)[key] = float(v)
    if effect.switch:
        conf[effect.switch] = True
    return scen, conf


@contextlib.contextmanager
def _shared_noise():
    """Noise seed from the scenario's ``seed`` only (common random numbers across parameter values)."""
    original = _plant_simulate._noise_seed

    def seed_only(s):
        return int(np.random.SeedSequence([s.seed, 0x3C0DE]).generate_state(1, np.uint32)[0])

    _plant_simulate._noise_seed = seed_only
    try:
        yield
    finally:
        _plant_simulate._noise_seed = original


def simulate_sets(model, sets: Sequence[tuple[Mapping, Mapping]], seeds: Sequence[int], n_samples: int,
                  conditions: Mapping | None = None, noise: bool = True,
                  signals: Sequence[str] = ("a1", "a2", "omega1", "angle_difference")) -> dict[str, np.ndarray]:
    """Run every parameter set x every seed on shared noise; -> {signal: (n_sets, n_seeds, n_samples)}.

    ``sets``: (scenario overrides, config overrides) per set, as :func:`apply_values` gives (merged on top
    of the model). ``conditions``: config overrides of the measurement (e.g. the recovered pulse timing).
    Sets with the same config overrides run as one batch.
    """
    seeds = [int(s) for s in seeds]
    groups: dict[str, list[int]] = {}
    for i, (_, conf) in enumerate(sets):
        groups.setdefault(repr(sorted(conf.items())), []).append(i)
    out = {s: np.empty((len(sets), len(seeds), n_samples)) for s in signals}
    with _shared_noise():
        for idx in groups.values():
            conf = dict(conditions or {})
            conf.update(sets[idx[0]][1])
            cfg = model.plant_config(conf)
            scen = []
            for i in idx:
                fields = dict(model.nominal)
                fields.update(sets[i][0])
                scen += [Scenario(width_m=fields["width_m"], eta_k=fields["eta_k"], n1=fields["n1"], seed=s)
                         for s in seeds]
            sim = PlantSimulator(scen, config=cfg, noise=noise, outputs=tuple(signals))
            ch = sim.run(n_samples)
            for s in signals:
                arr = getattr(ch, s).reshape(len(idx), len(seeds), n_samples)
                out[s][idx] = arr
    return out
