"""Declared, described and validated node parameters.

Each node lists its parameters as :class:`ParameterSpec` (name, default, description, allowed
range or choices). :func:`declare_and_validate` declares them with a ``ParameterDescriptor`` (so
``ros2 param describe`` shows the description and range) and checks the values the node was
started with. A bad value raises :class:`ParameterValueError` naming the parameter and what is
allowed; :func:`backlash_monitor.ros.runtime.run_node` turns that into one clear log line and
exit code 2 — the node does not start. Values set later at run time are checked by the same rule and refused with the same reason.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from rcl_interfaces.msg import (FloatingPointRange, IntegerRange, ParameterDescriptor,
                                SetParametersResult)


class ParameterValueError(ValueError):
    """A parameter value outside what the node allows."""


@dataclass(frozen=True)
class ParameterSpec:
    name: str
    default: object
    description: str
    minimum: float | None = None
    maximum: float | None = None
    choices: tuple | None = None
    read_only: bool = True

    def allowed(self) -> str:
        if self.choices is not None:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        lo = "-inf" if self.minimum is None else f"{self.minimum:g}"
        hi = "inf" if self.maximum is None else f"{self.maximum:g}"
        return f"{lo} <= {self.name} <= {hi}"

    def check(self, value):
        if isinstance(self.default, bool):
            if not isinstance(value, bool):
                raise ParameterValueError(f"parameter '{self.name}' = {value!r}: allowed: true or false")
            return value
        if isinstance(self.default, (int, float)):
            if isinstance(value, bool) or not isinstance(value, (int, float)) or \
                    (isinstance(self.default, int) and not isinstance(value, int)):
                kind = "an integer" if isinstance(self.default, int) else "a number"
                raise ParameterValueError(f"parameter '{self.name}' = {value!r} is not {kind}; "
                                          f"allowed: {self.allowed()}")
            if not math.isfinite(value) or (self.minimum is not None and value < self.minimum) or \
                    (self.maximum is not None and value > self.maximum):
                raise ParameterValueError(f"parameter '{self.name}' = {value!r} is out of range; "
                                          f"allowed: {self.allowed()}")
        if self.choices is not None and value not in self.choices:
            raise ParameterValueError(f"parameter '{self.name}' = {value!r} is not allowed; "
                                      f"allowed: {self.allowed()}")
        return value

    def descriptor(self) -> ParameterDescriptor:
        descriptor = ParameterDescriptor(description=self.description, read_only=self.read_only)
        if self.choices is not None:
            descriptor.additional_constraints = "allowed: " + self.allowed()
        elif isinstance(self.default, bool):
            pass
        elif isinstance(self.default, int) and (self.minimum is not None and self.maximum is not None):
            descriptor.integer_range = [IntegerRange(from_value=int(self.minimum),
                                                     to_value=int(self.maximum), step=1)]
        elif isinstance(self.default, float) and (self.minimum is not None and self.maximum is not None):
            descriptor.floating_point_range = [FloatingPointRange(
                from_value=float(self.minimum), to_value=float(self.maximum), step=0.0)]
        return descriptor


def declare_and_validate(node, specs) -> dict:
    """Declare ``specs`` on ``node``; return {name: value}; raise ParameterValueError on a bad value.

    The descriptors' ranges are not enforced by rclpy for the start-up values (``--ros-args -p``
    overrides bypass them), so every value is checked here explicitly.
    """
    by_name = {spec.name: spec for spec in specs}
    values = {}
    for spec in specs:
        try:
            value = node.declare_parameter(spec.name, spec.default, spec.descriptor()).value
        except Exception as error:  # rclpy's type/range errors: report them the same way
            raise ParameterValueError(f"parameter '{spec.name}': {error}; allowed: {spec.allowed()}") \
                from None
        values[spec.name] = spec.check(value)

    def on_set(params):
        for param in params:
            spec = by_name.get(param.name)
            if spec is None:
                continue
            try:
                spec.check(param.value)
            except ParameterValueError as error:
                return SetParametersResult(successful=False, reason=str(error))
        return SetParametersResult(successful=True)

    node.add_on_set_parameters_callback(on_set)
    return values


def ros_parameter_args(values: dict) -> list[str]:
    """``--ros-args -p name:=value ...`` for a node's parameter values (YAML-quoted where needed)."""
    out = ["--ros-args"]
    for name, value in values.items():
        if isinstance(value, bool):
            value = str(value).lower()
        elif isinstance(value, str):
            value = f"'{value}'" if value == "" or ":" in value or "," in value else value
        out += ["-p", f"{name}:={value}"]
    return out
