"""Drive train: backlash clutch, working machine and the full right-hand side (SPEC section 3).

State (11 per scenario), in this order (``STATE_NAMES``):

    psi_sa, psi_sb, psi_ra, psi_rb  [p.u.]   motor flux linkages
    w1                              [p.u.]   motor speed, Omega1 = w1*Omega_mb
    delta                           [rad]    Delta = alpha1 - alpha2, integrated as a state
    alpha1, alpha2                  [rad]    shaft angles (outputs; nothing depends on them)
    omega2                          [rad/s]  wheel speed Omega2
    z                               [m]      spring/absorber extension z = r*alpha2 - x
    xdot                            [m/s]    mass speed

:func:`plant_derivatives` is written with arithmetic and numpy ufuncs only, so the same code runs
on floats inside the numba kernel and on arrays in the numpy backend and the solve_ivp reference.
"""
from __future__ import annotations

import math

import numpy as np

from ._numba import jitable

from .motor import flux_derivatives

STATE_NAMES = ("psi_sa", "psi_sb", "psi_ra", "psi_rb", "w1", "delta", "alpha1", "alpha2", "omega2", "z", "xdot")
N_STATES = len(STATE_NAMES)
(S_PSA, S_PSB, S_PRA, S_PRB, S_W1, S_DELTA, S_ALPHA1, S_ALPHA2, S_OMEGA2, S_Z, S_XDOT) = range(N_STATES)

# Global parameter vector layout (one vector for all scenarios).
PARAM_NAMES = ("r_s", "r_r", "x_s", "x_r", "x_m", "w", "omega_b", "T_m", "omega_mb", "T_b",
               "k_c", "d_c", "J2", "r", "k", "m", "F0",
               "on_clutch", "on_spring", "on_absorber", "on_resistance")
N_PARAMS = len(PARAM_NAMES)
(P_RS, P_RR, P_XS, P_XR, P_XM, P_W, P_OMEGA_B, P_TM, P_OMEGA_MB, P_TB,
 P_KC, P_DC, P_J2, P_R, P_K, P_M, P_F0,
 P_ON_CLUTCH, P_ON_SPRING, P_ON_ABSORBER, P_ON_RESISTANCE) = range(N_PARAMS)


def global_parameters(cfg) -> np.ndarray:
    """The global parameter vector of a :class:`PlantConfig` (layout ``PARAM_NAMES``)."""
    m, c, ld, e = cfg.motor, cfg.clutch, cfg.load, cfg.effects
    return np.array([m.r_s_pu, m.r_r_pu, m.x_s_pu, m.x_r_pu, m.x_m_pu, m.w_pu, m.base_angular_frequency_rad_s,
                     m.mechanical_time_constant_s, m.base_mechanical_speed_rad_s, m.base_torque_Nm,
                     c.contact_stiffness_Nm_per_rad, c.contact_damping_Nms_per_rad, ld.wheel_inertia_kgm2,
                     ld.wheel_radius_m, ld.spring_stiffness_N_per_m, ld.mass_kg, ld.working_resistance_N,
                     float(e.backlash_clutch), float(e.spring), float(e.absorber_power_law),
                     float(e.working_resistance)], dtype=np.float64)


def half_gap_rad(width_m, cfg) -> float:
    """beta = b/r: the zone is |Delta| < beta (paper eq. 1: |alpha1 - alpha2| < K2/r)."""
    return width_m / cfg.load.wheel_radius_m


def absorber_coefficient(eta_k, n1, cfg):
    """c = eta_k * S1 / h^n1  [N*(s/m)^n1]."""
    return eta_k * cfg.load.absorber_area_m2 / cfg.load.absorber_gap_m ** n1


def clutch_torque(delta, rel_speed, beta, k_c, d_c):
    """Backlash clutch torque T_c [N*m]: 0 in the zone, a stiff contact that never pulls outside."""
    ad = np.abs(delta)
    s = np.sign(delta)
    engaged = ad >= beta
    return engaged * s * np.maximum(0.0, k_c * (ad - beta) + s * d_c * rel_speed)


def absorber_force(v, c, n1):
    """Ostwald-de Waele absorber force c*|v|^n1*sign(v) [N]."""
    return c * np.abs(v) ** n1 * np.sign(v)


def plant_derivatives(psa, psb, pra, prb, w1, delta, omega2, z, xdot, ua, ub, load_pu, beta, c, n1, p):
    """Right-hand side of the plant. Returns the 11 state derivatives (``STATE_NAMES`` order) and
    (t_e [p.u.], T_c [N*m], F [N]).

    ``load_pu``: the motor's load moment from the held inputs (pulse load + disturbances + constant), p.u.
    ``beta``, ``c``, ``n1``: per scenario; ``p``: global parameter vector.
    """
    dpsa, dpsb, dpra, dprb, te = flux_derivatives(psa, psb, pra, prb, w1, ua, ub, p[P_RS], p[P_RR], p[P_XS],
                                                  p[P_XR], p[P_XM], p[P_W], p[P_OMEGA_B])
    omega1 = w1 * p[P_OMEGA_MB]
    rel = omega1 - omega2
    # balance clutch_torque_Nm
    tc = p[P_ON_CLUTCH] * clutch_torque(delta, rel, beta, p[P_KC], p[P_DC])
    # balance rim_mass_force_N
    v = p[P_R] * omega2 - xdot
    f = p[P_ON_SPRING] * p[P_K] * z + p[P_ON_ABSORBER] * absorber_force(v, c, n1)
    # motor: T_m dw1/dt = t_e - T_c/T_b - load   (balance motor_load_moment_pu enters as load_pu)
    dw1 = (te - tc / p[P_TB] - load_pu) / p[P_TM]
    # wheel: J2 dOmega2/dt = T_c - r F   (balance wheel_torque_Nm: none built in)
    domega2 = (tc - p[P_R] * f) / p[P_J2]
    # mass: m x'' = F - F0   (balance mass_force_N)
    dxdot = (f - p[P_ON_RESISTANCE] * p[P_F0]) / p[P_M]
    return (dpsa, dpsb, dpra, dprb, dw1, rel, omega1, omega2, domega2, v, dxdot), (te, tc, f)


@jitable
def plant_derivatives_scalar(psa, psb, pra, prb, w1, delta, omega2, z, xdot, ua, ub, load_pu, beta, c, n1, p,
                             mode=0):
    """:func:`plant_derivatives` for one scenario on floats, written for the compiled kernel (branches
    instead of masks, exp/log instead of pow). Same equations; the tests check both agree.

    ``mode``: 0 = the zone test |Delta| < beta decides; 1 = in contact, 2 = in the zone (forced; used by
    the integrator on either side of a located zone crossing, where |Delta| = beta up to rounding)."""
    dpsa, dpsb, dpra, dprb, te = flux_derivatives(psa, psb, pra, prb, w1, ua, ub, p[P_RS], p[P_RR], p[P_XS],
                                                  p[P_XR], p[P_XM], p[P_W], p[P_OMEGA_B])
    omega1 = w1 * p[P_OMEGA_MB]
    rel = omega1 - omega2
    tc = 0.0
    engaged = (abs(delta) >= beta) if mode == 0 else (mode == 1)
    if engaged:
        if delta > 0.0:
            tc = p[P_KC] * (delta - beta) + p[P_DC] * rel
            if tc < 0.0:
                tc = 0.0
        else:
            tc = p[P_KC] * (delta + beta) + p[P_DC] * rel
            if tc > 0.0:
                tc = 0.0
    tc *= p[P_ON_CLUTCH]
    v = p[P_R] * omega2 - xdot
    av = abs(v)
    fa = math.copysign(c * math.exp(n1 * math.log(av)), v) if av > 0.0 else 0.0
    f = p[P_ON_SPRING] * p[P_K] * z + p[P_ON_ABSORBER] * fa
    dw1 = (te - tc / p[P_TB] - load_pu) / p[P_TM]
    domega2 = (tc - p[P_R] * f) / p[P_J2]
    dxdot = (f - p[P_ON_RESISTANCE] * p[P_F0]) / p[P_M]
    return (dpsa, dpsb, dpra, dprb, dw1, rel, omega1, omega2, domega2, v, dxdot), (te, tc, f)
