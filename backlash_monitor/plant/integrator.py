"""Fixed-step classical RK4 at the sample step, inputs held over each step (SPEC section 3).

Two backends with the same arithmetic (both call :func:`drivetrain.plant_derivatives`):

- ``numba``: a compiled loop, scenarios outer, samples inner, the state in registers;
- ``numpy``: the step vectorised over the scenarios (one numpy call per operation and stage).

Per step k (state x_k at t_k = k*h, held load L_k, supply u evaluated at t_k, t_k+h/2, t_k+h):
    k1 = f(x_k, u(t_k)), k2 = f(x_k + h/2 k1, u(t_k+h/2)), k3 = f(x_k + h/2 k2, u(t_k+h/2)),
    k4 = f(x_k + h k3, u(t_k+h)),  x_{k+1} = x_k + h/6 (k1 + 2 k2 + 2 k3 + k4).
The recorded sample k holds x_k and the exact derivatives k1 (a1 = r*Omega_mb*dw1/dt, a2 = x'').

Zone crossings: when |Delta| - beta changes sign over a step, the step is redone by
:func:`crossing_step` (crossing located on the Hermite interpolant of Delta, RK4 to it and from it),
because the clutch's damper engages with a jump in torque there.
"""
from __future__ import annotations

import numpy as np

import math

from ._numba import HAVE_NUMBA, jitable, numba
from .drivetrain import (N_STATES, P_ON_CLUTCH, P_OMEGA_B, P_OMEGA_MB, P_R, S_ALPHA1, S_ALPHA2, S_DELTA, S_OMEGA2, S_PRA, S_PRB, S_PSA,
                         S_PSB, S_W1, S_XDOT, S_Z, plant_derivatives,
                         plant_derivatives_scalar)

# recorded outputs, first axis of the output block
OUTPUT_NAMES = ("a1", "a2", "omega1", "omega2", "angle_difference", "alpha1", "alpha2", "transmitted_torque_Nm")
N_OUTPUTS = len(OUTPUT_NAMES)


@jitable
def _derivs_at(y, tau, phase, u_amp, ld, bs, cs, ns, p, mode, out):
    ph = phase + p[P_OMEGA_B] * tau
    der, aux = plant_derivatives_scalar(y[0], y[1], y[2], y[3], y[4], y[5], y[8], y[9], y[10],
                                        u_amp * math.cos(ph), u_amp * math.sin(ph), ld, bs, cs, ns, p, mode)
    for i in range(11):
        out[i] = der[i]


@jitable
def _rk4_substep(y, hs, tau0, phase, u_amp, ld, bs, cs, ns, p, mode):
    """One classical RK4 step of length hs from y (in place), starting tau0 after the sample instant."""
    k1 = np.empty(11)
    k2 = np.empty(11)
    k3 = np.empty(11)
    k4 = np.empty(11)
    tmp = np.empty(11)
    _derivs_at(y, tau0, phase, u_amp, ld, bs, cs, ns, p, mode, k1)
    for i in range(11):
        tmp[i] = y[i] + 0.5 * hs * k1[i]
    _derivs_at(tmp, tau0 + 0.5 * hs, phase, u_amp, ld, bs, cs, ns, p, mode, k2)
    for i in range(11):
        tmp[i] = y[i] + 0.5 * hs * k2[i]
    _derivs_at(tmp, tau0 + 0.5 * hs, phase, u_amp, ld, bs, cs, ns, p, mode, k3)
    for i in range(11):
        tmp[i] = y[i] + hs * k3[i]
    _derivs_at(tmp, tau0 + hs, phase, u_amp, ld, bs, cs, ns, p, mode, k4)
    for i in range(11):
        y[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@jitable
def crossing_step(y0, y1, h, phase, u_amp, ld, bs, cs, ns, p):
    """Redo a step in which Delta crossed the zone boundary |Delta| = beta (the clutch's damper engages
    with a jump there, which costs a plain RK4 step O(h) accuracy): locate the crossing on the cubic
    Hermite interpolant of Delta (slopes Omega1 - Omega2 at both ends), then RK4 up to it with the
    start side's law and on from it with the other side's. y0: state at the step start; y1: the plain
    step's result, overwritten with the located one. Returns the crossing's fraction of the step."""
    omb = p[P_OMEGA_MB]
    d0, d1 = y0[5], y1[5]
    r0 = (y0[4] * omb - y0[8]) * h
    r1 = (y1[4] * omb - y1[8]) * h
    inside0 = abs(d0) < bs
    sgn = (1.0 if d1 > 0.0 else -1.0) if inside0 else (1.0 if d0 > 0.0 else -1.0)
    target = sgn * bs
    lo, hi = 0.0, 1.0
    f_lo = d0 - target
    for _ in range(60):
        th = 0.5 * (lo + hi)
        t2 = th * th
        t3 = t2 * th
        val = ((2 * t3 - 3 * t2 + 1) * d0 + (t3 - 2 * t2 + th) * r0 + (-2 * t3 + 3 * t2) * d1
               + (t3 - t2) * r1) - target
        if (val > 0.0) == (f_lo > 0.0):
            lo = th
            f_lo = val
        else:
            hi = th
    th = 0.5 * (lo + hi)
    mode0 = 2 if inside0 else 1
    mode1 = 1 if inside0 else 2
    for i in range(11):
        y1[i] = y0[i]
    if th > 0.0:
        _rk4_substep(y1, th * h, 0.0, phase, u_amp, ld, bs, cs, ns, p, mode0)
    if th < 1.0:
        _rk4_substep(y1, (1.0 - th) * h, th * h, phase, u_amp, ld, bs, cs, ns, p, mode1)
    return th


def _rk4_loop(x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, out, states, record_states):
    n_scen = x.shape[0]
    n = load.shape[1]
    r = p[P_R]
    omega_mb = p[P_OMEGA_MB]
    clutch_on = p[P_ON_CLUTCH] != 0.0
    y0 = np.empty(11)
    y1 = np.empty(11)
    for s in range(n_scen):
        psa = x[s, 0]; psb = x[s, 1]; pra = x[s, 2]; prb = x[s, 3]; w1 = x[s, 4]; d = x[s, 5]
        al1 = x[s, 6]; al2 = x[s, 7]; o2 = x[s, 8]; z = x[s, 9]; xd = x[s, 10]
        bs = beta[s]; cs = c[s]; ns = n1[s]
        for k in range(n):
            ld = load[s, k]
            if record_states:
                states[0, s, k] = psa; states[1, s, k] = psb; states[2, s, k] = pra; states[3, s, k] = prb
                states[4, s, k] = w1; states[5, s, k] = d; states[6, s, k] = al1; states[7, s, k] = al2
                states[8, s, k] = o2; states[9, s, k] = z; states[10, s, k] = xd
            f1, aux = plant_derivatives_scalar(psa, psb, pra, prb, w1, d, o2, z, xd, ua[k, 0], ub[k, 0], ld, bs, cs, ns, p)
            out[0, s, k] = r * omega_mb * f1[4]
            out[1, s, k] = f1[10]
            out[2, s, k] = w1 * omega_mb
            out[3, s, k] = o2
            out[4, s, k] = d
            out[5, s, k] = al1
            out[6, s, k] = al2
            out[7, s, k] = aux[1]
            hh = 0.5 * h
            f2, aux = plant_derivatives_scalar(psa + hh * f1[0], psb + hh * f1[1], pra + hh * f1[2], prb + hh * f1[3],
                                        w1 + hh * f1[4], d + hh * f1[5], o2 + hh * f1[8], z + hh * f1[9],
                                        xd + hh * f1[10], ua[k, 1], ub[k, 1], ld, bs, cs, ns, p)
            f3, aux = plant_derivatives_scalar(psa + hh * f2[0], psb + hh * f2[1], pra + hh * f2[2], prb + hh * f2[3],
                                        w1 + hh * f2[4], d + hh * f2[5], o2 + hh * f2[8], z + hh * f2[9],
                                        xd + hh * f2[10], ua[k, 1], ub[k, 1], ld, bs, cs, ns, p)
            f4, aux = plant_derivatives_scalar(psa + h * f3[0], psb + h * f3[1], pra + h * f3[2], prb + h * f3[3],
                                        w1 + h * f3[4], d + h * f3[5], o2 + h * f3[8], z + h * f3[9],
                                        xd + h * f3[10], ua[k, 2], ub[k, 2], ld, bs, cs, ns, p)
            h6 = h / 6.0
            psa_new = psa + h6 * (f1[0] + 2.0 * f2[0] + 2.0 * f3[0] + f4[0])
            psb_new = psb + h6 * (f1[1] + 2.0 * f2[1] + 2.0 * f3[1] + f4[1])
            pra_new = pra + h6 * (f1[2] + 2.0 * f2[2] + 2.0 * f3[2] + f4[2])
            prb_new = prb + h6 * (f1[3] + 2.0 * f2[3] + 2.0 * f3[3] + f4[3])
            w1_new = w1 + h6 * (f1[4] + 2.0 * f2[4] + 2.0 * f3[4] + f4[4])
            d_new = d + h6 * (f1[5] + 2.0 * f2[5] + 2.0 * f3[5] + f4[5])
            al1_new = al1 + h6 * (f1[6] + 2.0 * f2[6] + 2.0 * f3[6] + f4[6])
            al2_new = al2 + h6 * (f1[7] + 2.0 * f2[7] + 2.0 * f3[7] + f4[7])
            o2_new = o2 + h6 * (f1[8] + 2.0 * f2[8] + 2.0 * f3[8] + f4[8])
            z_new = z + h6 * (f1[9] + 2.0 * f2[9] + 2.0 * f3[9] + f4[9])
            xd_new = xd + h6 * (f1[10] + 2.0 * f2[10] + 2.0 * f3[10] + f4[10])
            if clutch_on and ((abs(d) < bs) != (abs(d_new) < bs)):
                y0[0] = psa; y0[1] = psb; y0[2] = pra; y0[3] = prb; y0[4] = w1; y0[5] = d
                y0[6] = al1; y0[7] = al2; y0[8] = o2; y0[9] = z; y0[10] = xd
                y1[0] = psa_new; y1[1] = psb_new; y1[2] = pra_new; y1[3] = prb_new; y1[4] = w1_new
                y1[5] = d_new; y1[6] = al1_new; y1[7] = al2_new; y1[8] = o2_new; y1[9] = z_new; y1[10] = xd_new
                crossing_step(y0, y1, h, phase[k], u_amp, ld, bs, cs, ns, p)
                psa_new = y1[0]; psb_new = y1[1]; pra_new = y1[2]; prb_new = y1[3]; w1_new = y1[4]
                d_new = y1[5]; al1_new = y1[6]; al2_new = y1[7]; o2_new = y1[8]; z_new = y1[9]; xd_new = y1[10]
            psa = psa_new; psb = psb_new; pra = pra_new; prb = prb_new; w1 = w1_new; d = d_new
            al1 = al1_new; al2 = al2_new; o2 = o2_new; z = z_new; xd = xd_new
        x[s, 0] = psa; x[s, 1] = psb; x[s, 2] = pra; x[s, 3] = prb; x[s, 4] = w1; x[s, 5] = d
        x[s, 6] = al1; x[s, 7] = al2; x[s, 8] = o2; x[s, 9] = z; x[s, 10] = xd


if HAVE_NUMBA:
    _rk4_numba = numba.njit(cache=True, nogil=True, fastmath=True)(_rk4_loop)
else:  # pragma: no cover
    _rk4_numba = None


def _rk4_numpy(x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, out, states, record_states):
    """Same scheme, vectorised over the scenarios (the state is advanced in place)."""
    n = load.shape[1]
    r, omega_mb = p[P_R], p[P_OMEGA_MB]
    y = [x[:, i].copy() for i in range(N_STATES)]

    def f(state, ua_, ub_, ld):
        der, aux = plant_derivatives(state[S_PSA], state[S_PSB], state[S_PRA], state[S_PRB], state[S_W1],
                                     state[S_DELTA], state[S_OMEGA2], state[S_Z], state[S_XDOT], ua_, ub_, ld,
                                     beta, c, n1, p)
        return der, aux

    for k in range(n):
        ld = load[:, k]
        if record_states:
            for i in range(N_STATES):
                states[i, :, k] = y[i]
        f1, aux = f(y, ua[k, 0], ub[k, 0], ld)
        out[0, :, k] = r * omega_mb * f1[4]
        out[1, :, k] = f1[10]
        out[2, :, k] = y[S_W1] * omega_mb
        out[3, :, k] = y[S_OMEGA2]
        out[4, :, k] = y[S_DELTA]
        out[5, :, k] = y[S_ALPHA1]
        out[6, :, k] = y[S_ALPHA2]
        out[7, :, k] = aux[1]
        f2, _ = f([y[i] + 0.5 * h * f1[i] for i in range(N_STATES)], ua[k, 1], ub[k, 1], ld)
        f3, _ = f([y[i] + 0.5 * h * f2[i] for i in range(N_STATES)], ua[k, 1], ub[k, 1], ld)
        f4, _ = f([y[i] + h * f3[i] for i in range(N_STATES)], ua[k, 2], ub[k, 2], ld)
        y_new = [y[i] + (h / 6.0) * (f1[i] + 2.0 * f2[i] + 2.0 * f3[i] + f4[i]) for i in range(N_STATES)]
        if p[P_ON_CLUTCH] != 0.0:
            crossed = np.flatnonzero((np.abs(y[S_DELTA]) < beta) != (np.abs(y_new[S_DELTA]) < beta))
            for s in crossed:   # rare: the same located crossing step as the compiled kernel, in Python
                y0 = np.array([y[i][s] for i in range(N_STATES)])
                y1 = np.array([y_new[i][s] for i in range(N_STATES)])
                crossing_step(y0, y1, h, phase[k], u_amp, float(ld[s]), float(beta[s]), float(c[s]), float(n1[s]), p)
                for i in range(N_STATES):
                    y_new[i][s] = y1[i]
        y = y_new
    for i in range(N_STATES):
        x[:, i] = y[i]


def resolve_backend(name: str) -> str:
    if name == "auto":
        return "numba" if HAVE_NUMBA else "numpy"
    if name == "numba" and not HAVE_NUMBA:
        raise ValueError("plant config: simulation.backend = 'numba' but numba is not installed; "
                         "allowed: 'auto', 'numpy' (or install numba)")
    return name


def rk4_advance(backend, x, load, ua, ub, phase, u_amp, beta, c, n1, p, h, record_states=False):
    """Advance ``x`` (n_scen, 11) in place by ``load.shape[1]`` steps; return (outputs, states or None)."""
    n_scen, n = load.shape
    out = np.empty((N_OUTPUTS, n_scen, n))
    states = np.empty((N_STATES, n_scen, n)) if record_states else np.empty((N_STATES, 0, 0))
    args = (x, np.ascontiguousarray(load), np.ascontiguousarray(ua), np.ascontiguousarray(ub),
            np.ascontiguousarray(phase, dtype=np.float64), float(u_amp),
            np.ascontiguousarray(beta, dtype=np.float64), np.ascontiguousarray(c, dtype=np.float64),
            np.ascontiguousarray(n1, dtype=np.float64), p, float(h), out, states, bool(record_states))
    if backend == "numba":
        _rk4_numba(*args)
    else:
        _rk4_numpy(*args)
    return out, (states if record_states else None)
