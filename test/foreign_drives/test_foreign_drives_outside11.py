"""The eleventh set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev11,
.outside_sealed11): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
kernel's new shapes and memory kinds, the development laws checked on the drive's own balances and signals (each term
recovered from the recorded, noise-free states: the cross-shaft governor, the off-delay brake, the one-way viscous
coupling, the dead-band speed switch, the 50 Hz notch, the stroke's trapped-air cushion, the upstream tension steps),
every sealed mechanism acting in its recorded balance only, the suites (made, written, deterministic, each mechanism row
visible above the criterion its strength was set by), ``forms`` withholding the sealed laws, and the outside bench's
set 11 (its sealed half UNSPENT: the loop refuses it without --sealed, the alarm check leaves it out).

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
from foreign_outside_recordings import held_per_segment, others_zero  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S
FS = 1.0 / C.SAMPLE_PERIOD_S

SET = OutsideSet(11, seed=211)
DEV11, SEALED11, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _binary_per_scan(x):
    """x (0 or 1 to 1e-9, held per segment) at the scans."""
    assert np.max(held_per_segment(x)) < 1e-9
    s = x[::SEG]
    assert np.all((np.abs(s) < 1e-9) | (np.abs(s - 1.0) < 1e-9))
    return np.round(s)


# ------------------------------------------------------------------ registry and truth vocabulary
def test_eleventh_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(11)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_wheel_runaway_governor": {"gain_Nm_s_per_rad": 0.0},
           "wheel_off_delay_overspeed_brake": {"torque_Nm": 0.0},
           "clutch_overrunning_viscous_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_dead_band_speed_switch": {"force_N": 0.0}, "mass_stroke_trapped_air_cushion": {"force_N": 0.0},
           "wheel_upstream_tension_steps": {"torque_Nm": 0.0},
           "motor_magnetic_coupling_rotor": {"pull_out_torque_Nm": 0.0}, "wheel_torque_sensing_ramp_brake": {"gain": 0.0},
           "clutch_fill_controlled_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "mass_rate_state_slideway": {"direct_N": 0.0, "evolution_N": 0.0}, "a1_telemetry_bit_errors": {"error_rate": 0.0},
           "a2_stitched_dual_range": {"gain_mismatch": 0.0}, "clutch_over_centre_toggle_spring": {"torque_Nm": 0.0}}
# the notch has no neutral setting (a filter): its law is checked on its own
NO_NEUTRAL = {"a2_mains_notch_filter"}


@pytest.mark.parametrize("name", sorted((set(DEV11) | set(SEALED11)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) | NO_NEUTRAL == set(DEV11) | set(SEALED11)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the kernel's new shapes and memory kinds
def test_the_new_shapes_are_a_logarithm_and_a_polytropic_law_with_its_stop():
    for x in (0.5, 1.0, 22.71, 40.0):
        assert K._shaped(K.XF_LOG, x, 22.71, 0.0, 0.0) == pytest.approx(math.log(x / 22.71), rel=1e-12, abs=1e-15)
    assert K._shaped(K.XF_LOG, 0.0, 1.0, 0.0, 0.0) == 0.0
    assert K._shaped(K.XF_POLYTROPIC, 0.0, 0.1, 1.4, 0.0) == 0.0                 # no force where nothing is squeezed
    for x in (-0.05, 0.01, 0.05):                                                # Boyle-Poisson: p*V^gamma constant
        assert K._shaped(K.XF_POLYTROPIC, x, 0.1, 1.4, 0.0) + 1.0 == pytest.approx((0.1 / (0.1 - x)) ** 1.4, rel=1e-12)
    stop = K._shaped(K.XF_POLYTROPIC, 0.09, 0.1, 1.4, 0.0)                      # the cylinder's stop at 0.9*L0
    assert K._shaped(K.XF_POLYTROPIC, 0.2, 0.1, 1.4, 0.0) == pytest.approx(stop, rel=1e-12)


def _memory(kind, a=0.0, b=0.0, c=0.0):
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND], P[K.P_MEMA], P[K.P_MEMB], P[K.P_MEMC] = kind, a, b, c
    return P


def _scan(P, kind, xs, t0=0.0):
    out = []
    for i, x in enumerate(xs):
        K._memory_scan11(kind, t0 + i * DT, x, P, DT)
        out.append(P[K.P_MEMSTATE])
    return np.array(out)


def test_the_fill_ramps_between_its_limits_and_the_off_delay_holds_for_its_time_after_the_last_scan_above():
    fill = _scan(_memory(K.MK_FILL, 0.01, 0.02), K.MK_FILL, [0.0] + [1.0] * 80 + [0.0] * 150)
    assert fill[0] == 0.0 and fill[25] == pytest.approx(25 * DT / 0.01)          # a straight ramp up ...
    assert fill[60] == 1.0 and np.max(fill) == 1.0                               # ... to its hard limit
    assert fill[80] - fill[90] == pytest.approx(10 * DT / 0.02)                  # down at its own rate
    assert fill[-1] == 0.0 and np.min(fill) == 0.0
    hold = 0.002                                                                  # 10 scans
    xs = [0.0, 5.0, 0.0, 5.0] + [0.0] * 20
    on = _scan(_memory(K.MK_OFF_DELAY, 1.0, hold), K.MK_OFF_DELAY, xs)
    assert list(on[:4]) == [0.0, 1.0, 1.0, 1.0]                                   # on at once
    assert np.all(on[3:13] == 1.0) and np.all(on[13:] == 0.0)                    # off 10 scans after the LAST scan above


def test_the_rate_state_relaxes_over_its_slip_distance_and_the_magnetic_coupling_carries_its_rotors_load_or_slips():
    dc = 0.5
    P = _memory(K.MK_RATE_STATE, dc)
    theta = _scan(P, K.MK_RATE_STATE, [20.0] * 3 + [25.0] * 400)
    assert theta[0] == pytest.approx(dc / 20.0)                                   # steady at the start
    travel = 25.0 * DT * np.arange(1, 401)                                        # slip since the speed step
    assert np.allclose(theta[3:], dc / 25.0 + (dc / 20.0 - dc / 25.0) * np.exp(-travel / dc), rtol=1e-9)
    # the coupling at a steady speed: the rotor turns with the shaft, the load its viscous load c_r*Omega
    tm, n, j, cr = 10.0, 4.0, 0.02, 0.03
    P = _memory(K.MK_MAG_COUPLING, tm, n, j)
    P[K.P_MEMR0 + K.MEM_EXTRA] = cr
    load = _scan(P, K.MK_MAG_COUPLING, [150.0] * 2000)
    assert np.allclose(load, cr * 150.0, rtol=1e-9)
    # overloaded (c_r*Omega > T_m) it slips poles: the load swings through both signs, its mean far below T_m
    P = _memory(K.MK_MAG_COUPLING, tm, n, j)
    P[K.P_MEMR0 + K.MEM_EXTRA] = 0.1
    load = _scan(P, K.MK_MAG_COUPLING, [150.0] * 20000)
    assert load.max() > 0.99 * tm and load.min() < -0.99 * tm and abs(load[5000:].mean()) < 0.5 * tm


# ------------------------------------------------------------------ the development laws
def test_runaway_governor_loads_the_motor_with_the_wheels_overspeed():
    p = _params("motor_wheel_runaway_governor")
    rec = rec_of("motor_wheel_runaway_governor", **p)
    tx, w2 = motor_term_Nm(rec), rec.signals["omega2"]
    law = DEV11["motor_wheel_runaway_governor"].torque(w2, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * p["gain_Nm_s_per_rad"] * 10
    below = w2 < p["set_speed_rad_s"]
    assert below.any() and (~below).any() and np.max(np.abs(tx[below])) < 1e-6 and np.max(tx) > 0.5
    # it reads the WHEEL's speed: where the jaw's halves run apart, the motor's own speed does not give it
    slip = np.abs(rec.signals["omega1"] - w2) > 1.0
    assert slip.any() and np.max(np.abs(tx - DEV11["motor_wheel_runaway_governor"].torque(rec.signals["omega1"], p))[
        slip]) > 0.5
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_off_delay_brake_holds_on_for_its_time_after_the_wheel_speed_falls_below_the_trip():
    p = _params("wheel_off_delay_overspeed_brake")
    rec = rec_of("wheel_off_delay_overspeed_brake", **p)
    tx = wheel_term_Nm(rec)
    on = _binary_per_scan(-tx / p["torque_Nm"])
    others_zero(rec, motor_term_Nm, mass_term_N)
    w = rec.signals["omega2"][::SEG]
    above = w > p["trip_speed_rad_s"]
    assert np.all(on[above] == 1.0)                                     # on at every scan above the trip
    held = (on == 1.0) & ~above
    assert held.any() and (on == 0.0).any()                             # held on below it, and released
    start = int(np.flatnonzero(above)[0])
    pred = DEV11["wheel_off_delay_overspeed_brake"].held(w[start:], p, DT, on=1.0, since_s=0.0)
    assert np.mean(pred == on[start:]) > 0.995
    # each release comes T_off after the last scan above: off_delay_s/DT scans
    k = int(round(p["off_delay_s"] / DT))
    for i in np.flatnonzero(np.diff(on) < 0) + 1:
        if i > start:
            assert not above[i - k + 1:i + 1].any() and above[i - k]


def test_overrunning_coupling_passes_the_slip_one_way_in_the_gap_and_in_contact():
    p = _params("clutch_overrunning_viscous_coupling")
    rec = rec_of("clutch_overrunning_viscous_coupling", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    slip = rec.signals["omega1"] - rec.signals["omega2"]
    law = DEV11["clutch_overrunning_viscous_coupling"].torque(slip, p)
    assert np.max(np.abs(extra - law)) < 1e-6
    assert (slip < -0.5).any() and np.all(extra[slip < 0] == 0.0)       # freewheeling while the wheel overruns
    gap = np.abs(i["jaw_angle_difference"]) < i["parameters"][K.P_BETA]
    assert np.max(extra[gap]) > 0.5                                      # it couples the halves in the gap too
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_dead_band_switch_pushes_below_its_band_brakes_above_it_and_leaves_the_band_alone():
    p = _params("mass_dead_band_speed_switch")
    rec = rec_of("mass_dead_band_speed_switch", **p)
    fx, v = mass_term_N(rec), rec.internal["mass_speed"]
    assert np.max(np.abs(fx - DEV11["mass_dead_band_speed_switch"].force(v, p))) < 1e-6
    f, v0, hb, w = p["force_N"], p["reference_speed_m_s"], p["half_band_m_s"], p["edge_width_m_s"]
    slow, fast, band = v < v0 - hb - 3 * w, v > v0 + hb + 3 * w, np.abs(v - v0) < hb - 3 * w
    assert slow.any() and fast.any() and band.any()                      # three levels in one recording
    assert np.allclose(fx[slow], f, atol=0.01 * f) and np.allclose(fx[fast], -f, atol=0.01 * f)
    assert np.max(np.abs(fx[band])) < 0.01 * f
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_notch_removes_its_band_from_a2_and_passes_the_strokes():
    p = _params("a2_mains_notch_filter")
    read = DEV11["a2_mains_notch_filter"].read
    t = np.arange(int(0.5 * FS)) / FS
    late = t > 0.25
    for f_hz, gain in ((p["notch_hz"], 0.0), (4.0, 1.0), (2000.0, 1.0)):
        y = read(np.sin(2 * math.pi * f_hz * t), p, FS)
        assert np.sqrt(2 * np.mean(y[late] ** 2)) == pytest.approx(gain, abs=0.02), f_hz
    # the -3 dB edges at f_0*(sqrt(1 + 1/(4Q^2)) -+ 1/(2Q)) (a second-order notch of quality Q)
    q = p["quality"]
    for f_hz in (p["notch_hz"] * (math.sqrt(1 + 1 / (4 * q * q)) + s / (2 * q)) for s in (-1, 1)):
        y = read(np.sin(2 * math.pi * f_hz * t), p, FS)
        assert np.sqrt(2 * np.mean(y[late] ** 2)) == pytest.approx(math.sqrt(0.5), abs=0.02)
    rec = rec_of("a2_mains_notch_filter", **p)
    assert np.array_equal(rec.signals["a1"], clean().signals["a1"])
    a, y = rec.internal["a2_physical"], rec.signals["a2"]
    settled = np.arange(a.size) / FS > 0.15                              # the pre-roll's start forgotten
    assert np.allclose(y[settled], read(a, p, FS)[settled], rtol=0, atol=1e-6)
    assert np.sqrt(np.mean((y - a) ** 2)) > 0.05


def test_trapped_air_cushion_springs_from_the_extension_at_each_strokes_start():
    p = _params("mass_stroke_trapped_air_cushion")
    rec = rec_of("mass_stroke_trapped_air_cushion", **p)
    fx, z = mass_term_N(rec), rec.internal["spring_extension"]
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    on = pulse_indicator(t, rec.spec.pulse_first_s)
    starts = np.flatnonzero(np.diff(on) > 0) + 1
    assert starts.size >= 2 and np.all(starts % SEG == 0)               # each stroke starts at a scan
    zk = np.full(z.size, np.nan)
    for a, b in zip(starts, list(starts[1:]) + [z.size]):
        zk[a:b] = z[a]
    known = ~np.isnan(zk)
    law = DEV11["mass_stroke_trapped_air_cushion"].force(z[known] - zk[known], p)
    assert np.max(np.abs(fx[known] - law)) < 1e-6 * p["force_N"] * 10
    assert np.max(np.abs(fx[starts])) < 1e-6                             # no force where the air was just trapped
    assert np.max(np.abs(fx[known])) > 0.5
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_upstream_tension_is_a_random_staircase_of_the_time():
    p = _params("wheel_upstream_tension_steps")
    rec = rec_of("wheel_upstream_tension_steps", **p)
    tx = wheel_term_Nm(rec)
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    q = (t - p["first_step_s"]) / p["step_s"]
    inner = np.abs(q - np.round(q)) > 1e-6                # off the updates' instants (the time's rounding there)
    assert np.max(np.abs(tx - DEV11["wheel_upstream_tension_steps"].torque(t, p))[inner]) < 1e-6
    k = np.floor(q)
    levels = [tx[inner & (k == j)] for j in np.unique(k)]
    assert len(levels) >= 5 and all(np.ptp(x) < 1e-6 for x in levels)    # constant between its updates
    steps = np.abs(np.diff([x[0] for x in levels]))
    assert np.all(steps > 1e-3) and np.max(np.abs(tx)) <= p["torque_Nm"]  # a new level at each
    others_zero(rec, motor_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED11))
def test_sealed11_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED11[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set11_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(11, DEV11, SEALED11, 11000, 11100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s)."""
    assert_rows_visible(("outside_dev11", "outside_sealed11"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev11", "outside_sealed11"))


@pytest.mark.parametrize("suite_name", ["outside_dev11", "outside_sealed11"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED11, DEV11)


def test_outside_bench_knows_set_11_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-11 are spent (set 11's sealed half ran once, 30 Nov): each sealed half is development data, in the loop's
    # default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(11, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(11)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(11, DURATION_S)
