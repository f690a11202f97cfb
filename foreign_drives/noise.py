"""The held inputs on the motor's load moment: the pulse load and the two disturbance generators (SPEC
section 3), from this package's own random streams.

The time axis is cut into segments of 0.2 ms (the Gaussian generator's hold time); every input is constant
over a segment (the pulse edges of SPEC's train, 0.05 s + i*0.25 s and 60 ms later, lie on that grid):

- Gaussian generator: N(0, 0.05) p.u., a new value every segment (2e-4 s);
- telegraph: +-sqrt(0.05) p.u. with a random sign, a new value every 10 segments (2e-3 s);
- pulse load: amplitude while (t - first) mod period < duration, for negative times too (the run-in sees the
  train extended periodically backwards).

Streams: ``numpy.random.Philox`` generators (not the PCG64 of numpy's default) spawned from
``SeedSequence([seed, 0x466F7265])``: run-in Gaussian, run-in telegraph, recording Gaussian, recording
telegraph, sensor noise a1, sensor noise a2. The recording's streams do not depend on the run-in's length.
"""
from __future__ import annotations

import math

import numpy as np

from . import constants as C

SEGMENT_S = C.GAUSSIAN_HOLD_S                          # 0.2 ms: the inputs' grid
SEGMENT_SAMPLES = int(round(SEGMENT_S * C.SAMPLE_RATE_HZ))   # 10
TELEGRAPH_SEGMENTS = int(round(C.TELEGRAPH_HOLD_S / SEGMENT_S))  # 10
STREAM_TAG = 0x466F7265                                # "Fore": keeps these streams apart from any other user of a seed
STREAMS = ("run_in_gaussian", "run_in_telegraph", "gaussian", "telegraph", "sensor_a1", "sensor_a2")

assert abs(SEGMENT_SAMPLES * C.SAMPLE_PERIOD_S - SEGMENT_S) < 1e-15
assert abs(TELEGRAPH_SEGMENTS * SEGMENT_S - C.TELEGRAPH_HOLD_S) < 1e-15


def streams(seed: int) -> dict:
    """{name: numpy Generator} of one recording's independent random streams."""
    children = np.random.SeedSequence([int(seed), STREAM_TAG]).spawn(len(STREAMS))
    return {name: np.random.Generator(np.random.Philox(ss)) for name, ss in zip(STREAMS, children)}


def segments_of(seconds: float, what: str) -> int:
    """A duration as a whole number of 0.2 ms segments (refused with one line if it is not)."""
    n = seconds / SEGMENT_S
    if abs(n - round(n)) > 1e-6:
        raise ValueError(f"{what} = {seconds!r} s is not a multiple of the inputs' 0.2 ms grid; allowed: k*0.0002 s")
    return int(round(n))


def pulse_train(seg0: int, n: int, amplitude_pu: float, first_s: float, period_s: float = C.PULSE_PERIOD_S,
                duration_s: float = C.PULSE_DURATION_S) -> np.ndarray:
    """The pulse load [p.u.] on segments seg0 .. seg0+n-1 (t = index*0.2 ms), periodic for all times."""
    j0 = segments_of(first_s, "pulse_first_s")
    jp = segments_of(period_s, "pulse period")
    jd = segments_of(duration_s, "pulse duration")
    j = np.arange(seg0, seg0 + n, dtype=np.int64)
    return np.where(np.mod(j - j0, jp) < jd, float(amplitude_pu), 0.0)


def gaussian_values(rng: np.random.Generator, n_segments: int) -> np.ndarray:
    """Held Gaussian disturbance, one value per segment [p.u.]: mean 0, variance 0.05."""
    return rng.standard_normal(n_segments) * math.sqrt(C.GAUSSIAN_VARIANCE_PU2)


def telegraph_values(rng: np.random.Generator, n_segments: int) -> np.ndarray:
    """Held random-sign telegraph [p.u.], a new value every 10 segments, amplitude sqrt(0.05); n_segments must
    start on a hold boundary."""
    n_hold = -(-n_segments // TELEGRAPH_SEGMENTS)
    signs = 2.0 * rng.integers(0, 2, size=n_hold) - 1.0
    return np.repeat(signs * math.sqrt(C.TELEGRAPH_VARIANCE_PU2), TELEGRAPH_SEGMENTS)[:n_segments]
