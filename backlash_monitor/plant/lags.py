"""First-order lags of the drive's states: memories the model carries besides its states (docs/effects.md "Kinds and balances", Lags).

A mechanism with a memory of its own -- a hidden inertia behind a viscous or elastic coupling (a flywheel on a belt, a
fan on a slipping coupling), a relaxing insert, a field current that follows the stroke with its coil's L/R -- needs a
state the model does not have. The simplest generic one is a first-order lag of a drive quantity q at a fixed time
constant tau, the exponential filter tau*dL/dt = q - L. A term may name L as a model variable (``omega1_lag_10ms``,
..., :data:`LAG_NAMES`): q - L is the torque of a slow hidden body on a viscous coupling (its speed is L, the
coupling's torque c*(q - L)), L itself a delayed and smoothed copy of q.

The lagged quantities (the drive's states a memory of the catalogue's kind reads): the motor speed Omega1 [rad/s], the
wheel speed Omega2 [rad/s], the mass speed xdot [m/s], the clutch's penetration max(|Delta| - beta, 0) [rad] (0 in the
gap: a relaxing insert forgets its load there) and the motor's load moment input [p.u.] (the strokes' pulse train).

The time constants (LAG_TIMES_S), from the drive's physics (config/plant.yaml):
- 10 ms: within one event -- an event's segment is 2048 samples (41 ms) after each backlash entry, the jaw's torsional
  mode ~33 Hz (a period of 30 ms), a contact lasts tens of ms; a memory of the last impact, gone before the next pulse;
- 100 ms: across one stroke -- between the pulse's length (60 ms) and its period (250 ms): it carries a stroke into
  the pause and has forgotten it (e^(-250/100) = 0.08) by the next;
- the infinite time constant, a memory of the whole record, is the speed's deviation from its operating point, which
  the proposal's library has already (candidate_terms._speed_deviations); slower memories than the pulse period
  (the spring-mass 0.5 Hz, the motor's T_m = 0.86 s) are between 100 ms and that.
A geometric ladder of factor 10: a lag at a time constant between them is, within a few per cent, a combination of
the two (measured on the foreign drives, docs/workbench.md "Terms with memory").

Only a kernel whose terms name a lag advances them (plant/codegen.py lags_used): otherwise they stay as settled at
the start, which nothing reads. Each lag is held over each sample step (as the load input and the pulse clock are) and
updated after the step, exactly for a quantity linear over the step (a first-order hold): with a = exp(-h/tau),
c = tau*(1 - a)/h,
    L_{k+1} = a*L_k + (1 - c)*q_{k+1} + (c - a)*q_k,
and for the load moment, held over the step itself, the zero-order hold's exact L_{k+1} = a*L_k + (1 - a)*q_k. Held,
a term reads L_k over step k: off the continuous lag by at most (h/tau)*|q - L| (0.2 % at 10 ms, 20 us steps).
"""
from __future__ import annotations

import math

import numpy as np

LAG_TIMES_S = (0.01, 0.1)
# (the quantity's name in the model variables, its expression on the kernel's containers: {w1}, {delta}, {omega2},
#  {xdot} the states, {load} the held load moment, {beta} the half gap angle, {omega_mb} the motor's base speed),
# whether it is the held input (a zero-order hold) rather than a state (a first-order hold)
QUANTITIES = (
    ("omega1", "{w1} * {omega_mb}", False),
    ("omega2", "{omega2}", False),
    ("xdot", "{xdot}", False),
    ("penetration", "fmax(fabs({delta}) - {beta}, 0.0)", False),
    ("load_moment", "{load}", True),
)
UNITS = {"omega1": "rad/s", "omega2": "rad/s", "xdot": "m/s", "penetration": "rad", "load_moment": "p.u."}
WORDS = {"omega1": "the motor speed Omega1", "omega2": "the wheel speed Omega2", "xdot": "the mass speed",
         "penetration": "the clutch's penetration max(|Delta| - beta, 0) (0 in the gap)",
         "load_moment": "the motor's load moment input (the strokes' pulse train)"}


def lag_name(quantity: str, tau_s: float) -> str:
    """The model variable of ``quantity``'s lag at ``tau_s``: ``omega1_lag_10ms``."""
    return f"{quantity}_lag_{tau_s * 1e3:g}ms"


# (model variable, quantity index, tau [s]) in the kernels' order
LAGS = tuple((lag_name(q, tau), i, tau) for i, (q, _, _) in enumerate(QUANTITIES) for tau in LAG_TIMES_S)
LAG_NAMES = tuple(n for n, _, _ in LAGS)
N_LAGS = len(LAGS)
MODEL_VARIABLES = {n: f"{WORDS[QUANTITIES[i][0]]} through a first-order lag of {tau * 1e3:g} ms, "
                      f"tau*dL/dt = q - L [{UNITS[QUANTITIES[i][0]]}] (held over each sample step; plant/lags.py)"
                   for n, i, tau in LAGS}


def coefficients(h_s: float) -> np.ndarray:
    """(N_LAGS, 3): per lag (A, B, C) of its update L_{k+1} = A*L_k + B*q_{k+1} + C*q_k over a step ``h_s`` (a held
    input: q_{k+1} := q_k, so B + C = 1 - A either way)."""
    out = np.empty((N_LAGS, 3))
    for j, (_, i, tau) in enumerate(LAGS):
        a = math.exp(-h_s / tau)
        c = tau * (1.0 - a) / h_s          # = 1 - h/(2 tau) + ...: B = 1 - c ~ h/(2 tau), C = c - a ~ h/(2 tau)
        out[j] = (a, 1.0 - c, c - a)
    return out


def render(i: int, w1: str, delta: str, omega2: str, xdot: str, load: str, beta: str, omega_mb: str) -> str:
    """The expression of quantity ``i`` on one backend's containers."""
    return QUANTITIES[i][1].format(w1=w1, delta=delta, omega2=omega2, xdot=xdot, load=load, beta=beta,
                                   omega_mb=omega_mb)


def quantities(y, load, beta, omega_mb) -> list:
    """The lagged quantities on numpy arrays (y: the state rows w1 = y[4], delta = y[5], omega2 = y[8], xdot = y[10])."""
    return [y[4] * omega_mb, y[8], y[10], np.maximum(np.abs(y[5]) - beta, 0.0), load]


def initial(x: np.ndarray, load: np.ndarray, beta: np.ndarray, omega_mb: float) -> np.ndarray:
    """(n_scen, N_LAGS): every lag settled at its quantity's present value (x: (n_scen, N_STATES); load: (n_scen,))."""
    q = quantities([x[:, i] for i in range(x.shape[1])], np.asarray(load, dtype=np.float64), beta, omega_mb)
    return np.ascontiguousarray(np.stack([np.broadcast_to(q[i], (x.shape[0],)) for _, i, _ in LAGS], axis=1),
                                dtype=np.float64)


def update(lags: list, q_old: list, q_new: list, coef: np.ndarray) -> list:
    """One step of every lag on numpy arrays (the numpy backend; the compiled ones generate the same line)."""
    return [coef[j, 0] * lags[j] + coef[j, 1] * (q_old[i] if QUANTITIES[i][2] else q_new[i]) + coef[j, 2] * q_old[i]
            for j, (_, i, _) in enumerate(LAGS)]
