"""The integrator: Dormand-Prince 5(4) with step-size control, its continuous extension for the 50 kHz output,
and located contact events.

Not the fixed-step classic RK4 at the sample period of ``backlash_monitor.plant``:

- the held inputs (pulse load, Gaussian generator every 0.2 ms, telegraph every 2 ms) change only on a
  0.2 ms grid, so the time axis is cut into SEGMENTS of 0.2 ms (10 samples) with a constant input each;
- inside a segment, adaptive Dormand-Prince 5(4) steps (FSAL; error per state against
  atol_i + rtol_i*|y_i|; step factor 0.9*err^(-1/5) in [0.2, 5]); a step never crosses a segment boundary;
- the samples inside a step come from the method's 4th-order continuous extension (Hairer's ``dense output``
  of DOPRI5); a1 and a2 are the right-hand side at the interpolated state (exact derivatives of the state,
  with the input held over [t_k, t_k+1));
- the contact mode (free / drive side / far side) is constant within a step. After each accepted step the mode
  the state implies is checked at the step's end and at three interior points of the interpolant; on a change,
  the first instant of change is found by bisection on the interpolant (to 1e-13 s), the step is redone up to
  that instant with the old law, and the mode is switched there;
- angles are re-referenced by whole turns at every segment (alpha1, alpha2 and the mass position move
  together, so every difference and every integer-order angle ripple is unchanged).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .physics import (N_STATES, P_KS, P_KW, P_R, S_A1, S_A2, S_AH, S_AR, S_V, S_W1, S_W2, S_X, implied_mode,
                      rhs)

# Dormand & Prince (1980), RK5(4)7M
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
B1, B3, B4, B5, B6 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40
# continuous extension (Hairer, Norsett & Wanner, Solving ODEs I, DOPRI5 dense output)
D1 = -12715105075 / 11282082432
D3 = 87487479700 / 32700410799
D4 = -10690763975 / 1880347072
D5 = 701980252875 / 199316789632
D6 = -1453857185 / 822651844
D7 = 69997945 / 29380423

# output columns of a recorded run
OUT_NAMES = ("a1", "a2", "omega1", "omega2", "angle_difference", "clutch_torque_Nm", "te_pu", "rim_force_N",
             "alpha1", "alpha2", "mode", "jaw_angle_difference")
N_OUT = len(OUT_NAMES)


@njit(cache=True)
def dopri_step(t, y, k, h, mode, u, P, tv, ynew, ytmp):
    """One DOPRI5 step from (t, y) with k[0] = f(t, y); fills k[1..6] (k[6] = f(ynew)) and ``ynew``;
    returns the error estimate vector in ``ytmp``'s place (ytmp is overwritten with it)."""
    n = y.size
    for i in range(n):
        ytmp[i] = y[i] + h * A21 * k[0, i]
    rhs(t + C2 * h, ytmp, mode, u, P, tv, k[1])
    for i in range(n):
        ytmp[i] = y[i] + h * (A31 * k[0, i] + A32 * k[1, i])
    rhs(t + C3 * h, ytmp, mode, u, P, tv, k[2])
    for i in range(n):
        ytmp[i] = y[i] + h * (A41 * k[0, i] + A42 * k[1, i] + A43 * k[2, i])
    rhs(t + C4 * h, ytmp, mode, u, P, tv, k[3])
    for i in range(n):
        ytmp[i] = y[i] + h * (A51 * k[0, i] + A52 * k[1, i] + A53 * k[2, i] + A54 * k[3, i])
    rhs(t + C5 * h, ytmp, mode, u, P, tv, k[4])
    for i in range(n):
        ytmp[i] = y[i] + h * (A61 * k[0, i] + A62 * k[1, i] + A63 * k[2, i] + A64 * k[3, i] + A65 * k[4, i])
    rhs(t + h, ytmp, mode, u, P, tv, k[5])
    for i in range(n):
        ynew[i] = y[i] + h * (B1 * k[0, i] + B3 * k[2, i] + B4 * k[3, i] + B5 * k[4, i] + B6 * k[5, i])
    rhs(t + h, ynew, mode, u, P, tv, k[6])
    for i in range(n):
        ytmp[i] = h * (E1 * k[0, i] + E3 * k[2, i] + E4 * k[3, i] + E5 * k[4, i] + E6 * k[5, i] + E7 * k[6, i])


@njit(cache=True)
def dense_coefficients(y, ynew, k, h, rc):
    """The 5 vectors of the continuous extension: y(t + th*h) = rc0 + th*(rc1 + (1-th)*(rc2 + th*(rc3 + (1-th)*rc4)))."""
    for i in range(y.size):
        dy = ynew[i] - y[i]
        bspl = h * k[0, i] - dy
        rc[0, i] = y[i]
        rc[1, i] = dy
        rc[2, i] = bspl
        rc[3, i] = dy - h * k[6, i] - bspl
        rc[4, i] = h * (D1 * k[0, i] + D3 * k[2, i] + D4 * k[3, i] + D5 * k[4, i] + D6 * k[5, i] + D7 * k[6, i])


@njit(cache=True)
def dense_eval(rc, th, out):
    th1 = 1.0 - th
    for i in range(out.size):
        out[i] = rc[0, i] + th * (rc[1, i] + th1 * (rc[2, i] + th * (rc[3, i] + th1 * rc[4, i])))


@njit(cache=True)
def _record(out, row, y, dy, tc, te, f, mode, P):
    out[row, 0] = P[P_R] * dy[S_W1]
    out[row, 1] = dy[S_V]
    out[row, 2] = y[S_W1]
    out[row, 3] = y[S_W2]
    out[row, 4] = y[S_A1] - y[S_A2]
    out[row, 5] = tc
    out[row, 6] = te
    out[row, 7] = f
    out[row, 8] = y[S_A1]
    out[row, 9] = y[S_A2]
    out[row, 10] = mode
    out[row, 11] = y[S_AH] - y[S_A2] if P[P_KS] > 0.0 else y[S_A1] - y[S_A2]


@njit(cache=True)
def _error_norm(err, y, ynew, atol, rtol):
    s = 0.0
    for i in range(y.size):
        a = abs(y[i])
        b = abs(ynew[i])
        sc = atol[i] + rtol[i] * (a if a > b else b)
        q = err[i] / sc
        s += q * q
    return math.sqrt(s / y.size)


@njit(cache=True)
def run_segments(y, mode, seg0, loads, seg_samples, dt, P, timevar, atol, rtol, h, out, stats):
    """Advance ``y`` (in place) over len(loads) segments of ``seg_samples`` samples of ``dt`` each, the
    held load moment ``loads[j]`` [p.u.] over segment j (absolute segment index seg0 + j, t = index*seg_dt).
    ``out`` (rows = samples, N_OUT columns) is filled when it has rows (else nothing is recorded).
    Returns (mode, h); ``stats`` += [accepted steps, rejected steps, events, right-hand side calls]."""
    n = y.size
    k = np.empty((7, n))
    ynew = np.empty(n)
    ytmp = np.empty(n)
    yint = np.empty(n)
    dyint = np.empty(n)
    rc = np.empty((5, n))
    seg_dt = seg_samples * dt
    record = out.shape[0] > 0
    two_pi = 2.0 * math.pi
    nacc = 0
    nrej = 0
    nev = 0
    nf = 0
    for j in range(loads.size):
        tj = (seg0 + j) * seg_dt
        u = loads[j]
        turns = math.floor(y[S_A2] / two_pi)
        if turns != 0.0:
            shift = turns * two_pi
            y[S_A1] -= shift
            y[S_A2] -= shift
            if P[P_KS] > 0.0:
                y[S_AH] -= shift
            if P[P_KW] > 0.0:
                y[S_AR] -= shift
            y[S_X] -= P[P_R] * shift
        tc, te, f = rhs(tj, y, mode, u, P, timevar, k[0])
        nf += 1
        if record:
            _record(out, j * seg_samples, y, k[0], tc, te, f, mode, P)
        tau = 0.0
        nxt = 1                       # next sample (within the segment) to record
        tiny = 0
        while seg_dt - tau > 1e-12 * seg_dt:
            hh = h if h < seg_dt - tau else seg_dt - tau
            if seg_dt - tau - hh < 0.01 * hh:
                hh = seg_dt - tau     # no sliver at the segment's end
            t = tj + tau
            dopri_step(t, y, k, hh, mode, u, P, timevar, ynew, ytmp)
            nf += 6
            err = _error_norm(ytmp, y, ynew, atol, rtol)
            if err > 1.0:
                h = hh * max(0.2, 0.9 * err ** -0.2)
                nrej += 1
                continue
            dense_coefficients(y, ynew, k, hh, rc)
            # ---- contact events: first instant at which the implied mode differs from the step's mode
            hi = -1.0
            for q in range(1, 5):
                th = 0.25 * q
                if q < 4:
                    dense_eval(rc, th, yint)
                    m = implied_mode(yint, P)
                else:
                    m = implied_mode(ynew, P)
                if m != mode:
                    hi = th
                    break
            if hi > 0.0:
                lo = hi - 0.25
                new_mode = m
                while (hi - lo) * hh > 1e-13:
                    mid = 0.5 * (lo + hi)
                    dense_eval(rc, mid, yint)
                    m = implied_mode(yint, P)
                    if m != mode:
                        hi = mid
                        new_mode = m
                    else:
                        lo = mid
                hs = hi * hh
                if hs > 1e-14:
                    dopri_step(t, y, k, hs, mode, u, P, timevar, ynew, ytmp)   # redo up to the event, old law
                    nf += 6
                    dense_coefficients(y, ynew, k, hs, rc)
                    tiny = 0
                elif tiny < 20:
                    hs = 0.0            # the change is at the step's start: switch the mode, step again
                    tiny += 1
                else:                   # a grazing contact that keeps flipping: take the whole step, then the
                    hs = hh             # mode its end state implies
                    new_mode = implied_mode(ynew, P)
                    tiny = 0
                step_len = hs
                nev += 1
            else:
                step_len = hh
                new_mode = mode
            # ---- samples inside (tau, tau + step_len]
            if record and step_len > 0.0:
                while nxt < seg_samples and nxt * dt <= tau + step_len + 1e-9 * dt:
                    th = (nxt * dt - tau) / step_len
                    if th > 1.0:
                        th = 1.0
                    dense_eval(rc, th, yint)
                    tc, te, f = rhs(tj + nxt * dt, yint, mode, u, P, timevar, dyint)
                    nf += 1
                    _record(out, j * seg_samples + nxt, yint, dyint, tc, te, f, mode, P)
                    nxt += 1
            if step_len > 0.0:
                for i in range(n):
                    y[i] = ynew[i]
                tau += step_len
            nacc += 1
            if new_mode != mode:
                mode = new_mode
                rhs(tj + tau, y, mode, u, P, timevar, k[0])
                nf += 1
            else:
                for i in range(n):
                    k[0, i] = k[6, i]
                if hi <= 0.0:
                    fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
                    h = hh * fac
    stats[0] += nacc
    stats[1] += nrej
    stats[2] += nev
    stats[3] += nf
    return mode, h
