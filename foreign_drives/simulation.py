"""One drive's run: the settled start (a periodic orbit found by Newton shooting), a run-in with the noise, the
recording at 50 kHz. numba kernels in :mod:`integrator`; this module is the numpy/scipy shell around them.

Settled start (not the run-in from an equivalent-circuit steady state of ``backlash_monitor.plant``):

1. a first guess: the motor's steady state in the synchronous frame at the pulse train's MEAN load (own
   equivalent-circuit solve), the clutch engaged on the drive side, the spring at F0/k;
2. four pulse periods integrated noise-free (towards the attractor);
3. Newton's method on the period map Phi (one pulse period, noise-free, without the terms that are not
   periodic with the pulse train): the states that return after a period (motor currents and rotor flux in
   the synchronous frame, speeds, angle differences to alpha2, spring extension z = y - x, mass speed);
   Jacobian by forward differences; until max_i |Phi(r)_i - r_i|/scale_i < 1e-10 (RESIDUAL_TOL);
4. a run-in of ``run_in_s`` (a whole number of periods, default 2 s) from that orbit with the noise and every
   term on, from the run-in's own random streams; then the recording starts at t = 0 (the pulse train's phase
   at 0 is the one the orbit was computed for).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from . import constants as C
from . import noise as N
from .kernel import (N_OUT, N_STATES, OUT_NAMES, P_A2TURNS, P_BETA, P_CLKT0, P_CT0, P_F0, P_K, P_KCD, P_KS, P_KW,
                     P_MEMINIT, P_PDUR,
                     P_PFIRST, P_PPER, P_RLYSTATE, P_TV, P_R, P_RR, P_RS, P_U, P_XM, P_XR, P_XS, S_A1, S_A2, S_AH, S_AR, S_ISD, S_ISQ, S_PRD, S_PRQ, S_V, S_W1, S_W2, S_WH, S_WR,
                     S_X, implied_mode, run_segments)

# tolerances of the DOPRI5 error control (per state; angles and the mass position absolute only)
ATOL = np.array([1e-9, 1e-9, 1e-9, 1e-9, 1e-8, 1e-10, 1e-8, 1e-10, 1e-8, 1e-10, 1e-8, 1e-10, 1e-10, 1e-9])
RTOL = np.array([1e-8, 1e-8, 1e-8, 1e-8, 1e-8, 0.0, 1e-8, 0.0, 1e-8, 0.0, 1e-8, 0.0, 0.0, 1e-8])
RESIDUAL_TOL = 1e-10
DEFAULT_RUN_IN_S = 2.0
DEFAULT_PRE_ROLL_S = 0.1        # outputs recorded before t = 0 (the sensor filters settle on them)

# reduced (periodic) coordinates: name, typical scale (Newton's residual and step are measured in these)
REDUCED = (("i_sd", 1.0), ("i_sq", 1.0), ("psi_rd", 1.0), ("psi_rq", 1.0), ("omega1", 100.0),
           ("alpha1-alpha2", 0.01), ("omega_hub", 100.0), ("alpha_hub-alpha2", 0.01), ("omega2", 100.0),
           ("omega_rim", 100.0), ("alpha_rim-alpha2", 0.01), ("z", 0.1), ("v", 10.0))


@dataclass
class Run:
    """A recorded run: ``out`` rows = samples from ``first_index`` (negative: the pre-roll before t = 0),
    columns :data:`integrator.OUT_NAMES`."""
    out: np.ndarray
    first_index: int
    sample_period_s: float
    stats: dict = field(default_factory=dict)

    def signal(self, name: str, pre_roll: bool = False) -> np.ndarray:
        col = self.out[:, OUT_NAMES.index(name)]
        return col if pre_roll else col[-self.first_index:]


def _active(P) -> np.ndarray:
    idx = [0, 1, 2, 3, 4, 5, 8, 11, 12]
    if P[P_KS] > 0.0:
        idx += [6, 7]
    if P[P_KW] > 0.0:
        idx += [9, 10]
    return np.array(sorted(idx))


def to_reduced(y, P) -> np.ndarray:
    r = P[P_R]
    a_rim = y[S_AR] if P[P_KW] > 0.0 else y[S_A2]
    return np.array([y[S_ISD], y[S_ISQ], y[S_PRD], y[S_PRQ], y[S_W1], y[S_A1] - y[S_A2], y[S_WH], y[S_AH] - y[S_A2],
                     y[S_W2], y[S_WR], y[S_AR] - y[S_A2], r * a_rim - y[S_X], y[S_V]])


def from_reduced(q, P) -> np.ndarray:
    y = np.zeros(N_STATES)
    y[S_ISD], y[S_ISQ], y[S_PRD], y[S_PRQ], y[S_W1] = q[0], q[1], q[2], q[3], q[4]
    y[S_A2] = 0.0
    y[S_A1] = q[5]
    if P[P_KS] > 0.0:
        y[S_WH], y[S_AH] = q[6], q[7]
    y[S_W2] = q[8]
    if P[P_KW] > 0.0:
        y[S_WR], y[S_AR] = q[9], q[10]
    a_rim = y[S_AR] if P[P_KW] > 0.0 else 0.0
    y[S_X] = P[P_R] * a_rim - q[11]
    y[S_V] = q[12]
    return y


def motor_steady_state(torque_pu: float, P) -> tuple:
    """(slip, i_s, psi_r) of the motor in the synchronous frame (supply U + j0) delivering ``torque_pu`` on the
    stable branch: 0 = U - r_s i_s - j psi_s, 0 = -r_r i_r - j s psi_r, solved for i_s and psi_r at a slip,
    then the slip by Brent's method."""
    rs, rr, xs, xr, xm, u = P[P_RS], P[P_RR], P[P_XS], P[P_XR], P[P_XM], P[P_U]
    sig, kr = (xs * xr - xm * xm) / xr, xm / xr

    def state(s):
        zr = rr * xm / (rr + 1j * s * xr)           # psi_r = zr * i_s
        i_s = u / (rs + 1j * sig + 1j * kr * zr)
        psi_r = zr * i_s
        return i_s, psi_r, kr * (psi_r.conjugate() * i_s).imag

    slips = np.geomspace(1e-6, 1.0, 400)
    te = np.array([state(s)[2] for s in slips])
    s_max = float(slips[int(np.argmax(te))])
    if not 0.0 < torque_pu < te.max():
        raise ValueError(f"motor: load {torque_pu:.4g} p.u. is outside the stable motoring range 0 < t < "
                         f"{te.max():.4g} p.u.")
    s = brentq(lambda x: state(x)[2] - torque_pu, 1e-9, s_max, xtol=1e-15)
    i_s, psi_r, _ = state(s)
    return s, i_s, psi_r


def first_guess(P, pulse_amplitude_pu: float) -> np.ndarray:
    """Full state: the motor at the mean load, the clutch engaged on the drive side, the spring at F0/k."""
    r = P[P_R]
    t_static = r * P[P_F0]
    mean_pulse = pulse_amplitude_pu * C.PULSE_DURATION_S / C.PULSE_PERIOD_S
    s, i_s, psi_r = motor_steady_state(t_static / C.BASE_TORQUE_NM + mean_pulse, P)
    w = (1.0 - s) * C.BASE_MECHANICAL_SPEED_RAD_S
    q = np.zeros(13)
    q[0], q[1], q[2], q[3] = i_s.real, i_s.imag, psi_r.real, psi_r.imag
    q[4] = q[6] = q[8] = q[9] = w
    jaw = P[P_BETA] + t_static / P[P_KCD]
    q[7] = jaw
    q[5] = jaw + (t_static / P[P_KS] if P[P_KS] > 0.0 else 0.0)
    q[10] = -t_static / P[P_KW] if P[P_KW] > 0.0 else 0.0
    q[11] = P[P_F0] / P[P_K]
    q[12] = r * w
    return from_reduced(q, P)


def _advance(y, mode, seg0, loads, P, timevar, tol_scale, h, out=None, stats=None):
    st = np.zeros(4, dtype=np.int64) if stats is None else stats
    o = np.zeros((0, N_OUT)) if out is None else out
    mode, h = run_segments(y, mode, seg0, np.ascontiguousarray(loads, dtype=np.float64), N.SEGMENT_SAMPLES,
                           C.SAMPLE_PERIOD_S, P, float(timevar), ATOL * tol_scale, RTOL * tol_scale, h, o, st)
    return mode, h


def set_pulse_timing(P, pulse_first_s: float) -> None:
    """The pulse train's timing on the segment grid into P (the kernel derives the held pulse indicator and the
    current pulse's start time from it, for outside terms that follow the pulse)."""
    P[P_PFIRST] = N.segments_of(pulse_first_s, "pulse_first_s")
    P[P_PPER] = N.segments_of(C.PULSE_PERIOD_S, "pulse period")
    P[P_PDUR] = N.segments_of(C.PULSE_DURATION_S, "pulse duration")


def period_map(q, P, pulse, tol_scale=1e-2):
    """Phi: the reduced state after one pulse period, noise-free, without the non-periodic terms."""
    y = from_reduced(q, P)
    mode = implied_mode(y, P)
    _advance(y, mode, 0, pulse, P, 0.0, tol_scale, 1e-5)
    return to_reduced(y, P)


def periodic_orbit(P, pulse_amplitude_pu: float, pulse_first_s: float, max_newton: int = 12) -> tuple:
    """(full state at t = 0 on the noise-free periodic orbit, info dict). Raises RuntimeError when Newton's
    method does not reach RESIDUAL_TOL (never silently returns an unsettled start)."""
    set_pulse_timing(P, pulse_first_s)
    n_per = N.segments_of(C.PULSE_PERIOD_S, "pulse period")
    pulse = N.pulse_train(0, n_per, pulse_amplitude_pu, pulse_first_s)
    act = _active(P)
    scale = np.array([s for _, s in REDUCED])[act]
    y = first_guess(P, pulse_amplitude_pu)
    mode = implied_mode(y, P)
    h = 1e-5
    for _ in range(4):
        mode, h = _advance(y, mode, 0, pulse, P, 0.0, 1e-2, h)
    q = to_reduced(y, P)
    info = {"newton_iterations": 0, "residual": None}
    for it in range(max_newton + 1):
        phi = period_map(q, P, pulse)
        res = (phi - q)[act]
        rnorm = float(np.max(np.abs(res) / scale))
        info["newton_iterations"], info["residual"] = it, rnorm
        if rnorm < RESIDUAL_TOL:
            return from_reduced(q, P), info
        if it == max_newton:
            break
        jac = np.empty((act.size, act.size))
        for c, i in enumerate(act):
            dq = q.copy()
            eps = 1e-6 * scale[c]
            dq[i] += eps
            jac[:, c] = ((period_map(dq, P, pulse) - phi)[act] - (dq - q)[act]) / eps
        step = np.linalg.solve(jac, -res)
        lam = 1.0
        while lam > 1e-3:          # damped Newton: accept a step that lowers the scaled residual
            qn = q.copy()
            qn[act] += lam * step
            rn = float(np.max(np.abs((period_map(qn, P, pulse) - qn)[act]) / scale))
            if rn < rnorm:
                break
            lam *= 0.5
        q = qn
    raise RuntimeError(f"settled start: Newton's method on the period map stopped at a residual {rnorm:.3g} "
                       f"(allowed < {RESIDUAL_TOL:g}) after {max_newton} iterations")


def simulate(P, *, duration_s: float, seed: int, noise: bool = True, pulse_amplitude_pu: float = C.PULSE_AMPLITUDE_PU,
             pulse_first_s: float = C.PULSE_FIRST_S, run_in_s: float = DEFAULT_RUN_IN_S,
             pre_roll_s: float = DEFAULT_PRE_ROLL_S, tol_scale: float = 1.0) -> Run:
    """The drive of parameter vector ``P`` from its settled start: ``duration_s`` recorded at 50 kHz (plus
    ``pre_roll_s`` before t = 0)."""
    n_rec = N.segments_of(duration_s, "duration_s")
    n_pre = N.segments_of(pre_roll_s, "pre_roll_s")
    n_run = N.segments_of(run_in_s, "run_in_s")
    n_per = N.segments_of(C.PULSE_PERIOD_S, "pulse period")
    if n_run % n_per:
        raise ValueError(f"run_in_s = {run_in_s} is not a whole number of pulse periods ({C.PULSE_PERIOD_S} s)")
    if n_pre > n_run:
        raise ValueError(f"pre_roll_s = {pre_roll_s} exceeds run_in_s = {run_in_s}")
    rng = N.streams(seed)
    set_pulse_timing(P, pulse_first_s)
    y, info = periodic_orbit(P, pulse_amplitude_pu, pulse_first_s)
    # the run with every term: the non-periodic ones act from here (the transmission error in implied_mode too); the
    # wheel angle is unwrapped and the relay starts off from the run-in's first segment (kernel: alpha2_turns, relay)
    P[P_TV] = 1.0
    P[P_A2TURNS] = 0.0
    P[P_RLYSTATE] = 0.0
    # the fourth set: the memory element starts afresh at the run-in's first scan, a contact in progress and the
    # clock the wheel's angle is compared with begin with the run-in (kernel: mem_*, contact_t0, clock_t0)
    P[P_MEMINIT] = 0.0
    P[P_CT0] = P[P_CLKT0] = -n_run * N.SEGMENT_S
    mode = implied_mode(y, P)
    loads_run = N.pulse_train(-n_run, n_run, pulse_amplitude_pu, pulse_first_s)
    loads_rec = N.pulse_train(0, n_rec, pulse_amplitude_pu, pulse_first_s)
    if noise:
        loads_run = loads_run + N.gaussian_values(rng["run_in_gaussian"], n_run) \
            + N.telegraph_values(rng["run_in_telegraph"], n_run)
        loads_rec = loads_rec + N.gaussian_values(rng["gaussian"], n_rec) + N.telegraph_values(rng["telegraph"], n_rec)
    stats = np.zeros(4, dtype=np.int64)
    ss = N.SEGMENT_SAMPLES
    out = np.empty(((n_pre + n_rec) * ss, N_OUT))
    h = 1e-5
    mode, h = _advance(y, mode, -n_run, loads_run[:n_run - n_pre], P, 1.0, tol_scale, h, stats=stats)
    if n_pre:
        mode, h = _advance(y, mode, -n_pre, loads_run[n_run - n_pre:], P, 1.0, tol_scale, h, out=out[:n_pre * ss],
                           stats=stats)
    mode, h = _advance(y, mode, 0, loads_rec, P, 1.0, tol_scale, h, out=out[n_pre * ss:], stats=stats)
    if not np.all(np.isfinite(out)):
        raise RuntimeError("the drive's simulation diverged (a non-finite state); its parameters leave the "
                           "range in which this drive runs (e.g. a load beyond the motor's breakdown torque)")
    st = dict(zip(("accepted_steps", "rejected_steps", "events", "rhs_calls"), (int(v) for v in stats)))
    st.update(info)
    return Run(out=out, first_index=-n_pre * ss, sample_period_s=C.SAMPLE_PERIOD_S, stats=st)
