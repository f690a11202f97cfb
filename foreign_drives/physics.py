"""The nominal drive's parameter vector (SPEC section 3). The right-hand side it feeds, written from SPEC's
equations in a formulation of its own, is compiled in :mod:`foreign_drives.kernel` (summary below).

Not the formulation of ``backlash_monitor.plant`` (docs/foreign_drives.md "Equations"):

- motor: stator CURRENT and rotor flux as states, in the SYNCHRONOUS frame (rotating with the supply, so the
  supply is the constant U and the electrical states are constant in steady state); the speed in rad/s
  (SI mechanical balance J1*dOmega1/dt = T_b*t_e - T_shaft - T_load);
- clutch: the two shaft ANGLES are states (alpha1, alpha2; the angle difference is a derived quantity), the
  contact state is a discrete MODE (free / drive-side contact / far-side contact) switched by located events
  (the integrator locates them) instead of a gate on the state;
- load: the mass in ABSOLUTE coordinates (position x and speed v), the rim at y = r*alpha2; the spring
  extension z = y - x is derived;
- optional extra states: a shaft hub of its own inertia between the motor and the jaw (shaft compliance
  with a real inertia) and a wheel rim of its own inertia on a torsional spring (a second torsional mode).

All angles are in rad, speeds in rad/s, torques in N*m, forces in N; the motor's electrical states are in
per unit. Every effect form of :mod:`foreign_drives.forms` acts through the parameter vector ``P`` (all
forms are compiled into this one right-hand side; a form at its neutral value is exactly absent).
"""
from __future__ import annotations

import numpy as np

from . import constants as C
from .kernel import (N_PARAMS, P_BETA, P_C, P_CEXP, P_CPRS, P_CREF, P_DC, P_F0, P_J1, P_J2, P_K, P_KCD, P_KCF,
                     P_M, P_MFANW, P_MFTW, P_N1, P_OMB, P_OMMB, P_R, P_RAILV, P_RR, P_RS, P_TB, P_U, P_WFDP,
                     P_WFTW, P_WSD, P_WSW, P_XM, P_XR, P_XS)


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
    p[P_CPRS] = 1.0e-4
    p[P_J2] = C.WHEEL_INERTIA_KGM2
    p[P_R], p[P_M], p[P_K] = C.WHEEL_RADIUS_M, C.MASS_KG, C.SPRING_STIFFNESS_N_PER_M
    p[P_C], p[P_N1] = C.absorber_coefficient(eta_k, n1), n1
    p[P_F0] = C.WORKING_RESISTANCE_N
    # speeds that scale smooth laws: never 0 (divisions), irrelevant while the torque/force beside them is 0
    p[P_WFTW] = p[P_MFTW] = p[P_RAILV] = 1.0
    p[P_WSW], p[P_WSD], p[P_WFDP] = 100.0, 1.0, 2.0
    p[P_MFANW] = C.BASE_MECHANICAL_SPEED_RAD_S
    return p


