"""The settled start: the computed steady state of the whole plant before the first pulse.

With the clutch engaged and no pulse, everything turns at one speed and the mass follows the rim:
v = 0, F = F0 (working resistance), z = F/k, T_c = r*F, Delta = beta + T_c/k_c, and the motor runs at
the slip where the equivalent circuit gives t_e = T_c/T_b + constant load (stable branch). The
motor's flux phasors are taken at supply angle 0 (sample 0 of the stream, t = 0).
"""
from __future__ import annotations

import dataclasses

import numpy as np

from .drivetrain import (N_STATES, S_ALPHA1, S_ALPHA2, S_DELTA, S_OMEGA2, S_PRA, S_PRB, S_PSA, S_PSB, S_W1,
                         S_XDOT, S_Z)
from .motor import MotorSteadyState, steady_state_at_torque


def settled_state(beta: np.ndarray, cfg, values: dict | None = None) -> tuple[np.ndarray, MotorSteadyState]:
    """(n_scenarios, 11) start state for half-gaps ``beta`` [rad], and the motor's steady state (of the
    first scenario). ``values``: the per-scenario parameter table of a PlantSimulator (drifted spring
    stiffness, working resistance, contact stiffness, constant load, rotor resistance, supply voltage); None: the config's values."""
    e, ld = cfg.effects, cfg.load
    beta = np.asarray(beta, dtype=np.float64)
    n = beta.size
    v = values or {}

    def col(key, default):
        return np.asarray(v.get(key, np.full(n, float(default))), dtype=np.float64)

    force_N = col("working_resistance.force_N", ld.working_resistance_N) if e.working_resistance else np.zeros(n)
    k_spring = col("spring.stiffness_N_per_m", ld.spring_stiffness_N_per_m)
    k_c = col("backlash_clutch.contact_stiffness_Nm_per_rad", cfg.clutch.contact_stiffness_Nm_per_rad)
    const = col("constant_motor_load.load_pu", cfg.constant_motor_load_pu)
    r_r = col("rotor_resistance_pu", cfg.motor.r_r_pu)               # after rotor_resistance_drift
    u_s = cfg.motor.supply_voltage_pu * col("supply_voltage_scale", 1.0)   # after supply_voltage_drift
    # the motor carries the working resistance only through an engaged clutch
    clutch_torque_Nm = ld.wheel_radius_m * force_N if e.backlash_clutch else np.zeros(n)
    load_pu = clutch_torque_Nm / cfg.motor.base_torque_Nm
    if e.constant_motor_load:
        load_pu = load_pu + const
    x = np.zeros((n, N_STATES))
    cache: dict = {}
    first = None
    for i in range(n):
        key = (float(load_pu[i]), float(r_r[i]), float(u_s[i]))
        ms = cache.get(key)
        if ms is None:
            motor = (cfg.motor if key[1:] == (cfg.motor.r_r_pu, cfg.motor.supply_voltage_pu)
                     else dataclasses.replace(cfg.motor, r_r_pu=key[1], supply_voltage_pu=key[2]))
            ms = cache[key] = steady_state_at_torque(key[0], motor)
        first = first or ms
        x[i, S_PSA], x[i, S_PSB] = ms.psi_s.real, ms.psi_s.imag
        x[i, S_PRA], x[i, S_PRB] = ms.psi_r.real, ms.psi_r.imag
        x[i, S_W1] = ms.w1_pu
        omega = ms.w1_pu * cfg.motor.base_mechanical_speed_rad_s
        x[i, S_OMEGA2] = omega
        x[i, S_XDOT] = ld.wheel_radius_m * omega
    x[:, S_Z] = np.where((k_spring > 0) & bool(e.spring), force_N / np.where(k_spring > 0, k_spring, 1.0), 0.0)
    x[:, S_DELTA] = beta + clutch_torque_Nm / k_c
    x[:, S_ALPHA1] = x[:, S_DELTA]  # alpha2 = 0 at the start
    x[:, S_ALPHA2] = 0.0
    return x, first
