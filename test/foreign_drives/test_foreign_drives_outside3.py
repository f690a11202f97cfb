"""The third set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev3, .outside_sealed3):
the registry and its truth vocabulary (every balance and state one the outside bench scores), zero strength = the
clean drive for each of the fourteen, the kernel's new shapes, the development laws checked on the drive's own
balances (each term recovered from the recorded, noise-free states), every sealed mechanism acting in its recorded
balance only, the suites and the outside bench's set 3.

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import kernel as K
from foreign_drives import outside as O
from foreign_drives import suites
from foreign_drives.drive import make_recording, pulse_indicator
from foreign_drives.spec import RecordingSpec
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import Recordings, assert_acts_in_its_balance_only, outside_bench, suite_effect  # test/

W = C.WHEEL_RADIUS_M

OUTSIDE = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
DEV3 = {n: f for n, f in OUTSIDE.items() if f.half == "dev3"}
SEALED3 = {n: f for n, f in OUTSIDE.items() if f.half == "sealed3"}
DURATION_S = 0.6


def _spec(effects, seed=173, width=0.0065, duration=DURATION_S):
    return RecordingSpec("t3", "outside" if effects else "clean", width, 0.025, 0.9, effects=tuple(effects), seed=seed,
                         duration_s=duration, noise=False)


RECORDINGS = Recordings(lambda effects, duration_s: _spec(effects, duration=duration_s), DURATION_S)
rec_of, clean = RECORDINGS.rec_of, RECORDINGS.clean


def _suite_effect(name):
    """The set-3 suite's use of a mechanism (its parameters at the suite's strength)."""
    return suite_effect(name, ("outside_dev3", "outside_sealed3"))


def _outside_bench():
    return outside_bench("outside_bench_under_test3")


# ------------------------------------------------------------------ registry and truth vocabulary
def test_third_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    from foreign_drives import outside_dev3, outside_sealed3
    assert {c.name for c in outside_dev3.FORM_CLASSES} == set(DEV3) and len(DEV3) == 7
    assert {c.name for c in outside_sealed3.FORM_CLASSES} == set(SEALED3) and len(SEALED3) == 7
    for half in (DEV3, SEALED3):
        assert {f.balance for f in half.values()} == set(O.BALANCES)
    bench = _outside_bench()
    known_states = {w for ws in bench.STATE_WORDS.values() for w in ws}
    known_balances = set(bench.BALANCE_WORDS.values())
    earlier = {n for n, f in OUTSIDE.items() if f.half not in ("dev3", "sealed3")}
    for name, f in {**DEV3, **SEALED3}.items():
        assert f.family is None and name not in F.CATALOGUE_FAMILIES and name not in earlier
        assert f.balance in O.BALANCES and f.balance in known_balances, name
        assert f.depends_on and set(f.depends_on) <= set(O.STATES) and set(f.depends_on) <= known_states, name
        assert (f.stage == "sensor") == (f.balance == "sensor"), name
        for p in f.parameters:
            lo, hi = p.bounds
            assert math.isfinite(lo) and math.isfinite(hi) and lo < hi, (name, p.name)


# the parameter that sets each mechanism's strength (0: absent)
STRENGTH = {"motor_accumulator_recharge": "torque_Nm", "wheel_weston_brake": "torque_Nm",
            "clutch_cardan_error": "amplitude_rad", "mass_pneumatic_holdback": "force_N",
            "a2_transmitter_deadband": "deadband_m_s2", "motor_speed_relay_load": "torque_Nm",
            "a2_stroke_ringing": "amplitude_m_s2"}


@pytest.mark.parametrize("name", sorted(DEV3) + sorted(SEALED3))
def test_zero_strength_is_the_clean_drive(name):
    """At its suite's parameters with the strength 0 (for the sealed ones: the parameter the generic test zeroes), the
    recording equals the clean drive's bit for bit."""
    p = dict(_suite_effect(name).parameters)
    if name in STRENGTH:
        p[STRENGTH[name]] = 0.0
    else:
        (k,) = [q.name for q in OUTSIDE[name].parameters if q.name.startswith(
            ("amplitude", "torque", "force", "damping", "coefficient", "gain", "relative", "deadband", "corner"))]
        p[k] = 0.0
    rec = rec_of(name, **p)
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


def test_the_kernels_new_shapes_are_their_formulas():
    for x in (-0.3, 0.0, 0.02, 0.07, 1.4):
        assert K._shaped(K.XF_ABS, x, 0.0, 0.0, 0.0) == abs(x)
        assert K._shaped(K.XF_SIGMOID, x, -0.05, 0.01, 0.0) == pytest.approx(0.5 * (1 - math.tanh((x - 0.01) / 0.05)))
        assert K._shaped(K.XF_DECAY_AFTER, x, 0.04, 0.06, 0.0) == (
            pytest.approx(math.exp(-(x - 0.06) / 0.04)) if x >= 0.06 else 0.0)
        assert K._shaped(K.XF_CUSHION, x, 0.01, 1.5, 0.0) == (pytest.approx((0.01 / (x + 0.01)) ** 1.5) if x >= 0
                                                              else 0.0)
    gate = [K._shaped(K.XF_PERIODIC_GATE, t, 1.3, 0.4, 0.3) for t in (-0.85, 0.39, 0.41, 0.69, 0.71, 1.71, 1.99, 2.01)]
    assert gate == [1.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 0.0]     # (t - 0.4) mod 1.3 < 0.3


# ------------------------------------------------------------------ the development laws on the drive's balances
def _pulse_phase(rec):
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    from foreign_drives.outside_dev3 import pulse_phase_s
    return pulse_phase_s(t, pulse_indicator(t, rec.spec.pulse_first_s))


def test_accumulator_recharge_loads_the_motor_from_each_pulses_end_only():
    p = {"torque_Nm": 4.0, "decay_s": 0.04}
    rec = rec_of("motor_accumulator_recharge", **p)
    ph = _pulse_phase(rec)
    tx = motor_term_Nm(rec)
    assert np.max(np.abs(tx - DEV3["motor_accumulator_recharge"].torque(ph, p))) < 1e-6 * 4.0
    assert np.max(np.abs(tx[ph < C.PULSE_DURATION_S - 1e-4])) < 1e-6 and tx.max() > 3.9     # nothing while it is on
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6


def test_weston_brake_holds_the_wheel_while_the_load_runs_ahead():
    p = {"torque_Nm": 4.0, "engage_width_rad": 0.003}
    rec = rec_of("wheel_weston_brake", **p)
    d = rec.internal["jaw_angle_difference"]
    tx = wheel_term_Nm(rec)
    assert np.max(np.abs(tx - DEV3["wheel_weston_brake"].torque(d, rec.signals["omega2"], p))) < 1e-6 * 4.0
    assert np.all(tx <= 1e-9)                                      # a brake: never drives the wheel
    assert tx[d < -0.01].max() < -3.9 and np.max(np.abs(tx[d > 0.01])) < 0.01     # engaged only with D < 0
    assert np.max(np.abs(motor_term_Nm(rec))) < 1e-6


def test_cardan_error_moves_the_backlash_boundaries_with_twice_the_motor_angle():
    p = {"amplitude_rad": 0.0008, "order": 2, "phase_rad": 0.7}
    rec = rec_of("clutch_cardan_error", **p)
    i = rec.internal
    err = 0.0008 * np.sin(2 * i["alpha1"] + 0.7)
    # the jaw's angle difference is the shafts' less the kinematic error; the recorded one is the shafts'
    assert np.max(np.abs(i["jaw_angle_difference"] - (i["angle_difference_exact"] - err))) < 1e-12
    # the contact acts exactly where the jaw's (not the shafts') angle difference is beyond the gap
    beta = rec.truth.true_width_m / W
    d = i["jaw_angle_difference"]
    sure = np.abs(np.abs(d) - beta) > 1e-6
    assert np.all((i["mode"] != 0)[sure] <= (np.abs(d) > beta)[sure])
    # a2 differs from the clean drive's (same seed): it matters
    assert np.max(np.abs(rec.signals["a2"] - clean().signals["a2"])) > 0.05


def test_pneumatic_holdback_follows_the_pulse_late_and_lagged():
    p = {"force_N": 12.0, "delay_s": 0.02, "lag_s": 0.01}
    rec = rec_of("mass_pneumatic_holdback", **p)
    ph = _pulse_phase(rec)
    fx = mass_term_N(rec)
    assert np.max(np.abs(fx - DEV3["mass_pneumatic_holdback"].force(ph, p))) < 1e-6 * 12.0
    assert np.max(np.abs(fx[ph < 0.02 - 1e-4])) < 1e-9 and fx.min() < -11.0        # nothing before the delay
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6


def test_speed_relay_switches_the_motor_load_with_hysteresis():
    rec = rec_of("motor_speed_relay_load", torque_Nm=3.0, on_above_rad_s=152.0, off_below_rad_s=149.0)
    tx = motor_term_Nm(rec)
    on = tx > 1.5
    assert np.max(np.abs(tx - 3.0 * on)) < 1e-6 * 3.0                 # 0 or T, nothing between
    w = rec.signals["omega1"]
    ks = np.flatnonzero(on[1:] != on[:-1]) + 1
    assert ks.size >= 4                                                # it switches within a pulse period or two
    for k in ks:                                                       # on above 152 rad/s, off below 149 (0.2 ms scan)
        assert (w[k - 10] > 152.0 - 0.05) if on[k] else (w[k - 10] < 149.0 + 0.05)
    # the memory: at the same speed (150.5 rad/s) the load is on and off
    mid = (w > 150.0) & (w < 151.0)
    assert on[mid].any() and (~on[mid]).any()


def test_deadband_holds_a2_within_the_band_and_only_changes_by_more_than_it():
    rec = rec_of("a2_transmitter_deadband", deadband_m_s2=0.4)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    assert np.max(np.abs(y - a)) <= 0.4 + 1e-12 and np.max(np.abs(y - a)) > 0.3
    steps = np.abs(np.diff(y))
    assert np.all((steps == 0.0) | (steps > 0.4))
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])


def test_stroke_ringing_is_on_a2_only_and_starts_with_each_pulse():
    p = {"amplitude_m_s2": 2.0, "frequency_hz": 173.0, "decay_s": 0.02}
    rec = rec_of("a2_stroke_ringing", **p)
    ph = _pulse_phase(rec)
    law = 2.0 * np.exp(-ph / 0.02) * np.sin(2 * np.pi * 173.0 * ph)
    assert np.max(np.abs(rec.signals["a2"] - rec.internal["a2_physical"] - law)) < 1e-9
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])   # the drive unchanged
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED3))
def test_sealed3_mechanism_acts_in_its_recorded_balance_only(name):
    rec = make_recording(_spec([_suite_effect(name)]))
    base = clean()
    assert_acts_in_its_balance_only(name, SEALED3[name].balance, rec, base)


# ------------------------------------------------------------------ suites and the bench
def test_set3_suites_have_one_row_per_mechanism_and_a_clean_control():
    dev, sealed = suites.suite("outside_dev3"), suites.suite("outside_sealed3")
    assert "outside_dev3" in suites.SUITES and "outside_sealed3" not in suites.SUITES
    assert "outside_sealed3" in suites.SUITE_NAMES
    others = [s for n in suites.SUITES if n != "outside_dev3" for s in suites.suite(n)]
    for s_, names, half in ((dev, DEV3, "dev3"), (sealed, SEALED3, "sealed3")):
        assert [s.kind for s in s_].count("clean") == 1 and len(s_) == len(names) + 1
        outside = [s for s in s_ if s.kind == "outside"]
        assert sorted(e.form for s in outside for e in s.effects) == sorted(names)    # one mechanism per row
        assert all(s.duration_s == 4.0 for s in s_)
        assert len({(s.width_m, s.eta_k, s.n1) for s in s_}) == len(s_)           # each at its own conditions
        for s in outside:
            for e in s.truth().effects:
                assert e.half == half and e.balance == F.get(e.form).balance and e.law
    seeds = [s.seed for s in dev + sealed]
    assert len(set(seeds)) == len(seeds) and not set(seeds) & {s.seed for s in others}
    labels = [s.label for s in dev + sealed + others]
    assert len(labels) == len(set(labels))


def test_outside_bench_knows_set_3_and_loops_on_its_spent_sealed_half():
    bench = _outside_bench()
    assert [s.label for s in bench.suite_rows(False, 3)] == [s.label for s in suites.suite("outside_dev3")]
    assert bench.suite_name(True, 3) == "outside_sealed3"
    # the third sealed half has been run once: development data now (the unspent one is set 4's)
    assert {"outside_dev3", "outside_sealed3"} <= set(bench.LOOP_DEVELOPMENT_SUITES)
    assert "outside_sealed3" not in bench.UNSPENT_SEALED
    # the truth of every set-3 row scores in the bench's words: a proposal in its balance on its state is right
    for s in suites.suite("outside_dev3") + suites.suite("outside_sealed3"):
        bal, st = bench._truth_of(s, s.truth())
        assert bool(bal) == (s.kind == "outside") and (not bal or st)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    for name in ("outside_dev3", "outside_sealed3"):
        spec = dataclasses.replace(next(s for s in suites.suite(name) if s.kind == "outside"), duration_s=DURATION_S)
        rec = make_recording(spec)
        assert all(np.all(np.isfinite(rec.signals[k])) for k in rec.signals)
        assert sum(k == "onset" for _, k in rec.true_entries()) >= 2
