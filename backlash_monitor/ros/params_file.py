"""Checks the ``--params-file`` files a node is started with, before rclpy reads them.

rclpy ignores a parameter a node does not declare, so a misspelled key (``warn_widht_m``) would
silently leave the default in force, and broken YAML ends in an rclpy traceback. Here every file
given after ``--ros-args`` with ``--params-file FILE`` is read first:

- broken YAML, a missing file or a file that is not ``node: {ros__parameters: {...}}`` is one
  line naming the file (and the line);
- a key under a section for one node (``/**/classifier``, ``/line1/drive7/classifier``,
  ``classifier``) must be a parameter that node declares; a key under a wildcard section
  (``/**``, ``/*/*``) one that some node of the package declares (the same file serves the
  chain's three nodes); a section for a node the package does not have is an error as well.
  The error names the key and the nearest valid one (difflib).

:func:`check_params_files` raises :class:`ParamsFileError` (a ParameterValueError: run_node
prints its one line and exits with 2).
"""
from __future__ import annotations

import importlib
import sys
from pathlib import Path

import yaml

from backlash_monitor.files.config import nearest, yaml_error_line
from backlash_monitor.ros.parameters import ParameterValueError

# node name -> module whose PARAMETERS (ParameterSpec tuple) the node declares
NODE_MODULES = {
    "windowing": "backlash_monitor.nodes.windowing",
    "denoise": "backlash_monitor.nodes.denoise",
    "classifier": "backlash_monitor.nodes.classifier",
    "plant_simulator": "backlash_monitor.nodes.plant_simulator",
    "record": "backlash_monitor.nodes.record",
    "replay": "backlash_monitor.nodes.replay",
}
# parameters every rclpy node has (declared by rclpy itself)
ROS_PARAMETERS = ("use_sim_time", "start_type_description_service")
ROS_PREFIXES = ("qos_overrides.",)


class ParamsFileError(ParameterValueError):
    """A parameters file that cannot be used as it is."""


class NodeParameters:
    """The parameter names of the package's nodes, imported only as far as needed: a node's
    module for its own section; for a wildcard section the modules already loaded first, the
    others only for a key none of those declares (the plant's module loads numba; a classifier
    started with drive.yaml need not)."""

    def __init__(self):
        self._names: dict[str, tuple[str, ...]] = {}

    def of(self, node: str) -> tuple[str, ...]:
        if node not in self._names:
            specs = importlib.import_module(NODE_MODULES[node]).PARAMETERS
            self._names[node] = tuple(spec.name for spec in specs) + ROS_PARAMETERS
        return self._names[node]

    def declared_anywhere(self, key: str) -> bool:
        loaded = [n for n, m in NODE_MODULES.items() if m in sys.modules or n in self._names]
        if any(key in self.of(n) for n in loaded):
            return True
        return any(key in self.of(n) for n in NODE_MODULES if n not in loaded)

    def everything(self) -> list[str]:
        return sorted({name for node in NODE_MODULES for name in self.of(node)})


def node_parameters() -> dict[str, tuple[str, ...]]:
    """{node name: the parameter names it declares} (imports every node module)."""
    names = NodeParameters()
    return {node: names.of(node) for node in NODE_MODULES}


def params_files(argv) -> list[str]:
    """The files given with ``--params-file`` after ``--ros-args`` in ``argv``."""
    files, in_ros = [], False
    argv = list(argv or [])
    for i, arg in enumerate(argv):
        if arg == "--ros-args":
            in_ros = True
        elif arg == "--":
            in_ros = False
        elif in_ros and arg == "--params-file" and i + 1 < len(argv):
            files.append(argv[i + 1])
    return files


def _flatten(mapping, prefix=""):
    for key, value in mapping.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            yield from _flatten(value, name + ".")
        else:
            yield name


def check_params_file(path, nodes: NodeParameters | None = None) -> None:
    """Raise ParamsFileError naming the file (and line / key) if ``path`` is not a valid file."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        raise ParamsFileError(f"parameters file {path}: cannot be read ({error.__class__.__name__}: "
                              f"{getattr(error, 'strerror', None) or error})") from None
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as error:
        raise ParamsFileError(f"parameters file {yaml_error_line(path, error)}") from None
    if data is None:
        return
    shape = ("allowed: '<node>:' sections each holding 'ros__parameters:' "
             "(e.g. '/**: {ros__parameters: {drive_name: drive7}}')")
    if not isinstance(data, dict):
        raise ParamsFileError(f"parameters file {path}: not a mapping of node sections; {shape}")
    nodes = NodeParameters() if nodes is None else nodes
    for section, body in data.items():
        node = str(section).rstrip("/").split("/")[-1]
        if not isinstance(body, dict) or set(body) != {"ros__parameters"} or \
                not isinstance(body["ros__parameters"], dict):
            keys = sorted(map(str, body)) if isinstance(body, dict) else []
            hint = nearest(keys[0], ["ros__parameters"]) if keys else ""
            raise ParamsFileError(f"parameters file {path}: section '{section}' must hold exactly "
                                  f"'ros__parameters' (has {keys or type(body).__name__}){hint}")
        if "*" not in node and node not in NODE_MODULES:
            raise ParamsFileError(f"parameters file {path}: section '{section}' is for node "
                                  f"'{node}', which backlash_monitor does not have"
                                  f"{nearest(node, NODE_MODULES)} (nodes: {', '.join(sorted(NODE_MODULES))})")
        for key in _flatten(body["ros__parameters"]):
            if key.startswith(ROS_PREFIXES):
                continue
            if "*" in node:
                if nodes.declared_anywhere(key):
                    continue
                allowed, scope = nodes.everything(), "any node of backlash_monitor"
            else:
                allowed, scope = nodes.of(node), f"node '{node}'"
                if key in allowed:
                    continue
            raise ParamsFileError(f"parameters file {path}: unknown key '{key}' in section "
                                  f"'{section}' (not a parameter of {scope}){nearest(key, allowed)}")


def check_params_files(argv) -> None:
    """:func:`check_params_file` for every ``--params-file`` in ``argv``."""
    files = params_files(argv)
    if not files:
        return
    nodes = NodeParameters()
    for path in files:
        check_params_file(path, nodes)
