"""Making the next model version: catalogue effects switched on with their (fitted) values."""
from __future__ import annotations

import copy
from dataclasses import dataclass, field

from . import plant_adapter
from .model import WorkbenchModel, _set_nested


@dataclass
class EffectValues:
    effect: str
    parameters: dict
    uncertainty: dict = field(default_factory=dict)
    source: str = ""


def add_effects(model: WorkbenchModel, additions, name: str | None = None) -> WorkbenchModel:
    """A new WorkbenchModel (version + 1) with every addition applied (validated)."""
    new = WorkbenchModel(name=name or model.name, version=model.version + 1,
                         parent=model.path.name if model.path else f"{model.name} v{model.version} (unsaved)",
                         nominal=dict(model.nominal), plant=copy.deepcopy(model.plant),
                         effects_added=copy.deepcopy(model.effects_added))
    for add in additions:
        eff = plant_adapter.effect_by_name(model, add.effect)
        known = {p.name for p in eff.parameters}
        unknown = sorted(set(add.parameters) - known)
        if unknown:
            raise ValueError(f"effect {add.effect}: unknown parameter {unknown[0]!r}; allowed: {', '.join(sorted(known))}")
        values = []
        for p in eff.parameters:
            v = float(add.parameters.get(p.name, p.default))
            if not p.lower <= v <= p.upper:
                raise ValueError(f"effect {add.effect}: {p.name} = {v:g} {p.unit} is out of its bounds; allowed: "
                                 f"{p.lower:g} <= {p.name} <= {p.upper:g}")
            values.append(v)
        scen, conf = plant_adapter.apply_values(eff, values)
        for k, v in scen.items():
            new.nominal[k] = v
        for k, v in conf.items():
            _set_nested(new.plant, k, v)
        new.effects_added.append({"effect": add.effect, "parameters": dict(zip([p.name for p in eff.parameters],
                                                                              values)),
                                  "uncertainty": {k: float(v) for k, v in (add.uncertainty or {}).items()},
                                  "from": add.source})
    new.plant_config()
    return new
