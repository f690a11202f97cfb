"""The thirteenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev13,
.outside_sealed13): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the paste mixer, the relief-valve pump, the hysteresis coupling, the wheel-tracking conveyor, the motor magnet's
pickup, the overspeed timed brake, the slip-pumped plate clutch), every sealed mechanism acting in its recorded balance
only, the suites (made, written, deterministic, each mechanism row visible above the criterion its strength was set by),
``forms`` withholding the sealed laws, and the outside bench's set 13 (spent: its sealed half ran once, at stop 50; the
loop's default suites and the alarm check hold both halves).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations


import numpy as np
import pytest

from foreign_drives import noise as N
from foreign_balance_terms import contact_law_Nm, mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_acts_in_its_balance_only, assert_forms_withholds_sealed,
                                        assert_recordings_repeat, assert_rows_visible, assert_set_registry,
                                        assert_set_suites, assert_suite_writes_one_recording)
from foreign_outside_recordings import (assert_alarm_check_covers_both_halves,  # test/
                                        assert_bench_guards_unspent_sealed)
from foreign_outside_recordings import held_per_segment, others_zero  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(13, seed=213)
DEV13, SEALED13, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


# ------------------------------------------------------------------ registry and truth vocabulary
def test_thirteenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(13)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_paste_mixer": {"coefficient_Nm": 0.0},
           "wheel_relief_valve_pump": {"coefficient_Nm_s_per_rad": 0.0},
           "clutch_hysteresis_coupling": {"torque_Nm": 0.0},
           "mass_wheel_tracking_conveyor": {"coefficient_N_s_per_m": 0.0},
           "a2_motor_magnet_pickup": {"amplitude_m_s2": 0.0},
           "motor_overspeed_timed_brake": {"torque_Nm": 0.0},
           "clutch_slip_pumped_plate_clutch": {"torque_Nm_per_cm3": 0.0},
           "motor_tuned_torsional_absorber": {"inertia_kgm2": 0.0},
           "wheel_impulse_relay_brake": {"torque_Nm": 0.0},
           "clutch_slip_monitored_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_friction_held_payload": {"friction_force_N": 0.0},
           "a2_asymmetric_rail_clip": {"positive_rail_m_s2": 100.0, "negative_rail_m_s2": 100.0},
           "mass_cable_ferrule_detent": {"force_N": 0.0}}
# a resampling of the sensor without a neutral value inside its bounds: checked in its balance only
NO_NEUTRAL = {"a1_integrating_adc_hold"}


@pytest.mark.parametrize("name", sorted((set(DEV13) | set(SEALED13)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit (the
    payload with no friction is carried by nothing; the rails far outside a2's range clip nothing)."""
    assert set(NEUTRAL) | NO_NEUTRAL == set(DEV13) | set(SEALED13)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_paste_mixer_loads_the_motor_with_the_logarithm_of_its_speed_above_its_reference():
    p = _params("motor_paste_mixer")
    law = DEV13["motor_paste_mixer"].torque
    c, w0 = p["coefficient_Nm"], p["reference_speed_rad_s"]
    below = np.linspace(0.1 * w0, w0, 9)
    assert np.all(law(below, p) == 0.0)
    # each e-fold of speed above Omega_0 adds c: equal steps of the load for equal ratios of the speed
    ratios = np.exp(np.arange(1, 6) * 0.25)
    assert np.allclose(np.diff(law(w0 * ratios, p)), 0.25 * c)
    rec = rec_of("motor_paste_mixer", **p)
    tx, w1 = motor_term_Nm(rec), rec.signals["omega1"]
    assert np.all(w1 > w0) and np.max(np.abs(tx - law(w1, p))) < 1e-6 * np.max(np.abs(tx))
    assert np.allclose(np.exp(tx / c) * w0, w1, rtol=1e-6)        # the speed recovered from the load
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_relief_valve_pump_is_viscous_below_its_relief_speed_and_constant_above():
    p = _params("wheel_relief_valve_pump")
    c, wr = p["coefficient_Nm_s_per_rad"], p["relief_speed_rad_s"]
    rec = rec_of("wheel_relief_valve_pump", **p)
    tx, w2 = wheel_term_Nm(rec), rec.signals["omega2"]
    assert np.max(np.abs(tx - DEV13["wheel_relief_valve_pump"].torque(w2, p))) < 1e-6
    below = np.abs(w2) < wr
    assert below.any() and (~below).any()                      # the wheel runs on both sides of the relief speed
    assert np.allclose(tx[below] / w2[below], -c, rtol=1e-6)
    assert np.allclose(tx[~below], -c * wr * np.sign(w2[~below]), rtol=1e-6)
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_hysteresis_coupling_passes_a_torque_nearly_independent_of_the_slip_in_the_gap_and_in_contact():
    p = _params("clutch_hysteresis_coupling")
    rec = rec_of("clutch_hysteresis_coupling", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    w1, w2 = rec.signals["omega1"], rec.signals["omega2"]
    assert np.max(np.abs(extra - DEV13["clutch_hysteresis_coupling"].torque(w1, w2, p))) < 1e-6
    slip = w1 - w2
    slipping = np.abs(slip) > 5 * p["smoothing_speed_rad_s"]
    assert slipping.any()
    # slipping, the torque is +-T_h whatever the slip's size (tanh(5) > 0.9999)
    assert np.allclose(np.abs(extra[slipping]), p["torque_Nm"], rtol=1e-4)
    assert np.all(np.sign(extra[slipping]) == np.sign(slip[slipping]))
    gap = i["mode"] == 0
    assert np.max(np.abs(extra[gap])) > 0.5 * p["torque_Nm"]
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_wheel_tracking_conveyor_drags_the_mass_towards_the_wheels_belt_speed():
    p = _params("mass_wheel_tracking_conveyor")
    rec = rec_of("mass_wheel_tracking_conveyor", **p)
    fx, v, w2 = mass_term_N(rec), rec.internal["mass_speed"], rec.signals["omega2"]
    assert np.max(np.abs(fx - DEV13["mass_wheel_tracking_conveyor"].force(w2, v, p))) < 1e-6
    # a linear law of the two speeds: the fit of F on (Omega2, v) gives c*r_b and -c
    coef, *_ = np.linalg.lstsq(np.column_stack([w2, v]), fx, rcond=None)
    c = p["coefficient_N_s_per_m"]
    assert coef == pytest.approx([c * p["belt_radius_m"], -c], rel=1e-6)
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_motor_magnet_pickup_adds_to_a2_a_wave_of_the_motor_angle_growing_with_the_motor_speed():
    p = _params("a2_motor_magnet_pickup")
    rec = rec_of("a2_motor_magnet_pickup", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    extra = rec.signals["a2"] - clean().signals["a2"]
    w1, alpha1 = rec.signals["omega1"], rec.internal["alpha1"]
    assert np.max(np.abs(extra - DEV13["a2_motor_magnet_pickup"].read(0.0, alpha1, w1, p))) < 1e-9
    # divided by the speed's share, it is a pure sine of p*alpha1: its amplitude A at Omega1 = 150 rad/s
    wave = extra / (w1 / 150.0)
    k = int(p["pole_pairs"])
    basis = np.column_stack([np.sin(k * alpha1), np.cos(k * alpha1)])
    (s, co), *_ = np.linalg.lstsq(basis, wave, rcond=None)
    assert np.hypot(s, co) == pytest.approx(p["amplitude_m_s2"], rel=1e-6)
    assert np.arctan2(co, s) == pytest.approx(p["phase_rad"], abs=1e-6)


def test_overspeed_timed_brake_holds_its_torque_for_a_fixed_time_from_each_rising_crossing():
    p = _params("motor_overspeed_timed_brake")
    rec = rec_of("motor_overspeed_timed_brake", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-9                          # held between its 0.2 ms scans
    on = tx[::SEG] / p["torque_Nm"]
    assert np.all((np.abs(on) < 1e-9) | (np.abs(on - 1.0) < 1e-9))      # off or the full torque
    on = np.round(on)
    w = rec.signals["omega1"][::SEG]
    i0 = int(np.argmax(on == 0)) + 1                                    # after a scan with the brake off
    pred = DEV13["motor_overspeed_timed_brake"].on(w[i0 - 1:], p, DT)
    assert np.array_equal(pred[1:], on[i0:])
    # each firing lasts T_h whatever the speed does meanwhile (the whole pulses inside the recording)
    starts, ends = np.flatnonzero(np.diff(on) > 0) + 1, np.flatnonzero(np.diff(on) < 0) + 1
    assert starts.size >= 2
    lengths = [e - s for s in starts for e in ends[ends > s][:1]]
    assert lengths and all(n == round(p["hold_s"] / DT) for n in lengths)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_slip_pumped_plate_clutch_passes_a_friction_clamped_by_the_fill_the_slip_pumps_and_an_orifice_drains():
    p = _params("clutch_slip_pumped_plate_clutch")
    form = DEV13["clutch_slip_pumped_plate_clutch"]
    rec = rec_of("clutch_slip_pumped_plate_clutch", **p)
    extra = rec.internal["clutch_torque_Nm"] - contact_law_Nm(rec)
    slip = rec.signals["omega1"] - rec.signals["omega2"]
    g = np.tanh(slip / form.SMOOTHING_RAD_S)
    # the fill, held over each scan, from the torque where the friction's sign is clear
    clear = np.abs(g) > 0.5
    m = np.full(slip.size, np.nan)
    m[clear] = extra[clear] / (p["torque_Nm_per_cm3"] * g[clear])
    m_scan = m[::SEG]
    known = np.flatnonzero(np.isfinite(m_scan))
    assert known.size > 10 and np.nanmax(m_scan) > 0.0
    i0 = known[0]
    pred = form.fill(slip[::SEG][i0 + 1:], p, DT, m0=m_scan[i0])
    later = known[1:]
    assert np.max(np.abs(pred[later - i0 - 1] - m_scan[later])) < 1e-6 * np.nanmax(m_scan)
    n = slip.size // SEG * SEG
    within = np.repeat(m_scan[:n // SEG], SEG)
    ok = np.isfinite(within) & clear[:n]
    assert np.allclose(m[:n][ok], within[ok], rtol=1e-6, atol=1e-9)     # held between the scans
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED13))
def test_sealed13_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED13[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set13_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(13, DEV13, SEALED13, 13000, 13100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s)."""
    assert_rows_visible(("outside_dev13", "outside_sealed13"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev13", "outside_sealed13"))


@pytest.mark.parametrize("suite_name", ["outside_dev13", "outside_sealed13"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED13, DEV13)


def test_outside_bench_knows_set_13_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-13 are spent (set 13's sealed half ran once, 30 Nov, stop 50): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(13, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(13)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(13, DURATION_S)
