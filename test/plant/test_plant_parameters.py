"""eta_k and n1 change the windows measurably, but less than one width step does.

Measured (noise-free, settled, docs/model.md): over the whole eta_k x n1 grid the far-side impact
time moves by 0.22 ms (0.0025 m) .. 0.70 ms (0.01 m); one width step moves it by >= 2.26 ms.
The RMS difference of the a1 windows: <= 21 m/s^2 across eta_k, n1 against >= 31 m/s^2 between
neighbouring widths. a2's level is carried by the absorber and moves strongly.
"""
import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.analysis import impact_times_ms, windows

WIDTHS = (0.0075, 0.009, 0.01)            # contains the smallest step in impact time (0.009 -> 0.01)
FLUIDS = ((0.025, 0.89), (0.0125, 0.89), (0.05, 0.97))   # pattern fluid and the grid's two corners


@pytest.fixture(scope="module")
def runs():
    scen = [Scenario(w, e, n) for (e, n) in FLUIDS for w in WIDTHS]
    sim = PlantSimulator(scen, config=load_plant_config(), noise=False)
    ch = sim.run(15_000)
    t = impact_times_ms(ch, sim.beta)
    a1 = windows(ch, "a1")
    a2 = windows(ch, "a2")
    out = {}
    for i, s in enumerate(scen):
        out[(s.eta_k, s.n1, s.width_m)] = (t[i][0], a1[i][0], a2[i][0])
    return out


def rms(x):
    return float(np.sqrt(np.mean(np.square(x))))


def test_fluid_shifts_impact_less_than_a_width_step(runs):
    base = {w: runs[(0.025, 0.89, w)][0] for w in WIDTHS}
    width_step = min(np.diff([base[w] for w in WIDTHS]))          # 2.26 ms measured
    for w in WIDTHS:
        shifts = [abs(runs[(e, n, w)][0] - base[w]) for (e, n) in FLUIDS[1:]]
        assert max(shifts) >= 0.1                                   # measurable: >= 5 samples (0.1 ms)
        assert max(shifts) < 0.4 * width_step                       # measured <= 0.7 / 2.26 = 0.31


def test_fluid_changes_a1_window_less_than_a_width_step(runs):
    for j, w in enumerate(WIDTHS):
        a1 = runs[(0.025, 0.89, w)][1]
        fluid = max(rms(runs[(e, n, w)][1] - a1) for (e, n) in FLUIDS[1:])
        neighbours = [rms(runs[(0.025, 0.89, w2)][1] - a1) for w2 in WIDTHS if w2 != w]
        assert fluid > 1.0                                          # measurable (m/s^2)
        assert fluid < 0.8 * min(neighbours)


def test_a2_level_depends_strongly_on_the_fluid(runs):
    w = 0.005 if (0.025, 0.89, 0.005) in runs else WIDTHS[0]
    means = [runs[(e, n, w)][2].mean() for (e, n) in FLUIDS]
    spread = max(means) - min(means)
    assert spread > 0.2 * rms(runs[(0.025, 0.89, w)][2])
