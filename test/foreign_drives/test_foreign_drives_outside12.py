"""The twelfth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev12,
.outside_sealed12): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the choked water brake, the pump-fed retarder, the hydrodynamic coupling, the tacho-fed eddy brake, the cable
echo, the lost-motion friction link, the stroke-gated cushion pump), every sealed mechanism acting in its recorded
balance only, the suites (made, written, deterministic, each mechanism row visible above the criterion its strength was
set by), ``forms`` withholding the sealed laws, and the outside bench's set 12 (its sealed half spent since its one run:
in the loop's default suites and the alarm check).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations


import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_drives.drive import pulse_indicator
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

SET = OutsideSet(12, seed=212)
DEV12, SEALED12, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


# ------------------------------------------------------------------ registry and truth vocabulary
def test_twelfth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(12)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_choked_water_brake": {"coefficient_Nm_s2_per_rad2": 0.0},
           "wheel_pump_fed_retarder": {"torque_Nm_per_l": 0.0},
           "clutch_hydrodynamic_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_tacho_fed_eddy_brake": {"coefficient_N_s_per_m": 0.0}, "a2_cable_echo": {"reflection": 0.0},
           "mass_lost_motion_friction_link": {"force_N": 0.0},
           "wheel_stroke_gated_cushion_pump": {"coefficient_Nm_s_per_rad": 0.0},
           "motor_rate_limited_conveyor": {"coefficient_Nm_s_per_rad": 0.0},
           "wheel_staged_retarder": {"stage_torque_Nm": 0.0},
           "clutch_fieldbus_slip_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_stroke_hooked_return_spring": {"stiffness_N_per_m": 0.0},
           "a2_transmitter_pre_emphasis": {"coefficient": 0.0},
           "clutch_centrifugally_bypassed_damper": {"coefficient_Nm_s_per_rad": 0.0}}
# a nonlinearity of the sensor without a neutral value inside its bounds: checked in its balance only
NO_NEUTRAL = {"a1_quadratic_distortion"}


@pytest.mark.parametrize("name", sorted((set(DEV12) | set(SEALED12)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) | NO_NEUTRAL == set(DEV12) | set(SEALED12)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_choked_water_brake_is_quadratic_below_its_choke_and_linear_in_the_motor_speed_above():
    p = _params("motor_choked_water_brake")
    law = DEV12["motor_choked_water_brake"].torque
    c, wc = p["coefficient_Nm_s2_per_rad2"], p["choke_speed_rad_s"]
    slow = np.linspace(0.1 * wc, 0.9 * wc, 9)
    fast = np.linspace(1.1 * wc, 2.0 * wc, 9)
    assert np.allclose(law(slow, p) / slow ** 2, c) and np.allclose(law(fast, p) / fast, c * wc)   # order 2 -> 1
    rec = rec_of("motor_choked_water_brake", **p)
    tx, w1 = motor_term_Nm(rec), rec.signals["omega1"]
    assert np.max(np.abs(tx - law(w1, p))) < 1e-6 * np.max(np.abs(tx))
    # loaded so, the motor runs below the choke (a clean drive: 147.6-153.7 rad/s): the recorded load over Omega1^2 is
    # c there, and over Omega1 it is c*Omega_c wherever the motor is above it
    below = w1 < wc
    assert below.any() and np.allclose(tx[below] / w1[below] ** 2, c, rtol=1e-6)
    assert np.allclose(tx[~below] / w1[~below], c * wc, rtol=1e-6)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_pump_fed_retarder_brakes_with_its_fill_which_the_wheel_speed_pumps_and_an_orifice_drains():
    p = _params("wheel_pump_fed_retarder")
    rec = rec_of("wheel_pump_fed_retarder", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-9                          # held between its 0.2 ms scans
    m, w = -tx[::SEG] / p["torque_Nm_per_l"], rec.signals["omega2"][::SEG]
    pred = DEV12["wheel_pump_fed_retarder"].fill(w[1:], p, DT, m0=m[0])
    assert np.max(np.abs(pred - m[1:])) < 1e-6 * np.max(m)
    # settled (the run-in is 2 s): inflow = outflow, sqrt(m) = a*Omega2/b on the mean
    assert np.mean(m) == pytest.approx((p["inflow_l_per_rad"] * np.mean(w) / p["drain_l_s_per_sqrt_l"]) ** 2, rel=0.02)
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_hydrodynamic_coupling_passes_the_slip_times_the_pump_speed_in_the_gap_and_in_contact():
    p = _params("clutch_hydrodynamic_coupling")
    rec = rec_of("clutch_hydrodynamic_coupling", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    w1, w2 = rec.signals["omega1"], rec.signals["omega2"]
    assert np.max(np.abs(extra - DEV12["clutch_hydrodynamic_coupling"].torque(w1, w2, p))) < 1e-6
    slip = w1 - w2
    big = np.abs(slip) > 1.0
    # the coefficient of the slip is c*Omega1/150 rad/s: it follows the motor's speed
    assert np.allclose(extra[big] / slip[big], p["coefficient_Nm_s_per_rad"] * w1[big] / 150.0, rtol=1e-6)
    gap = np.abs(i["jaw_angle_difference"]) < i["parameters"][K.P_BETA]
    assert np.max(np.abs(extra[gap])) > 0.5
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_tacho_fed_eddy_brake_damps_the_mass_in_proportion_to_the_motor_speed():
    p = _params("mass_tacho_fed_eddy_brake")
    rec = rec_of("mass_tacho_fed_eddy_brake", **p)
    fx, v, w1 = mass_term_N(rec), rec.internal["mass_speed"], rec.signals["omega1"]
    assert np.max(np.abs(fx - DEV12["mass_tacho_fed_eddy_brake"].force(v, w1, p))) < 1e-6
    # the damping coefficient -F/v is c*Omega1/150 rad/s, not a constant: it spans the motor speed's range
    coef = -fx / v
    assert np.allclose(coef, p["coefficient_N_s_per_m"] * w1 / 150.0, rtol=1e-6) and np.ptp(coef) > 0.01 * coef.mean()
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_cable_echo_adds_one_delayed_copy_of_a2():
    p = _params("a2_cable_echo")
    read, d = DEV12["a2_cable_echo"].read, int(p["delay_samples"])
    impulse = np.zeros(50)
    impulse[10] = 1.0
    y = read(impulse, p)
    assert y[10] == 1.0 and y[10 + d] == pytest.approx(p["reflection"]) and np.count_nonzero(y) == 2
    rec = rec_of("a2_cable_echo", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    a, y = clean().signals["a2"], rec.signals["a2"]
    assert np.allclose(y[d:], a[d:] + p["reflection"] * a[:-d], rtol=0, atol=1e-9)
    assert np.sqrt(np.mean((y - a) ** 2)) > 0.05


def test_lost_motion_link_springs_across_its_slot_and_drags_its_slider_at_the_slot_ends():
    p = _params("mass_lost_motion_friction_link")
    rec = rec_of("mass_lost_motion_friction_link", **p)
    fx, z = mass_term_N(rec), rec.internal["spring_extension"]
    f, a = p["force_N"], p["half_slot_m"]
    # at each scan never more than the clamp's friction (between scans the slider is held: the pads spring on)
    assert np.max(np.abs(fx[::SEG])) <= f * (1 + 1e-9)
    s_scan = z[::SEG] - fx[::SEG] * a / f                                # the slider at each scan
    pred = DEV12["mass_lost_motion_friction_link"].slider(z[::SEG][1:], p, s0=s_scan[0])
    assert np.max(np.abs(pred - s_scan[1:])) < 1e-9
    s = np.repeat(s_scan, SEG)[:z.size]
    assert np.max(np.abs(fx - f * (z - s) / a)) < 1e-6                   # a spring F/a across the slot in between
    at_end = np.abs(np.abs(fx[::SEG]) - f) < 1e-9
    assert at_end.any() and (~at_end).any()                               # dragging and inside the slot both occur
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_cushion_pump_loads_the_wheel_with_its_speed_only_while_the_pulse_is_on():
    p = _params("wheel_stroke_gated_cushion_pump")
    rec = rec_of("wheel_stroke_gated_cushion_pump", **p)
    tx, w2 = wheel_term_Nm(rec), rec.signals["omega2"]
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    on = pulse_indicator(t, rec.spec.pulse_first_s)
    assert on.any() and (on == 0).any()
    assert np.max(np.abs(tx - DEV12["wheel_stroke_gated_cushion_pump"].torque(w2, on, p))) < 1e-6
    assert np.max(np.abs(tx[on == 0])) < 1e-9 and np.max(np.abs(tx[on > 0])) > 0.5
    others_zero(rec, motor_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED12))
def test_sealed12_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED12[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set12_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(12, DEV12, SEALED12, 12000, 12100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s)."""
    assert_rows_visible(("outside_dev12", "outside_sealed12"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev12", "outside_sealed12"))


@pytest.mark.parametrize("suite_name", ["outside_dev12", "outside_sealed12"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED12, DEV12)


def test_outside_bench_knows_set_12_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-12 are spent (set 12's sealed half ran once, 30 Nov, stop 49): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(12, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(12)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(12, DURATION_S)
