"""The seventeenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev17,
.outside_sealed17): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the tension-staged eddy brake on the motor, the geared lubricator's crank on the wheel, the orifice damper
across the jaw, the motor's pinch-roll drag on the carriage, a2's strain-sensitive gain, the impact-sampled
anti-clatter actuator on the wheel, the torsion bar re-anchored at each stroke across the jaw), every sealed mechanism
acting in its recorded balance only, the suites (made, written, deterministic, each mechanism row visible above the
criterion its strength was set by), ``forms`` withholding the sealed laws, and the outside bench's set 17 (its sealed
half spent: run once at stop 54, in the loop's default suites and the alarm check).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import noise as N
from foreign_drives.drive import pulse_indicator
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_acts_in_its_balance_only, assert_forms_withholds_sealed,
                                        assert_recordings_repeat, assert_rows_visible, assert_set_registry,
                                        assert_set_suites, assert_suite_writes_one_recording)
from foreign_outside_recordings import assert_alarm_check_covers_both_halves, assert_bench_guards_unspent_sealed  # test/
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero, sample_times_s, slip_rad_s  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(17, seed=217)
DEV17, SEALED17, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _pulse(rec):
    """The load pulse's indicator at each sample (the kernel's held one)."""
    return pulse_indicator(sample_times_s(rec), rec.spec.pulse_first_s)


def test_seventeenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(17)


# each mechanism's neutral setting at its suite's parameters: a strength 0 (the blanking hold switched off)
NEUTRAL = {"motor_tension_staged_eddy_brake": {"torque_per_stage_Nm": 0.0},
           "wheel_geared_lubricator_crank": {"torque_Nm": 0.0},
           "clutch_orifice_rotary_damper": {"coefficient_Nm_s2_per_rad2": 0.0},
           "mass_motor_pinch_roll_drag": {"force_N": 0.0},
           "a2_strain_sensitive_gain": {"gain_per_m": 0.0},
           "wheel_impact_sampled_anti_clatter": {"coefficient_Nm_s_per_rad": 0.0},
           "clutch_stroke_reanchored_torsion_bar": {"stiffness_Nm_per_rad": 0.0},
           "motor_tension_run_on_brake": {"torque_Nm": 0.0},
           "wheel_slip_peak_eddy_brake": {"coefficient_Nm_s_per_rad": 0.0},
           "clutch_slew_limited_mr_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_tension_switch_drag_shoe": {"force_N": 0.0},
           "a2_stroke_blanking_hold": {"enabled": 0.0},
           "mass_cambered_rail": {"force_N": 0.0},
           "motor_timer_dumped_accumulator_pump": {"torque_Nm": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV17) | set(SEALED17)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV17) | set(SEALED17)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_staged_brake_loads_the_motor_by_whole_stages_of_the_extension_above_its_threshold():
    p = _params("motor_tension_staged_eddy_brake")
    rec = rec_of("motor_tension_staged_eddy_brake", **p)
    tx, z = motor_term_Nm(rec), rec.internal["spring_extension"]
    law = DEV17["motor_tension_staged_eddy_brake"].torque(z, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * np.max(np.abs(tx))
    stages = tx / p["torque_per_stage_Nm"]
    assert np.allclose(stages, np.round(stages), atol=1e-6)              # whole stages only
    assert len(set(np.round(stages).astype(int).tolist())) >= 2          # the switch steps during the recording
    assert np.all(np.abs(tx[z <= p["threshold_m"]]) < 1e-9)            # nothing below the threshold
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_lubricator_crank_is_locked_to_the_wheel_angle_at_order_one_over_n():
    p = _params("wheel_geared_lubricator_crank")
    rec = rec_of("wheel_geared_lubricator_crank", **p)
    tx = wheel_term_Nm(rec)
    theta = np.unwrap(rec.internal["alpha2"])                            # the wheel's own angle from sample 0
    n = p["reduction"]
    basis = np.column_stack([np.sin(theta / n), np.cos(theta / n)])
    (cs, cc), *_ = np.linalg.lstsq(basis, tx, rcond=None)
    assert np.hypot(cs, cc) == pytest.approx(p["torque_Nm"], rel=1e-6)  # its amplitude ...
    assert np.max(np.abs(tx - basis @ [cs, cc])) < 1e-6 * p["torque_Nm"]   # ... and it explains the whole term
    # at order 1/N, not at the wheel's turn: order 1 explains little of it
    one = np.column_stack([np.sin(theta), np.cos(theta)])
    r1 = tx - one @ np.linalg.lstsq(one, tx, rcond=None)[0]
    assert np.std(r1) > 0.5 * np.std(tx)
    # the law on the simulator's angle unwrapped from the run-in's start (the whole turns the integrator took off,
    # kernel alpha2_turns, at the run's end), phase and all
    from foreign_drives import kernel as K
    end = rec.internal["alpha2"][-1] + 2.0 * np.pi * rec.internal["parameters"][K.P_A2TURNS]
    law = DEV17["wheel_geared_lubricator_crank"].torque(end - (theta[-1] - theta), p)
    assert np.max(np.abs(tx - law)) < 1e-6 * p["torque_Nm"]
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_orifice_damper_passes_the_slip_squared_with_its_sign_in_the_gap_and_in_contact():
    p = _params("clutch_orifice_rotary_damper")
    rec = rec_of("clutch_orifice_rotary_damper", **p)
    extra, s = extra_clutch_Nm(rec), slip_rad_s(rec)
    law = DEV17["clutch_orifice_rotary_damper"].torque(s, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(extra))
    gap = rec.internal["mode"] == 0
    assert gap.any() and (~gap).any()
    assert np.max(np.abs(extra[gap])) > 0.1                              # in the gap too
    assert np.all(np.sign(extra[np.abs(s) > 1e-3]) == np.sign(s[np.abs(s) > 1e-3]))   # it drags the faster half back
    # the second power: twice the slip, four times the torque
    big = np.abs(s) > 0.5 * np.max(np.abs(s))
    assert np.allclose(extra[big] / s[big] ** 2, p["coefficient_Nm_s2_per_rad2"] * np.sign(s[big]), rtol=1e-5)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_pinch_rolls_drag_the_carriage_towards_the_motor_rims_speed_with_a_dry_friction():
    p = _params("mass_motor_pinch_roll_drag")
    rec = rec_of("mass_motor_pinch_roll_drag", **p)
    fx, w1, v = mass_term_N(rec), rec.signals["omega1"], rec.internal["mass_speed"]
    law = DEV17["mass_motor_pinch_roll_drag"].force(w1, v, C.WHEEL_RADIUS_M, p)
    assert np.max(np.abs(fx - law)) < 1e-6 * np.max(np.abs(fx))
    dv = C.WHEEL_RADIUS_M * w1 - v
    assert (dv > 0).any() and (dv < 0).any()                             # both ways in one recording
    fast = np.abs(dv) > 3.0 * p["speed_scale_m_s"]                       # dry: beyond its scale, the force itself
    assert fast.any() and np.allclose(np.abs(fx[fast]), p["force_N"], rtol=1e-2)
    assert np.all(np.sign(fx[fast]) == np.sign(dv[fast]))
    # the motor's rim, not the wheel's: the wheel speed's difference does not give it
    dv2 = C.WHEEL_RADIUS_M * rec.signals["omega2"] - v
    assert np.max(np.abs(fx - p["force_N"] * np.tanh(dv2 / p["speed_scale_m_s"]))) > 0.1 * p["force_N"]
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_strain_sensitive_gain_scales_a2_by_the_spring_extension():
    p = _params("a2_strain_sensitive_gain")
    rec = rec_of("a2_strain_sensitive_gain", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])
    a, z = rec.internal["a2_physical"], rec.internal["spring_extension"]
    read = DEV17["a2_strain_sensitive_gain"].read(a, z, p)
    assert np.max(np.abs(rec.signals["a2"] - read)) < 1e-9 * np.max(np.abs(a))
    # a gain, not an offset: where a2 is 0 it reads 0; the ratio is 1 + g*(z - z_c)
    ok = np.abs(a) > 0.1 * np.max(np.abs(a))
    assert np.allclose(rec.signals["a2"][ok] / a[ok], 1.0 + p["gain_per_m"] * (z[ok] - p["reference_m"]), rtol=1e-9)
    assert np.ptp(z) > 0.01                                              # the gain moves over the recording
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_anti_clatter_actuator_holds_the_slip_sampled_at_each_impact_on_the_wheel():
    p = _params("wheel_impact_sampled_anti_clatter")
    c = p["coefficient_Nm_s_per_rad"]
    rec = rec_of("wheel_impact_sampled_anti_clatter", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * max(1.0, np.max(np.abs(tx)))   # held between its 0.2 ms scans
    held = tx[::SEG] / c                                                 # S after each scan
    s = slip_rad_s(rec)[::SEG]                                                # the slip at each scan's start
    mode = rec.internal["mode"]
    changes = np.flatnonzero(np.abs(np.diff(held)) > 1e-9) + 1
    assert changes.size >= 2
    for k in changes:
        assert held[k] == pytest.approx(s[k], abs=1e-6 * max(1.0, abs(s[k])))   # the slip at that scan ...
        seg = mode[(k - 1) * SEG:k * SEG + 1]
        assert np.any((seg[:-1] == 0) & (seg[1:] != 0))                 # ... just after a contact from the gap began
    # every contact from the gap (one scan before the recording's end at the latest) takes a new sample
    starts = np.flatnonzero((mode[:-1] == 0) & (mode[1:] != 0)) + 1
    next_scans = set(((starts - 1) // SEG + 1).tolist())
    assert {k for k in next_scans if k < held.size} <= set(changes.tolist())
    assert np.any(held > 0.0) or np.any(held < 0.0)
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_torsion_bar_centres_the_jaw_on_its_angle_at_each_strokes_start():
    p = _params("clutch_stroke_reanchored_torsion_bar")
    k = p["stiffness_Nm_per_rad"]
    rec = rec_of("clutch_stroke_reanchored_torsion_bar", **p)
    extra, d = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"]
    anchor = d + extra / k                                               # S = D + T/k
    assert np.max(held_per_segment(anchor)) < 1e-9                     # S held between scans
    anchor = anchor[::SEG]
    dd = d[::SEG]                                                        # D at each scan's start
    starts = np.flatnonzero(np.diff(_pulse(rec)[::SEG]) > 0.5) + 1      # each load pulse's first scan
    assert starts.size >= 2
    counts = np.cumsum(np.isin(np.arange(dd.size), starts))
    i0 = starts[0]
    pred = DEV17["clutch_stroke_reanchored_torsion_bar"].anchors(dd[i0:], counts[i0:])
    assert np.max(np.abs(pred - anchor[i0:])) < 1e-9
    moves = np.flatnonzero(np.abs(np.diff(anchor)) > 1e-9) + 1
    assert set(moves.tolist()) <= set(starts.tolist())                   # it re-anchors at a stroke's start only
    assert np.max(np.abs(extra[rec.internal["mode"] == 0])) > 0.1        # a spring across the gap too
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED17))
def test_sealed17_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED17[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set17_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(17, DEV17, SEALED17, 17000, 17100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (three with its single scaling)."""
    assert_rows_visible(("outside_dev17", "outside_sealed17"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev17", "outside_sealed17"))


@pytest.mark.parametrize("suite_name", ["outside_dev17", "outside_sealed17"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED17, DEV17)


def test_outside_bench_knows_set_17_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-17 are spent (set 17's sealed half ran once, 1 Dec, stop 54): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(17, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(17)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(17, DURATION_S)
