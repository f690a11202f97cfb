"""The drive registry: one YAML file naming each drive, its nominal conditions and its current model version,
pattern library and watch reference, with the versions before (docs/registry.md).

The registry *is* the fleet file (config/fleet.yaml's layout, ``fleet/drives.py``): ``lines: {LINE: {DRIVE:
{...}}}`` with ``defaults``; a drive's entry holds the fleet's keys (width_m, eta_k, n1, seed, ...) and the
registry's::

    model: drives/line1_drive01_v2.yaml      # its current workbench model version (null: the default model at
                                             #   the drive's nominal width_m, eta_k, n1)
    library: drives/line1_drive01_v2.npz     # the pattern library its classifier uses (null: the packaged one)
    watch_reference: drives/line1_drive01_v2.watch.npz   # its model watch's reference (null: the default
                                                         #   model's, from the cache)
    versions:                                # the versions before, oldest first (written by train --drive)
      - {version: 1, model: null, library: null, watch_reference: null, until_utc: "2026-11-28T22:40:00+00:00"}

Paths are relative to the registry file. A drive is named by its hardware id ``LINE/DRIVE`` (its namespace is
``/LINE/DRIVE``) or by ``DRIVE`` alone when no other line has a drive of that name. Plain YAML and numpy-free: the
workbench commands, the model watch and the fleet all read it; only :func:`register` writes it (the whole file,
written beside and renamed, so a reader never sees half a file; comments in it are not kept).
"""
from __future__ import annotations

import datetime as _dt
import os
from dataclasses import dataclass, field
from pathlib import Path
import yaml

DEFAULT_REGISTRY = "drives.yaml"
VERSION_KEYS = ("model", "library", "watch_reference")   # what one version of a drive is
REGISTRY_KEYS = VERSION_KEYS + ("versions", "registered_utc")   # the registry's keys in a drive's entry
NOMINAL_DEFAULTS = {"width_m": 0.005, "eta_k": 0.025, "n1": 0.89}   # the fleet's (fleet/drives.py)


class RegistryError(ValueError):
    """A registry file or drive name that cannot be used (the message names it and the allowed values)."""


@dataclass
class DriveEntry:
    """One drive of the registry, its paths resolved against the registry file's folder."""
    line: str
    name: str
    parameters: dict                       # its fleet keys with the defaults applied (width_m, eta_k, n1, seed, ...)
    model: Path | None = None
    library: Path | None = None
    watch_reference: Path | None = None
    versions: list = field(default_factory=list)

    @property
    def hardware_id(self) -> str:
        return f"{self.line}/{self.name}"

    @property
    def namespace(self) -> str:
        return f"/{self.line}/{self.name}"

    @property
    def nominal(self) -> dict:
        """{width_m, eta_k, n1}: the drive's nominal conditions (the fleet's defaults where none is given)."""
        return {k: float(self.parameters.get(k, v)) for k, v in NOMINAL_DEFAULTS.items()}

    @property
    def version(self) -> int:
        return len(self.versions) + 1

    @property
    def model_name(self) -> str:
        """The name its models carry in the workbench history: the hardware id with '_' for '/'."""
        return self.hardware_id.replace("/", "_")


def read(path) -> dict:
    """The registry file's content (a mapping with ``lines``); RegistryError naming the problem."""
    p = Path(path)
    if not p.is_file():
        raise RegistryError(f"registry {p} does not exist; give the drive registry YAML with --registry "
                            f"(default ./{DEFAULT_REGISTRY}; layout: docs/registry.md)")
    try:
        data = yaml.safe_load(p.read_text(encoding="utf-8")) or {}
    except yaml.YAMLError as exc:
        raise RegistryError(f"registry {p} is not valid YAML: {str(exc).splitlines()[0]}") from None
    if not isinstance(data, dict) or not isinstance(data.get("lines"), dict) or not data["lines"]:
        raise RegistryError(f"registry {p}: needs 'lines: {{line1: {{drive01: {{...}}}}}}' with at least one drive "
                            "(docs/registry.md)")
    return data


def _resolve(root: Path, value, where: str, key: str) -> Path | None:
    if value is None or value == "":
        return None
    if not isinstance(value, str):
        raise RegistryError(f"{where}: {key} = {value!r}; allowed: a file path (relative to the registry) or null")
    return (root / value) if not os.path.isabs(value) else Path(value)


def entries(path) -> list[DriveEntry]:
    """Every drive of the registry ``path``."""
    data = read(path)
    root = Path(path).resolve().parent
    defaults = data.get("defaults") or {}
    if not isinstance(defaults, dict):
        raise RegistryError(f"registry {path}: defaults must be a mapping")
    out = []
    for line, members in data["lines"].items():
        if not isinstance(members, dict):
            raise RegistryError(f"registry {path}: line {line} must map drive names to their entries")
        for name, params in members.items():
            params = {**defaults, **(params or {})}
            if not isinstance(params, dict):
                raise RegistryError(f"registry {path}: {line}/{name} must be a mapping")
            where = f"registry {path}: {line}/{name}"
            versions = params.get("versions") or []
            if not isinstance(versions, list) or not all(isinstance(v, dict) for v in versions):
                raise RegistryError(f"{where}: versions must be a list of mappings (model, library, watch_reference)")
            out.append(DriveEntry(str(line), str(name), {k: v for k, v in params.items() if k not in REGISTRY_KEYS},
                                  *(_resolve(root, params.get(k), where, k) for k in VERSION_KEYS),
                                  versions=[dict(v) for v in versions]))
    return out


def find(path, name: str) -> DriveEntry:
    """The drive ``name`` (LINE/DRIVE, /LINE/DRIVE, or DRIVE when unique) of the registry ``path``."""
    drives = entries(path)
    key = str(name).strip("/")
    hits = [d for d in drives if d.hardware_id == key] or [d for d in drives if d.name == key]
    if len(hits) == 1:
        return hits[0]
    allowed = ", ".join(d.hardware_id for d in drives)
    if hits:
        raise RegistryError(f"--drive {name}: {len(hits)} drives of that name in {path}; give LINE/DRIVE: {allowed}")
    raise RegistryError(f"--drive {name}: no such drive in {path}; allowed: {allowed}")


def match(drives: list[DriveEntry], namespace: str | None = None, drive_name: str | None = None) -> DriveEntry | None:
    """The drive a recording belongs to: by its topics' namespace (/LINE/DRIVE) or its recorded drive name
    (hardware id LINE/DRIVE); None when no drive matches."""
    for key in (namespace, drive_name):
        k = str(key or "").strip("/")
        if not k:
            continue
        for d in drives:
            if d.hardware_id == k:
                return d
    return None


def register(path, name: str, model=None, library=None, watch_reference=None) -> DriveEntry:
    """Make (model, library, watch_reference) the drive's current version; the current one goes to its
    ``versions``. Paths are written relative to the registry file. The file is written beside and renamed."""
    p = Path(path)
    data = read(p)
    entry = find(p, name)
    root = p.resolve().parent
    node = data["lines"][entry.line].get(entry.name) or {}
    data["lines"][entry.line][entry.name] = node
    now = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    before = {k: node.get(k) for k in VERSION_KEYS}
    node.setdefault("versions", [])
    node["versions"].append({"version": len(node["versions"]) + 1, **before, "until_utc": now})

    def rel(x):
        return None if x is None else os.path.relpath(Path(x).resolve(), root)
    node.update({"model": rel(model), "library": rel(library), "watch_reference": rel(watch_reference),
                 "registered_utc": now})
    tmp = p.with_name(p.name + ".partial")
    tmp.write_text("# drive registry (docs/registry.md); written by train --drive\n"
                   + yaml.safe_dump(data, sort_keys=False), encoding="utf-8")
    os.replace(tmp, p)
    return find(p, name)
