"""The ninth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev9, .outside_sealed9):
the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the development laws checked
on the drive's own balances and signals (each term recovered from the recorded, noise-free states: the centrifugal
clutch's blower, the Geneva indexer, the Belleville snap-through, the check-valve damper's lag, the loose seismic
mass's play, the cable guide's friction, the fixed-point smoothing filter), every sealed mechanism acting in its
recorded balance only, the suites (made, written, deterministic, each mechanism row visible above the criterion its
strength was set by), ``forms`` withholding the sealed laws, and the outside bench's set 9 (its sealed half UNSPENT:
the loop refuses it without --sealed).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import math

import numpy as np
import pytest

from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_balance_terms import contact_law_Nm, mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_acts_in_its_balance_only,  # test/
                                        assert_forms_withholds_sealed, assert_recordings_repeat,
                                        assert_rows_visible, assert_set_registry, assert_set_suites,
                                        assert_suite_writes_one_recording)
from foreign_outside_recordings import (assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_alarm_check_covers_both_halves,
                                        assert_bench_guards_unspent_sealed)
from foreign_outside_recordings import held_per_segment, others_zero  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(9, seed=197)
DEV9, SEALED9, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _a_sensor_only(rec):
    """A sensor mechanism leaves the drive and a1 untouched."""
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])


# ------------------------------------------------------------------ registry and truth vocabulary
def test_ninth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(9)


# each mechanism's neutral setting at its suite's parameters: a strength 0 (the play: a half-width 0)
NEUTRAL = {"motor_centrifugal_clutch_blower": {"blower_torque_Nm": 0.0}, "wheel_geneva_indexer": {"torque_Nm": 0.0},
           "clutch_belleville_snap_through": {"spring_torque_Nm": 0.0},
           "mass_check_valve_damper": {"coefficient_N_s_per_m": 0.0}, "a2_loose_seismic_mass": {"play_m_s2": 0.0},
           "mass_cable_guide_friction": {"coefficient_N_per_m": 0.0},
           "motor_tension_particle_brake": {"coefficient_Nm_s_per_rad_m": 0.0}, "wheel_cam_timed_brake": {"torque_Nm": 0.0},
           "clutch_gap_bumpers": {"stiffness_Nm_per_rad": 0.0}, "mass_wheel_blower_sail": {"coefficient_N_s2_per_rad2": 0.0},
           "motor_rotary_distributor_valve": {"torque_Nm": 0.0}, "wheel_drag_cup_governor": {"gain_Nm_s_per_rad": 0.0}}
# two filters have no neutral setting (a least step, a resonance): their laws are checked on their own
NO_NEUTRAL = {"a2_fixed_point_smoothing", "a1_bracket_resonance"}


@pytest.mark.parametrize("name", sorted((set(DEV9) | set(SEALED9)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) | NO_NEUTRAL == set(DEV9) | set(SEALED9)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_centrifugal_clutch_blower_is_a_square_law_switched_on_by_the_speed():
    w0 = clean().signals["omega1"]
    p = {"blower_torque_Nm": 6.0, "engage_speed_rad_s": float(np.median(w0)),
         "engage_width_rad_s": 0.1 * float(np.percentile(w0, 95) - np.percentile(w0, 5))}
    rec = rec_of("motor_centrifugal_clutch_blower", **p)
    tx, w1 = motor_term_Nm(rec), rec.signals["omega1"]
    law = DEV9["motor_centrifugal_clutch_blower"].torque(w1, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * p["blower_torque_Nm"]
    # engaged (above Omega_e + w) it is most of the square law, disengaged (below Omega_e - w) a small part of it
    we, w = p["engage_speed_rad_s"], p["engage_width_rad_s"]
    sq = p["blower_torque_Nm"] * (w1 / we) ** 2
    up, down = w1 > we + w, w1 < we - w
    assert up.any() and down.any()
    assert np.min(tx[up] / sq[up]) > 0.88 and np.max(tx[down] / sq[down]) < 0.12
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_geneva_indexer_drags_the_wheel_in_one_window_every_n_turns():
    p = _params("wheel_geneva_indexer")
    rec = rec_of("wheel_geneva_indexer", **p)
    tx = wheel_term_Nm(rec)
    others_zero(rec, motor_term_Nm, mass_term_N)
    theta = np.unwrap(rec.internal["alpha2"])
    n, period = p["turns_per_index"], 2 * math.pi * p["turns_per_index"]
    # the record's unwrapped angle differs from the kernel's (from the run-in's start) by whole turns: one of n fits
    errors = []
    for j in range(n):
        law = DEV9["wheel_geneva_indexer"].torque(theta + 2 * math.pi * j, rec.signals["omega2"], p)
        q = np.mod(theta + 2 * math.pi * j - p["phase_rad"], period)
        clear = (np.abs(q - p["window_rad"]) > 1e-3) & (q > 1e-3) & (period - q > 1e-3)
        errors.append(np.max(np.abs(tx - law)[clear]))
    assert min(errors) < 1e-6 * p["torque_Nm"]
    # a sub-harmonic of the rotation: it brakes during a share W/(2*pi*N) of the wheel angle
    on = tx < -0.5 * p["torque_Nm"]
    assert on.any() and np.ptp(theta[on]) > 2 * math.pi
    assert on.mean() == pytest.approx(p["window_rad"] / period, abs=0.05)


def test_belleville_snap_through_adds_a_torque_that_falls_beyond_its_peak():
    p = _params("clutch_belleville_snap_through")
    rec = rec_of("clutch_belleville_snap_through", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    d, mode, beta = i["jaw_angle_difference"], i["mode"], i["parameters"][K.P_BETA]
    overlap = np.sign(d) * np.maximum(0.0, np.abs(d) - beta)             # the faces' overlap, pushing or not
    law = DEV9["clutch_belleville_snap_through"].torque(overlap, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * p["spring_torque_Nm"]
    gap = np.abs(d) < beta
    assert np.all(extra[gap] == 0.0) and (mode == 0).mean() > 0.02 and (mode != 0).mean() > 0.02
    # the law itself: odd, its peak ~0.77 T_b near q = 0.42, 0 at q = 1 and negative beyond (a falling torque)
    h = p["free_height_rad"]
    q = np.linspace(0.0, 1.5, 1501)
    t = DEV9["clutch_belleville_snap_through"].torque(q * h, p)
    assert q[np.argmax(t)] == pytest.approx(1 - 1 / math.sqrt(3), abs=2e-3)
    assert np.max(t) == pytest.approx(0.77 * p["spring_torque_Nm"], rel=0.01)
    assert abs(t[1000]) < 1e-9 and np.all(t[1001:] < 0)
    assert np.allclose(DEV9["clutch_belleville_snap_through"].torque(-q * h, p), -t)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_check_valve_damper_follows_the_speed_fast_up_and_slow_down():
    v = clean().internal["mass_speed"]
    p = {"coefficient_N_s_per_m": 50.0, "crack_speed_m_s": float(np.min(v)) - 0.5, "rise_time_s": 0.005,
         "fall_time_s": 0.1}
    rec = rec_of("mass_check_valve_damper", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-6
    others_zero(rec, motor_term_Nm, wheel_term_Nm)
    m = p["crack_speed_m_s"] - fx[::SEG] / p["coefficient_N_s_per_m"]          # the chamber's state at the scans
    x = rec.internal["mass_speed"][::SEG]
    law = DEV9["mass_check_valve_damper"].lagged(np.concatenate(([m[0]], x[1:])), p, DT)
    assert np.max(np.abs(m - law)) < 1e-6
    # rising it catches up fast, falling it stays above the speed longer and farther (an envelope of the speed)
    assert np.mean(m >= x) > 0.5 and np.max(m - x) > np.max(x - m) > 0.0


def test_loose_seismic_mass_is_a_play_on_a2():
    p = _params("a2_loose_seismic_mass")
    rec = rec_of("a2_loose_seismic_mass", **p)
    _a_sensor_only(rec)
    a, y, h = rec.internal["a2_physical"], rec.signals["a2"], p["play_m_s2"]
    assert np.max(np.abs(y - a)) <= h * (1 + 1e-12) and np.max(np.abs(y - a)) > 0.9 * h
    moved = np.flatnonzero(np.diff(y) != 0) + 1
    assert moved.size and np.allclose(np.abs(y[moved] - a[moved]), h, rtol=0, atol=1e-12)   # dragged by its edge
    read = DEV9["a2_loose_seismic_mass"].read
    s = 2.0 * np.sin(np.linspace(0.0, 4 * math.pi, 4001))
    out = read(s, p)
    top = np.argmax(s[:2000])
    assert np.all(out[top:top + 200] == out[top])                     # flat while the input turns back
    assert np.max(out) == pytest.approx(2.0 - h, abs=1e-6)           # rate-independent: the peak less h


def test_cable_guide_friction_is_the_spring_extension_times_the_sign_of_the_speed():
    p = _params("mass_cable_guide_friction")
    rec = rec_of("mass_cable_guide_friction", **p)
    fx, i = mass_term_N(rec), rec.internal
    law = DEV9["mass_cable_guide_friction"].force(i["spring_extension"], i["mass_speed"], p)
    assert np.max(np.abs(fx - law)) < 1e-6 * p["coefficient_N_per_m"]
    assert np.ptp(fx) > 0.05 * np.max(np.abs(fx))                    # it follows z: not a constant force
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_fixed_point_smoothing_moves_in_whole_steps_and_stalls_on_small_errors():
    p = _params("a2_fixed_point_smoothing")
    rec = rec_of("a2_fixed_point_smoothing", **p)
    _a_sensor_only(rec)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    q, div = p["step_m_s2"], p["step_m_s2"] * 2 ** p["shift"]
    assert np.allclose(np.diff(y), q * np.round((a[1:] - y[:-1]) / div), rtol=0, atol=1e-12)
    read = DEV9["a2_fixed_point_smoothing"].read
    # a step input: it approaches the step ~1/2^k per sample and stalls within q*2^(k-1) of it
    out = read(np.concatenate((np.zeros(10), np.ones(2000))), p)
    assert 0 < 1.0 - out[-1] <= div / 2 and out[-1] == out[-500]
    assert out[10 + 2 ** p["shift"]] == pytest.approx(1 - math.exp(-1), abs=0.05)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED9))
def test_sealed9_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED9[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set9_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(9, DEV9, SEALED9, 9000, 9100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s)."""
    assert_rows_visible(("outside_dev9", "outside_sealed9"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev9", "outside_sealed9"))


@pytest.mark.parametrize("suite_name", ["outside_dev9", "outside_sealed9"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED9, DEV9)


def test_outside_bench_knows_set_9_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-9 are spent (set 9's sealed half ran once, 30 Nov): each sealed half is development data, in the loop's
    # default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(9, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(9)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(9, DURATION_S)
