"""Disturbance generators: mean 0, variance 0.05, hold times 2e-4 s and 2e-3 s; independence."""
import numpy as np

from backlash_monitor.plant import load_plant_config
from backlash_monitor.plant.disturbances import MotorLoadInput, pulse_load_pu

CFG = load_plant_config()
N_INTERVALS = 40_000


def _held(seq, hold):
    x = seq.samples(0, N_INTERVALS * hold)
    blocks = x.reshape(N_INTERVALS, hold)
    return x, blocks


def test_gaussian_generator_statistics_and_hold():
    gen = MotorLoadInput(seed=11, cfg=CFG).gaussian
    assert gen.hold_samples == 10                                # 2e-4 s at 50 kHz
    x, blocks = _held(gen, 10)
    assert np.all(blocks == blocks[:, :1])                       # held within an interval
    values = blocks[:, 0]
    assert np.mean(values[1:] != values[:-1]) > 0.999            # a new value every interval
    # N = 40000 independent values: std error of the mean sqrt(0.05/N) = 1.1e-3 -> 5 sigma = 5.6e-3;
    # of the variance 0.05*sqrt(2/N) = 3.5e-4 -> 5 sigma = 1.8e-3
    assert abs(values.mean()) < 5.6e-3
    assert abs(values.var() - 0.05) < 1.8e-3
    # roughly normal: kurtosis 3 +- 5*sqrt(24/N)
    k = np.mean((values - values.mean()) ** 4) / values.var() ** 2
    assert abs(k - 3.0) < 5 * np.sqrt(24 / N_INTERVALS)


def test_telegraph_generator_statistics_and_hold():
    gen = MotorLoadInput(seed=11, cfg=CFG).telegraph
    assert gen.hold_samples == 100                               # 2e-3 s at 50 kHz
    x, blocks = _held(gen, 100)
    assert np.all(blocks == blocks[:, :1])
    values = blocks[:, 0]
    assert np.allclose(np.abs(values), np.sqrt(0.05))            # amplitude sqrt(0.05): variance exactly 0.05
    assert abs(values.mean()) < 5.6e-3                           # 5 sigma of the mean
    assert abs(values.var() - 0.05) < 1.8e-3
    # random sign: about half of the interval boundaries change sign (binomial, 5 sigma)
    flips = np.mean(values[1:] != values[:-1])
    assert abs(flips - 0.5) < 5 * 0.5 / np.sqrt(N_INTERVALS)


def test_generators_independent_and_chunking_invariant():
    inp = MotorLoadInput(seed=5, cfg=CFG)
    g = inp.gaussian.samples(0, 100_000)[::10]
    t = inp.telegraph.samples(0, 100_000)[::10]
    assert abs(np.corrcoef(g, t)[0, 1]) < 5 / np.sqrt(g.size / 10)
    other = MotorLoadInput(seed=6, cfg=CFG).gaussian.samples(0, 100_000)[::10]
    assert abs(np.corrcoef(g, other)[0, 1]) < 5 / np.sqrt(g.size)
    again = MotorLoadInput(seed=5, cfg=CFG)
    parts = [again.gaussian.samples(k0, n) for k0, n in ((0, 7), (7, 993), (1000, 53_000), (54_000, 46_000))]
    assert np.array_equal(np.concatenate(parts), MotorLoadInput(seed=5, cfg=CFG).gaussian.samples(0, 100_000))


def test_pulse_load_schedule():
    p = pulse_load_pu(0, 50_000, CFG)
    on = np.flatnonzero(np.diff(p) > 0) + 1
    off = np.flatnonzero(np.diff(p) < 0) + 1
    assert list(on) == [2500, 15_000, 27_500, 40_000]            # first at 0.05 s, every 0.25 s
    assert list(off - on) == [3000] * 4                          # 60 ms
    assert set(np.unique(p)) == {0.0, 1.6}
