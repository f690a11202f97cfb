"""The eighth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev8, .outside_sealed8):
the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the kernel's new shape and
memory kinds from their definitions, the development laws checked on the drive's own balances and signals (each term
recovered from the recorded, noise-free states: the resonance peak, the period tachometer's brake, the detent, the
run-to-run force, the wrap, the oscillator, the codec), every sealed mechanism acting in its recorded balance only, the
suites (made, written, deterministic, each mechanism row visible above the criterion its strength was set by, but the
one row its module says is below it), ``forms`` withholding the sealed laws, and the outside bench's set 8 (its sealed
half run once, 30 Nov: spent).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import math

import numpy as np
import pytest

from foreign_drives import constants as C
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

SET = OutsideSet(8, seed=193)
DEV8, SEALED8, DURATION_S = SET.dev, SET.sealed, SET.duration_s
# the one row left below it, as its module's docstring says (its scaling would have passed its parameter's bound)
BELOW_CRITERION = {"os8_clutch_cracked_jaw_tooth"}
rec_of, clean, _suite_effect = SET.rec_of, SET.clean, SET.effect


def _stroke_at_scans(rec):
    """The load pulse's number at each scan (the first pulse at or after sample 0 is 0; -1 before it)."""
    seg = np.arange(rec.n_samples // SEG)
    first = round(rec.spec.pulse_first_s / DT)
    return np.floor((seg - first) / round(C.PULSE_PERIOD_S / DT))


# ------------------------------------------------------------------ registry and truth vocabulary
def test_eighth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(8)


# each mechanism's neutral setting at its suite's parameters: a strength 0, a range never reached
NEUTRAL = {"motor_fan_blade_flutter": {"peak_torque_Nm": 0.0}, "wheel_period_tacho_brake": {"gain_Nm_s_per_rad": 0.0},
           "clutch_ball_detent": {"detent_torque_Nm": 0.0}, "mass_run_to_run_booster": {"gain_N_s_per_m": 0.0},
           "wheel_brake_squeal": {"torque_Nm": 0.0}, "motor_shaft_generator_constant_power": {"power_W": 0.0},
           "wheel_snail_cam_knockout": {"torque_Nm": 0.0}, "clutch_cracked_jaw_tooth": {"softening": 0.0},
           "mass_coolant_tray_friction": {"friction_N_per_kg": 0.0}, "a1_auto_ranging": {"up_m_s2": 10000.0},
           "motor_step_controlled_throttle": {"torque_per_step_Nm": 0.0},
           "mass_eddy_rail_brake_characteristic": {"peak_force_N": 0.0}}
# a wrap at its largest range: a2 + R - R, equal to a2 to the rounding of R's size
NEAR_NEUTRAL = {"a2_fixed_point_wrap": {"range_m_s2": 1000.0}}
# the codec has no neutral setting (its steps are never 0): its law is checked on its own below
NO_NEUTRAL = {"a2_delta_modulator_codec"}


@pytest.mark.parametrize("name", sorted((set(DEV8) | set(SEALED8)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit (the
    wrap's: to 1e-10 m/s^2)."""
    assert set(NEUTRAL) | set(NEAR_NEUTRAL) | NO_NEUTRAL == set(DEV8) | set(SEALED8)
    setting = NEAR_NEUTRAL.get(name, NEUTRAL.get(name))
    rec = rec_of(name, **{**_suite_effect(name).parameters, **setting})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        if name in NEAR_NEUTRAL and k == "a2":
            assert np.max(np.abs(rec.signals[k] - clean().signals[k])) < 1e-10
        else:
            assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


def test_the_kernels_new_shape_a_resonance_peak():
    a, b = 1.5, 150.0
    assert K._shaped(K.XF_LORENTZ, b, a, b, 0.0) == 1.0
    assert K._shaped(K.XF_LORENTZ, b + a, a, b, 0.0) == pytest.approx(0.5)          # half at the half-width
    assert K._shaped(K.XF_LORENTZ, b - 2 * a, a, b, 0.0) == pytest.approx(0.2)      # symmetric, 1/(1 + 4)
    assert K._shaped(K.XF_LORENTZ, b + 100 * a, a, b, 0.0) < 1e-4


def _scan(kind, xs, a=0.0, b=0.0, c=0.0, counts=None, extra=()):
    """The eighth set's memory element scanned over the inputs ``xs`` (one 0.2 ms scan each at t = i*dt; the pulse
    count ``counts``, else 0): its output after each scan."""
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND], P[K.P_MEMA], P[K.P_MEMB], P[K.P_MEMC] = float(kind), a, b, c
    for i, v in enumerate(extra):
        P[K.P_MEMR0 + K.MEM_EXTRA + i] = v
    out = []
    for i, x in enumerate(xs):
        P[K.P_PCOUNT] = 0.0 if counts is None else counts[i]
        K._memory_scan8(kind, i * DT, x, P, DT)
        out.append(P[K.P_MEMSTATE])
    return np.array(out)


def test_the_kernels_new_memory_kinds_from_their_definitions():
    # a period tachometer on an angle turning at 150 rad/s: 0 until the mark's second pass, then 2*pi over the whole
    # scans between the two latest passes (150 rad/s to the scan's 0.5 %), stepping only at the passes
    w = 150.0
    m = _scan(K.MK_PERIOD_TACHO, [w * i * DT + 0.1 for i in range(3000)], a=0.5)
    passes = np.flatnonzero(np.diff(np.floor((w * np.arange(3000) * DT + 0.1 - 0.5) / (2 * math.pi))) != 0) + 1
    assert np.all(m[:passes[1]] == 0.0) and m[passes[1]] == pytest.approx(2 * math.pi / ((passes[1] - passes[0]) * DT))
    assert np.all(np.abs(m[passes[1]:] - w) < 0.005 * w)
    assert set(np.flatnonzero(np.diff(m) != 0) + 1) <= set(passes)
    # a run-to-run controller: at each pulse's first scan the force moves by -G*(mean since the last - v_ref), clipped
    m = _scan(K.MK_RUN_TO_RUN, [1.0, 3.0, 5.0, 4.0, 4.0, 0.0], a=2.0, b=2.0, c=5.0, counts=[0, 0, 0, 1, 1, 2])
    assert m.tolist() == [0.0, 0.0, 0.0, -2.0 * (3.0 - 2.0), -2.0, -5.0]          # the last: -2 - 2*(4 - 2), clipped
    # a tank: fills to (q/c)^2 under a steady inflow; empties in 2*sqrt(V0)/c without one (Torricelli), never below 0
    m = _scan(K.MK_TANK, [1.0] * 200000, a=10.0, b=2.5)
    assert m[0] == 0.0 and m[-1] == pytest.approx((10.0 / 2.5) ** 2, rel=1e-3)
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND], P[K.P_MEMA], P[K.P_MEMB], P[K.P_MEMINIT], P[K.P_MEMSTATE] = K.MK_TANK, 10.0, 2.5, 1.0, 4.0
    levels = []
    for _ in range(10000):
        K._memory_scan8(K.MK_TANK, 0.0, 0.0, P, DT)
        levels.append(P[K.P_MEMSTATE])
    empty_s = (np.argmax(np.array(levels) == 0.0) + 1) * DT
    assert empty_s == pytest.approx(2 * math.sqrt(4.0) / 2.5, rel=0.01) and min(levels) == 0.0
    # a van der Pol oscillator: above its onset it grows to the limit cycle (amplitude ~2 for a small negative
    # damping) at its own frequency; below it decays to the floor 1e-3
    f = 25.0
    m = _scan(K.MK_SQUEAL, [152.0] * 25000, a=2 * math.pi * f, b=0.1, c=151.0)
    tail = m[-5000:]                                                    # the last second
    assert 1.9 < np.max(tail) < 2.1
    crossings = np.flatnonzero(np.diff(np.sign(tail)) > 0).size        # upward crossings over 1 s
    assert crossings == pytest.approx(f, abs=1.5)
    m = _scan(K.MK_SQUEAL, [140.0] * 25000, a=2 * math.pi * f, b=0.1, c=151.0)
    assert np.max(np.abs(m[-5000:])) < 1.5e-3 and np.max(np.abs(m[-5000:])) >= 0.5e-3
    # a three-point step controller: one step per T_s (3 scans) above the band, held inside it, one down per T_s
    # below it, within 0..N (N = 2)
    xs = [10.0] * 10 + [5.0] * 4 + [0.0] * 10
    m = _scan(K.MK_STEP, xs, a=5.0, b=1.0, c=3 * DT, extra=(2.0,))
    assert m.tolist() == [0, 0, 1, 1, 1, 2, 2, 2, 2, 2] + [2] * 4 + [2, 2, 1, 1, 1, 0, 0, 0, 0, 0]


# ------------------------------------------------------------------ the development laws on the drive's balances
def test_fan_blade_flutter_is_a_load_peaked_at_its_resonance_speed():
    p = _suite_effect("motor_fan_blade_flutter").parameters
    rec = rec_of("motor_fan_blade_flutter", **p)
    tx = motor_term_Nm(rec)
    w1 = rec.signals["omega1"]
    law = DEV8["motor_fan_blade_flutter"].torque(w1, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * p["peak_torque_Nm"]
    # its largest where the speed is nearest Omega_r, below half of it farther than w: a peak in the speed
    near = np.abs(w1 - p["resonance_speed_rad_s"]) < 0.2
    far = np.abs(w1 - p["resonance_speed_rad_s"]) > p["half_width_rad_s"]
    assert near.any() and np.min(tx[near]) > 0.98 * p["peak_torque_Nm"]
    assert far.any() and np.max(tx[far]) < 0.5 * p["peak_torque_Nm"] + 1e-6
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_period_tacho_brake_brakes_on_the_speed_of_the_last_whole_wheel_turn():
    p = {"gain_Nm_s_per_rad": 2.0, "set_speed_rad_s": float(np.percentile(clean().signals["omega2"], 30)),
         "phase_rad": 0.5}
    rec = rec_of("wheel_period_tacho_brake", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6
    others_zero(rec, motor_term_Nm, mass_term_N)
    theta2 = np.unwrap(rec.internal["alpha2"])[::SEG]
    k = np.floor((theta2 - p["phase_rad"]) / (2 * math.pi))
    passes = np.flatnonzero(np.diff(k) != 0) + 1
    assert passes.size >= 10
    start = passes[0] - 1                                               # from the scan before the record's first pass
    reading = DEV8["wheel_period_tacho_brake"].measured(theta2[start:], p, DT)[passes[1] - start:]
    law = -2.0 * np.maximum(0.0, reading - p["set_speed_rad_s"])
    assert np.max(np.abs(tx[::SEG][passes[1]:passes[1] + law.size] - law)) < 1e-6
    assert np.any(law < -0.1) and np.any(law == 0.0)
    # the brake steps only at the mark's passes: once per wheel turn, not with the speed between them
    steps = np.flatnonzero(np.abs(np.diff(tx[::SEG][passes[1]:])) > 1e-9) + passes[1] + 1
    assert steps.size and set(steps) <= set(passes)


def test_ball_detent_is_periodic_in_the_jaws_angle_difference_in_the_gap_and_in_contact():
    p = _suite_effect("clutch_ball_detent").parameters
    rec = rec_of("clutch_ball_detent", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    d = i["jaw_angle_difference"]
    law = DEV8["clutch_ball_detent"].torque(d, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * p["detent_torque_Nm"]
    free = i["mode"] == 0
    assert free.mean() > 0.02 and (~free).mean() > 0.02
    # several wells across the gap: the torque changes sign more than once while D crosses the gap
    gap = np.abs(d) < i["parameters"][K.P_BETA]
    assert np.ptp(d[gap]) > 2 * p["pitch_rad"] and np.max(extra[gap]) > 0.9 * p["detent_torque_Nm"]
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_run_to_run_booster_changes_its_force_once_per_stroke_from_the_strokes_mean_speed():
    v0 = clean().internal["mass_speed"]
    p = {"gain_N_s_per_m": 10.0, "reference_speed_m_s": float(np.mean(v0)) - 0.05, "force_limit_N": 20.0}
    rec = rec_of("mass_run_to_run_booster", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-6
    others_zero(rec, motor_term_Nm, wheel_term_Nm)
    k = _stroke_at_scans(rec)
    start = int(np.argmax(k == 0))                                      # the record's first stroke start
    v = rec.internal["mass_speed"][::SEG]
    law = DEV8["mass_run_to_run_booster"].force(v[start:], k[start:], p, f0=fx[::SEG][start])
    assert np.max(np.abs(fx[::SEG][start:start + law.size] - law)) < 1e-6
    # a staircase: constant within a stroke period, a step (a braking one: the carriage faster than v_ref) at each
    # stroke's start
    changes = np.flatnonzero(np.abs(np.diff(law)) > 1e-9) + 1
    assert changes.size >= 1 and set(changes) <= set(np.flatnonzero(np.diff(k[start:]) != 0) + 1)
    assert np.all(np.diff(law)[changes - 1] < 0.0)


def test_fixed_point_wrap_folds_a2_beyond_its_range_to_the_other_sign():
    r = float(np.percentile(np.abs(clean().internal["a2_physical"]), 95))
    rec = rec_of("a2_fixed_point_wrap", range_m_s2=r)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    inside = np.abs(a) < r
    assert np.allclose(y[inside], a[inside], rtol=0.0, atol=1e-12)
    over, under = a >= r, a < -r
    assert over.any() or under.any()
    assert np.allclose(y[over], a[over] - 2 * r, atol=1e-12) and np.allclose(y[under], a[under] + 2 * r, atol=1e-12)
    assert np.all(np.sign(y[over | under]) != np.sign(a[over | under]))        # the opposite sign
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(a, clean().internal["a2_physical"])           # a sensor: the drive is untouched


def test_brake_squeal_is_a_tone_of_its_own_that_grows_only_above_its_onset_speed():
    p = _suite_effect("wheel_brake_squeal").parameters
    rec = rec_of("wheel_brake_squeal", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6
    others_zero(rec, motor_term_Nm, mass_term_N)
    x = -tx[::SEG] / (0.5 * p["torque_Nm"])                              # the oscillator's state at the scans
    assert 1.5 < np.max(np.abs(x)) < 2.5                                 # grown to about its limit cycle
    big = np.abs(x) > 0.5
    up = np.flatnonzero(np.diff(np.sign(x)) > 0)
    period_s = np.median(np.diff(up)) * DT
    assert big.mean() > 0.2 and 1.0 / period_s == pytest.approx(p["frequency_hz"], rel=0.1)
    # with its onset above every speed of the drive it never grows beyond the floor
    quiet = rec_of("wheel_brake_squeal", **{**p, "onset_speed_rad_s": 200.0})
    assert np.max(np.abs(wheel_term_Nm(quiet))) < 0.5 * p["torque_Nm"] * 1.5e-3


def test_delta_modulator_codec_steps_by_an_adaptive_step_towards_a2():
    p = _suite_effect("a2_delta_modulator_codec").parameters
    rec = rec_of("a2_delta_modulator_codec", **p)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(a, clean().internal["a2_physical"])           # a sensor: the drive is untouched
    step = np.abs(np.diff(y))
    lo, hi = p["min_step_m_s2"], p["max_step_m_s2"]
    assert np.all(step >= lo * (1 - 1e-9)) and np.all(step <= hi * (1 + 1e-9))
    assert np.max(np.abs(y - a)) > 0.5 * lo                              # not the identity
    read = DEV8["a2_delta_modulator_codec"].read
    # a constant input: the output idles around it within a step or two of the smallest
    idle = read(np.full(2000, 0.3), p)
    assert np.max(np.abs(idle[100:] - 0.3)) <= 2 * lo * p["growth"] ** 2
    # a ramp steeper than the largest step per sample: the output's slope saturates at s_max (slope overload)
    ramp = read(np.arange(2000) * 2 * hi, p)
    assert np.allclose(np.diff(ramp)[200:], hi)
    # a ramp slower than the smallest: followed within a few steps (granular noise only)
    slow = np.arange(2000) * 0.3 * lo
    assert np.max(np.abs(read(slow, p) - slow)[100:]) < 3 * lo * p["growth"] ** 2


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED8))
def test_sealed8_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_suite_effect(name).parameters)
    assert_acts_in_its_balance_only(name, SEALED8[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set8_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(8, DEV8, SEALED8, 8800, 8900)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); the one row its module leaves below the criterion is below it, and visible."""
    assert_rows_visible(("outside_dev8", "outside_sealed8"), BELOW_CRITERION)


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev8", "outside_sealed8"))


@pytest.mark.parametrize("suite_name", ["outside_dev8", "outside_sealed8"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED8, DEV8)


def test_outside_bench_knows_set_8_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-8 are spent (set 8's sealed half ran once, 30 Nov): each sealed half is development data, in the loop's
    # default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(8, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(8)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(8, DURATION_S)
