"""Making the next model version: catalogue effects switched on with their (fitted) values."""
from __future__ import annotations

import copy
from dataclasses import dataclass, field

from . import plant_adapter
from .diagnosis import MEASURAND_EFFECTS
from .model import WorkbenchModel, _set_nested


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
    A backlash width drift among the additions is refused: the width is what the monitor measures."""
    for add in additions:
        if add.effect in MEASURAND_EFFECTS:
            raise ValueError(f"effect {add.effect}: the backlash width is the monitor's measurand, not a model effect; "
                             "set the model's nominal width instead (--width-m), or let add-effect take it from a "
                             "diagnosis")
    new = WorkbenchModel(name=name or model.name, version=model.version + 1,
                         parent=model.path.name if model.path else f"{model.name} v{model.version} (unsaved)",
                         nominal={**model.nominal, **(nominal or {})}, plant=copy.deepcopy(model.plant),
                         effects_added=copy.deepcopy(model.effects_added),
                         effect_files=list(model.effect_files), provenance=dict(provenance or {}))
    cands = plant_adapter.catalogue(model, not_event_locked=True)   # a version may hold any catalogue effect
    for add in additions:
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
