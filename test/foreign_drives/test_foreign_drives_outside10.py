"""The tenth set of mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside_dev10, .outside_sealed10):
the registry and its truth vocabulary, each mechanism's neutral setting = the clean drive, the kernel's new shapes and
memory kinds, the development laws checked on the drive's own balances and signals (each term recovered from the
recorded, noise-free states: the stroke's torsional ring, the thermal cut-out's relaxation cycle, the stroke's leaf
spring, the impulse relay's toggling, the mu-law codec, the viscoelastic coupling's lag, the contact-interlocked brake),
every sealed mechanism acting in its recorded balance only, the suites (made, written, deterministic, each mechanism row
visible above the criterion its strength was set by), ``forms`` withholding the sealed laws, and the outside bench's
set 10 (its sealed half UNSPENT: the loop refuses it without --sealed).

This file names the sealed mechanisms only through the registry and the suite; it prints and states no sealed law."""
from __future__ import annotations

import math

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import kernel as K
from foreign_drives import noise as N
from foreign_drives.drive import pulse_indicator
from foreign_drives.outside_dev3 import pulse_phase_s
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

SET = OutsideSet(10, seed=198)
DEV10, SEALED10, DURATION_S = SET.dev, SET.sealed, SET.duration_s
rec_of, clean, _params = SET.rec_of, SET.clean, SET.params


def _pulse(rec):
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    on = pulse_indicator(t, rec.spec.pulse_first_s)
    return on, pulse_phase_s(t, on)


def _runs(flag):
    """(start, stop) index pairs of the runs where ``flag`` is true."""
    f = np.concatenate(([False], np.asarray(flag, dtype=bool), [False]))
    edges = np.flatnonzero(f[1:] != f[:-1])
    return list(zip(edges[::2], edges[1::2]))


def _binary_per_scan(x):
    """x (0 or 1 to 1e-9, held per segment) at the scans."""
    assert np.max(held_per_segment(x)) < 1e-9
    s = x[::SEG]
    assert np.all((np.abs(s) < 1e-9) | (np.abs(s - 1.0) < 1e-9))
    return np.round(s)


# ------------------------------------------------------------------ registry and truth vocabulary
def test_tenth_set_is_seven_and_seven_each_half_over_every_balance_in_the_benchs_words():
    assert_set_registry(10)


# each mechanism's neutral setting at its suite's parameters: a strength 0
NEUTRAL = {"motor_stroke_torsional_ring": {"amplitude_Nm": 0.0},
           "wheel_thermal_cutout_brake": {"coefficient_Nm_s_per_rad": 0.0},
           "clutch_stroke_leaf_spring": {"stiffness_Nm_per_rad": 0.0}, "mass_impulse_relay_brake": {"force_N": 0.0},
           "clutch_viscoelastic_coupling": {"coefficient_Nm_s_per_rad": 0.0},
           "wheel_contact_interlock_brake": {"torque_Nm": 0.0},
           "motor_averaged_speed_pump": {"gain_Nm_s_per_rad": 0.0}, "wheel_worn_chain_links": {"torque_Nm": 0.0},
           "clutch_misaligned_diaphragm": {"amplitude_Nm": 0.0}, "mass_neighbour_press_shocks": {"force_N": 0.0},
           "a2_piezo_hysteresis": {"half_height_m_s2": 0.0}, "a1_crossover_dead_zone": {"dead_zone_m_s2": 0.0},
           "mass_impact_sampled_brake": {"gain_N_s_per_m": 0.0}}
# the codec has no neutral setting (a quantiser): its law is checked on its own
NO_NEUTRAL = {"a1_mu_law_codec"}


@pytest.mark.parametrize("name", sorted((set(DEV10) | set(SEALED10)) - NO_NEUTRAL))
def test_neutral_setting_is_the_clean_drive(name):
    """At its suite's parameters with its neutral setting the recording equals the clean drive's bit for bit."""
    assert set(NEUTRAL) | NO_NEUTRAL == set(DEV10) | set(SEALED10)
    rec = rec_of(name, **{**_params(name), **NEUTRAL[name]})
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], clean().signals[k]), (name, k)


# ------------------------------------------------------------------ the kernel's new shapes and memory kinds
def test_the_new_shapes_are_a_hash_on_steps_and_a_train_of_decays():
    for x in (-3.7, -0.2, 0.0, 0.31, 1.0, 5.5, 1234.56):
        assert K._shaped(K.XF_HASH_STEP, x, 7.0, 0.25, 0.1) == K._shaped(K.XF_HASH, math.floor((x - 0.1) / 0.25), 7.0,
                                                                          0.0, 0.0)
        q = (x - 0.2) % 0.7
        assert K._shaped(K.XF_PERIODIC_DECAY, x, 0.7, 0.2, 0.05) == pytest.approx(math.exp(-q / 0.05), rel=1e-12)
    start = 0.2 + 3 * 0.7                                            # a period's start: the decay restarts there
    assert K._shaped(K.XF_PERIODIC_DECAY, start + 1e-6, 0.7, 0.2, 0.05) == pytest.approx(1.0, abs=1e-4)
    assert K._shaped(K.XF_PERIODIC_DECAY, start - 1e-6, 0.7, 0.2, 0.05) < math.exp(-13.9)


def _memory(kind, a=0.0, b=0.0, c=0.0):
    P = np.zeros(K.N_PARAMS)
    P[K.P_MEMKIND], P[K.P_MEMA], P[K.P_MEMB], P[K.P_MEMC] = kind, a, b, c
    return P


def test_the_moving_mean_forgets_each_input_after_its_window_and_the_impact_sample_holds_between_contacts():
    n = 5
    P = _memory(K.MK_MOVING_MEAN, float(n))
    xs = [3.0] + [0.0] * 3 + [10.0] + [0.0] * 8
    out = []
    for x in xs:
        K._memory_scan10(K.MK_MOVING_MEAN, x, P, DT)
        out.append(P[K.P_MEMSTATE])
    padded = np.concatenate((np.full(n - 1, xs[0]), xs))
    assert np.allclose(out, np.convolve(padded, np.ones(n) / n, mode="valid"), rtol=0, atol=1e-12)
    assert out[8] == pytest.approx(10.0 / n) and out[9] == 0.0      # the 10 counts n scans, then is gone at once
    P = _memory(K.MK_IMPACT_SAMPLE)
    held = []
    for x, t0 in ((1.0, 0.0), (2.0, 0.0), (3.0, 0.5), (4.0, 0.5), (5.0, 0.5), (6.0, 0.9)):
        P[K.P_CT0] = t0
        K._memory_scan10(K.MK_IMPACT_SAMPLE, x, P, DT)
        held.append(P[K.P_MEMSTATE])
    assert held == [1.0, 1.0, 3.0, 3.0, 3.0, 6.0]         # a new sample at each new contact's start only


# ------------------------------------------------------------------ the development laws
def test_stroke_ring_is_a_decaying_oscillation_from_each_strokes_start_in_the_motors_balance():
    p = _params("motor_stroke_torsional_ring")
    rec = rec_of("motor_stroke_torsional_ring", **p)
    tx = motor_term_Nm(rec)
    on, ph = _pulse(rec)
    law = DEV10["motor_stroke_torsional_ring"].torque(ph, on, p)
    assert np.max(np.abs(tx - law)) < 1e-6 * p["amplitude_Nm"]
    assert np.max(np.abs(tx[on == 0])) < 1e-9                       # nothing between strokes
    early, late = on.astype(bool) & (ph < p["decay_time_s"]), on.astype(bool) & (ph > 2.5 * p["decay_time_s"])
    assert np.max(np.abs(tx[early])) > 0.5 * p["amplitude_Nm"] > 5 * np.max(np.abs(tx[late]))   # it decays
    assert (tx[early] > 0).any() and (tx[early] < 0).any()          # and it rings: both signs
    others_zero(rec, wheel_term_Nm, mass_term_N)


def test_the_stroke_rings_plugin_is_the_law_in_the_projects_plugin_form(tmp_path):
    from backlash_monitor.plant import builtin_catalogue
    p = {"amplitude_pu": 0.5, "frequency_hz": 80.0, "decay_rate_per_s": 50.0}
    path = tmp_path / "ring.py"
    path.write_text(DEV10["motor_stroke_torsional_ring"].plugin(p))
    cls = builtin_catalogue().with_files([str(path)]).get("motor_stroke_torsional_ring")
    assert cls.balance == "motor_load_moment_pu"
    law = {"amplitude_Nm": 0.5, "frequency_hz": 80.0, "decay_time_s": 0.02}
    for t in (0.0, 0.003, 0.011, 0.04, 0.059):                        # in the pulse: its off-time is the older edge
        got = float(cls.term(pulse_time_s=t, pulse_off_time_s=t + 0.19, **p))
        assert got == pytest.approx(float(DEV10["motor_stroke_torsional_ring"].torque(t, 1.0, law)), abs=1e-9)
    assert float(cls.term(pulse_time_s=0.1, pulse_off_time_s=0.04, **p)) == 0.0     # between strokes


def test_thermal_cutout_switches_the_brake_by_its_own_heat_with_the_laws_periods():
    p = _params("wheel_thermal_cutout_brake")
    rec = rec_of("wheel_thermal_cutout_brake", **p)
    tx, w2 = wheel_term_Nm(rec), rec.signals["omega2"]
    c, tau, h_off, h_on = (p["coefficient_Nm_s_per_rad"], p["cooling_time_s"], p["off_above_J"], p["on_below_J"])
    on = _binary_per_scan(-tx / (c * w2))
    others_zero(rec, motor_term_Nm, mass_term_N)
    # off, the heat decays from H_off to H_on: tau*ln(H_off/H_on), whatever the drive does
    offs = [(a, b) for a, b in _runs(on == 0) if a > 0 and b < on.size]
    assert offs
    for a, b in offs:
        assert (b - a) * DT == pytest.approx(tau * math.log(h_off / h_on), abs=3 * DT)
    # on, it heats with the brake's power c*Omega2^2 from the wheel's own speed: the recursion from a switch-on
    # predicts every later scan's state (its heat there is H_on less at most one scan's cooling)
    start = next(a for a, b in _runs(on == 1) if a > 0)
    pred, _ = DEV10["wheel_thermal_cutout_brake"].switched(w2[::SEG][start:], p, DT, on=1.0,
                                                          heat_J=h_on * (1 - 0.5 * DT / tau))
    assert np.mean(pred == on[start:]) > 0.995 and (pred == 0).any()
    # the law alone at a steady speed: on for tau*ln((P*tau - H_on)/(P*tau - H_off)), P = c*Omega^2
    w = 150.0
    state, _ = DEV10["wheel_thermal_cutout_brake"].switched(np.full(40_000, w), p, DT)
    cycle = _runs(state == 1)[2]
    power = c * w * w
    assert (cycle[1] - cycle[0]) * DT == pytest.approx(tau * math.log((power * tau - h_on) / (power * tau - h_off)),
                                                       rel=0.01)


def test_stroke_leaf_spring_is_a_stiffness_across_the_jaw_during_each_stroke_only():
    p = _params("clutch_stroke_leaf_spring")
    rec = rec_of("clutch_stroke_leaf_spring", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    on, _ = _pulse(rec)
    d = i["jaw_angle_difference"]
    law = DEV10["clutch_stroke_leaf_spring"].torque(d, on, p)
    assert np.max(np.abs(extra - law)) < 1e-6 * p["stiffness_Nm_per_rad"]
    gap = (np.abs(d) < i["parameters"][K.P_BETA]) & (on == 1)
    assert gap.any() and np.max(np.abs(extra[gap])) > 0.5 * p["stiffness_Nm_per_rad"] * np.max(np.abs(d[gap]))
    assert np.all(extra[on == 0] == 0.0)
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_impulse_relay_toggles_the_rail_brake_each_time_the_extension_rises_past_its_switch():
    p = _params("mass_impulse_relay_brake")
    # the brake moves the spring's equilibrium by F/k (~49 mm at k = 100 N/m), so the relay and the carriage make a slow
    # cycle of their own: 1.2 s to see it toggle both ways
    rec = rec_of("mass_impulse_relay_brake", duration=1.2, **p)
    fx = mass_term_N(rec)
    on = _binary_per_scan(-fx / p["force_N"])
    others_zero(rec, motor_term_Nm, wheel_term_Nm)
    z = rec.internal["spring_extension"][::SEG]
    # the relay's state at sample 0 comes from the run-in: one of the four initial states reproduces every scan
    fits = [np.array_equal(DEV10["mass_impulse_relay_brake"].toggled(z, p, on=on[0], armed=armed)[1:], on[1:])
            for armed in (False, True)]
    assert any(fits)
    flips = np.flatnonzero(np.diff(on) != 0) + 1
    assert flips.size >= 2 and np.all(z[flips] > p["on_above_m"])     # each toggle at a scan above z_on
    # a divider: it toggles at most once per excursion above z_on
    above = _runs(z > p["on_above_m"])
    assert flips.size <= len(above)


def test_mu_law_codec_reads_a1_in_steps_that_grow_with_its_magnitude():
    p = _params("a1_mu_law_codec")
    rec = rec_of("a1_mu_law_codec", **p)
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
    a, y = rec.internal["a1_physical"], rec.signals["a1"]
    read = DEV10["a1_mu_law_codec"].read
    assert np.allclose(y, read(a, p), rtol=0, atol=1e-12) and not np.allclose(y, a, rtol=0, atol=1e-3)
    full = p["full_scale_m_s2"]
    ramp = np.linspace(-full, full, 200_001)
    levels = np.unique(read(ramp, p))
    assert levels.size == 255                                        # codes -127..127
    steps = np.diff(levels[levels > 0])
    assert steps[-1] / steps[0] > 100                                # coarse near full scale, fine near zero
    mid = np.abs(ramp) > 0.1 * full
    assert np.max(np.abs(read(ramp, p) - ramp)[mid] / np.abs(ramp[mid])) < 0.025     # a relative error, ~constant


def test_viscoelastic_coupling_passes_the_slip_relaxed_by_its_time_at_all_times():
    p = _params("clutch_viscoelastic_coupling")
    rec = rec_of("clutch_viscoelastic_coupling", **p)
    i = rec.internal
    extra = i["clutch_torque_Nm"] - contact_law_Nm(rec)
    assert np.max(held_per_segment(extra)) < 1e-6
    m = extra[::SEG] / p["coefficient_Nm_s_per_rad"]
    slip = (rec.signals["omega1"] - rec.signals["omega2"])[::SEG]
    law = DEV10["clutch_viscoelastic_coupling"].relaxed(np.concatenate(([m[0]], slip[1:])), p, DT)
    assert np.max(np.abs(m - law)) < 1e-6
    gap = np.abs(i["jaw_angle_difference"]) < i["parameters"][K.P_BETA]
    assert np.max(np.abs(extra[gap])) > 0.5                          # it couples the halves in the gap too
    assert np.max(np.abs(m - slip)) > 0.3 * np.max(np.abs(slip))     # and it lags the slip
    others_zero(rec, motor_term_Nm, wheel_term_Nm, mass_term_N)


def test_contact_interlock_brake_rises_from_each_contacts_start_and_is_off_in_the_gap():
    p = _params("wheel_contact_interlock_brake")
    rec = rec_of("wheel_contact_interlock_brake", **p)
    tx, mode = wheel_term_Nm(rec), rec.internal["mode"]
    others_zero(rec, motor_term_Nm, mass_term_N)
    assert np.max(np.abs(tx[mode == 0])) < 1e-6 and np.all(tx < 1e-6)
    tau, dt = p["rise_time_s"], C.SAMPLE_PERIOD_S
    age = -tau * np.log1p(np.minimum(tx, 0.0) / p["torque_Nm"])     # t_c from the law, inverted
    fresh = 0
    runs = [(a, b) for a, b in _runs(mode != 0) if a > 0]
    for a, b in runs:
        young = np.arange(a, b)[age[a:b] < 3 * tau]
        if young.size > 2:
            assert np.allclose(np.diff(age[young]), dt, rtol=0, atol=1e-7)     # t_c advances with the time
        fresh += 0.0 < age[a] <= dt + 1e-9                           # and starts at the contact's start
    assert runs and fresh >= 0.5 * len(runs)


# ------------------------------------------------------------------ the sealed half: in its balance only
@pytest.mark.parametrize("name", sorted(SEALED10))
def test_sealed10_mechanism_acts_in_its_recorded_balance_only(name):
    rec = rec_of(name, **_params(name))
    assert_acts_in_its_balance_only(name, SEALED10[name].balance, rec, clean())


# ------------------------------------------------------------------ suites, recordings, forms, bench
def test_set10_suites_have_one_row_per_mechanism_and_a_clean_control():
    assert_set_suites(10, DEV10, SEALED10, 10000, 10100)


def test_each_mechanism_row_is_visible_above_the_criterion_its_strength_was_set_by():
    """The visibility simulation of docs/foreign_drives.md, repeated: each row against the same spec without its
    mechanism (same seed, 4 s)."""
    assert_rows_visible(("outside_dev10", "outside_sealed10"))


def test_a_recording_is_the_same_each_time_it_is_made():
    assert_recordings_repeat(("outside_dev10", "outside_sealed10"))


@pytest.mark.parametrize("suite_name", ["outside_dev10", "outside_sealed10"])
def test_each_suite_writes_its_recordings_and_manifest(tmp_path, suite_name):
    assert_suite_writes_one_recording(tmp_path, suite_name)


def test_forms_withholds_the_sealed_laws_and_shows_the_development_ones(capsys):
    from foreign_drives.cli import main
    assert main(["forms"]) == 0
    assert_forms_withholds_sealed(capsys.readouterr().out, SEALED10, DEV10)


def test_outside_bench_knows_set_10_and_never_loops_on_an_unspent_sealed_half(capsys, monkeypatch):
    # sets 1-10 are spent (set 10's sealed half ran once, 30 Nov): each sealed half is development data, in the loop's
    # default suites; the guard, for the next set's sealed half while it is unspent
    assert_bench_guards_unspent_sealed(10, capsys, monkeypatch)


def test_the_alarm_check_covers_both_halves_once_the_sealed_one_is_spent():
    assert_alarm_check_covers_both_halves(10)


def test_a_row_of_each_half_simulates_at_its_own_conditions_and_crosses_the_backlash():
    assert_a_row_of_each_half_crosses_the_backlash(10, DURATION_S)
