"""Plant configuration: dataclasses, YAML loading and validation (SPEC section 3).

The defaults live in ``config/plant.yaml``; :func:`load_plant_config` reads it (or another file,
or a dict of overrides), checks every key against its allowed range and returns a frozen
:class:`PlantConfig`. Bad input raises ``ValueError`` naming the key and the allowed range.
"""
from __future__ import annotations

import copy
import dataclasses
import json
import math
import os
from dataclasses import dataclass, field, fields
from pathlib import Path
from typing import Any, Mapping

import yaml

from backlash_monitor.files.config import closest, config_file
from .effects import NOMINAL
from .catalogue import builtin_catalogue

# the packaged config/plant.yaml (files.config: the source tree's, else the installed one)
DEFAULT_CONFIG_PATH = config_file("plant.yaml")


@dataclass(frozen=True)
class MotorConfig:
    r_s_pu: float = 0.059
    r_r_pu: float = 0.048
    x_s_pu: float = 1.92
    x_r_pu: float = 1.92
    x_m_pu: float = 1.82
    mechanical_time_constant_s: float = 0.86
    supply_voltage_pu: float = 1.0
    supply_frequency_hz: float = 50.0
    pole_pairs: int = 2
    base_torque_Nm: float = 20.0

    @property
    def w_pu(self) -> float:
        """w = x_s*x_r - x_m^2 (0.374 for the paper's values)."""
        return self.x_s_pu * self.x_r_pu - self.x_m_pu ** 2

    @property
    def base_angular_frequency_rad_s(self) -> float:
        """Omega_b = 2*pi*f."""
        return 2.0 * math.pi * self.supply_frequency_hz

    @property
    def base_mechanical_speed_rad_s(self) -> float:
        """Omega_mb = Omega_b / p."""
        return self.base_angular_frequency_rad_s / self.pole_pairs

    @property
    def rotor_inertia_kgm2(self) -> float:
        """J1 = T_m * T_b / Omega_mb."""
        return self.mechanical_time_constant_s * self.base_torque_Nm / self.base_mechanical_speed_rad_s


@dataclass(frozen=True)
class ClutchConfig:
    contact_stiffness_Nm_per_rad: float = 3000.0
    contact_damping_Nms_per_rad: float = 20.0


@dataclass(frozen=True)
class LoadConfig:
    mass_kg: float = 10.0
    spring_stiffness_N_per_m: float = 100.0
    wheel_radius_m: float = 0.15
    wheel_inertia_kgm2: float = 0.2
    absorber_area_m2: float = 0.00311565
    absorber_gap_m: float = 1.0e-6
    working_resistance_N: float = 30.0


@dataclass(frozen=True)
class PulseLoadConfig:
    amplitude_pu: float = 1.6
    duration_s: float = 0.06
    period_s: float = 0.25
    first_s: float = 0.05


@dataclass(frozen=True)
class DisturbanceConfig:
    gaussian_mean_pu: float = 0.0
    gaussian_variance_pu2: float = 0.05
    gaussian_hold_s: float = 2.0e-4
    pulse_mean_pu: float = 0.0
    pulse_variance_pu2: float = 0.05
    pulse_hold_s: float = 2.0e-3


@dataclass(frozen=True)
class SimulationConfig:
    sample_rate_hz: float = 50000.0
    window_samples: int = 2048
    backend: str = "auto"
    run_in_s: float = 4.0

    @property
    def sample_period_s(self) -> float:
        return 1.0 / self.sample_rate_hz


class EffectSwitches(dict):
    """On/off switch of every effect of the config's catalogue (``PlantConfig.catalogue``): a
    read-only dict name -> bool that also reads as attributes (``cfg.effects.spring``). It holds the
    nominal model's eight switches (as the former dataclass did, so a nominal config's
    ``dataclasses.asdict`` and hash are unchanged) and every other effect that is switched on; any other
    effect of the catalogue (``known``: its names; None: the built-in catalogue) reads as False."""

    def __init__(self, switches=None, known=None):
        data = {c.name: bool(c.nominal) for c in NOMINAL}
        for key, value in dict(switches or {}).items():
            if key in data or value:
                data[key] = bool(value)
        dict.update(self, data)
        object.__setattr__(self, "_known", None if known is None else frozenset(known))

    def _is_known(self, key) -> bool:
        if self._known is not None:
            return key in self._known
        return key in builtin_catalogue()

    def __missing__(self, key):
        if self._is_known(key):
            return False
        raise KeyError(key)

    def get(self, key, default=None):
        if key in self:
            return dict.__getitem__(self, key)
        return False if self._is_known(key) else default

    def __getattr__(self, key):
        if key.startswith("__"):
            raise AttributeError(key)
        try:
            return self[key]
        except KeyError:
            raise AttributeError(key) from None

    def _readonly(self, *args, **kwargs):
        raise TypeError("EffectSwitches is read-only; use PlantConfig.with_overrides")

    __setitem__ = __delitem__ = update = pop = popitem = clear = setdefault = _readonly
    __setattr__ = _readonly

    def __hash__(self):
        return hash(tuple(sorted(self.items())))

    def __reduce__(self):                 # copy, deepcopy and pickle rebuild through __init__
        return (EffectSwitches, (dict(self), self._known))


EffectsConfig = EffectSwitches   # the former dataclass's name


@dataclass(frozen=True)
class PlantConfig:
    motor: MotorConfig = field(default_factory=MotorConfig)
    clutch: ClutchConfig = field(default_factory=ClutchConfig)
    load: LoadConfig = field(default_factory=LoadConfig)
    pulse_load: PulseLoadConfig = field(default_factory=PulseLoadConfig)
    disturbances: DisturbanceConfig = field(default_factory=DisturbanceConfig)
    simulation: SimulationConfig = field(default_factory=SimulationConfig)
    effects: EffectSwitches = field(default_factory=EffectSwitches)
    constant_motor_load_pu: float = 0.0

    def __eq__(self, other):
        if not isinstance(other, PlantConfig):
            return NotImplemented
        return self.to_dict() == other.to_dict()      # effect parameters included


    @property
    def catalogue(self):
        """The EffectCatalogue this config's effect names were validated against (load_plant_config's
        ``catalogue``; default: the built-in one, backlash_monitor.plant.catalogue.builtin_catalogue)."""
        cat = self.__dict__.get("_catalogue")
        if cat is None:
            cat = builtin_catalogue()
        return cat

    @property
    def effect_parameters(self) -> dict:
        """Parameters of the catalogue's effects that have no key in the sections above:
        {effect name: {parameter name: value}} (defaults from the effect class when absent). Not a dataclass
        field, so ``dataclasses.asdict`` (and the classifier's config hash) of a nominal config is unchanged."""
        return self.__dict__.get("_effect_parameters", {})

    def to_dict(self) -> dict:
        out = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name == "effects":
                out[f.name] = dict(value)
            elif dataclasses.is_dataclass(value):
                out[f.name] = dataclasses.asdict(value)
            else:
                out[f.name] = value
        for name, params in self.effect_parameters.items():
            out[name] = dict(params)
        return out

    def effect_parameter(self, effect: str, name: str) -> float:
        """The configured value of one effect parameter (its config key, its section, or the default)."""
        cls = self.catalogue.get(effect)
        p = cls.parameter(name)
        if p.config_key is not None:
            node = self
            for part in p.config_key.split("."):
                node = getattr(node, part)
            return float(node)
        return float(self.effect_parameters.get(effect, {}).get(name, p.default))

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), sort_keys=True)

    def with_overrides(self, overrides: Mapping[str, Any]) -> "PlantConfig":
        """A validated copy with ``{"section.key": value}`` or nested-dict overrides applied (same catalogue)."""
        data = self.to_dict()
        _merge(data, _unflatten(overrides))
        return config_from_dict(data, catalogue=self.catalogue)


_SECTIONS = {
    "motor": MotorConfig,
    "clutch": ClutchConfig,
    "load": LoadConfig,
    "pulse_load": PulseLoadConfig,
    "disturbances": DisturbanceConfig,
    "simulation": SimulationConfig,
}

# (low, high, low_inclusive, high_inclusive) for numbers; a tuple of strings for choices.
INF = float("inf")
RANGES: dict[str, Any] = {
    "motor.r_s_pu": (0.0, 1.0, False, True),
    "motor.r_r_pu": (0.0, 1.0, False, True),
    "motor.x_s_pu": (0.0, 20.0, False, True),
    "motor.x_r_pu": (0.0, 20.0, False, True),
    "motor.x_m_pu": (0.0, 20.0, False, True),
    "motor.mechanical_time_constant_s": (0.0, 100.0, False, True),
    "motor.supply_voltage_pu": (0.0, 2.0, False, True),
    "motor.supply_frequency_hz": (0.0, 1000.0, False, True),
    "motor.pole_pairs": (1, 64, True, True),
    "motor.base_torque_Nm": (0.0, 1.0e6, False, True),
    "clutch.contact_stiffness_Nm_per_rad": (0.0, 1.0e7, False, True),
    "clutch.contact_damping_Nms_per_rad": (0.0, 1.0e5, True, True),
    "load.mass_kg": (0.0, 1.0e5, False, True),
    "load.spring_stiffness_N_per_m": (0.0, 1.0e7, True, True),
    "load.wheel_radius_m": (0.0, 10.0, False, True),
    "load.wheel_inertia_kgm2": (0.0, 1.0e4, False, True),
    "load.absorber_area_m2": (0.0, 10.0, True, True),
    "load.absorber_gap_m": (0.0, 1.0, False, True),
    "load.working_resistance_N": (0.0, 1.0e5, True, True),
    "pulse_load.amplitude_pu": (-10.0, 10.0, True, True),
    "pulse_load.duration_s": (0.0, 1.0e4, True, True),
    "pulse_load.period_s": (0.0, 1.0e4, False, True),
    "pulse_load.first_s": (0.0, 1.0e4, True, True),
    "disturbances.gaussian_mean_pu": (-10.0, 10.0, True, True),
    "disturbances.gaussian_variance_pu2": (0.0, 10.0, True, True),
    "disturbances.gaussian_hold_s": (0.0, 1.0e4, False, True),
    "disturbances.pulse_mean_pu": (-10.0, 10.0, True, True),
    "disturbances.pulse_variance_pu2": (0.0, 10.0, True, True),
    "disturbances.pulse_hold_s": (0.0, 1.0e4, False, True),
    "simulation.sample_rate_hz": (1000.0, 1.0e7, True, True),
    "simulation.window_samples": (1, 1 << 24, True, True),
    "simulation.backend": ("auto", "numba", "numba-scalar", "numpy"),
    "simulation.run_in_s": (0.0, 1.0e4, True, True),
    "constant_motor_load_pu": (-10.0, 10.0, True, True),
}


def _describe_range(spec) -> str:
    if isinstance(spec[0], str):
        return "one of " + ", ".join(repr(s) for s in spec)
    lo, hi, lo_inc, hi_inc = spec
    return f"{lo} {'<=' if lo_inc else '<'} value {'<=' if hi_inc else '<'} {hi}"


def _check_value(key: str, value: Any, expected_type: type) -> Any:
    spec = RANGES.get(key)
    if expected_type is bool:
        if not isinstance(value, bool):
            raise ValueError(f"plant config: {key} = {value!r} is not allowed; allowed: true or false")
        return value
    if expected_type is str:
        if not isinstance(value, str) or (spec is not None and value not in spec):
            raise ValueError(f"plant config: {key} = {value!r} is not allowed; allowed: {_describe_range(spec)}")
        return value
    if isinstance(value, str):  # YAML 1.1 reads "1e-6" (no dot) as a string
        try:
            value = float(value)
        except ValueError:
            pass
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ValueError(f"plant config: {key} = {value!r} is not a number; allowed: {_describe_range(spec)}")
    if expected_type is int:
        if float(value) != int(value):
            raise ValueError(f"plant config: {key} = {value!r} is not an integer; allowed: {_describe_range(spec)}")
        value = int(value)
    else:
        value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"plant config: {key} = {value!r} is not finite; allowed: {_describe_range(spec)}")
    lo, hi, lo_inc, hi_inc = spec
    ok_lo = value >= lo if lo_inc else value > lo
    ok_hi = value <= hi if hi_inc else value < hi
    if not (ok_lo and ok_hi):
        raise ValueError(f"plant config: {key} = {value!r} is out of range; allowed: {_describe_range(spec)}")
    return value


def _field_type(f) -> type:
    t = f.type if not isinstance(f.type, str) else {"float": float, "int": int, "bool": bool, "str": str}[f.type]
    return t


def _build_section(name: str, cls, data: Any):
    if data is None:
        data = {}
    if not isinstance(data, Mapping):
        raise ValueError(f"plant config: section {name!r} must be a mapping of keys to values")
    known = {f.name: f for f in fields(cls)}
    unknown = sorted(set(data) - set(known))
    if unknown:
        raise ValueError(f"plant config: unknown key {name}.{unknown[0]}"
                         f"{_nearest(f'{name}.{unknown[0]}', [f'{name}.{k}' for k in known])}; allowed keys in {name!r}: "
                         + ", ".join(sorted(known)))
    kwargs = {}
    for key, value in data.items():
        kwargs[key] = _check_value(f"{name}.{key}", value, _field_type(known[key]))
    # validate the defaults too (keeps one code path) and the cross-key rules below
    return cls(**kwargs)


def _nearest(key: str, candidates) -> str:
    """`` (nearest valid key: x)``: a plant config always names its closest key (files.config.closest)."""
    near = closest(key, candidates, cutoff=0.0)
    return f" (nearest valid key: {near})" if near else ""


def _valid_keys(reg) -> list:
    """Every valid dotted key (for the nearest-key hint); ``reg``: the EffectCatalogue."""
    keys = [f"{name}.{f.name}" for name, cls in _SECTIONS.items() for f in fields(cls)]
    keys += ["constant_motor_load_pu"]
    for n, c in reg.items():
        keys.append(f"effects.{n}")
        keys += [f"{n}.{p.name}" for p in c.parameters if p.config_key is None and p.source == "config"]
    return keys


def _build_switches(data: Any, reg) -> EffectSwitches:
    if data is None:
        data = {}
    if not isinstance(data, Mapping):
        raise ValueError("plant config: section 'effects' must be a mapping of effect names to true/false")
    for key, value in data.items():
        if key not in reg:
            raise ValueError(f"plant config: unknown key effects.{key}{_nearest('effects.' + str(key), ['effects.' + n for n in reg])}; "
                             "allowed: the effects of the catalogue (docs/effects.md; "
                             "plug-ins with --effects-file FILE)")
        if not isinstance(value, bool):
            raise ValueError(f"plant config: effects.{key} = {value!r} is not allowed; allowed: true or false")
    return EffectSwitches(dict(data), known=reg.names)


def _build_effect_parameters(name: str, cls, data: Any, reg) -> dict:
    if not isinstance(data, Mapping):
        raise ValueError(f"plant config: section {name!r} must be a mapping of parameter names to values")
    own = {p.name: p for p in cls.parameters if p.config_key is None and p.source == "config"}
    out = {}
    for key, value in data.items():
        if key not in own:
            raise ValueError(f"plant config: unknown key {name}.{key}{_nearest(f'{name}.{key}', [f'{name}.{k}' for k in own] or _valid_keys(reg))}; "
                             f"allowed keys in {name!r}: " + (", ".join(own) or "none"))
        if isinstance(value, str):
            try:
                value = float(value)
            except ValueError:
                pass
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"plant config: {name}.{key} = {value!r} is not a number; allowed: "
                             f"{own[key].bounds[0]} <= value <= {own[key].bounds[1]} [{own[key].unit}]")
        try:
            own[key].check(name, float(value))
        except ValueError as exc:
            raise ValueError(f"plant config: {exc}") from None
        out[key] = float(value)
    return out


def config_from_dict(data: Mapping[str, Any] | None, catalogue=None) -> PlantConfig:
    """Validated :class:`PlantConfig` from a (possibly partial) nested dict; missing keys take defaults.
    ``catalogue``: the EffectCatalogue whose effects it may switch on and set (default: the built-in one);
    the config carries it (``cfg.catalogue``)."""
    if catalogue is None:
        catalogue = builtin_catalogue()
    data = dict(data or {})
    reg = catalogue
    param_sections = {n: c for n, c in reg.items()
                      if any(p.config_key is None and p.source == "config" for p in c.parameters)}
    allowed_top = set(_SECTIONS) | {"constant_motor_load_pu", "effects"} | set(param_sections)
    unknown = sorted(set(data) - allowed_top)
    if unknown:
        sub = data[unknown[0]]
        if isinstance(sub, Mapping) and sub:           # name the whole key and the nearest valid whole key
            key = f"{unknown[0]}.{next(iter(sub))}"
            raise ValueError(f"plant config: unknown key {key}{_nearest(key, _valid_keys(reg))}; allowed: "
                             "SECTION.KEY of config/plant.yaml or EFFECT.PARAMETER of an effect of the catalogue")
        raise ValueError(f"plant config: unknown key {unknown[0]!r}{_nearest(unknown[0], sorted(allowed_top))}; "
                         "allowed top-level keys: " + ", ".join(sorted(allowed_top)))
    kwargs = {name: _build_section(name, cls, data.get(name)) for name, cls in _SECTIONS.items()}
    kwargs["effects"] = _build_switches(data.get("effects"), reg)
    if "constant_motor_load_pu" in data:
        kwargs["constant_motor_load_pu"] = _check_value("constant_motor_load_pu", data["constant_motor_load_pu"], float)
    effect_parameters = {n: _build_effect_parameters(n, c, data[n], reg) for n, c in param_sections.items()
                         if data.get(n)}
    cfg = PlantConfig(**kwargs)
    object.__setattr__(cfg, "_effect_parameters", effect_parameters)
    object.__setattr__(cfg, "_catalogue", catalogue)
    _check_cross_rules(cfg)
    return cfg


def _check_cross_rules(cfg: PlantConfig) -> None:
    m = cfg.motor
    if m.w_pu <= 0.0:
        raise ValueError(f"plant config: motor.x_m_pu = {m.x_m_pu} gives w = x_s*x_r - x_m^2 = {m.w_pu:.4g}; "
                         "allowed: x_m_pu^2 < x_s_pu*x_r_pu")
    fs = cfg.simulation.sample_rate_hz
    for key, value in (("pulse_load.duration_s", cfg.pulse_load.duration_s),
                       ("pulse_load.period_s", cfg.pulse_load.period_s),
                       ("pulse_load.first_s", cfg.pulse_load.first_s),
                       ("disturbances.gaussian_hold_s", cfg.disturbances.gaussian_hold_s),
                       ("disturbances.pulse_hold_s", cfg.disturbances.pulse_hold_s)):
        n = value * fs
        if abs(n - round(n)) > 1e-6 * max(1.0, n):
            raise ValueError(f"plant config: {key} = {value} is not a whole number of sample periods "
                             f"(1/{fs:g} s); allowed: integer multiples of the sample period")
    for key in ("disturbances.gaussian_hold_s", "disturbances.pulse_hold_s", "pulse_load.period_s"):
        section, name = key.split(".")
        if round(getattr(getattr(cfg, section), name) * fs) < 1:
            raise ValueError(f"plant config: {key} is shorter than one sample period; allowed: >= {1.0 / fs:g} s")
    if cfg.pulse_load.duration_s > cfg.pulse_load.period_s:
        raise ValueError(f"plant config: pulse_load.duration_s = {cfg.pulse_load.duration_s} exceeds "
                         f"pulse_load.period_s = {cfg.pulse_load.period_s}; allowed: 0 <= duration_s <= period_s")


def _unflatten(overrides: Mapping[str, Any]) -> dict:
    out: dict = {}
    for key, value in overrides.items():
        if isinstance(value, Mapping):
            _merge(out.setdefault(key, {}), _unflatten(value))
            continue
        parts = key.split(".")
        node = out
        for p in parts[:-1]:
            node = node.setdefault(p, {})
        node[parts[-1]] = value
    return out


def _merge(base: dict, extra: Mapping) -> None:
    for key, value in extra.items():
        if isinstance(value, Mapping) and isinstance(base.get(key), dict):
            _merge(base[key], value)
        else:
            base[key] = value


_PARSED: dict = {}          # a config file's text -> its parsed YAML (parsing plant.yaml costs ~7 ms; a
_PARSED_MAX = 8             # workbench fit or a test session loads it hundreds of times); the few last texts


def _parse_yaml(text: str):
    """``yaml.safe_load(text)``, remembered by the text itself (so an edited file is parsed again); the caller
    gets its own deep copy to change."""
    parsed = _PARSED.get(text)
    if parsed is None:
        parsed = yaml.safe_load(text)
        if len(_PARSED) >= _PARSED_MAX:
            _PARSED.pop(next(iter(_PARSED)))
        _PARSED[text] = parsed
    return copy.deepcopy(parsed)


def load_plant_config(path: str | os.PathLike | None = None,
                      overrides: Mapping[str, Any] | None = None, catalogue=None) -> PlantConfig:
    """Load and validate the plant config (default: ``config/plant.yaml``).

    ``overrides``: ``{"load.mass_kg": 12.0}`` or nested dicts, applied on top of the file.
    ``catalogue``: the EffectCatalogue of the effects it may name (default: the built-in one; with a user's
    plug-ins: ``builtin_catalogue().with_files([...])``); the config carries it as ``cfg.catalogue``.
    Raises ``ValueError`` naming the key and its allowed range on bad input.
    """
    p = Path(path) if path is not None else DEFAULT_CONFIG_PATH
    if not p.is_file():
        raise ValueError(f"plant config: file {str(p)!r} does not exist")
    try:
        data = _parse_yaml(p.read_text()) or {}
    except yaml.YAMLError as exc:
        raise ValueError(f"plant config: {p} is not valid YAML: {exc}") from None
    if not isinstance(data, dict):
        raise ValueError(f"plant config: {p} must hold a mapping of sections")
    if overrides:
        _merge(data, _unflatten(overrides))
    return config_from_dict(data, catalogue=catalogue)


def parse_override(text: str) -> tuple:
    """``"SECTION.KEY=VALUE"`` -> (key, YAML-parsed value) (the ``--set`` syntax of the commands and the
    plant_simulator node's ``plant_set``)."""
    if "=" not in text:
        raise ValueError(f"plant config override {text!r}: expected SECTION.KEY=VALUE, e.g. load.mass_kg=12 or "
                         "effects.wheel_coulomb_friction=true")
    key, value = text.split("=", 1)
    try:
        parsed = yaml.safe_load(value)
    except yaml.YAMLError:
        parsed = value
    return key.strip(), parsed
