"""Fixed-step classical RK4 at the sample step, inputs held over each step (SPEC section 3).

Three backends, same scheme, all generated from the enabled effects' terms (:mod:`codegen`):

- ``numba`` (default): compiled, samples outer and scenarios inner, each RK4 stage one loop over the
  scenarios around the right-hand side, which LLVM vectorises (SIMD; mathlib's polynomial exp/log/sin);
- ``numba-scalar``: compiled, scenarios outer, samples inner, the state in named locals (the generated
  ``rk4_scalar``/``f_tuple``, terms with libm exp/log/sin; ``f_scalar`` for the zone-crossing step);
- ``numpy``: the step vectorised over the scenarios with numpy calls (the same block on arrays).

Per step k (state x_k at t_k = k*h, held load L_k and pulse clock c_k, supply u evaluated at t_k, t_k+h/2, t_k+h):
    k1 = f(x_k, u(t_k)), k2 = f(x_k + h/2 k1, u(t_k+h/2)), k3 = f(x_k + h/2 k2, u(t_k+h/2)),
    k4 = f(x_k + h k3, u(t_k+h)),  x_{k+1} = x_k + h/6 (k1 + 2 k2 + 2 k3 + k4).
The recorded sample k holds x_k and the exact derivatives k1; the outputs (a1 = r*Omega_mb*dw1/dt,
a2 = x'', ...) are the expressions of :mod:`outputs` on them, in every backend.

Zone crossings: when |Delta| - beta changes sign over a step, the step is redone by
:func:`crossing_step` (crossing located on the Hermite interpolant of Delta, RK4 to it and from it),
because the clutch's damper engages with a jump in torque there.
"""
from __future__ import annotations

import contextlib
import time

import numpy as np

from . import codegen
from . import lags as _lags
from .disturbances import NO_PULSE_S
from ._numba import HAVE_NUMBA
from .state import N_STATES, STATE_NAMES  # noqa: F401 (re-exported: the layout beside the S_* indices)

S_PSA, S_PSB, S_PRA, S_PRB, S_W1, S_DELTA, S_ALPHA1, S_ALPHA2, S_OMEGA2, S_Z, S_XDOT = range(N_STATES)

# recorded outputs, first axis of the output block: defined once in outputs.py
from .outputs import N_OUTPUTS, OUTPUT_NAMES, numpy_outputs  # noqa: E402, F401 (OUTPUT_NAMES re-exported)


def _rk4_numpy(kernel, x, lags, load, clock, ua, ub, phase, u_amp, P, G, h, out, states, record_states):
    """Same scheme, vectorised over the scenarios with numpy calls (the state and the lags are advanced in place)."""
    n = load.shape[1]
    rhs = kernel.rhs_numpy
    y = [x[:, i].copy() for i in range(N_STATES)]
    lg = [lags[:, j].copy() for j in range(_lags.N_LAGS)]
    coef = _lags.coefficients(h)
    clutch = "backlash_clutch" in kernel.names
    beta = P[0]
    for k in range(n):
        ld = load[:, k]
        pt, po = clock[k, 0], clock[k, 1]
        if record_states:
            for i in range(N_STATES):
                states[i, :, k] = y[i]
        f1, aux = rhs(y, ua[k, 0], ub[k, 0], ld, pt, po, P, G, lags=lg)
        for j, v in enumerate(numpy_outputs(y, f1, aux[1], G)):
            out[j, :, k] = v
        f2, _ = rhs([y[i] + 0.5 * h * f1[i] for i in range(N_STATES)], ua[k, 1], ub[k, 1], ld, pt, po, P, G, lags=lg)
        f3, _ = rhs([y[i] + 0.5 * h * f2[i] for i in range(N_STATES)], ua[k, 1], ub[k, 1], ld, pt, po, P, G, lags=lg)
        f4, _ = rhs([y[i] + h * f3[i] for i in range(N_STATES)], ua[k, 2], ub[k, 2], ld, pt, po, P, G, lags=lg)
        y_new = [y[i] + (h / 6.0) * (f1[i] + 2.0 * f2[i] + 2.0 * f3[i] + f4[i]) for i in range(N_STATES)]
        if clutch:
            crossed = np.flatnonzero((np.abs(y[S_DELTA]) < beta) != (np.abs(y_new[S_DELTA]) < beta))
            for s in crossed:   # rare: the same located crossing step as the compiled kernel
                y0 = np.array([y[i][s] for i in range(N_STATES)])
                y1 = np.array([y_new[i][s] for i in range(N_STATES)])
                kernel.module.crossing_step(y0, y1, h, phase[k], u_amp, float(ld[s]), float(pt), float(po),
                                            np.array([v[s] for v in lg]), np.ascontiguousarray(P[:, s]), G)
                for i in range(N_STATES):
                    y_new[i][s] = y1[i]
        if kernel.carries_lags:      # as the compiled kernels: only when a term names a lag (codegen.lags_used)
            lg = _lags.update(lg, _lags.quantities(y, ld, beta, G[8]), _lags.quantities(y_new, ld, beta, G[8]), coef)
        y = y_new
    for i in range(N_STATES):
        x[:, i] = y[i]
    for j in range(_lags.N_LAGS):
        lags[:, j] = lg[j]


@contextlib.contextmanager
def _compile_errors(kernel):
    """A term that numba cannot compile (against the rules of docs/effects.md) -> one-line ValueError."""
    try:
        yield
    except Exception as exc:  # noqa: BLE001 - numba's typing/lowering errors have no common public base
        if HAVE_NUMBA and type(exc).__module__.startswith("numba"):
            lines = [ln.strip() for ln in str(exc).splitlines() if ln.strip() and not ln.startswith("Failed in")
                     and not ln.strip().startswith(("During:", "File ", "^", "\x1b"))]
            first = (lines[0] if lines else type(exc).__name__)[:200]
            raise ValueError(f"the generated kernel of the effects {', '.join(kernel.names)} does not compile "
                             f"({first}); allowed in a term: arithmetic, where(), the mathlib helpers "
                             f"(docs/effects.md); source: {kernel.path}") from None
        raise


_FIRST_CALL_CPU_S = [0.0]


def first_call_cpu_seconds() -> float:
    """This process's CPU time [s] so far in the compiled kernels' first calls (_first_call_compiles): each kernel's
    compile on a cold cache (~10-25 s of one core after a change of its effects or of the generator), else the load
    of numba's cached code (~0.03-0.6 s). A one-time cost, not one of the runs: a caller that reports its own CPU
    time per recording takes it out and names it (proposal.Proposal.first_call_cpu_seconds)."""
    return _FIRST_CALL_CPU_S[0]


def _first_call_compiles(kernel, x, lags, common, out, states, record_states, record_outputs, sel) -> None:
    """This process's first call of the kernel, on one scenario and one sample of the same types (dimensions, dtype,
    layout) as the real call, under codegen.compile_lock: it compiles the kernel, or loads what another process
    compiled meanwhile, and leaves the real arrays untouched. Its CPU time adds to first_call_cpu_seconds."""
    c0 = time.process_time()
    try:
        _first_call(kernel, x, lags, common, out, states, record_states, record_outputs, sel)
    finally:
        _FIRST_CALL_CPU_S[0] += time.process_time() - c0


def _first_call(kernel, x, lags, common, out, states, record_states, record_outputs, sel) -> None:
    load, clock, ua, ub, phase, u_amp, P, G, h = common
    n = min(1, load.shape[1])
    tiny = (np.array(x[:1]), np.array(lags[:1]), np.ascontiguousarray(load[:1, :n]), np.ascontiguousarray(clock[:n]), np.ascontiguousarray(ua[:n]),
            np.ascontiguousarray(ub[:n]), np.ascontiguousarray(phase[:n]), u_amp, np.ascontiguousarray(P[:, :1]), G, h)
    out1 = np.empty((out.shape[0], 1, n)) if out.shape[1] else np.empty(out.shape)
    states1 = np.empty((states.shape[0], 1, n)) if states.shape[1] else np.empty(states.shape)
    with codegen.compile_lock(kernel):
        kernel.module.rk4_simd(*tiny, out1, states1, bool(record_states), bool(record_outputs), sel)


BACKENDS = ("auto", "numba", "numba-scalar", "numpy")


def resolve_backend(name: str) -> str:
    """'auto' -> 'numba' when numba is importable, else 'numpy'."""
    if name not in BACKENDS:
        raise ValueError(f"backend {name!r} is not allowed; allowed: " + ", ".join(repr(b) for b in BACKENDS))
    if name == "auto":
        return "numba" if HAVE_NUMBA else "numpy"
    if name.startswith("numba") and not HAVE_NUMBA:
        raise ValueError(f"plant config: simulation.backend = {name!r} but numba is not installed; "
                         "allowed: 'auto', 'numpy' (or install numba)")
    return name


def initial_lags(x, load_first, P, G) -> np.ndarray:
    """(n_scen, N_LAGS): the first-order lags (plant/lags.py) settled at their quantities in the state ``x`` (n_scen,
    N_STATES) with the held load ``load_first`` (n_scen,); ``P``'s first row is beta, ``G[8]`` the motor's base
    speed."""
    return _lags.initial(np.asarray(x), load_first, np.asarray(P)[0], float(np.asarray(G)[8]))


def rk4_advance(backend, kernel, x, load, ua, ub, phase, u_amp, P, G, h, record_states=False,
                record_outputs=True, outputs=None, pulse_clock=None, lags=None):
    """Advance ``x`` (n_scen, N_STATES) in place by ``load.shape[1]`` steps with the backends of ``kernel``
    (:func:`codegen.kernel_for`); ``P``: (len(kernel.param_rows), n_scen) per-scenario parameters, ``G``:
    global motor constants. Return (outputs (n_out, n_scen, n) or None when ``record_outputs`` is false
    (numba backend only), states (N_STATES, n_scen, n) or None).

    ``outputs``: indices into OUTPUT_NAMES of the outputs to record, in that order (None: all N_OUTPUTS);
    the numba kernel writes only those, the other backends compute all and return the selected rows.

    ``pulse_clock``: (n, 2) the held pulse clock of each step [s] (disturbances.pulse_clock_s: the time since the
    latest load pulse began, since it ended; the model variables pulse_time_s, pulse_off_time_s), one for every
    scenario; None: no load pulse (both NO_PULSE_S, so every response to an edge is 0).

    ``lags``: (n_scen, N_LAGS) the first-order lags of plant/lags.py, advanced in place with ``x`` (a caller that runs
    in chunks carries them from one call to the next, as it does ``x``); None: settled at the start (initial_lags)."""
    n_scen, n = load.shape
    sel = np.arange(N_OUTPUTS, dtype=np.int64) if outputs is None else np.asarray(outputs, dtype=np.int64)
    if sel.ndim != 1 or np.any((sel < 0) | (sel >= N_OUTPUTS)):
        raise ValueError(f"rk4_advance: outputs = {outputs!r}; allowed: indices 0..{N_OUTPUTS - 1} into OUTPUT_NAMES")
    P = np.ascontiguousarray(P, dtype=np.float64)
    G = np.ascontiguousarray(G, dtype=np.float64)
    if pulse_clock is None:
        pulse_clock = np.full((n, 2), NO_PULSE_S)
    pulse_clock = np.ascontiguousarray(pulse_clock, dtype=np.float64)
    if pulse_clock.shape != (n, 2):
        raise ValueError(f"rk4_advance: pulse_clock has shape {pulse_clock.shape}; allowed: ({n}, 2), the held "
                         "(time since the pulse began, since it ended) of each step")
    if lags is None:
        lags = initial_lags(x, load[:, 0] if n else np.zeros(n_scen), P, G)
    if lags.shape != (n_scen, _lags.N_LAGS) or lags.dtype != np.float64 or not lags.flags.c_contiguous:
        raise ValueError(f"rk4_advance: lags has shape {lags.shape}, dtype {lags.dtype}; allowed: a C-contiguous "
                         f"float64 array ({n_scen}, {_lags.N_LAGS}) (plant/lags.py)")
    common = (np.ascontiguousarray(load), pulse_clock, np.ascontiguousarray(ua), np.ascontiguousarray(ub),
              np.ascontiguousarray(phase, dtype=np.float64), float(u_amp), P, G, float(h))
    if backend == "numba":
        out = np.empty((sel.size, n_scen, n)) if record_outputs else np.empty((sel.size, 0, 0))
        states = np.empty((N_STATES, n_scen, n)) if record_states else np.empty((N_STATES, 0, 0))
        with _compile_errors(kernel):
            if not kernel.module.rk4_simd.signatures:
                _first_call_compiles(kernel, x, lags, common, out, states, record_states, record_outputs, sel)
            kernel.module.rk4_simd(x, lags, *common, out, states, bool(record_states), bool(record_outputs), sel)
        return (out if record_outputs else None), (states if record_states else None)
    out = np.empty((N_OUTPUTS, n_scen, n))
    states = np.empty((N_STATES, n_scen, n)) if record_states else np.empty((N_STATES, 0, 0))
    with _compile_errors(kernel):
        if backend == "numba-scalar":
            kernel.module.rk4_scalar(x, lags, *common, out, states, bool(record_states))
        else:
            _rk4_numpy(kernel, x, lags, *common, out, states, bool(record_states))
    if outputs is not None:
        out = out[sel]
    return out, (states if record_states else None)
