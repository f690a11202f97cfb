"""The sixth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev6, .outside_sealed6):
the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the kernel's new shapes, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the sign, the gate, the memory, the units), every sealed mechanism acting in its recorded balance only, the
suites (made, written, deterministic, each mechanism row visible above the criterion its strength was set by),
``forms`` withholding the sealed laws, and the outside bench's set 6 (its sealed half run once: spent).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_drives import outside as O
from foreign_drives import suites
from foreign_drives.drive import make_recording
from foreign_drives.spec import RecordingSpec
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (Recordings, assert_acts_in_its_balance_only,  # test/
                                        assert_forms_withholds_sealed, assert_recordings_repeat,
                                        assert_rows_visible, assert_set_registry, assert_set_suites,
                                        assert_suite_writes_one_recording, outside_bench, suite_effect)
from foreign_outside_recordings import held_per_segment  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)

OUTSIDE = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
DEV6 = {n: f for n, f in OUTSIDE.items() if f.half == "dev6"}
SEALED6 = {n: f for n, f in OUTSIDE.items() if f.half == "sealed6"}
DURATION_S = 0.6


def _spec(effects, seed=181, width=0.0065, duration=DURATION_S):
    return RecordingSpec("t6", "outside" if effects else "clean", width, 0.025, 0.9, effects=tuple(effects), seed=seed,
                         duration_s=duration, noise=False)


RECORDINGS = Recordings(lambda effects, duration_s: _spec(effects, duration=duration_s), DURATION_S)
rec_of, clean = RECORDINGS.rec_of, RECORDINGS.clean


def _suite_effect(name):
    """The set-6 suite's use of a mechanism (its parameters at the suite's strength)."""
    return suite_effect(name, ("outside_dev6", "outside_sealed6"))


def _t(rec):
    return np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S


def _nominal_contact_Nm(rec):
    """The contact law's own torque (SPEC: k_c*p + d_c*p', far side negative) from the exact angle difference and
    the speeds (no shaft hub: the rate of D is Omega1 - Omega2)."""
    i = rec.internal
    d, dd, mode = i["jaw_angle_difference"], rec.signals["omega1"] - rec.signals["omega2"], i["mode"]
    beta = rec.truth.true_width_m / C.WHEEL_RADIUS_M
    k, c = C.CONTACT_STIFFNESS_NM_PER_RAD, C.CONTACT_DAMPING_NMS_PER_RAD
    return np.where(mode > 0, k * (d - beta) + c * dd, np.where(mode < 0, -(k * (-d - beta) - c * dd), 0.0))


# ------------------------------------------------------------------ registry and truth vocabulary
def test_sixth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(6)


# each mechanism's neutral setting at its suite's parameters: a strength 0, a range or a limit nothing reaches, no latency
NEUTRAL = {"motor_slip_hub_flywheel": {"slip_torque_Nm": 0.0}, "wheel_idler_gear_rattle": {"inertia_kgm2": 0.0},
           "clutch_torque_limiter": {"limit_Nm": 500.0}, "mass_tray_parts": {"force_per_part_N": 0.0},
           "a2_bilinear_gain": {"asymmetry": 0.0}, "a2_overload_recovery": {"range_m_s2": 1000.0},
           "wheel_pwm_brake": {"torque_Nm": 0.0}, "motor_batch_blank_thickness": {"torque_Nm": 0.0},
           "wheel_pi_speed_brake": {"max_torque_Nm": 0.0}, "clutch_dahl_friction_ring": {"friction_torque_Nm": 0.0},
           "mass_rate_limited_balancer": {"gain_N_per_m": 0.0}, "a1_telemetry_jitter": {"max_latency_s": 0.0},
           "motor_accumulator_unloader": {"displacement_Nm_per_bar": 0.0}, "mass_slack_tow_chain": {"cart_mass_kg": 0.0}}


@pytest.mark.parametrize("name", sorted(DEV6) + sorted(SEALED6))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV6) | set(SEALED6)
    p = {**_suite_effect(name).parameters, **NEUTRAL[name]}
    rec = rec_of(name, **p)
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


def test_the_kernels_new_shapes_a_random_count_a_dead_zone_and_a_residue():
    u = [K._shaped(K.XF_HASH, float(k) + 0.5, 17.0, 0.0, 0.0) for k in range(-20, 200)]
    assert all(-1.0 <= x < 1.0 for x in u) and len(set(u)) == len(u)           # one value per whole number
    assert abs(np.mean(u)) < 0.15 and 0.45 < np.std(u) < 0.7                   # spread over [-1, 1) (uniform: 0.577)
    assert np.corrcoef(u[:-1], u[1:])[0, 1] ** 2 < 0.05                        # the next stroke's unlike the last's
    assert K._shaped(K.XF_HASH, 3.99, 17.0, 0.0, 0.0) == K._shaped(K.XF_HASH, 3.0, 17.0, 0.0, 0.0)
    for x, want in ((50.0, 10.0), (-50.0, -10.0), (39.9, 0.0), (-39.9, 0.0), (0.0, 0.0)):
        assert K._shaped(K.XF_DEADZONE, x, 40.0, 0.0, 0.0) == pytest.approx(want)
    for k, want in ((-1.0, 2.0), (0.0, 3.0), (1.0, 0.0), (4.0, 3.0), (5.0, 0.0), (6.0, 1.0)):
        assert K._shaped(K.XF_MOD, k, 4.0, 1.0, 0.0) == want


# ------------------------------------------------------------------ the development laws on the drive's balances
def test_slip_hub_flywheel_sticks_below_its_slip_torque_and_passes_it_while_slipping():
    p = _suite_effect("motor_slip_hub_flywheel").parameters
    rec = rec_of("motor_slip_hub_flywheel", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6                         # the hub's torque held over each 0.2 ms
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6
    ts, jf, dt = p["slip_torque_Nm"], p["inertia_kgm2"], N.SEGMENT_S
    t_seg = tx[::SEG]
    assert np.max(np.abs(t_seg)) <= ts + 1e-9
    slipping = np.abs(np.abs(t_seg) - ts) < 1e-9
    assert 0.05 < slipping.mean() < 0.95                                # both regimes: the jaw's impacts make it slip
    # stuck, the disc follows the shaft: its torque is J_f times the shaft's acceleration over the last scan
    w1 = rec.signals["omega1"][::SEG]
    stuck_after_stuck = ~slipping[1:] & ~slipping[:-1]
    assert np.allclose(t_seg[1:][stuck_after_stuck], jf * np.diff(w1)[stuck_after_stuck] / dt, atol=1e-6)
    # the law from Omega1 at the segments' starts (the disc's speed from the first segment on): once it has stuck, the
    # recorded run and the law agree scan by scan
    law = DEV6["motor_slip_hub_flywheel"].hub_torque(w1, p, dt)
    first_stuck = int(np.argmax(~slipping[1:] & (np.abs(law[1:]) < ts))) + 1
    assert first_stuck < w1.size // 2
    assert np.max(np.abs(law[first_stuck:] - t_seg[first_stuck:])) < 1e-6


def test_idler_gear_rattles_in_its_backlash_and_takes_its_drag_through_the_driving_flank():
    p = _suite_effect("wheel_idler_gear_rattle").parameters
    rec = rec_of("wheel_idler_gear_rattle", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6
    assert np.max(np.abs(motor_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6
    t_seg = tx[::SEG]
    ji, lam = p["inertia_kgm2"], p["drag_per_s"]
    # on the driving flank the wheel drives the idler (a braking torque); in flight nothing; on the far flank the idler
    # drives the wheel: all three occur
    assert np.mean(t_seg < -1e-9) > 0.3 and np.mean(np.abs(t_seg) <= 1e-12) > 0.01 and np.any(t_seg > 0.5)
    # over the recording the flanks pass the idler's bearing drag and its change of speed: mean(-T) = J_i*(lambda*mean
    # speed + the wheel's mean acceleration), the idler's own relative motion averaging out to within its gap
    w2 = rec.signals["omega2"][::SEG]
    mean_acc = (w2[-1] - w2[0]) / (N.SEGMENT_S * (w2.size - 1))
    want = ji * (lam * w2.mean() + mean_acc)
    assert np.mean(-t_seg) == pytest.approx(want, rel=0.15, abs=0.02)
    # a contact never pulls, so the wheel is braked only while the idler lags it: mostly, on the driving flank
    assert np.median(t_seg[t_seg < 0]) > -ji * 2000.0


def test_torque_limiter_caps_the_contact_torque_and_keeps_its_sign():
    lim = 20.0
    rec = rec_of("clutch_torque_limiter", limit_Nm=lim)
    i = rec.internal
    nominal = _nominal_contact_Nm(rec)
    total = i["clutch_torque_Nm"]
    want = np.sign(nominal) * np.minimum(np.abs(nominal), lim)
    assert np.max(np.abs(total - want)) < 1e-6 * lim
    assert np.mean(np.abs(nominal) > lim) > 0.001 and np.max(np.abs(nominal)) > 2 * lim   # the impacts are cut
    assert np.all(total[i["mode"] == 0] == 0.0)
    assert np.all(total[i["mode"] > 0] > -1e-9) and np.all(total[i["mode"] < 0] < 1e-9)
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6


def test_tray_parts_load_the_rail_one_part_per_stroke_and_reset_every_n_strokes():
    p = {"force_per_part_N": 1.5, "every_n": 3, "first_empty": 1}
    rec = rec_of("mass_tray_parts", duration=1.2, **p)
    fx = mass_term_N(rec)
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6
    seg = np.floor(_t(rec) / N.SEGMENT_S + 1e-9)
    first = round(rec.spec.pulse_first_s / N.SEGMENT_S)
    k = np.floor((seg - first) / round(C.PULSE_PERIOD_S / N.SEGMENT_S))    # the stroke's number (-1 before the first)
    parts = np.mod(k - 1, 3)
    law = -1.5 * parts * np.tanh(rec.internal["mass_speed"] / 0.01)
    assert np.max(np.abs(fx - law)) < 1e-6
    assert set(np.unique(parts)) == {0.0, 1.0, 2.0}                     # a staircase, emptied every third stroke
    assert np.all(rec.internal["mass_speed"] > 1.0)                     # against the motion: v > 0 throughout


def test_bilinear_gain_reads_each_direction_with_its_own_gain():
    rec = rec_of("a2_bilinear_gain", asymmetry=0.1)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    pos, neg = a > 0.05, a < -0.05
    assert np.allclose(y[pos], 1.1 * a[pos], rtol=1e-12) and np.allclose(y[neg], 0.9 * a[neg], rtol=1e-12)
    assert pos.mean() > 0.2 and neg.mean() > 0.2
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(a, clean().internal["a2_physical"])           # a sensor: the drive is untouched


def test_overload_recovery_mutes_a2_over_its_range_and_for_the_recovery_after():
    a_clean = clean().internal["a2_physical"]
    rng_ = 0.85 * float(np.max(np.abs(a_clean)))                        # the largest swings overload it
    rec = rec_of("a2_overload_recovery", range_m_s2=rng_, recovery_s=0.002)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    over = np.flatnonzero(np.abs(a) > rng_)
    assert over.size > 10
    muted = np.zeros(a.size, dtype=bool)
    for i in over:                                                      # 2 ms = 100 samples after each overload
        muted[i:i + 101] = True
    assert np.all(y[muted] == 0.0) and np.array_equal(y[~muted], a[~muted])
    assert 0.001 < muted.mean() < 0.5
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])


def test_pwm_brake_is_all_or_nothing_with_the_duty_of_the_speed_sampled_at_each_carrier_period():
    p = {"torque_Nm": 6.5, "carrier_period_s": 0.005, "zero_duty_speed_rad_s": 149.0, "full_duty_span_rad_s": 6.0}
    rec = rec_of("wheel_pwm_brake", **p)
    t_seg = wheel_term_Nm(rec)[::SEG]
    assert np.max(held_per_segment(wheel_term_Nm(rec))) < 1e-6
    assert np.all((np.abs(t_seg) < 1e-6) | (np.abs(t_seg + 6.5) < 1e-6))
    on = t_seg < -3.0
    assert 0.05 < on.mean() < 0.95
    w2 = rec.signals["omega2"][::SEG]
    per = 25                                                            # 5 ms of 0.2 ms scans
    # the carrier's phase: the one offset at which every period is on for round(d*25) scans first, then off
    good = []
    for off in range(per):
        ok = True
        for j in range(off, w2.size - per, per):
            d = min(max((w2[j] - 149.0) / 6.0, 0.0), 1.0)
            n_on = round(d * per)
            ok &= bool(np.all(on[j:j + n_on]) and not np.any(on[j + n_on:j + per]))
        good.append(ok)
    assert sum(good) == 1
    assert np.max(np.abs(motor_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED6))
def test_sealed6_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_suite_effect(name).parameters)
    assert_acts_in_its_balance_only(name, SEALED6[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set6_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(6, DEV6, SEALED6, 8400, 8500)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s)."""
    assert_rows_visible(("outside_dev6", "outside_sealed6"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev6", "outside_sealed6"), rows=(0, 1, 5))


@pytest.mark.parametrize("suite_name", ["outside_dev6", "outside_sealed6"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED6, DEV6)


def test_outside_bench_knows_set_6_whose_sealed_half_is_spent_now():
    """Set 6's sealed half was run once (412d392): development data now, in the loop's default suites (the unspent sealed
    half's guard is tested with set 7, test_foreign_drives_outside7)."""
    bench = outside_bench("outside_bench_under_test6")
    assert [s.label for s in bench.suite_rows(False, 6)] == [s.label for s in suites.suite("outside_dev6")]
    assert bench.suite_name(True, 6) == "outside_sealed6" and "outside_sealed6" not in bench.UNSPENT_SEALED
    assert {"outside_dev6", "outside_sealed6", "outside_sealed5"} <= set(bench.LOOP_DEVELOPMENT_SUITES)
    for s in suites.suite("outside_dev6") + suites.suite("outside_sealed6"):
        bal, st = bench._truth_of(s, s.truth())
        assert bool(bal) == (s.kind == "outside") and (not bal or st)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    from importlib.util import module_from_spec, spec_from_file_location
    from foreign_outside_recordings import OUTSIDE_BENCH
    spec = spec_from_file_location("width_caveat_under_test6", OUTSIDE_BENCH.parent / "width_caveat.py")
    module = module_from_spec(spec)
    spec.loader.exec_module(module)
    # the sealed half joined once it was spent (run once, 30 Nov), as every earlier set's did
    assert "outside_dev6" in module.alarm_suites() and "outside_sealed6" in module.alarm_suites()


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    for name in ("outside_dev6", "outside_sealed6"):
        spec = dataclasses.replace(next(s for s in suites.suite(name) if s.kind == "outside"), duration_s=DURATION_S)
        rec = make_recording(spec)
        assert all(np.all(np.isfinite(rec.signals[k])) for k in rec.signals)
        assert sum(k == "onset" for _, k in rec.true_entries()) >= 2
