"""Config files: where they are, and one-line messages for what is wrong in one.

:func:`config_file` is the one resource locator for the packaged config files (config/*.yaml):
the windowing, plant and trend loaders find their defaults through it. YAML errors and unknown
keys are reported by :func:`yaml_error_line` and :func:`nearest` (the YAML loaders:
windowing/config.py, ros/params_file.py). No rclpy.
"""
from __future__ import annotations

import difflib
from pathlib import Path

SOURCE_CONFIG_DIR = Path(__file__).resolve().parents[2] / "config"   # <repo>/config in a checkout
PACKAGE = "backlash_monitor"


def _share_config_dir() -> Path | None:
    """share/backlash_monitor/config of the installed package (colcon), or None without ROS or
    without an installed package."""
    try:
        # deferred: optional: without ROS or an installed package the source tree's config/ is used
        from ament_index_python.packages import get_package_share_directory  # type: ignore
        return Path(get_package_share_directory(PACKAGE)) / "config"
    except Exception:  # noqa: BLE001 - no ROS, or the package is not installed
        return None


def config_file(name: str) -> Path:
    """The packaged config file ``name`` (e.g. ``"windowing.yaml"``): the source tree's
    ``config/NAME`` when it exists, else the installed package's ``share/backlash_monitor/config/NAME``
    when that exists, else the source tree's path (which does not exist: the caller's error names it)."""
    source = SOURCE_CONFIG_DIR / name
    if source.is_file():
        return source
    share = _share_config_dir()
    if share is not None and (share / name).is_file():
        return share / name
    return source


def yaml_error_line(path, error) -> str:
    """``FILE:LINE:COLUMN: broken YAML: problem (context at line N)`` of a yaml.YAMLError."""
    mark = getattr(error, "problem_mark", None) or getattr(error, "context_mark", None)
    where = f":{mark.line + 1}:{mark.column + 1}" if mark is not None else ""
    problem = getattr(error, "problem", None) or str(error).splitlines()[0]
    context, cmark = getattr(error, "context", None), getattr(error, "context_mark", None)
    if context and cmark is not None and (mark is None or cmark.line != mark.line):
        problem += f" ({context} at line {cmark.line + 1})"
    return f"{path}{where}: broken YAML: {problem}"


def closest(name, allowed, cutoff: float = 0.5) -> str | None:
    """The closest of ``allowed`` to ``name`` (difflib's ratio at least ``cutoff``; 0: always one), or None."""
    match = difflib.get_close_matches(str(name), sorted(str(a) for a in allowed), n=1, cutoff=cutoff)
    return match[0] if match else None


def nearest(name, allowed) -> str:
    """``; did you mean 'x'?`` for the closest of ``allowed`` (difflib), or ``""``."""
    match = closest(name, allowed)
    return f"; did you mean '{match}'?" if match else ""
