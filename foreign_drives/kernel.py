"""The compiled drive: state and parameter layout, the right-hand side, and its integrator (numba).

One file on purpose: numba's on-disk cache (``cache=True``) is invalidated only when the file that holds a
cached function changes; a change in a file it depends on (a layout index, an inlined right-hand side) is not
seen. Everything the compiled functions use is therefore here. The equations: :mod:`foreign_drives.physics`
and docs/foreign_drives.md.

Right-hand side
---------------
The drive's right-hand side, written from the equations of SPEC section 3 in a formulation of its own.

Not the formulation of ``backlash_monitor.plant`` (docs/foreign_drives.md "Equations"):

- motor: stator CURRENT and rotor flux as states, in the SYNCHRONOUS frame (rotating with the supply, so the
  supply is the constant U and the electrical states are constant in steady state); the speed in rad/s
  (SI mechanical balance J1*dOmega1/dt = T_b*t_e - T_shaft - T_load);
- clutch: the two shaft ANGLES are states (alpha1, alpha2; the angle difference is a derived quantity), the
  contact state is a discrete MODE (free / drive-side contact / far-side contact) switched by located events
  (below) instead of a gate on the state;
- load: the mass in ABSOLUTE coordinates (position x and speed v), the rim at y = r*alpha2; the spring
  extension z = y - x is derived;
- optional extra states: a shaft hub of its own inertia between the motor and the jaw (shaft compliance
  with a real inertia) and a wheel rim of its own inertia on a torsional spring (a second torsional mode).

All angles are in rad, speeds in rad/s, torques in N*m, forces in N; the motor's electrical states are in
per unit. Every effect form of :mod:`foreign_drives.forms` acts through the parameter vector ``P`` (all
forms are compiled into this one right-hand side; a form at its neutral value is exactly absent).

Integrator
----------
The integrator: Dormand-Prince 5(4) with step-size control, its continuous extension for the 50 kHz output,
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
    # damping per rad of penetration; an insert's preload and the penetration over which it builds up;
    # progressive-law penetration scale, 0 = off)
    "beta", "kc_drive", "kc_far", "dc", "contact_exponent", "contact_ref_rad", "hc_lambda", "contact_preload",
    "contact_preload_scale", "progressive_p0",
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
    # the pulse train's timing on the 0.2 ms segment grid (first, period, duration, in segments), and the held
    # pulse indicator and the start time of the current pulse [s] (set per segment by run_segments)
    "pulse_first_seg", "pulse_period_seg", "pulse_duration_seg", "pulse_on", "pulse_start_s",
    # OUTSIDE terms (forms outside the catalogue, foreign_drives.outside): the number of active slots, then
    # OUTSIDE_SLOTS slots of OUTSIDE_STRIDE values each (see outside_terms)
    "outside_active",
) + tuple(f"x{i}_{k}" for i in range(6) for k in ("balance", "amplitude", "nonperiodic", "sel1", "shape1", "a1",
                                                    "b1", "c1", "sel2", "shape2", "a2", "b2", "c2")) + (
    # the third set of outside mechanisms (foreign_drives.outside_dev3/_sealed3):
    # - a kinematic transmission error between the drive half and the jaw (a Cardan shaft at an angle, a misaligned
    #   coupling): the jaw's angle difference is D - A*sin(n*alpha_drive + phi) [rad] (0 = off);
    # - whether the terms that are not periodic with the pulse train act (set by run_segments from its ``timevar``;
    #   the transmission error reads it where no timevar is passed: implied_mode);
    # - the whole turns the integrator took off alpha2 since the run-in began (the wheel angle unwrapped);
    # - a relay (two-point switch with hysteresis) scanned at every 0.2 ms segment: the selector it reads (XS_*, 0 =
    #   none), on when the quantity rises above ``relay_on_above``, off when it falls below ``relay_off_below``, its
    #   state (0/1)
    "te_amplitude", "te_order", "te_phase", "timevar_on", "alpha2_turns", "relay_sel", "relay_on_above",
    "relay_off_below", "relay_state",
    # the fourth set (foreign_drives.outside_dev4/_sealed4):
    # - the number of the current load pulse (0 = the first pulse at or after sample 0; set per segment);
    # - the time the current contact began [s] (set at a switch into a contact mode from the gap; XS_CONTACT_AGE);
    # - a clock the wheel's unwrapped angle is compared with: its rate [rad/s] and its start [s] (XS_ALPHA2_MINUS_CLOCK);
    # - one MEMORY element per recording, advanced once per 0.2 ms segment from the state at the segment's start (see
    #   memory_scan): its kind (MK_*), the selector it reads, three parameters, whether it has been initialised, its
    #   output (XS_MEMORY), the input at the previous scan, a time, a counter, and a ring of MEMORY_RING values
    "pulse_count", "contact_t0", "clock_rate", "clock_t0", "mem_kind", "mem_sel", "mem_a", "mem_b", "mem_c",
    "mem_init", "mem_state", "mem_prev", "mem_t0", "mem_n",
    # - a Maxwell branch in the jaw's contact law (a viscoelastic insert): its stiffness [N*m/rad]; it adds
    #   k_m*(p - q) to the law, q the memory element's output (the relaxed penetration); 0 = off
    "maxwell_stiffness") + tuple(f"mem_r{i}" for i in range(64))
N_PARAMS = len(PARAM_NAMES)
PI = {name: i for i, name in enumerate(PARAM_NAMES)}
(P_RS, P_RR, P_XS, P_XR, P_XM, P_U, P_OMB, P_OMMB, P_TB, P_J1,
 P_BETA, P_KCD, P_KCF, P_DC, P_CEXP, P_CREF, P_HCL, P_CPRE, P_CPRS, P_PROG,
 P_KS, P_DS, P_JH,
 P_J2, P_KW, P_DW, P_JR,
 P_R, P_M, P_K, P_Z0, P_C, P_N1, P_F0,
 P_WFT, P_WFTW, P_WFL, P_WFDC, P_WFDP, P_WSC, P_WSE, P_WSW, P_WSD, P_WCT,
 P_MFT, P_MFTW, P_MFV, P_MFAN, P_MFANW, P_MCT,
 P_RAILF, P_RAILV, P_MDC, P_MCF,
 P_RN0, P_RA0, P_RP0, P_RN1, P_RA1, P_RP1, P_RN2, P_RA2, P_RP2, P_RN3, P_RA3, P_RP3,
 P_EME, P_EMN, P_EMP, P_GMA, P_GMN, P_GMP,
 P_VIBA, P_VIBF, P_VIBP,
 P_PFIRST, P_PPER, P_PDUR, P_PON, P_PT0, P_XN) = range(PARAM_NAMES.index("x0_balance"))
OUTSIDE_SLOTS = 6
OUTSIDE_STRIDE = 13
P_X0 = PARAM_NAMES.index("x0_balance")
# offsets within a slot
(X_BAL, X_AMP, X_NP, X_S1, X_F1, X_A1, X_B1, X_C1, X_S2, X_F2, X_A2, X_B2, X_C2) = range(OUTSIDE_STRIDE)
# balances of an outside slot: the balance its term is added to
XB_OFF, XB_MOTOR_LOAD, XB_WHEEL, XB_CLUTCH, XB_MASS = range(5)
(P_TEA, P_TEN, P_TEP, P_TV, P_A2TURNS, P_RLYSEL, P_RLYON, P_RLYOFF, P_RLYSTATE) = (
    PI[k] for k in ("te_amplitude", "te_order", "te_phase", "timevar_on", "alpha2_turns", "relay_sel",
                    "relay_on_above", "relay_off_below", "relay_state"))
(P_PCOUNT, P_CT0, P_CLKRATE, P_CLKT0, P_MEMKIND, P_MEMSEL, P_MEMA, P_MEMB, P_MEMC, P_MEMINIT, P_MEMSTATE, P_MEMPREV,
 P_MEMT0, P_MEMN, P_MAXK, P_MEMR0) = (PI[k] for k in ("pulse_count", "contact_t0", "clock_rate", "clock_t0", "mem_kind",
                                                     "mem_sel", "mem_a", "mem_b", "mem_c", "mem_init", "mem_state",
                                                     "mem_prev", "mem_t0", "mem_n", "maxwell_stiffness", "mem_r0"))
MEMORY_RING = 64
# memory kinds: a lag with a rise and a fall time constant (c = 1: falling towards 0 instead of towards the input); a
# sampled delay line (a = scan in segments, b = delay in scans); a one-shot (a = threshold the input rises through,
# b = hold time [s]); a schedule (on for b seconds from each of the mem_n times in the ring)
MK_OFF, MK_LAG, MK_DELAY, MK_ONESHOT, MK_SCHEDULE = range(5)
# the fifth set (foreign_drives.outside_dev5/_sealed5): a play (a backlash operator: m follows x once x is more than a
# away from it); a sample taken at each load pulse's start (held until the next); a resonator driven by the input's
# rate (a tuned absorber: a = its angular frequency [rad/s], b = its damping ratio; its relative displacement and
# speed in the ring's first two places; output w^2*d + 2*zeta*w*d')
MK_PLAY, MK_STROKE_SAMPLE, MK_RESONATOR = 5, 6, 7
# the sixth set (foreign_drives.outside_dev6/_sealed6), see _memory_scan6: a hidden inertia on a slip hub (stick-slip);
# a hidden body in a gap driven by its carrier's speed (a rattle, or with the ring's one-sided flag a slack chain); a PI
# controller with a saturated output and clamping anti-windup; a Dahl friction element; a rate limiter; an accumulator's
# pressure with an unloader; a PWM actuator whose duty is sampled at each carrier period's start. Their extra parameters
# sit in the ring from MEM_EXTRA on (set by the form), their states in the ring's first places.
MK_SLIP_HUB, MK_RATTLE, MK_PI_SAT, MK_DAHL, MK_RATE_LIMIT, MK_UNLOADER, MK_PWM = 8, 9, 10, 11, 12, 13, 14
MEM_EXTRA = 8
# the seventh set (foreign_drives.outside_dev7/_sealed7), see _memory_scan7: a latch set by a threshold and reset at each
# load pulse's start; an on-delay timer (a debounced switch); the integral of the input since each load pulse's start;
# a thermal integrator heated by the input's square; a peak detector with a decay
MK_LATCH, MK_ON_DELAY, MK_SINCE_STROKE, MK_HEAT, MK_PEAK = 15, 16, 17, 18, 19
# the eighth set (foreign_drives.outside_dev8/_sealed8), see _memory_scan8: a once-per-turn period tachometer (2*pi over
# the time between the two latest passes of an index mark); a run-to-run controller (updated at each load pulse's start
# from the input's mean over the scans since the last); a tank filled by the input and draining through an orifice
# (sqrt law); a van der Pol oscillator whose negative damping the input sets; a three-point step controller (a stepping
# integrator with a dead band)
MK_PERIOD_TACHO, MK_RUN_TO_RUN, MK_TANK, MK_SQUEAL, MK_STEP = 20, 21, 22, 23, 24
# the tenth set (foreign_drives.outside_dev10/_sealed10), see _memory_scan10: a thermal cut-out (a heat integrator of
# the input's square behind a hysteresis switch it drives itself); an impulse (latching) relay toggled each time the
# input rises past a threshold (re-armed below a lower one); a moving average over the last a scans (a boxcar); a
# sample of the input taken at each contact from the gap (the scan after it began), held
MK_THERMOSTAT, MK_TOGGLE, MK_MOVING_MEAN, MK_IMPACT_SAMPLE = 25, 26, 27, 28
# the eleventh set (foreign_drives.outside_dev11/_sealed11), see _memory_scan11: a hidden rotor behind a magnetic
# (pole-slipping, sinusoidal) coupling; an off-delay timer (on while the input is above a threshold and for a set time
# after); a fill level ramping up while the input is on and down while it is off, clamped to [0, 1]; the state (the
# contact's age) of a rate-and-state friction law
MK_MAG_COUPLING, MK_OFF_DELAY, MK_FILL, MK_RATE_STATE = 29, 30, 31, 32
# the fifteenth set (foreign_drives.outside_dev15), see _memory_scan15: a running maximum of the input reset at each load
# pulse's start (a peak held since the stroke began)
MK_STROKE_PEAK = 33
# selectors: the drive quantity a factor reads
(XS_ONE, XS_OMEGA1, XS_OMEGA2, XS_RIM_SPEED, XS_MASS_SPEED, XS_PENETRATION, XS_SPRING_EXTENSION, XS_ALPHA1,
 XS_ALPHA2, XS_PULSE, XS_TIME, XS_PULSE_AGE, XS_JAW_SPEED, XS_MOTOR_RIM_MINUS_MASS, XS_MODE, XS_CONTACT_TORQUE,
 XS_SIGN_OMEGA2, XS_JAW_ANGLE, XS_PULSE_PHASE, XS_GAP_DISTANCE, XS_ALPHA2_UNWRAPPED, XS_RELAY, XS_PULSE_COUNT,
 XS_CONTACT_AGE, XS_SIGNED_PENETRATION, XS_MEMORY, XS_MEMORY_EXCESS, XS_ALPHA2_MINUS_CLOCK, XS_PENETRATION_DEPTH) = (
    range(29))
# the fifth set: the carriage's position unwrapped from the run-in's start [m]; the power the contact dissipates
# |T_c*D'| [W] (the contact law's torque at the state, 0 free)
XS_MASS_POSITION, XS_CONTACT_POWER = 29, 30
# the ninth set: the jaw's angle difference beyond the gap, sign(D)*max(0, |D| - beta), whatever the contact mode (a
# term on it stays continuous where the contact law stops pushing)
XS_JAW_OVERLAP = 31
# shapes of a factor f(x; a, b, c)
(XF_ONE, XF_X, XF_POWER, XF_SIN, XF_SIN_POSITIVE, XF_EXCESS_POWER, XF_RAMP, XF_TANH, XF_RISE, XF_COS,
 XF_RISE_AFTER, XF_ABS, XF_SIGMOID, XF_DECAY_AFTER, XF_CUSHION, XF_PERIODIC_GATE, XF_CLIP) = range(17)
XF_STAIRS = 17                   # the fifth set: a*floor((x - b)/a) above b, else 0 (whole steps of a, a quantiser)
# the sixth set: a pseudo-random number in [-1, 1) from the whole number floor(x) and a seed a (exact integer
# arithmetic); the excess beyond +-a (a dead zone: sign(x)*max(0, |x| - a)); (x - b) mod a (a count's residue)
XF_HASH, XF_DEADZONE, XF_MOD = 18, 19, 20
# the seventh set: the pull of two faces at +-b on a body at x across the gap between them, (a/(b - x + a))^c -
# (a/(b + x + a))^c for |x| < b, else 0 (an inverse power of the distance to each face); a chirp switched on at x = c,
# sin(2*pi*(a*(x - c) + b*(x - c)^2/2)) for x >= c, else 0 (a frequency a + b*(x - c))
XF_FACE_PULL, XF_CHIRP = 21, 22
# the eighth set: a resonance peak 1/(1 + ((x - b)/a)^2) (a Lorentzian of half-width a at x = b)
XF_LORENTZ = 23
# the tenth set: a pseudo-random number in [-1, 1) from the whole number floor((x - c)/b) and a seed a (XF_HASH's
# arithmetic on steps of b from c); a decay exp(-((x - b) mod a)/c) restarting every a from b (a train of decays)
XF_HASH_STEP, XF_PERIODIC_DECAY = 24, 25
# the eleventh set: a logarithm ln(x/a) (0 for x <= 0); a polytropic gas law (1/(1 - q))^b - 1, q = x/a taken at most
# 0.9 (an air column of length a squeezed by x, its exponent b)
XF_LOG, XF_POLYTROPIC = 26, 27


@njit(cache=True, inline="always")
def contact_torque(pen, pen_rate, k, P):
    """Torque [N*m] the jaw contact law gives at penetration ``pen`` [rad] (>= 0 where it acts) and
    penetration rate ``pen_rate`` [rad/s]:
    T_pre*(1 - exp(-p/p_s)) + k*p_ref*(p/p_ref)^n*(1 + (p/p0)^2) + k_m*(p - q) + (d + lambda*p)*p' (k_m*(p - q): a
    Maxwell branch, q the memory element's relaxed penetration, only with the non-periodic terms on).
    The nominal law (n = 1, T_pre = 0, p0 = 0, lambda = 0) is k*p + d*p' (SPEC)."""
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
    if P[P_CPRE] != 0.0:
        el += P[P_CPRE] * (1.0 - math.exp(-pp / P[P_CPRS]))
    if P[P_MAXK] != 0.0 and P[P_TV] != 0.0:      # a Maxwell branch, q its relaxed penetration (memory element)
        el += P[P_MAXK] * (pp - P[P_MEMSTATE])
    return el + (P[P_DC] + P[P_HCL] * pp) * pen_rate


@njit(cache=True, inline="always")
def clutch_angles(y, P):
    """(angle difference across the jaw [rad], its rate [rad/s]): drive half = hub if there is a shaft, else the
    motor; less a kinematic transmission error A*sin(n*alpha_drive + phi) between the drive half and the jaw when
    one is set and the non-periodic terms act (P_TV)."""
    if P[P_KS] > 0.0:
        d, dd, ad, wd = y[S_AH] - y[S_A2], y[S_WH] - y[S_W2], y[S_AH], y[S_WH]
    else:
        d, dd, ad, wd = y[S_A1] - y[S_A2], y[S_W1] - y[S_W2], y[S_A1], y[S_W1]
    if P[P_TEA] != 0.0 and P[P_TV] != 0.0:
        arg = P[P_TEN] * ad + P[P_TEP]
        d -= P[P_TEA] * math.sin(arg)
        dd -= P[P_TEA] * P[P_TEN] * wd * math.cos(arg)
    return d, dd


@njit(cache=True, inline="always")
def transmission_ratio(y, P):
    """d(jaw angle)/d(drive half angle) with a transmission error (1 without): the jaw's torque reaches the drive
    half multiplied by it (virtual work)."""
    if P[P_TEA] != 0.0 and P[P_TV] != 0.0:
        ad = y[S_AH] if P[P_KS] > 0.0 else y[S_A1]
        return 1.0 + P[P_TEA] * P[P_TEN] * math.cos(P[P_TEN] * ad + P[P_TEP])
    return 1.0


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
def _quantity(sel, t, y, P, mode, pen, tcc):
    """The drive quantity an outside factor reads (XS_*), SI units."""
    r = P[P_R]
    if sel == XS_ONE:
        return 1.0
    if sel == XS_OMEGA1:
        return y[S_W1]
    if sel == XS_OMEGA2:
        return y[S_W2]
    if sel == XS_RIM_SPEED:
        return r * (y[S_WR] if P[P_KW] > 0.0 else y[S_W2])
    if sel == XS_MASS_SPEED:
        return y[S_V]
    if sel == XS_PENETRATION:
        return pen
    if sel == XS_SPRING_EXTENSION:
        return r * (y[S_AR] if P[P_KW] > 0.0 else y[S_A2]) - y[S_X]
    if sel == XS_ALPHA1:
        return y[S_A1]
    if sel == XS_ALPHA2:
        return y[S_A2]
    if sel == XS_PULSE:
        return P[P_PON]
    if sel == XS_TIME:
        return t
    if sel == XS_PULSE_AGE:
        return t - P[P_PT0] if P[P_PON] > 0.0 else -1.0
    if sel == XS_JAW_SPEED:
        return (y[S_WH] if P[P_KS] > 0.0 else y[S_W1]) - y[S_W2]
    if sel == XS_MOTOR_RIM_MINUS_MASS:
        return r * y[S_W1] - y[S_V]
    if sel == XS_MODE:
        return float(mode)
    if sel == XS_CONTACT_TORQUE:
        return tcc
    if sel == XS_SIGN_OMEGA2:
        return _sgn(y[S_W2])
    if sel == XS_JAW_ANGLE:
        return (y[S_AH] if P[P_KS] > 0.0 else y[S_A1]) - y[S_A2]
    if sel == XS_PULSE_PHASE:                    # time since the latest pulse began, on or off [s]
        return t - P[P_PT0]
    if sel == XS_GAP_DISTANCE:                   # while free: the distance to the nearer jaw face [rad]; -1 in contact
        return P[P_BETA] - abs(clutch_angles(y, P)[0]) if mode == 0 else -1.0
    if sel == XS_ALPHA2_UNWRAPPED:               # alpha2 with the whole turns taken off since the run-in began
        return y[S_A2] + 2.0 * math.pi * P[P_A2TURNS]
    if sel == XS_RELAY:
        return P[P_RLYSTATE]
    if sel == XS_PULSE_COUNT:                    # the current load pulse's number (0: the first at or after sample 0)
        return P[P_PCOUNT]
    if sel == XS_CONTACT_AGE:                    # in contact: the time since it began from the gap [s]; -1 in the gap
        return t - P[P_CT0] if mode != 0 else -1.0
    if sel == XS_SIGNED_PENETRATION:             # the penetration, + on the drive side, - on the far side; 0 free [rad]
        return clutch_angles(y, P)[0] - P[P_BETA] * mode if mode != 0 else 0.0
    if sel == XS_PENETRATION_DEPTH:              # in contact, the penetration on either side [rad] (>= 0); 0 free
        return abs(clutch_angles(y, P)[0]) - P[P_BETA] if mode != 0 else 0.0
    if sel == XS_MEMORY:                         # the memory element's output (memory_scan)
        return P[P_MEMSTATE]
    if sel == XS_ALPHA2_MINUS_CLOCK:             # the unwrapped wheel angle less a clock's angle [rad]
        return y[S_A2] + 2.0 * math.pi * P[P_A2TURNS] - P[P_CLKRATE] * (t - P[P_CLKT0])
    if sel == XS_MASS_POSITION:                  # the mass position with the integrator's whole turns put back [m]
        return y[S_X] + r * 2.0 * math.pi * P[P_A2TURNS]
    if sel == XS_CONTACT_POWER:                  # |T_c * D'| of the contact law at this state [W]; 0 free
        if mode == 0:
            return 0.0
        d, dd = clutch_angles(y, P)
        if mode > 0:
            tq = contact_torque(d - P[P_BETA], dd, P[P_KCD], P)
        else:
            tq = contact_torque(-d - P[P_BETA], -dd, P[P_KCF], P)
        return abs(tq * dd)
    if sel == XS_JAW_OVERLAP:                    # the jaw faces' geometric overlap, + drive side, pushing or not [rad]
        d = clutch_angles(y, P)[0]
        e = abs(d) - P[P_BETA]
        return (e if d > 0.0 else -e) if e > 0.0 else 0.0
    return 0.0


@njit(cache=True)
def _selected(sel, t, y, P, mode, pen, tcc):
    """The drive quantity an outside factor reads (XS_*), SI units; XS_MEMORY_EXCESS: the memory element's input now
    less its output."""
    if sel == XS_MEMORY_EXCESS:
        return _quantity(int(P[P_MEMSEL]), t, y, P, mode, pen, tcc) - P[P_MEMSTATE]
    return _quantity(sel, t, y, P, mode, pen, tcc)


@njit(cache=True)
def _memory_scan5(kind, x, P, seg_dt):
    """The fifth set's memory kinds, one 0.2 ms scan with the input ``x``:
    - MK_PLAY: m -> min(max(m, x - a), x + a) (first scan: m = x);
    - MK_STROKE_SAMPLE: m = x at the first scan of each load pulse (the pulse count changed), held (first scan: m = x);
    - MK_RESONATOR: d'' = -w^2*d - 2*zeta*w*d' - x', x' = the input's change over the last scan / seg_dt (w = a,
      zeta = b; four semi-implicit Euler steps per scan); m = w^2*d + 2*zeta*w*d' (first scan: at rest, d = d' = 0)."""
    a, b = P[P_MEMA], P[P_MEMB]
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMSTATE] = 0.0 if kind == MK_RESONATOR else x
        P[P_MEMPREV] = P[P_PCOUNT] if kind == MK_STROKE_SAMPLE else x
        P[P_MEMR0] = 0.0
        P[P_MEMR0 + 1] = 0.0
        return
    if kind == MK_PLAY:
        m = P[P_MEMSTATE]
        if m < x - a:
            m = x - a
        elif m > x + a:
            m = x + a
        P[P_MEMSTATE] = m
    elif kind == MK_STROKE_SAMPLE:
        if P[P_PCOUNT] != P[P_MEMPREV]:
            P[P_MEMSTATE] = x
            P[P_MEMPREV] = P[P_PCOUNT]
    elif kind == MK_RESONATOR:
        acc = (x - P[P_MEMPREV]) / seg_dt
        P[P_MEMPREV] = x
        d, dd = P[P_MEMR0], P[P_MEMR0 + 1]
        h = 0.25 * seg_dt
        for _ in range(4):
            dd += h * (-a * a * d - 2.0 * b * a * dd - acc)
            d += h * dd
        P[P_MEMR0], P[P_MEMR0 + 1] = d, dd
        P[P_MEMSTATE] = a * a * d + 2.0 * b * a * dd


@njit(cache=True)
def _rattle_scan(x, P, seg_dt):
    """MK_RATTLE: a hidden body in a gap +-a (input units: rad or m) on a carrier whose speed is ``x``: its displacement
    d and speed d' relative to the carrier in the ring's first two places; contact (|d| > a; one-sided flag in the ring:
    only d < -a) with angular frequency b and damping ratio ring[MEM_EXTRA], never pulling; a drag -c*(x + d') on its
    absolute speed; the carrier's acceleration = its speed's change over the last scan. Eight semi-implicit Euler steps
    per scan; the output: minus the mean contact acceleration over the scan (the reaction on the carrier per unit of the
    body's mass or inertia)."""
    g, w, lam = P[P_MEMA], P[P_MEMB], P[P_MEMC]
    zeta, one_sided = P[P_MEMR0 + MEM_EXTRA], P[P_MEMR0 + MEM_EXTRA + 1]
    acc = (x - P[P_MEMPREV]) / seg_dt
    P[P_MEMPREV] = x
    d, dd = P[P_MEMR0], P[P_MEMR0 + 1]
    h = 0.125 * seg_dt
    tot = 0.0
    for _ in range(8):
        ca = 0.0
        if d < -g:
            ca = -w * w * (d + g) - 2.0 * zeta * w * dd
            if ca < 0.0:
                ca = 0.0
        elif d > g and one_sided == 0.0:
            ca = -w * w * (d - g) - 2.0 * zeta * w * dd
            if ca > 0.0:
                ca = 0.0
        dd += h * (ca - lam * (x + dd) - acc)
        d += h * dd
        tot += ca
    P[P_MEMR0], P[P_MEMR0 + 1] = d, dd
    P[P_MEMSTATE] = -tot / 8.0


@njit(cache=True)
def _memory_scan6(kind, x, P, seg_dt):
    """The sixth set's memory kinds, one 0.2 ms scan with the input ``x`` (first scan: initialised, output below):
    - MK_SLIP_HUB: a hidden inertia a on a slip hub of slip torque b: the torque to bring it to x over the scan,
      a*(x - w_f)/dt, passed whole while within +-b (w_f = x), else +-b (w_f moves by +-b/a*dt); output: that torque
      (first scan: w_f = x, 0);
    - MK_RATTLE: _rattle_scan (first scan: at rest on the driving flank, d = -a - c*x/b^2, d' = 0);
    - MK_PI_SAT: u = K_p*e + I limited to [0, c], e = x - ring[MEM_EXTRA], K_p = a; I += b*e*dt unless u is at a limit
      and e pushes it further; output u (first scan: I = 0);
    - MK_DAHL: s -> sign(dx) - (sign(dx) - s)*exp(-|dx|/a) for the input's change dx since the last scan (first: s = 0);
    - MK_RATE_LIMIT: m moves towards x by at most a*dt (first scan: m = x);
    - MK_UNLOADER: p += (on*a*x - b*pulse)*dt (p >= 0); on -> 0 above c, -> 1 below ring[MEM_EXTRA]; output on*p
      (first scan: p = ring[MEM_EXTRA], on);
    - MK_PWM: at every a-th scan the duty clip((x - b)/c, 0, 1) is taken; output 1 for the first round(duty*a) scans of
      the period, else 0 (first scan: the period starts)."""
    a, b, c = P[P_MEMA], P[P_MEMB], P[P_MEMC]
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMPREV] = x
        P[P_MEMSTATE] = 0.0
        P[P_MEMN] = 0.0
        P[P_MEMR0] = 0.0
        P[P_MEMR0 + 1] = 0.0
        if kind == MK_SLIP_HUB:
            P[P_MEMR0] = x
            return
        if kind == MK_RATTLE:
            P[P_MEMR0] = -a - c * x / (b * b)
            return
        if kind == MK_DAHL:
            return
        if kind == MK_RATE_LIMIT:
            P[P_MEMSTATE] = x
            return
        if kind == MK_UNLOADER:
            P[P_MEMR0] = P[P_MEMR0 + MEM_EXTRA]
            P[P_MEMR0 + 1] = 1.0
            P[P_MEMSTATE] = P[P_MEMR0]
            return
    if kind == MK_SLIP_HUB:
        need = a * (x - P[P_MEMR0]) / seg_dt
        if abs(need) <= b:
            P[P_MEMR0] = x
            P[P_MEMSTATE] = need
        else:
            tq = b if need > 0.0 else -b
            P[P_MEMR0] += tq / a * seg_dt
            P[P_MEMSTATE] = tq
    elif kind == MK_RATTLE:
        _rattle_scan(x, P, seg_dt)
    elif kind == MK_PI_SAT:
        e = x - P[P_MEMR0 + MEM_EXTRA]
        u = a * e + P[P_MEMR0]
        if not ((u >= c and e > 0.0) or (u <= 0.0 and e < 0.0)):
            P[P_MEMR0] += b * e * seg_dt
            u = a * e + P[P_MEMR0]
        P[P_MEMSTATE] = 0.0 if u < 0.0 else (c if u > c else u)
    elif kind == MK_DAHL:
        dx = x - P[P_MEMPREV]
        P[P_MEMPREV] = x
        if dx != 0.0:
            sg = 1.0 if dx > 0.0 else -1.0
            P[P_MEMSTATE] = sg - (sg - P[P_MEMSTATE]) * math.exp(-abs(dx) / a)
    elif kind == MK_RATE_LIMIT:
        step = x - P[P_MEMSTATE]
        lim = a * seg_dt
        P[P_MEMSTATE] += -lim if step < -lim else (lim if step > lim else step)
    elif kind == MK_UNLOADER:
        p = P[P_MEMR0] + (P[P_MEMR0 + 1] * a * x - b * P[P_PON]) * seg_dt
        p = p if p > 0.0 else 0.0
        if P[P_MEMR0 + 1] != 0.0 and p > c:
            P[P_MEMR0 + 1] = 0.0
        elif P[P_MEMR0 + 1] == 0.0 and p < P[P_MEMR0 + MEM_EXTRA]:
            P[P_MEMR0 + 1] = 1.0
        P[P_MEMR0] = p
        P[P_MEMSTATE] = P[P_MEMR0 + 1] * p
    elif kind == MK_PWM:
        n = int(P[P_MEMN])
        per = int(a)
        k = n % per
        if k == 0:
            q = (x - b) / c
            P[P_MEMR0] = 0.0 if q < 0.0 else (1.0 if q > 1.0 else q)
        P[P_MEMSTATE] = 1.0 if k < round(P[P_MEMR0] * per) else 0.0
        P[P_MEMN] = n + 1.0


@njit(cache=True)
def _memory_scan7(kind, x, P, seg_dt):
    """The seventh set's memory kinds, one 0.2 ms scan with the input ``x`` (the output m in mem_state):
    - MK_LATCH: at a load pulse's first scan (the pulse count changed) m -> 0; then m -> 1 if x > a (first scan: m = 0,
      set if x > a);
    - MK_ON_DELAY: n = the number of consecutive scans up to this one with x > a (0 when x <= a); m = 1 when n*dt >= b
      - 1e-12, else 0 (first scan: n counted from it);
    - MK_SINCE_STROKE: at a load pulse's first scan m -> 0, else m += x*dt (x at the scan's start; first scan: m = 0);
    - MK_HEAT: m += dt*(a*x^2 - m/b) (first scan: m = 0);
    - MK_PEAK: m -> max(x, m*exp(-dt/a)) (first scan: m = x)."""
    a, b = P[P_MEMA], P[P_MEMB]
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMPREV] = P[P_PCOUNT]
        P[P_MEMN] = 0.0
        P[P_MEMSTATE] = 0.0
        if kind == MK_LATCH:
            P[P_MEMSTATE] = 1.0 if x > a else 0.0
            return
        if kind == MK_PEAK:
            P[P_MEMSTATE] = x
            return
        if kind != MK_ON_DELAY:
            return
    if kind == MK_LATCH:
        if P[P_PCOUNT] != P[P_MEMPREV]:
            P[P_MEMPREV] = P[P_PCOUNT]
            P[P_MEMSTATE] = 0.0
        if x > a:
            P[P_MEMSTATE] = 1.0
    elif kind == MK_ON_DELAY:
        n = P[P_MEMN] + 1.0 if x > a else 0.0
        P[P_MEMN] = n
        P[P_MEMSTATE] = 1.0 if n * seg_dt >= b - 1e-12 and n > 0.0 else 0.0
    elif kind == MK_SINCE_STROKE:
        if P[P_PCOUNT] != P[P_MEMPREV]:
            P[P_MEMPREV] = P[P_PCOUNT]
            P[P_MEMSTATE] = 0.0
        else:
            P[P_MEMSTATE] += x * seg_dt
    elif kind == MK_HEAT:
        P[P_MEMSTATE] += seg_dt * (a * x * x - P[P_MEMSTATE] / b)
    elif kind == MK_PEAK:
        m = P[P_MEMSTATE] * math.exp(-seg_dt / a)
        P[P_MEMSTATE] = x if x > m else m


@njit(cache=True)
def _memory_scan8(kind, t, x, P, seg_dt):
    """The eighth set's memory kinds, one 0.2 ms scan at ``t`` with the input ``x`` (the output m in mem_state):
    - MK_PERIOD_TACHO: x an unwrapped angle, k = floor((x - a)/(2*pi)) the index mark's passes; at a scan where k
      changed, m -> 2*pi/(t - t_last) if there was an earlier pass (its time t_last in ring[0], ring[1] = 1), then
      t_last = t (first scan: m = 0, no pass yet);
    - MK_RUN_TO_RUN: at a load pulse's first scan (the pulse count changed), if scans were summed since the last,
      m -> clip(m - a*(mean - b), -c, c); then the sum restarts; every scan adds x to the sum (ring[0]) and counts
      (ring[1]) (first scan: m = 0, summed from it);
    - MK_TANK: m -> max(0, m + dt*(a*x - b*sqrt(m))) (first scan: m = 0);
    - MK_SQUEAL: a van der Pol oscillator X'' = w*g*(x - c)*(1 - X^2)*X' - w^2*X (w = a, g = b; X, X' in ring[0:2];
      eight semi-implicit Euler steps per scan); when X^2 + (X'/w)^2 < 1e-6 the state is scaled up to that amplitude
      (a floor); m = X (first scan: X = 1e-3, X' = 0);
    - MK_STEP: d = +1 if x > a + b, -1 if x < a - b, else 0; n = the consecutive scans with the same d != 0 since the
      last step (ring[0]; its d in ring[1]); when n*dt >= c - 1e-12, m -> clip(m + d, 0, ring[MEM_EXTRA]) and n = 0
      (first scan: m = 0, counted from it)."""
    a, b, c = P[P_MEMA], P[P_MEMB], P[P_MEMC]
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMPREV] = P[P_PCOUNT]
        P[P_MEMSTATE] = 0.0
        P[P_MEMR0] = 0.0
        P[P_MEMR0 + 1] = 0.0
        if kind == MK_PERIOD_TACHO:
            P[P_MEMPREV] = math.floor((x - a) / (2.0 * math.pi))
            return
        if kind == MK_TANK:
            return
        if kind == MK_SQUEAL:
            P[P_MEMR0] = 1e-3
            P[P_MEMSTATE] = 1e-3
            return
    if kind == MK_PERIOD_TACHO:
        k = math.floor((x - a) / (2.0 * math.pi))
        if k != P[P_MEMPREV]:
            P[P_MEMPREV] = k
            if P[P_MEMR0 + 1] != 0.0 and t > P[P_MEMR0]:
                P[P_MEMSTATE] = 2.0 * math.pi / (t - P[P_MEMR0])
            P[P_MEMR0] = t
            P[P_MEMR0 + 1] = 1.0
    elif kind == MK_RUN_TO_RUN:
        if P[P_PCOUNT] != P[P_MEMPREV]:
            P[P_MEMPREV] = P[P_PCOUNT]
            if P[P_MEMR0 + 1] > 0.0:
                m = P[P_MEMSTATE] - a * (P[P_MEMR0] / P[P_MEMR0 + 1] - b)
                P[P_MEMSTATE] = -c if m < -c else (c if m > c else m)
            P[P_MEMR0] = 0.0
            P[P_MEMR0 + 1] = 0.0
        P[P_MEMR0] += x
        P[P_MEMR0 + 1] += 1.0
    elif kind == MK_TANK:
        v = P[P_MEMSTATE]
        v += seg_dt * (a * x - b * math.sqrt(v if v > 0.0 else 0.0))
        P[P_MEMSTATE] = v if v > 0.0 else 0.0
    elif kind == MK_SQUEAL:
        mu = a * b * (x - c)
        q, dq = P[P_MEMR0], P[P_MEMR0 + 1]
        h = 0.125 * seg_dt
        for _ in range(8):
            dq += h * (mu * (1.0 - q * q) * dq - a * a * q)
            q += h * dq
        amp2 = q * q + (dq / a) ** 2
        if amp2 < 1e-6:
            if amp2 > 0.0:
                s = 1e-3 / math.sqrt(amp2)
                q, dq = q * s, dq * s
            else:
                q = 1e-3
        P[P_MEMR0], P[P_MEMR0 + 1] = q, dq
        P[P_MEMSTATE] = q
    elif kind == MK_STEP:
        d = 1.0 if x > a + b else (-1.0 if x < a - b else 0.0)
        if d == 0.0:
            n = 0.0
        elif d == P[P_MEMR0 + 1]:
            n = P[P_MEMR0] + 1.0
        else:
            n = 1.0
        P[P_MEMR0 + 1] = d
        if d != 0.0 and n * seg_dt >= c - 1e-12:
            m = P[P_MEMSTATE] + d
            top = P[P_MEMR0 + MEM_EXTRA]
            P[P_MEMSTATE] = 0.0 if m < 0.0 else (top if m > top else m)
            n = 0.0
        P[P_MEMR0] = n


@njit(cache=True)
def _memory_scan10(kind, x, P, seg_dt):
    """The tenth set's memory kinds, one 0.2 ms scan with the input ``x`` (the output m in mem_state):
    - MK_THERMOSTAT: heat h (ring[0]) += dt*(m*a*x^2 - h/b); m -> 0 when h > c, -> 1 when h < ring[MEM_EXTRA] (first
      scan: h = 0, m = 1);
    - MK_TOGGLE: armed (ring[0]) and x > a: m -> 1 - m, disarmed; disarmed and x < b: armed (first scan: m = 0, armed
      when x < b);
    - MK_MOVING_MEAN: the ring's place n mod a takes x (n the scan's number), m = the mean of the ring's first a places
      (a <= MEMORY_RING; first scan: all a places = x, m = x);
    - MK_IMPACT_SAMPLE: m -> x at a scan where the contact's start time (contact_t0) changed since the last (first
      scan: m = x)."""
    a, b, c = P[P_MEMA], P[P_MEMB], P[P_MEMC]
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMN] = 0.0
        P[P_MEMPREV] = P[P_CT0]
        P[P_MEMSTATE] = x
        if kind == MK_THERMOSTAT:
            P[P_MEMR0] = 0.0
            P[P_MEMSTATE] = 1.0
        elif kind == MK_TOGGLE:
            P[P_MEMR0] = 1.0 if x < b else 0.0
            P[P_MEMSTATE] = 0.0
        elif kind == MK_MOVING_MEAN:
            for i in range(int(a)):
                P[P_MEMR0 + i] = x
            P[P_MEMN] = 1.0
        return
    if kind == MK_THERMOSTAT:
        h = P[P_MEMR0] + seg_dt * (P[P_MEMSTATE] * a * x * x - P[P_MEMR0] / b)
        P[P_MEMR0] = h
        if P[P_MEMSTATE] != 0.0 and h > c:
            P[P_MEMSTATE] = 0.0
        elif P[P_MEMSTATE] == 0.0 and h < P[P_MEMR0 + MEM_EXTRA]:
            P[P_MEMSTATE] = 1.0
    elif kind == MK_TOGGLE:
        if P[P_MEMR0] != 0.0 and x > a:
            P[P_MEMSTATE] = 1.0 - P[P_MEMSTATE]
            P[P_MEMR0] = 0.0
        elif P[P_MEMR0] == 0.0 and x < b:
            P[P_MEMR0] = 1.0
    elif kind == MK_MOVING_MEAN:
        na = int(a)
        n = int(P[P_MEMN])
        P[P_MEMR0 + n % na] = x
        P[P_MEMN] = n + 1.0
        tot = 0.0
        for i in range(na):
            tot += P[P_MEMR0 + i]
        P[P_MEMSTATE] = tot / na
    elif kind == MK_IMPACT_SAMPLE:
        if P[P_CT0] != P[P_MEMPREV]:
            P[P_MEMPREV] = P[P_CT0]
            P[P_MEMSTATE] = x


@njit(cache=True)
def _memory_scan11(kind, t, x, P, seg_dt):
    """The eleventh set's memory kinds, one 0.2 ms scan at ``t`` with the input ``x`` (the output m in mem_state):
    - MK_MAG_COUPLING: a hidden rotor behind a magnetic coupling of pull-out torque a and b pole pairs, inertia c, viscous
      load ring[MEM_EXTRA]: its speed w (ring[1]) += dt*(a*sin(b*phi) - ring[MEM_EXTRA]*w)/c, then the angle phi of the
      input's shaft ahead of it (ring[0]) += dt*(x - w); m = a*sin(b*phi) (first scan: w = x, b*phi = asin(ring[MEM_EXTRA]
      *x/a), 0 when a = 0);
    - MK_OFF_DELAY: m -> 1 at a scan with x > a (its time kept), -> 0 once b seconds have passed since the last such scan
      (first scan: m = 1 if x > a, else 0);
    - MK_FILL: m += dt/a while x > 0.5, m -= dt/b otherwise, clamped to [0, 1] (first scan: m = 0);
    - MK_RATE_STATE: m -> a/x + (m - a/x)*exp(-x*dt/a) (theta' = 1 - x*theta/a over the scan at the input x > 0; m +=
      dt where x <= 0) (first scan: m = a/x)."""
    a, b, c = P[P_MEMA], P[P_MEMB], P[P_MEMC]
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMN] = 0.0
        P[P_MEMT0] = t
        if kind == MK_MAG_COUPLING:
            q = P[P_MEMR0 + MEM_EXTRA] * x / a if a > 0.0 else 0.0
            q = -1.0 if q < -1.0 else (1.0 if q > 1.0 else q)
            P[P_MEMR0] = math.asin(q) / b
            P[P_MEMR0 + 1] = x
            P[P_MEMSTATE] = a * math.sin(b * P[P_MEMR0])
        elif kind == MK_OFF_DELAY:
            P[P_MEMSTATE] = 1.0 if x > a else 0.0
        elif kind == MK_FILL:
            P[P_MEMSTATE] = 0.0
        else:
            P[P_MEMSTATE] = a / x if x > 0.0 else 0.0
        return
    if kind == MK_MAG_COUPLING:
        w = P[P_MEMR0 + 1]
        w += seg_dt * (a * math.sin(b * P[P_MEMR0]) - P[P_MEMR0 + MEM_EXTRA] * w) / c
        P[P_MEMR0 + 1] = w
        P[P_MEMR0] += seg_dt * (x - w)
        P[P_MEMSTATE] = a * math.sin(b * P[P_MEMR0])
    elif kind == MK_OFF_DELAY:
        if x > a:
            P[P_MEMSTATE] = 1.0
            P[P_MEMT0] = t
        elif P[P_MEMSTATE] != 0.0 and t - P[P_MEMT0] >= b - 1e-12:
            P[P_MEMSTATE] = 0.0
    elif kind == MK_FILL:
        m = P[P_MEMSTATE] + (seg_dt / a if x > 0.5 else -seg_dt / b)
        P[P_MEMSTATE] = 0.0 if m < 0.0 else (1.0 if m > 1.0 else m)
    elif kind == MK_RATE_STATE:
        if x > 0.0:
            ss = a / x
            P[P_MEMSTATE] = ss + (P[P_MEMSTATE] - ss) * math.exp(-x * seg_dt / a)
        else:
            P[P_MEMSTATE] += seg_dt


@njit(cache=True)
def _memory_scan15(kind, x, P):
    """The fifteenth set's memory kind, one 0.2 ms scan with the input ``x`` (the output m in mem_state):
    - MK_STROKE_PEAK: at a load pulse's first scan (the pulse count changed) m -> x, else m -> max(m, x) (first scan:
      m = x)."""
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMPREV] = P[P_PCOUNT]
        P[P_MEMSTATE] = x
        return
    if kind == MK_STROKE_PEAK:
        if P[P_PCOUNT] != P[P_MEMPREV]:
            P[P_MEMPREV] = P[P_PCOUNT]
            P[P_MEMSTATE] = x
        elif x > P[P_MEMSTATE]:
            P[P_MEMSTATE] = x


@njit(cache=True)
def memory_scan(t, y, P, mode, seg_dt):
    """Advance the memory element by one 0.2 ms segment from the state ``y`` at the segment's start ``t``:
    - MK_LAG: m -> x + (m - x)*exp(-dt/a) while x > m, else x + (m - x)*exp(-dt/b) (c = 1: m*exp(-dt/b));
    - MK_DELAY: every a-th segment x is sampled into the ring and m becomes the sample taken b scans before;
    - MK_ONESHOT: m -> 1 when x rises through a (from at or below a at the previous scan) while m = 0, back to 0 b
      seconds later;
    - MK_SCHEDULE: m = 1 within b seconds from any of the mem_n times in the ring, else 0.
    The first scan initialises it (m = x; the ring filled with x; the one-shot off)."""
    kind = int(P[P_MEMKIND])
    a, b = P[P_MEMA], P[P_MEMB]
    if kind == MK_SCHEDULE:
        on = 0.0
        for i in range(int(P[P_MEMN])):
            s = P[P_MEMR0 + i]
            if s - 1e-12 <= t < s + b - 1e-12:
                on = 1.0
        P[P_MEMSTATE] = on
        return
    x = _quantity(int(P[P_MEMSEL]), t, y, P, mode, 0.0, 0.0)
    if kind >= MK_STROKE_PEAK:
        _memory_scan15(kind, x, P)
        return
    if kind >= MK_MAG_COUPLING:
        _memory_scan11(kind, t, x, P, seg_dt)
        return
    if kind >= MK_THERMOSTAT:
        _memory_scan10(kind, x, P, seg_dt)
        return
    if kind >= MK_PERIOD_TACHO:
        _memory_scan8(kind, t, x, P, seg_dt)
        return
    if kind >= MK_LATCH:
        _memory_scan7(kind, x, P, seg_dt)
        return
    if kind >= MK_SLIP_HUB:
        _memory_scan6(kind, x, P, seg_dt)
        return
    if kind >= MK_PLAY:
        _memory_scan5(kind, x, P, seg_dt)
        return
    if P[P_MEMINIT] == 0.0:
        P[P_MEMINIT] = 1.0
        P[P_MEMSTATE] = 0.0 if kind == MK_ONESHOT else x
        P[P_MEMPREV] = x
        P[P_MEMN] = 0.0
        for i in range(MEMORY_RING):
            P[P_MEMR0 + i] = x
        if kind != MK_DELAY:
            return
    if kind == MK_LAG:
        m = P[P_MEMSTATE]
        if x > m:
            m = x + (m - x) * math.exp(-seg_dt / a)
        elif P[P_MEMC] == 0.0:
            m = x + (m - x) * math.exp(-seg_dt / b)
        else:
            m = m * math.exp(-seg_dt / b)
        P[P_MEMSTATE] = m
    elif kind == MK_DELAY:
        n = int(P[P_MEMN])
        scan = int(a)
        if n % scan == 0:
            k = n // scan
            P[P_MEMR0 + k % MEMORY_RING] = x
            P[P_MEMSTATE] = P[P_MEMR0 + (k - int(b)) % MEMORY_RING]
        P[P_MEMN] = n + 1.0
    elif kind == MK_ONESHOT:
        if P[P_MEMSTATE] != 0.0 and t - P[P_MEMT0] >= b - 1e-12:
            P[P_MEMSTATE] = 0.0
        if P[P_MEMSTATE] == 0.0 and P[P_MEMPREV] <= a < x:
            P[P_MEMSTATE] = 1.0
            P[P_MEMT0] = t
        P[P_MEMPREV] = x


@njit(cache=True)
def _shaped(shape, x, a, b, c):
    """A factor's shape f(x; a, b, c) (XF_*)."""
    if shape == XF_ONE:
        return 1.0
    if shape == XF_X:
        return x
    if shape == XF_POWER:
        return abs(x) ** a * _sgn(x)
    if shape == XF_SIN:
        return math.sin(a * x + b)
    if shape == XF_SIN_POSITIVE:
        s = math.sin(a * x + b)
        return s ** c if s > 0.0 else 0.0
    if shape == XF_EXCESS_POWER:
        e = x - a
        return e ** b if e > 0.0 else 0.0
    if shape == XF_RAMP:
        q = x / a
        return 0.0 if q < 0.0 else (1.0 if q > 1.0 else q)
    if shape == XF_TANH:
        return math.tanh(x / a)
    if shape == XF_RISE:
        return 1.0 - math.exp(-x / a) if x >= 0.0 else 0.0
    if shape == XF_COS:
        return math.cos(a * x + b)
    if shape == XF_RISE_AFTER:                   # a first-order rise of time constant a from x = b (0 before)
        return 1.0 - math.exp(-(x - b) / a) if x >= b else 0.0
    if shape == XF_ABS:
        return abs(x)
    if shape == XF_SIGMOID:                      # a smooth step from 0 to 1 at x = b, width a (a < 0: 1 to 0)
        return 0.5 * (1.0 + math.tanh((x - b) / a))
    if shape == XF_DECAY_AFTER:                  # a first-order decay of time constant a from x = b (0 before)
        return math.exp(-(x - b) / a) if x >= b else 0.0
    if shape == XF_CUSHION:                      # (a/(x + a))^b for x >= 0, else 0 (a film ~ 1/h^b, finite at 0)
        return (a / (x + a)) ** b if x >= 0.0 else 0.0
    if shape == XF_PERIODIC_GATE:                # 1 while (x - b) mod a < c, else 0 (a timer's window)
        q = (x - b) - a * math.floor((x - b) / a)
        return 1.0 if q < c else 0.0
    if shape == XF_CLIP:                         # x + b limited to [-a, a]
        q = x + b
        return -a if q < -a else (a if q > a else q)
    if shape == XF_STAIRS:                       # whole steps of a above b (a quantiser), 0 below b
        return a * math.floor((x - b) / a) if x > b else 0.0
    if shape == XF_HASH:                         # pseudo-random in [-1, 1) from the whole number floor(x), seed a
        k = math.floor(x)
        q = k * k * 7919.0 + k * 40503.0 + a * 104729.0
        return 2.0 * (q - 65521.0 * math.floor(q / 65521.0)) / 65521.0 - 1.0
    if shape == XF_DEADZONE:                     # the excess beyond +-a
        e = abs(x) - a
        return (e if x > 0.0 else -e) if e > 0.0 else 0.0
    if shape == XF_MOD:                          # (x - b) mod a
        q = x - b
        return q - a * math.floor(q / a)
    if shape == XF_FACE_PULL:                    # two faces at +-b pulling on x between them, ~ 1/distance^c
        if x >= b or x <= -b:
            return 0.0
        return (a / (b - x + a)) ** c - (a / (b + x + a)) ** c
    if shape == XF_CHIRP:                        # a chirp from x = c: frequency a + b*(x - c)
        if x < c:
            return 0.0
        q = x - c
        return math.sin(2.0 * math.pi * (a * q + 0.5 * b * q * q))
    if shape == XF_LORENTZ:                      # a resonance peak of half-width a at x = b
        q = (x - b) / a
        return 1.0 / (1.0 + q * q)
    if shape == XF_HASH_STEP:                    # pseudo-random in [-1, 1) from the step floor((x - c)/b), seed a
        k = math.floor((x - c) / b)
        q = k * k * 7919.0 + k * 40503.0 + a * 104729.0
        return 2.0 * (q - 65521.0 * math.floor(q / 65521.0)) / 65521.0 - 1.0
    if shape == XF_PERIODIC_DECAY:               # exp(-((x - b) mod a)/c): a decay restarting every a from b
        q = x - b
        return math.exp(-(q - a * math.floor(q / a)) / c)
    if shape == XF_LOG:                          # ln(x/a), 0 for x <= 0
        return math.log(x / a) if x > 0.0 else 0.0
    if shape == XF_POLYTROPIC:                   # (1/(1 - q))^b - 1, q = x/a at most 0.9 (an air column squeezed)
        q = x / a
        if q > 0.9:
            q = 0.9
        return (1.0 / (1.0 - q)) ** b - 1.0
    return 0.0


@njit(cache=True)
def outside_terms(t, y, P, timevar, mode, pen, tcc, out):
    """The outside slots' terms summed per balance into ``out`` = [motor load N*m, wheel N*m (+ drives the wheel),
    clutch N*m (+ motor to wheel), mass N (+ along x)]. Each slot: amplitude * f1(sel1) * f2(sel2); a slot marked
    non-periodic (angle- or time-locked) acts only when ``timevar`` is on (not in the settled start's period map)."""
    out[0] = 0.0
    out[1] = 0.0
    out[2] = 0.0
    out[3] = 0.0
    for i in range(int(P[P_XN])):
        o = P_X0 + i * OUTSIDE_STRIDE
        bal = int(P[o + X_BAL])
        if bal == XB_OFF or (P[o + X_NP] != 0.0 and timevar == 0.0):
            continue
        v = P[o + X_AMP]
        v *= _shaped(int(P[o + X_F1]), _selected(int(P[o + X_S1]), t, y, P, mode, pen, tcc),
                     P[o + X_A1], P[o + X_B1], P[o + X_C1])
        v *= _shaped(int(P[o + X_F2]), _selected(int(P[o + X_S2]), t, y, P, mode, pen, tcc),
                     P[o + X_A2], P[o + X_B2], P[o + X_C2])
        out[bal - 1] += v


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
        pen = d - P[P_BETA]
        tc = contact_torque(pen, dd, P[P_KCD], P)
    elif mode == -1:
        pen = -d - P[P_BETA]
        tc = -contact_torque(pen, -dd, P[P_KCF], P)
    else:
        pen = 0.0
        tc = 0.0
    xw = 0.0
    xf = 0.0
    if P[P_XN] > 0.0:
        xs = np.empty(4)
        outside_terms(t, y, P, timevar, mode, pen, tc, xs)
        tload += xs[0]
        tc += xs[2]
        xw = xs[1]
        xf = xs[3]
    tcd = tc if P[P_TEA] == 0.0 else tc * transmission_ratio(y, P)     # the jaw's torque on the drive half
    if P[P_KS] > 0.0:
        dy[S_W1] = (tb * te - tshaft - tload) / P[P_J1]
        dy[S_WH] = (tshaft - tcd) / P[P_JH]
        dy[S_AH] = y[S_WH]
    else:
        dy[S_W1] = (tb * te - tcd - tload) / P[P_J1]
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
        dy[S_W2] = (tc - twist - tf + xw) / P[P_J2]
        dy[S_WR] = (twist - r * f) / P[P_JR]
        dy[S_AR] = y[S_WR]
    else:
        dy[S_W2] = (tc - r * f - tf + xw) / P[P_J2]
        dy[S_WR] = 0.0
        dy[S_AR] = 0.0
    dy[S_A2] = w2
    dy[S_X] = v
    fm = f - P[P_F0] + P[P_MCF] + xf
    if P[P_RAILF] != 0.0:
        fm -= P[P_RAILF] * math.tanh(v / P[P_RAILV])
    if P[P_MDC] != 0.0:
        fm -= P[P_MDC] * v * abs(v)
    dy[S_V] = fm / P[P_M]
    return tc, te, f



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
             "alpha1", "alpha2", "mode", "jaw_angle_difference", "wheel_acceleration", "mass_speed",
             "spring_extension")
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
    """The 5 vectors of the continuous extension:
    y(t + th*h) = rc0 + th*(rc1 + (1-th)*(rc2 + th*(rc3 + (1-th)*rc4)))."""
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
    out[row, 11] = clutch_angles(y, P)[0]
    out[row, 12] = dy[S_W2]
    out[row, 13] = y[S_V]
    out[row, 14] = P[P_R] * (y[S_AR] if P[P_KW] > 0.0 else y[S_A2]) - y[S_X]


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
    P[P_TV] = timevar
    for j in range(loads.size):
        tj = (seg0 + j) * seg_dt
        u = loads[j]
        if P[P_PPER] > 0.0:           # the held pulse indicator of this segment and its pulse's start time
            ja = float(seg0 + j) - P[P_PFIRST]
            q = ja - P[P_PPER] * math.floor(ja / P[P_PPER])
            P[P_PON] = 1.0 if q < P[P_PDUR] else 0.0
            P[P_PT0] = (seg0 + j - q) * seg_dt
            P[P_PCOUNT] = math.floor(ja / P[P_PPER])
        turns = math.floor(y[S_A2] / two_pi)
        if turns != 0.0:
            P[P_A2TURNS] += turns
            shift = turns * two_pi
            y[S_A1] -= shift
            y[S_A2] -= shift
            if P[P_KS] > 0.0:
                y[S_AH] -= shift
            if P[P_KW] > 0.0:
                y[S_AR] -= shift
            y[S_X] -= P[P_R] * shift
        if P[P_RLYSEL] > 0.0:         # the relay, scanned once per segment (a two-point switch with hysteresis)
            xr = _selected(int(P[P_RLYSEL]), tj, y, P, mode, 0.0, 0.0)
            if P[P_RLYSTATE] == 0.0 and xr > P[P_RLYON]:
                P[P_RLYSTATE] = 1.0
            elif P[P_RLYSTATE] != 0.0 and xr < P[P_RLYOFF]:
                P[P_RLYSTATE] = 0.0
        if P[P_MEMKIND] > 0.0:        # the memory element, scanned once per segment
            memory_scan(tj, y, P, mode, seg_dt)
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
                # a contact begins from the gap (XS_CONTACT_AGE): the jaw at a face; a re-touch with the faces still
                # pressed (the law's torque back above 0 after it fell to 0) continues the contact that was
                if mode != 0 and abs(abs(clutch_angles(y, P)[0]) - P[P_BETA]) < 1e-6:
                    P[P_CT0] = tj + tau
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
