"""The fifteenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev15,
.outside_sealed15): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
kernel's new memory kind from its definition, the development laws checked on the drive's own balances and signals
(each term recovered from the recorded, noise-free states: the slip-monitor motor brake, the carriage runaway brake on
the wheel, the hardening elastomer spider, the stroke gas spring, a2's ground loop through the drive faces, the ratchet
cable tensioner, the knock-triggered rail brake), every sealed mechanism acting in its recorded balance only, the suites
(made, written, deterministic, each mechanism row visible above the criterion its strength was set by), ``forms``
withholding the sealed laws, and the outside bench's set 15 (its sealed half spent: run once at stop 52, in the
loop's default suites and the alarm check).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_drives.drive import pulse_indicator
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_acts_in_its_balance_only, assert_forms_withholds_sealed,
                                        assert_recordings_repeat, assert_rows_visible, assert_set_registry,
                                        assert_set_suites, assert_suite_writes_one_recording)
from foreign_outside_recordings import assert_alarm_check_covers_both_halves, assert_bench_guards_unspent_sealed  # test/
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(15, seed=215)
DEV15, SEALED15, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _pulse(rec):
    """The load pulse's indicator at each sample (the kernel's held one)."""
    return pulse_indicator(np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S, rec.spec.pulse_first_s)


# ------------------------------------------------------------------ registry and truth vocabulary
def test_fifteenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(15)


# each mechanism's neutral setting at its suite's parameters: a strength 0 (a latency of 0 samples)
NEUTRAL = {"motor_slip_monitor_brake": {"coefficient_Nm_s_per_rad": 0.0},
           "wheel_carriage_runaway_brake": {"coefficient_Nm_s_per_m": 0.0},
           "clutch_hardening_elastomer_spider": {"stiffness_Nm_per_rad3": 0.0},
           "mass_stroke_gas_spring": {"stiffness_N_per_m": 0.0},
           "a2_drive_face_ground_loop": {"offset_m_s2": 0.0},
           "wheel_ratchet_cable_tensioner": {"coefficient_Nm_per_m": 0.0},
           "mass_knock_triggered_rail_brake": {"force_N": 0.0},
           "motor_pi_speed_limit_brake": {"max_torque_Nm": 0.0},
           "wheel_drive_contact_fill_brake": {"torque_Nm": 0.0},
           "clutch_heat_thinned_viscous_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_wire_rope_strand_friction": {"friction_force_N": 0.0},
           "a1_telemetry_buffer_latency": {"latency_samples": 0},
           "a2_tacho_shared_return": {"gain_m_s2_per_rad_s": 0.0},
           "motor_jaw_gap_approach_brake": {"torque_Nm": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV15) | set(SEALED15)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV15) | set(SEALED15)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the kernel's new memory kind
def test_the_kernels_stroke_peak_is_a_running_maximum_reset_at_each_pulses_first_scan():
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND] = float(K.MK_STROKE_PEAK)
    xs, counts = [1.0, 0.5, 2.0, 1.5, 0.2, 0.7, 0.1, 3.0], [0, 0, 0, 0, 1, 1, 2, 2]
    out = []
    for x, k in zip(xs, counts):
        P[K.P_PCOUNT] = float(k)
        K._memory_scan15(K.MK_STROKE_PEAK, x, P)
        out.append(P[K.P_MEMSTATE])
    assert out == [1.0, 1.0, 2.0, 2.0, 0.2, 0.7, 0.1, 3.0]
    # the same from the dispatcher, reading the time as its input (kinds below 33 never reach it)
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND], P[K.P_MEMSEL] = float(K.MK_STROKE_PEAK), float(K.XS_TIME)
    y = np.zeros(K.N_STATES)
    for t in (0.3, 0.1, 0.2):
        K.memory_scan(t, y, P, 0, DT)
    assert P[K.P_MEMSTATE] == 0.3
    assert K.MK_STROKE_PEAK == 33 and K.MK_STROKE_PEAK > max(K.MK_MAG_COUPLING, K.MK_OFF_DELAY, K.MK_FILL,
                                                              K.MK_RATE_STATE)


# ------------------------------------------------------------------ the development laws
def test_slip_monitor_brake_loads_the_motor_with_the_slips_magnitude_either_way():
    p = _params("motor_slip_monitor_brake")
    c = p["coefficient_Nm_s_per_rad"]
    rec = rec_of("motor_slip_monitor_brake", **p)
    tx, w1, w2 = motor_term_Nm(rec), rec.signals["omega1"], rec.signals["omega2"]
    assert np.max(np.abs(tx - DEV15["motor_slip_monitor_brake"].torque(w1, w2, p))) < 1e-6 * np.max(np.abs(tx))
    assert np.all(tx >= -1e-6)                                          # a brake whichever half runs ahead
    s = w1 - w2
    ahead, behind = s > 0.5, s < -0.5
    assert ahead.any() and behind.any()
    assert np.polyfit(s[ahead], tx[ahead], 1) == pytest.approx([c, 0.0], abs=1e-6 * c * 100)
    assert np.polyfit(s[behind], tx[behind], 1) == pytest.approx([-c, 0.0], abs=1e-6 * c * 100)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_carriage_runaway_brake_brakes_the_wheel_beyond_the_carriages_trip_speed_not_the_wheels():
    p = _params("wheel_carriage_runaway_brake")
    k, v0 = p["coefficient_Nm_s_per_m"], p["trip_speed_m_s"]
    rec = rec_of("wheel_carriage_runaway_brake", **p)
    tx, v = wheel_term_Nm(rec), rec.internal["mass_speed"]
    assert np.max(np.abs(tx - DEV15["wheel_carriage_runaway_brake"].torque(v, p))) < 1e-6 * max(1.0, np.max(np.abs(tx)))
    over = v > v0
    assert over.any() and (~over).any()                                # the carriage runs on both sides of v_0
    assert np.all(np.abs(tx[~over]) < 1e-6)
    assert np.polyfit(v[over], tx[over], 1) == pytest.approx([-k, k * v0], rel=1e-5)
    # the carriage's speed, not the wheel's rim: samples with the rim beyond v_0 and the carriage below it stay unbraked
    rim = C.WHEEL_RADIUS_M * rec.signals["omega2"]
    rim_only = (rim > v0 + 0.05) & ~over
    assert rim_only.any() and np.all(np.abs(tx[rim_only]) < 1e-6)
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_elastomer_spider_is_a_cubic_spring_across_the_jaw_in_the_gap_and_in_contact():
    p = _params("clutch_hardening_elastomer_spider")
    rec = rec_of("clutch_hardening_elastomer_spider", **p)
    extra, d = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"]
    law = DEV15["clutch_hardening_elastomer_spider"].torque(d, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(extra))
    clear = np.abs(d) > 1e-3
    assert np.allclose(extra[clear] / d[clear] ** 3, p["stiffness_Nm_per_rad3"], rtol=1e-6)
    assert np.all(np.sign(extra[clear]) == np.sign(d[clear]))        # it centres the halves (odd, restoring)
    gap = rec.internal["mode"] == 0
    assert np.max(np.abs(extra[gap])) > 0.5                          # in the gap too
    # hardening: at twice the angle, eight times the torque (not a linear spring)
    big, small = clear & (np.abs(d) > 0.03), clear & (np.abs(d) < 0.015)
    assert big.any() and small.any()
    assert np.median(np.abs(extra[big] / d[big])) > 4.0 * np.median(np.abs(extra[small] / d[small]))
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_stroke_gas_spring_is_a_stiffness_on_the_carriage_during_the_pulse_only():
    p = _params("mass_stroke_gas_spring")
    kp, z0 = p["stiffness_N_per_m"], p["reference_m"]
    rec = rec_of("mass_stroke_gas_spring", **p)
    fx, z, pulse = mass_term_N(rec), rec.internal["spring_extension"], _pulse(rec)
    assert np.max(np.abs(fx - DEV15["mass_stroke_gas_spring"].force(z, pulse, p))) < 1e-6 * np.max(np.abs(fx))
    on = pulse > 0.5
    assert on.any() and (~on).any()
    assert np.all(np.abs(fx[~on]) < 1e-6)
    assert np.polyfit(z[on], fx[on], 1) == pytest.approx([kp, -kp * z0], rel=1e-5)
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_ground_loop_shifts_a2s_zero_while_the_drive_faces_touch_and_only_then():
    p = _params("a2_drive_face_ground_loop")
    rec = rec_of("a2_drive_face_ground_loop", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])
    extra, mode = rec.signals["a2"] - clean().signals["a2"], rec.internal["mode"]
    drive = mode == 1
    assert drive.any() and (mode == -1).any() and (mode == 0).any()   # drive faces, far faces, the gap
    assert np.allclose(extra[drive], p["offset_m_s2"], rtol=0.0, atol=1e-12)
    assert np.all(np.abs(extra[~drive]) < 1e-12)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_ratchet_tensioner_brakes_the_wheel_by_the_extensions_peak_since_the_stroke_began():
    p = _params("wheel_ratchet_cable_tensioner")
    c, z0 = p["coefficient_Nm_per_m"], p["reference_m"]
    rec = rec_of("wheel_ratchet_cable_tensioner", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-9                          # held between its 0.2 ms scans
    brake = -tx[::SEG]
    assert np.all(brake >= -1e-9) and np.any(brake > 0.5)
    z = rec.internal["spring_extension"][::SEG]                          # the extension at each scan's start
    starts = np.flatnonzero(np.diff(_pulse(rec)[::SEG]) > 0.5) + 1      # each load pulse's first scan
    assert starts.size >= 2
    counts = np.cumsum(np.isin(np.arange(z.size), starts))
    i0 = starts[0]                                                       # the pawl knocked out: m = z there
    pred = DEV15["wheel_ratchet_cable_tensioner"].held(z[i0:], counts[i0:])
    assert np.max(np.abs(c * np.maximum(0.0, pred - z0) - brake[i0:])) < 1e-6 * np.max(brake)
    # a ratchet: within a stroke the brake never lets go; it drops at a stroke's first scan only
    falls = np.flatnonzero(brake[i0 + 1:] < brake[i0:-1] - 1e-9) + i0 + 1
    assert falls.size and set(falls.tolist()) <= set(starts.tolist())
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_knock_triggered_rail_brake_fires_for_its_hold_time_at_the_jaws_impacts():
    p = _params("mass_knock_triggered_rail_brake")
    rec = rec_of("mass_knock_triggered_rail_brake", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-9
    on = -fx[::SEG] / p["force_N"]
    assert np.all((np.abs(on) < 1e-6) | (np.abs(on - 1.0) < 1e-6))     # all or nothing
    on = np.round(on)
    d, mode = rec.internal["jaw_angle_difference"][::SEG], rec.internal["mode"][::SEG]
    beta = rec.internal["parameters"][K.P_BETA]
    depth = np.where(mode != 0, np.abs(d) - beta, 0.0)                   # the penetration depth at each scan's start
    i0 = int(np.argmax(on[:-1] == 0.0)) + 1                              # a scan after one with the brake off
    pred = DEV15["mass_knock_triggered_rail_brake"].on(depth[i0:], p, DT, state0=(0.0, 0, depth[i0 - 1]))
    assert np.array_equal(pred, on[i0:])
    # each firing lasts its hold time and begins at a scan where the jaw struck through p_t
    rises = np.flatnonzero(np.diff(on) > 0.5) + 1
    assert rises.size >= 3
    n_h = round(p["hold_s"] / DT)
    pt = p["trigger_penetration_rad"]
    for r in rises:
        assert depth[r - 1] <= pt < depth[r]
        if r + n_h < on.size:
            assert np.all(on[r:r + n_h] == 1.0)
            retriggered = depth[r + n_h - 1] <= pt < depth[r + n_h]
            assert on[r + n_h] == (1.0 if retriggered else 0.0)
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED15))
def test_sealed15_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED15[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set15_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(15, DEV15, SEALED15, 15000, 15100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (five with its single scaling)."""
    assert_rows_visible(("outside_dev15", "outside_sealed15"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev15", "outside_sealed15"))


@pytest.mark.parametrize("suite_name", ["outside_dev15", "outside_sealed15"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED15, DEV15)


def test_outside_bench_knows_set_15_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-15 are spent (set 15's sealed half ran once, 1 Dec, stop 52): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(15, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(15)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(15, DURATION_S)
