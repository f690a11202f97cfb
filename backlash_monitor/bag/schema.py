"""ROS 2 `.msg` definitions: find them, concatenate them as rosbag2 does, parse them.

`full_definition("backlash_monitor_msgs/msg/SignalChunk")` gives the text that rosbag2 (Jazzy,
`rosbag2_cpp::LocalMessageDefinitionSource::get_full_text`) stores as the MCAP schema of a topic
with schema encoding `ros2msg`: the type's own `.msg` file verbatim, then, for each dependency
(sorted by name as written in the file, depth-first, each type once), a newline, a line of 80 `=`,
a line `MSG: pkg/Name` and that type's `.msg` file verbatim.

`parse_schema(name, text)` turns such a text (written by us, by rosbag2 or by rosbags) back into
`MsgSpec` objects, one per type, keyed by normalised name `pkg/msg/Name`.

Where the `.msg` files are looked for, in order: the ament index (`ament_index_python`, the
`AMENT_PREFIX_PATH` of a sourced install), `<sys.prefix>/share` (the PyPI ROS wheels put the standard
interfaces there), then this repository's `msg_defs/msg` (and its installed copy in
`share/backlash_monitor/msg_defs/msg`) for `backlash_monitor_msgs`.
"""
from __future__ import annotations

import functools
import json
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path

from .errors import UnknownSchemaError

OUR_PACKAGE = "backlash_monitor_msgs"
DELIMITER = "=" * 80 + "\n"

# rosbag2's regex for field types in .msg text ("foo_msgs/Bar" in "foo_msgs/Bar[] bar").
_MSG_FIELD_TYPE_RE = re.compile(r"(?:^|\n)\s*([a-zA-Z0-9_/]+)(?:\[[^\]]*\])?\s+")
_ROSBAG2_PRIMITIVES = {"bool", "byte", "char", "float32", "float64", "int8", "uint8", "int16",
                       "uint16", "int32", "uint32", "int64", "uint64", "string"}

# CDR primitive types: name -> (numpy dtype char, size in bytes)
PRIMITIVES = {
    "bool": ("?", 1), "byte": ("B", 1), "char": ("B", 1), "uint8": ("B", 1), "int8": ("b", 1),
    "uint16": ("H", 2), "int16": ("h", 2), "uint32": ("I", 4), "int32": ("i", 4),
    "uint64": ("Q", 8), "int64": ("q", 8), "float32": ("f", 4), "float64": ("d", 8),
}
STRING_TYPES = {"string", "wstring"}


def split_type_name(type_name: str) -> tuple[str, str, str]:
    """`pkg/msg/Name` or `pkg/Name` -> (pkg, 'msg', Name); anything else raises UnknownSchemaError."""
    parts = type_name.strip().split("/")
    if len(parts) == 2:
        return parts[0], "msg", parts[1]
    if len(parts) == 3:
        return parts[0], parts[1], parts[2]
    raise UnknownSchemaError(f"message type name {type_name!r} is not of the form pkg/msg/Name")


def normalize_type_name(type_name: str, package_context: str | None = None) -> str:
    """`pkg/Name`, `pkg/msg/Name` or (with a package context) `Name` -> `pkg/msg/Name`."""
    if "/" not in type_name:
        if type_name == "Header":  # ROS 1 shorthand, still accepted by parsers
            return "std_msgs/msg/Header"
        if not package_context:
            raise UnknownSchemaError(f"type {type_name!r} has no package")
        return f"{package_context}/msg/{type_name}"
    pkg, ns, name = split_type_name(type_name)
    return f"{pkg}/{ns}/{name}"


# ----------------------------------------------------------------------------------------------
# Finding .msg files


def _repo_msg_dirs() -> list[Path]:
    here = Path(__file__).resolve()
    dirs = [here.parents[2] / "msg_defs" / "msg"]  # source tree: <repo>/msg_defs/msg
    # installed ament_python package: <prefix>/lib/pythonX/site-packages/backlash_monitor/bag
    for parent in here.parents:
        cand = parent / "share" / "backlash_monitor" / "msg_defs" / "msg"
        if cand.is_dir():
            dirs.append(cand)
            break
    return dirs


def _share_dirs(package: str) -> list[Path]:
    out: list[Path] = []
    try:
        # deferred: optional (no ROS, or not installed: the AMENT_PREFIX_PATH walk below)
        from ament_index_python.packages import get_package_share_directory

        out.append(Path(get_package_share_directory(package)))
    except Exception:  # noqa: BLE001 - not installed / no ament index: fall through
        pass
    for prefix in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep):
        if prefix:
            out.append(Path(prefix) / "share" / package)
    out.append(Path(sys.prefix) / "share" / package)
    return out


@functools.lru_cache(maxsize=None)
def find_msg_file(type_name: str) -> Path:
    """Path of the `.msg` file of `pkg/msg/Name`; raises UnknownSchemaError when none is found."""
    pkg, ns, name = split_type_name(type_name)
    candidates = [d / ns / f"{name}.msg" for d in _share_dirs(pkg)]
    if pkg == OUR_PACKAGE and ns == "msg":
        candidates += [d / f"{name}.msg" for d in _repo_msg_dirs()]
    for cand in candidates:
        if cand.is_file():
            return cand
    raise UnknownSchemaError(
        f"no .msg definition found for {type_name!r} (looked in: "
        + ", ".join(str(c) for c in candidates) + ")")


def load_msg_text(type_name: str) -> str:
    return find_msg_file(normalize_type_name(type_name)).read_text(encoding="utf-8")


@functools.lru_cache(maxsize=None)
def type_hash(type_name: str) -> str:
    """The RIHS01 type hash of a type (from rosidl's `share/pkg/msg/Name.json`), or "" if unknown."""
    pkg, ns, name = split_type_name(normalize_type_name(type_name))
    full = f"{pkg}/{ns}/{name}"
    dirs = [d / ns for d in _share_dirs(pkg)]
    for d in dirs:
        path = d / f"{name}.json"
        if path.is_file():
            try:
                data = json.loads(path.read_text(encoding="utf-8"))
                for entry in data.get("type_hashes", []):
                    if entry.get("type_name") == full:
                        return str(entry.get("hash_string", ""))
            except (OSError, ValueError):
                continue
    return ""


def _rosbag2_dependencies(text: str, package_context: str) -> list[str]:
    deps = set()
    for m in _MSG_FIELD_TYPE_RE.finditer(text):
        t = m.group(1)
        if t in _ROSBAG2_PRIMITIVES:
            continue
        deps.add(t if "/" in t else f"{package_context}/{t}")
    return sorted(deps)  # std::set<std::string> order


@functools.lru_cache(maxsize=None)
def full_definition(type_name: str) -> str:
    """The concatenated definition text rosbag2 writes as the MCAP schema of `type_name`."""
    root = normalize_type_name(type_name)
    seen: set[str] = set()

    def rec(name: str, depth: int) -> str:
        if depth <= 0:
            raise UnknownSchemaError(f"definition of {root} nests too deep")
        pkg = split_type_name(name)[0]
        text = load_msg_text(name)
        out = text
        for dep in _rosbag2_dependencies(text, pkg):
            key = normalize_type_name(dep)
            if key in seen:
                continue
            seen.add(key)
            out += "\n" + DELIMITER + "MSG: " + dep + "\n" + rec(dep, depth - 1)
        return out

    return rec(root, 50)


# ----------------------------------------------------------------------------------------------
# Parsing


@dataclass(frozen=True)
class Field:
    name: str
    type: str            # primitive name, 'string'/'wstring', or normalised 'pkg/msg/Name'
    is_array: bool = False
    array_size: int | None = None   # fixed size T[N]; None for sequences T[] / T[<=N]
    upper_bound: int | None = None  # T[<=N]
    string_bound: int | None = None  # string<=N

    @property
    def is_primitive(self) -> bool:
        return self.type in PRIMITIVES

    @property
    def is_string(self) -> bool:
        return self.type in STRING_TYPES

    @property
    def is_complex(self) -> bool:
        return not (self.is_primitive or self.is_string)


@dataclass
class MsgSpec:
    name: str                      # pkg/msg/Name
    fields: list[Field] = field(default_factory=list)
    constants: dict[str, tuple[str, str]] = field(default_factory=dict)  # NAME -> (type, text)


_TYPE_RE = re.compile(
    r"^(?P<base>[A-Za-z][A-Za-z0-9_]*(?:/[A-Za-z][A-Za-z0-9_]*){0,2})"
    r"(?:<=(?P<sbound>\d+))?"
    r"(?P<arr>\[(?P<alen><=)?(?P<n>\d*)\])?$")


def parse_msg(name: str, text: str) -> MsgSpec:
    """Parse one `.msg` text (no delimiters) of type `name` (`pkg/msg/Name`)."""
    name = normalize_type_name(name)
    pkg = split_type_name(name)[0]
    spec = MsgSpec(name)
    for lineno, raw in enumerate(text.splitlines(), 1):
        line = raw.split("#", 1)[0].strip() if not _is_string_constant(raw) else raw.strip()
        if not line:
            continue
        parts = line.split(None, 1)
        if len(parts) < 2:
            raise UnknownSchemaError(f"{name}, line {lineno}: cannot parse {raw!r}")
        type_tok, rest = parts
        # constant: "TYPE NAME=VALUE" (spaces allowed around '=')
        if "=" in rest and (re.match(r"^[A-Za-z][A-Za-z0-9_]*\s*=", rest)):
            cname, value = rest.split("=", 1)
            spec.constants[cname.strip()] = (type_tok, value.strip())
            continue
        fname = rest.split(None, 1)[0]
        m = _TYPE_RE.match(type_tok)
        if not m:
            raise UnknownSchemaError(f"{name}, line {lineno}: bad field type {type_tok!r}")
        base = m.group("base")
        if base in PRIMITIVES or base in STRING_TYPES:
            btype = base
        else:
            btype = normalize_type_name(base, pkg)
        is_array = m.group("arr") is not None
        n = m.group("n")
        array_size = upper = None
        if is_array and n:
            if m.group("alen"):
                upper = int(n)
            else:
                array_size = int(n)
        sb = m.group("sbound")
        spec.fields.append(Field(fname, btype, is_array, array_size, upper,
                                 int(sb) if sb else None))
    return spec


def _is_string_constant(raw: str) -> bool:
    s = raw.strip()
    return bool(re.match(r"^w?string(<=\d+)?\s+[A-Za-z][A-Za-z0-9_]*\s*=", s))


def parse_schema(type_name: str, text: str, encoding: str = "ros2msg") -> dict[str, MsgSpec]:
    """Parse a concatenated `ros2msg` schema into {pkg/msg/Name: MsgSpec} (root included)."""
    if encoding != "ros2msg":
        raise UnknownSchemaError(
            f"schema of {type_name!r} has encoding {encoding!r}; only 'ros2msg' is supported")
    root = normalize_type_name(type_name)
    sections = re.split(r"^=+[ \t]*\r?$\n?", text, flags=re.M)
    specs: dict[str, MsgSpec] = {root: parse_msg(root, sections[0])}
    for sec in sections[1:]:
        lines = sec.split("\n", 1)
        head = lines[0].strip()
        if not head.startswith("MSG:"):
            raise UnknownSchemaError(f"schema of {type_name!r}: section without 'MSG:' line: {head!r}")
        dep = normalize_type_name(head[4:].strip())
        specs[dep] = parse_msg(dep, lines[1] if len(lines) > 1 else "")
    _check_resolved(root, specs)
    return specs


def _check_resolved(root: str, specs: dict[str, MsgSpec]) -> None:
    for spec in specs.values():
        for f in spec.fields:
            if f.is_complex and f.type not in specs:
                # builtin_interfaces are often left out by hand-written schemas: load them locally
                try:
                    dep_spec = parse_msg(f.type, load_msg_text(f.type))
                except UnknownSchemaError:
                    raise UnknownSchemaError(
                        f"schema of {root!r}: field {spec.name}.{f.name} has type {f.type!r} "
                        "whose definition is neither in the schema nor installed") from None
                specs[f.type] = dep_spec
                _check_resolved(root, specs)
                return


def local_specs(type_name: str) -> dict[str, MsgSpec]:
    """Specs of an installed/known type, parsed from its rosbag2 full definition."""
    return parse_schema(type_name, full_definition(type_name))
