"""One-line messages for configuration files: where YAML broke, and the nearest valid key.

Shared by the YAML loaders (windowing/config.py, nodes/params_file.py); no rclpy.
"""
from __future__ import annotations

import difflib


def yaml_error_line(path, error) -> str:
    """``FILE:LINE:COLUMN: broken YAML: problem (context at line N)`` of a yaml.YAMLError."""
    mark = getattr(error, "problem_mark", None) or getattr(error, "context_mark", None)
    where = f":{mark.line + 1}:{mark.column + 1}" if mark is not None else ""
    problem = getattr(error, "problem", None) or str(error).splitlines()[0]
    context, cmark = getattr(error, "context", None), getattr(error, "context_mark", None)
    if context and cmark is not None and (mark is None or cmark.line != mark.line):
        problem += f" ({context} at line {cmark.line + 1})"
    return f"{path}{where}: broken YAML: {problem}"


def nearest(name, allowed) -> str:
    """``; did you mean 'x'?`` for the closest of ``allowed`` (difflib), or ``""``."""
    match = difflib.get_close_matches(str(name), sorted(str(a) for a in allowed), n=1, cutoff=0.5)
    return f"; did you mean '{match[0]}'?" if match else ""
