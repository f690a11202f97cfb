"""The drive's right-hand side, written from the equations of SPEC section 3 in a formulation of its own.

Not the formulation of ``backlash_monitor.plant`` (docs/foreign_drives.md "Equations"):

- motor: stator CURRENT and rotor flux as states, in the SYNCHRONOUS frame (rotating with the supply, so the
  supply is the constant U and the electrical states are constant in steady state); the speed in rad/s
  (SI mechanical balance J1*dOmega1/dt = T_b*t_e - T_shaft - T_load);
- clutch: the two shaft ANGLES are states (alpha1, alpha2; the angle difference is a derived quantity), the
  contact state is a discrete MODE (free / drive-side contact / far-side contact) switched by located events
  (:mod:`foreign_drives.integrator`) instead of a gate on the state;
- load: the mass in ABSOLUTE coordinates (position x and speed v), the rim at y = r*alpha2; the spring
  extension z = y - x is derived;
- optional extra states: a shaft hub of its own inertia between the motor and the jaw (shaft compliance
  with a real inertia) and a wheel rim of its own inertia on a torsional spring (a second torsional mode).

All angles are in rad, speeds in rad/s, torques in N*m, forces in N; the motor's electrical states are in
per unit. Every effect form of :mod:`foreign_drives.forms` acts through the parameter vector ``P`` (all
forms are compiled into this one right-hand side; a form at its neutral value is exactly absent).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from . import constants as C

# ---------------------------------------------------------------- state layout (14 states)
STATE_NAMES = ("i_sd", "i_sq", "psi_rd", "psi_rq", "omega1", "alpha1", "omega_hub", "alpha_hub",
               "omega2", "alpha2", "omega_rim", "alpha_rim", "x", "v")
(S_ISD, S_ISQ, S_PRD, S_PRQ, S_W1, S_A1, S_WH, S_AH, S_W2, S_A2, S_WR, S_AR, S_X, S_V) = range(14)
N_STATES = 14
ANGLE_STATES = (S_A1, S_AH, S_A2, S_AR)

# ---------------------------------------------------------------- parameter vector layout
PARAM_NAMES = (
    # motor
    "rs", "rr", "xs", "xr", "xm", "supply_pu", "omega_b", "omega_mb", "torque_base", "j1",
    # clutch contact law (per side stiffness; exponent and reference penetration of a power law; Hunt-Crossley
    # damping per rad of penetration; preload at contact; progressive-law penetration scale, 0 = off)
    "beta", "kc_drive", "kc_far", "dc", "contact_exponent", "contact_ref_rad", "hc_lambda", "contact_preload",
    "progressive_p0",
    # shaft with a hub inertia (ks = 0: rigid, no hub)
    "shaft_k", "shaft_d", "hub_inertia",
    # wheel (hub) inertia, optional rim on a torsional spring (wheel_k = 0: no rim)
    "j2", "wheel_k", "wheel_d", "rim_inertia",
    # load
    "radius", "mass", "spring_k", "spring_z0", "absorber_c", "absorber_n", "working_force",
    # wheel friction forms (torques against the wheel's rotation)
    "wf_tanh_torque", "wf_tanh_speed", "wf_load_mu_r", "wf_drag_c", "wf_drag_p",
    "wf_str_coulomb", "wf_str_excess", "wf_str_speed", "wf_str_exponent", "wheel_const_torque",
    # motor-side forms (torques on the motor shaft's load)
    "mf_tanh_torque", "mf_tanh_speed", "mf_viscous_b", "m_fan_torque", "m_fan_speed", "m_const_torque",
    # mass forms (forces on the mass, + along x)
    "rail_force", "rail_speed", "mass_drag_c", "mass_const_force",
    # torque ripples locked to the motor angle on the load moment (p.u.; integer orders), four harmonics
    "rip_n0", "rip_a0", "rip_ph0", "rip_n1", "rip_a1", "rip_ph1", "rip_n2", "rip_a2", "rip_ph2",
    "rip_n3", "rip_a3", "rip_ph3",
    # ripple of the electromagnetic torque (relative), gear mesh on the wheel (N*m, locked to alpha2)
    "em_eps", "em_n", "em_ph", "gm_torque", "gm_n", "gm_ph",
    # structural vibration at a fixed frequency on the motor's load moment (p.u.)
    "vib_pu", "vib_hz", "vib_ph",
)
N_PARAMS = len(PARAM_NAMES)
PI = {name: i for i, name in enumerate(PARAM_NAMES)}
(P_RS, P_RR, P_XS, P_XR, P_XM, P_U, P_OMB, P_OMMB, P_TB, P_J1,
 P_BETA, P_KCD, P_KCF, P_DC, P_CEXP, P_CREF, P_HCL, P_CPRE, P_PROG,
 P_KS, P_DS, P_JH,
 P_J2, P_KW, P_DW, P_JR,
 P_R, P_M, P_K, P_Z0, P_C, P_N1, P_F0,
 P_WFT, P_WFTW, P_WFL, P_WFDC, P_WFDP, P_WSC, P_WSE, P_WSW, P_WSD, P_WCT,
 P_MFT, P_MFTW, P_MFV, P_MFAN, P_MFANW, P_MCT,
 P_RAILF, P_RAILV, P_MDC, P_MCF,
 P_RN0, P_RA0, P_RP0, P_RN1, P_RA1, P_RP1, P_RN2, P_RA2, P_RP2, P_RN3, P_RA3, P_RP3,
 P_EME, P_EMN, P_EMP, P_GMA, P_GMN, P_GMP,
 P_VIBA, P_VIBF, P_VIBP) = range(N_PARAMS)


def nominal_parameters(width_m: float, eta_k: float, n1: float) -> np.ndarray:
    """The parameter vector of the nominal drive (SPEC section 3) at a width, eta_k, n1; every effect off."""
    p = np.zeros(N_PARAMS)
    p[P_RS], p[P_RR] = C.STATOR_RESISTANCE_PU, C.ROTOR_RESISTANCE_PU
    p[P_XS], p[P_XR], p[P_XM] = C.STATOR_REACTANCE_PU, C.ROTOR_REACTANCE_PU, C.MAGNETISING_REACTANCE_PU
    p[P_U], p[P_OMB], p[P_OMMB] = C.SUPPLY_VOLTAGE_PU, C.BASE_ELECTRICAL_SPEED_RAD_S, C.BASE_MECHANICAL_SPEED_RAD_S
    p[P_TB], p[P_J1] = C.BASE_TORQUE_NM, C.MOTOR_INERTIA_KGM2
    p[P_BETA] = width_m / C.WHEEL_RADIUS_M
    p[P_KCD] = p[P_KCF] = C.CONTACT_STIFFNESS_NM_PER_RAD
    p[P_DC] = C.CONTACT_DAMPING_NMS_PER_RAD
    p[P_CEXP], p[P_CREF] = 1.0, 1.0e-3
    p[P_J2] = C.WHEEL_INERTIA_KGM2
    p[P_R], p[P_M], p[P_K] = C.WHEEL_RADIUS_M, C.MASS_KG, C.SPRING_STIFFNESS_N_PER_M
    p[P_C], p[P_N1] = C.absorber_coefficient(eta_k, n1), n1
    p[P_F0] = C.WORKING_RESISTANCE_N
    # speeds that scale smooth laws: never 0 (divisions), irrelevant while the torque/force beside them is 0
    p[P_WFTW] = p[P_MFTW] = p[P_RAILV] = 1.0
    p[P_WSW], p[P_WSD], p[P_WFDP] = 100.0, 1.0, 2.0
    p[P_MFANW] = C.BASE_MECHANICAL_SPEED_RAD_S
    return p


@njit(cache=True, inline="always")
def contact_torque(pen, pen_rate, k, P):
    """Torque [N*m] the jaw contact law gives at penetration ``pen`` [rad] (>= 0 where it acts) and
    penetration rate ``pen_rate`` [rad/s]: preload + k*p_ref*(p/p_ref)^n*(1 + (p/p0)^2) + (d + lambda*p)*p'.
    The nominal law (n = 1, no preload, p0 = 0, lambda = 0) is k*p + d*p' (SPEC)."""
    pp = pen if pen > 0.0 else 0.0
    n = P[P_CEXP]
    if n == 1.0:
        el = k * pp
    else:
        el = k * P[P_CREF] * (pp / P[P_CREF]) ** n
    p0 = P[P_PROG]
    if p0 > 0.0:
        q = pp / p0
        el = el * (1.0 + q * q)
    return P[P_CPRE] + el + (P[P_DC] + P[P_HCL] * pp) * pen_rate


@njit(cache=True, inline="always")
def clutch_angles(y, P):
    """(angle difference across the jaw [rad], its rate [rad/s]): drive half = hub if there is a shaft, else the
    motor."""
    if P[P_KS] > 0.0:
        return y[S_AH] - y[S_A2], y[S_WH] - y[S_W2]
    return y[S_A1] - y[S_A2], y[S_W1] - y[S_W2]


@njit(cache=True)
def implied_mode(y, P):
    """The contact mode the state implies: +1 drive side pushing (jaw angle difference > beta and the law's
    torque > 0), -1 far side pushing, 0 free (in the gap, or touching without pushing: a contact never pulls)."""
    d, dd = clutch_angles(y, P)
    beta = P[P_BETA]
    pen = d - beta
    if pen > 0.0 and contact_torque(pen, dd, P[P_KCD], P) > 0.0:
        return 1
    pen = -d - beta
    if pen > 0.0 and contact_torque(pen, -dd, P[P_KCF], P) > 0.0:
        return -1
    return 0


@njit(cache=True, inline="always")
def _sgn(x):
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


@njit(cache=True)
def rhs(t, y, mode, load_pu, P, timevar, dy):
    """dy/dt of the 14 states into ``dy``; returns (clutch torque T_c [N*m], electromagnetic torque [p.u.],
    rim-mass force F [N]). ``load_pu``: the held motor load moment (pulse + disturbances) [p.u.];
    ``timevar``: 1.0 = include the terms that are not periodic with the pulse train (angle-locked ripples,
    a fixed-frequency vibration), 0.0 = leave them out (the periodic orbit of the settled start)."""
    # ---- motor, synchronous frame (supply = U + j0), states i_s and psi_r
    xs, xr, xm = P[P_XS], P[P_XR], P[P_XM]
    sig = (xs * xr - xm * xm) / xr          # transient reactance w/x_r
    kr = xm / xr
    ob = P[P_OMB]
    isd, isq, prd, prq = y[S_ISD], y[S_ISQ], y[S_PRD], y[S_PRQ]
    w1 = y[S_W1]
    a1 = y[S_A1]
    slip = 1.0 - w1 / P[P_OMMB]
    ird = (prd - xm * isd) / xr
    irq = (prq - xm * isq) / xr
    dprd = ob * (-P[P_RR] * ird + slip * prq)      # dpsi_r/dt = Omega_b(-r_r i_r - j(1 - w) psi_r)
    dprq = ob * (-P[P_RR] * irq - slip * prd)
    psd = sig * isd + kr * prd
    psq = sig * isq + kr * prq
    dpsd = ob * (P[P_U] - P[P_RS] * isd + psq)     # dpsi_s/dt = Omega_b(U - r_s i_s - j psi_s)
    dpsq = ob * (-P[P_RS] * isq - psd)
    dy[S_ISD] = (dpsd - kr * dprd) / sig           # psi_s = sig*i_s + kr*psi_r
    dy[S_ISQ] = (dpsq - kr * dprq) / sig
    dy[S_PRD] = dprd
    dy[S_PRQ] = dprq
    te = psd * isq - psq * isd                     # = kr*(psi_rd i_sq - psi_rq i_sd)
    if timevar != 0.0 and P[P_EME] != 0.0:
        te = te * (1.0 + P[P_EME] * math.sin(P[P_EMN] * a1 + P[P_EMP]))
    # ---- load moment on the motor [N*m]
    tl = load_pu
    if timevar != 0.0:
        if P[P_RA0] != 0.0:
            tl += P[P_RA0] * math.sin(P[P_RN0] * a1 + P[P_RP0])
        if P[P_RA1] != 0.0:
            tl += P[P_RA1] * math.sin(P[P_RN1] * a1 + P[P_RP1])
        if P[P_RA2] != 0.0:
            tl += P[P_RA2] * math.sin(P[P_RN2] * a1 + P[P_RP2])
        if P[P_RA3] != 0.0:
            tl += P[P_RA3] * math.sin(P[P_RN3] * a1 + P[P_RP3])
        if P[P_VIBA] != 0.0:
            tl += P[P_VIBA] * math.sin(2.0 * math.pi * P[P_VIBF] * t + P[P_VIBP])
    tb = P[P_TB]
    tload = tb * tl
    if P[P_MFT] != 0.0:
        tload += P[P_MFT] * math.tanh(w1 / P[P_MFTW])
    if P[P_MFV] != 0.0:
        tload += P[P_MFV] * w1
    if P[P_MFAN] != 0.0:
        q = w1 / P[P_MFANW]
        tload += P[P_MFAN] * q * abs(q)
    tload += P[P_MCT]
    # ---- shaft and clutch
    if P[P_KS] > 0.0:
        tshaft = P[P_KS] * (a1 - y[S_AH]) + P[P_DS] * (w1 - y[S_WH])
    else:
        tshaft = 0.0
    d, dd = clutch_angles(y, P)
    if mode == 1:
        tc = contact_torque(d - P[P_BETA], dd, P[P_KCD], P)
    elif mode == -1:
        tc = -contact_torque(-d - P[P_BETA], -dd, P[P_KCF], P)
    else:
        tc = 0.0
    if P[P_KS] > 0.0:
        dy[S_W1] = (tb * te - tshaft - tload) / P[P_J1]
        dy[S_WH] = (tshaft - tc) / P[P_JH]
        dy[S_AH] = y[S_WH]
    else:
        dy[S_W1] = (tb * te - tc - tload) / P[P_J1]
        dy[S_WH] = 0.0
        dy[S_AH] = 0.0
    dy[S_A1] = w1
    # ---- wheel, rim, spring/absorber, mass (absolute coordinates)
    r = P[P_R]
    w2 = y[S_W2]
    a2 = y[S_A2]
    if P[P_KW] > 0.0:
        twist = P[P_KW] * (a2 - y[S_AR]) + P[P_DW] * (w2 - y[S_WR])
        yr = r * y[S_AR]
        yrd = r * y[S_WR]
    else:
        twist = 0.0
        yr = r * a2
        yrd = r * w2
    x = y[S_X]
    v = y[S_V]
    z = yr - x
    fs = P[P_K] * z
    if P[P_Z0] > 0.0:
        q = z / P[P_Z0]
        fs = fs * (1.0 + q * q)
    vr = yrd - v
    fa = P[P_C] * abs(vr) ** P[P_N1] * _sgn(vr)
    f = fs + fa
    s2 = _sgn(w2)
    tf = P[P_WCT]
    if P[P_WFT] != 0.0:
        tf += P[P_WFT] * math.tanh(w2 / P[P_WFTW])
    if P[P_WFL] != 0.0:
        tf += P[P_WFL] * abs(f) * s2
    if P[P_WFDC] != 0.0:
        tf += P[P_WFDC] * abs(w2) ** P[P_WFDP] * s2
    if P[P_WSC] != 0.0 or P[P_WSE] != 0.0:
        tf += (P[P_WSC] + P[P_WSE] * math.exp(-(abs(w2) / P[P_WSW]) ** P[P_WSD])) * s2
    if timevar != 0.0 and P[P_GMA] != 0.0:
        tf += P[P_GMA] * math.sin(P[P_GMN] * a2 + P[P_GMP])
    if P[P_KW] > 0.0:
        dy[S_W2] = (tc - twist - tf) / P[P_J2]
        dy[S_WR] = (twist - r * f) / P[P_JR]
        dy[S_AR] = y[S_WR]
    else:
        dy[S_W2] = (tc - r * f - tf) / P[P_J2]
        dy[S_WR] = 0.0
        dy[S_AR] = 0.0
    dy[S_A2] = w2
    dy[S_X] = v
    fm = f - P[P_F0] + P[P_MCF]
    if P[P_RAILF] != 0.0:
        fm -= P[P_RAILF] * math.tanh(v / P[P_RAILV])
    if P[P_MDC] != 0.0:
        fm -= P[P_MDC] * v * abs(v)
    dy[S_V] = fm / P[P_M]
    return tc, te, f
