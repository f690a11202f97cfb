"""Batch plant simulator: many scenarios advanced together, chunk by chunk, at the sample rate."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from .config import PlantConfig, load_plant_config
from .disturbances import MotorLoadInput, motor_load_batch, pulse_load_pu
from .drivetrain import STATE_NAMES, absorber_coefficient, global_parameters, half_gap_rad
from .integrator import OUTPUT_NAMES, rk4_advance, resolve_backend
from .motor import supply_phase, supply_voltage
from .scenarios import Scenario
from .steady_state import settled_state

ENTRY_ONSET = "onset"    # entered from Delta >= beta: the load side overruns the motor (pulse starts)
ENTRY_RETURN = "return"  # entered from Delta <= -beta: the motor catches up (after the pulse)


@dataclass
class SimulationChunk:
    """``n_samples`` consecutive samples of every scenario; arrays shaped (n_scenarios, n_samples)."""
    # (every output but angle_difference is None when the simulator was built without it in ``outputs``)
    a1: np.ndarray | None          # r*dOmega1/dt [m/s^2], drive-wheel circumference, motor side
    a2: np.ndarray | None          # x'' [m/s^2], the mass
    omega1: np.ndarray | None      # [rad/s]
    omega2: np.ndarray | None      # [rad/s]
    angle_difference: np.ndarray   # Delta = alpha1 - alpha2 [rad], integrated as a state (always recorded)
    alpha1: np.ndarray | None      # [rad]
    alpha2: np.ndarray | None      # [rad]
    transmitted_torque_Nm: np.ndarray | None  # T_c [N*m]
    first_sample_index: int
    sample_period_s: float
    entries: list                  # per scenario: list of (sample_index, kind), kind "onset" | "return"
    states: dict | None = None     # full state (STATE_NAMES -> array) when record_states=True
    scenarios: list = field(default_factory=list)

    @property
    def n_samples(self) -> int:
        return self.angle_difference.shape[1]

    @property
    def time_s(self) -> np.ndarray:
        return (self.first_sample_index + np.arange(self.n_samples)) * self.sample_period_s


def find_entries(delta: np.ndarray, beta: np.ndarray, previous_delta: np.ndarray | None, first_sample_index: int):
    """True backlash-zone entries: sample k with |Delta_k| < beta and |Delta_{k-1}| >= beta.

    Kind: "onset" when Delta_{k-1} >= beta (the drive side was in contact), "return" when <= -beta.
    ``previous_delta``: last sample of the previous chunk per scenario (None at the stream start).
    """
    n_scen, n = delta.shape
    if n == 0:
        return [[] for _ in range(n_scen)]
    b = beta[:, None]
    inside = np.abs(delta) < b
    entering = np.empty_like(inside)
    entering[:, 1:] = inside[:, 1:] & ~inside[:, :-1]
    if previous_delta is None:
        entering[:, 0] = False  # no entry at sample 0 of the stream
    else:
        entering[:, 0] = inside[:, 0] & ~(np.abs(previous_delta) < beta)
    ss, ks = np.nonzero(entering)                   # row-major: by scenario, then sample
    prev = np.zeros(n_scen) if previous_delta is None else np.asarray(previous_delta, dtype=np.float64)
    before = np.where(ks > 0, delta[ss, np.maximum(ks - 1, 0)], prev[ss])   # Delta at k-1
    kinds = np.where(before > 0, ENTRY_ONSET, ENTRY_RETURN)
    out = [[] for _ in range(n_scen)]
    for s, k, kind in zip(ss.tolist(), (ks + first_sample_index).tolist(), kinds.tolist()):
        out[s].append((k, kind))
    return out


class PlantSimulator:
    """Advances every scenario at the sample rate from a settled start; ``run(n)`` continues seamlessly.

    noise: the two disturbance generators on/off (their effect switches still apply).
    record_states: also return the full state (for energy checks and the workbench).
    backend: "auto" | "numba" | "numba-scalar" | "numpy" (default from the config).
    outputs: names (OUTPUT_NAMES) of the signals to record, None = all eight; angle_difference is always
    recorded (entries need it), the chunk's fields of the others are None (the numba kernel then
    writes less: e.g. the five the pipeline uses, a1 a2 omega1 omega2 angle_difference).
    """

    def __init__(self, scenarios: Sequence[Scenario], config: PlantConfig | None = None, noise: bool = True,
                 record_states: bool = False, backend: str | None = None, outputs: Sequence[str] | None = None):
        if len(scenarios) == 0:
            raise ValueError("PlantSimulator: no scenarios given; allowed: one or more Scenario")
        self.config = config if config is not None else load_plant_config()
        self.scenarios = list(scenarios)
        self.noise = bool(noise)
        self.record_states = bool(record_states)
        self.backend = resolve_backend(backend or self.config.simulation.backend)
        if outputs is None:
            self.outputs = OUTPUT_NAMES
        else:
            unknown = [o for o in outputs if o not in OUTPUT_NAMES]
            if unknown or isinstance(outputs, str):
                raise ValueError(f"PlantSimulator: outputs = {outputs!r}; allowed: a sequence of "
                                 + ", ".join(repr(o) for o in OUTPUT_NAMES))
            wanted = set(outputs) | {"angle_difference"}
            self.outputs = tuple(o for o in OUTPUT_NAMES if o in wanted)
        self._output_index = None if self.outputs == OUTPUT_NAMES else [OUTPUT_NAMES.index(o) for o in self.outputs]
        cfg = self.config
        self.sample_period_s = cfg.simulation.sample_period_s
        self.beta = np.array([half_gap_rad(s.width_m, cfg) for s in self.scenarios])
        self.n1 = np.array([float(s.n1) for s in self.scenarios])
        self.c = np.array([absorber_coefficient(s.eta_k, s.n1, cfg) for s in self.scenarios])
        self.params = global_parameters(cfg)
        self.inputs = [MotorLoadInput(_noise_seed(s), cfg) for s in self.scenarios]
        self.state, self.motor_steady_state = settled_state(self.beta, cfg)
        self.sample_index = 0
        self._last_delta = None
        run_in = int(round(cfg.simulation.run_in_s * cfg.simulation.sample_rate_hz))
        if run_in > 0:
            self._run_in(run_in)

    def _run_in(self, n: int) -> None:
        """Advance samples -n..-1 before sample 0: the pulse train extended periodically backwards and,
        with noise on, the disturbances from their own run-in streams. Starts from the computed steady
        state rotated to the supply angle at t = -n/fs."""
        cfg = self.config
        theta = -2.0 * np.pi * cfg.motor.supply_frequency_hz * n / cfg.simulation.sample_rate_hz
        rot = np.exp(1j * theta)
        for ia, ib in ((0, 1), (2, 3)):
            z = (self.state[:, ia] + 1j * self.state[:, ib]) * rot
            self.state[:, ia], self.state[:, ib] = z.real, z.imag
        run_in_inputs = [MotorLoadInput(_noise_seed(s) ^ 0x5EED, cfg) for s in self.scenarios]
        step = 12_500  # in chunks: bounded memory
        for k0 in range(-n, 0, step):
            m = min(step, -k0)
            ua, ub, phase = self._supply(k0, m)
            pulse = pulse_load_pu(k0, m, cfg)
            load = motor_load_batch(run_in_inputs, k0 + n, m, self.noise, pulse=pulse)
            rk4_advance(self.backend, self.state, load, ua, ub, phase, cfg.motor.supply_voltage_pu, self.beta,
                        self.c, self.n1, self.params, self.sample_period_s, record_outputs=False)

    def _supply(self, k0: int, n: int):
        m = self.config.motor
        fs = self.config.simulation.sample_rate_hz
        k = np.arange(k0, k0 + n, dtype=np.int64)
        cols_a, cols_b = [], []
        for off in (0.0, 0.5, 1.0):
            a, b = supply_voltage(k, off, fs, m.supply_frequency_hz, m.supply_voltage_pu)
            cols_a.append(a)
            cols_b.append(b)
        return np.stack(cols_a, axis=1), np.stack(cols_b, axis=1), supply_phase(k, fs, m.supply_frequency_hz)

    def motor_load_pu(self, k0: int, n: int) -> np.ndarray:
        """The held motor load moment [p.u.] of every scenario for samples k0..k0+n-1 (advances the generators)."""
        pulse = pulse_load_pu(k0, n, self.config)
        return motor_load_batch(self.inputs, k0, n, self.noise, pulse=pulse)

    def run(self, n_samples: int) -> SimulationChunk:
        """Advance every scenario by ``n_samples`` samples and return them."""
        n = int(n_samples)
        if n < 0:
            raise ValueError(f"PlantSimulator.run: n_samples = {n_samples} is negative; allowed: >= 0")
        k0 = self.sample_index
        load = self.motor_load_pu(k0, n)
        ua, ub, phase = self._supply(k0, n)
        out, states = rk4_advance(self.backend, self.state, load, ua, ub, phase, self.config.motor.supply_voltage_pu,
                                  self.beta, self.c, self.n1, self.params, self.sample_period_s, self.record_states,
                                  outputs=self._output_index)
        sig = dict.fromkeys(OUTPUT_NAMES)
        sig.update(zip(self.outputs, out))
        delta = sig["angle_difference"]
        entries = find_entries(delta, self.beta, self._last_delta, k0)
        if n > 0:
            self._last_delta = delta[:, -1].copy()
        self.sample_index += n
        return SimulationChunk(**sig, first_sample_index=k0,
                               sample_period_s=self.sample_period_s, entries=entries,
                               states=None if states is None else dict(zip(STATE_NAMES, states)),
                               scenarios=self.scenarios)


def _noise_seed(s: Scenario) -> int:
    """Noise entropy of a scenario: its seed and its parameters, so every scenario's generators are
    independent of every other's, and the same scenario always gets the same noise."""
    return int(np.random.SeedSequence([s.seed, round(s.width_m * 1e9), round(s.eta_k * 1e9),
                                       round(s.n1 * 1e9)]).generate_state(1, np.uint32)[0])


def simulate_batch(scenarios: Sequence[Scenario], duration_s: float = 1.0, config: PlantConfig | None = None,
                   noise: bool = True, record_states: bool = False, backend: str | None = None,
                   outputs: Sequence[str] | None = None) -> SimulationChunk:
    """One ``run()`` of the whole duration from the settled start."""
    sim = PlantSimulator(scenarios, config=config, noise=noise, record_states=record_states, backend=backend,
                         outputs=outputs)
    n = int(round(duration_s / sim.sample_period_s))
    if n <= 0:
        raise ValueError(f"simulate_batch: duration_s = {duration_s} gives no samples; allowed: >= "
                         f"{sim.sample_period_s} s")
    return sim.run(n)
