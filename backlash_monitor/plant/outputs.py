"""The recorded outputs, defined once (docs/model.md "Outputs", docs/effects.md "Backends").

Each output is one expression in

- the states (``codegen.STATE_NAMES``: ``w1``, ``delta``, ``omega2``, ...),
- their time derivatives at the sample, ``d_<state>`` (``d_w1`` = dw1/dt, ``d_xdot`` = x''): the RK4
  scheme's first stage k1, so the accelerations are exact derivatives of the recorded state,
- ``tc``, the transmitted (clutch) torque T_c of that stage,
- the global motor constants ``g_*`` (``codegen.GLOBAL_NAMES``: ``g_r`` = r, ``g_omega_mb`` = Omega_mb).

Every backend takes its outputs from this table: the generated SIMD loop (``rk4_simd``) and scalar loop
(``rk4_scalar``) get the expressions rendered onto their own containers by :func:`render`, the numpy
backend and the solve_ivp reference call :func:`numpy_outputs`. Arithmetic only (it runs on floats in
the compiled loops and on arrays in numpy).
"""
from __future__ import annotations

import ast
from dataclasses import dataclass

from backlash_monitor.plant.state import GLOBAL_NAMES, STATE_NAMES


@dataclass(frozen=True)
class Output:
    name: str          # the recorded signal (SimulationChunk field, topic field)
    unit: str
    expression: str    # in the variables above
    description: str


OUTPUTS = (
    Output("a1", "m/s^2", "g_r * g_omega_mb * d_w1",
           "drive-wheel circumference acceleration, motor side: r*Omega_mb*dw1/dt = r*dOmega1/dt"),
    Output("a2", "m/s^2", "d_xdot", "acceleration of the mass x''"),
    Output("omega1", "rad/s", "w1 * g_omega_mb", "motor speed Omega1 = w1*Omega_mb"),
    Output("omega2", "rad/s", "omega2", "wheel speed Omega2"),
    Output("angle_difference", "rad", "delta", "Delta = alpha1 - alpha2 (integrated as a state)"),
    Output("alpha1", "rad", "alpha1", "motor-side shaft angle"),
    Output("alpha2", "rad", "alpha2", "wheel angle"),
    Output("transmitted_torque_Nm", "N*m", "tc", "clutch torque T_c (0 in the backlash zone)"),
)
OUTPUT_NAMES = tuple(o.name for o in OUTPUTS)
N_OUTPUTS = len(OUTPUTS)


def _variables() -> dict:
    """{variable name: its kind and index}: ("state", i), ("derivative", i), ("tc", 0), ("global", i)."""
    v = {n: ("state", i) for i, n in enumerate(STATE_NAMES)}
    v.update({f"d_{n}": ("derivative", i) for i, n in enumerate(STATE_NAMES)})
    v["tc"] = ("tc", 0)
    v.update({n: ("global", i) for i, n in enumerate(GLOBAL_NAMES)})
    return v


def render(expression: str, state: str, derivative: str, tc: str) -> str:
    """``expression`` with every state / derivative / tc name replaced by the container access given as a
    format string with ``{i}`` (e.g. state="Y[{i}, s]", derivative="K1[{i}, s]", tc="TC[s]"); the g_*
    names stay (the caller binds them). The expression's tree (its order of operations) is kept."""
    variables = _variables()
    forms = {"state": state, "derivative": derivative, "tc": tc}
    tree = ast.parse(expression, mode="eval")

    class Sub(ast.NodeTransformer):
        def visit_Name(self, node):
            if node.id not in variables:
                raise ValueError(f"output expression {expression!r} names {node.id!r}; allowed: "
                                 + ", ".join(sorted(variables)))
            kind, i = variables[node.id]
            if kind == "global":
                return node
            return ast.copy_location(ast.parse(forms[kind].format(i=i), mode="eval").body, node)
    return ast.unparse(Sub().visit(tree).body)


_NUMPY_FN = None


def numpy_outputs(y, d, tc, G) -> tuple:
    """All outputs (in OUTPUT_NAMES order) from the state ``y`` and derivatives ``d`` (sequences indexed
    like STATE_NAMES, of arrays or floats), ``tc`` and the global vector ``G``."""
    global _NUMPY_FN
    if _NUMPY_FN is None:
        body = "\n".join(f"    {n} = G[{i}]" for i, n in enumerate(GLOBAL_NAMES))
        exprs = ", ".join(render(o.expression, "y[{i}]", "d[{i}]", "tc") for o in OUTPUTS)
        src = f"def outputs(y, d, tc, G):\n{body}\n    return ({exprs},)\n"
        ns: dict = {}
        exec(compile(src, "<plant outputs>", "exec"), ns)  # noqa: S102 - generated from the table above
        _NUMPY_FN = ns["outputs"]
    return _NUMPY_FN(y, d, tc, G)
