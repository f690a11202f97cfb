"""The twenty-fourth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev24,
.outside_sealed24): the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the
development laws checked on the drive's own balances and signals (each term recovered from the recorded, noise-free
states: the jam guard's on-delayed brake on the motor, the stroke-dumped metered brake on the wheel, the loose-bolt disc
pack across the jaw, the worn rail section on the carriage, a1's electrostatic softening, the knock-sampled tension
clamp on the carriage, the brake chopper on the motor), every sealed mechanism acting in its recorded balance only, the
suites (made, written, deterministic, each mechanism row visible above the criterion its strength was set by, but one
sealed row left below it, its single scaling not made), ``forms`` withholding the sealed laws, and the outside bench's
set 24 (its sealed half UNSPENT: the loop refuses it without --sealed, the alarm check leaves it out).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import numpy as np
import pytest

from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_drives.drive import mass_position
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/
from foreign_outside_recordings import (OutsideSet, assert_a_row_of_each_half_crosses_the_backlash,  # test/
                                        assert_acts_in_its_balance_only_on_its_suite_row,
                                        assert_forms_withholds_sealed, assert_recordings_repeat, assert_rows_visible,
                                        assert_set_registry, assert_set_suites, assert_suite_writes_one_recording)
from foreign_outside_recordings import (assert_alarm_check_leaves_out_the_unspent_sealed_half,  # test/
                                        assert_bench_refuses_the_unspent_sealed_half)
from foreign_outside_recordings import extra_clutch_Nm, held_per_segment, others_zero  # test/

SEG = N.SEGMENT_SAMPLES            # samples per 0.2 ms segment (the memory elements' scan)
DT = N.SEGMENT_S

SET = OutsideSet(24, seed=224)
DEV24, SEALED24, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _stroke_starts(rec, n_scans: int) -> list:
    """The scans at which a load pulse begins in the recording (the kernel's pulse count changes there)."""
    P = rec.internal["parameters"]
    first, period = P[K.P_PFIRST], P[K.P_PPER]                            # in 0.2 ms segments from sample 0
    return [int(np.ceil(first + k * period)) for k in range(1000) if first + k * period < n_scans]


def _depth(rec):
    """The jaw's penetration depth on either side at each sample (0 free) [rad]."""
    P = rec.internal["parameters"]
    d, mode = rec.internal["jaw_angle_difference"], rec.internal["mode"]
    return np.where(mode != 0, np.abs(d) - P[K.P_BETA], 0.0)


def test_twenty_fourth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(24)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_jaw_jam_guard_brake": {"torque_Nm": 0.0},
           "wheel_stroke_dumped_metered_brake": {"coefficient_Nm_per_m_s": 0.0},
           "clutch_loose_bolt_disc_pack": {"stiffness_Nm_per_rad": 0.0},
           "mass_worn_rail_section": {"force_N": 0.0},
           "a1_electrostatic_softening": {"coefficient_s4_per_m2": 0.0},
           "mass_knock_sampled_tension_clamp": {"gain_N_per_m": 0.0},
           "motor_line_overspeed_brake_chopper": {"torque_Nm": 0.0},
           "motor_slip_held_brake_resistor": {"torque_Nm": 0.0},
           "wheel_press_crank_traverse": {"torque_Nm": 0.0},
           "clutch_sprag_wet_band": {"torque_Nm": 0.0},
           "mass_drum_peak_tacho_holdback": {"coefficient_N_s_per_rad": 0.0},
           "a2_transmitter_squelch": {"threshold_m_s2": 0.0},
           "a2_auxiliary_winding_sag_gain": {"gain_per_pu": 0.0},
           "clutch_half_wave_eddy_coupling": {"coefficient_Nm_s_per_rad": 0.0}}


@pytest.mark.parametrize("name", sorted(set(DEV24) | set(SEALED24)))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) == set(DEV24) | set(SEALED24)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the development laws
def test_jam_guard_brakes_the_motor_once_the_jaw_has_stayed_deep_for_the_delay():
    p = _params("motor_jaw_jam_guard_brake")
    tq = p["torque_Nm"]
    rec = rec_of("motor_jaw_jam_guard_brake", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * tq
    m = tx[::SEG] / tq
    assert np.all((np.abs(m) < 1e-6) | (np.abs(m - 1.0) < 1e-6))           # on or off
    depth = _depth(rec)[::SEG]
    # from a scan at or within p_t (the on-delay's count reset there), the law scan by scan
    j = int(np.flatnonzero(depth <= p["threshold_rad"])[0])
    law = DEV24["motor_jaw_jam_guard_brake"].held(depth[j + 1:], p, DT)
    assert np.array_equal(law, np.round(m[j + 1:]))
    assert np.any(law == 1.0) and np.any(law == 0.0)
    # the delay: never on before the depth has been beyond p_t for t_d
    run = np.zeros(depth.size)
    for i in range(1, depth.size):
        run[i] = run[i - 1] + 1.0 if depth[i] > p["threshold_rad"] else 0.0
    on = np.round(m) == 1.0
    assert np.all(run[on][1:] * DT >= p["delay_s"] - 1e-12)
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_metered_brake_integrates_the_extension_over_each_stroke_on_the_wheel():
    p = _params("wheel_stroke_dumped_metered_brake")
    c = p["coefficient_Nm_per_m_s"]
    rec = rec_of("wheel_stroke_dumped_metered_brake", **p)
    tx = wheel_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-9 * c
    m = -tx[::SEG] / c
    starts = _stroke_starts(rec, m.size)
    assert len(starts) >= 2
    count = np.searchsorted(np.asarray(starts), np.arange(m.size), side="right")   # the pulse count at each scan
    z = rec.internal["spring_extension"][::SEG]
    j = starts[0]
    law = DEV24["wheel_stroke_dumped_metered_brake"].integral(z[j:], count[j:], DT, count0=count[j] - 1)
    assert np.max(np.abs(m[j:] - law)) < 1e-9
    # dumped to 0 at each stroke's start, rising between
    assert all(abs(m[s]) < 1e-12 for s in starts)
    assert np.all(np.diff(m[starts[0]:starts[1]]) > 0.0)
    others_zero(rec, motor_term_Nm, mass_term_N)


def test_disc_pack_stiffness_varies_once_a_motor_turn():
    p = _params("clutch_loose_bolt_disc_pack")
    k, e = p["stiffness_Nm_per_rad"], p["modulation"]
    rec = rec_of("clutch_loose_bolt_disc_pack", **p)
    extra, d, a1 = extra_clutch_Nm(rec), rec.internal["jaw_angle_difference"], rec.internal["alpha1"]
    law = DEV24["clutch_loose_bolt_disc_pack"].torque(d, a1, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * np.max(np.abs(law)) + 1e-9
    # the stiffness extra/D: k*(1 + e*sin(alpha1 + phi)), over its whole range within the recording
    twisted = np.abs(d) > 0.01
    stiff = extra[twisted] / d[twisted]
    assert np.allclose(stiff, k * (1.0 + e * np.sin(a1[twisted] + p["phase_rad"])), rtol=1e-6)
    assert np.ptp(stiff) > 1.5 * k * e
    gap = rec.internal["mode"] == 0
    assert gap.any() and np.max(np.abs(extra[gap])) > 0.1                # in the gap too
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_worn_rail_section_resists_the_carriage_at_one_place_on_its_track():
    # the section's centre where this file's short drive passes (its suite's lies beyond it)
    c0 = clean()
    x0 = mass_position(c0.internal["alpha2"], c0.internal["spring_extension"], c0.internal["parameters"])
    p = {**_params("mass_worn_rail_section"), "centre_m": float(np.mean(x0)), "half_width_m": 1.0}
    f0, w = p["force_N"], p["half_width_m"]
    rec = rec_of("mass_worn_rail_section", **p)
    fx = mass_term_N(rec)
    x_c = mass_position(rec.internal["alpha2"], rec.internal["spring_extension"], rec.internal["parameters"])
    law = DEV24["mass_worn_rail_section"].force(x_c, p)
    assert np.max(np.abs(fx - law)) < 1e-6 * f0
    # the full resistance at the centre, half of it w either side, falling off beyond
    i = int(np.argmin(np.abs(x_c - p["centre_m"])))
    assert abs(fx[i] + f0) < 1e-3 * f0
    for side in (-1.0, 1.0):
        k = int(np.argmin(np.abs(x_c - p["centre_m"] - side * w)))
        assert abs(fx[k] + 0.5 * f0) < 0.01 * f0
    assert np.all(fx < 0.0) and np.max(fx) > -0.05 * f0
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_electrostatic_softening_expands_a1_by_its_cube():
    p = _params("a1_electrostatic_softening")
    k = p["coefficient_s4_per_m2"]
    rec = rec_of("a1_electrostatic_softening", **p)
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
    assert np.array_equal(rec.internal["a1_physical"], clean().internal["a1_physical"])
    x = rec.internal["a1_physical"]
    err = rec.signals["a1"] - x
    assert np.allclose(err, k * x ** 3, rtol=1e-9, atol=1e-9 * np.max(np.abs(x)))
    # odd: the error has the sign of the reading and grows with its cube
    big = np.abs(x) > 0.5 * np.max(np.abs(x))
    assert big.any() and np.all(np.sign(err[big]) == np.sign(x[big]))
    form = DEV24["a1_electrostatic_softening"]
    assert np.allclose(form.read(np.array([-100.0, 0.0, 100.0]), p), [-100.0 - k * 1e6, 0.0, 100.0 + k * 1e6])
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_tension_clamp_holds_the_carriage_back_by_the_extensions_shortfall_sampled_at_each_impact():
    # the reference at this file's drive's mean extension (the sampled extension lies on both sides of it)
    z0 = clean().internal["spring_extension"]
    p = {**_params("mass_knock_sampled_tension_clamp"), "reference_m": float(np.mean(z0))}
    k, zr = p["gain_N_per_m"], p["reference_m"]
    rec = rec_of("mass_knock_sampled_tension_clamp", **p)
    fx = mass_term_N(rec)
    assert np.max(held_per_segment(fx)) < 1e-6
    f = fx[::SEG]
    assert np.all(f <= 1e-9) and np.any(f < -0.1) and np.any(np.abs(f) < 1e-9)
    z, mode = rec.internal["spring_extension"][::SEG], rec.internal["mode"]
    # it changes only at a scan after a contact from the gap began, to the law of the extension at that scan (where it
    # holds back, the held sample z_k = z_r + F/k is that extension)
    changed = np.flatnonzero(np.abs(np.diff(f)) > 1e-9) + 1
    assert changed.size >= 1
    law = DEV24["mass_knock_sampled_tension_clamp"].force(z, p)
    for i in changed:
        assert abs(f[i] - law[i]) < 1e-6
        seg = mode[(i - 1) * SEG:i * SEG + 1]
        assert np.any((seg[:-1] == 0) & (seg[1:] != 0))                   # a contact from the gap in the scan before
    # from the first change on, where it holds back, z_r + F/k is one of the extensions sampled at the changes
    after = f[changed[0]:]
    held = after < -1e-6
    assert held.any()
    zk = zr + after[held] / k
    assert np.max(np.min(np.abs(zk[:, None] - z[changed][None, :]), axis=1)) < 1e-9
    others_zero(rec, motor_term_Nm, wheel_term_Nm)


def test_brake_chopper_loads_the_motor_by_a_duty_the_sampled_carriage_speed_sets():
    # the line speed a little below this file's drive's mean carriage speed (the duty then between 0 and 1)
    v0 = clean().internal["mass_speed"]
    p = {**_params("motor_line_overspeed_brake_chopper"), "line_speed_m_s": float(np.mean(v0)) - 0.03}
    tq = p["torque_Nm"]
    rec = rec_of("motor_line_overspeed_brake_chopper", **p)
    tx = motor_term_Nm(rec)
    assert np.max(held_per_segment(tx)) < 1e-6 * tq
    g = tx[::SEG] / tq
    assert np.all((np.abs(g) < 1e-6) | (np.abs(g - 1.0) < 1e-6))          # fully in or out
    # the periods start at the run-in's first scan, a whole number of periods before sample 0
    run_in_scans = round(rec.spec.run_in_s / DT)
    per = round(p["period_s"] / DT)
    law = DEV24["motor_line_overspeed_brake_chopper"].gate(rec.internal["mass_speed"][::SEG], p,
                                                            phase0=run_in_scans % per)
    ok = np.isfinite(law)
    assert ok.sum() > 100
    assert np.array_equal(np.round(g[ok]), law[ok])
    assert np.any(law == 1.0) and np.any(law == 0.0)
    others_zero(rec, wheel_term_Nm, mass_term_N)


# ------------------------------------------------------------------ the sealed half: in its balance only
# the parameter each sealed mechanism's check doubles on its suite row's own drive (where it acts at its suite's
# conditions, which this file's short drive may not reach)
STRENGTH = {"motor_slip_held_brake_resistor": "torque_Nm",
            "wheel_press_crank_traverse": "torque_Nm",
            "clutch_sprag_wet_band": "torque_Nm",
            "mass_drum_peak_tacho_holdback": "coefficient_N_s_per_rad",
            "a2_transmitter_squelch": "threshold_m_s2",
            "a2_auxiliary_winding_sag_gain": "gain_per_pu",
            "clutch_half_wave_eddy_coupling": "coefficient_Nm_s_per_rad"}


@pytest.mark.parametrize("name", sorted(SEALED24))
def test_sealed24_mechanism_acts_in_its_recorded_balance_only(name):
    assert set(STRENGTH) == set(SEALED24)
    assert_acts_in_its_balance_only_on_its_suite_row(name, SEALED24[name].balance, "outside_sealed24", _params(name),
                                                     STRENGTH[name])


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set24_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(24, DEV24, SEALED24, 24000, 24100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s); every row is above the criterion (the development rows as written or after their
    single scaling) but one sealed row left below it, its single scaling not made."""
    assert_rows_visible(("outside_dev24", "outside_sealed24"), below={"os24_a2_auxiliary_winding_sag_gain"})


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev24", "outside_sealed24"))


@pytest.mark.parametrize("suite_name", ["outside_dev24", "outside_sealed24"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED24, DEV24)


def test_outside_bench_knows_set_24_and_refuses_its_unspent_sealed_half(capsys):
    assert_bench_refuses_the_unspent_sealed_half(24, capsys)


def test_the_alarm_check_leaves_out_the_unspent_sealed_half():
    assert_alarm_check_leaves_out_the_unspent_sealed_half(24)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(24, DURATION_S)
