"""The workbench's one door to the plant simulator: the candidate catalogue and batched, shared-noise runs.

Built on the plug-in effects API (docs/effects.md): the model's catalogue (``model.catalogue``, an
EffectCatalogue: the built-in effects plus the model's plug-in files) gives every effect with
its parameters (unit, default, bounds); ``PlantSimulator(parameters={name: per-scenario array},
noise_seed=k)`` runs many candidate parameter sets as one batch on one noise realisation.

- A *parameter set* is a dict ``{"effect.param": value}``; the effects it names are switched on.
- Every catalogue effect is switched on in every workbench run (at its neutral default unless the model or
  the set gives a value): one compiled kernel for the whole catalogue, candidates differ only in run-time
  parameters (the effects API's advice; no compilation per candidate).
- Common random numbers: every (set, seed) pair is one scenario of ONE batch; candidate values are
  per-scenario parameters, so all scenarios of seed k have the same (seed, width, eta_k, n1) and the
  simulator's per-scenario noise derivation gives them the same realisation bit for bit (checked in
  test_workbench_model.py); the K seeds are K independent realisations. (``noise_seed=`` would put every
  scenario of a batch on one realisation: K batches instead of one, ~10x slower for small sets.)
- Fit ranges: an effect's bounds are the physically allowed values (wide); the fit searches a practical
  range inside them (FIT_RANGES, reasons in docs/workbench.md). A user's plug-in effect without an entry is
  searched over its own bounds.
- Multi-signal sensor effects (accelerometer_bias/gain/lowpass) are fitted per signal: one candidate per
  parameter (e.g. ``accelerometer_lowpass[a2]``), the other left at its value.
- ``torque_ripple`` is not fitted from the event average (a ripple not locked to the events averages out);
  the spectral-peak view shows it (NOT_EVENT_LOCKED).
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from backlash_monitor.plant import PlantSimulator, Scenario
from backlash_monitor.plant import effects as plant_effects

SIGNALS = ("a1", "a2", "omega1", "omega2", "angle_difference")
# a sensor effect's discrete form parameter: one candidate per value, held fixed in it while the rest is fitted (the
# low-pass's order: a sensor's anti-alias filter has 1, 2 or 4 poles; measured on foreign drives: a 2nd-order Bessel and
# a 4th-order Butterworth were 'partial' or 'nothing explains' with a first-order low-pass alone)
DISCRETE_FORMS = {"accelerometer_lowpass": ("sections", (1.0, 2.0, 4.0))}
NOT_EVENT_LOCKED = ("torque_ripple",)

# practical search range of each parameter [unit of the parameter]; "width" = relative to the model's width.
# Every range is the size of the error real drives and sensors show (docs/workbench.md "Fit ranges" has the
# reasons; F0*r = 4.5 N*m is the working resistance's torque at the rim, T_b = 20 N*m the motor's base torque,
# the wheel turns at ~151 rad/s):
FIT_RANGES = {
    "wheel_coulomb_friction.torque_Nm": (0.0, 5.0),            # up to F0*r: more would stall the load
    "wheel_viscous_friction.damping_Nms_per_rad": (0.0, 0.05),  # 7.5 N*m at 151 rad/s (1.7 F0*r)
    "wheel_stribeck_friction.excess_torque_Nm": (0.0, 5.0),     # as the dry friction
    "wheel_stribeck_friction.stribeck_speed_rad_s": (0.5, 50.0),  # lubricated bearings to dry contacts
    "motor_coulomb_friction.torque_Nm": (0.0, 10.0),            # half of T_b: a failing motor bearing or brake
    "clutch_contact_stiffness.relative_change": (-0.6, 1.5),    # elastomer jaws: worn soft to aged hard
    "clutch_contact_damping.relative_change": (-0.8, 3.0),      # elastomer damping: temperature, ageing
    "shaft_compliance.compliance_rad_per_Nm": (0.0, 2e-3),      # a shaft up to 6x softer than the jaw contact
    "mass_force_offset.force_N": (-60.0, 60.0),                 # 2 F0: an incline up to ~37 deg, a preload
    "motor_load_offset.load_pu": (-0.4, 0.4),                   # 40 % of T_b: a constant extra load or drag
    "accelerometer_bias.a1_m_s2": (-10.0, 10.0),                # MEMS offset (+-0.2 g) + gravity on a tilted axis
    "accelerometer_bias.a2_m_s2": (-10.0, 10.0),                # (up to 1 g)
    "accelerometer_gain.a1_relative_change": (-0.5, 0.5),       # sensitivity error to a range set x2 / x0.5
    "accelerometer_gain.a2_relative_change": (-0.5, 0.5),
    "accelerometer_lowpass.a1_time_constant_s": (0.0, 2e-3),    # sensor bandwidths down to 80 Hz
    "accelerometer_lowpass.a2_time_constant_s": (0.0, 2e-3),
    "backlash_width_drift.change": ("width", -0.4, 0.4),        # wear: a clutch is serviced long before +40 %
    "absorber_consistency_drift.relative_change": (-0.6, 1.5),  # fluid viscosity: ~-2 %/K over +-30 K
    "absorber_flow_index_drift.change": (-0.1, 0.1),            # shear-thinning index: temperature, ageing
    "spring_stiffness_drift.relative_change": (-0.75, 3.0),     # a spring of another grade, or a cracked one
    "load_mass_drift.relative_change": (-0.5, 1.0),             # the product carried: half to double
    "wheel_inertia_drift.relative_change": (-0.5, 1.0),         # another wheel or hub mounted
    "working_resistance_drift.relative_change": (-1.0, 2.0),    # the process force: gone to tripled
    "pulse_amplitude_drift.relative_change": (-0.3, 0.3),       # the machine's duty cycle load +-30 %
    "rotor_resistance_drift.relative_change": (-0.3, 1.5),      # r_r +0.4 %/K: a rotor 75 K colder than rated to
                                                                # one 200 K hotter (+80 %), with broken bars more
    "supply_voltage_drift.relative_change": (-0.2, 0.1),        # the grid's +-10 % (EN 50160) and a sag to -20 %
}


@dataclass(frozen=True)
class EffectParameter:
    name: str          # the effect's parameter name, e.g. "torque_Nm"
    unit: str
    default: float     # the model's current value (the effect's neutral default when the model lacks it)
    lower: float       # search range of the fit
    upper: float
    key: str           # "effect.param"


@dataclass(frozen=True)
class CandidateEffect:
    name: str                  # candidate id: the effect's name, or "effect[a2]" for one signal of a sensor
    effect: str                # the catalogue effect's name
    balance: str
    description: str
    parameters: tuple          # the fitted EffectParameters
    signal: str | None = None
    fixed: tuple = ()          # ("effect.param", value): parameters this candidate holds at a fixed value (a form)
    phase_index: int = -1      # a term locked to a shaft's angle: the index of its phase parameter (angle_phase_index)

    @property
    def fixed_values(self) -> dict:
        """The fixed parameters by their names, e.g. {"a1_sections": 2.0}."""
        return {k.split(".", 1)[1]: float(v) for k, v in self.fixed}

    def default_vector(self) -> np.ndarray:
        return np.array([p.default for p in self.parameters])

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        return np.array([p.lower for p in self.parameters]), np.array([p.upper for p in self.parameters])


def _current(cfg, effect: str, pname: str) -> float:
    return float(cfg.effect_parameter(effect, pname))


def _range(key, p, cfg, width_m, current):
    spec = FIT_RANGES.get(key)
    lo_b, hi_b = p.bounds
    if spec is None:
        lo, hi = lo_b, hi_b
    elif spec[0] == "width":
        lo, hi = spec[1] * width_m, spec[2] * width_m
    else:
        lo, hi = spec
    lo, hi = max(lo, lo_b), min(hi, hi_b)
    # the model's current value stays inside the range
    return min(lo, current), max(hi, current)


def candidate_effect_names(catalogue, not_event_locked: bool = False) -> list[str]:
    """The effects the workbench fits from the event average, of an EffectCatalogue (a model's:
    ``model.catalogue``): the built-in catalogue's (event-locked ones) and the user's plug-ins in it (not
    nominal, not built-in catalogue); with ``not_event_locked`` also the ones fitted elsewhere (a torque
    ripple, from the raw spectrum: ripple.py), which a model version may hold as well."""
    reg = catalogue
    skip = () if not_event_locked else NOT_EVENT_LOCKED
    names = [n for n in plant_effects.CATALOGUE_NAMES if n in reg and n not in skip]
    names += [n for n, c in reg.items() if n not in names and n not in skip and not c.nominal
              and n not in plant_effects.CATALOGUE_NAMES and c.kind in ("term", "drift", "sensor")]
    return names


def catalogue(model, not_event_locked: bool = False) -> list[CandidateEffect]:
    """The candidate effects the workbench fits on ``model`` (a WorkbenchModel), defaults = its values;
    ``not_event_locked``: also the effects fitted outside the event average (candidate_effect_names)."""
    cfg = model.plant_config()
    reg = model.catalogue
    names = candidate_effect_names(reg, not_event_locked)
    out = []
    for name in names:
        cls = reg[name]
        params = []
        for p in cls.parameters:
            key = f"{name}.{p.name}"
            cur = _current(cfg, name, p.name)
            lo, hi = _range(key, p, cfg, model.nominal["width_m"], cur)
            params.append(EffectParameter(p.name, p.unit, cur, lo, hi, key))
        if cls.kind == "sensor" and all(p.name.startswith(("a1_", "a2_")) for p in params):
            variant = DISCRETE_FORMS.get(name)
            for sig in ("a1", "a2"):
                sub = tuple(p for p in params if p.name.startswith(sig + "_")
                            and not (variant and p.name == f"{sig}_{variant[0]}"))
                if not variant:
                    out.append(CandidateEffect(f"{name}[{sig}]", name, cls.balance, cls.description, sub, sig))
                    continue
                key = f"{name}.{sig}_{variant[0]}"
                current = _current(cfg, name, f"{sig}_{variant[0]}")
                # a drive without the effect yet: one candidate per form; with it: its own form only
                forms = variant[1] if all(p.default == 0.0 for p in sub) else (current,)
                for v in forms:
                    label = f"{name}[{sig}]" if v == variant[1][0] else f"{name}[{sig},{variant[0]}={v:g}]"
                    out.append(CandidateEffect(label, name, cls.balance, cls.description, sub, sig,
                                               ((key, float(v)),)))
        else:
            out.append(CandidateEffect(name, name, cls.balance, cls.description, tuple(params),
                                       phase_index=angle_phase_index(cls)))
    return out


ANGLE_VARIABLES = ("alpha1", "alpha2")


def angle_phase_index(cls) -> int:
    """The index of a term's phase parameter when the term is locked to a shaft's angle, else -1: a term effect that
    names ``alpha1`` or ``alpha2`` and has a parameter in rad whose name says phase (``phase_rad``, ``phi_rad``...).
    Such a term is fitted as a sine/cosine pair (fitting.screen): at the model's amplitude 0 its phase has no
    derivative, and the model's shaft angle lines up with the recording's only up to a constant, which the phase
    takes up."""
    if getattr(cls, "kind", "") != "term" or getattr(cls, "nominal", False):
        return -1
    try:
        args = plant_effects.term_arguments(cls)
    except (ValueError, TypeError, OSError, SyntaxError):
        return -1
    if not any(a in args for a in ANGLE_VARIABLES):
        return -1
    for i, p in enumerate(cls.parameters):
        if p.unit.strip().lower() in ("rad", "radian", "radians") and ("phase" in p.name or p.name.startswith("phi")):
            return i
    return -1


def effect_by_name(model, name: str) -> CandidateEffect:
    effects = {e.name: e for e in catalogue(model)}
    if name not in effects:
        raise ValueError(f"effect {name!r} is not in the catalogue; allowed: {', '.join(effects)}")
    return effects[name]


def apply_values(effect: CandidateEffect, values) -> dict:
    """The parameter set {"effect.param": value} that puts ``values`` (one per fitted parameter) in, with the
    candidate's fixed parameters."""
    out = {p.key: float(v) for p, v in zip(effect.parameters, np.atleast_1d(values))}
    out.update({k: float(v) for k, v in effect.fixed})
    return out


def config_overrides(parameter_set: Mapping) -> dict:
    """Config overrides (switch + value) that make a parameter set part of a model version."""
    out = {}
    for key, value in parameter_set.items():
        effect, pname = key.split(".", 1)
        out[f"effects.{effect}"] = True
        out[f"{effect}.{pname}"] = float(value)
    return out


def _catalogue_switches(catalogue) -> dict:
    """Every candidate effect of ``catalogue`` switched on (at its defaults, which an effect's author makes
    neutral: docs/effects.md)."""
    return {f"effects.{n}": True for n in candidate_effect_names(catalogue)}


_CONFIG_CACHE: dict = {}


def _plant_config(model, extra: Mapping | None = None):
    """model.plant_config(extra), remembered per (model content, extra): the validated config is frozen and a
    diagnosis asks for the same one ~100 times (a YAML parse each: 2.7 s of a 4 s recording's diagnosis)."""
    key = (json.dumps(model.plant, sort_keys=True, default=repr), tuple(str(f) for f in model.effect_files),
           tuple(sorted((str(k), repr(v)) for k, v in (extra or {}).items())))
    cfg = _CONFIG_CACHE.get(key)
    if cfg is None:
        if len(_CONFIG_CACHE) >= 64:
            _CONFIG_CACHE.clear()
        cfg = _CONFIG_CACHE[key] = model.plant_config(extra)
    return cfg


def simulate_sets(model, sets: Sequence[Mapping], seeds: Sequence[int], n_samples: int,
                  conditions: Mapping | None = None, noise: bool = True,
                  signals: Sequence[str] = ("a1", "a2", "omega1", "angle_difference")) -> dict[str, np.ndarray]:
    """Run every parameter set x every seed; -> {signal: (n_sets, n_seeds, n_samples)}.

    One batch per seed (``noise_seed=seed``: all sets on the same noise), the sets as its scenarios with
    per-scenario parameters. ``conditions``: config overrides of the measurement (e.g. pulse timing).
    """
    seeds = [int(s) for s in seeds]
    extra = dict(conditions or {})
    # the model's own effect switches stay as they are; every other catalogue effect on at its neutral default
    switches = _catalogue_switches(model.catalogue)
    own = _plant_config(model)
    enabled = {c.name for c in own.catalogue.enabled(own)}
    switches = {k: v for k, v in switches.items() if k.split(".", 1)[1] not in enabled}
    extra.update(switches)
    cfg = _plant_config(model, extra)
    lead = pulse_lead_samples(cfg)
    if lead:
        # a recording that starts inside a pulse: the model starts `lead` samples earlier, where no pulse is on,
        # with the same train, and those samples are dropped (pulse_lead_samples)
        extra["pulse_load.first_s"] = (round(cfg.pulse_load.first_s * cfg.simulation.sample_rate_hz) + lead
                                       - round(cfg.pulse_load.period_s * cfg.simulation.sample_rate_hz)) \
            / cfg.simulation.sample_rate_hz
        cfg = _plant_config(model, extra)
    keys = sorted({k for s in sets for k in s})
    n_sets, n_seeds = len(sets), len(seeds)
    params = {}
    for k in keys:
        effect, pname = k.split(".", 1)
        cur = _current(cfg, effect, pname)
        per_set = np.array([float(s.get(k, cur)) for s in sets])
        params[k] = np.repeat(per_set, n_seeds)          # scenario order: set-major, then seed
    nom = model.nominal
    # one batch: every (set, seed) a scenario. The drifts are parameters, not scenario fields, so every
    # scenario of seed k has the same (seed, width, eta_k, n1) and hence the same noise (common random
    # numbers across the sets); different seeds are independent realisations.
    scen = [Scenario(width_m=nom["width_m"], eta_k=nom["eta_k"], n1=nom["n1"], seed=int(seed))
            for _ in sets for seed in seeds]
    sim = PlantSimulator(scen, config=cfg, noise=noise, outputs=tuple(signals), parameters=params or None)
    if lead:
        sim.run(lead)
    ch = sim.run(n_samples)
    out = {s: getattr(ch, s).reshape(n_sets, n_seeds, n_samples) for s in signals}
    return out


def pulse_lead_samples(cfg) -> int:
    """Samples the model must run before a recording's first sample so that its pulse train is periodic over the
    whole recording: 0, unless a pulse is on at sample 0.

    The plant's pulse train is periodic before sample 0 (the run-in) and starts at ``first_s`` after it: a pulse that
    began before sample 0 stops at sample 0 (plant/disturbances.pulse_load_pu; the paper's settled start, first
    pulse at 0.05 s). A recording cut from a running drive -- a watch's snapshot, any bag that starts mid-stream --
    starts where its phase falls: its recovered ``first_s`` (analysis.recover_conditions: the next pulse's start)
    is above period - duration when a pulse is on at its first sample, and the model would then drop that pulse's
    1.6 p.u. for up to its 60 ms. A snapshot starts ~2 s (8 periods) before an onset entry, so just after a pulse's
    start: recovered first_s 0.2499 s, the model's first pulse cut to 4 samples, its motor speeding up and its next
    events settling from it (noise-free, a drive cut 0.4 ms after a pulse's start: the model's motor speed off by
    77 % of its spread rms, its event average by 4.4 m/s^2 rms; test_workbench_conditions.py). Measured on a friction
    snapshot (docs/model_watch.md): diagnose said 'partial' (friction explains 99 %, the event-average residual 3.9x
    the noise floor in the settling phase at level a6; the model's a2-vs-motor-speed correlation -0.10..0.30 against
    the drive's 0.75). With the lead the model starts ``duration`` samples earlier, where that pulse starts, and the
    train is the recording's throughout."""
    fs = cfg.simulation.sample_rate_hz
    pl = cfg.pulse_load
    k0, period, duration = (int(round(x * fs)) for x in (pl.first_s, pl.period_s, pl.duration_s))
    if duration <= 0 or period <= duration or not (period - duration < k0 < period):
        return 0
    return duration
