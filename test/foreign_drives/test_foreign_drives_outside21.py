"""The twenty-first set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev21,
.outside_sealed21): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the self-excited generator's squared excess of the motor's speed on the motor, the gap guard's on-delayed
holding brake on the wheel, the viscoelastic boot's Maxwell element across the jaw, the averaged-speed booster on the
carriage, a1's torque-following hum, a2's drum-encoder-clocked hold, the metering-land damper across the jaw), every
sealed mechanism acting in its recorded balance only, the suites (made, written, deterministic, each mechanism row
visible above the criterion its strength was set by, but one sealed row left below it as written), ``forms``
withholding the sealed laws, and the outside bench's set 21 (its sealed half spent: run once at stop 58, in the
loop's default suites and the alarm check).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import numpy as np
import pytest

from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_acts_in_its_balance_only, assert_forms_withholds_sealed,
                                        assert_recordings_repeat, assert_rows_visible, assert_set_registry,
                                        assert_set_suites, assert_suite_writes_one_recording)
from foreign_outside_recordings import assert_alarm_check_covers_both_halves, assert_bench_guards_unspent_sealed  # test/
from foreign_outside_recordings import assert_acts_in_its_balance_only_on_its_suite_row  # test/
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero, sample_times_s, slip_rad_s  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(21, seed=221)
DEV21, SEALED21, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _gap_distance(rec):
    """The kernel's XS_GAP_DISTANCE: beta - |D| while the jaw is free, -1 in contact."""
    beta = rec.internal["parameters"][K.P_BETA]
    d = rec.internal["jaw_angle_difference"]
    return np.where(rec.internal["mode"] == 0, beta - np.abs(d), -1.0)


def test_twenty_first_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(21)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_self_excited_generator": {"coefficient_Nm_s2_per_rad2": 0.0},
           "wheel_gap_guard_holding_brake": {"torque_Nm": 0.0},
           "clutch_viscoelastic_boot": {"stiffness_Nm_per_rad": 0.0},
           "mass_averaged_speed_booster": {"gain_N_s_per_m": 0.0},
           "a1_torque_following_hum": {"coefficient_m_s2": 0.0},
           "clutch_metering_land_damper": {"coefficient_Nm_s_per_rad": 0.0},
           "motor_wheel_overspeed_relay_eddy_brake": {"coefficient_Nm_s_per_rad": 0.0},
           "wheel_ac_fed_eddy_brake": {"coefficient_Nm_s_per_rad": 0.0},
           "clutch_pi_slip_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_cable_span_whirl": {"force_N": 0.0},
           "a2_packet_loss_repetition": {"loss_rate": 0.0},
           "motor_converter_fed_induction_machine": {"pull_out_torque_Nm": 0.0},
           "wheel_centrifugal_speed_brake": {"torque_Nm": 0.0}}
# a resampling of the sensor without a neutral value inside its bounds: checked in its balance only
NO_NEUTRAL = {"a2_drum_encoder_clocked_hold"}


@pytest.mark.parametrize("name", sorted((set(DEV21) | set(SEALED21)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) | NO_NEUTRAL == set(DEV21) | set(SEALED21)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_self_excited_generator_brakes_the_motor_with_the_square_of_its_speeds_excess():
    p = _params("motor_self_excited_generator")
    c, wc = p["coefficient_Nm_s2_per_rad2"], p["critical_speed_rad_s"]
    rec = rec_of("motor_self_excited_generator", **p)
    tx, w1 = motor_term_Nm(rec), rec.signals["omega1"]
    law = DEV21["motor_self_excited_generator"].torque(w1, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * max(1.0, np.max(law))
    # nothing below the critical speed, the excess's square above it (not its proportion)
    below, above = w1 < wc - 1e-3, w1 > wc + 1.0
    assert below.any() and above.any()
    assert np.max(np.abs(tx[below])) < 1e-6
    assert np.allclose(tx[above] / (w1[above] - wc) ** 2, c, rtol=1e-4)
    assert np.max(tx) > 0.5
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_gap_guard_applies_the_wheel_brake_once_the_jaw_has_stayed_open_for_its_delay():
    p = _params("wheel_gap_guard_holding_brake")
    tq = p["torque_Nm"]
    rec = rec_of("wheel_gap_guard_holding_brake", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * tq                       # held between its 0.2 ms scans
    m = -tx[::SEG] / tq
    assert np.all((np.abs(m) < 1e-6) | (np.abs(m - 1.0) < 1e-6))           # on or off
    gap = _gap_distance(rec)[::SEG]                                       # the gap distance at each scan's start
    # from the first scan with the faces nearer than h_t (the timer reset), the law scan by scan
    j = int(np.flatnonzero(gap <= p["gap_rad"])[0])
    pred = DEV21["wheel_gap_guard_holding_brake"].states(gap[j + 1:], p, DT)
    assert np.array_equal(pred, np.round(m[j + 1:]))
    # an on-delay, not a switch: the jaw opens further than h_t more often than the brake comes on, and the brake is
    # never on in contact
    assert pred.any() and np.count_nonzero(gap > p["gap_rad"]) > np.count_nonzero(pred)
    assert np.all(pred[gap[j + 1:] < 0.0] == 0.0)
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_viscoelastic_boot_passes_the_jaws_twist_less_its_relaxed_part():
    p = _params("clutch_viscoelastic_boot")
    k = p["stiffness_Nm_per_rad"]
    rec = rec_of("clutch_viscoelastic_boot", **p)
    extra, d = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"]
    q = d - extra / k                                                     # the relaxed twist the term implies
    assert np.max(held_per_segment(q)) < 1e-9                            # advanced once a scan
    qs, ds = q[::SEG], d[::SEG]
    pred = DEV21["clutch_viscoelastic_boot"].relaxed(ds[1:], p, DT, qs[0])
    assert np.max(np.abs(pred - qs[1:])) < 1e-9
    # a relaxation, not a spring: q creeps after D and the boot passes torque in the gap too
    gap = rec.internal["mode"] == 0
    assert gap.any() and np.max(np.abs(extra[gap])) > 0.1
    assert np.ptp(qs) > 0.2 * np.ptp(ds) and np.max(np.abs(ds - qs)) > 0.01
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_booster_pushes_the_carriage_by_the_limited_excess_of_its_averaged_speed():
    p = _params("mass_averaged_speed_booster")
    kg, n = p["gain_N_s_per_m"], int(p["window_scans"])
    rec = rec_of("mass_averaged_speed_booster", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-9 * kg                      # held between its 0.2 ms scans
    v = rec.internal["mass_speed"][::SEG]                                 # the carriage's speed at each scan's start
    mean = np.convolve(v, np.ones(n) / n, mode="valid")                   # over the last n scans, from scan n - 1
    law = DEV21["mass_averaged_speed_booster"].force(mean, p)
    assert np.max(np.abs(law - fx[::SEG][n - 1:])) < 1e-9 * kg
    # a boxcar of the speed, not the speed itself, and limited to +-K*d
    assert np.max(np.abs(fx)) <= kg * p["limit_m_s"] * (1.0 + 1e-9)
    now = DEV21["mass_averaged_speed_booster"].force(v[n - 1:], p)
    assert np.max(np.abs(now - fx[::SEG][n - 1:])) > 0.1
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_torque_following_hum_adds_the_motors_torque_times_a_mains_sine_to_a1():
    p = _params("a1_torque_following_hum")
    rec = rec_of("a1_torque_following_hum", **p)
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
    assert np.array_equal(rec.internal["a1_physical"], clean().internal["a1_physical"])
    a1, te, t = rec.internal["a1_physical"], rec.internal["te_pu"], sample_times_s(rec)
    read = DEV21["a1_torque_following_hum"].read(a1, te, t, p)
    assert np.max(np.abs(rec.signals["a1"] - read)) < 1e-9 * np.max(np.abs(a1))
    # an additive hum whose amplitude is the torque: the error over the mains sine is k*t_e wherever the sine is large
    err = rec.signals["a1"] - a1
    s = np.sin(2.0 * np.pi * p["mains_hz"] * t + p["phase_rad"])
    big = np.abs(s) > 0.5
    assert np.allclose(err[big] / s[big], p["coefficient_m_s2"] * te[big], rtol=1e-6, atol=1e-9)
    assert np.ptp(te) > 0.2 and np.max(np.abs(err)) > 0.3
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_drum_encoder_clocked_hold_samples_a2_at_the_encoders_pulses():
    p = _params("a2_drum_encoder_clocked_hold")
    rec = rec_of("a2_drum_encoder_clocked_hold", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    a2 = rec.internal["a2_physical"]
    form = DEV21["a2_drum_encoder_clocked_hold"]
    marks = form.pulse_marks(rec.internal["alpha2"], p)
    # the pulses: N a turn of the wheel
    turns = np.ptp(np.unwrap(rec.internal["alpha2"])) / (2.0 * np.pi)
    assert abs(marks.size - int(p["pulses_per_turn"]) * turns) <= 1.5
    # from the first pulse in the recording on, a2 is the sample taken at the latest pulse (the earlier ones fell in the
    # pre-roll)
    y = form.read(a2, rec.internal["alpha2"], p)
    assert np.array_equal(rec.signals["a2"][marks[0]:], y[marks[0]:])
    assert np.all(rec.signals["a2"][marks] == a2[marks])
    held = rec.signals["a2"][marks[0]:]
    assert np.count_nonzero(np.diff(held)) == marks.size - 1
    assert np.max(np.abs(rec.signals["a2"] - a2)) > 0.05
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_metering_land_damps_the_slip_most_while_the_jaw_is_aligned():
    p = _params("clutch_metering_land_damper")
    c, w = p["coefficient_Nm_s_per_rad"], p["land_rad"]
    rec = rec_of("clutch_metering_land_damper", **p)
    extra, d, s = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"], slip_rad_s(rec)
    law = DEV21["clutch_metering_land_damper"].torque(s, d, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * max(1.0, np.max(np.abs(extra)))
    # a damping whose coefficient is a Lorentzian of the twist: c aligned, c/2 at w, and in the gap too
    moving = np.abs(s) > 0.1
    coeff = extra[moving] / s[moving]
    assert np.allclose(coeff, c / (1.0 + (d[moving] / w) ** 2), rtol=1e-6)
    assert np.max(coeff) > 0.9 * c and np.min(coeff) < 0.5 * c
    gap = rec.internal["mode"] == 0
    assert gap.any() and np.max(np.abs(extra[gap])) > 0.1
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
# a sealed mechanism that acts now and then, which this file's 0.6 s drive hardly sees: checked on its suite row's own
# drive without noise (4 s), at twice its suite strength
ON_ITS_SUITE_ROW = {"a2_packet_loss_repetition": "loss_rate"}


@pytest.mark.parametrize("name", sorted(SEALED21))
def test_sealed21_mechanism_acts_in_its_recorded_balance_only(name):
    if name not in ON_ITS_SUITE_ROW:
        assert_acts_in_its_balance_only(name, SEALED21[name].balance, rec_of(name, **_params(name)), clean())
        return
    assert_acts_in_its_balance_only_on_its_suite_row(name, SEALED21[name].balance, "outside_sealed21", _params(name),
                                                     ON_ITS_SUITE_ROW[name])


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set21_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(21, DEV21, SEALED21, 21000, 21100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (six with their single scaling) but one sealed row its
    module leaves below it as written (why: in the sealed file only)."""
    assert_rows_visible(("outside_dev21", "outside_sealed21"), below={"os21_a2_packet_loss_repetition"})


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev21", "outside_sealed21"))


@pytest.mark.parametrize("suite_name", ["outside_dev21", "outside_sealed21"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED21, DEV21)


def test_outside_bench_knows_set_21_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-21 are spent (set 21's sealed half ran once, 2 Dec, stop 58): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(21, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(21)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(21, DURATION_S)
