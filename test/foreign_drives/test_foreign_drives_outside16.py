"""The sixteenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev16,
.outside_sealed16): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the flying shear's cut on the motor, the hydrostatic booster on the wheel, the cable-loaded friction plate
across the jaw, the motor unbalance's frame shake on the carriage, a2's drag-chain triboelectric zero shift, the wheel
overspeed's timed rail brake, the peak-tension regenerative brake), every sealed mechanism acting in its recorded
balance only, the suites (made, written, deterministic, each mechanism row visible above the criterion its strength was
set by), ``forms`` withholding the sealed laws, and the outside bench's set 16 (its sealed half spent: run once at
stop 53, in the loop's default suites and the alarm check).

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
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero, sample_times_s  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(16, seed=216)
DEV16, SEALED16, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _pulse(rec):
    """The load pulse's indicator at each sample (the kernel's held one)."""
    return pulse_indicator(sample_times_s(rec), rec.spec.pulse_first_s)


# ------------------------------------------------------------------ registry and truth vocabulary
def test_sixteenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(16)


# each mechanism's neutral setting at its suite's parameters: a strength 0 (a corner of 0 Hz)
NEUTRAL = {"motor_flying_shear_cut": {"torque_Nm": 0.0},
           "wheel_hydrostatic_booster": {"coefficient_Nm_s2_per_rad2": 0.0},
           "clutch_cable_loaded_friction_plate": {"coefficient_Nm_per_m": 0.0},
           "mass_motor_unbalance_frame_shake": {"coefficient_N_s2_per_rad2": 0.0},
           "a2_drag_chain_triboelectric": {"offset_m_s2": 0.0},
           "mass_wheel_overspeed_timed_rail_brake": {"force_N": 0.0},
           "motor_peak_tension_regen_brake": {"coefficient_Nm_per_m": 0.0},
           "motor_stroke_sampled_energy_brake": {"coefficient_Nm_s_per_rad": 0.0},
           "wheel_slack_bowden_brake": {"coefficient_Nm_per_m": 0.0},
           "clutch_tacho_excited_slip_coupling": {"coefficient_Nm_s2_per_rad2": 0.0},
           "mass_alternate_stroke_drag_shoe": {"force_N": 0.0},
           "a2_ac_coupled_input": {"corner_hz": 0.0},
           "wheel_tension_proportional_brake": {"torque_Nm": 0.0},
           "clutch_leaky_vane_damper": {"coefficient_Nm_s_per_rad": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV16) | set(SEALED16)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV16) | set(SEALED16)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_flying_shear_loads_the_motor_with_a_peak_at_its_delay_into_each_stroke_and_not_between():
    p = _params("motor_flying_shear_cut")
    rec = rec_of("motor_flying_shear_cut", **p)
    tx, pulse, t = motor_term_Nm(rec), _pulse(rec), sample_times_s(rec)
    first, period = rec.spec.pulse_first_s, C.PULSE_PERIOD_S
    age = t - (first + period * np.floor((t - first) / period))          # the time since the latest pulse began
    law = DEV16["motor_flying_shear_cut"].torque(age, pulse, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * np.max(np.abs(tx))
    on = pulse > 0.5
    assert on.any() and (~on).any()
    assert np.all(np.abs(tx[~on]) < 1e-6)                               # nothing between the strokes
    assert np.max(tx) > 0.99 * p["torque_Nm"]                           # its peak reached ...
    assert abs(age[np.argmax(tx)] - p["cut_delay_s"]) <= C.SAMPLE_PERIOD_S   # ... at t_c into the stroke
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_hydrostatic_booster_drives_the_wheel_with_the_motor_speed_squared():
    p = _params("wheel_hydrostatic_booster")
    c = p["coefficient_Nm_s2_per_rad2"]
    rec = rec_of("wheel_hydrostatic_booster", **p)
    tx, w1, w2 = wheel_term_Nm(rec), rec.signals["omega1"], rec.signals["omega2"]
    assert np.max(np.abs(tx - DEV16["wheel_hydrostatic_booster"].torque(w1, p))) < 1e-6 * np.max(np.abs(tx))
    assert np.all(tx > 0.0)                                              # it drives the wheel
    assert np.allclose(tx / w1 ** 2, c, rtol=1e-6)
    # the motor's speed, not the wheel's: the term is no function of Omega2 where the two differ
    assert np.max(np.abs(tx - c * w2 ** 2)) > 100.0 * np.max(np.abs(tx - c * w1 ** 2))
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_friction_plate_is_a_dry_friction_of_the_slip_pressed_by_the_spring_extension():
    p = _params("clutch_cable_loaded_friction_plate")
    rec = rec_of("clutch_cable_loaded_friction_plate", **p)
    extra, z = extra_clutch_Nm(rec), rec.internal["spring_extension"]
    s = rec.signals["omega1"] - rec.signals["omega2"]
    law = DEV16["clutch_cable_loaded_friction_plate"].torque(s, z, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(extra))
    gap = rec.internal["mode"] == 0
    assert np.max(np.abs(extra[gap])) > 0.5                              # in the gap too
    # dry: well beyond its slip scale the torque is the normal force times mu, whatever the slip's size
    fast = np.abs(s) > 5.0 * p["slip_scale_rad_s"]
    assert fast.any()
    press = p["coefficient_Nm_per_m"] * np.maximum(0.0, z[fast] - p["reference_m"])
    assert np.allclose(np.abs(extra[fast]), press, rtol=1e-3, atol=1e-6)
    assert np.all(np.sign(extra[fast]) == np.sign(s[fast]))              # it drags the faster half back
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_frame_shake_is_locked_to_the_motor_angle_and_grows_with_the_motor_speed_squared():
    p = _params("mass_motor_unbalance_frame_shake")
    rec = rec_of("mass_motor_unbalance_frame_shake", **p)
    fx, w1, a1 = mass_term_N(rec), rec.signals["omega1"], rec.internal["alpha1"]
    law = DEV16["mass_motor_unbalance_frame_shake"].force(w1, a1, p)
    assert np.max(np.abs(fx - law)) < 1e-6 * np.max(np.abs(fx))
    # on the motor's angle, not the wheel's: a fit of sin/cos of alpha1 (scaled by Omega1^2) explains it all
    q = fx / w1 ** 2
    (cs, cc), *_ = np.linalg.lstsq(np.column_stack([np.sin(a1), np.cos(a1)]), q, rcond=None)
    assert np.hypot(cs, cc) == pytest.approx(p["coefficient_N_s2_per_rad2"], rel=1e-6)
    assert np.arctan2(cc, cs) == pytest.approx(p["phase_rad"], abs=1e-6)
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_drag_chain_shifts_a2s_zero_by_the_carriage_speeds_direction():
    p = _params("a2_drag_chain_triboelectric")
    rec = rec_of("a2_drag_chain_triboelectric", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])
    extra, v = rec.signals["a2"] - clean().signals["a2"], rec.internal["mass_speed"]
    read = DEV16["a2_drag_chain_triboelectric"].read(np.zeros_like(v), v, p)
    assert np.max(np.abs(extra - read)) < 1e-12
    # odd and saturating: reversed, the chain shifts it the other way; far beyond v_s it is the offset itself
    assert np.allclose(DEV16["a2_drag_chain_triboelectric"].read(np.zeros(3), -np.array([1.0, 5.0, 20.0]), p),
                       -DEV16["a2_drag_chain_triboelectric"].read(np.zeros(3), np.array([1.0, 5.0, 20.0]), p))
    fast = np.abs(v) > 10.0 * p["speed_scale_m_s"]
    assert fast.any() and np.allclose(extra[fast], p["offset_m_s2"] * np.sign(v[fast]), rtol=1e-6)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_wheel_overspeed_fires_the_carriages_rail_brake_for_its_hold_time():
    p = _params("mass_wheel_overspeed_timed_rail_brake")
    rec = rec_of("mass_wheel_overspeed_timed_rail_brake", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-9
    on = -fx[::SEG] / p["force_N"]
    assert np.all((np.abs(on) < 1e-6) | (np.abs(on - 1.0) < 1e-6))     # all or nothing
    on = np.round(on)
    w2 = rec.signals["omega2"][::SEG]                                    # the wheel speed at each scan's start
    i0 = int(np.argmax(on[:-1] == 0.0)) + 1                              # a scan after one with the brake off
    pred = DEV16["mass_wheel_overspeed_timed_rail_brake"].on(w2[i0:], p, DT, state0=(0.0, 0, w2[i0 - 1]))
    assert np.array_equal(pred, on[i0:])
    rises = np.flatnonzero(np.diff(on) > 0.5) + 1
    assert rises.size >= 1
    n_h = round(p["hold_s"] / DT)
    wt = p["trip_speed_rad_s"]
    for r in rises:
        assert w2[r - 1] <= wt < w2[r]                                   # fired by the wheel rising through Omega_t
        if r + n_h < on.size:
            assert np.all(on[r:r + n_h] == 1.0)
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_peak_tension_brake_loads_the_motor_by_the_extensions_peak_since_the_stroke_began():
    p = _params("motor_peak_tension_regen_brake")
    c, z0 = p["coefficient_Nm_per_m"], p["reference_m"]
    rec = rec_of("motor_peak_tension_regen_brake", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * max(1.0, np.max(np.abs(tx)))   # held between its 0.2 ms scans
    brake = tx[::SEG]
    assert np.all(brake >= -1e-6) and np.any(brake > 0.5)
    z = rec.internal["spring_extension"][::SEG]                          # the extension at each scan's start
    starts = np.flatnonzero(np.diff(_pulse(rec)[::SEG]) > 0.5) + 1      # each load pulse's first scan
    assert starts.size >= 2
    counts = np.cumsum(np.isin(np.arange(z.size), starts))
    i0 = starts[0]                                                       # the peak cleared: m = z there
    pred = DEV16["motor_peak_tension_regen_brake"].held(z[i0:], counts[i0:])
    assert np.max(np.abs(c * np.maximum(0.0, pred - z0) - brake[i0:])) < 1e-5 * np.max(brake)
    # a peak hold: within a stroke the brake never lets go; it drops at a stroke's first scan only
    falls = np.flatnonzero(brake[i0 + 1:] < brake[i0:-1] - 1e-6) + i0 + 1
    assert set(falls.tolist()) <= set(starts.tolist())
    others_zero(rec, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED16))
def test_sealed16_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED16[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set16_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(16, DEV16, SEALED16, 16000, 16100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (three with its single scaling)."""
    assert_rows_visible(("outside_dev16", "outside_sealed16"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev16", "outside_sealed16"))


@pytest.mark.parametrize("suite_name", ["outside_dev16", "outside_sealed16"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED16, DEV16)


def test_outside_bench_knows_set_16_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-16 are spent (set 16's sealed half ran once, 1 Dec, stop 53): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(16, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(16)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(16, DURATION_S)
