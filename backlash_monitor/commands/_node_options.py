"""Command-line options generated from a node's declared parameters (ParameterSpec).

`python -m backlash_monitor record --output run.mcap` runs the same node as
`ros2 run backlash_monitor record --ros-args -p output:=run.mcap`: every parameter is an option
with its description and allowed values. The values are checked here, before the node starts, with
the option's name in the message (the node checks them again, naming the parameter).

An option takes the CLI vocabulary's name where the parameter's name differs from it
(commands/vocabulary.py): replay's ``rate`` is ``--rate-factor``, record's ``duration_s`` is
``--duration``; the parameter's own spelling (``--rate``, ``--duration-s``) still works for one
release, with a one-line deprecation on stderr.
"""
from __future__ import annotations

import argparse
import math

from backlash_monitor.errors import DeprecatedSpelling, UsageError
from backlash_monitor.ros.parameters import ros_parameter_args  # noqa: F401  (re-exported)

# parameter name -> the vocabulary's option (the parameter's own spelling is the deprecated one)
VOCABULARY_FLAGS = {"rate": "--rate-factor", "duration_s": "--duration"}
METAVARS = {"rate": "X", "duration_s": "S", "output": "FILE.mcap"}


def flag_of(spec) -> str:
    return VOCABULARY_FLAGS.get(spec.name, "--" + spec.name.replace("_", "-"))


def add_parameter_options(parser, specs, positional: str | None = None) -> None:
    for spec in specs:
        constrained = spec.choices is not None or (
            isinstance(spec.default, (int, float)) and not isinstance(spec.default, bool)
            and (spec.minimum is not None or spec.maximum is not None))
        help_text = (f"{spec.description} (allowed: {_allowed(spec)})" if constrained
                     else spec.description)
        if spec.name == positional:
            parser.add_argument(spec.name, nargs="?", default=spec.default, help=help_text)
            continue
        flag = flag_of(spec)
        metavar = METAVARS.get(spec.name)
        if isinstance(spec.default, bool):
            parser.add_argument(flag, dest=spec.name, action="store_true", default=spec.default,
                                help=help_text)
            continue
        kind = {int: int, float: float}.get(type(spec.default))
        parser.add_argument(flag, dest=spec.name, type=kind, default=spec.default, metavar=metavar,
                            choices=None if kind else spec.choices, help=help_text)
        if spec.name in VOCABULARY_FLAGS:
            parser.add_argument("--" + spec.name.replace("_", "-"), dest=spec.name, type=kind,
                                action=DeprecatedSpelling, new=flag, metavar=metavar, help=argparse.SUPPRESS)


def _allowed(spec) -> str:
    if spec.choices is not None:
        return ", ".join(str(c) for c in spec.choices)
    lo = "-inf" if spec.minimum is None else f"{spec.minimum:g}"
    hi = "inf" if spec.maximum is None else f"{spec.maximum:g}"
    return f"{lo}..{hi}"


def check_options(args, specs) -> None:
    """Every value the user changed, against its parameter's allowed values: a UsageError in the CLI's one
    range form, naming the option, before the node starts."""
    for spec in specs:
        value = getattr(args, spec.name)
        if value == spec.default or isinstance(spec.default, (bool, str)):
            continue
        if not math.isfinite(value) or (spec.minimum is not None and value < spec.minimum) or \
                (spec.maximum is not None and value > spec.maximum):
            raise UsageError(f"{flag_of(spec)} {value:g}: out of range, allowed {_allowed(spec)}")


def ros_arguments(args, specs) -> list[str]:
    """``--ros-args -p name:=value ...`` for every parameter the user changed."""
    check_options(args, specs)
    return ros_parameter_args({spec.name: getattr(args, spec.name) for spec in specs
                               if getattr(args, spec.name) != spec.default})
