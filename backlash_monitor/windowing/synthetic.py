"""Cheap synthetic angle-difference records with exactly known entries (for tests and drift runs).

One period (``period_s``): contact at the + side, Delta = beta + defl_hi; at ``t_on`` a load pulse
starts and Delta leaves it as a parabola (relative acceleration ``accel``) down to the - contact
-(beta + defl_lo) (a hard stop); at ``t_on + pulse_s`` it leaves the - contact up again as a parabola
back to the + contact.  ``departures`` are the samples where the parabolas start, ``crossings`` the
samples nearest to where Delta has moved ``crossing_rad`` (default 1.5e-3 rad, the detector's
contact_deflection_rad) from the contact it left (exact: departure + sqrt(2*crossing_rad/accel); what the
contact-loss trigger reports as the entry) and ``entries`` the first samples with |Delta| < beta (what the
paper trigger and the plant call the true entry).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SyntheticPeriod", "synthetic_period", "tile_events", "tile_record"]


@dataclass
class SyntheticPeriod:
    delta: np.ndarray          # (n,) rad
    w_rel: np.ndarray          # (n,) rad/s, the exact derivative of delta
    departures: list           # [(sample, kind)]
    entries: list              # [(sample, kind)] first sample with |delta| < beta
    beta: float
    sample_period_s: float
    crossings: list = None     # [(sample, kind)] |delta - contact| = crossing_rad after each departure


def _traverse(t, t0, start, stop, accel):
    """Parabola from ``start`` towards ``stop`` starting at t0 with zero speed; clamps at ``stop``."""
    s = np.sign(stop - start)
    tau = np.clip(t - t0, 0.0, None)
    x = start + s * 0.5 * accel * tau ** 2
    v = s * accel * tau
    done = (x - stop) * s >= 0
    return np.where(done, stop, x), np.where(done, 0.0, v)


def synthetic_period(width_m: float = 0.005, radius_m: float = 0.15, sample_period_s: float = 2e-5,
                     period_s: float = 0.25, t_on_s: float = 0.05, pulse_s: float = 0.06,
                     accel: float = 120.0, defl_hi: float = 1.5e-3, defl_lo: float = 3e-3,
                     bounce_rad: float = 0.0, bounce_s: float = 0.004,
                     crossing_rad: float = 1.5e-3) -> SyntheticPeriod:
    """One period of the synthetic record.  ``bounce_rad`` > 0 adds a contact bounce after each impact
    (Delta comes back into the zone by that much, a half sine of ``bounce_s``)."""
    n = int(round(period_s / sample_period_s))
    t = np.arange(n) * sample_period_s
    beta = width_m / radius_m
    hi, lo = beta + defl_hi, -(beta + defl_lo)
    t_off = t_on_s + pulse_s
    d1, v1 = _traverse(t, t_on_s, hi, lo, accel)
    d2, v2 = _traverse(t, t_off, lo, hi, accel)
    delta = np.where(t < t_on_s, hi, np.where(t < t_off, d1, d2))
    w = np.where(t < t_on_s, 0.0, np.where(t < t_off, v1, v2))
    if bounce_rad > 0:
        for t0, sgn, lvl in ((t_on_s, 1.0, lo), (t_off, -1.0, hi)):
            t_imp = t0 + np.sqrt(2 * abs(hi - lo) / accel)
            m = (t >= t_imp) & (t < t_imp + bounce_s)
            ph = np.pi * (t[m] - t_imp) / bounce_s
            extra = bounce_rad + abs(lvl) - beta
            delta[m] += sgn * extra * np.sin(ph)
            w[m] += sgn * extra * np.pi / bounce_s * np.cos(ph)
    k_on, k_off = int(np.ceil(t_on_s / sample_period_s)), int(np.ceil(t_off / sample_period_s))
    inside = np.abs(delta) < beta
    e_on = k_on + int(np.argmax(inside[k_on:]))
    e_off = k_off + int(np.argmax(inside[k_off:]))
    lag = np.sqrt(2.0 * crossing_rad / accel) / sample_period_s   # samples from departure to the crossing
    c_on = int(np.floor(t_on_s / sample_period_s + lag + 0.5))
    c_off = int(np.floor(t_off / sample_period_s + lag + 0.5))
    return SyntheticPeriod(delta, w, [(k_on, "onset"), (k_off, "return")], [(e_on, "onset"), (e_off, "return")],
                           beta, sample_period_s, [(c_on, "onset"), (c_off, "return")])


def tile_events(p: SyntheticPeriod, events: list, n_periods: int) -> list:
    """``events`` of one period (e.g. ``p.crossings``) repeated for ``n_periods`` periods."""
    n = p.delta.size
    return [(k + i * n, kind) for i in range(n_periods) for k, kind in events]


def tile_record(p: SyntheticPeriod, n_periods: int):
    """(delta, w_rel, departures, entries) of ``n_periods`` consecutive periods."""
    n = p.delta.size
    delta = np.tile(p.delta, n_periods)
    w = np.tile(p.w_rel, n_periods)
    dep = [(k + i * n, kind) for i in range(n_periods) for k, kind in p.departures]
    ent = [(k + i * n, kind) for i in range(n_periods) for k, kind in p.entries]
    return delta, w, dep, ent
