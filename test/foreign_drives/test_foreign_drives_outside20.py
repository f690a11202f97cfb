"""The twentieth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev20,
.outside_sealed20): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the travel marker's sawtooth on the motor, the gerotor's slip assist on the wheel, the half-wave magnet's
centring across the jaw, the level-wind's fleet angle on the carriage, a1's flange twist, the tension PI brake on the
wheel, the slip relay's cylinder brake on the motor), every sealed mechanism acting in its recorded balance only, the
suites (made, written, deterministic, each mechanism row visible above the criterion its strength was set by),
``forms`` withholding the sealed laws, and the outside bench's set 20 (its sealed half spent: run once at stop 58, in
the loop's default suites and the alarm check).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_acts_in_its_balance_only, assert_forms_withholds_sealed,
                                        assert_recordings_repeat, assert_rows_visible, assert_set_registry,
                                        assert_set_suites, assert_suite_writes_one_recording)
from foreign_outside_recordings import assert_alarm_check_covers_both_halves, assert_bench_guards_unspent_sealed  # test/
from foreign_outside_recordings import assert_acts_in_its_balance_only_on_its_suite_row  # test/
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero, sample_times_s, slip_rad_s  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(20, seed=220)
DEV20, SEALED20, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _wheel_angle_unwrapped(rec):
    """The wheel's angle unwrapped from the run-in's start [rad], the kernel's XS_ALPHA2_UNWRAPPED: alpha2 with the
    whole turns the integrator took off (kernel alpha2_turns, at the run's end) put back."""
    theta = np.unwrap(rec.internal["alpha2"])
    end = rec.internal["alpha2"][-1] + 2.0 * np.pi * rec.internal["parameters"][K.P_A2TURNS]
    return end - (theta[-1] - theta)


def _carriage_position(rec):
    """The carriage's position unwrapped from the run-in's start [m], the kernel's XS_MASS_POSITION."""
    return C.WHEEL_RADIUS_M * _wheel_angle_unwrapped(rec) - rec.internal["spring_extension"]


def test_twentieth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(20)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_travel_marker_cylinder": {"torque_Nm": 0.0},
           "wheel_gerotor_slip_assist": {"torque_Nm": 0.0},
           "clutch_half_wave_magnet_centring": {"stiffness_Nm_per_rad": 0.0},
           "mass_level_wind_fleet_angle": {"coefficient_N_per_m": 0.0},
           "a1_coupling_flange_twist": {"twist_rad_per_Nm": 0.0},
           "wheel_tension_pi_brake": {"gain_Nm_per_m": 0.0, "integral_Nm_per_m_s": 0.0},
           "motor_slip_relay_cylinder_brake": {"torque_Nm": 0.0},
           "motor_tension_pwm_eddy_brake": {"torque_Nm": 0.0},
           "wheel_line_speed_step_trim": {"torque_per_step_Nm": 0.0},
           "clutch_dust_seal_squeal": {"torque_Nm": 0.0},
           "mass_tension_pumped_holdback": {"force_N": 0.0},
           "a2_baseline_restorer": {"clamp_gain": 0.0},
           "mass_strip_gripper_holdback": {"force_N": 0.0},
           "clutch_preloaded_centring_cartridge": {"preload_Nm": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV20) | set(SEALED20)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV20) | set(SEALED20)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_travel_marker_loads_the_motor_with_a_sawtooth_of_the_carriages_travel():
    p = _params("motor_travel_marker_cylinder")
    tq, pitch = p["torque_Nm"], p["pitch_m"]
    rec = rec_of("motor_travel_marker_cylinder", **p)
    tx, x = motor_term_Nm(rec), _carriage_position(rec)
    q = np.mod(x - p["offset_m"], pitch)
    clear = (q > 1e-6) & (q < pitch - 1e-6)                                  # away from the marks themselves
    law = DEV20["motor_travel_marker_cylinder"].torque(x, p)
    assert np.max(np.abs(tx - law)[clear]) < 1e-6 * tq
    assert np.all(tx >= -1e-6) and np.max(tx) <= tq * (1.0 + 1e-6)           # a load, up to its torque at a mark
    assert np.min(tx) < 0.1 * tq and np.max(tx) > 0.9 * tq
    # a sawtooth of the travel: it rises with x between marks and drops by about T at each
    marks = np.count_nonzero(np.diff(tx) < -0.5 * tq)
    assert marks >= 5 and abs(marks - np.ptp(x) / pitch) <= 1.5
    rising = clear[1:] & clear[:-1] & (np.diff(tx) > -0.5 * tq)
    assert np.allclose(np.diff(tx)[rising], tq / pitch * np.diff(x)[rising], atol=1e-6 * tq)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_gerotor_assist_drives_the_wheel_by_a_smooth_step_of_the_slip():
    p = _params("wheel_gerotor_slip_assist")
    tq = p["torque_Nm"]
    rec = rec_of("wheel_gerotor_slip_assist", **p)
    tx, s = wheel_term_Nm(rec), slip_rad_s(rec)
    law = DEV20["wheel_gerotor_slip_assist"].torque(s, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * tq
    assert np.all(tx >= -1e-6) and np.all(tx <= tq * (1.0 + 1e-6))          # an assist, within 0..T
    # a step of the slip, not its proportion: off below the onset, on above it, and through its width in between
    below, above = s < p["onset_rad_s"] - 2.0 * p["width_rad_s"], s > p["onset_rad_s"] + p["width_rad_s"]
    assert below.any() and above.any()
    assert np.max(tx[below]) < 0.02 * tq and np.min(tx[above]) > 0.85 * tq
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_the_gerotor_assists_plugin_is_the_law_in_the_projects_plugin_form(tmp_path):
    from backlash_monitor.plant import builtin_catalogue
    p = {"torque_Nm": 2.0, "onset_rad_s": 1.0, "width_rad_s": 0.5}
    path = tmp_path / "gerotor.py"
    path.write_text(DEV20["wheel_gerotor_slip_assist"].plugin(p))
    cls = builtin_catalogue().with_files([str(path)]).get("wheel_gerotor_slip_assist")
    assert cls.balance == "wheel_torque_Nm"
    for s in (-3.0, 0.0, 0.8, 1.0, 1.3, 2.5):
        got = float(cls.term(rel_speed=s, **p))
        assert got == pytest.approx(float(DEV20["wheel_gerotor_slip_assist"].torque(s, p)), abs=1e-12)


def test_half_wave_magnet_centres_the_jaw_with_a_stiffness_pulsating_with_the_mains():
    p = _params("clutch_half_wave_magnet_centring")
    k, f = p["stiffness_Nm_per_rad"], p["mains_hz"]
    rec = rec_of("clutch_half_wave_magnet_centring", **p)
    extra, d, t = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"], sample_times_s(rec)
    law = DEV20["clutch_half_wave_magnet_centring"].torque(d, t, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(extra))
    gap = rec.internal["mode"] == 0
    assert gap.any() and (~gap).any() and np.max(np.abs(extra[gap])) > 0.1   # in the gap too
    # a centring stiffness that pulses with the mains: -T/D follows k*max(0, sin)^2, nothing in the half-cycles the
    # diode blocks, the full k at the current's peaks
    moved = np.abs(d) > 1e-3
    ratio = -extra[moved] / d[moved]
    s = np.sin(2.0 * np.pi * f * t[moved] + p["phase_rad"])
    assert np.allclose(ratio, k * np.where(s > 0.0, s, 0.0) ** 2, atol=1e-6 * k)
    assert np.all(np.abs(ratio[s < 0.0]) < 1e-6 * k) and np.max(ratio) > 0.99 * k
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_level_wind_takes_a_slow_cosine_of_the_turns_off_the_cables_pull():
    p = _params("mass_level_wind_fleet_angle")
    c, n = p["coefficient_N_per_m"], p["turns_per_cycle"]
    rec = rec_of("mass_level_wind_fleet_angle", duration=1.5, **p)     # a few level-wind cycles (N turns each)
    fx, z, theta = mass_term_N(rec), rec.internal["spring_extension"], _wheel_angle_unwrapped(rec)
    law = DEV20["mass_level_wind_fleet_angle"].force(z, theta, p)
    assert np.max(np.abs(fx - law)) < 1e-6 * c
    assert np.all(fx <= 1e-9)                                                # it only takes pull off
    # a product: the force over the extension is the slow cosine of the turns, 0..2c, over more than one cycle
    g = -fx / (c * z)
    assert np.allclose(g, 1.0 - np.cos((theta - p["angle_rad"]) / n), atol=1e-6)
    assert np.ptp(theta) / (2.0 * np.pi * n) > 1.0 and np.min(g) < 0.05 and np.max(g) > 1.9
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_flange_twist_adds_the_jaws_torque_times_the_centripetal_acceleration_to_a1():
    p = _params("a1_coupling_flange_twist")
    rec = rec_of("a1_coupling_flange_twist", **p)
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
    assert np.array_equal(rec.internal["a1_physical"], clean().internal["a1_physical"])
    a1, tc, w1 = rec.internal["a1_physical"], rec.internal["clutch_torque_Nm"], rec.signals["omega1"]
    read = DEV20["a1_coupling_flange_twist"].read(a1, tc, w1, p)
    assert np.max(np.abs(rec.signals["a1"] - read)) < 1e-9 * np.max(np.abs(a1))
    # an additive error (not a gain) of the jaw's torque: 0 in the gap, r*Omega1^2*e per N*m in contact
    err = rec.signals["a1"] - a1
    gap = rec.internal["mode"] == 0
    assert gap.any() and np.max(np.abs(err[gap])) < 1e-9
    ratio = err[~gap] / tc[~gap]
    assert np.allclose(ratio, C.WHEEL_RADIUS_M * w1[~gap] ** 2 * p["twist_rad_per_Nm"], rtol=1e-6)
    assert np.max(np.abs(err)) > 0.25
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_tension_pi_brake_holds_the_extension_with_a_clamped_pi_law():
    p = _params("wheel_tension_pi_brake")
    kp, top = p["gain_Nm_per_m"], p["max_torque_Nm"]
    rec = rec_of("wheel_tension_pi_brake", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * top                       # held between its 0.2 ms scans
    u = -tx[::SEG]
    assert np.all(u >= -1e-6) and np.all(u <= top * (1.0 + 1e-6))          # a brake within 0..T_max
    z = rec.internal["spring_extension"][::SEG]                           # the extension at each scan's start
    # the integral after the first scan the output is off both limits, then the law scan by scan from there
    inside = np.flatnonzero((u > 1e-3 * top) & (u < (1.0 - 1e-3) * top))
    assert inside.size > 10
    j = int(inside[0])
    pred = DEV20["wheel_tension_pi_brake"].outputs(z[j + 1:], p, DT, integral0=u[j] - kp * (z[j] - p["reference_m"]))
    assert np.max(np.abs(pred - u[j + 1:])) < 1e-6 * top
    # a controller that moves: inside its limits a good part of the time, its integral not a constant
    assert inside.size > 0.2 * u.size and np.ptp(u) > 0.3 * top
    integral = u[inside] - kp * (z[inside] - p["reference_m"])
    assert np.ptp(integral) > 0.05 * top
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_slip_relay_fills_and_drains_the_motor_brakes_cylinder_at_the_laws_rates():
    p = _params("motor_slip_relay_cylinder_brake")
    tq = p["torque_Nm"]
    rec = rec_of("motor_slip_relay_cylinder_brake", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * tq                       # held between its 0.2 ms scans
    m = tx[::SEG] / tq
    assert np.all(m >= -1e-6) and np.all(m <= 1.0 + 1e-6)
    s = slip_rad_s(rec)[::SEG]                                                 # the slip at each scan's start
    # from the first scan with the slip below s_off (the relay off after it), the law scan by scan
    j = int(np.flatnonzero(s < p["off_below_rad_s"])[0])
    relay, pred = DEV20["motor_slip_relay_cylinder_brake"].fills(s[j + 1:], p, DT, on0=0.0, m0=m[j])
    assert np.max(np.abs(pred - m[j + 1:])) < 1e-6
    # the relay switches both ways and the fill moves at 1/T_f up and 1/T_e down, away from its limits
    assert relay.any() and not relay.all()
    dm = np.diff(m[j:])
    up, down = dm > 1e-9, dm < -1e-9
    assert np.allclose(dm[up][(m[j + 1:][up] < 1.0 - 1e-9)], DT / p["fill_time_s"], rtol=1e-6)
    assert np.allclose(dm[down][(m[j + 1:][down] > 1e-9)], -DT / p["drain_time_s"], rtol=1e-6)
    assert np.max(m) > 0.2
    others_zero(rec, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
# a sealed mechanism that acts in bursts, which this file's 0.6 s drive never starts: checked on its suite row's own
# drive without noise (4 s), at twice its suite strength (once at it, a single burst is exactly the helper's 0.5 N*m)
ON_ITS_SUITE_ROW = {"wheel_line_speed_step_trim": "torque_per_step_Nm"}


@pytest.mark.parametrize("name", sorted(SEALED20))
def test_sealed20_mechanism_acts_in_its_recorded_balance_only(name):
    if name not in ON_ITS_SUITE_ROW:
        assert_acts_in_its_balance_only(name, SEALED20[name].balance, rec_of(name, **_params(name)), clean())
        return
    assert_acts_in_its_balance_only_on_its_suite_row(name, SEALED20[name].balance, "outside_sealed20", _params(name),
                                                     ON_ITS_SUITE_ROW[name])


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set20_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(20, DEV20, SEALED20, 20000, 20100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (four with their single scaling) but two sealed rows
    its module leaves below it as written (why: in the sealed file only)."""
    assert_rows_visible(("outside_dev20", "outside_sealed20"), below={"os20_mass_tension_pumped_holdback"},
                        invisible={"os20_clutch_dust_seal_squeal"})


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev20", "outside_sealed20"))


@pytest.mark.parametrize("suite_name", ["outside_dev20", "outside_sealed20"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED20, DEV20)


def test_outside_bench_knows_set_20_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-20 are spent (set 20's sealed half ran once, 2 Dec, stop 58): each sealed half is development data, in
    # the loop's default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(20, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(20)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(20, DURATION_S)
