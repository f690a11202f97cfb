"""The fourth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev4, .outside_sealed4):
the registry and its truth vocabulary, zero strength = the clean drive for each of the fourteen, the kernel's new
shape, the development laws checked on the drive's own balances and signals (each term recovered from the recorded,
noise-free states: the sign, the gate, the memory, the units), every sealed mechanism acting in its recorded balance
only, the suites (made, and written as recordings), ``forms`` withholding the sealed laws, and the outside bench's set 4.

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_drives import outside as O
from foreign_drives import suites
from foreign_drives.drive import make_recording, pulse_indicator
from foreign_drives.spec import EffectSpec as E
from foreign_drives.spec import RecordingSpec
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (Recordings, assert_acts_in_its_balance_only,  # test/
                                       assert_forms_withholds_sealed, assert_set_registry, assert_set_suites,
                                       assert_suite_writes_one_recording,
                                       outside_bench, suite_effect)

W = C.WHEEL_RADIUS_M
SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)

OUTSIDE = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
DEV4 = {n: f for n, f in OUTSIDE.items() if f.half == "dev4"}
SEALED4 = {n: f for n, f in OUTSIDE.items() if f.half == "sealed4"}
DURATION_S = 0.6


def _spec(effects, seed=173, width=0.0065, duration=DURATION_S):
    return RecordingSpec("t4", "outside" if effects else "clean", width, 0.025, 0.9, effects=tuple(effects), seed=seed,
                         duration_s=duration, noise=False)


RECORDINGS = Recordings(lambda effects, duration_s: _spec(effects, duration=duration_s), DURATION_S)
rec_of, clean = RECORDINGS.rec_of, RECORDINGS.clean


def _suite_effect(name):
    """The set-4 suite's use of a mechanism (its parameters at the suite's strength)."""
    return suite_effect(name, ("outside_dev4", "outside_sealed4"))


def _outside_bench():
    return outside_bench("outside_bench_under_test4")


# ------------------------------------------------------------------ registry and truth vocabulary
def test_fourth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(4)


def _strength(name):
    (k,) = [q.name for q in OUTSIDE[name].parameters if q.name.startswith(
        ("torque", "force", "coefficient", "gain", "stiffness", "lag", "window"))]
    return k


@pytest.mark.parametrize("name", sorted(DEV4) + sorted(SEALED4))
def test_zero_strength_is_the_clean_drive(name):
    """At its suite's parameters with the strength 0 the recording equals the clean drive's bit for bit (the slew-rate
    limit: at the highest slew rate its bounds allow, to rounding)."""
    p = dict(_suite_effect(name).parameters)
    if name == "a1_isolation_amp_slew":
        p["slew_rate_m_s3"] = 1e9
    else:
        p[_strength(name)] = 0.0
    rec = rec_of(name, **p)
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        if name == "a1_isolation_amp_slew" and k == "a1":
            assert np.max(np.abs(rec.signals[k] - clean().signals[k])) < 1e-9
            continue
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


def test_the_kernels_clip_shape_is_its_formula():
    for x in (-3.0, -0.2, 0.0, 0.1, 2.5):
        assert K._shaped(K.XF_CLIP, x, 0.5, 0.1, 0.0) == min(0.5, max(-0.5, x + 0.1))


def test_a_second_memory_element_in_one_recording_is_refused_in_one_line():
    spec = _spec([E("wheel_freewheel_flywheel", {"coefficient_Nms_per_rad": 1.0, "lock_time_s": 0.02,
                                                 "coast_time_s": 20.0}),
                  E("clutch_viscoelastic_insert", {"stiffness_Nm_per_rad": 100.0, "relaxation_time_s": 0.01})])
    with pytest.raises(ValueError, match="a second mechanism with a memory element in one recording; allowed: one"):
        make_recording(spec)


# ------------------------------------------------------------------ the development laws on the drive's balances
def _t(rec):
    return np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S


def test_nth_stroke_pierce_loads_the_motor_on_every_nth_stroke_only():
    p = {"torque_Nm": 8.0, "every_n": 2, "station": 1}
    rec = rec_of("motor_nth_stroke_pierce", **p)
    t = _t(rec)
    pulse = pulse_indicator(t, rec.spec.pulse_first_s)
    rise = np.flatnonzero((pulse[1:] > 0) & (pulse[:-1] == 0)) + 1
    assert rise.size == 3                                   # strokes 0, 1, 2 in 0.6 s
    k = np.searchsorted(rise, np.arange(rec.n_samples), side="right") - 1
    tx = motor_term_Nm(rec)
    law = DEV4["motor_nth_stroke_pierce"].torque(k, pulse, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * 8.0
    on = [tx[r:r + 100].mean() for r in rise]               # the extra load on stroke 1 only, in N*m
    assert on[1] == pytest.approx(8.0, abs=1e-5) and abs(on[0]) < 1e-6 and abs(on[2]) < 1e-6
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6


def test_freewheel_flywheel_only_brakes_and_keeps_a_one_way_memory_of_the_wheel_speed():
    p = {"coefficient_Nms_per_rad": 9.0, "lock_time_s": 0.02, "coast_time_s": 20.0}
    rec = rec_of("wheel_freewheel_flywheel", **p)
    tx = wheel_term_Nm(rec)
    w2 = rec.signals["omega2"]
    assert np.all(tx <= 1e-6) and tx.min() < -1.0           # a brake: never drives the wheel
    assert np.max(np.abs(motor_term_Nm(rec))) < 1e-6
    # within a 0.2 ms segment the flywheel's speed is one value: w_f = Omega2 + T/c wherever the sprag drives it
    n_seg = rec.n_samples // SEG
    wf = np.full(n_seg, np.nan)
    for j in range(n_seg):
        sl = slice(j * SEG, (j + 1) * SEG)
        engaged = tx[sl] < -1e-3
        if engaged.any():
            vals = (w2[sl] + tx[sl] / 9.0)[engaged]
            assert np.ptp(vals) < 1e-6
            wf[j] = vals.mean()
    # from one segment to the next: towards Omega2 with tau_l while the wheel is faster, else coasting with tau_c
    dt = N.SEGMENT_S
    both = np.flatnonzero(np.isfinite(wf[:-1]) & np.isfinite(wf[1:]))
    assert both.size > 50
    for j in both:
        x = w2[(j + 1) * SEG]
        want = x + (wf[j] - x) * math.exp(-dt / 0.02) if x > wf[j] else wf[j] * math.exp(-dt / 20.0)
        assert wf[j + 1] == pytest.approx(want, abs=1e-6)
    # the memory: at the same wheel speed the sprag drives in one part of the period and is free in another
    mid = (w2 > np.percentile(w2, 60)) & (w2 < np.percentile(w2, 95))
    assert (tx[mid] < -1e-3).any() and (tx[mid] > -1e-9).any()


def _nominal_contact_Nm(rec):
    """The contact law's own torque (SPEC: k_c*p + d_c*p', far side negative) from the exact angle difference and
    the speeds (no shaft hub: the rate of D is Omega1 - Omega2)."""
    i = rec.internal
    d, dd, mode = i["jaw_angle_difference"], rec.signals["omega1"] - rec.signals["omega2"], i["mode"]
    beta = rec.truth.true_width_m / W
    k, c = C.CONTACT_STIFFNESS_NM_PER_RAD, C.CONTACT_DAMPING_NMS_PER_RAD
    return np.where(mode > 0, k * (d - beta) + c * dd, np.where(mode < 0, -(k * (-d - beta) - c * dd), 0.0))


def test_viscoelastic_insert_adds_a_relaxing_branch_to_the_contact_law():
    p = {"stiffness_Nm_per_rad": 6000.0, "relaxation_time_s": 0.01}
    rec = rec_of("clutch_viscoelastic_insert", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - _nominal_contact_Nm(rec)
    mode = i["mode"]
    assert np.all(extra[mode == 0] == 0.0) and np.max(np.abs(extra)) > 5.0      # nothing in the gap
    beta = rec.truth.true_width_m / W
    depth = np.where(mode != 0, np.abs(i["jaw_angle_difference"]) - beta, 0.0)   # the penetration on either side
    # q: the depth through a first-order lag, advanced at each segment's start; from q = 0 at sample 0, compared after
    # 10 tau (the start's error has decayed by e^-10 by then)
    q = np.empty(rec.n_samples)
    qj, a = 0.0, math.exp(-N.SEGMENT_S / 0.01)
    for j in range(rec.n_samples // SEG):
        x = depth[j * SEG]
        qj = x + (qj - x) * a if j else qj
        q[j * SEG:(j + 1) * SEG] = qj
    law = mode * 6000.0 * (depth - q)                                             # N*m, the far side's negative
    late = slice(int(0.1 / C.SAMPLE_PERIOD_S), None)
    assert np.max(np.abs(extra[late] - law[late])) < 0.05
    # the contact holds exactly while the whole law (with the branch) pushes
    total = i["clutch_torque_Nm"]
    assert np.all(total[mode > 0] > -1e-9) and np.all(total[mode < 0] < 1e-9)
    # relaxation: pressing into the face the branch pushes back (stiffer than the law); held, it fades
    assert (mode * extra)[late].max() > 5.0 and (mode * extra)[late].min() < 0.0
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6


def test_spring_switch_clamp_fires_once_per_rise_through_the_set_extension_for_a_fixed_time():
    p = {"force_N": 10.0, "trigger_extension_m": 0.31, "hold_s": 0.03}
    rec = rec_of("mass_spring_switch_clamp", **p)
    fx = mass_term_N(rec)
    on = fx < -5.0
    assert np.max(np.abs(fx - np.where(on, -10.0, 0.0))) < 1e-3                  # -F*sign(v) (v ~ 22.7 m/s) or 0
    starts = np.flatnonzero(on[1:] & ~on[:-1]) + 1
    ends = np.flatnonzero(~on[1:] & on[:-1]) + 1
    assert starts.size >= 2
    z = rec.internal["spring_extension"]
    for s in starts:
        assert s % SEG == 0 and z[s] > 0.31 and z[s - SEG] <= 0.31            # scanned: risen through z_on
    for s, e in zip(starts, ends[ends > starts[0]]):
        assert e - s == 1500                                                  # 30 ms, however long z stays up
    assert np.max(np.abs(wheel_term_Nm(rec))) < 1e-6 and np.max(np.abs(motor_term_Nm(rec))) < 1e-6


def test_isolation_amp_limits_a1s_slew_only():
    rec = rec_of("a1_isolation_amp_slew", slew_rate_m_s3=1.5e6)
    a, y = rec.internal["a1_physical"], rec.signals["a1"]
    step = 1.5e6 * C.SAMPLE_PERIOD_S                                           # 30 m/s^2 per sample
    assert np.max(np.abs(np.diff(y))) <= step + 1e-9
    assert np.max(np.abs(np.diff(a))) > step                                   # the impacts are faster
    assert np.max(np.abs(y - a)) > 5.0
    assert np.mean(np.abs(y - a) < 1e-9) > 0.5                                 # slow content passes as it is
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
    assert np.array_equal(rec.internal["a1_physical"], clean().internal["a1_physical"])


def test_telemetry_shadow_holds_a1_over_an_angle_window_of_each_revolution():
    p = {"window_rad": 0.5, "start_rad": 1.0}
    rec = rec_of("a1_telemetry_shadow_hold", **p)
    a, y = rec.internal["a1_physical"], rec.signals["a1"]
    inside = DEV4["a1_telemetry_shadow_hold"].shadowed(rec.internal["alpha1"], p)
    assert np.array_equal(y[~inside], a[~inside])
    starts = np.flatnonzero(inside[1:] & ~inside[:-1]) + 1
    assert starts.size >= 10                                                   # once per revolution (~24 Hz)
    for s in starts:
        e = s + np.argmax(~inside[s:]) if (~inside[s:]).any() else inside.size
        assert np.all(y[s:e] == a[s - 1])                                      # the last value received
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])


def test_servo_assist_acts_on_the_mass_speed_sampled_and_three_scans_late():
    p = {"gain_Ns_per_m": 60.0, "reference_speed_m_s": 22.717, "scan_s": 0.001, "latency_scans": 3}
    rec = rec_of("mass_servo_assist_sampled", **p)
    fx = mass_term_N(rec)
    v = rec.internal["mass_speed"]
    scan = 50                                                                  # samples per 1 ms scan
    n = rec.n_samples // scan
    for i in range(3, n):
        want = -60.0 * (v[(i - 3) * scan] - 22.717)
        assert np.max(np.abs(fx[i * scan:(i + 1) * scan] - want)) < 1e-6
    assert np.max(np.abs(fx)) > 1.0 and np.max(np.abs(wheel_term_Nm(rec))) < 1e-6


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED4))
def test_sealed4_mechanism_acts_in_its_recorded_balance_only(name):
    duration = 3.0 if name == "mass_air_kicker" else DURATION_S               # its suite's firings begin after 2.7 s
    rec = make_recording(_spec([_suite_effect(name)], duration=duration))
    base = clean(duration)
    assert_acts_in_its_balance_only(name, SEALED4[name].balance, rec, base)


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set4_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(4, DEV4, SEALED4, 8000, 8100)


@pytest.mark.parametrize("suite_name", ["outside_dev4", "outside_sealed4"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED4, DEV4)


def test_outside_bench_knows_set_4_whose_sealed_half_is_spent_now():
    """Set 4's sealed half was run once (29 Nov): development data now, in the loop's default suites (the unspent
    sealed half's guard is tested with set 5, test_foreign_drives_outside5)."""
    bench = _outside_bench()
    assert [s.label for s in bench.suite_rows(False, 4)] == [s.label for s in suites.suite("outside_dev4")]
    assert bench.suite_name(True, 4) == "outside_sealed4" and "outside_sealed4" not in bench.UNSPENT_SEALED
    assert {"outside_dev4", "outside_sealed4", "outside_sealed2", "outside_sealed3"} <= set(bench.LOOP_DEVELOPMENT_SUITES)
    for s in suites.suite("outside_dev4") + suites.suite("outside_sealed4"):
        bal, st = bench._truth_of(s, s.truth())
        assert bool(bal) == (s.kind == "outside") and (not bal or st)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    for name in ("outside_dev4", "outside_sealed4"):
        spec = dataclasses.replace(next(s for s in suites.suite(name) if s.kind == "outside"), duration_s=DURATION_S)
        rec = make_recording(spec)
        assert all(np.all(np.isfinite(rec.signals[k])) for k in rec.signals)
        assert sum(k == "onset" for _, k in rec.true_entries()) >= 2
