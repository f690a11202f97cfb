"""Making the next model version: catalogue effects switched on with their (fitted) values."""
from __future__ import annotations

import copy
from dataclasses import dataclass, field

from . import plant_adapter
from .diagnosis_result import MEASURAND_EFFECTS
from .model import WorkbenchModel, _set_nested


# a drift's target (plant/effects.py DRIFTS) -> where its nominal value lives: "nominal.KEY" (the model's nominal
# conditions) or a plant config key; targets "effect.param" map through the parameter's config_key. A drift whose
# target has no nominal value in the config (supply_voltage_scale: the grid's, 1.0 by definition) stays an effect.
NOMINAL_TARGETS = {"eta_k": "nominal.eta_k", "n1": "nominal.n1", "mass_kg": "load.mass_kg",
                   "wheel_inertia_kgm2": "load.wheel_inertia_kgm2", "rotor_resistance_pu": "motor.r_r_pu"}


def nominal_key(model: WorkbenchModel, effect: str) -> str | None:
    """Where the nominal value a catalogue drift ``effect`` moves lives ("nominal.n1", "load.mass_kg", ...); None:
    not a drift of a nominal value (an effect, or a drift with no nominal value in the config)."""
    cls = model.catalogue.get(effect) if effect in model.catalogue else None
    if cls is None or getattr(cls, "kind", None) != "drift" or effect in MEASURAND_EFFECTS:
        return None
    target = cls.target
    if target in NOMINAL_TARGETS:
        return NOMINAL_TARGETS[target]
    if "." in target:
        owner, pname = target.split(".", 1)
        if owner in model.catalogue:
            try:
                return model.catalogue[owner].parameter(pname).config_key
            except (KeyError, ValueError, AttributeError):
                return None
    return None


def _config_value(cfg, key: str) -> float:
    node = cfg
    for part in key.split("."):
        node = getattr(node, part)
    return float(node)


def fold_drift(model: WorkbenchModel, new: WorkbenchModel, add: "EffectValues") -> dict | None:
    """A diagnosed drift of a nominal value made the new version's nominal value: ``new``'s nominal (or plant
    value) set to the value the drift fitted, the drift not switched on. -> the nominal update's record, or None
    when ``add`` is not such a drift (it is then added as an effect). The fitted change replaces the model's own
    drift of that kind (a candidate's value overrides the model's), so the new value is base (+) change."""
    key = nominal_key(model, add.effect)
    if key is None or len(add.parameters) != 1:
        return None
    cls = model.catalogue[add.effect]
    (pname, change), = add.parameters.items()
    change = float(change)
    lower, upper = cls.parameter(pname).bounds
    if not lower <= change <= upper:
        raise ValueError(f"effect {add.effect}: {pname} = {change:g} is out of its range; allowed: "
                         f"{lower:g} <= {pname} <= {upper:g}")
    if key.startswith("nominal."):
        old = float(model.nominal[key.split(".", 1)[1]])
    else:
        old = _config_value(model.plant_config(), key)
    value = old * (1.0 + change) if cls.relative else old + change
    sigma = (add.uncertainty or {}).get(pname)
    sigma = None if sigma is None else abs(float(sigma)) * (abs(old) if cls.relative else 1.0)
    if key.startswith("nominal."):
        new.nominal[key.split(".", 1)[1]] = value
    else:
        _set_nested(new.plant, key, value)
    # the model's own drift of this kind (an older version that stacked it) is folded in: switched off
    if new.plant.get("effects", {}).get(add.effect):
        new.plant["effects"][add.effect] = False
        new.plant.pop(add.effect, None)
    return {"parameter": key.split(".", 1)[1] if key.startswith("nominal.") else key, "from": old, "value": value,
            "uncertainty": sigma, "effect": add.effect, "change": {pname: change}, "from_diagnosis": add.source}


@dataclass
class EffectValues:
    effect: str
    parameters: dict
    uncertainty: dict = field(default_factory=dict)
    source: str = ""


def add_effects(model: WorkbenchModel, additions, name: str | None = None, nominal=None,
                provenance=None) -> WorkbenchModel:
    """A new WorkbenchModel (version + 1) with every addition applied (validated); ``nominal``: nominal values
    that change (a measured backlash width: the measurand, never an effect); ``provenance``: where it came from.
    A backlash width drift among the additions is refused: the width is what the monitor measures. A drift of a
    nominal value (n1, eta_k, mass, stiffness, ...: :func:`nominal_key`) becomes the new version's nominal value,
    recorded in ``nominal_updates`` with its uncertainty and its source; every other addition is an effect."""
    for add in additions:
        if add.effect in MEASURAND_EFFECTS:
            raise ValueError(f"effect {add.effect}: the backlash width is the monitor's measurand, not a model effect; "
                             "set the model's nominal width instead (--width-m), or let add-effect take it from a "
                             "diagnosis")
    new = WorkbenchModel(name=name or model.name, version=model.version + 1,
                         parent=model.path.name if model.path else f"{model.name} v{model.version} (unsaved)",
                         nominal={**model.nominal, **(nominal or {})}, plant=copy.deepcopy(model.plant),
                         effects_added=copy.deepcopy(model.effects_added),
                         effect_files=list(model.effect_files), provenance=dict(provenance or {}),
                         nominal_updates=copy.deepcopy(model.nominal_updates))
    cands = plant_adapter.catalogue(model, not_event_locked=True)   # a version may hold any catalogue effect
    for add in additions:
        update = fold_drift(model, new, add)
        if update is not None:
            new.nominal_updates.append(update)
            continue
        mine = [c for c in cands if c.effect == add.effect or c.name == add.effect]
        if not mine:
            raise ValueError(f"effect {add.effect!r} is not in the catalogue; allowed: "
                             + ", ".join(sorted({c.effect for c in cands})))
        params = {p.name: (p.key, p.unit, p.lower, p.upper) for c in mine for p in c.parameters}
        # a candidate's fixed form parameters (the low-pass's sections): within the effect's own bounds
        cls = model.catalogue[mine[0].effect]
        for c in mine:
            for key, _ in c.fixed:
                q = cls.parameter(key.split(".", 1)[1])
                params.setdefault(q.name, (key, q.unit, q.bounds[0], q.bounds[1]))
        unknown = sorted(set(add.parameters) - set(params))
        if unknown:
            raise ValueError(f"effect {add.effect}: unknown parameter {unknown[0]!r}; allowed: {', '.join(sorted(params))}")
        values = {}
        for pname, v in add.parameters.items():
            key, unit, lower, upper = params[pname]
            v = float(v)
            if not lower <= v <= upper:
                raise ValueError(f"effect {add.effect}: {pname} = {v:g} {unit} is out of its range; allowed: "
                                 f"{lower:g} <= {pname} <= {upper:g}")
            values[key] = v
        for k, v in plant_adapter.config_overrides(values).items():
            _set_nested(new.plant, k, v)
        new.effects_added.append({"effect": mine[0].effect, "parameters": {k.split(".", 1)[1]: v for k, v in values.items()},
                                  "uncertainty": {k: float(v) for k, v in (add.uncertainty or {}).items()},
                                  "from": add.source})
    new.plant_config()
    return new
