"""SPEC section 3 behaviour: 8 entries/s (4 onset + 4 return), no re-trigger inside a window,
noise-free far-side impact times after the onset entry."""
import numpy as np

from backlash_monitor.plant import K2_WIDTHS_M, PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.analysis import impact_times_ms

SPEC_IMPACT_MS = (14.7, 19.1, 22.9, 29.5, 33.1, 35.4)   # SPEC section 3, eta_k = 0.025, n1 = 0.89


def test_entries_per_second_by_kind_with_noise():
    scen = [Scenario(w, eta, n1, seed=s) for w in K2_WIDTHS_M for (eta, n1, s) in ((0.025, 0.89, 0), (0.05, 0.97, 1))]
    sim = PlantSimulator(scen, config=load_plant_config(), noise=True)
    ch = sim.run(50_000)      # 1 s
    for entries in ch.entries:
        kinds = [kind for _, kind in entries]
        assert kinds.count("onset") == 4 and kinds.count("return") == 4
        ks = np.array([k for k, _ in entries])
        assert np.all(np.diff(ks) >= 2048)            # no re-trigger inside a window


def test_noise_free_impact_times():
    scen = [Scenario(w, 0.025, 0.89) for w in K2_WIDTHS_M]
    sim = PlantSimulator(scen, config=load_plant_config(), noise=False)
    ch = sim.run(50_000)
    times = impact_times_ms(ch, sim.beta)
    for spec, t in zip(SPEC_IMPACT_MS, times):
        assert len(t) == 4
        assert max(abs(x - spec) for x in t) < 0.3, (spec, t)
        assert max(t) < 2048 / 50.0                   # inside the 41 ms window
