"""Backends generated from the enabled effects' terms (docs/effects.md, "Backends").

For one set of enabled term effects, one Python source is generated: the right-hand side as one
block of straight-line code (the motor, then each balance as the sum of its terms, each term a small
function inlined by numba), placed

- inside the SIMD stage: a loop over one tile of up to WR scenarios around the block (LLVM vectorises it; the
  terms use :mod:`mathlib`, which has no libm calls and no branches),
- inside the scalar right-hand side ``f_scalar`` (the ``numba-scalar`` backend and the zone-crossing
  step),

plus the RK4 loops around them. The source is written to a real file in a cache directory, named by
the hash of (the source, which holds the term sources; mathlib's source; numba's and Python's
versions), so numba's on-disk cache works (numba caches no ``exec``'d code). The same block runs
on numpy arrays (numpy backend, solve_ivp reference) by ``exec`` in mathlib's numpy namespace.

Parameters are run-time values: one row per parameter of a per-scenario array ``P`` (rows
``param_rows``), so a fit over parameters never recompiles. Global motor constants are in ``G``.
"""
from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import os
import sys
import textwrap
from dataclasses import dataclass
from pathlib import Path
import ast
import tempfile


import numpy as np

from backlash_monitor.files.locks import exclusive
import backlash_monitor.plant.effects as _effects
import backlash_monitor.plant.lags as _lags
import backlash_monitor.plant.outputs as _outputs
from backlash_monitor.plant._numba import HAVE_NUMBA, numba
from backlash_monitor.plant.state import GLOBAL_NAMES, N_STATES, STATE_NAMES  # noqa: F401 (the kernels' layout)
from backlash_monitor.plant.mathlib import NUMPY_NAMESPACE
import backlash_monitor.plant.mathlib as mathlib
BASE_ROWS = ("beta", "wheel_inertia_kgm2", "mass_kg",   # per-scenario model values every kernel reads (the motor's
             "rotor_resistance_pu", "supply_voltage_scale")  # two that drift with temperature and the grid among them)
GENERATOR_VERSION = "13"   # 11: the lags advanced only in a kernel whose terms name one (lags_used); 12: gated terms;
                           # 13: the coupling_torque_Nm balance (ungated, beside the jaw)


def global_vector(cfg) -> np.ndarray:
    m = cfg.motor
    return np.array([m.r_s_pu, m.r_r_pu, m.x_s_pu, m.x_r_pu, m.x_m_pu, m.w_pu, m.base_angular_frequency_rad_s,
                     m.mechanical_time_constant_s, m.base_mechanical_speed_rad_s, m.base_torque_Nm,
                     cfg.load.wheel_radius_m], dtype=np.float64)


def _pname(effect: str, param: str) -> str:
    return f"p_{effect}__{param}"


def param_rows(effect_classes) -> tuple:
    """Names of the rows of P: the base model values, then "effect.param" of every enabled term effect."""
    rows = list(BASE_ROWS)
    for cls in effect_classes:
        rows += [f"{cls.name}.{p.name}" for p in cls.parameters]
    return tuple(rows)


def _body(effect_classes, indent: str, prefix: str = "_t_", gated=()) -> str:
    """The right-hand side as straight-line code; reads the state names, ua, ub, load_pu, the pulse clock
    (pulse_time_s, pulse_off_time_s: held over the step like load_pu), mode, the g_* globals and the P rows bound to
    their local names; defines d0..d10, te, tc, f. ``gated`` (_gated_terms): those terms are not in the sums; each
    balance that has some reads their sum from its accumulator row instead (the SIMD stage's passes)."""
    skip = {c.name for c, _ in gated}
    acc = {c.balance for c, _ in gated}
    by_balance = {b: [c for c in effect_classes if c.balance == b and c.name not in skip] for b in _effects.BALANCES}
    names = {c.name for c in effect_classes}
    clutch = "backlash_clutch" in names

    def call(cls):
        args = []
        own = cls.parameter_names()
        for a in _effects.term_arguments(cls):
            args.append(_pname(cls.name, a) if a in own else a)
        return f"{prefix}{cls.name}({', '.join(args)})"

    def total(balance):
        cs = [call(c) for c in by_balance[balance]]
        if balance in acc:
            cs.append(f"WS[(R_XB + {_effects.BALANCES.index(balance)}) * WR + s]")
        return " + ".join(cs) if cs else None

    lines = [
        "iw = 1.0 / g_w",
        "isa = (g_xr * psi_sa - g_xm * psi_ra) * iw",
        "isb = (g_xr * psi_sb - g_xm * psi_rb) * iw",
        "ira = (g_xs * psi_ra - g_xm * psi_sa) * iw",
        "irb = (g_xs * psi_rb - g_xm * psi_sb) * iw",
        # ua, ub: the supply at the config's amplitude, times the scenario's scale of it (x 1.0 exactly at nominal; a
        # product, not a ratio of amplitudes: a division in the loop stops the SIMD stage from vectorising)
        "d0 = g_omega_b * (ua * supply_voltage_scale - g_rs * isa)",
        "d1 = g_omega_b * (ub * supply_voltage_scale - g_rs * isb)",
        "d2 = g_omega_b * (-rotor_resistance_pu * ira - w1 * psi_rb)",
        "d3 = g_omega_b * (-rotor_resistance_pu * irb + w1 * psi_ra)",
        "te = psi_sa * isb - psi_sb * isa",
        "omega1 = w1 * g_omega_mb",
        "rel_speed = omega1 - omega2",
        "v = g_r * omega2 - xdot",
        "wheel_radius_m = g_r",
        "base_torque_Nm = g_T_b",
        "base_mechanical_speed_rad_s = g_omega_mb",
        "ad = fabs(delta)",
        "contact_sign = where(delta > 0.0, 1.0, -1.0)",
        "penetration = ad - beta",
        "approach_speed = contact_sign * rel_speed",
        "load_moment_pu = load_pu",
    ]
    if clutch:
        lines += ["contact_stiffness_Nm_per_rad = " + _pname("backlash_clutch", "contact_stiffness_Nm_per_rad"),
                  "contact_damping_Nms_per_rad = " + _pname("backlash_clutch", "contact_damping_Nms_per_rad"),
                  # balance clutch_torque_Nm: the contact law (sum of terms), gated: 0 in the zone, never pulls
                  "raw = " + total("clutch_torque_Nm"),
                  "engaged = where(mode == 0, ad >= beta, mode == 1)",
                  "tc = where(engaged, contact_sign * fmax(raw, 0.0), 0.0)"]
    else:
        lines += ["contact_stiffness_Nm_per_rad = 0.0", "contact_damping_Nms_per_rad = 0.0", "tc = 0.0 * delta"]
    lines.append("contact_torque_Nm = tc")     # the model variable: every balance after the clutch's may name it
    rim = total("rim_mass_force_N")
    lines.append("f = " + (rim if rim else "0.0 * z"))
    lm, tw, fm = total("motor_load_moment_pu"), total("wheel_torque_Nm"), total("mass_force_N")
    # balance coupling_torque_Nm: a torque from the motor's shaft to the wheel's beside the jaw, ungated (in the zone
    # too, either sign): the wheel takes it, the motor gives it up. Without such terms the source is as it was
    tk = total("coupling_torque_Nm")
    ts = f"(tc + ({tk}))" if tk else "tc"
    lines.append(f"d4 = (te - {ts} / g_T_b - load_pu" + (f" - ({lm})" if lm else "") + ") / g_T_m")
    lines.append(f"d8 = ({ts} - g_r * f" + (f" + ({tw})" if tw else "") + ") / wheel_inertia_kgm2")
    lines.append("d10 = (f" + (f" + ({fm})" if fm else "") + ") / mass_kg")
    lines += ["d5 = rel_speed", "d6 = omega1", "d7 = omega2", "d9 = v"]
    return textwrap.indent("\n".join(lines), indent)


def _binds(effect_classes, src_state: str, src_param: str, indent: str, src_lag: str) -> str:
    """Assignments of the local names from the state / parameter / lag containers (format strings with {i})."""
    lines = [f"{n} = {src_state.format(i=i)}" for i, n in enumerate(STATE_NAMES)]
    lines += [f"{n} = {src_lag.format(i=j)}" for j, n in enumerate(_lags.LAG_NAMES)]
    rows = param_rows(effect_classes)
    for j, row in enumerate(rows):
        local = row if "." not in row else _pname(*row.split("."))
        lines.append(f"{local} = {src_param.format(i=j)}")
    return textwrap.indent("\n".join(lines), indent)


# the right-hand side's quantities a gated term may name: known before the clutch's torque (codegen _body's lines up to
# load_moment_pu), with the names they are computed from
_PRE_CLUTCH = (
    ("iw", "1.0 / g_w"), ("isa", "(g_xr * psi_sa - g_xm * psi_ra) * iw"), ("isb", "(g_xr * psi_sb - g_xm * psi_rb) * iw"),
    ("te", "psi_sa * isb - psi_sb * isa"), ("omega1", "w1 * g_omega_mb"), ("rel_speed", "omega1 - omega2"),
    ("v", "g_r * omega2 - xdot"), ("wheel_radius_m", "g_r"), ("base_torque_Nm", "g_T_b"),
    ("base_mechanical_speed_rad_s", "g_omega_mb"), ("ad", "fabs(delta)"),
    ("contact_sign", "where(delta > 0.0, 1.0, -1.0)"), ("penetration", "ad - beta"),
    ("approach_speed", "contact_sign * rel_speed"), ("load_moment_pu", "load_pu"))


def _gated_terms(effect_classes) -> list:
    """(effect class, the row of P of its factor) of every term the SIMD stage computes only on a tile where it can be
    non-zero: a plug-in's term (not the nominal model's, not plant's own catalogue) whose return value is one of its
    parameters times an expression (``c * (...)``: exactly 0 where c = 0, for a finite expression), that names only
    quantities known before the clutch's torque (_PRE_CLUTCH, the states, lags, parameters). 52 of the proposal's
    library's terms are such terms, each at 0 but on the scenarios that fit it: measured (6 sets x 8 seeds), its
    kernel's step 1.95 -> 1.13 s of CPU, the catalogue's kernel 1.07 s (which has none: its source unchanged)."""
    rows = param_rows(effect_classes)
    known = set(STATE_NAMES) | set(_lags.LAG_NAMES) | {n for n, _ in _PRE_CLUTCH} | {
        "load_pu", "pulse_time_s", "pulse_off_time_s", "beta"}
    out = []
    for c in effect_classes:
        if c.nominal or c.__module__.startswith("backlash_monitor.plant"):
            continue
        fn = ast.parse(_effects.term_source(c)).body[0]
        ret = fn.body[-1] if fn.body else None
        own = set(c.parameter_names())
        if not (len(fn.body) == 1 and isinstance(ret, ast.Return) and isinstance(ret.value, ast.BinOp)
                and isinstance(ret.value.op, ast.Mult)):
            continue
        factor = next((side.id for side in (ret.value.left, ret.value.right)
                       if isinstance(side, ast.Name) and side.id in own), None)
        if factor is None or not all(a in own or a in known for a in _effects.term_arguments(c)):
            continue
        out.append((c, rows.index(f"{c.name}.{factor}")))
    return out


def _gated_header(gated) -> str:
    """The workspace's rows and the constants of the gated terms (without any: the rows end with the lags')."""
    if not gated:
        return "WS_ROWS = R_LG + N_LAGS\n"
    return ("R_XB = R_LG + N_LAGS        # per balance, the sum of its gated terms (codegen._gated_terms), in BALANCES'"
            " order\n"
            f"WS_ROWS = R_XB + {len(_effects.BALANCES)}\n"
            f"N_GATED = {len(gated)}\n"
            f"GATE_ROWS = {tuple(r for _, r in gated)!r}     # per gated term, the row of P of its factor\n")


def _gated_passes(effect_classes, gated, indent: str) -> str:
    """The SIMD stage's passes of the gated terms: each balance's accumulator row zeroed, then per term, on a tile where
    its factor is non-zero on some scenario (act[k]), one loop over the tile adding it to its balance's row."""
    if not gated:
        return ""
    lines = []
    for b in sorted({_effects.BALANCES.index(c.balance) for c, _ in gated}):
        lines += ["for s in range(nl):", f"    WS[(R_XB + {b}) * WR + s] = 0.0"]
    rows = param_rows(effect_classes)
    prefix = dict(_PRE_CLUTCH)
    for k, (c, _) in enumerate(gated):
        own = c.parameter_names()
        args = _effects.term_arguments(c)
        need, order = set(), []

        def visit(name):
            if name in need:
                return
            need.add(name)
            if name in prefix:
                for dep in sorted({n.id for n in ast.walk(ast.parse(prefix[name])) if isinstance(n, ast.Name)}):
                    visit(dep)
                order.append(name)
        for a in args:
            if a not in own:
                visit(a)
        body = []
        for n in sorted(need):      # sorted: the same source (the same cache key) in every process
            if n in STATE_NAMES:
                body.append(f"{n} = WS[(ry + {STATE_NAMES.index(n)}) * WR + s]")
            elif n in _lags.LAG_NAMES:
                body.append(f"{n} = WS[(R_LG + {_lags.LAG_NAMES.index(n)}) * WR + s]")
            elif n == "beta":
                body.append("beta = WS[(R_P + 0) * WR + s]")
            elif n == "load_pu":
                body.append("load_pu = WS[R_LD * WR + s]")
        body += [f"{n} = {prefix[n]}" for n in order]
        call = ", ".join(f"WS[(R_P + {rows.index(f'{c.name}.{a}')}) * WR + s]" if a in own else a for a in args)
        b = _effects.BALANCES.index(c.balance)
        body.append(f"WS[(R_XB + {b}) * WR + s] += _t_{c.name}({call})")
        lines += [f"if act[{k}]:", "    for s in range(nl):"] + [f"        {x}" for x in body]
    return textwrap.indent("\n".join(lines), indent) + "\n"


def _globals(indent: str) -> str:
    return textwrap.indent("\n".join(f"{n} = G[{i}]" for i, n in enumerate(GLOBAL_NAMES)), indent)


_KERNEL_TEMPLATE = '''
@numba.njit(**_TJIT)
def stage(WS, ry, rk, ua, ub, pulse_time_s, pulse_off_time_s, G, nl{act_arg}):
    """One RK4 stage for the nl scenarios of a tile (nl a multiple of W): K = f(Y) with Y the N_STATES rows of
    the workspace from row ``ry``, K those from row ``rk``, T_c into row R_TC; inlined where it is called, so
    the rows are constants and every access is the workspace's base plus a constant plus s (the pulse clock, like
    ua and ub, is one value of the step for every scenario: the pulse train is the config's). The inner loop
    over one block of W scenarios becomes one vector per operation (no run-time alias check, no scalar
    remainder); the outer loop runs the nl / W blocks (docs/effects.md, "Backends": the tiles)."""
{globals}
    mode = 0                    # the zone test decides (a located crossing is the scalar step's)
{gated_passes}    for blk in range(nl // W):
        for lane in range(W):
            s = blk * W + lane
            load_pu = WS[R_LD * WR + s]
{binds_simd}
{body_simd}
            WS[(rk + 0) * WR + s] = d0; WS[(rk + 1) * WR + s] = d1; WS[(rk + 2) * WR + s] = d2
            WS[(rk + 3) * WR + s] = d3; WS[(rk + 4) * WR + s] = d4; WS[(rk + 5) * WR + s] = d5
            WS[(rk + 6) * WR + s] = d6; WS[(rk + 7) * WR + s] = d7; WS[(rk + 8) * WR + s] = d8
            WS[(rk + 9) * WR + s] = d9; WS[(rk + 10) * WR + s] = d10
            WS[R_TC * WR + s] = tc


@numba.njit(**_JIT)
def f_scalar(y, ua, ub, load_pu, pulse_time_s, pulse_off_time_s, lg, ps, G, mode, out):
    """The right-hand side of one scenario (lg: its lags, held over the step; ps: its column of P); writes out,
    returns T_c.
    mode: 0 = the zone test decides, 1 = in contact, 2 = in the zone (forced, at a located crossing)."""
{globals_1}
{binds_scalar}
{body_scalar}
    out[0] = d0; out[1] = d1; out[2] = d2; out[3] = d3; out[4] = d4; out[5] = d5
    out[6] = d6; out[7] = d7; out[8] = d8; out[9] = d9; out[10] = d10
    return tc


@numba.njit(**_JIT)
def f_tuple(y0, y1, y2, y3, y4, y5, y6, y7, y8, y9, y10, ua, ub, load_pu, pulse_time_s, pulse_off_time_s, lg, ps, G, mode):
    """The right-hand side on named scalars (the numba-scalar loop keeps its state in registers)."""
{globals_1}
{binds_tuple}
{body_scalar}
    return d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10, tc
'''

_LOOPS = '''
@numba.njit(**_JIT)
def _derivs_at(y, tau, phase, u_amp, ld, pt, po, lg, ps, G, mode, out):
    ph = phase + G[6] * tau
    return f_scalar(y, u_amp * math.cos(ph), u_amp * math.sin(ph), ld, pt, po, lg, ps, G, mode, out)


@numba.njit(**_JIT)
def _rk4_substep(y, hs, tau0, phase, u_amp, ld, pt, po, lg, ps, G, mode):
    k1 = np.empty(N_STATES); k2 = np.empty(N_STATES); k3 = np.empty(N_STATES); k4 = np.empty(N_STATES)
    tmp = np.empty(N_STATES)
    _derivs_at(y, tau0, phase, u_amp, ld, pt, po, lg, ps, G, mode, k1)
    for i in range(N_STATES):
        tmp[i] = y[i] + 0.5 * hs * k1[i]
    _derivs_at(tmp, tau0 + 0.5 * hs, phase, u_amp, ld, pt, po, lg, ps, G, mode, k2)
    for i in range(N_STATES):
        tmp[i] = y[i] + 0.5 * hs * k2[i]
    _derivs_at(tmp, tau0 + 0.5 * hs, phase, u_amp, ld, pt, po, lg, ps, G, mode, k3)
    for i in range(N_STATES):
        tmp[i] = y[i] + hs * k3[i]
    _derivs_at(tmp, tau0 + hs, phase, u_amp, ld, pt, po, lg, ps, G, mode, k4)
    for i in range(N_STATES):
        y[i] += hs / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])


@numba.njit(**_JIT)
def crossing_step(y0, y1, h, phase, u_amp, ld, pt, po, lg, ps, G):
    """Redo a step in which Delta crossed |Delta| = beta: locate the crossing on the cubic Hermite
    interpolant of Delta, RK4 to it with the start side's law and on with the other side's (docs/model.md).
    Returns the crossing's fraction of the step."""
    bs = ps[0]
    omb = G[8]
    d0, d1 = y0[5], y1[5]
    r0 = (y0[4] * omb - y0[8]) * h
    r1 = (y1[4] * omb - y1[8]) * h
    inside0 = abs(d0) < bs
    sgn = (1.0 if d1 > 0.0 else -1.0) if inside0 else (1.0 if d0 > 0.0 else -1.0)
    target = sgn * bs
    lo, hi = 0.0, 1.0
    f_lo = d0 - target
    for _ in range(60):
        th = 0.5 * (lo + hi)
        t2 = th * th
        t3 = t2 * th
        val = ((2 * t3 - 3 * t2 + 1) * d0 + (t3 - 2 * t2 + th) * r0 + (-2 * t3 + 3 * t2) * d1
               + (t3 - t2) * r1) - target
        if (val > 0.0) == (f_lo > 0.0):
            lo = th
            f_lo = val
        else:
            hi = th
    th = 0.5 * (lo + hi)
    mode0 = 2 if inside0 else 1
    mode1 = 1 if inside0 else 2
    for i in range(N_STATES):
        y1[i] = y0[i]
    if th > 0.0:
        _rk4_substep(y1, th * h, 0.0, phase, u_amp, ld, pt, po, lg, ps, G, mode0)
    if th < 1.0:
        _rk4_substep(y1, (1.0 - th) * h, th * h, phase, u_amp, ld, pt, po, lg, ps, G, mode1)
    return th


@numba.njit(**_JIT)
def rk4_simd(x, lags, load, clock, ua, ub, phase, u_amp, P, G, h, out, states, record_states, record_outputs, sel):
    """Scenarios in tiles of nl = up to WR (a multiple of W, a run-time count), samples inner per tile; each
    tile's state, stages, parameters and load in one workspace whose rows are WR apart. The loops over a
    tile's scenarios run to the run-time nl: LLVM keeps them loops of whole vectors (loops of a constant 8
    were unrolled into mostly scalar code, measured: ~1.6x slower, docs/effects.md). The last tile is padded
    to a multiple of W with copies of the last scenario (never written out, never take the crossing step).
    ``lags`` (S, N_LAGS): each scenario's first-order lags (plant/lags.py), held over each step, advanced in place."""
    S = x.shape[0]
    n = load.shape[1]
{GLOBALS}
    hh = 0.5 * h; h6 = h / 6.0
    WS = np.empty(WS_ROWS * WR)
    y0 = np.empty(N_STATES); y1 = np.empty(N_STATES); ps = np.empty(N_PARAMS); lg = np.empty(N_LAGS)
    LC = lag_coefficients(h)
{ACT_INIT}    nsel = sel.shape[0]
    buf = np.empty((nsel, OUT_BLOCK, WR))
    t0 = 0
    while t0 < S:
        nl = min(WR, (S - t0 + W - 1) // W * W)
        live = min(nl, S - t0)
        for s in range(nl):
            sc = min(t0 + s, S - 1)
            for i in range(N_STATES):
                WS[(R_Y + i) * WR + s] = x[sc, i]
            for j in range(N_PARAMS):
                WS[(R_P + j) * WR + s] = P[j, sc]
            for j in range(N_LAGS):
                WS[(R_LG + j) * WR + s] = lags[sc, j]
{ACT_TILE}        for k in range(n):
            for s in range(nl):
                WS[R_LD * WR + s] = load[min(t0 + s, S - 1), k]
            if record_states:
                for i in range(N_STATES):
                    for s in range(live):
                        states[i, t0 + s, k] = WS[(R_Y + i) * WR + s]
            for i in range(N_STATES):
                for s in range(nl):
                    WS[(R_T + i) * WR + s] = WS[(R_Y + i) * WR + s]
                    WS[(R_A + i) * WR + s] = 0.0
            for st in range(4):
                # the right-hand side at the trial state T, into K; the stage's weight into the sum A; the
                # next trial state. One inlined stage in a loop (not four): a quarter of the compile time
                c = (st + 1) // 2
                stage(WS, R_T, R_K, ua[k, c], ub[k, c], clock[k, 0], clock[k, 1], G, nl{ACT_ARG})
                if st == 0 and record_outputs:
                    b = k % OUT_BLOCK
                    for j in range(nsel):
                        o = sel[j]
{OUTPUT_SELECT}
                    if b == OUT_BLOCK - 1 or k == n - 1:
                        k_start = k - b
                        for j in range(nsel):
                            for s in range(live):
                                for bb in range(b + 1):
                                    out[j, t0 + s, k_start + bb] = buf[j, bb, s]
                wt = 1.0 if st == 0 or st == 3 else 2.0
                ht = h if st == 2 else hh
                for i in range(N_STATES):
                    for s in range(nl):
                        WS[(R_A + i) * WR + s] += wt * WS[(R_K + i) * WR + s]
                        WS[(R_T + i) * WR + s] = WS[(R_Y + i) * WR + s] + ht * WS[(R_K + i) * WR + s]
            for i in range(N_STATES):
                for s in range(nl):
                    WS[(R_T + i) * WR + s] = WS[(R_Y + i) * WR + s] + h6 * WS[(R_A + i) * WR + s]
            if CLUTCH:
                for s in range(live):
                    bs = WS[R_P * WR + s]
                    if (abs(WS[(R_Y + 5) * WR + s]) < bs) != (abs(WS[(R_T + 5) * WR + s]) < bs):
                        for i in range(N_STATES):
                            y0[i] = WS[(R_Y + i) * WR + s]; y1[i] = WS[(R_T + i) * WR + s]
                        for j in range(N_PARAMS):
                            ps[j] = WS[(R_P + j) * WR + s]
                        for j in range(N_LAGS):
                            lg[j] = WS[(R_LG + j) * WR + s]
                        crossing_step(y0, y1, h, phase[k], u_amp, WS[R_LD * WR + s], clock[k, 0], clock[k, 1], lg, ps,
                                      G)
                        for i in range(N_STATES):
                            WS[(R_T + i) * WR + s] = y1[i]
{LAG_UPDATE_SIMD}
            for i in range(N_STATES):
                for s in range(nl):
                    WS[(R_Y + i) * WR + s] = WS[(R_T + i) * WR + s]
        for s in range(live):
            for i in range(N_STATES):
                x[t0 + s, i] = WS[(R_Y + i) * WR + s]
            for j in range(N_LAGS):
                lags[t0 + s, j] = WS[(R_LG + j) * WR + s]
        t0 += nl
'''

_ACT_INIT = "    act = np.zeros(N_GATED, dtype=np.bool_)\n"
_ACT_TILE = (
    "        for g in range(N_GATED):      # a gated term is computed on this tile when its factor is non-zero somewhere\n"
    "            act[g] = False\n"
    "            for s in range(nl):\n"
    "                if WS[(R_P + GATE_ROWS[g]) * WR + s] != 0.0:\n"
    "                    act[g] = True\n")

_HEADER = '''# Generated by backlash_monitor.plant.codegen (generator {version}) -- do not edit.
# Effects: {effects}
import math
import numpy as np
import numba
from backlash_monitor.plant.mathlib import (where, fabs, fmax, fmin, sign, smooth_sign, sqrt, exp, log,
                                            power, sin, cos, s_exp, s_log, s_power, s_sin, s_cos)

_JIT = dict(cache=True, nogil=True, fastmath=True, error_model="numpy")
_TJIT = dict(inline="always", fastmath=True, error_model="numpy")
N_STATES = {n_states}
W = 8                       # a tile holds a multiple of W scenarios: one AVX-512 vector, two AVX2 ones
WR = 32                     # the most scenarios in a tile (the workspace's rows are WR apart): 16-32 measured
                            # equal at <= 12 scenarios, 32 ~5 % faster at >= 48; 64 slower at 6
N_PARAMS = {n_params}
N_LAGS = {n_lags}
LAG_TIMES = {lag_times!r}     # each lag's time constant [s] (plant/lags.py LAGS)


@numba.njit(**_JIT)
def lag_coefficients(h):
    """(N_LAGS, 3): each lag's update L' = A*L + B*q_new + C*q_old over a step h (plant/lags.py coefficients)."""
    out = np.empty((N_LAGS, 3))
    for j in range(N_LAGS):
        a = math.exp(-h / LAG_TIMES[j])
        c = LAG_TIMES[j] * (1.0 - a) / h
        out[j, 0] = a; out[j, 1] = 1.0 - c; out[j, 2] = c - a
    return out
R_Y = 0                     # the workspace's rows (each WR wide): state, RK4 trial state, a stage's
R_T = N_STATES              # derivatives, their weighted sum, T_c, the load, the parameters
R_K = 2 * N_STATES
R_A = 3 * N_STATES
R_TC = 4 * N_STATES
R_LD = R_TC + 1
R_P = R_TC + 2
R_LG = R_P + N_PARAMS       # the scenarios' first-order lags (plant/lags.py)
{gated_rows}OUT_BLOCK = 32
CLUTCH = {clutch}
EFFECTS = {effect_names!r}
PARAM_ROWS = {rows!r}
'''


_SCALAR_HELPERS = ("exp", "log", "power", "sin", "cos")


def _scalar_term_source(cls) -> str:
    """The term renamed ``_ts_<name>`` and calling mathlib's libm forms (``s_exp`` ...) instead of the
    polynomial ones: the scalar right-hand side is latency-bound, where one libm call is faster than a
    vectorisable polynomial (measured: numba-scalar 0.6-0.8x of the former kernel with the polynomials)."""
    tree = ast.parse(_effects.term_source(cls))

    class Rename(ast.NodeTransformer):
        def visit_Name(self, node):
            if node.id in _SCALAR_HELPERS:
                return ast.copy_location(ast.Name(id="s_" + node.id, ctx=node.ctx), node)
            return node
    fn = Rename().visit(tree).body[0]
    fn.name = f"_ts_{cls.name}"
    return ast.unparse(fn)


def lags_used(effect_classes) -> bool:
    """Whether a term of these effects names a first-order lag (plant/lags.py LAG_NAMES) among its arguments: only
    then does the kernel advance the lags (every one of them) at each step; else they stay as they were given (settled
    at the start), which no term reads (measured, 6 sets x 8 seeds: the update was ~5 % of a step of the catalogue's
    kernel and of the proposal's library kernel; the catalogue's recordings bit for bit the same without it)."""
    return any(a in _lags.LAG_NAMES for c in effect_classes for a in _effects.term_arguments(c))


def _lag_update(indent: str, old: str, new: str, lag: str, beta: str, load: str) -> str:
    """The lines advancing every lag over one step (plant/lags.py): ``old``/``new`` the state containers before and
    after it (format strings with {i}), ``lag`` the lag's container ({j}); a held input's q_new is its q_old."""
    lines = []
    for i, (_, _, held) in enumerate(_lags.QUANTITIES):
        def q(src):
            return _lags.render(i, *(src.format(i=k) for k in (4, 5, 8, 10)), load, beta, "g_omega_mb")
        lines.append(f"qo = {q(old)}")
        lines.append("qn = qo" if held else f"qn = {q(new)}")
        for j, (_, qi, _) in enumerate(_lags.LAGS):
            if qi == i:
                lines.append(f"{lag.format(j=j)} = LC[{j}, 0] * {lag.format(j=j)} + LC[{j}, 1] * qn + LC[{j}, 2] * qo")
    return textwrap.indent("\n".join(lines), indent)


def _simd_output_select() -> str:
    """rk4_simd's recording of the selected outputs ``sel`` into ``buf``: one branch per output of
    :data:`outputs.OUTPUTS` (the only definition), on the first stage's trial state (the state itself), its
    derivatives K and T_c."""
    lines = []
    for j, o in enumerate(_outputs.OUTPUTS):
        kw = "if" if j == 0 else ("else" if j == len(_outputs.OUTPUTS) - 1 else "elif")
        lines.append(f"                        {kw}:" if kw == "else" else f"                        {kw} o == {j}:")
        lines.append("                            for s in range(nl): buf[j, b, s] = "
                     + _outputs.render(o.expression, "WS[(R_T + {i}) * WR + s]", "WS[(R_K + {i}) * WR + s]",
                                       "WS[R_TC * WR + s]"))
    return "\n".join(lines)


def _scalar_loop(carry_lags: bool = True) -> str:
    """rk4_scalar: scenarios outer, samples inner, the state in named locals (registers), the four stages
    calling f_tuple; the same scheme as rk4_simd (``carry_lags``: lags_used)."""
    N = N_STATES
    ys = ", ".join(f"y{i}" for i in range(N))

    def stage(tag, src, coef, col):
        args = ", ".join(f"y{i} + {coef} * {src}{i}" for i in range(N)) if src else ys
        outs = ", ".join(f"{tag}{i}" for i in range(N))
        return f"            {outs}, tc = f_tuple({args}, ua[k, {col}], ub[k, {col}], ld, pt, po, lg, ps, G, 0)"

    lines = [
        "@numba.njit(**_JIT)",
        "def rk4_scalar(x, lags, load, clock, ua, ub, phase, u_amp, P, G, h, out, states, record_states):",
        '    """Scenarios outer, samples inner (the numba-scalar backend)."""',
        "    n_scen = x.shape[0]", "    n = load.shape[1]", _globals("    "),
        "    hh = 0.5 * h", "    h6 = h / 6.0",
        "    y0a = np.empty(N_STATES); y1a = np.empty(N_STATES); ps = np.empty(P.shape[0]); lg = np.empty(N_LAGS)",
        "    LC = lag_coefficients(h)",
        "    for s in range(n_scen):",
        "        " + "; ".join(f"y{i} = x[s, {i}]" for i in range(N)),
        "        for j in range(P.shape[0]):", "            ps[j] = P[j, s]",
        "        bs = ps[0]",
        "        for j in range(N_LAGS):", "            lg[j] = lags[s, j]",
        "        for k in range(n):",
        "            ld = load[s, k]; pt = clock[k, 0]; po = clock[k, 1]",
        "            if record_states:",
        "                " + "; ".join(f"states[{i}, s, k] = y{i}" for i in range(N)),
        stage("a", None, None, 0),
        *(f"            out[{j}, s, k] = {_outputs.render(o.expression, 'y{i}', 'a{i}', 'tc')}"
          for j, o in enumerate(_outputs.OUTPUTS)),
        stage("b", "a", "hh", 1), stage("c", "b", "hh", 1), stage("e", "c", "h", 2),
        "            " + "; ".join(f"n{i} = y{i} + h6 * (a{i} + 2.0 * b{i} + 2.0 * c{i} + e{i})" for i in range(N)),
        "            if CLUTCH and ((abs(y5) < bs) != (abs(n5) < bs)):",
        "                " + "; ".join(f"y0a[{i}] = y{i}; y1a[{i}] = n{i}" for i in range(N)),
        "                crossing_step(y0a, y1a, h, phase[k], u_amp, ld, pt, po, lg, ps, G)",
        "                " + "; ".join(f"n{i} = y1a[{i}]" for i in range(N)),
        *([_lag_update("            ", "y{i}", "n{i}", "lg[{j}]", "bs", "ld")] if carry_lags else []),
        "            " + "; ".join(f"y{i} = n{i}" for i in range(N)),
        "        " + "; ".join(f"x[s, {i}] = y{i}" for i in range(N)),
        "        for j in range(N_LAGS):", "            lags[s, j] = lg[j]",
    ]
    return "\n\n" + "\n".join(lines) + "\n"


def generate_source(effect_classes) -> str:
    """The kernel module's source for these (term) effects, in this order."""
    terms = "\n\n".join("@numba.njit(**_TJIT)\n" + _effects.term_source(c) for c in effect_classes)
    terms += "\n\n\n" + "\n\n".join("@numba.njit(**_TJIT)\n" + _scalar_term_source(c) for c in effect_classes)
    names = tuple(c.name for c in effect_classes)
    carry = lags_used(effect_classes)
    gated = _gated_terms(effect_classes)
    head = _HEADER.format(version=GENERATOR_VERSION, effects=", ".join(names) or "(none)", n_states=N_STATES,
                          n_params=len(param_rows(effect_classes)),
                          clutch="backlash_clutch" in names, effect_names=names, rows=param_rows(effect_classes),
                          n_lags=_lags.N_LAGS, lag_times=tuple(tau for _, _, tau in _lags.LAGS),
                          gated_rows=_gated_header(gated))
    # the gated terms' machinery (their tile flags ``act``) only in a kernel that has some: without, the same source
    # as before gating existed (the same cache key)
    act_arg, act_init, act_tile = (", act", _ACT_INIT, _ACT_TILE) if gated else ("", "", "")
    kern = _KERNEL_TEMPLATE.format(gated_passes=_gated_passes(effect_classes, gated, "    "), act_arg=act_arg,
        globals=_globals("    "), globals_1=_globals("    "),
        binds_simd=_binds(effect_classes, "WS[(ry + {i}) * WR + s]", "WS[(R_P + {i}) * WR + s]", "            ",
                          "WS[(R_LG + {i}) * WR + s]"),
        body_simd=_body(effect_classes, "            ", gated=gated),
        binds_scalar=_binds(effect_classes, "y[{i}]", "ps[{i}]", "    ", "lg[{i}]"),
        binds_tuple=_binds(effect_classes, "y{i}", "ps[{i}]", "    ", "lg[{i}]"),
        body_scalar=_body(effect_classes, "    ", "_ts_"))
    loops = (_LOOPS.replace("{GLOBALS}", _globals("    ")).replace("{OUTPUT_SELECT}", _simd_output_select())
             .replace("{LAG_UPDATE_SIMD}", _simd_lag_update(carry))
             .replace("{ACT_INIT}", act_init).replace("{ACT_TILE}", act_tile).replace("{ACT_ARG}", act_arg))
    return head + "\n\n" + terms + "\n\n" + kern + loops + _scalar_loop(carry)


def _simd_lag_update(carry_lags: bool) -> str:
    """rk4_simd's advance of the lags after each step (nothing when no term names one: lags_used)."""
    if not carry_lags:
        return "            # no term names a lag (codegen.lags_used): the lags are not advanced"
    return ("            # the lags, from the state before (Y) and after (T) the step and the load held over it\n"
            "            for s in range(nl):\n"
            + _lag_update("                ", "WS[(R_Y + {i}) * WR + s]", "WS[(R_T + {i}) * WR + s]",
                          "WS[(R_LG + {j}) * WR + s]", "WS[R_P * WR + s]", "WS[R_LD * WR + s]"))


def generate_numpy(effect_classes):
    """The right-hand side on arrays (numpy backend, solve_ivp reference): f(y_list, ua, ub, load_pu, pulse_time_s,
    pulse_off_time_s, P, G, mode, lags) -> (11 derivatives, (te, tc, f)); the same block, run in mathlib's numpy
    namespace. ``lags``: the list of the N_LAGS lags (plant/lags.py); None: each settled at its quantity's value."""
    terms = "\n\n".join(_effects.term_source(c) for c in effect_classes)
    src = (terms + "\n\n\ndef rhs(y, ua, ub, load_pu, pulse_time_s, pulse_off_time_s, P, G, mode=0, lags=None):\n"
           + _globals("    ") + "\n"
           + "    if lags is None:   # no memory given (a reference solution): every lag settled at its quantity\n"
           + "        q = LAG_QUANTITIES(y, load_pu, P[0], g_omega_mb)\n"
           + "        lags = [q[i] for i in LAG_QUANTITY_OF]\n"
           + _binds(effect_classes, "y[{i}]", "P[{i}]", "    ", "lags[{i}]") + "\n" + _body(effect_classes, "    ") + "\n"
           + "    return (d0, d1, d2, d3, d4, d5, d6, d7, d8, d9, d10), (te, tc, f)\n")
    ns = dict(NUMPY_NAMESPACE, LAG_QUANTITIES=_lags.quantities, LAG_QUANTITY_OF=tuple(i for _, i, _ in _lags.LAGS))
    exec(compile(src, f"<numpy rhs: {', '.join(c.name for c in effect_classes)}>", "exec"), ns)  # noqa: S102
    return ns["rhs"]


def cache_dir() -> Path:
    env = os.environ.get("BACKLASH_MONITOR_KERNEL_CACHE")
    if env:
        return Path(env)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "backlash_monitor" / "kernels"


def _cache_key(source: str) -> str:
    h = hashlib.sha256()
    h.update(source.encode())
    h.update(Path(mathlib.__file__).read_bytes())
    h.update(f"numba {numba.__version__ if HAVE_NUMBA else '-'} python {sys.version}".encode())
    return h.hexdigest()[:20]


@dataclass
class Kernel:
    """The backends of one effect set."""
    effects: tuple            # effect classes (term kind), in catalogue order
    param_rows: tuple         # rows of P
    rhs_numpy: object         # numpy right-hand side
    module: object = None     # the generated numba module (None without numba)
    path: Path | None = None  # its file
    carries_lags: bool = True  # a term names a lag: every backend advances the lags (lags_used)

    @property
    def names(self) -> tuple:
        return tuple(c.name for c in self.effects)


_KERNELS: dict = {}


def compile_lock(kernel: Kernel):
    """Hold an exclusive lock beside the kernel's file while its first call compiles it (or loads numba's cache):
    processes that start on a cold cache at once (analyze FOLDER --jobs N, a fleet's drive processes, pytest's
    workers) compile each kernel once, ~10 s of one core; the others wait, then load it (~0.6 s). Released when the
    process ends, also if it is killed (files/locks.py: without fcntl or a writable directory, no lock)."""
    if kernel.path is None:                   # no numba: nothing is compiled
        return contextlib.nullcontext()
    return exclusive(kernel.path.with_name(kernel.path.name + ".lock"))


def kernel_for(effect_classes) -> Kernel:
    """The (memoised) backends for a tuple of term effect classes: generated, written, imported."""
    key = tuple(effect_classes)
    k = _KERNELS.get(key)
    if k is not None:
        return k
    rhs_np = generate_numpy(effect_classes)
    module = path = None
    if HAVE_NUMBA:
        source = generate_source(effect_classes)
        digest = _cache_key(source)
        d = cache_dir()
        try:
            d.mkdir(parents=True, exist_ok=True)
            probe = d / f".probe.{os.getpid()}"
            probe.write_text("")
            probe.unlink()
        except OSError:                      # read-only home: a per-user directory under the temp dir
            d = Path(tempfile.gettempdir()) / f"backlash_monitor_kernels_{os.getuid() if hasattr(os, 'getuid') else 0}"
            d.mkdir(parents=True, exist_ok=True)
        path = d / f"kernel_{digest}.py"
        if not path.is_file() or path.read_text() != source:
            tmp = d / f".kernel_{digest}.{os.getpid()}.tmp"
            tmp.write_text(source)
            os.replace(tmp, path)             # atomic: parallel processes never see half a file
        mod_name = f"backlash_monitor_kernel_{digest}"
        module = sys.modules.get(mod_name)
        if module is None:
            spec = importlib.util.spec_from_file_location(mod_name, path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[mod_name] = module
            spec.loader.exec_module(module)
    k = Kernel(effects=key, param_rows=param_rows(effect_classes), rhs_numpy=rhs_np, module=module, path=path,
               carries_lags=lags_used(effect_classes))
    _KERNELS[key] = k
    return k
