"""How much each catalogue effect changes a1/a2 (docs/effects.md, "Identifiability"): one batch, the whole
catalogue compiled once, every scenario on the same noise (common random numbers), each effect alone at the
moderate value of bench/simulator.py's CATALOGUE_PARAMETERS, 6 widths x 0.5 s after a 1 s run-in.
Prints one JSON object: per effect, RMS(a - a_nominal)/RMS(a_nominal) for a1 and a2, and for comparison
the same ratio between two noise realisations of the nominal model."""
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from backlash_monitor.plant import K2_WIDTHS_M, PlantSimulator, Scenario, load_plant_config  # noqa: E402
from backlash_monitor.plant.effects import CATALOGUE  # noqa: E402
from simulator import CATALOGUE_PARAMETERS  # noqa: E402


def main():
    cfg = load_plant_config(overrides={"simulation.run_in_s": 1.0, **{f"effects.{c.name}": True for c in CATALOGUE}})
    cases = [("nominal", {})] + [(c.name, {k: v for k, v in CATALOGUE_PARAMETERS.items() if k.startswith(c.name + ".")})
                                 for c in CATALOGUE]
    cases.append(("wheel_stribeck_friction (w_s = 10 rad/s)", {"wheel_stribeck_friction.excess_torque_Nm": 0.5,
                                                               "wheel_stribeck_friction.stribeck_speed_rad_s": 10.0}))
    scen = [Scenario(w, 0.025, 0.89) for _ in cases for w in K2_WIDTHS_M]
    n_w = len(K2_WIDTHS_M)
    params = {}
    for i, (_, p) in enumerate(cases):
        for k, v in p.items():
            params.setdefault(k, np.full(len(scen), 10.0 if k.endswith("stribeck_speed_rad_s") else 0.0))
            params[k][i * n_w:(i + 1) * n_w] = v
    for k in params:                            # the Stribeck speed's neutral value is its default
        if k.endswith("stribeck_speed_rad_s"):
            params[k][params[k] == 0.0] = 10.0
    ch = PlantSimulator(scen, config=cfg, noise=True, noise_seed=11, parameters=params).run(25_000)
    other = PlantSimulator(scen[:n_w], config=cfg, noise=True, noise_seed=12).run(25_000)
    rms = lambda x: float(np.sqrt(np.mean(x ** 2)))  # noqa: E731
    out = {}
    for i, (name, _) in enumerate(cases):
        sl = slice(i * n_w, (i + 1) * n_w)
        out[name] = {s: round(rms(getattr(ch, s)[sl] - getattr(ch, s)[:n_w]) / rms(getattr(ch, s)[:n_w]), 5)
                     for s in ("a1", "a2")}
    out["noise (another realisation)"] = {s: round(rms(getattr(other, s) - getattr(ch, s)[:n_w])
                                                   / rms(getattr(ch, s)[:n_w]), 5) for s in ("a1", "a2")}
    print(json.dumps(out))


if __name__ == "__main__":
    main()
