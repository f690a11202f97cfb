"""Inputs held over each sample step: the pulse load and the two disturbance generators (SPEC section 3).

All act on the motor's load moment, in p.u. Every input is a function of the global sample index
k (t = k/fs) and is held over the step [k, k+1). The generators draw their values in fixed blocks,
so the sequence does not depend on how the stream is cut into chunks.
"""
from __future__ import annotations

import math

import numpy as np

_BLOCK = 1024  # hold intervals drawn per block (fixed: makes the stream independent of chunking)


def pulse_load_pu(first_sample: int, n_samples: int, cfg) -> np.ndarray:
    """t_pulse for samples first_sample .. first_sample+n-1: amplitude while (k - k0) mod P < D and k >= k0.

    Negative k (the run-in before sample 0) see the same train extended periodically backwards, so
    the run-in ends in the pulse train's periodic steady state with the next pulse at k0."""
    k, k0, period, duration = _pulse_train(first_sample, n_samples, cfg)
    on = ((k >= k0) | (k < 0)) & (np.mod(k - k0, period) < duration)
    return np.where(on, cfg.pulse_load.amplitude_pu, 0.0)


def _pulse_train(first_sample: int, n_samples: int, cfg) -> tuple:
    """(the sample indices first_sample .. first_sample+n-1, the first rise k0, the period P, the duration D) of the
    pulse train, in samples: the one geometry the load and its clock share."""
    fs = cfg.simulation.sample_rate_hz
    pl = cfg.pulse_load
    k = np.arange(first_sample, first_sample + n_samples, dtype=np.int64)
    return k, int(round(pl.first_s * fs)), int(round(pl.period_s * fs)), int(round(pl.duration_s * fs))


NO_PULSE_S = 1.0e6   # the pulse clock without a load pulse [s]: "never", so every exp(-t/tau) response to an edge is 0


def pulse_clock_s(first_sample: int, n_samples: int, cfg) -> np.ndarray:
    """The pulse clock of samples first_sample .. first_sample+n-1, held over each step like the load: (n, 2), column 0
    the time since the latest load pulse began (its rising edge) [s], column 1 the time since it ended (its falling
    edge, ``duration_s`` after the rise) [s]; both in [0, period_s). The model variables ``pulse_time_s`` and
    ``pulse_off_time_s`` (plant/effects.py MODEL_VARIABLES).

    The same train as :func:`pulse_load_pu`: the rises at k0 + j*P for every integer j (before k0 the train extended
    periodically backwards, as in the run-in), so a term of these lines up with the model's pulses and, through the
    recovered ``pulse_load.first_s`` (workbench/analysis.recover_conditions), with the recording's. One exception the
    load has and the clock does not: a pulse that the settled start cuts at sample 0 (its rise before 0 and its end
    after) ends at sample 0 in the load but at rise + duration on the clock (the workbench starts its model runs
    before such a pulse: plant_adapter.pulse_lead_samples). With the pulse load switched off both are NO_PULSE_S."""
    if not cfg.effects.pulse_load:
        return np.full((n_samples, 2), NO_PULSE_S)
    fs = cfg.simulation.sample_rate_hz
    k, k0, period, duration = _pulse_train(first_sample, n_samples, cfg)
    out = np.empty((n_samples, 2))
    out[:, 0] = np.mod(k - k0, period) / fs
    out[:, 1] = np.mod(k - k0 - duration, period) / fs
    return out


class HeldSequence:
    """A random sequence whose values are held for ``hold_samples`` samples each.

    ``draw(rng, n)`` returns n new interval values. ``samples(k0, n)`` gives the held values for
    samples k0..k0+n-1; calls must move forward in the stream (they may overlap the last interval).
    """

    def __init__(self, rng: np.random.Generator, draw, hold_samples: int):
        self._rng = rng
        self._draw = draw
        self.hold_samples = int(hold_samples)
        self._values = np.empty(0)
        self._first_interval = 0  # interval index of self._values[0]

    def samples(self, k0: int, n: int) -> np.ndarray:
        if n == 0:
            return np.empty(0)
        i0 = k0 // self.hold_samples
        i1 = (k0 + n - 1) // self.hold_samples
        if i0 < self._first_interval:
            raise ValueError("HeldSequence: samples must be requested in forward order")
        # drop intervals before i0, draw blocks until i1 is covered
        drop = min(i0 - self._first_interval, len(self._values))
        self._values = self._values[drop:]
        self._first_interval += drop
        parts = [self._values]
        have = self._first_interval + len(self._values)
        while have <= i1:
            block_start = (have // _BLOCK) * _BLOCK
            block = self._draw(self._rng, _BLOCK)
            parts.append(block[have - block_start:])
            have = block_start + _BLOCK
        self._values = np.concatenate(parts) if len(parts) > 1 else self._values
        # the held values: intervals i0..i1 repeated, cut to k0..k0+n-1 (same values as indexing
        # self._values[k // hold - first] per sample, ~5x cheaper)
        a = i0 - self._first_interval
        held = np.repeat(self._values[a:a + i1 - i0 + 1], self.hold_samples)
        start = k0 - i0 * self.hold_samples
        return held[start:start + n]


def gaussian_generator(seed_sequence: np.random.SeedSequence, cfg) -> HeldSequence:
    """Normally distributed values, mean and variance from the config, a new value every gaussian_hold_s."""
    d = cfg.disturbances
    mean, std = d.gaussian_mean_pu, math.sqrt(d.gaussian_variance_pu2)
    hold = int(round(d.gaussian_hold_s * cfg.simulation.sample_rate_hz))
    return HeldSequence(np.random.default_rng(seed_sequence), lambda rng, n: rng.normal(mean, std, n), hold)


def telegraph_generator(seed_sequence: np.random.SeedSequence, cfg) -> HeldSequence:
    """Rectangular impulses: mean +- sqrt(variance) with a random sign, a new value every pulse_hold_s."""
    d = cfg.disturbances
    mean, amp = d.pulse_mean_pu, math.sqrt(d.pulse_variance_pu2)
    hold = int(round(d.pulse_hold_s * cfg.simulation.sample_rate_hz))
    return HeldSequence(np.random.default_rng(seed_sequence),
                        lambda rng, n: mean + amp * np.where(rng.random(n) < 0.5, -1.0, 1.0), hold)


class MotorLoadInput:
    """The held motor load moment [p.u.] of one scenario: the sum of the switched-on input terms."""

    def __init__(self, seed: int, cfg):
        self.cfg = cfg
        self.constant_pu = cfg.constant_motor_load_pu      # per scenario (PlantSimulator parameters)
        gauss_seq, tele_seq = np.random.SeedSequence(seed).spawn(2)
        self.gaussian = gaussian_generator(gauss_seq, cfg)
        self.telegraph = telegraph_generator(tele_seq, cfg)

    def samples(self, k0: int, n: int, noise: bool, pulse: np.ndarray | None = None) -> np.ndarray:
        out = np.zeros(n)
        if self.cfg.effects.pulse_load and pulse is None:
            pulse = pulse_load_pu(k0, n, self.cfg)
        self.add_to(out, k0, n, noise, pulse)
        return out

    def add_to(self, row: np.ndarray, k0: int, n: int, noise: bool, pulse: np.ndarray | None,
               constant: float | None = None) -> None:
        """Add the switched-on terms for samples k0..k0+n-1 to ``row`` (``pulse``: the pulse load
        of those samples when it is on; ``constant``: the constant load, default ``self.constant_pu``).
        Asking again for the same samples returns the same values (scenarios with the same noise
        entropy share one input)."""
        e = self.cfg.effects
        if e.pulse_load:
            row += pulse
        if e.constant_motor_load:
            row += self.constant_pu if constant is None else constant
        if noise:
            # always advance both generators so that switching one off does not change the other
            g = self.gaussian.samples(k0, n)
            t = self.telegraph.samples(k0, n)
            if e.gaussian_disturbance:
                row += g
            if e.pulse_disturbance:
                row += t


def motor_load_batch(inputs, k0: int, n: int, noise: bool, pulse: np.ndarray | None = None,
                     constants=None) -> np.ndarray:
    """``np.stack([inp.samples(k0, n, noise, pulse) for inp in inputs])``, bit-identical (the same additions
    in the same order), written row by row into one array (each row stays in cache). ``constants``: the
    constant load per row (default: each input's own)."""
    out = np.zeros((len(inputs), n))
    if len(inputs) == 0 or n == 0:
        return out
    cfg = inputs[0].cfg
    e = cfg.effects
    if e.pulse_load and pulse is None:
        pulse = pulse_load_pu(k0, n, cfg)
    consts = [None] * len(inputs) if constants is None else constants
    if pulse is not None and np.ndim(pulse) == 2:       # per-scenario pulse amplitudes
        for inp, row, pr, c in zip(inputs, out, pulse, consts):
            inp.add_to(row, k0, n, noise, pr, c)
        return out
    for inp, row, c in zip(inputs, out, consts):
        inp.add_to(row, k0, n, noise, pulse, c)
    return out
