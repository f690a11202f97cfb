"""Mechanisms OUTSIDE the project's effect catalogue (issue 31, part 4): what a real drive may have that nobody
wrote down -- not a catalogue family in another functional form (those are in :mod:`forms`), but another kind of
term altogether. Each is a :class:`OutsideForm` with bounded named parameters, the family tag ``None``, and its
TRUTH for a bench that checks a proposed term:

- ``balance``: where the term acts, one of :data:`BALANCES` (the balances the workbench's proposal puts terms
  into: the motor's load moment, the wheel torque, the clutch torque, the mass force, or a sensor);
- ``depends_on``: the drive states the term reads, from :data:`STATES`;
- ``law(p)``: the law in words and symbols with the parameter values;
- ``plugin(p)``: where the law is one a user can write as a plug-in of the documented form (docs/effects.md), the
  plug-in's source (else None).

The development half is :mod:`outside_dev`; the sealed half :mod:`outside_sealed` (not to be read by whoever
tunes the proposal; run once, so now development data too). The second set: :mod:`outside_dev2` (development) and
:mod:`outside_sealed2` (sealed: run once, development data now). The third set: :mod:`outside_dev3` (development)
and :mod:`outside_sealed3` (sealed: not to be read by whoever tunes the proposal).

Physics terms act through the compiled kernel's generic OUTSIDE slots (kernel.outside_terms): each slot adds
``amplitude * f1(x1) * f2(x2)`` to one balance, x a drive quantity (kernel.XS_*), f a shape (kernel.XF_*). A
mechanism may fill several slots (a law with two harmonics). Sensor mechanisms act on the recorded a1/a2 in the
sensor chain, with the run's internal signals (the angles, the physical accelerations).
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Form

# the five balances of the workbench's proposal (issue 31): exactly these names
BALANCES = ("motor_load_moment", "wheel_torque", "clutch_torque", "mass_force", "sensor")
# the drive states a term may depend on; motor_acceleration and mass_acceleration only for sensor terms that read
# a1 (= r*dOmega1/dt) or a2 (= dv/dt) themselves
STATES = ("motor_speed", "wheel_speed", "rim_speed", "mass_speed", "clutch_penetration", "spring_extension",
          "motor_angle", "wheel_angle", "load_pulse", "time", "motor_acceleration", "mass_acceleration")
_BALANCE_CODE = {"motor_load_moment": K.XB_MOTOR_LOAD, "wheel_torque": K.XB_WHEEL, "clutch_torque": K.XB_CLUTCH,
                 "mass_force": K.XB_MASS}


class OutsideForm(Form):
    """A mechanism outside the catalogue: family None, its balance and states recorded as its truth."""
    family = None
    balance = ""                 # one of BALANCES
    depends_on: tuple = ()       # names of STATES
    half = ""                    # "dev" | "sealed" | "dev2" | "sealed2" | ... | "dev6" | "sealed6"
    uses_states = False          # a sensor form that reads the run's internal signals

    def law(self, p: dict) -> str:
        """The law with the parameter values, in words and symbols."""
        raise NotImplementedError

    def plugin(self, p: dict):
        """The source of a plug-in (docs/effects.md) with this exact law, or None."""
        return None


def set_relay(b, name: str, selector: int, on: float, off: float, on_name: str = "", off_name: str = "") -> None:
    """Set the drive's one relay (K.XS_RELAY: on above ``on``, off below ``off``) on the state ``selector``, for the
    form ``name``; ``on_name``/``off_name``: the form's parameters giving them, named when off is above on (no check
    without them). A second relay in one recording is refused."""
    if on_name and off > on:
        raise ValueError(f"{name}: {off_name} {off} is above {on_name} {on}; allowed: {off_name} <= {on_name}")
    if b.P[K.P_RLYSEL] != 0.0:
        raise ValueError(f"{name}: a second relay in one recording; allowed: one")
    b.P[K.P_RLYSEL] = selector
    b.P[K.P_RLYON], b.P[K.P_RLYOFF] = on, off


def add_term(b, balance: str, amplitude: float, factor1=(K.XS_ONE, K.XF_ONE, 0.0, 0.0, 0.0),
             factor2=(K.XS_ONE, K.XF_ONE, 0.0, 0.0, 0.0), nonperiodic: bool = False) -> None:
    """Fill the next free outside slot of the drive's parameter vector: ``amplitude * f1 * f2`` into ``balance``;
    a factor is (selector XS_*, shape XF_*, a, b, c). ``nonperiodic``: a term locked to an angle or to the time (left
    out of the settled start's period map, like the ripples)."""
    i = int(b.P[K.P_XN])
    if i >= K.OUTSIDE_SLOTS:
        raise ValueError(f"outside mechanisms: more than {K.OUTSIDE_SLOTS} terms in one recording; allowed: fewer "
                         "outside mechanisms per recording")
    o = K.P_X0 + i * K.OUTSIDE_STRIDE
    b.P[o + K.X_BAL] = _BALANCE_CODE[balance]
    b.P[o + K.X_AMP] = amplitude
    b.P[o + K.X_NP] = 1.0 if nonperiodic else 0.0
    for off, (sel, shape, a, bb, c) in ((K.X_S1, factor1), (K.X_S2, factor2)):
        b.P[o + off] = sel
        b.P[o + off + 1] = shape
        b.P[o + off + 2], b.P[o + off + 3], b.P[o + off + 4] = a, bb, c
    b.P[K.P_XN] = i + 1


def wrap_phase(x: float) -> float:
    """An angle in (-pi, pi]."""
    return float(np.angle(np.exp(1j * x)))
