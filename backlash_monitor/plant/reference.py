"""Adaptive-step reference solution with scipy's solve_ivp, for accuracy checks and the benchmark.

Same model (the generated numpy right-hand side of the simulator's effects, ``sim.kernel.rhs_numpy``), same settled start and same held inputs as a
:class:`PlantSimulator`; the supply voltage is evaluated continuously. The integration restarts at
every change of the held load, so no step straddles an input discontinuity.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from .disturbances import pulse_clock_s
from .drivetrain import N_STATES
from .outputs import OUTPUT_NAMES, numpy_outputs


def reference_run(sim, index: int, load_pu: np.ndarray, method: str = "DOP853", rtol: float = 1e-9,
                  atol: float = 1e-12, state0: np.ndarray | None = None, first_sample_index: int = 0,
                  rhs=None, extra=None) -> dict:
    """Integrate scenario ``index`` of ``sim`` over len(load_pu) samples from ``state0`` (default: its
    current state) with solve_ivp; return the samples of every output (outputs.OUTPUT_NAMES: a1, a2, omega1,
    ..., from the one definition in outputs.py), the states and the solver statistics (nfev).

    ``rhs``: another :class:`codegen.Kernel` (e.g. the nominal model's, for a test that adds an effect's
    equation written independently; its parameters are taken from the simulator's values); ``extra(t, y,
    der)``: returns corrections added to the 11 derivatives (that independent form)."""
    cfg = sim.config
    if rhs is None:
        rhs_np, P = sim.kernel.rhs_numpy, sim.P[:, index]
    elif hasattr(rhs, "param_rows"):         # a codegen.Kernel: its rows from the simulator's values
        rhs_np, P = rhs.rhs_numpy, np.array([sim.parameter_values(r)[index] for r in rhs.param_rows])
    else:
        rhs_np, P = rhs, sim.P[:, index]
    G = sim.G
    h = sim.sample_period_s
    omega_b = cfg.motor.base_angular_frequency_rad_s
    u_amp = cfg.motor.supply_voltage_pu
    n = len(load_pu)
    x = (sim.state[index] if state0 is None else state0).astype(np.float64).copy()
    t0 = first_sample_index * h
    clock = pulse_clock_s(first_sample_index, n, cfg)     # held over each sample step, as in the simulator

    def rhs(t, y, ld):
        ph = omega_b * t
        c = clock[min(max(int((t - t0) / h), 0), n - 1)]
        der, _ = rhs_np(list(y), u_amp * math.cos(ph), u_amp * math.sin(ph), ld, c[0], c[1], P, G)
        der = np.array(der, dtype=np.float64)
        if extra is not None:
            der = der + extra(t, y, der)
        return der

    states = np.empty((n, N_STATES))
    changes = np.flatnonzero(np.diff(load_pu)) + 1
    bounds = np.concatenate([[0], changes, [n]])
    nfev = 0
    for a, b in zip(bounds[:-1], bounds[1:]):
        ld = float(load_pu[a])
        t_eval = t0 + np.arange(a, b + 1) * h
        sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), x, method=method, rtol=rtol, atol=atol, t_eval=t_eval,
                        args=(ld,))
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        nfev += sol.nfev
        states[a:b] = sol.y[:, :-1].T
        x = sol.y[:, -1].copy()
    # exact derivatives at the samples, as the simulator records them
    k = first_sample_index + np.arange(n)
    ph = omega_b * k * h
    Pn = np.repeat(P[:, None], n, axis=1)
    der, aux = rhs_np([states[:, i] for i in range(N_STATES)], u_amp * np.cos(ph), u_amp * np.sin(ph), load_pu,
                      clock[:, 0], clock[:, 1], Pn, G)
    der = [np.broadcast_to(d, (n,)) for d in der]
    if extra is not None:
        corr = np.array([extra(float(t0 + k_ * h), states[k_], None) for k_ in range(n)])
        der = [der[i] + corr[:, i] for i in range(N_STATES)]
    res = dict(zip(OUTPUT_NAMES, numpy_outputs([states[:, i] for i in range(N_STATES)], der, aux[1], G)))
    res.update(states=states, final_state=x, nfev=nfev)
    return res
