"""What a pattern library is trained on by default: the simulated stretch per scenario and the noise seeds.

Its own module, without the simulator, so that `train --help` and `evaluate --help` show these defaults
without loading the plant (numba, scipy.optimize: ~1 s at start-up, python -X importtime, 29 Nov).
"""
# 9 onset entries per scenario (4 per second, the first at ~0.05 s): the first has no sensor offset
# estimate yet (no whole load period behind it), the monitor classifies the 8 after it [s]
DEFAULT_DURATION_S = 2.25
DEFAULT_TRAIN_SEEDS = tuple(range(1000, 1008))   # training noise seeds; evaluation uses 0..4
