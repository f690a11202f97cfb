"""The generic library of candidate terms a proposal is built from (docs/workbench.md, "Proposing a missing term").

Each term is coefficient x f(states), put into one balance of the model (docs/effects.md "Kinds and balances"):
the motor's load moment [p.u.], the clutch's contact torque [N*m], the rim force between wheel and mass [N], the
wheel torque [N*m], the mass force [N]. f is dimensionless and of order 1 at the operating point (each state divided
by the scale below), so the coefficient carries the balance's unit. The library is not a list of known faults: it is
the powers and signs of the speeds and each body's speed deviation from the recording's mean (_speed_deviations),
the clutch's penetration and its rate (and their product), the spring extension's powers, the harmonics of both shafts' angles (integer orders 1 and 2, as sine/cosine pairs that are
linear in their coefficients: a pair is one group, selected together, reported as amplitude and phase), the
electromagnetic torque, the load pulse (the responses after its edges, on the pulse clock pulse_time_s,
pulse_off_time_s, are written -- edge_terms -- but not in the default library: EDGES_IN_LIBRARY), and products of
the clutch's contact torque (the model variable ``contact_torque_Nm``) with a speed's sign in the balances after the
clutch's (_contact_torque_products), terms with a memory of their own on the plant's first-order lags (memory_terms:
a hidden body on a viscous coupling, a relaxing contact, a stroke through a lag; plant/lags.py); computed on the recorded events instead of simulated (recorded_terms), a
sensor's terms, its own dynamics (_sensor_dynamics) and a slow change with the time in the record.

The library is written as a plug-in file (the documented ``--effects-file`` form): every term one Effect class with
one bounded coefficient, default 0 (neutral), so that the model's simulator screens all of them on common random
numbers in one batch. A proposal is written back in the same form (``proposal_source``).
"""
from __future__ import annotations

import dataclasses
import hashlib
import math
import os
from dataclasses import dataclass
from pathlib import Path
import re

import numpy as np

from backlash_monitor.plant.lags import LAG_TIMES_S, lag_name

PREFIX = "cand_"     # the library's effect names: cand_<balance>_<what>

# the scales f divides the states by [unit of the state] -- the size of each state at the paper's operating point
# (config/plant.yaml; measured on the nominal model: Omega ~151.5 +- 1.5 rad/s, a clutch torque up to ~35 N*m at
# k_c = 3000 N*m/rad, the spring's static extension F0/k = 0.3 m):
SPEED_REF = "base_mechanical_speed_rad_s"     # speeds by the motor's base speed Omega_mb (a model variable)
REL_SPEED_SCALE_RAD_S = 10.0                  # Omega1 - Omega2 while the gap is crossed: a few rad/s
PENETRATION_SCALE_RAD = 3e-3                  # ~10 N*m / k_c: the jaw's penetration under the working load
APPROACH_SCALE_RAD_S = 1.0                    # the contact's closing speed at entry: ~1 rad/s
EXTENSION_SCALE_M = 0.3                       # the spring's static extension F0/k
RIM_SPEED_SCALE_M_S = 0.1                     # r*Omega2 - xdot: the spring's rate, ~0.1 m/s
JAW_SIDE_SMOOTHING_RAD = 1e-3                 # the jaw's side sgn(Δ) smoothed over this angle: a third of the working
                                              # penetration (PENETRATION_SCALE_RAD), small against the gap (β ~ 0.05 rad)
PULSE_SCALE_PU = 1.6                          # the load pulse's height (config/plant.yaml pulse_load: 1.6 p.u.)
# the responses after the load pulse's edges: exp(-t/tau), t the time since the rising (pulse_time_s) or the falling
# edge (pulse_off_time_s), at these FIXED decay times [s]: a geometric ladder (factor 4) over the pulse's length D =
# 60 ms, D/6 and 2D/3. 10 ms is a quarter of an event's segment (2048 samples, ~41 ms: a fast transient there, a
# valve, a pressure wave, is seen); 40 ms is the pulse's own scale and dies within the pause (190 ms: e^(-190/40) =
# 0.009, so the clock's restart at the next pulse cuts nothing). A first-order response between ~5 and ~100 ms is a
# combination of the two and the pulse term (the infinite decay: a step over the pulse); a response delayed and
# lagged behind the pulse is the pulse term less these. Ungated: a linear response after an edge goes on across the
# next edge (superposition). Each edge in each balance is ONE group of the two (selected together): 6 groups, each one
# more hypothesis the selection tests; two decays, not three: measured on the pneumatic hold-back (outside_dev3 #7),
# a ladder of three (5, 20, 80 ms) fitted alternating coefficients of 50-75 N, at the bounds in another balance, and
# cost 18 simulated sets
EDGE_DECAYS_S = (0.01, 0.04)
# NOT in the default library (measured on outside_dev3, `bench/_workbench/outside.py --set 3`, 29 Nov): with them the
# three rows that need them gained nothing (the accumulator recharge stays invisible, verdict consistent; the
# pneumatic hold-back and the stroke ringing got wrong-balance proposals: the wheel's falling-edge pair at its bounds,
# +-20 N*m -- after the fall both decays have died before the next event, so the pair is a free kick in the pause),
# the deadband row lost its right balance, and the proposal's CPU rose from 33-44 s to 58-61 s a recording (12 more
# simulated sets). Switched on, a user or a later library gets them (library(edges=True))
EDGES_IN_LIBRARY = False
EDGE_EXP_CAP = 600.0                          # exp(-min(t/tau, 600)): inside mathlib's exp range (y > -690), e^-600 = 0
# the balances: (unit of the coefficient, the screening's step = a small amount of the term in its balance, the
# coefficient's bounds); the step ~ a tenth of the balance's own size (F0*r = 4.5 N*m at the rim, T_b = 20 N*m). The
# motor's bound: its breakdown torque, 1.75 p.u. (plant.motor.breakdown_slip on the model's circuit, slip 0.236), is
# what a law of the speed's square, (Omega1/Omega_mb)^2, reaches at 2.5 p.u. at 132 rad/s (0.84 Omega_mb: a drive loaded
# near breakdown): a larger coefficient stalls the motor. (It was 1 p.u., 0.75 p.u. of load at the 136 rad/s of a
# heavily loaded drive: a paste mixer's ~0.9 p.u. was pinned there, the record mean's speed 12.9x its limit; at 1.22
# p.u. 0.1x)
BALANCES = {
    "motor_load_moment_pu": ("p.u.", 0.02, 2.5),
    "clutch_torque_Nm": ("N*m", 2.0, 200.0),
    "rim_mass_force_N": ("N", 3.0, 200.0),
    "wheel_torque_Nm": ("N*m", 0.5, 20.0),
    "mass_force_N": ("N", 3.0, 200.0),
    # a torque from the motor's shaft to the wheel's beside the jaw, in the gap and in contact: a flexible element in
    # parallel with it or a slip coupling carries a part of the transmitted torque (~10-35 N*m): a few N*m
    "coupling_torque_Nm": ("N*m", 0.5, 50.0),
    # a term the sensor adds to one accelerometer (recorded terms: computed on the recorded events, not simulated)
    "sensor_a1_m_s2": ("m/s²", 0.5, 200.0),
    "sensor_a2_m_s2": ("m/s²", 0.5, 200.0),
}
SIMULATED_BALANCES = ("motor_load_moment_pu", "clutch_torque_Nm", "rim_mass_force_N", "wheel_torque_Nm", "mass_force_N",
                      "coupling_torque_Nm")
BALANCE_WORDS = {"motor_load_moment_pu": "motor load moment", "clutch_torque_Nm": "clutch torque",
                 "rim_mass_force_N": "rim force", "wheel_torque_Nm": "wheel torque", "mass_force_N": "mass force",
                 "coupling_torque_Nm": "coupling torque", "sensor_a1_m_s2": "measured a1",
                 "sensor_a2_m_s2": "measured a2"}
SHORT = {"motor_load_moment_pu": "motor", "clutch_torque_Nm": "clutch", "rim_mass_force_N": "rim",
         "wheel_torque_Nm": "wheel", "mass_force_N": "mass", "coupling_torque_Nm": "coupling", "sensor_a1_m_s2": "a1",
         "sensor_a2_m_s2": "a2"}
CUBIC_SCALE_M_S2 = 50.0                       # an accelerometer's own signal by this in its cube: the jaw's impacts, ~50 m/s^2
CHANNEL_SCALE_M_S2 = 10.0                     # the other accelerometer's signal by this: its event swing, ~10-50 m/s^2
RECORD_TIME = "t/T"          # the time in the record over its length (0 at sample 0, 1 at its end)


@dataclass(frozen=True)
class Term:
    name: str            # effect name in the library
    balance: str
    expression: str      # f, in model variables (docs/effects.md), dimensionless
    symbol: str          # f in symbols, for the law
    state: str           # the state it depends on: a speed, an angle, penetration, extension, te, constant
    group: str           # terms selected together (a harmonic's sine and cosine)
    variables: tuple     # model variables f names
    harmonic: tuple | None = None     # (angle variable, order, "sin"/"cos")
    recorded: tuple | None = None     # not simulated (event_design.py): ("sensor", signal, shape) with shape
                                      # ("harmonic", angle, order, fn) | ("speed", speed) | ("time",) | ("channel",
                                      # the other accelerometer) | ("cubic", itself); or ("time", the
                                      # constant term it modulates) -- a slow change of a constant in its balance
    center: str | None = None         # a speed's deviation from the recording's operating point (_speed_deviations):
                                      # the recorded speed whose mean is the term's CENTER parameter (set per
                                      # recording, centers()); written as a number in a proposal (with_center)
    knot: str | None = None           # a hinge's state (hinge_terms): the variable of HINGE_STATES whose knot is the
                                      # term's KNOT parameter (set per recording, hinge_knots()); written as a number
                                      # in a proposal (with_knot)

    @property
    def simulated(self) -> bool:
        """The term is a plug-in term the simulator runs (not a sensor's, not one of the time in the record)."""
        return self.recorded is None


def _speed_terms(balance, var, sym, scale_expr):
    b = SHORT[balance]
    x = f"({var} / {scale_expr})"
    return [Term(f"{PREFIX}{b}_{var}_sign", balance, f"smooth_sign({var}, 1e-3)", f"sgn({sym})", var,
                 f"{b}_{var}_sign", (var,)),
            Term(f"{PREFIX}{b}_{var}_1", balance, x, f"{sym}/{sym}ref", var, f"{b}_{var}_1", (var,)),
            Term(f"{PREFIX}{b}_{var}_2", balance, f"{x} * fabs({x})", f"({sym}/{sym}ref)·|{sym}/{sym}ref|", var,
                 f"{b}_{var}_2", (var,))]


def _harmonics(balance, var, sym, orders=(1, 2)):
    b = SHORT[balance]
    out = []
    for k in orders:
        arg = f"{k} * {var}" if k != 1 else var
        for fn in ("sin", "cos"):
            out.append(Term(f"{PREFIX}{b}_{var}_{fn}{k}", balance, f"{fn}({arg})", f"{fn}({k if k != 1 else ''}{sym})",
                            var, f"{b}_{var}_h{k}", (var,), (var, k, fn)))
    return out


def library(edges: bool = EDGES_IN_LIBRARY, memory: bool | None = None) -> tuple[Term, ...]:
    """The candidate terms, in a fixed order (``edges``: with the responses after the load pulse's edges,
    edge_terms; ``memory``: with the terms with a memory, memory_terms; None: MEMORY_IN_LIBRARY)."""
    memory = MEMORY_IN_LIBRARY if memory is None else memory
    ms, ws = f"({SPEED_REF})", f"({SPEED_REF})"
    t: list[Term] = []
    # the motor's load moment: its speed, the torque it delivers, both shafts' angles
    t += _speed_terms("motor_load_moment_pu", "omega1", "Ω₁", ms)
    t.append(Term(f"{PREFIX}motor_te", "motor_load_moment_pu", "te", "t_e", "te", "motor_te", ("te",)))
    t.append(Term(f"{PREFIX}motor_xdot", "motor_load_moment_pu", f"xdot / (wheel_radius_m * {SPEED_REF})",
                  "ẋ/(rΩ_mb)", "xdot", "motor_xdot", ("xdot",)))
    t += _harmonics("motor_load_moment_pu", "alpha1", "α₁")
    t += _harmonics("motor_load_moment_pu", "alpha2", "α₂", (1,))
    # the wheel torque: its speed, both shafts' angles
    t += _speed_terms("wheel_torque_Nm", "omega2", "Ω₂", ws)
    t += _harmonics("wheel_torque_Nm", "alpha2", "α₂")
    t += _harmonics("wheel_torque_Nm", "alpha1", "α₁", (1,))
    # the clutch's contact: a constant in contact (a preload), the penetration's powers, its rate, their product
    p = f"(penetration / {PENETRATION_SCALE_RAD})"
    q = f"(approach_speed / {APPROACH_SCALE_RAD_S})"
    t += [Term(f"{PREFIX}clutch_const", "clutch_torque_Nm", "1.0 + 0.0 * penetration", "1 (in contact)",
               "penetration", "clutch_const", ("penetration",)),
          Term(f"{PREFIX}clutch_pen_1", "clutch_torque_Nm", p, f"p/{PENETRATION_SCALE_RAD:g}", "penetration",
               "clutch_pen_1", ("penetration",)),
          Term(f"{PREFIX}clutch_pen_2", "clutch_torque_Nm", f"{p} * {p}", f"(p/{PENETRATION_SCALE_RAD:g})²",
               "penetration", "clutch_pen_2", ("penetration",)),
          Term(f"{PREFIX}clutch_rate", "clutch_torque_Nm", q, f"ṗ/{APPROACH_SCALE_RAD_S:g}", "penetration rate",
               "clutch_rate", ("approach_speed",)),
          Term(f"{PREFIX}clutch_pen_rate", "clutch_torque_Nm", f"{p} * {q}", "(p/p₀)·(ṗ/ṗ₀)", "penetration rate",
               "clutch_pen_rate", ("penetration", "approach_speed"))]
    # the coupling beside the jaw (a torque from the motor's shaft to the wheel's, in the gap and in contact, either
    # sign; the clutch's own balance is gated, 0 in the gap, never pulling): the slip across it (a slip coupling, a
    # drag between the halves; it was a wheel torque, which left the motor's side of it out) and the twist across it
    # (a flexible element in parallel with the jaw -- a spider, a leaf spring, a torsion bar -- its linear and cubic
    # stiffness one group: the twist Δ by the gap's half-width β is ±1 at the jaw's faces)
    t.append(Term(f"{PREFIX}coupling_rel_speed", "coupling_torque_Nm", f"rel_speed / {REL_SPEED_SCALE_RAD_S}",
                  f"(Ω₁−Ω₂)/{REL_SPEED_SCALE_RAD_S:g}", "rel_speed", "coupling_rel_speed", ("rel_speed",)))
    # the slip's sign: a dry friction across the coupling (a friction plate or a slipping disc beside the jaw, a brake
    # between the halves), as every other speed of the library has its sign (_speed_terms); smoothed over the
    # contact's closing speed (APPROACH_SCALE_RAD_S), where the slip crosses 0 in contact
    t.append(Term(f"{PREFIX}coupling_rel_sign", "coupling_torque_Nm",
                  f"smooth_sign(rel_speed, {APPROACH_SCALE_RAD_S!r})", "sgn(Ω₁−Ω₂)", "rel_speed", "coupling_rel_sign",
                  ("rel_speed",)))
    t += [Term(f"{PREFIX}coupling_twist_1", "coupling_torque_Nm", "delta / beta", "Δ/β", "delta", "coupling_twist",
               ("delta", "beta")),
          Term(f"{PREFIX}coupling_twist_3", "coupling_torque_Nm", "(delta / beta) * (delta / beta) * (delta / beta)",
               "(Δ/β)³", "delta", "coupling_twist", ("delta", "beta"))]
    # the clutch's contact locked to a shaft's angle: a torque in contact that comes and goes with the angle (the
    # gap's boundaries moving with it: a shaft at an angle, an eccentric jaw, a tooth of uneven pitch)
    t += _harmonics("clutch_torque_Nm", "alpha1", "α₁")
    # the load side ahead of its drive (a gate on the clutch's angle difference Δ: 1 while the jaw is off its drive
    # side, Δ·sgn Ω₁ < 0, crossing the gap or bearing on its far side; 0 while the motor drives it): a torque or force
    # that switches with the side the jaw bears on -- a load brake, a latch, a one-way clutch, a pawl. One-sided, so
    # that one group holds it (beside the balance's constant, sgn Δ would need two)
    for balance in ("motor_load_moment_pu", "wheel_torque_Nm", "mass_force_N"):
        b = SHORT[balance]
        t.append(Term(f"{PREFIX}{b}_overrun", balance,
                      f"0.5 * (1.0 - smooth_sign(delta, {JAW_SIDE_SMOOTHING_RAD!r}) * smooth_sign(omega1, 1.0))",
                      "[Δ·sgnΩ₁ < 0]", "penetration", f"{b}_overrun", ("delta", "omega1")))
    # the rim force (spring and absorber between wheel and mass): the extension's powers, its rate
    z = f"(z / {EXTENSION_SCALE_M})"
    v = f"(v / {RIM_SPEED_SCALE_M_S})"
    t += [Term(f"{PREFIX}rim_z_1", "rim_mass_force_N", z, f"z/{EXTENSION_SCALE_M:g}", "z", "rim_z_1", ("z",)),
          Term(f"{PREFIX}rim_z_2", "rim_mass_force_N", f"{z} * fabs({z})", f"(z/{EXTENSION_SCALE_M:g})·|z/{EXTENSION_SCALE_M:g}|",
               "z", "rim_z_2", ("z",)),
          Term(f"{PREFIX}rim_z_3", "rim_mass_force_N", f"{z} * {z} * {z}", f"(z/{EXTENSION_SCALE_M:g})³", "z",
               "rim_z_3", ("z",)),
          Term(f"{PREFIX}rim_v_1", "rim_mass_force_N", v, f"v/{RIM_SPEED_SCALE_M_S:g}", "v", "rim_v_1", ("v",)),
          Term(f"{PREFIX}rim_v_sign", "rim_mass_force_N", "smooth_sign(v, 1e-4)", "sgn(v)", "v", "rim_v_sign", ("v",))]
    # the mass: its speed's powers and sign
    xs = f"(wheel_radius_m * {SPEED_REF})"
    t += _speed_terms("mass_force_N", "xdot", "ẋ", xs)
    t += _harmonics("mass_force_N", "alpha2", "α₂", (1,))    # a roller or a link driven off the wheel shaft
    t += _harmonics("mass_force_N", "alpha1", "α₁", (1,))    # the frame shaken by the motor's shaft (a rotor's
                                                             # unbalance) felt by the carriage on its rails
    # the load pulse (the press stroke): a force or torque that comes and goes with it, in every balance but the
    # clutch's (a lag behind the pulse's edges is a change of the event's shape the pulse's own column holds in part)
    for balance, sym in (("motor_load_moment_pu", "m"), ("wheel_torque_Nm", "w"), ("mass_force_N", "x")):
        b = SHORT[balance]
        t.append(Term(f"{PREFIX}{b}_pulse", balance, f"load_moment_pu / {PULSE_SCALE_PU}",
                      f"T_L/{PULSE_SCALE_PU:g}", "load pulse", f"{b}_pulse", ("load_moment_pu",)))
    # the responses after the load pulse's edges (EDGE_DECAYS_S): in the same balances as the pulse itself -- a pump
    # that recharges an accumulator after each stroke, a cylinder switched by the press's valve, a hydraulic line's
    # pressure wave
    for balance in (("motor_load_moment_pu", "wheel_torque_Nm", "mass_force_N") if edges else ()):
        t += edge_terms(balance)
    # a constant in each balance (a load, a torque, a force that does not depend on the states)
    for balance, var in (("motor_load_moment_pu", "w1"), ("wheel_torque_Nm", "omega2"), ("mass_force_N", "xdot")):
        b = SHORT[balance]
        t.append(Term(f"{PREFIX}{b}_const", balance, f"1.0 + 0.0 * {var}", "1", "constant", f"{b}_const", (var,)))
    t += _contact_torque_products()
    t += _speed_deviations()
    if memory:
        t += memory_terms()
    return tuple(t)


# ------------------------------------------------------------------ a speed's deviation from its operating point
SPEED_DEVIATION_SCALE_RAD_S = 1.5   # a shaft speed's spread about its mean within a record (a 4 s foreign clean drive:
                                    # Omega1, Omega2 std 1.4, 1.6 rad/s; 1 %-99 % within -3.6 .. +2.1 rad/s)
CENTER = "center_rad_s"             # the deviation terms' second parameter: the operating point's speed [rad/s]
DEVIATIONS = (("motor_load_moment_pu", "omega1", "Ω₁", "omega1", "(omega1 - center_rad_s)", "omega1"),
              ("wheel_torque_Nm", "omega2", "Ω₂", "omega2", "(omega2 - center_rad_s)", "omega2"),
              ("mass_force_N", "xdot", "ẋ/r", "omega2", "(xdot / wheel_radius_m - center_rad_s)", "xdot"))


def _speed_deviations() -> list:
    """c · (Ω − Ω̄)/1.5 rad/s of each body's own speed (the motor's Ω₁, the wheel's Ω₂, the mass's ẋ/r), Ω̄ the
    recording's mean speed (the parameter CENTER, set per recording by centers(): the mass runs at r·Ω₂ on average).
    The library's other speed terms are by the base speed Ω_mb (157 rad/s): at the operating point Ω/Ω_mb is
    0.965 ± 0.01, a constant in all but 1 %, which the events cannot tell from the balance's constant (alike) and whose
    bounded coefficient moves the balance by at most 1 % of its bound with the speed. A load that follows the speed's
    swing about its operating point -- a speed loop (a servo on the carriage), a flywheel dragged by the shaft, an
    eddy-current or fan brake linearised at its speed, a governor -- is this term: its column is the speed's
    variation within a stroke, zero on average."""
    out = []
    for balance, var, sym, mean_of, dev, state in DEVIATIONS:
        b = SHORT[balance]
        out.append(Term(f"{PREFIX}{b}_{var}_dev", balance, f"{dev} / {SPEED_DEVIATION_SCALE_RAD_S!r}",
                        f"({sym}−Ω̄)/{SPEED_DEVIATION_SCALE_RAD_S:g}", state, f"{b}_{var}_dev", (var,), center=mean_of))
    return out


def centers(signals: dict) -> dict:
    """{recorded speed: its mean over the record [rad/s]} for the deviation terms' CENTER (omega2 for the mass: it
    runs at r·Ω₂ on average); a speed the recording lacks is left out (its terms keep the center 0: then they are the
    plain speed, still neutral at coefficient 0)."""
    return {k: float(np.mean(np.asarray(signals[k], dtype=float))) for k in ("omega1", "omega2") if k in signals}


def center_key(term: Term) -> str:
    return f"{term.name}.{CENTER}"


def with_center(term: Term, center_rad_s: float) -> Term:
    """The term with its center written as a number (a proposal's law and plug-in file)."""
    if term.center is None:
        return term
    num = f"{center_rad_s:.6g}"
    return dataclasses.replace(term, expression=term.expression.replace(CENTER, num),
                               symbol=term.symbol.replace("Ω̄", num), center=None)


# ------------------------------------------------------------------ hinges of a selected term's state (the form)
# A limiter caps the contact torque (a hinge of the penetration), a deadband or a saturation is a hinge of a speed, a
# brake with limits is a clipped function of a speed deviation: one fixed power or sign of a state holds none of them;
# a piecewise-linear function of the SAME state does, and stays linear in its coefficients. The proposal's form stage
# (proposal.FORM_STAGE) adds, for each selected simulated group whose state is one of these, max(0, s - k_j) and
# max(0, k_j - s) in the same balance at the knots k_j below, screens them in one batch and selects among them by the
# same rule as the library's terms.
# OFF (measured, docs/workbench.md "The proposed term's form", 30 Nov, branch `form`): on 8 development rows (7 where a
# term had been proposed in the right balance but not consistent, 1 wrong) consistent 0 of 8 with the stage as without;
# a hinge entered on 2 rows and helped neither: the od6 torque limiter's entered on the contact's OPENING speed
# (max(0, -0.47 - ṗ), z 5.1, stable 100 %) and the fitted terms then stopped the model crossing its backlash (the law
# was lost until the fallback below kept the one without the hinges), the od6 PWM brake's at its bound (+20 N*m *
# max(0, 148.5 - Ω₂)/1.5: 94 % -> 92 % explained); the other rows selected none (or had MAX_GROUPS already, or no
# simulated group); the proposal's CPU +3-9 s a recording (max 36 s), the library kernel's compile 41 -> 66 s once.
# Switched on (with the library's kernel then holding the hinges, gated: neutral at 0), the stage runs as written
HINGES_IN_PROPOSAL = False
KNOT = "knot"            # a hinge's knot parameter, in the state's own unit (set per recording: hinge_knots)
KNOT_TOKEN = "⟨k⟩"       # the knot's place in a hinge's symbol (with_knot writes the number there)
# the knots at these quantiles of the state over the recording's events: the middle (a deadband's or a switch's
# centre) and both tails (a limit, a cap, a saturation acting on the largest or smallest values). Three knots x two
# sides = 6 hinges a state: each is one more hypothesis the forward selection tests on ~16 events (CV_Z standard
# errors each), and one more simulated set (~0.5 s of CPU); a finer grid fits the knot to the events' noise
HINGE_QUANTILES = (0.1, 0.5, 0.9)


@dataclass(frozen=True)
class HingeState:
    balance: str
    state: str           # the Term.state of the library's terms it refines (and the hinge's own)
    expression: str      # the state in its unit, in model variables
    scale: float         # the hinge divided by this (the library's scale of the state): f of order 1
    symbol: str
    unit: str
    bounds: tuple        # the knot's bounds [unit]


# the scalar states of the model whose distribution over the events is known (proposal._state_samples: the recorded
# speeds, the carriage's speed from the recorded a2, the contact's penetration and its rate from the model's run);
# not the spring's extension and rate nor t_e (no output of the plant gives them), not the angles (their harmonics)
HINGE_STATES = {
    "omega1": HingeState("motor_load_moment_pu", "omega1", "omega1", SPEED_DEVIATION_SCALE_RAD_S, "Ω₁", "rad/s",
                         (-1000.0, 1000.0)),
    "omega2": HingeState("wheel_torque_Nm", "omega2", "omega2", SPEED_DEVIATION_SCALE_RAD_S, "Ω₂", "rad/s",
                         (-1000.0, 1000.0)),
    "rel_speed": HingeState("coupling_torque_Nm", "rel_speed", "rel_speed", REL_SPEED_SCALE_RAD_S, "(Ω₁−Ω₂)", "rad/s",
                            (-1000.0, 1000.0)),
    "xdot": HingeState("mass_force_N", "xdot", "(xdot / wheel_radius_m)", SPEED_DEVIATION_SCALE_RAD_S, "ẋ/r",
                       "rad/s", (-1000.0, 1000.0)),
    "penetration": HingeState("clutch_torque_Nm", "penetration", "penetration", PENETRATION_SCALE_RAD, "p", "rad",
                              (-1.0, 1.0)),
    "approach_speed": HingeState("clutch_torque_Nm", "penetration rate", "approach_speed", APPROACH_SCALE_RAD_S, "ṗ",
                                 "rad/s", (-1000.0, 1000.0)),
}
HINGE_SIDES = (("above", 1.0), ("below", -1.0))


def hinge_terms() -> tuple[Term, ...]:
    """max(0, ±(s - k_j))/scale for every state of HINGE_STATES in its balance, each side, each knot slot j (the knot a
    parameter, KNOT); each term its own group. Not screened with the library: the proposal's form stage screens the
    hinges of the selected groups' states only (hinges_for)."""
    out = []
    for var, hs in HINGE_STATES.items():
        b = SHORT[hs.balance]
        for side, sgn in HINGE_SIDES:
            d = f"({hs.expression} - {KNOT})" if sgn > 0 else f"({KNOT} - {hs.expression})"
            expr = f"0.5 * ({d} + fabs({d})) / {hs.scale!r}"
            sym = (f"max(0, {hs.symbol} − {KNOT_TOKEN})" if sgn > 0 else f"max(0, {KNOT_TOKEN} − {hs.symbol})") \
                + f"/{hs.scale:g}"
            for j in range(len(HINGE_QUANTILES)):
                name = f"{PREFIX}{b}_{var}_hinge_{side}{j}"
                out.append(Term(name, hs.balance, expr, sym, hs.state, name, tuple(_variables_of(hs.expression)),
                                knot=var))
    return tuple(out)


def _variables_of(expr: str) -> list:
    return [v for v in re.findall(r"[A-Za-z_][A-Za-z_0-9]*", expr) if v not in ("fabs",)]


def hinge_slot(term: Term) -> int:
    """The knot slot j of a hinge term (its knot is HINGE_QUANTILES[j] of its state)."""
    return int(term.name[-1])


def hinge_states_of(term: Term) -> list:
    """The HINGE_STATES a selected library term refines: in its own balance, its own state (a clutch term: every state
    of the contact it names -- (p/p₀)(ṗ/ṗ₀) both). Not a harmonic, a sensor's, a slow change or a hinge itself."""
    if not term.simulated or term.harmonic is not None or term.knot is not None:
        return []
    out = []
    for var, hs in HINGE_STATES.items():
        if hs.balance != term.balance:
            continue
        if term.state == hs.state or (term.balance == "clutch_torque_Nm" and hs.expression in term.variables):
            out.append(var)
    return out


def hinges_for(states) -> list:
    """The hinge terms of these states (hinge_terms), in library order."""
    states = set(states)
    return [t for t in hinge_terms() if t.knot in states]


def hinge_knots(samples: dict) -> dict:
    """{state: its knots [unit]}: HINGE_QUANTILES of each state's samples over the recording's events (``samples``:
    state -> 1-D array; a state with fewer than 100 samples is left out)."""
    return {v: [float(q) for q in np.quantile(np.asarray(x, dtype=float), HINGE_QUANTILES)]
            for v, x in samples.items() if v in HINGE_STATES and np.size(x) >= 100}


def knot_key(term: Term) -> str:
    return f"{term.name}.{KNOT}"


def with_knot(term: Term, knot: float) -> Term:
    """The hinge with its knot written as a number (a proposal's law and plug-in file)."""
    if term.knot is None:
        return term
    num = f"{knot:.6g}"
    return dataclasses.replace(term, expression=term.expression.replace(KNOT, f"({num})"),
                               symbol=term.symbol.replace(KNOT_TOKEN, num), knot=None)


# ------------------------------------------------------------------ terms with a memory (issue 31, part 2)
# the first-order lags the plant carries (plant/lags.py: the motor, wheel and mass speeds, the clutch's penetration,
# the load moment input, each at LAG_TIMES_S = 10 and 100 ms; the infinite time constant is the speed deviation above)
MEMORY_IN_LIBRARY = False    # off by default: on the development rows they won one right balance (the sealed5 eddy
                             # brake, now consistent) and lost two (outside_dev3's a2 deadband to a wheel-speed memory,
                             # outside_dev6's torque limiter: nothing stable with them, the clutch's penetration rate
                             # without), and the proposal's CPU rose to 52-67 s (goal <= 60); library(memory=True) has
                             # them, and the proposal runs it in a second pass where the first proposes nothing
                             # (proposal.MEMORY_SECOND_PASS; docs/workbench.md "Terms with memory")
MEMORY_SPEEDS = (("motor_load_moment_pu", "omega1", "Ω₁", f"{SPEED_DEVIATION_SCALE_RAD_S!r}"),
                 ("wheel_torque_Nm", "omega2", "Ω₂", f"{SPEED_DEVIATION_SCALE_RAD_S!r}"),
                 ("mass_force_N", "xdot", "ẋ", f"(wheel_radius_m * {SPEED_DEVIATION_SCALE_RAD_S!r})"))


def memory_terms() -> list:
    """Terms of the first-order lags L_tau (plant/lags.py), each balance's two time constants ONE group (selected
    together, two coefficients: a memory between 10 and 100 ms is within a few per cent a combination of the two):

    - (q - L_tau(q))/scale of the balance's own body's speed (Ω₁ in the motor's, Ω₂ in the wheel's, ẋ in the mass's;
      scale the speed's spread 1.5 rad/s, r·1.5 m/s for the mass): a hidden body of speed L on a viscous coupling
      (a flywheel on a creeping belt, a fan, a governor's sleeve) loads its shaft with c·(q - L), L -> q with
      tau = J/c; also a speed loop's delay, q - L being the speed's recent change;
    - (p - L_tau(p))/p₀ of the clutch's penetration in its own balance (in contact): a relaxing (viscoelastic) contact,
      stiffer in an impact than under a steady load -- the Maxwell branch k·(p - q), q -> p with tau;
    - L_tau(T_L)/1.6 of the load moment input (the strokes' pulse train) in the motor's, the wheel's and the mass's:
      a force that follows the stroke through its own lag (a coil's field current, a valve and a line filling).
    Not lags of a product (a softening that follows the dissipated power), nor a one-way or a play's memory (only in
    part: measured, docs/workbench.md "Terms with memory")."""
    out = []
    for balance, var, sym, scale in MEMORY_SPEEDS:
        b = SHORT[balance]
        for tau in LAG_TIMES_S:
            ms = f"{tau * 1e3:g}"
            lag = lag_name(var, tau)
            out.append(Term(f"{PREFIX}{b}_{var}_memory_{ms}ms", balance, f"({var} - {lag}) / {scale}",
                            f"({sym}−lag{ms}ms({sym}))/{SPEED_DEVIATION_SCALE_RAD_S:g}", var, f"{b}_{var}_memory",
                            (var, lag)))
    for tau in LAG_TIMES_S:
        ms = f"{tau * 1e3:g}"
        lag = lag_name("penetration", tau)
        out.append(Term(f"{PREFIX}clutch_pen_memory_{ms}ms", "clutch_torque_Nm",
                        f"(penetration - {lag}) / {PENETRATION_SCALE_RAD!r}",
                        f"(p−lag{ms}ms(p))/{PENETRATION_SCALE_RAD:g}", "penetration", "clutch_pen_memory",
                        ("penetration", lag)))
    for balance in ("motor_load_moment_pu", "wheel_torque_Nm", "mass_force_N"):
        b = SHORT[balance]
        for tau in LAG_TIMES_S:
            ms = f"{tau * 1e3:g}"
            lag = lag_name("load_moment", tau)
            out.append(Term(f"{PREFIX}{b}_pulse_memory_{ms}ms", balance, f"{lag} / {PULSE_SCALE_PU}",
                            f"lag{ms}ms(T_L)/{PULSE_SCALE_PU:g}", "load pulse", f"{b}_pulse_memory", (lag,)))
    return out


# ------------------------------------------------------------------ products of the contact torque (issue 31, part 2)
CONTACT_SIGN_SPEED_RAD_S = 1.0    # sgn(Ω) smoothed over this speed, as the overrun gate's: the drive runs at > 140


def _contact_torque_products() -> list:
    """The clutch's contact torque T_c (the model variable ``contact_torque_Nm``, by T_b: ~0.5-1.75 at the operating
    point) in the balances after the clutch's -- products of the contact (penetration and its rate, through the
    contact law) with a speed's sign, where the units allow:

    - the motor's and the wheel's: |T_c|/T_b · sgn(Ω) of the balance's own shaft -- a friction that the transmitted
      torque presses on (a thrust bearing under the jaw's axial push, a seal or a spline loaded by the torque); its
      magnitude follows the contact, its sign opposes the own shaft's motion. The other shaft's sign is left out: the
      drive never reverses within a record, so sgn Ω₁ = sgn Ω₂ and the data cannot tell them apart (they would only
      add to the selection's multiple tests);
    - the mass's: T_c/T_b, signed -- the torque's reaction through the frame the mass runs on (a frame that twists
      under the clutch's torque and pushes the carriage).

    Not in the clutch's own balance (its terms make T_c) nor the rim force's (between wheel and mass, a spring's:
    no mechanism presses it by the clutch's torque). A small set on purpose: each group costs the selection a test."""
    tc = "(fabs(contact_torque_Nm) / base_torque_Nm)"
    out = []
    for balance, speed, sym in (("motor_load_moment_pu", "omega1", "Ω₁"), ("wheel_torque_Nm", "omega2", "Ω₂")):
        b = SHORT[balance]
        out.append(Term(f"{PREFIX}{b}_contact_{speed}_sign", balance,
                        f"{tc} * smooth_sign({speed}, {CONTACT_SIGN_SPEED_RAD_S!r})", f"|T_c|/T_b·sgn({sym})",
                        "penetration", f"{b}_contact_{speed}_sign", ("contact_torque_Nm", "base_torque_Nm", speed)))
    out.append(Term(f"{PREFIX}mass_contact", "mass_force_N", "contact_torque_Nm / base_torque_Nm", "T_c/T_b",
                    "penetration", "mass_contact", ("contact_torque_Nm", "base_torque_Nm")))
    return out


EDGES = (("rise", "pulse_time_s", "t_r"), ("fall", "pulse_off_time_s", "t_f"))


def edge_terms(balance: str) -> list:
    """The responses after each edge of the load pulse in ``balance``: per edge one group, exp(-t/tau) for every tau of
    EDGE_DECAYS_S (t the time since that edge, a model variable held over each step)."""
    b = SHORT[balance]
    out = []
    for edge, var, sym in EDGES:
        for tau in EDGE_DECAYS_S:
            out.append(Term(f"{PREFIX}{b}_{edge}_{tau * 1e3:g}ms", balance,
                            f"exp(-fmin({var} / {tau!r}, {EDGE_EXP_CAP!r}))", f"e^(−{sym}/{tau * 1e3:g} ms)",
                            "load pulse", f"{b}_{edge}", (var,)))
    return out


def recorded_terms() -> tuple[Term, ...]:
    """The terms computed on the recorded events instead of simulated (event_design.py): what a sensor adds to a1 or
    a2 -- harmonics of both shafts' angles (orders 1, 2), the shafts' speeds, a drift with the time in the record, the
    other channel's signal (crosstalk), the channel's own cube (a compressing sensor), its own running integral
    (an AC-coupled sensor's residual) -- and a slow change (linear in the time in the record) of each balance's constant."""
    out: list[Term] = []
    for sig in ("a1", "a2"):
        balance = f"sensor_{sig}_m_s2"
        b = SHORT[balance]
        for var, sym in (("alpha1", "α₁"), ("alpha2", "α₂")):
            for k in (1, 2):
                for fn in ("sin", "cos"):
                    out.append(Term(f"{PREFIX}{b}_{var}_{fn}{k}", balance, f"{fn}({k} * {var})",
                                    f"{fn}({k if k != 1 else ''}{sym})", var, f"{b}_{var}_h{k}", (var,),
                                    (var, k, fn), ("sensor", sig, ("harmonic", var, k, fn))))
        for var, sym in (("omega1", "Ω₁"), ("omega2", "Ω₂")):
            out.append(Term(f"{PREFIX}{b}_{var}", balance, f"({var} - mean) / {REL_SPEED_SCALE_RAD_S:g}",
                            f"({sym}−mean)/{REL_SPEED_SCALE_RAD_S:g}", var, f"{b}_{var}", (var,), None,
                            ("sensor", sig, ("speed", var))))
        out.append(Term(f"{PREFIX}{b}_time", balance, RECORD_TIME, RECORD_TIME, "time", f"{b}_time", (), None,
                        ("sensor", sig, ("time",))))
        # the other channel leaking into this one (a shared cable, a multiplexed ADC, a cross-axis sensitivity)
        other = "a2" if sig == "a1" else "a1"
        sym = "a₂" if other == "a2" else "a₁"
        out.append(Term(f"{PREFIX}{b}_from_{other}", balance, f"{other} / {CHANNEL_SCALE_M_S2:g}",
                        f"{sym}/{CHANNEL_SCALE_M_S2:g}", other, f"{b}_from_{other}", (), None,
                        ("sensor", sig, ("channel", other))))
        # the channel's own odd nonlinearity (a sensing element or an amplifier compressing large accelerations)
        own = "a₁" if sig == "a1" else "a₂"
        out.append(Term(f"{PREFIX}{b}_cubed", balance, f"({sig} / {CUBIC_SCALE_M_S2:g})^3",
                        f"({own}/{CUBIC_SCALE_M_S2:g})³", sig, f"{b}_cubed", (), None, ("sensor", sig, ("cubic", sig))))
        out += _sensor_dynamics(sig)
    for c in library():
        if c.state == "constant":
            b = SHORT[c.balance]
            out.append(Term(f"{PREFIX}{b}_time", c.balance, RECORD_TIME, RECORD_TIME, "time", f"{b}_time", (), None,
                            ("time", c.name)))
    return tuple(out)


# ------------------------------------------------------------------ a sensor's own dynamics (issue 31, part 2)
INTEGRAL_TIME_SCALE_S = 0.1   # the running integral of a channel by this time [s]: the corner of an AC-coupled sensor
                              # (piezoelectric charge amplifiers, IEPE couplers: 0.5-5 Hz, tau = 1/(2 pi f_c) = 0.03-0.3 s)


def _sensor_dynamics(sig: str) -> list:
    """A sensor that does not read its acceleration flat: a first-order high-pass (AC coupling) of corner
    f_c = 1/(2 pi tau) reads y = a - LP_tau(a), and y' = a' - y/tau gives a = y + (1/tau) ∫y dt (+ a constant): the
    residual it leaves against the model, y - a, is -(1/tau) times the running integral of the RECORDED signal, for any
    corner, linear in the one coefficient -1/tau (by INTEGRAL_TIME_SCALE_S and CHANNEL_SCALE_M_S2 here). Exact on the
    recorded signal, where a low-pass of fixed time constants is not: the low-pass acts on what the sensor saw, which
    the recording does not hold (measured on a 1.5 Hz charge amplifier: a grid of three time constants on the recorded
    a1 named the right channel, 97 % explained, but outside the noise band -- LP(y) = LP(a) - LP(LP(a)), ~35 % off
    at the 4 Hz pulse train). The integral's mean and linear trend over the record are removed: the high-pass passes
    no DC, so a ramp can only come from an offset or a drift of the channel, which other terms hold."""
    balance = f"sensor_{sig}_m_s2"
    b = SHORT[balance]
    own = "a₁" if sig == "a1" else "a₂"
    return [Term(f"{PREFIX}{b}_integral", balance,
                 f"∫{sig} dt / ({INTEGRAL_TIME_SCALE_S:g} s · {CHANNEL_SCALE_M_S2:g})",
                 f"∫{own}dt/({INTEGRAL_TIME_SCALE_S:g}s·{CHANNEL_SCALE_M_S2:g})", sig, f"{b}_integral", (), None,
                 ("sensor", sig, ("integral", sig)))]


def by_name() -> dict:
    return {t.name: t for t in library() + recorded_terms() + hinge_terms()}


def groups(terms=None) -> dict:
    """group -> [term names], in library order (``terms``: default the simulated library)."""
    out: dict = {}
    for t in (library() if terms is None else terms):
        out.setdefault(t.group, []).append(t.name)
    return out


def coefficient_name(term: Term) -> str:
    unit = BALANCES[term.balance][0]
    return {"p.u.": "coefficient_pu", "N*m": "coefficient_Nm", "N": "coefficient_N"}[unit]


def _class_source(cls_name, name, balance, description, params, args, body) -> str:
    plist = ",\n                  ".join(params)
    return (f"class {cls_name}(Effect):\n"
            f"    name = {name!r}\n"
            f"    balance = {balance!r}\n"
            f"    description = {description!r}\n"
            f"    parameters = ({plist},)\n\n"
            f"    @staticmethod\n"
            f"    def term({', '.join(args)}):\n"
            f"        return {body}\n")


HEADER = ("from backlash_monitor.plant.effects import Effect, Parameter\n"
          "from backlash_monitor.plant.mathlib import cos, exp, fabs, fmin, sin, smooth_sign  # noqa: F401\n\n\n")


def _variables(expr: str, extra=()) -> list:
    # deferred: backlash_monitor.plant (numba) costs ~1000 ms at start-up (python -X importtime, 29 Nov)
    from backlash_monitor.plant.effects import MODEL_VARIABLES
    names = set(re.findall(r"[A-Za-z_][A-Za-z_0-9]*", expr))
    return [v for v in MODEL_VARIABLES if v in names] + list(extra)


def library_source(memory: bool | None = None) -> str:
    """The library as plug-in source (``memory``: as library's)."""
    parts = ['"""The candidate terms of a proposal (backlash_monitor/workbench/candidate_terms.py), generated."""\n'
             + HEADER]
    for i, t in enumerate(library(memory=memory) + (hinge_terms() if HINGES_IN_PROPOSAL else ())):
        unit, _, bound = BALANCES[t.balance]
        c = coefficient_name(t)
        params = [f"Parameter({c!r}, {unit!r}, 0.0, ({-bound!r}, {bound!r}), 'the coefficient')"]
        extra = []
        if t.center is not None:     # the operating point's speed, set per recording (centers)
            params.append(f"Parameter({CENTER!r}, 'rad/s', 0.0, (-1000.0, 1000.0), 'the mean speed')")
            extra = [CENTER]
        if t.knot is not None:       # a hinge's knot, set per recording (hinge_knots)
            hs = HINGE_STATES[t.knot]
            params.append(f"Parameter({KNOT!r}, {hs.unit!r}, 0.0, {hs.bounds!r}, 'the knot')")
            extra = [KNOT]
        parts.append(_class_source(f"Cand{i}", t.name, t.balance, f"{BALANCE_WORDS[t.balance]} += c * {t.symbol}",
                                   params, _variables(t.expression) + [c] + extra, f"{c} * ({t.expression})"))
    return "\n\n".join(parts)


def cache_dir() -> Path:
    base = os.environ.get("BACKLASH_MONITOR_KERNEL_CACHE")
    root = Path(base) if base else Path.home() / ".cache" / "backlash_monitor"
    d = root / "proposals"
    d.mkdir(parents=True, exist_ok=True)
    return d


def library_file(memory: bool | None = None) -> Path:
    """The library as a plug-in file in the cache (named by its content; written once, atomically; ``memory``: as
    library's)."""
    src = library_source(memory)
    path = cache_dir() / f"candidate_terms_{hashlib.sha256(src.encode()).hexdigest()[:16]}.py"
    if not path.exists():
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_text(src)
        os.replace(tmp, path)
    return path


# --------------------------------------------------------------------------------------------- a proposal's forms
@dataclass
class ProposedPiece:
    """One selected group with its fitted coefficients: plain terms (one coefficient each) or a harmonic (amplitude and
    phase from its sine/cosine pair: c_s sin(k a) + c_c cos(k a) = A sin(k a + phi))."""
    terms: tuple            # Term objects of the group
    coefficients: tuple     # fitted, one per term
    uncertainties: tuple
    alike: tuple = ()       # the first Term of each group the data cannot tell from this one (proposal.alike_groups)

    @property
    def balance(self) -> str:
        return self.terms[0].balance

    @property
    def harmonic(self) -> bool:
        return self.terms[0].harmonic is not None

    def amplitude_phase(self) -> tuple[float, float, float]:
        """(A, phi, sigma_A) of a harmonic pair."""
        cs = dict(zip((t.harmonic[2] for t in self.terms), self.coefficients))
        us = dict(zip((t.harmonic[2] for t in self.terms), self.uncertainties))
        s, c = cs.get("sin", 0.0), cs.get("cos", 0.0)
        a = math.hypot(s, c)
        sig = math.sqrt(((s * us.get("sin", 0.0)) ** 2 + (c * us.get("cos", 0.0)) ** 2)) / a if a > 0 else 0.0
        return a, math.atan2(c, s), sig

    def law(self) -> str:
        unit = BALANCES[self.balance][0].replace("*", "·")
        if self.harmonic:
            a, phi, _ = self.amplitude_phase()
            var, k, _ = self.terms[0].harmonic
            sym = {"alpha1": "α₁", "alpha2": "α₂"}[var]
            return f"{a:.3g} {unit} · sin({'' if k == 1 else k}{sym} {'+' if phi >= 0 else '−'} {abs(phi):.2f})"
        return " ".join(f"{c:+.3g} {unit} · {t.symbol}" for t, c in zip(self.terms, self.coefficients))

    def state(self) -> str:
        return self.terms[0].state

    def alike_text(self) -> str:
        """" (alike: ...)" naming the groups that would fit the events as well, or ""."""
        if not self.alike:
            return ""
        return " (as well: " + ", ".join(f"{BALANCE_WORDS[t.balance]} · {t.symbol}" for t in self.alike) + ")"


def proposal_law(pieces) -> str:
    """The law in words and symbols, one line per balance: "wheel torque += 2.9 N·m · sin(α₂ + 0.31)"."""
    by: dict = {}
    for p in pieces:
        by.setdefault(p.balance, []).append(p.law())
    return "; ".join(f"{BALANCE_WORDS[b]} += " + " ".join(
        (x if i == 0 or x.startswith(("+", "-", "−")) else "+ " + x) for i, x in enumerate(laws))
        for b, laws in by.items())


def proposal_source(pieces, name: str = "proposed_term") -> tuple[str, dict]:
    """A plug-in file (docs/effects.md) holding the proposal: one Effect per balance, its parameters the fitted
    coefficients (a harmonic as amplitude and phase), each bounded, its default 0 (neutral; add-effect sets the
    fitted values). -> (source, {effect name: {parameter: fitted value}})."""
    by: dict = {}
    for p in pieces:
        if p.terms[0].simulated:       # a sensor's term or one of the time in the record has no plug-in form yet
            by.setdefault(p.balance, []).append(p)
    own = [p for p in pieces if own_signal_sensor_piece(p)]     # but a channel's own cube: a sensor stage
    if not by and not own:
        return "", {}
    parts = ['"""A term the workbench proposed from a residual (docs/workbench.md, "Proposing a missing term").\n'
             "Read it, edit it: each parameter is bounded, its default 0 does nothing; the fitted values are in the\n"
             'model version add-effect --accept-proposal writes."""\n' + HEADER]
    values: dict = {}
    for j, (balance, pieces_b) in enumerate(by.items()):
        unit, _, bound = BALANCES[balance]
        params, body, args = [], [], set()
        ename = f"{name}_{SHORT[balance]}"
        vals = {}
        for i, p in enumerate(pieces_b):
            if p.harmonic:
                a, phi, _ = p.amplitude_phase()
                var, k, _ = p.terms[0].harmonic
                an, ph = f"amplitude{i}_{coefficient_name(p.terms[0]).split('_', 1)[1]}", f"phase{i}_rad"
                params += [f"Parameter({an!r}, {unit!r}, 0.0, (0.0, {bound!r}), 'amplitude')",
                           f"Parameter({ph!r}, 'rad', 0.0, ({-math.pi!r}, {math.pi!r}), 'phase')"]
                arg = var if k == 1 else f"{k} * {var}"
                body.append(f"{an} * sin({arg} + {ph})")
                args |= {var}
                vals[an], vals[ph] = a, phi
            else:
                for m, (term, coef) in enumerate(zip(p.terms, p.coefficients)):   # a group of several: each its own
                    cn = f"c{i}{'' if len(p.terms) == 1 else chr(97 + m)}_{coefficient_name(term).split('_', 1)[1]}"
                    params.append(f"Parameter({cn!r}, {unit!r}, 0.0, ({-bound!r}, {bound!r}), {term.symbol!r})")
                    body.append(f"{cn} * ({term.expression})")
                    args |= set(_variables(term.expression))
                    vals[cn] = coef
        # deferred: backlash_monitor.plant (numba) costs ~1000 ms at start-up (python -X importtime, 29 Nov)
        from backlash_monitor.plant.effects import MODEL_VARIABLES
        arglist = [v for v in MODEL_VARIABLES if v in args] + [q.split("'")[1] for q in params]
        law = proposal_law(pieces_b)
        parts.append(_class_source(f"Proposed{j}", ename, balance, law, params, arglist, " + ".join(body)))
        values[ename] = vals
    for j, sig in enumerate(sorted({p.terms[0].recorded[1] for p in own})):
        ename = f"{name}_{sig}"
        pieces_s = [p for p in own if p.terms[0].recorded[1] == sig]
        params, body, vals = [], [], {}
        for i, p in enumerate(pieces_s):
            cn = f"c{i}_m_s2"
            params.append(f"Parameter({cn!r}, 'm/s^2', 0.0, ({-BALANCES[p.balance][2]!r}, "
                          f"{BALANCES[p.balance][2]!r}), {p.terms[0].symbol!r})")
            body.append(f"values[{cn!r}][:, None] * (a / {CUBIC_SCALE_M_S2!r}) ** 3")
            vals[cn] = float(p.coefficients[0])
        parts.append(_sensor_class_source(f"ProposedSensor{j}", ename, sig, proposal_law(pieces_s), params,
                                          " + ".join(body)))
        values[ename] = vals
    return "\n\n".join(parts), values


def own_signal_sensor_piece(piece) -> bool:
    """A proposed sensor's term of its own signal alone (the channel's cube): a plug-in sensor stage holds it (a
    stage sees only its signal: a term of the drive's states or of the other channel has no plug-in form)."""
    return all(t.recorded is not None and t.recorded[0] == "sensor" and t.recorded[2] == ("cubic", t.recorded[1])
               for t in piece.terms)


def _sensor_class_source(cls_name, name, signal, description, params, body) -> str:
    """A plug-in sensor stage (docs/effects.md: kind "sensor", apply) adding ``body`` to ``signal``, after the
    built-in low-pass, gain and bias (order 3)."""
    plist = ",\n                  ".join(params)
    return (f"class {cls_name}(Effect):\n"
            f"    name = {name!r}\n"
            f"    balance = 'sensor_a1_a2'\n"
            f"    kind = 'sensor'\n"
            f"    order = 3\n"
            f"    description = {description!r}\n"
            f"    parameters = ({plist},)\n\n"
            f"    @staticmethod\n"
            f"    def apply(signal, a, values, state, h):\n"
            f"        if signal != {signal!r}:\n"
            f"            return a\n"
            f"        return a + {body}\n")
