"""The nineteenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev19,
.outside_sealed19): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the accumulator-charging pump on the motor, the cable's guide rollers on the wheel, the tension-fed torsion
bellows across the jaw, the drum grooving's crossover on the carriage, a2's tilt on the wavy track, the slip-averaging
anti-clatter motor on the wheel, the impact-severity brake on the motor), every sealed mechanism acting in its recorded
balance only, the suites (made, written, deterministic, each mechanism row visible above the criterion its strength was
set by), ``forms`` withholding the sealed laws, and the outside bench's set 19 (its sealed half spent: run once at stop
57, in the loop's default suites and the alarm check).

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
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero, sample_times_s, slip_rad_s  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(19, seed=219)
DEV19, SEALED19, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _since_stroke_s(rec):
    """The time since the latest load pulse began, on or off [s] (the kernel's XS_PULSE_PHASE), from the pulse's
    rising edges (the one before the recording's first a period before its first)."""
    t = sample_times_s(rec)
    pulse = pulse_indicator(t, rec.spec.pulse_first_s)
    starts = t[np.flatnonzero(np.diff(pulse) > 0.5) + 1]
    assert starts.size >= 2
    starts = np.concatenate([[starts[0] - C.PULSE_PERIOD_S], starts])
    return t - starts[np.searchsorted(starts, t + 1e-12, side="right") - 1]


def _carriage_position(rec):
    """The carriage's position unwrapped from the run-in's start [m], the kernel's XS_MASS_POSITION: r*alpha2 - z on the
    wheel's angle with the whole turns the integrator took off (kernel alpha2_turns, at the run's end) put back."""
    theta = np.unwrap(rec.internal["alpha2"])
    end = rec.internal["alpha2"][-1] + 2.0 * np.pi * rec.internal["parameters"][K.P_A2TURNS]
    return C.WHEEL_RADIUS_M * (end - (theta[-1] - theta)) - rec.internal["spring_extension"]


def test_nineteenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(19)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_accumulator_charging_pump": {"torque_Nm": 0.0},
           "wheel_cable_guide_rollers": {"torque_Nm": 0.0},
           "clutch_tension_fed_torsion_bellows": {"stiffness_Nm_per_rad_m": 0.0},
           "mass_drum_grooving_crossover": {"force_N": 0.0},
           "a2_wavy_track_tilt": {"amplitude_m_s2": 0.0},
           "wheel_slip_averaging_anti_clatter": {"coefficient_Nm_s_per_rad": 0.0},
           "motor_impact_severity_brake": {"coefficient_Nm_per_W": 0.0},
           "motor_slip_latched_guard_brake": {"torque_Nm": 0.0},
           "wheel_debounced_tension_brake": {"torque_Nm": 0.0},
           "clutch_thermal_cutout_drag_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_guide_shoe_squeal": {"force_N": 0.0},
           "a1_own_clock_skew": {"skew": 0.0},
           "mass_eccentric_coil_back_tension": {"force_N": 0.0},
           "clutch_centrifugal_shoe_clutch": {"capacity_Nm_s_per_rad": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV19) | set(SEALED19)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV19) | set(SEALED19)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_accumulator_pump_loads_the_motor_with_a_ramp_from_each_strokes_start_held_at_full_charge():
    p = _params("motor_accumulator_charging_pump")
    tq, tc = p["torque_Nm"], p["charge_time_s"]
    rec = rec_of("motor_accumulator_charging_pump", **p)
    tx, since = motor_term_Nm(rec), _since_stroke_s(rec)
    law = DEV19["motor_accumulator_charging_pump"].torque(since, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * tq
    assert np.all(tx >= -1e-6) and np.max(tx) <= tq * (1.0 + 1e-6)        # a load, never beyond full charge
    ramp, full = since < 0.9 * tc, since > 1.1 * tc
    assert ramp.any() and full.any()
    assert np.allclose(tx[full], tq, rtol=1e-6)                            # held at its top after T_c ...
    assert np.allclose(tx[ramp], tq * since[ramp] / tc, atol=1e-6 * tq)    # ... linear in the time before
    # the pump is timed by the stroke, the pulse on or off: it ramps on through the pulse's end
    off = pulse_indicator(sample_times_s(rec), rec.spec.pulse_first_s) == 0
    assert np.any(ramp & off) and np.any(ramp & ~off)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_guide_rollers_drag_the_wheel_by_a_half_wave_sine_of_the_carriages_travel():
    p = _params("wheel_cable_guide_rollers")
    rec = rec_of("wheel_cable_guide_rollers", **p)
    tx, x = wheel_term_Nm(rec), _carriage_position(rec)
    law = DEV19["wheel_cable_guide_rollers"].torque(x, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * p["torque_Nm"]
    assert np.all(tx <= 1e-6) and np.min(tx) < -0.9 * p["torque_Nm"]         # a drag, reaching its full torque
    q = np.mod(x - p["offset_m"], p["pitch_m"]) / p["pitch_m"]
    free = (q > 0.51) & (q < 0.99)                                           # the half of each pitch between rollers
    assert free.any() and np.all(np.abs(tx[free]) < 1e-6)
    # locked to the carriage's travel: several pitches pass in the recording
    assert np.ptp(x) > 2.0 * p["pitch_m"]
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_torsion_bellows_centres_the_jaw_with_a_stiffness_the_cables_extension_sets():
    p = _params("clutch_tension_fed_torsion_bellows")
    k, z0 = p["stiffness_Nm_per_rad_m"], p["reference_m"]
    rec = rec_of("clutch_tension_fed_torsion_bellows", **p)
    extra, d, z = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"], rec.internal["spring_extension"]
    law = DEV19["clutch_tension_fed_torsion_bellows"].torque(d, z, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(extra))
    gap = rec.internal["mode"] == 0
    assert gap.any() and (~gap).any()
    assert np.max(np.abs(extra[gap])) > 0.1                                  # in the gap too
    moved = np.abs(d) > 1e-3
    assert np.all(np.sign(extra[moved]) == -np.sign(d[moved]))              # a centring torque
    # a stiffness scheduled by the extension, not a constant one: -T/D follows k*(z - z_0) and moves by a good part
    ratio = -extra[moved] / d[moved]
    assert np.allclose(ratio, k * (z[moved] - z0), rtol=1e-6)
    assert np.ptp(ratio) > 0.2 * np.mean(ratio)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_grooving_crossover_jerks_the_carriage_back_once_per_turn_of_the_wheel():
    p = _params("mass_drum_grooving_crossover")
    f, w = p["force_N"], p["arc_rad"]
    rec = rec_of("mass_drum_grooving_crossover", **p)
    fx, a2 = mass_term_N(rec), rec.internal["alpha2"]
    q = np.mod(a2 - p["angle_rad"], 2.0 * np.pi)
    clear = (np.abs(q - w) > 1e-6) & (q > 1e-6) & (q < 2.0 * np.pi - 1e-6)   # away from the window's edges
    law = DEV19["mass_drum_grooving_crossover"].force(a2, p)
    assert np.max(np.abs(fx - law)[clear]) < 1e-6 * f
    on = clear & (q < w)
    assert np.allclose(fx[on], -f, rtol=1e-6) and np.all(np.abs(fx[clear & ~on]) < 1e-6)
    # once per turn: the share of the recording in the window is the arc's share of a turn, over several turns
    assert on.sum() / clear.sum() == pytest.approx(w / (2.0 * np.pi), abs=0.03)
    turns = np.ptp(np.unwrap(a2)) / (2.0 * np.pi)
    windows = np.count_nonzero(np.diff(on.astype(int)) == 1)
    assert turns > 5 and abs(windows - turns) <= 2
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_wavy_track_tilt_adds_a_cosine_of_the_carriages_travel_to_a2():
    p = _params("a2_wavy_track_tilt")
    rec = rec_of("a2_wavy_track_tilt", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])
    a2, x = rec.internal["a2_physical"], _carriage_position(rec)
    read = DEV19["a2_wavy_track_tilt"].read(a2, x, p)
    assert np.max(np.abs(rec.signals["a2"] - read)) < 1e-9 * np.max(np.abs(a2))
    # an additive error (not a gain): its own amplitude whatever a2 is, locked to the travel, not to the time
    err = rec.signals["a2"] - a2
    assert np.max(np.abs(err)) == pytest.approx(p["amplitude_m_s2"], rel=0.01)
    assert np.ptp(x) > 2.0 * p["wavelength_m"]
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_anti_clatter_motor_drives_the_wheel_with_the_slip_averaged_over_its_window():
    p = _params("wheel_slip_averaging_anti_clatter")
    c, n = p["coefficient_Nm_s_per_rad"], int(p["window_scans"])
    rec = rec_of("wheel_slip_averaging_anti_clatter", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * max(1.0, np.max(np.abs(tx)))   # held between its 0.2 ms scans
    s = slip_rad_s(rec)[::SEG]                                                 # the slip at each scan's start
    pred = c * DEV19["wheel_slip_averaging_anti_clatter"].means(s, n)
    held = tx[::SEG][n - 1:]
    assert np.max(np.abs(pred - held)) < 1e-6 * max(1.0, np.max(np.abs(tx)))
    assert np.max(np.abs(tx)) > 0.5
    # an average over a window, not the slip itself nor a first-order lag of it: it lags the slip's swings by about
    # half the window and forgets them after a whole one
    assert np.max(np.abs(held - c * s[n - 1:])) > 0.3 * np.max(np.abs(held))
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_impact_severity_brake_loads_the_motor_with_the_contacts_recent_peak_power():
    p = _params("motor_impact_severity_brake")
    c, tau = p["coefficient_Nm_per_W"], p["decay_s"]
    rec = rec_of("motor_impact_severity_brake", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * max(1.0, np.max(np.abs(tx)))   # held between its 0.2 ms scans
    assert np.all(tx >= -1e-6)                                              # a brake
    power = np.abs(rec.internal["clutch_torque_Nm"] * slip_rad_s(rec))[::SEG]    # |T_c*D'| at each scan's start
    m = tx[::SEG] / c
    pred = DEV19["motor_impact_severity_brake"].peaks(power[1:], tau, DT, m0=m[0])
    assert np.max(np.abs(pred - m[1:])) < 1e-6 * np.max(m)
    assert np.max(tx) > 0.5
    # a peak hold with a bleed: between impacts it decays by exp(-dt/tau) a scan
    falling = (m[2:] < m[1:-1]) & (m[1:-1] > 0.01 * np.max(m))
    assert falling.any() and np.allclose(m[2:][falling] / m[1:-1][falling], np.exp(-DT / tau), rtol=1e-6)
    others_zero(rec, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED19))
def test_sealed19_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED19[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set19_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(19, DEV19, SEALED19, 19000, 19100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (three with its single scaling)."""
    assert_rows_visible(("outside_dev19", "outside_sealed19"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev19", "outside_sealed19"))


@pytest.mark.parametrize("suite_name", ["outside_dev19", "outside_sealed19"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED19, DEV19)


def test_outside_bench_knows_set_19_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-19 are spent (set 19's sealed half ran once, 2 Dec, stop 57): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(19, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(19)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(19, DURATION_S)
