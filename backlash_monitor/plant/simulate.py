"""Batch plant simulator: many scenarios advanced together, chunk by chunk, at the sample rate."""
from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any, Mapping, Sequence

import numpy as np

from .config import PlantConfig, load_plant_config
from .disturbances import MotorLoadInput, motor_load_batch, pulse_clock_s, pulse_load_pu
from .drivetrain import absorber_coefficient
from .codegen import global_vector, kernel_for
from .state import STATE_NAMES
from .integrator import OUTPUT_NAMES, initial_lags, rk4_advance, resolve_backend
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



@lru_cache(maxsize=64)
def supply_samples(k0: int, n: int, sample_rate_hz: float, frequency_hz: float, amplitude_pu: float):
    """The supply voltage (u_a, u_b at each sample step's start, middle and end: (n, 3) each) and its phase for samples
    k0..k0+n-1 -- the same for every simulation of one config, so kept (a diagnosis simulates the same chunks of
    samples ~100 times: 3 % of its CPU was this). Read-only arrays: a caller must not change them."""
    k = np.arange(k0, k0 + n, dtype=np.int64)
    cols_a, cols_b = [], []
    for off in (0.0, 0.5, 1.0):
        a, b = supply_voltage(k, off, sample_rate_hz, frequency_hz, amplitude_pu)
        cols_a.append(a)
        cols_b.append(b)
    out = (np.stack(cols_a, axis=1), np.stack(cols_b, axis=1), supply_phase(k, sample_rate_hz, frequency_hz))
    for x in out:
        x.flags.writeable = False
    return out

class PlantSimulator:
    """Advances every scenario at the sample rate from a settled start; ``run(n)`` continues seamlessly.

    noise: the two disturbance generators on/off (their effect switches still apply).
    record_states: also return the full state (for energy checks and the workbench).
    backend: "auto" | "numba" | "numba-scalar" | "numpy" (default from the config).
    outputs: names (OUTPUT_NAMES) of the signals to record, None = all eight; angle_difference is always
    recorded (entries need it), the chunk's fields of the others are None (the numba kernel then
    writes less: e.g. the five the pipeline uses, a1 a2 omega1 omega2 angle_difference).
    parameters: {"effect.param": scalar or (n_scenarios,) array} of enabled effects (docs/effects.md):
    per-scenario values, run-time (never recompiles).
    noise_seed: None = each scenario's noise from (seed, width, eta_k, n1) as always; an int = every
    scenario on the same noise realisation (common random numbers); a sequence of ints, one per
    scenario = scenarios with the same value share a realisation. Scenarios with the same noise
    entropy share one generator (drawn once).
    """

    def __init__(self, scenarios: Sequence[Scenario], config: PlantConfig | None = None, noise: bool = True,
                 record_states: bool = False, backend: str | None = None, outputs: Sequence[str] | None = None,
                 parameters: Mapping[str, Any] | None = None, noise_seed=None):
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
        self.noise_seed = _check_noise_seed(noise_seed, len(self.scenarios))
        cfg = self.config
        self.sample_period_s = cfg.simulation.sample_period_s
        self.effects = cfg.catalogue.enabled(cfg)
        self.kernel = kernel_for(tuple(c for c in self.effects if c.kind == "term"))
        self._overrides = dict(parameters or {})
        self._derive_parameters()
        self._seeds = [self._seed(i) for i in range(len(self.scenarios))]
        self.inputs = _shared_inputs(self._seeds, cfg)
        self._sensor_state: dict = {}
        self.state, self.motor_steady_state = settled_state(self.beta, cfg, values=self._values)
        self.lags = None     # the first-order lags (plant/lags.py), settled at the state on the first step
        self.sample_index = 0
        self._last_delta = None
        run_in = int(round(cfg.simulation.run_in_s * cfg.simulation.sample_rate_hz))
        if run_in > 0:
            self._run_in(run_in)

    # ------------------------------------------------------------------ parameters
    def _derive_parameters(self) -> None:
        """The per-scenario values and the kernel's parameter arrays from the config and the overrides."""
        cfg = self.config
        self._values = self._parameter_table(self._overrides)
        v = self._values
        self.beta = v["width_m"] / cfg.load.wheel_radius_m
        self.n1 = v["absorber_power_law.flow_index"]
        self.c = v["absorber_power_law.coefficient"]
        self.P = np.array([v[row] for row in self.kernel.param_rows], dtype=np.float64).reshape(
            len(self.kernel.param_rows), len(self.scenarios))
        self.G = global_vector(cfg)
        self._constants = [float(c) for c in v["constant_motor_load.load_pu"]]
        amp = v["pulse_load.amplitude_pu"]
        self._pulse_scale = None if np.all(amp == cfg.pulse_load.amplitude_pu) else amp

    def set_config(self, config: PlantConfig) -> None:
        """Change the plant's effect parameters at run time: the simulation goes on from its current state with
        ``config``'s values (an effect that wears in, a sensor that fails mid-run). Only what the effects API
        makes run-time may change: the effects' parameters (``<effect>.<parameter>``) and the values of the
        sections the kernel reads per step (load, clutch, absorber values). The set of switched-on effects must
        stay the same (it is the compiled kernel): switch an effect on from the start at its neutral default
        (every catalogue effect's default is neutral) and give it its value here. The sample rate, the motor,
        the pulse train and the disturbances cannot change (they fix the stream's timing, the settled start and
        the noise generators)."""
        check_runtime_change(self.config, config)
        self.config = config
        self._derive_parameters()

    def set_parameters(self, parameters: Mapping[str, Any]) -> None:
        """Change per-scenario effect parameters at run time ({"effect.param": scalar or (n_scenarios,) array},
        as ``parameters=`` of the constructor; the effects must be switched on): the simulation goes on from its
        current state with them."""
        merged = dict(self._overrides)
        merged.update(parameters)
        old = self._overrides
        self._overrides = merged
        try:
            self._derive_parameters()
        except ValueError:
            self._overrides = old
            raise

    def _parameter_table(self, overrides: Mapping[str, Any]) -> dict:
        """Per-scenario values (n_scenarios,) of every model value and every parameter of the enabled
        effects: defaults (config, effect class, Scenario), then ``overrides``, then the drifts."""
        cfg, n = self.config, len(self.scenarios)
        full = lambda x: np.full(n, float(x))  # noqa: E731
        v = {"width_m": np.array([s.width_m for s in self.scenarios], dtype=np.float64),
             "eta_k": np.array([s.eta_k for s in self.scenarios], dtype=np.float64),
             "n1": np.array([float(s.n1) for s in self.scenarios], dtype=np.float64),
             "mass_kg": full(cfg.load.mass_kg), "wheel_inertia_kgm2": full(cfg.load.wheel_inertia_kgm2),
             "rotor_resistance_pu": full(cfg.motor.r_r_pu), "supply_voltage_scale": full(1.0)}
        reg = cfg.catalogue
        known = {}
        for cls in list(reg.values()):
            for p in cls.parameters:
                known[f"{cls.name}.{p.name}"] = (cls, p)
        enabled = {c.name for c in self.effects}
        for key in overrides:
            if key not in known:
                near = difflib.get_close_matches(str(key), list(known), n=1)
                raise ValueError(f"PlantSimulator: unknown parameter {key!r}" + (f" (nearest: {near[0]!r})" if near else "")
                                 + "; allowed: 'effect.param' of an effect of the config's catalogue")
            if known[key][0].name not in enabled and known[key][0].name != "absorber_power_law":
                raise ValueError(f"PlantSimulator: parameter {key!r} belongs to effect {known[key][0].name!r}, which "
                                 f"is switched off; allowed: switch it on (effects.{known[key][0].name}: true)")
        for cls in self.effects + ([reg["absorber_power_law"]] if "absorber_power_law" not in enabled else []):
            for p in cls.parameters:
                key = f"{cls.name}.{p.name}"
                if p.source == "scenario":
                    continue
                v[key] = full(cfg.effect_parameter(cls.name, p.name))
        v.setdefault("pulse_load.amplitude_pu", full(cfg.pulse_load.amplitude_pu))
        v.setdefault("constant_motor_load.load_pu", full(cfg.constant_motor_load_pu))
        for key, value in overrides.items():
            cls, p = known[key]
            arr = np.asarray(value, dtype=np.float64)
            if arr.ndim == 0:
                arr = np.full(n, float(arr))
            if arr.shape != (n,):
                raise ValueError(f"PlantSimulator: parameter {key!r} has shape {arr.shape}; allowed: a scalar or "
                                 f"({n},), one value per scenario")
            p.check(cls.name, arr)
            v[key] = arr.copy()
        for cls in self.effects:
            if cls.kind != "drift":
                continue
            change = v[f"{cls.name}.{cls.parameters[0].name}"]
            if cls.target not in v:
                continue              # the drifting term is switched off
            v[cls.target] = v[cls.target] * (1.0 + change) if cls.relative else v[cls.target] + change
        if np.any(v["width_m"] <= 0.0):
            raise ValueError("PlantSimulator: backlash width after backlash_width_drift is <= 0; allowed: width "
                             "+ change > 0")
        if np.any(v["n1"] <= 0.0):
            raise ValueError("PlantSimulator: flow index after absorber_flow_index_drift is <= 0; allowed: > 0")
        if "absorber_power_law.flow_index" not in overrides:
            v["absorber_power_law.flow_index"] = v["n1"]
        if "absorber_power_law.coefficient" not in overrides:
            nominal = ("absorber_consistency_drift" not in enabled and "absorber_flow_index_drift" not in enabled)
            v["absorber_power_law.coefficient"] = (
                np.array([absorber_coefficient(s.eta_k, s.n1, cfg) for s in self.scenarios]) if nominal
                else v["eta_k"] * cfg.load.absorber_area_m2 / cfg.load.absorber_gap_m ** v["absorber_power_law.flow_index"])
        v["beta"] = v["width_m"] / cfg.load.wheel_radius_m
        return v

    @property
    def parameter_names(self) -> tuple:
        """Every per-scenario parameter "effect.param" of the enabled effects (usable in ``parameters=``)."""
        return tuple(f"{c.name}.{p.name}" for c in self.effects for p in c.parameters)

    def parameter_values(self, name: str) -> np.ndarray:
        """(n_scenarios,) values in use for a parameter or model value (after drifts)."""
        if name not in self._values:
            raise ValueError(f"PlantSimulator: no parameter {name!r}; allowed: " + ", ".join(sorted(self._values)))
        return self._values[name].copy()

    @property
    def params(self) -> np.ndarray:
        """The per-scenario kernel parameter array (rows ``kernel.param_rows``)."""
        return self.P

    def _seed(self, i: int) -> int:
        if self.noise_seed is None:
            return _noise_seed(self.scenarios[i])
        if isinstance(self.noise_seed, int):
            return _crn_seed(self.noise_seed)
        return _crn_seed(self.noise_seed[i])

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
        run_in_inputs = _shared_inputs([s ^ 0x5EED for s in self._seeds], cfg)
        step = 12_500  # in chunks: bounded memory
        for k0 in range(-n, 0, step):
            m = min(step, -k0)
            ua, ub, phase = self._supply(k0, m)
            pulse = self._pulse(k0, m)
            load = motor_load_batch(run_in_inputs, k0 + n, m, self.noise, pulse=pulse, constants=self._constants)
            if self.lags is None:
                self.lags = initial_lags(self.state, load[:, 0], self.P, self.G)
            rk4_advance(self.backend, self.kernel, self.state, load, ua, ub, phase, cfg.motor.supply_voltage_pu,
                        self.P, self.G, self.sample_period_s, record_outputs=False, pulse_clock=pulse_clock_s(k0, m, cfg),
                        lags=self.lags)

    def _pulse(self, k0: int, n: int):
        pulse = pulse_load_pu(k0, n, self.config)
        if self._pulse_scale is None:
            return pulse
        on = pulse != 0.0
        return np.where(on[None, :], self._pulse_scale[:, None], 0.0)

    def _supply(self, k0: int, n: int):
        m = self.config.motor
        return supply_samples(int(k0), int(n), float(self.config.simulation.sample_rate_hz),
                              float(m.supply_frequency_hz), float(m.supply_voltage_pu))

    def motor_load_pu(self, k0: int, n: int) -> np.ndarray:
        """The held motor load moment [p.u.] of every scenario for samples k0..k0+n-1 (advances the generators)."""
        return motor_load_batch(self.inputs, k0, n, self.noise, pulse=self._pulse(k0, n), constants=self._constants)

    def run(self, n_samples: int) -> SimulationChunk:
        """Advance every scenario by ``n_samples`` samples and return them."""
        n = int(n_samples)
        if n < 0:
            raise ValueError(f"PlantSimulator.run: n_samples = {n_samples} is negative; allowed: >= 0")
        k0 = self.sample_index
        load = self.motor_load_pu(k0, n)
        ua, ub, phase = self._supply(k0, n)
        if self.lags is None:
            self.lags = initial_lags(self.state, load[:, 0] if n else np.zeros(len(self.scenarios)), self.P, self.G)
        out, states = rk4_advance(self.backend, self.kernel, self.state, load, ua, ub, phase,
                                  self.config.motor.supply_voltage_pu, self.P, self.G, self.sample_period_s,
                                  self.record_states, outputs=self._output_index,
                                  pulse_clock=pulse_clock_s(k0, n, self.config), lags=self.lags)
        sig = dict.fromkeys(OUTPUT_NAMES)
        sig.update(zip(self.outputs, out))
        self.sensor_stage(sig)
        delta = sig["angle_difference"]
        entries = find_entries(delta, self.beta, self._last_delta, k0)
        if n > 0:
            self._last_delta = delta[:, -1].copy()
        self.sample_index += n
        return SimulationChunk(**sig, first_sample_index=k0,
                               sample_period_s=self.sample_period_s, entries=entries,
                               states=None if states is None else dict(zip(STATE_NAMES, states)),
                               scenarios=self.scenarios)


    def sensor_stage(self, sig: dict) -> None:
        """The enabled sensor effects on the recorded a1/a2 of ``sig`` ({"a1": (n_scen, n), ...}), in place:
        low-pass, then gain, then bias. Stateful (the low-pass continues across calls, starting settled
        on the first sample it sees); run() applies it to every chunk."""
        sensors = sorted((c for c in self.effects if c.kind == "sensor"), key=lambda c: c.order)
        if not sensors:
            return
        # deferred: scipy.signal costs ~1000 ms at start-up (python -X importtime, 29 Nov); only sensor effects use it
        from scipy.signal import lfilter
        h = self.sample_period_s
        for name in ("a1", "a2"):
            a = sig.get(name)
            if a is None or a.shape[1] == 0:
                continue
            a = a.copy()
            for cls in sensors:
                if cls.name == "accelerometer_lowpass":
                    tau = self._values[f"accelerometer_lowpass.{name}_time_constant_s"]
                    sections = np.clip(np.rint(self._values[f"accelerometer_lowpass.{name}_sections"]), 1, 4)
                    # one state per section, each starting settled on sample 0
                    prev = [self._sensor_state.setdefault(f"{name}#{k}", a[:, 0].copy()) for k in range(4)]
                    for i in np.flatnonzero(tau > 0.0):
                        alpha = -np.expm1(-h / tau[i])
                        for k in range(int(sections[i])):
                            a[i], _ = lfilter([alpha], [1.0, alpha - 1.0], a[i], zi=[(1.0 - alpha) * prev[k][i]])
                            prev[k][i] = a[i, -1]
                elif cls.name == "accelerometer_gain":
                    a *= 1.0 + self._values[f"accelerometer_gain.{name}_relative_change"][:, None]
                elif cls.name == "accelerometer_bias":
                    a += self._values[f"accelerometer_bias.{name}_m_s2"][:, None]
                else:     # a plug-in sensor stage: apply(a, values of its parameters for this signal, state)
                    a = cls.apply(name, a, {p.name: self._values[f"{cls.name}.{p.name}"] for p in cls.parameters},
                                  self._sensor_state.setdefault(cls.name + "." + name, {}), h)
            sig[name] = a


def check_runtime_change(old: PlantConfig, new: PlantConfig) -> None:
    """ValueError (naming what) when ``new`` cannot replace ``old`` in a running simulator (set_config): another
    set of switched-on effects, or another simulation, motor, pulse train or disturbance section."""
    new_classes, old_classes = new.catalogue.enabled(new), old.catalogue.enabled(old)
    names = [c.name for c in new_classes]
    have = [c.name for c in old_classes]
    if names == have and new_classes != old_classes:
        other = [c.name for c, o in zip(new_classes, old_classes) if c is not o]
        raise ValueError(f"plant change at run time: effect {other[0]!r} is another class in the new config's "
                         "catalogue (another plug-in file); allowed: the running config's catalogue (cfg.catalogue)")
    if names != have:
        on = sorted(set(names) - set(have))
        off = sorted(set(have) - set(names))
        what = "; ".join(x for x in (f"would switch on {', '.join(on)}" if on else "",
                                     f"would switch off {', '.join(off)}" if off else "") if x)
        raise ValueError(f"plant change at run time: the switched-on effects cannot change ({what}); allowed: "
                         "switch an effect on from the start at its neutral default and change its parameters")
    fixed = [sec for sec in ("simulation", "motor", "pulse_load", "disturbances")
             if getattr(new, sec) != getattr(old, sec)]
    if fixed:
        raise ValueError(f"plant change at run time: section(s) {', '.join(fixed)} cannot change; allowed: effect "
                         "parameters and the load, clutch and absorber values")


def _check_noise_seed(noise_seed, n: int):
    def ok(x):
        return isinstance(x, (int, np.integer)) and not isinstance(x, bool) and x >= 0
    if noise_seed is None:
        return None
    if ok(noise_seed):
        return int(noise_seed)
    if isinstance(noise_seed, (list, tuple, np.ndarray)) and len(noise_seed) == n and all(ok(x) for x in noise_seed):
        return [int(x) for x in noise_seed]
    raise ValueError(f"PlantSimulator: noise_seed = {noise_seed!r}; allowed: None, an integer >= 0, or {n} such "
                     "integers (one per scenario)")


def _shared_inputs(seeds, cfg) -> list:
    """One MotorLoadInput per distinct seed, shared by the scenarios that have it (drawn once; the same
    values as separate inputs, since a repeated request returns the same samples)."""
    by_seed: dict = {}
    return [by_seed.setdefault(s, MotorLoadInput(s, cfg)) if s not in by_seed else by_seed[s] for s in seeds]


def _crn_seed(noise_seed: int) -> int:
    """Noise entropy shared by every scenario of a batch (common random numbers)."""
    return int(np.random.SeedSequence([int(noise_seed), 0xC0FFEE]).generate_state(1, np.uint32)[0])


def _noise_seed(s: Scenario) -> int:
    """Noise entropy of a scenario: its seed and its parameters, so every scenario's generators are
    independent of every other's, and the same scenario always gets the same noise."""
    return int(np.random.SeedSequence([s.seed, round(s.width_m * 1e9), round(s.eta_k * 1e9),
                                       round(s.n1 * 1e9)]).generate_state(1, np.uint32)[0])


def simulate_batch(scenarios: Sequence[Scenario], duration_s: float = 1.0, config: PlantConfig | None = None,
                   noise: bool = True, record_states: bool = False, backend: str | None = None,
                   outputs: Sequence[str] | None = None, parameters: Mapping[str, Any] | None = None,
                   noise_seed=None) -> SimulationChunk:
    """One ``run()`` of the whole duration from the settled start."""
    sim = PlantSimulator(scenarios, config=config, noise=noise, record_states=record_states, backend=backend,
                         outputs=outputs, parameters=parameters, noise_seed=noise_seed)
    n = int(round(duration_s / sim.sample_period_s))
    if n <= 0:
        raise ValueError(f"simulate_batch: duration_s = {duration_s} gives no samples; allowed: >= "
                         f"{sim.sample_period_s} s")
    return sim.run(n)
