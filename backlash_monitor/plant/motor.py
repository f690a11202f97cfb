"""Per-unit induction motor in the stationary alpha-beta frame (SPEC section 3).

The simulated right-hand side writes these equations once, in the generated block of
:mod:`codegen` (``codegen._body``: the same text in every backend). :func:`currents` below is an
independent array form for tests and analyses (energy balance, stator current); it works on floats and
on numpy arrays alike.

    i_s = (x_r psi_s - x_m psi_r)/w,   i_r = (x_s psi_r - x_m psi_s)/w
    dpsi_s/dt = Omega_b (u_s - r_s i_s)
    dpsi_r/dt = Omega_b (-r_r i_r + w1 J psi_r),   J(a, b) = (-b, a)
    t_e = psi_sa i_sb - psi_sb i_sa
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ._numba import jitable
from scipy.optimize import brentq


@jitable
def currents(psa, psb, pra, prb, xs, xr, xm, w):
    """Stator and rotor currents (p.u.) from the flux linkages."""
    iw = 1.0 / w
    isa = (xr * psa - xm * pra) * iw
    isb = (xr * psb - xm * prb) * iw
    ira = (xs * pra - xm * psa) * iw
    irb = (xs * prb - xm * psb) * iw
    return isa, isb, ira, irb


@dataclass(frozen=True)
class MotorSteadyState:
    """Steady state of the per-unit equivalent circuit at supply angle 0 (u_s = (U, 0))."""
    slip: float
    w1_pu: float
    torque_pu: float
    stator_current_pu: float       # |I_s| (peak of the alpha/beta sinusoid = rms in p.u.)
    psi_s: complex
    psi_r: complex
    i_s: complex
    i_r: complex


def equivalent_circuit(slip: float, motor) -> MotorSteadyState:
    """Per-unit steady-state equivalent circuit at slip s (phasors rotating at Omega_b).

    (r_s + j x_s) I_s + j x_m I_r = U
    j s x_m I_s + (r_r + j s x_r) I_r = 0
    Psi_s = x_s I_s + x_m I_r,  Psi_r = x_m I_s + x_r I_r,  t_e = Im(conj(Psi_s) I_s)
    """
    U = motor.supply_voltage_pu
    A = np.array([[motor.r_s_pu + 1j * motor.x_s_pu, 1j * motor.x_m_pu],
                  [1j * slip * motor.x_m_pu, motor.r_r_pu + 1j * slip * motor.x_r_pu]])
    i_s, i_r = np.linalg.solve(A, np.array([U, 0.0 + 0j]))
    psi_s = motor.x_s_pu * i_s + motor.x_m_pu * i_r
    psi_r = motor.x_m_pu * i_s + motor.x_r_pu * i_r
    te = (np.conj(psi_s) * i_s).imag
    return MotorSteadyState(slip=slip, w1_pu=1.0 - slip, torque_pu=float(te), stator_current_pu=float(abs(i_s)),
                            psi_s=complex(psi_s), psi_r=complex(psi_r), i_s=complex(i_s), i_r=complex(i_r))


def breakdown_slip(motor) -> float:
    """Slip of maximum motoring torque (searched numerically; 4000 slips, so remembered per circuit: every
    simulator construction asks for it, the workbench ~100 times per diagnosis)."""
    return _breakdown_slip(motor.r_s_pu, motor.x_s_pu, motor.x_m_pu, motor.r_r_pu, motor.x_r_pu,
                           motor.supply_voltage_pu)


@functools.lru_cache(maxsize=64)
def _breakdown_slip(r_s_pu, x_s_pu, x_m_pu, r_r_pu, x_r_pu, supply_voltage_pu) -> float:
    motor = SimpleNamespace(r_s_pu=r_s_pu, x_s_pu=x_s_pu, x_m_pu=x_m_pu, r_r_pu=r_r_pu, x_r_pu=x_r_pu,
                            supply_voltage_pu=supply_voltage_pu)
    s = np.geomspace(1e-5, 1.0, 4000)
    te = [equivalent_circuit(x, motor).torque_pu for x in s]
    return float(s[int(np.argmax(te))])


def steady_state_at_torque(load_torque_pu: float, motor) -> MotorSteadyState:
    """Motoring steady state (stable branch, 0 <= s < s_breakdown) that delivers ``load_torque_pu``."""
    if load_torque_pu == 0.0:
        return equivalent_circuit(0.0, motor)
    s_max = breakdown_slip(motor)
    t_max = equivalent_circuit(s_max, motor).torque_pu
    if not (0.0 < load_torque_pu < t_max):
        raise ValueError(f"load torque {load_torque_pu:.4g} p.u. is outside the motor's stable motoring range "
                         f"0 < t < {t_max:.4g} p.u. (breakdown)")
    s = brentq(lambda x: equivalent_circuit(x, motor).torque_pu - load_torque_pu, 0.0, s_max, xtol=1e-15, rtol=1e-14)
    return equivalent_circuit(s, motor)


def supply_phase(sample_index, sample_rate_hz: float, frequency_hz: float):
    """Supply angle Omega_b*t [rad] at t = sample_index/fs, reduced to [0, 2*pi) exactly (see supply_voltage)."""
    k = np.asarray(sample_index, dtype=np.int64)
    if float(frequency_hz).is_integer() and float(sample_rate_hz).is_integer():
        cycles = np.mod(k * int(frequency_hz), int(sample_rate_hz)) / sample_rate_hz
    else:
        cycles = np.mod(k * (frequency_hz / sample_rate_hz), 1.0)
    return 2.0 * math.pi * cycles


def supply_voltage(sample_index, offset_samples, sample_rate_hz: float, frequency_hz: float, amplitude_pu: float):
    """u_s = U (cos Omega_b t, sin Omega_b t) at t = (sample_index + offset)/fs, phase reduced exactly.

    ``sample_index`` is an int64 array; the supply phase is computed from (k*f mod fs) so that it
    stays exact over hours of running when f and fs are whole numbers.
    """
    k = np.asarray(sample_index, dtype=np.int64)
    if float(frequency_hz).is_integer() and float(sample_rate_hz).is_integer():
        cycles = (np.mod(k * int(frequency_hz), int(sample_rate_hz)) + offset_samples * frequency_hz) / sample_rate_hz
    else:
        cycles = np.mod((k + offset_samples) * (frequency_hz / sample_rate_hz), 1.0)
    phase = 2.0 * math.pi * cycles
    return amplitude_pu * np.cos(phase), amplitude_pu * np.sin(phase)
