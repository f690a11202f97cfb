"""The eighteenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev18,
.outside_sealed18): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the rail-section dynamo on the motor, the stroke-peak carriage-speed brake on the wheel, the induction slip
coupling across the jaw, the stroke-re-armed overspeed catch on the carriage, a2's reference shared with a1, the
torsion bar on a creeping anchor across the jaw, the rail sections' slopes on the carriage), every sealed mechanism
acting in its recorded balance only, the suites (made, written, deterministic, each mechanism row visible above the
criterion its strength was set by), ``forms`` withholding the sealed laws, and the outside bench's set 18 (its sealed
half spent: run once at stop 55, in the loop's default suites and the alarm check).

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

SET = OutsideSet(18, seed=218)
DEV18, SEALED18, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _pulse(rec):
    """The load pulse's indicator at each sample (the kernel's held one)."""
    return pulse_indicator(sample_times_s(rec), rec.spec.pulse_first_s)


def _stroke_scans(rec):
    """(each load pulse's first scan, the pulse count at each scan) on the 0.2 ms scan grid."""
    pulse = _pulse(rec)[::SEG]
    starts = np.flatnonzero(np.diff(pulse) > 0.5) + 1
    return starts, np.cumsum(np.isin(np.arange(pulse.size), starts))


def _carriage_position(rec):
    """The carriage's position unwrapped from the run-in's start [m], the kernel's XS_MASS_POSITION: r*alpha2 - z on the
    wheel's angle with the whole turns the integrator took off (kernel alpha2_turns, at the run's end) put back."""
    theta = np.unwrap(rec.internal["alpha2"])
    end = rec.internal["alpha2"][-1] + 2.0 * np.pi * rec.internal["parameters"][K.P_A2TURNS]
    return C.WHEEL_RADIUS_M * (end - (theta[-1] - theta)) - rec.internal["spring_extension"]


def test_eighteenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(18)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_rail_section_dynamo": {"coefficient_Nm_s_per_rad": 0.0},
           "wheel_stroke_peak_carriage_speed_brake": {"coefficient_Nm_s_per_m": 0.0},
           "clutch_induction_slip_coupling": {"pullout_torque_Nm": 0.0},
           "mass_stroke_rearmed_overspeed_catch": {"force_N": 0.0},
           "a2_reference_shared_with_a1": {"gain_per_m_s2": 0.0},
           "clutch_creeping_anchor_torsion_bar": {"stiffness_Nm_per_rad": 0.0},
           "mass_rail_section_slopes": {"force_N": 0.0},
           "motor_averaged_tension_brake": {"coefficient_Nm_per_m": 0.0},
           "wheel_pole_slipping_synchronous_motor": {"torque_Nm": 0.0},
           "clutch_slip_timed_damper_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_jaw_impact_ringing": {"force_N": 0.0},
           "a1_pyroelectric_motor_heat": {"coefficient_m_s": 0.0},
           "motor_far_contact_dynamic_brake": {"torque_Nm": 0.0},
           "wheel_check_valve_tension_brake": {"coefficient_Nm_per_m": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV18) | set(SEALED18)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV18) | set(SEALED18)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_rail_section_dynamo_loads_the_motor_with_its_speed_while_the_carriage_is_on_a_live_section():
    p = _params("motor_rail_section_dynamo")
    rec = rec_of("motor_rail_section_dynamo", **p)
    tx, w1, x = motor_term_Nm(rec), rec.signals["omega1"], _carriage_position(rec)
    q = np.mod(x - p["offset_m"], p["pitch_m"])
    clear = (np.abs(q - p["live_m"]) > 1e-6) & (q > 1e-6) & (q < p["pitch_m"] - 1e-6)   # away from a section's edge
    law = DEV18["motor_rail_section_dynamo"].torque(w1, x, p)
    assert clear.mean() > 0.99
    assert np.max(np.abs(tx - law)[clear]) < 1e-6 * np.max(np.abs(tx))
    live = clear & (q < p["live_m"])
    assert live.any() and (clear & ~live).any()                          # on and off in one recording
    assert np.allclose(tx[live] / w1[live], p["coefficient_Nm_s_per_rad"], rtol=1e-6)   # a generator: ~ its speed
    assert np.all(np.abs(tx[clear & ~live]) < 1e-6)
    # switched by the carriage's travel, not the time: the live share of the recording is the live share of a pitch
    assert live.sum() / clear.sum() == pytest.approx(p["live_m"] / p["pitch_m"], abs=0.05)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_stroke_peak_brake_holds_the_carriages_highest_speed_since_each_stroke_began_on_the_wheel():
    p = _params("wheel_stroke_peak_carriage_speed_brake")
    c, vr = p["coefficient_Nm_s_per_m"], p["reference_speed_m_s"]
    rec = rec_of("wheel_stroke_peak_carriage_speed_brake", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * max(1.0, np.max(np.abs(tx)))   # held between its 0.2 ms scans
    assert np.all(tx <= 1e-6)                                            # a brake
    starts, counts = _stroke_scans(rec)
    assert starts.size >= 2
    i0 = starts[0]
    v = rec.internal["mass_speed"][::SEG]                                # the carriage's speed at each scan's start
    peaks = DEV18["wheel_stroke_peak_carriage_speed_brake"].peaks(v[i0:], counts[i0:])
    pred = -c * np.maximum(0.0, peaks - vr)
    assert np.max(np.abs(pred - tx[::SEG][i0:])) < 1e-6 * max(1.0, np.max(np.abs(tx)))
    assert np.min(tx) < -0.1                                             # it brakes ...
    held = tx[::SEG][i0:]
    rises = np.flatnonzero(np.diff(held) > 1e-9) + 1 + i0                # ... and releases at a stroke's start only
    assert set(rises.tolist()) <= set(starts.tolist())
    # a peak, not the speed itself: the brake holds while the carriage slows down within a stroke
    assert np.max(np.abs(held + c * np.maximum(0.0, v[i0:] - vr))) > 0.1
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_induction_coupling_passes_a_torque_that_peaks_at_its_pullout_slip_in_the_gap_and_in_contact():
    p = _params("clutch_induction_slip_coupling")
    tk, sk = p["pullout_torque_Nm"], p["pullout_slip_rad_s"]
    rec = rec_of("clutch_induction_slip_coupling", **p)
    extra, s = extra_clutch_Nm(rec), slip_rad_s(rec)
    law = DEV18["clutch_induction_slip_coupling"].torque(s, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(extra))
    gap = rec.internal["mode"] == 0
    assert gap.any() and (~gap).any()
    assert np.max(np.abs(extra[gap])) > 0.1                              # in the gap too
    moving = np.abs(s) > 1e-3
    assert np.all(np.sign(extra[moving]) == np.sign(s[moving]))          # it drags the faster half back
    assert np.max(np.abs(extra)) <= tk * (1.0 + 1e-6)                    # never beyond its pull-out torque
    # linear at small slips (2*T_k/s_k per rad/s), not a dry friction
    small = moving & (np.abs(s) < 0.1 * sk)
    assert small.any() and np.allclose(extra[small] / s[small], 2.0 * tk / sk, rtol=0.02)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_overspeed_catch_drags_the_carriage_from_its_overspeed_to_the_next_strokes_start():
    # the trip speed within this file's drive's range of the carriage's speed (its suite's 22.76 m/s is above it here)
    v_clean = clean().internal["mass_speed"]
    p = {**_params("mass_stroke_rearmed_overspeed_catch"), "trip_speed_m_s": float(np.quantile(v_clean, 0.7))}
    f, vt = p["force_N"], p["trip_speed_m_s"]
    rec = rec_of("mass_stroke_rearmed_overspeed_catch", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-6 * f                     # held between its 0.2 ms scans
    m = -fx[::SEG] / f
    assert np.allclose(m, np.round(m), atol=1e-6) and set(np.round(m).astype(int).tolist()) == {0, 1}
    starts, counts = _stroke_scans(rec)
    assert starts.size >= 2
    i0 = starts[0]
    v = rec.internal["mass_speed"][::SEG]
    pred = DEV18["mass_stroke_rearmed_overspeed_catch"].latches(v[i0:], counts[i0:], vt)
    assert np.array_equal(pred, np.round(m[i0:]))
    releases = np.flatnonzero(np.diff(np.round(m)) < -0.5) + 1
    assert releases.size >= 1 and set(releases.tolist()) <= set(starts.tolist())   # released at a stroke's start only
    # a latch: it stays on while the carriage is back below v_t
    on = np.round(m) == 1
    assert np.any(on & (v <= vt))
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_shared_reference_scales_a2_by_a1s_signal():
    p = _params("a2_reference_shared_with_a1")
    rec = rec_of("a2_reference_shared_with_a1", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(rec.internal["a2_physical"], clean().internal["a2_physical"])
    a2, a1 = rec.internal["a2_physical"], rec.internal["a1_physical"]
    read = DEV18["a2_reference_shared_with_a1"].read(a2, a1, p)
    assert np.max(np.abs(rec.signals["a2"] - read)) < 1e-9 * np.max(np.abs(a2))
    # a gain, not an added crosstalk: where a2 is 0 it reads 0; the ratio is 1 + g*a1
    ok = np.abs(a2) > 0.1 * np.max(np.abs(a2))
    assert np.allclose(rec.signals["a2"][ok] / a2[ok], 1.0 + p["gain_per_m_s2"] * a1[ok], rtol=1e-9)
    assert np.ptp(p["gain_per_m_s2"] * a1) > 0.05                       # the gain moves by several per cent
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_torsion_bar_centres_the_jaw_on_an_anchor_creeping_at_most_its_rate():
    p = _params("clutch_creeping_anchor_torsion_bar")
    k, r = p["stiffness_Nm_per_rad"], p["creep_rad_s"]
    rec = rec_of("clutch_creeping_anchor_torsion_bar", **p)
    extra, d = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"]
    anchor = d + extra / k                                               # m = D + T/k
    assert np.max(held_per_segment(anchor)) < 1e-9                     # m held between scans
    anchor, dd = anchor[::SEG], d[::SEG]                                 # m after each scan, D at each scan's start
    pred = DEV18["clutch_creeping_anchor_torsion_bar"].anchors(dd[1:], r, DT, m0=anchor[0])
    assert np.max(np.abs(pred - anchor[1:])) < 1e-9
    steps = np.abs(np.diff(anchor))
    assert np.max(steps) <= r * DT * (1.0 + 1e-6)                       # it creeps at most R ...
    assert np.mean(steps > r * DT * (1.0 - 1e-6)) > 0.01                 # ... and creeps at that rate for a while
    assert np.max(np.abs(extra[rec.internal["mode"] == 0])) > 0.1        # a spring across the gap too
    # not a spring about a fixed centre (the first sealed half's anti-backlash spring): the anchor follows the jaw's
    # angle, so a fixed-centre spring leaves a large residual
    fixed = -k * (d - np.mean(d))
    assert np.max(np.abs(extra - fixed)) > 0.2 * np.max(np.abs(extra))
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_rail_section_slopes_push_the_carriage_by_a_fixed_random_level_per_section():
    p = _params("mass_rail_section_slopes")
    rec = rec_of("mass_rail_section_slopes", **p)
    fx, x = mass_term_N(rec), _carriage_position(rec)
    q = (x - p["offset_m"]) / p["section_m"]
    clear = np.abs(q - np.round(q)) > 1e-6                               # away from a section's edge
    law = DEV18["mass_rail_section_slopes"].force(x, p)
    assert np.max(np.abs(fx - law)[clear]) < 1e-6 * p["force_N"]
    assert np.all(np.abs(fx) <= p["force_N"] * (1.0 + 1e-9))
    # constant over each section, a level of its own per section, several sections in the recording
    section = np.floor(q).astype(np.int64)
    levels = {}
    for s_, f_ in zip(section[clear].tolist(), fx[clear].tolist()):
        levels.setdefault(s_, []).append(f_)
    assert len(levels) >= 10
    assert max(np.ptp(v) for v in levels.values()) < 1e-6 * p["force_N"]
    means = np.array([np.mean(v) for v in levels.values()])
    assert np.ptp(means) > p["force_N"]                                  # random from section to section
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED18))
def test_sealed18_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED18[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set18_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(18, DEV18, SEALED18, 18000, 18100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (four with its single scaling)."""
    assert_rows_visible(("outside_dev18", "outside_sealed18"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev18", "outside_sealed18"))


@pytest.mark.parametrize("suite_name", ["outside_dev18", "outside_sealed18"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED18, DEV18)


def test_outside_bench_knows_set_18_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-18 are spent (set 18's sealed half ran once, 1 Dec, stop 55): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(18, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(18)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(18, DURATION_S)
