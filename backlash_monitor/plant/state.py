"""The plant's state layout: the integrated states and the globals every generated kernel reads.

A leaf of ``plant/``: the code generator (codegen.py), the outputs table (outputs.py), the integrator
and the drivetrain read the layout from here, so none of them imports another to learn it.

- :data:`STATE_NAMES`: the states in the order of the state vector's first axis (SPEC section 3):
  stator and rotor fluxes [pu], motor speed w1 [pu], angle difference delta [rad], shaft angles
  alpha1/alpha2 [rad], wheel speed omega2 [rad/s], absorber state z and its rate xdot;
- :data:`GLOBAL_NAMES`: the motor's per-unit constants and bases in the global vector ``G``
  (codegen.global_vector builds it in this order).
"""
from __future__ import annotations

STATE_NAMES = ("psi_sa", "psi_sb", "psi_ra", "psi_rb", "w1", "delta", "alpha1", "alpha2", "omega2", "z", "xdot")
N_STATES = len(STATE_NAMES)
GLOBAL_NAMES = ("g_rs", "g_rr", "g_xs", "g_xr", "g_xm", "g_w", "g_omega_b", "g_T_m", "g_omega_mb", "g_T_b", "g_r")
