"""Drive train: state layout and the nominal model's derived quantities (SPEC section 3).

State (11 per scenario), in this order (``STATE_NAMES``):

    psi_sa, psi_sb, psi_ra, psi_rb  [p.u.]   motor flux linkages
    w1                              [p.u.]   motor speed, Omega1 = w1*Omega_mb
    delta                           [rad]    Delta = alpha1 - alpha2, integrated as a state
    alpha1, alpha2                  [rad]    shaft angles (outputs; nothing depends on them but terms that name them)
    omega2                          [rad/s]  wheel speed Omega2
    z                               [m]      spring/absorber extension z = r*alpha2 - x
    xdot                            [m/s]    mass speed

The right-hand side itself is generated from the enabled effects (:mod:`codegen`, :mod:`effects`):
every term is written once, in its effect class.
"""
from __future__ import annotations

import numpy as np

from .state import N_STATES, STATE_NAMES  # noqa: F401 (re-exported: the layout beside the S_* indices)

(S_PSA, S_PSB, S_PRA, S_PRB, S_W1, S_DELTA, S_ALPHA1, S_ALPHA2, S_OMEGA2, S_Z, S_XDOT) = range(N_STATES)


def half_gap_rad(width_m, cfg) -> float:
    """beta = b/r: the zone is |Delta| < beta (paper eq. 1: |alpha1 - alpha2| < K2/r)."""
    return width_m / cfg.load.wheel_radius_m


def absorber_coefficient(eta_k, n1, cfg):
    """c = eta_k * S1 / h^n1  [N*(s/m)^n1]."""
    return eta_k * cfg.load.absorber_area_m2 / cfg.load.absorber_gap_m ** n1


def clutch_torque(delta, rel_speed, beta, k_c, d_c):
    """Backlash clutch torque T_c [N*m]: 0 in the zone, a stiff contact that never pulls outside
    (an independent array form of the clutch law, for tests and analyses)."""
    ad = np.abs(delta)
    s = np.sign(delta)
    engaged = ad >= beta
    return engaged * s * np.maximum(0.0, k_c * (ad - beta) + s * d_c * rel_speed)


def absorber_force(v, c, n1):
    """Ostwald-de Waele absorber force c*|v|^n1*sign(v) [N]."""
    return c * np.abs(v) ** n1 * np.sign(v)
