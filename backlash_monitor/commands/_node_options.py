"""Command-line options generated from a node's declared parameters (ParameterSpec).

`python -m backlash_monitor record --output run.mcap` runs the same node as
`ros2 run backlash_monitor record --ros-args -p output:=run.mcap`: every parameter is an option
with its description and allowed values, and the node validates the values itself.
"""
from __future__ import annotations

from backlash_monitor.nodes.parameters import ros_parameter_args  # noqa: F401  (re-exported)


def add_parameter_options(parser, specs, positional: str | None = None) -> None:
    for spec in specs:
        constrained = spec.choices is not None or (
            isinstance(spec.default, (int, float)) and not isinstance(spec.default, bool)
            and (spec.minimum is not None or spec.maximum is not None))
        help_text = (f"{spec.description} (allowed: {spec.allowed()})" if constrained
                     else spec.description)
        if spec.name == positional:
            parser.add_argument(spec.name, nargs="?", default=spec.default, help=help_text)
            continue
        flag = "--" + spec.name.replace("_", "-")
        if isinstance(spec.default, bool):
            parser.add_argument(flag, dest=spec.name, action="store_true", default=spec.default,
                                help=help_text)
        elif isinstance(spec.default, int):
            parser.add_argument(flag, dest=spec.name, type=int, default=spec.default, help=help_text)
        elif isinstance(spec.default, float):
            parser.add_argument(flag, dest=spec.name, type=float, default=spec.default,
                                help=help_text)
        else:
            parser.add_argument(flag, dest=spec.name, default=spec.default,
                                choices=spec.choices, help=help_text)


def ros_arguments(args, specs) -> list[str]:
    """``--ros-args -p name:=value ...`` for every parameter the user changed."""
    return ros_parameter_args({spec.name: getattr(args, spec.name) for spec in specs
                               if getattr(args, spec.name) != spec.default})
