"""The second set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev2, .outside_sealed2):
the registry and its truth vocabulary, a short recording of every development row (it simulates, its truth is
complete, the drive still crosses its backlash), the development laws checked on the drive's own balances (each term
recovered from the recorded, noise-free states), and the sealed suite built (specs, truths, parameter vectors).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law
or label (zero amplitude = the clean drive is checked for every outside form in test_foreign_drives_outside.py)."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import outside as O
from foreign_drives import suites
from foreign_drives.drive import build_parameters, make_recording
from foreign_drives.spec import RecordingSpec
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import Recordings, outside_bench              # test/

T_B = C.BASE_TORQUE_NM

OUTSIDE = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
DEV2 = {n: f for n, f in OUTSIDE.items() if f.half == "dev2"}
SEALED2 = {n: f for n, f in OUTSIDE.items() if f.half == "sealed2"}
DURATION_S = 0.6


def _spec(effects, seed=171, width=0.0065, duration=DURATION_S):
    return RecordingSpec("t2", "outside" if effects else "clean", width, 0.025, 0.9, effects=tuple(effects), seed=seed,
                         duration_s=duration, noise=False)


RECORDINGS = Recordings(lambda effects, duration_s: _spec(effects, duration=duration_s), DURATION_S)
rec_of, clean = RECORDINGS.rec_of, RECORDINGS.clean


def test_second_set_is_seven_and_seven_over_all_balances_with_valid_truth_vocabulary():
    from foreign_drives import outside_dev2, outside_sealed2
    assert {c.name for c in outside_dev2.FORM_CLASSES} == set(DEV2) and len(DEV2) == 7
    assert {c.name for c in outside_sealed2.FORM_CLASSES} == set(SEALED2) and len(SEALED2) == 7
    both = {f.balance for f in DEV2.values()} | {f.balance for f in SEALED2.values()}
    assert both == set(O.BALANCES)
    for name, f in {**DEV2, **SEALED2}.items():
        assert f.family is None and name not in F.CATALOGUE_FAMILIES
        assert f.balance in O.BALANCES and f.depends_on and set(f.depends_on) <= set(O.STATES), name
        assert (f.stage == "sensor") == (f.balance == "sensor"), name
    # the sealed suite is made on demand, not listed
    assert "outside_sealed2" not in suites.SUITES and "outside_dev2" in suites.SUITES


@pytest.mark.parametrize("i", range(len(suites.suite("outside_dev2"))))
def test_every_dev2_row_simulates_with_its_truth_and_crosses_the_backlash(i):
    spec = dataclasses.replace(suites.suite("outside_dev2")[i], duration_s=DURATION_S)
    rec = make_recording(spec)
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.all(np.isfinite(rec.signals[k])) and rec.signals[k].size == round(DURATION_S * C.SAMPLE_RATE_HZ)
    mode = rec.internal["mode"]
    assert np.sum((mode[1:] == 0) & (mode[:-1] != 0)) >= 2          # entries into the gap: the monitor's events
    truth = rec.truth
    assert truth.true_width_m > 0
    for e in truth.effects:
        if F.get(e.form).family is None:
            assert e.balance in O.BALANCES and set(e.depends_on) <= set(O.STATES) and e.half == "dev2"
            assert isinstance(e.law, str) and e.law and (e.plugin is None or "class " in e.plugin)
    assert (spec.kind == "clean") == (not truth.outside)


def test_sealed2_suite_builds_without_showing_its_laws():
    specs = suites.suite("outside_sealed2")
    assert len(specs) >= 9
    assert sum(s.kind == "outside" for s in specs) >= 7 and any(s.kind == "clean" for s in specs)
    for s in specs:
        truth = s.truth()
        P, _ = build_parameters(s)
        assert np.all(np.isfinite(P))
        for e in truth.effects:
            if F.get(e.form).family is None:
                assert e.half == "sealed2" and e.balance in O.BALANCES and set(e.depends_on) <= set(O.STATES)
    used = {e.form for s in specs for e in s.effects}
    assert set(SEALED2) <= used


# ------------------------------------------------------------------ the development laws on the drive's balances
def test_eccentric_roller_is_its_law_on_the_mass_only():
    rec = rec_of("mass_eccentric_roller", amplitude_N=4.0, phase_rad=-0.8)
    law = 4.0 * np.cos(rec.internal["alpha2"] - 0.8)
    assert np.max(np.abs(mass_term_N(rec) - law)) < 1e-6 * 4.0
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6


def test_overload_brake_acts_on_the_motor_only_beyond_its_threshold():
    rec = rec_of("motor_overload_band_brake", coefficient_Nm_per_m=300.0, threshold_m=0.295)
    z = rec.internal["spring_extension"]
    tx = motor_term_Nm(rec)
    assert np.max(np.abs(tx - 300.0 * np.maximum(0.0, z - 0.295))) < 1e-6 * T_B
    assert (z > 0.295).any() and (z < 0.295).any() and tx.min() > -1e-6      # a brake: never drives the motor


def test_timed_brake_is_zero_before_its_instant_and_rises_after():
    rec = rec_of("wheel_timed_brake", torque_Nm=3.0, start_s=0.3, build_up_s=0.05)
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    law = np.where(t >= 0.3, -3.0 * (1.0 - np.exp(-(t - 0.3) / 0.05)), 0.0)
    assert np.max(np.abs(wheel_term_Nm(rec) - law)) < 1e-6 * 3.0
    assert np.array_equal(rec.signals["a1"][:1000], clean().signals["a1"][:1000])


def test_dry_friction_adds_a_hysteresis_in_contact_and_nothing_in_the_gap():
    from foreign_drives.kernel import P_BETA, P_DC, P_KCD
    rec = rec_of("clutch_jaw_dry_friction", coefficient_Nm_per_rad=450.0, sign_speed_rad_s=0.2)
    i, P = rec.internal, rec.internal["parameters"]
    mode = i["mode"]
    assert np.all(i["clutch_torque_Nm"][mode == 0] == 0.0)
    on = mode != 0
    s = mode[on]
    rel = rec.signals["omega1"][on] - rec.signals["omega2"][on]
    pen = s * i["jaw_angle_difference"][on] - P[P_BETA]
    contact = s * (P[P_KCD] * pen + P[P_DC] * s * rel)          # the nominal contact law k*p + d*p'
    law = 450.0 * pen * np.tanh(rel / 0.2)                      # c*p*tanh(p'/eps) with the sign of the rate
    assert np.max(np.abs(i["clutch_torque_Nm"][on] - contact - law)) < 1e-6 * 450.0 * np.max(pen)
    # a hysteresis: more torque while the jaw presses in than while it lets go
    assert np.max(law) > 1.0 and np.min(law) < -1.0


def test_sensor_mechanisms_change_only_their_channel():
    sat = rec_of("a1_soft_saturation", gain_inverse_limit_s2_per_m=0.01)
    a = sat.internal["a1_physical"]
    assert np.max(np.abs(sat.signals["a1"] - 100.0 * np.tanh(a / 100.0))) < 1e-9
    assert np.array_equal(sat.signals["a2"], clean().signals["a2"])
    tilt = rec_of("a2_bracket_tilt", gain_m_s2_per_m=19.6, centre_m=0.29)
    z = tilt.internal["spring_extension"]
    assert np.max(np.abs(tilt.signals["a2"] - tilt.internal["a2_physical"] - 19.6 * (z - 0.29))) < 1e-9
    assert np.array_equal(tilt.signals["a1"], clean().signals["a1"])


# ------------------------------------------------------------------ the outside bench's sets and its loop's guard
def _outside_bench():
    return outside_bench("outside_bench_under_test")


def test_outside_bench_knows_both_sets_and_loops_on_the_spent_sealed_half():
    bench = _outside_bench()
    assert [s.label for s in bench.suite_rows(False, 2)] == [s.label for s in suites.suite("outside_dev2")]
    assert bench.suite_name(True, 2) == "outside_sealed2" and bench.suite_name(True, 1) == "outside_sealed"
    # the second sealed half has been run once: development data now (every sealed half through set 23 has been; the
    # unspent one is set 24's)
    assert "outside_sealed2" in bench.LOOP_DEVELOPMENT_SUITES and "outside_sealed2" not in bench.UNSPENT_SEALED
    with pytest.raises(ValueError,
                       match="allowed: 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24"):
        bench.suite_name(False, 25)
