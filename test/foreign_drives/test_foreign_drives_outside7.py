"""The seventh set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev7, .outside_sealed7):
the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the kernel's new shapes and
memory kinds, the development laws checked on the drive's own balances and signals (each term recovered from the
recorded, noise-free states: the product, the latch, the attraction, the timer, the gain, the window, the median), every
sealed mechanism acting in its recorded balance only, the suites (made, written, deterministic, each mechanism row
visible above the criterion its strength was set by, but the one row its module says is below it), ``forms``
withholding the sealed laws, and the outside bench's set 7 (its sealed half run once, 30 Nov: spent).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import math

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
from foreign_outside_recordings import held_per_segment  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(7, seed=191)
DEV7, SEALED7, DURATION_S = SET.dev, SET.sealed, SET.duration_s
# the one row left below it, as its module's docstring says (scaled, its simulation did not finish)
BELOW_CRITERION = {"os7_clutch_insert_mullins_softening"}
rec_of, clean, _suite_effect = SET.rec_of, SET.clean, SET.effect


def _t(rec):
    return np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S


def _stroke_at_scans(rec):
    """The load pulse's number at each scan (the first pulse at or after sample 0 is 0; -1 before it)."""
    seg = np.arange(rec.n_samples // SEG)
    first = round(rec.spec.pulse_first_s / DT)
    return np.floor((seg - first) / round(C.PULSE_PERIOD_S / DT))


# ------------------------------------------------------------------ registry and truth vocabulary
def test_seventh_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(7)


# each mechanism's neutral setting at its suite's parameters: a strength 0, a window of one sample
NEUTRAL = {"motor_eddy_disc_wobble": {"drag_Nms_per_rad": 0.0}, "wheel_overspeed_latch_brake": {"torque_Nm": 0.0},
           "clutch_magnetic_face_latch": {"pull_Nm": 0.0}, "mass_debounced_overspeed_brake": {"force_N": 0.0},
           "a2_supply_sag_gain": {"sag": 0.0}, "motor_metered_roll_feed": {"torque_Nm": 0.0},
           "a2_median_spike_filter": {"window_samples": 1}, "motor_bearing_warmup": {"cold_torque_Nm": 0.0},
           "wheel_runup_chirp": {"amplitude_Nm": 0.0}, "clutch_insert_mullins_softening": {"softening_Nm_per_rad2": 0.0},
           "mass_eddy_damper_bracket": {"damping_Ns_per_m": 0.0}, "a2_reference_ripple_gain": {"depth": 0.0},
           "mass_stroke_holddown_eccentric": {"force_N": 0.0}}
# a gain control has no exactly neutral setting inside its bounds: its largest reference leaves a1 within 1 %
NEAR_NEUTRAL = {"a1_telemetry_agc": ({"reference_m_s2": 10000.0}, 0.01)}


@pytest.mark.parametrize("name", sorted(DEV7) + sorted(SEALED7))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit (a gain
    control's: within 1 % of a1's largest value)."""
    assert set(NEUTRAL) | set(NEAR_NEUTRAL) == set(DEV7) | set(SEALED7)
    if name in NEAR_NEUTRAL:
        setting, rel = NEAR_NEUTRAL[name]
        rec = rec_of(name, **{**_suite_effect(name).parameters, **setting})
        a = clean().signals["a1"]
        assert np.max(np.abs(rec.signals["a1"] - a)) < rel * np.max(np.abs(a))
        assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
        return
    rec = rec_of(name, **{**_suite_effect(name).parameters, **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


def test_the_kernels_new_shapes_a_pull_of_two_faces_and_a_chirp():
    b, g0 = 0.04, 0.002
    pull = [K._shaped(K.XF_FACE_PULL, x, g0, b, 2.0) for x in (-0.03, 0.0, 0.01, 0.039)]
    assert pull[1] == 0.0 and pull[2] > 0.0 and pull[0] < 0.0                  # towards the nearer face, 0 midway
    assert K._shaped(K.XF_FACE_PULL, 0.03, g0, b, 2.0) == pytest.approx(-pull[0])   # odd
    assert pull[3] == pytest.approx((g0 / (0.001 + g0)) ** 2 - (g0 / (0.079 + g0)) ** 2)   # inverse square
    assert K._shaped(K.XF_FACE_PULL, 0.0401, g0, b, 2.0) == 0.0 == K._shaped(K.XF_FACE_PULL, -0.05, g0, b, 2.0)
    # the chirp: 0 before its start, its zero crossings closer together as its frequency a + b*(x - c) rises
    x = np.arange(0.0, 4.0, 1e-4)
    y = np.array([K._shaped(K.XF_CHIRP, v, 2.0, 12.0, 0.5) for v in x])
    assert np.all(y[x < 0.5] == 0.0) and np.max(np.abs(y)) <= 1.0
    crossings = x[1:][np.diff(np.sign(y)) != 0]
    crossings = crossings[crossings > 0.51]
    f_local = 0.5 / np.diff(crossings)                                          # half a period between crossings
    mid = 0.5 * (crossings[1:] + crossings[:-1])
    assert np.allclose(f_local, 2.0 + 12.0 * (mid - 0.5), rtol=0.02, atol=0.3)


def _scan(kind, xs, a=0.0, b=0.0, counts=None):
    """The seventh set's memory element scanned over the inputs ``xs`` (one 0.2 ms scan each; the pulse count
    ``counts``, else 0): its output after each scan."""
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND], P[K.P_MEMA], P[K.P_MEMB] = float(kind), a, b
    out = []
    for i, x in enumerate(xs):
        P[K.P_PCOUNT] = 0.0 if counts is None else counts[i]
        K._memory_scan7(kind, x, P, DT)
        out.append(P[K.P_MEMSTATE])
    return np.array(out)


def test_the_kernels_new_memory_kinds_from_their_definitions():
    # a latch: set by the threshold, held, reset at the next pulse's first scan
    m = _scan(K.MK_LATCH, [0, 2, 0, 0, 0, 0, 2], a=1.0, counts=[0, 0, 0, 1, 1, 2, 2])
    assert m.tolist() == [0, 1, 1, 0, 0, 0, 1]
    # an on-delay: on after 3 consecutive scans above (0.6 ms), off at the first scan at or below
    m = _scan(K.MK_ON_DELAY, [2, 2, 0, 2, 2, 2, 2, 0], a=1.0, b=3 * DT)
    assert m.tolist() == [0, 0, 0, 0, 0, 1, 1, 0]
    # the input summed since the pulse began (x*dt per scan after the pulse's first scan)
    m = _scan(K.MK_SINCE_STROKE, [5, 5, 5, 5, 5], counts=[0, 0, 1, 1, 1])
    assert np.allclose(m, [0, 5 * DT, 0, 5 * DT, 10 * DT])
    # a thermal integrator heated by x^2: towards a*x^2*b with the time constant b
    m = _scan(K.MK_HEAT, [10.0] * 20001, a=1e-3, b=0.5)
    assert m[0] == 0.0 and m[-1] == pytest.approx(0.05 * (1.0 - math.exp(-4.0 / 0.5)), rel=1e-3)
    # a peak detector: the largest input, decaying with the time constant a until a larger one comes
    m = _scan(K.MK_PEAK, [1.0, 0.0, 0.0, 0.5, 2.0], a=DT / math.log(2.0))
    assert np.allclose(m, [1.0, 0.5, 0.25, 0.5, 2.0])


# ------------------------------------------------------------------ the development laws on the drive's balances
def test_eddy_disc_wobble_is_a_drag_whose_coefficient_turns_with_the_motor_angle():
    p = _suite_effect("motor_eddy_disc_wobble").parameters
    rec = rec_of("motor_eddy_disc_wobble", **p)
    tx = motor_term_Nm(rec)
    law = DEV7["motor_eddy_disc_wobble"].torque(rec.signals["omega1"], rec.internal["alpha1"], p)
    assert np.max(np.abs(tx - law)) < 1e-6 * np.max(np.abs(law))
    # the coefficient tx/Omega1 swings by +-e around c once per turn, whatever the speed
    coeff = tx / rec.signals["omega1"]
    assert np.max(coeff) == pytest.approx(p["drag_Nms_per_rad"] * (1 + p["wobble"]), rel=1e-3)
    assert np.min(coeff) == pytest.approx(p["drag_Nms_per_rad"] * (1 - p["wobble"]), rel=1e-3)
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6


def test_overspeed_latch_brakes_from_the_trip_until_the_next_stroke():
    trip = float(np.percentile(clean().signals["omega2"], 70))
    p = {"torque_Nm": 4.0, "trip_speed_rad_s": trip}
    rec = rec_of("wheel_overspeed_latch_brake", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6
    assert np.max(np.abs(motor_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6
    on = tx[::SEG] < -2.0
    assert np.all((np.abs(tx[::SEG]) < 1e-6) | (np.abs(tx[::SEG] + 4.0) < 1e-6))
    k = _stroke_at_scans(rec)
    w2 = rec.signals["omega2"][::SEG]
    start = int(np.argmax(k == 0))                                      # the first stroke's start: a known reset
    law = DEV7["wheel_overspeed_latch_brake"].latched(w2[start:], k[start:], trip)
    assert np.array_equal(on[start:], law.astype(bool))
    assert 0.05 < on.mean() < 0.95
    # latched, it stays on through speeds below the trip: a memory, not a threshold
    assert np.any(on & (w2 < trip - 0.5))


def test_magnetic_face_latch_pulls_towards_the_nearer_face_in_the_gap_only():
    p = _suite_effect("clutch_magnetic_face_latch").parameters
    rec = rec_of("clutch_magnetic_face_latch", **p)
    i = rec.internal
    beta = i["parameters"][K.P_BETA]
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    law = DEV7["clutch_magnetic_face_latch"].torque(i["jaw_angle_difference"], beta, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * p["pull_Nm"]
    free = i["mode"] == 0
    assert free.mean() > 0.02 and np.max(np.abs(extra[~free])) < 1e-9
    gap = free & (np.abs(i["jaw_angle_difference"]) < beta)          # in the gap (free and touching: 0, as in contact)
    d = i["jaw_angle_difference"][gap]
    # towards the nearer face: a clutch torque > 0 pushes D down (as the drive-side contact's does), so near the drive
    # side (D > 0) the pull is < 0, near the far side > 0
    assert np.all(extra[gap][d > 0.5 * beta] < 0.0) and np.all(extra[gap][d < -0.5 * beta] > 0.0)
    assert np.any(d > 0.5 * beta) and np.any(d < -0.5 * beta)
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6


def test_debounced_overspeed_brake_waits_its_delay_above_the_limit_and_lets_go_at_once():
    v = clean().internal["mass_speed"]
    p = {"force_N": 10.0, "max_speed_m_s": float(np.percentile(v, 40)), "delay_s": 0.002}
    rec = rec_of("mass_debounced_overspeed_brake", **p)
    fx = mass_term_N(rec)
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6
    vs = rec.internal["mass_speed"]
    above = vs[::SEG] > p["max_speed_m_s"]
    start = int(np.argmin(above))                                       # the first scan at or below: the count is 0
    on = DEV7["mass_debounced_overspeed_brake"].on(vs[::SEG][start:], p, DT)
    law = -10.0 * np.repeat(on, SEG) * np.tanh(vs[start * SEG:start * SEG + on.size * SEG] / 0.01)
    assert np.max(np.abs(fx[start * SEG:start * SEG + law.size] - law)) < 1e-6
    assert 0.05 < on.mean() < 0.95
    # above the limit for fewer than the delay's scans: no brake
    on = np.concatenate([np.zeros(start), on])
    starts = np.flatnonzero(above[1:] & ~above[:-1]) + 1
    assert starts.size and np.all(on[starts] == 0.0)


def test_supply_sag_lowers_a2s_gain_while_the_pulse_is_on():
    rec = rec_of("a2_supply_sag_gain", sag=0.1)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    pulse = pulse_indicator(_t(rec), rec.spec.pulse_first_s)
    assert 0.1 < pulse.mean() < 0.5
    assert np.array_equal(y[pulse == 0], a[pulse == 0])
    assert np.allclose(y[pulse == 1], 0.9 * a[pulse == 1], rtol=1e-12, atol=0.0)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    assert np.array_equal(a, clean().internal["a2_physical"])           # a sensor: the drive is untouched


def test_metered_roll_feed_loads_the_motor_until_the_shaft_has_turned_the_feed_angle_since_the_stroke():
    p = {"torque_Nm": 6.0, "feed_angle_rad": 15.0}
    rec = rec_of("motor_metered_roll_feed", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-5
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6
    on = tx[::SEG] > 3.0
    assert np.all((np.abs(tx[::SEG]) < 1e-5) | (np.abs(tx[::SEG] - 6.0) < 1e-5))
    k = _stroke_at_scans(rec)
    w1 = rec.signals["omega1"][::SEG]
    start = int(np.argmax(k == 0))
    theta, law = 0.0, []
    for i in range(start, w1.size):
        theta = 0.0 if k[i] != k[i - 1] else theta + w1[i] * DT
        law.append(theta < 15.0)
    assert np.array_equal(on[start:], np.array(law))
    # its window is an angle: about theta_f/Omega1 long after each stroke's start
    assert np.sum(on[start:start + round(C.PULSE_PERIOD_S / DT)]) * DT == pytest.approx(15.0 / np.mean(w1), rel=0.05)


def test_median_spike_filter_reads_the_median_of_a2s_last_samples():
    w = 11
    rec = rec_of("a2_median_spike_filter", window_samples=w)
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    for i in (w, 1000, a.size // 2, a.size - 1):
        assert y[i] == np.median(a[i - w + 1:i + 1])
    assert np.max(np.abs(y - a)) > 0.01                                 # not the identity
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    with pytest.raises(ValueError, match="odd"):
        DEV7["a2_median_spike_filter"].read(a, {"window_samples": 4})


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED7))
def test_sealed7_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_suite_effect(name).parameters)
    assert_acts_in_its_balance_only(name, SEALED7[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set7_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(7, DEV7, SEALED7, 8600, 8700)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); the one row its module leaves below the criterion is below it, and visible."""
    assert_rows_visible(("outside_dev7", "outside_sealed7"), BELOW_CRITERION)


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev7", "outside_sealed7"))


@pytest.mark.parametrize("suite_name", ["outside_dev7", "outside_sealed7"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED7, DEV7)


def test_outside_bench_knows_set_7_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-7 are spent (set 7's sealed half ran once, 30 Nov): each sealed half is development data, in the loop's
    # default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(7, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(7)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(7, DURATION_S)
