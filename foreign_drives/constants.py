"""The constants of SPEC section 3 (/work/shared/SPEC.md), written out here with their source.

This package shares nothing with ``backlash_monitor`` but these numbers: its physics, integrator, noise
generators, settled start and effect forms are written independently (docs/foreign_drives.md). Every
value below is copied from SPEC section 3 ("paper" = the paper's value as SPEC quotes it; "SPEC" = a
project decision that SPEC states); none is read from ``config/plant.yaml``.
"""
from __future__ import annotations

import math

# --- induction motor, per unit, stationary alpha-beta frame in SPEC (this package uses the synchronous frame)
STATOR_RESISTANCE_PU = 0.059        # paper: r_s
ROTOR_RESISTANCE_PU = 0.048         # paper: r_r
STATOR_REACTANCE_PU = 1.92          # paper: x_s
ROTOR_REACTANCE_PU = 1.92           # paper: x_r
MAGNETISING_REACTANCE_PU = 1.82     # paper: x_m  (w = x_s*x_r - x_m^2 = 0.374)
MECHANICAL_TIME_CONSTANT_S = 0.86   # paper: T_m
SUPPLY_VOLTAGE_PU = 1.0             # paper: 1 p.u. supply
SUPPLY_FREQUENCY_HZ = 50.0          # paper: 50 Hz
POLE_PAIRS = 2                      # SPEC: p = 2
BASE_TORQUE_NM = 20.0               # SPEC: T_b = 20 N*m

BASE_ELECTRICAL_SPEED_RAD_S = 2.0 * math.pi * SUPPLY_FREQUENCY_HZ            # Omega_b = 314.16 rad/s
BASE_MECHANICAL_SPEED_RAD_S = BASE_ELECTRICAL_SPEED_RAD_S / POLE_PAIRS       # Omega_mb = 157.08 rad/s
MOTOR_INERTIA_KGM2 = MECHANICAL_TIME_CONSTANT_S * BASE_TORQUE_NM / BASE_MECHANICAL_SPEED_RAD_S  # J1 = 0.1095

# --- backlash clutch (SPEC)
CONTACT_STIFFNESS_NM_PER_RAD = 3000.0   # SPEC: k_c, elastic-jaw coupling (~33 Hz torsional mode)
CONTACT_DAMPING_NMS_PER_RAD = 20.0      # SPEC: d_c, damping ratio ~0.7

# --- working machine (paper values and SPEC decisions)
MASS_KG = 10.0                       # paper: m
SPRING_STIFFNESS_N_PER_M = 100.0     # paper: k
WHEEL_RADIUS_M = 0.15                # paper: r
WHEEL_INERTIA_KGM2 = 0.2             # SPEC: J2
ABSORBER_AREA_M2 = 0.00311565        # paper: S1
ABSORBER_GAP_M = 1.0e-6              # SPEC: effective gap h in c = eta_k*S1/h^n1
WORKING_RESISTANCE_N = 30.0          # SPEC: F0 on the mass

# --- system load: rectangular pulses on the motor's load moment (SPEC)
PULSE_AMPLITUDE_PU = 1.6             # SPEC
PULSE_DURATION_S = 0.06              # SPEC: 60 ms
PULSE_PERIOD_S = 0.25                # SPEC: every 0.25 s
PULSE_FIRST_S = 0.05                 # SPEC: first pulse 0.05 s after the settled start

# --- disturbances into the motor's load moment, p.u. (paper)
GAUSSIAN_VARIANCE_PU2 = 0.05         # paper: mean 0, variance 0.05
GAUSSIAN_HOLD_S = 2.0e-4             # paper: a new value every 2e-4 s, held
TELEGRAPH_VARIANCE_PU2 = 0.05        # paper: random-sign telegraph, amplitude sqrt(0.05)
TELEGRAPH_HOLD_S = 2.0e-3            # paper: a new value every 2e-3 s, held

# --- sampling (paper)
SAMPLE_RATE_HZ = 50_000.0            # paper: 50 kHz
SAMPLE_PERIOD_S = 1.0 / SAMPLE_RATE_HZ
WINDOW_SAMPLES = 2048                # paper: 2048 samples after each backlash entry

# --- the nominal grid (paper: eta_k in {0.0125 .. 0.05}, n1 in {0.89 .. 0.97}, widths 2.5 .. 10 mm)
ETA_K_RANGE = (0.0125, 0.05)         # Pa*s^n
N1_RANGE = (0.89, 0.97)              # -
WIDTH_RANGE_M = (0.0025, 0.01)       # m

# --- the project's stream (msg_defs/msg/SignalChunk.msg, backlash_monitor/signals.py's names and units)
SIGNAL_UNITS = {"a1": "m/s^2", "a2": "m/s^2", "omega1": "rad/s", "omega2": "rad/s", "angle_difference": "rad"}


def absorber_coefficient(eta_k: float, n1: float) -> float:
    """c = eta_k*S1/h^n1 [N*(s/m)^n1] (SPEC section 3)."""
    return eta_k * ABSORBER_AREA_M2 / ABSORBER_GAP_M ** n1
