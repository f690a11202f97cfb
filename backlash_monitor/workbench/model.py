"""A workbench *model*: a versioned YAML holding the plant config (as overrides of config/plant.yaml), the
drive's nominal conditions (width, eta_k, n1) and the effects added so far; plus its history log.

File layout (docs/workbench.md)::

    workbench_model: 1          # format version
    name: drive7
    version: 2                  # model version, counts up with every add-effect
    parent: drive7_v1.yaml      # the file this version was made from (null for the first)
    nominal: {width_m: 0.0075, eta_k: 0.025, n1: 0.89}
    plant: {load: {mass_kg: 12.9}, effects: {constant_motor_load: true}, constant_motor_load_pu: 0.1}
    effects_added:              # what add-effect put in, with the fitted values and uncertainties
      - {effect: load_mass, parameters: {mass_kg: 12.9}, uncertainty: {mass_kg: 0.2}, from: diagnosis.json}
    nominal_updates:            # nominal values a diagnosed drift moved (the drift is not kept as an effect)
      - {parameter: n1, from: 0.89, value: 0.9104, uncertainty: 0.0004, effect: absorber_flow_index_drift,
         from_diagnosis: diag.json of 2026-11-28 22:12}
    effect_files: [my_effects.py]   # optional: the user's plug-in effect files (relative to this file)

The history log is ``workbench_history.jsonl`` beside the model file: one JSON line per version made and
per check (compare/diagnose of a version against a measurement, with its errors).
"""
from __future__ import annotations

import copy
import datetime as _dt
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Mapping, Sequence
import os

import yaml

from backlash_monitor.plant import PATTERN_ETA_K, builtin_catalogue, load_plant_config
from backlash_monitor.plant.config import _merge, _unflatten

FORMAT_VERSION = 1
HISTORY_FILE = "workbench_history.jsonl"
DEFAULT_NOMINAL = {"width_m": 0.0075, "eta_k": PATTERN_ETA_K, "n1": 0.89}
NOMINAL_RANGES = {"width_m": (0.0, 0.05), "eta_k": (0.0, 100.0), "n1": (0.0, 3.0)}


class ModelError(ValueError):
    """A model file or override that cannot be used (the message names the key and the allowed values)."""


@dataclass
class WorkbenchModel:
    name: str = "default"
    version: int = 1
    parent: str | None = None
    nominal: dict = field(default_factory=lambda: dict(DEFAULT_NOMINAL))
    plant: dict = field(default_factory=dict)        # overrides of config/plant.yaml (nested)
    effects_added: list = field(default_factory=list)
    path: Path | None = None
    effect_files: list = field(default_factory=list)  # absolute paths of the user's plug-in effect files
    provenance: dict = field(default_factory=dict)    # the diagnosis this version came from (add-effect): its file,
                                                      # measurement and measured width, for train's check
    nominal_updates: list = field(default_factory=list)   # nominal values a diagnosed drift moved (add-effect):
                                                          # {parameter, from, value, uncertainty, effect, from_diagnosis}

    @property
    def catalogue(self):
        """The EffectCatalogue of this model: the built-in effects plus its plug-in files (``effect_files``),
        built once per list of files and then frozen (its configs carry it)."""
        key = tuple(self.effect_files)
        cached = self.__dict__.get("_catalogue")
        if cached is None or cached[0] != key:
            try:
                cat = builtin_catalogue().with_files(key).freeze()
            except ValueError as exc:
                raise ModelError(str(exc)) from None
            cached = self.__dict__["_catalogue"] = (key, cat)
        return cached[1]

    def plant_config(self, extra: Mapping | None = None):
        """The validated PlantConfig of this model (``extra``: flat overrides on top, e.g. conditions); it
        carries the model's catalogue."""
        data = copy.deepcopy(self.plant)
        if extra:
            _merge(data, _unflatten(dict(extra)))
        try:
            return load_plant_config(overrides=data or None, catalogue=self.catalogue)
        except ValueError as exc:
            raise ModelError(str(exc)) from None

    def to_dict(self, directory=None) -> dict:
        """The file's content; ``directory``: where it is saved (plug-in files are written relative to it)."""
        out = {"workbench_model": FORMAT_VERSION, "name": self.name, "version": int(self.version),
               "parent": self.parent, "nominal": dict(self.nominal), "plant": copy.deepcopy(self.plant),
               "effects_added": copy.deepcopy(self.effects_added)}
        if self.effect_files:
            out["effect_files"] = [os.path.relpath(f, directory) if directory else str(f)
                                   for f in self.effect_files]
        if self.provenance:
            out["provenance"] = copy.deepcopy(self.provenance)
        if self.nominal_updates:
            out["nominal_updates"] = copy.deepcopy(self.nominal_updates)
        return out

    def label(self) -> str:
        return f"{self.name} v{self.version}"

    def save(self, path) -> Path:
        p = Path(path)
        p.write_text("# backlash_monitor workbench model (docs/workbench.md)\n"
                     + yaml.safe_dump(self.to_dict(p.resolve().parent), sort_keys=False))
        self.path = p
        return p


def _set_nested(data: dict, key: str, value) -> None:
    parts = key.split(".")
    node = data
    for part in parts[:-1]:
        node = node.setdefault(part, {})
        if not isinstance(node, dict):
            raise ModelError(f"--set {key}: {part} is not a section")
    node[parts[-1]] = value


def parse_set(text: str) -> tuple[str, object]:
    if "=" not in text:
        raise ModelError(f"--set {text!r}: expected SECTION.KEY=VALUE, e.g. load.mass_kg=12")
    key, value = text.split("=", 1)
    return key.strip(), yaml.safe_load(value)


def _load_effect_files(paths) -> list:
    """The absolute paths of the user's plug-in effect files ``paths``, checked: they load together into a
    catalogue with the built-in effects (ModelError naming the problem otherwise)."""
    out = []
    for f in paths:
        f = Path(f).resolve()
        if f not in out:
            out.append(f)
    try:
        builtin_catalogue().with_files(out)
    except ValueError as exc:
        raise ModelError(str(exc)) from None
    return out


MODEL_KEYS = ("workbench_model", "name", "version", "parent", "nominal", "plant", "effects_added", "effect_files",
              "provenance", "nominal_updates")


def model_from_dict(data, path=None, base_dir=None) -> WorkbenchModel:
    """A model from a model file's content (or a diagnosis's recorded effective model); ``path``: the file it
    was read from (effect files are relative to it, or to ``base_dir``). Not yet validated (load_model does)."""
    where = f"model file {path}" if path is not None else "model"
    if not isinstance(data, dict) or data.get("workbench_model") != FORMAT_VERSION:
        raise ModelError(f"{where}: not a workbench model (needs 'workbench_model: {FORMAT_VERSION}'; "
                         "see docs/workbench.md)")
    unknown = sorted(set(data) - set(MODEL_KEYS))
    if unknown:
        raise ModelError(f"{where}: unknown key {unknown[0]!r}; allowed: {', '.join(MODEL_KEYS[1:])}")
    files = data.get("effect_files") or []
    if not isinstance(files, list) or not all(isinstance(f, str) for f in files):
        raise ModelError(f"{where}: effect_files must be a list of Python file paths (relative to the model file)")
    root = Path(path).resolve().parent if path is not None else Path(base_dir or ".").resolve()
    files = [root / f for f in files]
    nominal = dict(DEFAULT_NOMINAL)
    nominal.update(data.get("nominal") or {})
    provenance = data.get("provenance") or {}
    if not isinstance(provenance, dict):
        raise ModelError(f"{where}: provenance must be a mapping (written by add-effect)")
    updates = data.get("nominal_updates") or []
    if not isinstance(updates, list) or not all(isinstance(u, dict) for u in updates):
        raise ModelError(f"{where}: nominal_updates must be a list of mappings (written by add-effect)")
    return WorkbenchModel(name=str(data.get("name", Path(path).stem if path else "default")),
                          version=int(data.get("version", 1)), parent=data.get("parent"), nominal=nominal,
                          plant=copy.deepcopy(data.get("plant") or {}),
                          effects_added=list(data.get("effects_added") or []),
                          path=Path(path) if path is not None else None,
                          effect_files=_load_effect_files(files), provenance=dict(provenance),
                          nominal_updates=copy.deepcopy(updates))


def load_model(path=None, sets: Sequence[str] = (), width_m: float | None = None, eta_k: float | None = None,
               n1: float | None = None, effect_files: Sequence = (), base: WorkbenchModel | None = None
               ) -> WorkbenchModel:
    """The model of ``path`` (None: the default model = config/plant.yaml at the default nominal
    conditions; ``base``: this model instead of a file, e.g. the one a diagnosis recorded), with ``--set``
    overrides and the nominal conditions' overrides; validated.
    ``effect_files``: the user's plug-in effect files (``--effects-file``), added to the model's
    catalogue (``model.catalogue``) that its plant config is validated against, and kept in the model
    (with those the file names)."""
    if base is not None:
        model = base
    elif path is None:
        model = WorkbenchModel()
    else:
        p = Path(path)
        if not p.is_file():
            raise ModelError(f"model file {str(p)!r} does not exist; give a workbench model YAML "
                             "(docs/workbench.md) or no --model for the default model")
        try:
            data = yaml.safe_load(p.read_text()) or {}
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            where = f" (line {mark.line + 1}, column {mark.column + 1})" if mark is not None else ""
            raise ModelError(f"model file {p} is not valid YAML{where}: {getattr(exc, 'problem', None) or exc}; "
                             "allowed: a workbench model YAML (docs/workbench.md)") from None
        model = model_from_dict(data, p)
    for f in _load_effect_files(effect_files):
        if f not in model.effect_files:
            model.effect_files.append(f)
    for text in sets:
        key, value = parse_set(text)
        _set_nested(model.plant, key, value)
    for key, value in (("width_m", width_m), ("eta_k", eta_k), ("n1", n1)):
        if value is not None:
            model.nominal[key] = float(value)
    for key, (lo, hi) in NOMINAL_RANGES.items():
        v = model.nominal.get(key)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or not lo < v <= hi:
            raise ModelError(f"model nominal {key} = {v!r} is out of range; allowed: {lo} < {key} <= {hi}")
        model.nominal[key] = float(v)
    unknown = sorted(set(model.nominal) - set(NOMINAL_RANGES))
    if unknown:
        raise ModelError(f"model nominal: unknown key {unknown[0]!r}; allowed: width_m, eta_k, n1")
    model.plant_config()   # validates the plant overrides (raises ModelError naming the key)
    return model


# --- history ---------------------------------------------------------------------------------------

def history_path(model_path) -> Path:
    return Path(model_path).resolve().parent / HISTORY_FILE


def append_history(model_path, entry: dict) -> None:
    entry = dict(entry)
    entry.setdefault("time_utc", _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"))
    with open(history_path(model_path), "a") as f:
        f.write(json.dumps(entry, default=float) + "\n")


def read_history(directory) -> list[dict]:
    p = Path(directory)
    p = p / HISTORY_FILE if p.is_dir() else history_path(p)
    if not p.is_file():
        return []
    out = []
    for line in p.read_text().splitlines():
        line = line.strip()
        if line:
            try:
                out.append(json.loads(line))
            except json.JSONDecodeError:
                continue
    return out


def record_check(model: WorkbenchModel, measurement: str, kind: str, fit_percent: dict, ratio: dict,
                 directory=None) -> Path | None:
    """Append a check of a model version against a measurement to its history: beside its file, or for an
    unsaved model (the default model, or one from --set/--width-m...) in ``directory`` (e.g. where the diagnosis
    is written, which add-effect's next version is usually written beside). None: nowhere to write it."""
    if model.path is None and directory is None:
        return None
    where = model.path if model.path is not None else Path(directory) / "(unsaved)"
    entry = {"type": "check", "model": model.path.name if model.path is not None else "(unsaved)",
             "name": model.name, "version": model.version, "measurement": str(measurement), "command": kind,
             "fit_percent": fit_percent, "residual_over_noise_floor": ratio}
    if model.path is None:
        entry["nominal"] = dict(model.nominal)
    append_history(where, entry)
    return history_path(where)
