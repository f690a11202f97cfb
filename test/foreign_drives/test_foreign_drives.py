"""foreign_drives: the second, independent generator of drive recordings (docs/foreign_drives.md).

What is tested: its code never imports the project's physics; its integrator (the tableau against scipy's
RK45, the continuous extension's order, convergence); its settled start (a periodic orbit); its noise
generators (SPEC's statistics); every effect form does what its physics says (balances over a pulse period,
spectral lines, filter responses, exact sensor operations); the truth; the bag/NPZ/CSV files read back through
the project's reader and the official mcap reader; the manifest round trip; the CLI. The cross-validation
against backlash_monitor.plant is in test_foreign_drives_crossval.py.
"""
import ast
import dataclasses
import functools
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import noise as N
from foreign_drives.drive import make_recording
from foreign_drives.spec import EffectSpec as E
from foreign_drives.spec import RecordingSpec, SensorNuisance, read_manifest, write_manifest

REPO = Path(__file__).resolve().parents[2]
PKG = REPO / "foreign_drives"
W = C.WHEEL_RADIUS_M


def spec(effects=(), kind=None, width=0.0075, eta=0.025, n1=0.89, seed=150, duration=1.0, noise=False, **kw):
    if kind is None:
        fams = [F.get(e.form).family for e in effects]
        kind = ("outside" if any(f is None for f in fams) else {0: "clean", 1: "one", 2: "two"}[len(fams)])
    return RecordingSpec("t", kind, width, eta, n1, effects=tuple(effects), seed=seed, duration_s=duration,
                         noise=noise, **kw)


@functools.lru_cache(maxsize=None)
def nominal_drive(duration=1.0):
    """make_recording(spec(duration=duration)), the clean nominal drive several tests compare against, made once
    per duration (the generator is deterministic for a spec); its arrays read-only, so no test changes another's."""
    rec = make_recording(spec(duration=duration))
    for group in (rec.signals, rec.internal):
        for value in group.values():
            if isinstance(value, np.ndarray):
                value.setflags(write=False)
    return rec


def whole_periods(x, fs=C.SAMPLE_RATE_HZ):
    """The samples of whole pulse periods (from sample 0): means over them are period averages."""
    n = int(round(C.PULSE_PERIOD_S * fs))
    return x[: (len(x) // n) * n]


def onset_entries(d, beta):
    inside = np.abs(d) < beta
    ks = np.flatnonzero(inside[1:] & ~inside[:-1]) + 1
    return [int(k) for k in ks if d[k - 1] > 0]


def far_impacts_ms(rec):
    d = rec.internal["jaw_angle_difference"]
    beta = rec.truth.true_width_m / W
    out = []
    for k in onset_entries(d, beta):
        hit = np.flatnonzero(d[k:k + C.WINDOW_SAMPLES] <= -beta)
        if hit.size and k + C.WINDOW_SAMPLES <= len(d):
            out.append(hit[0] * C.SAMPLE_PERIOD_S * 1e3)
    return np.array(out)


def spectrum(x, fs=C.SAMPLE_RATE_HZ):
    x = x - x.mean()
    win = np.hanning(x.size)
    return np.fft.rfftfreq(x.size, 1 / fs), np.abs(np.fft.rfft(x * win))


# ------------------------------------------------------------------------------------------- independence
ALLOWED_THIRD_PARTY = {"numpy", "scipy", "numba", "mcap", "mcap_ros2"}


def _relative_import_module(node) -> bool:
    """``importlib.import_module(".name", __package__)`` (the name a string or an f-string starting with "."): a module
    of foreign_drives itself, as forms.py's outside sets and suites.py's sealed halves are imported on use."""
    if getattr(node.func, "attr", "") != "import_module" or len(node.args) != 2:
        return False
    name, package = node.args
    if not (isinstance(package, ast.Name) and package.id == "__package__"):
        return False
    first = name.values[0] if isinstance(name, ast.JoinedStr) and name.values else name
    return isinstance(first, ast.Constant) and isinstance(first.value, str) and first.value.startswith(".")


def test_package_imports_only_numpy_scipy_numba_mcap_and_the_standard_library():
    """The hard rule: the foreign generator shares no code with backlash_monitor (only SPEC's constants)."""
    files = sorted(PKG.glob("*.py"))
    assert len(files) >= 8
    for f in files:
        tree = ast.parse(f.read_text(), filename=str(f))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                mods = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level > 0:          # relative: inside foreign_drives
                    continue
                mods = [node.module]
            elif isinstance(node, ast.Call) and getattr(node.func, "attr", getattr(node.func, "id", "")) in (
                    "import_module", "__import__"):
                if _relative_import_module(node):      # importlib.import_module(".name", __package__): inside
                    continue
                pytest.fail(f"{f.name}:{node.lineno}: dynamic import")
            else:
                continue
            for m in mods:
                top = m.split(".")[0]
                assert top in ALLOWED_THIRD_PARTY or top in sys.stdlib_module_names, \
                    f"{f.name}:{node.lineno} imports {m}"
        named = [n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)
                 and (n.value == "backlash_monitor" or n.value.startswith("backlash_monitor."))]
        assert not named, f"{f.name} names a backlash_monitor module: {named}"


def test_the_catalogue_families_written_out_are_the_catalogues_and_each_has_a_foreign_form():
    from backlash_monitor.plant.effects import CATALOGUE_NAMES
    assert set(F.CATALOGUE_FAMILIES) == set(CATALOGUE_NAMES)
    covered = {f.family for f in F.FORMS.values()}
    assert set(CATALOGUE_NAMES) <= covered
    assert sum(f.family is None for f in F.FORMS.values()) >= 5
    for f in F.FORMS.values():
        assert f.description and f.parameters and f.stage in F.STAGES


def test_constants_are_spec_section_3():
    w = C.STATOR_REACTANCE_PU * C.ROTOR_REACTANCE_PU - C.MAGNETISING_REACTANCE_PU ** 2
    assert w == pytest.approx(0.374, abs=5e-4)
    assert C.MOTOR_INERTIA_KGM2 == pytest.approx(0.1095, abs=1e-4)
    assert C.BASE_MECHANICAL_SPEED_RAD_S == pytest.approx(157.08, abs=0.01)
    assert C.absorber_coefficient(0.025, 0.89) == pytest.approx(17.0, abs=0.05)     # docs/model.md


# ------------------------------------------------------------------------------------------- integrator
def _drive_rhs(P, mode=1, load=0.3):
    from foreign_drives.kernel import N_STATES, rhs

    def f(t, y):
        dy = np.empty(N_STATES)
        rhs(t, np.asarray(y, dtype=float), mode, load, P, 1.0, dy)
        return dy
    return f


def _engaged_state():
    from foreign_drives.physics import nominal_parameters
    from foreign_drives.simulation import first_guess
    P = nominal_parameters(0.005, 0.025, 0.89)
    return P, first_guess(P, C.PULSE_AMPLITUDE_PU)


def test_one_dopri_step_is_scipys_rk45_step():
    """The Dormand-Prince tableau: one step equals scipy's RK45 step of the same length (same method)."""
    from scipy.integrate import RK45
    from foreign_drives.kernel import dopri_step
    P, y0 = _engaged_state()
    f = _drive_rhs(P)
    h = 1.5e-4
    solver = RK45(f, 0.0, y0, 1.0, first_step=h, max_step=h, rtol=1e3, atol=1e3)
    solver.step()
    assert solver.t == pytest.approx(h, rel=1e-12)
    k = np.zeros((7, y0.size))
    k[0] = f(0.0, y0)
    ynew, ytmp = np.empty_like(y0), np.empty_like(y0)
    dopri_step(0.0, y0.copy(), k, h, 1, 0.3, P, 1.0, ynew, ytmp)
    np.testing.assert_allclose(ynew, solver.y, rtol=1e-13, atol=1e-13)


def test_continuous_extension_is_fourth_order():
    """The samples between steps come from DOPRI5's continuous extension: its mid-step error falls as h^5."""
    from foreign_drives.kernel import dense_coefficients, dense_eval, dopri_step
    P, y0 = _engaged_state()
    f = _drive_rhs(P)

    def step(y, h):
        k = np.zeros((7, y.size))
        k[0] = f(0.0, y)
        yn, yt = np.empty_like(y), np.empty_like(y)
        dopri_step(0.0, y.copy(), k, h, 1, 0.3, P, 1.0, yn, yt)
        return k, yn

    def reference(y, t, m=400):
        for _ in range(m):
            _, y = step(y, t / m)
        return y
    errs = []
    for h in (8e-4, 4e-4):
        k, yn = step(y0, h)
        rc = np.empty((5, y0.size))
        dense_coefficients(y0, yn, k, h, rc)
        ymid = np.empty_like(y0)
        dense_eval(rc, 0.3, ymid)
        errs.append(abs(ymid[4] - reference(y0, 0.3 * h)[4]))       # the motor speed
    assert errs[0] / errs[1] > 20.0                                   # 2^5 = 32 for a 4th-order extension


def test_recording_converges_with_the_tolerance():
    """a1/a2/angle of a noisy run at the default tolerance against 1000x tighter: far below the noise."""
    s = spec(duration=0.6, noise=True)
    a = make_recording(s)
    b = make_recording(s, tol_scale=1e-3)
    for name in ("a1", "a2"):
        peak = np.max(np.abs(b.signals[name]))
        assert np.max(np.abs(a.signals[name] - b.signals[name])) < 1e-5 * peak
    assert np.max(np.abs(a.signals["angle_difference"] - b.signals["angle_difference"])) < 1e-8
    assert b.stats["accepted_steps"] > a.stats["accepted_steps"]


def test_settled_start_is_the_periodic_orbit():
    """Noise-free, the first onset's far-side impact is the last one's, and the period map's residual is tiny."""
    rec = make_recording(spec(width=0.01, duration=2.0))
    imp = far_impacts_ms(rec)
    assert len(imp) == 8
    assert np.ptp(imp) <= 0.02 + 1e-9          # one sample
    assert rec.stats["residual"] < 1e-10
    n = int(round(C.PULSE_PERIOD_S / C.SAMPLE_PERIOD_S))
    for name in ("a1", "a2", "omega1"):
        x = rec.signals[name]
        assert np.max(np.abs(x[:n] - x[-n:])) < 1e-4 * np.max(np.abs(x))


# ------------------------------------------------------------------------------------------- noise
def test_noise_generators_have_specs_statistics():
    rng = N.streams(123)
    g = N.gaussian_values(rng["gaussian"], 200_000)
    t = N.telegraph_values(rng["telegraph"], 200_000)
    assert g.var() == pytest.approx(0.05, rel=0.02) and abs(g.mean()) < 0.003
    assert set(np.round(np.unique(t), 12)) == {round(-math.sqrt(0.05), 12), round(math.sqrt(0.05), 12)}
    assert abs(t.mean()) < 0.01
    held = t.reshape(-1, N.TELEGRAPH_SEGMENTS)                        # 2 ms holds: 10 segments of 0.2 ms
    assert np.all(held == held[:, :1])
    assert abs(np.corrcoef(held[1:, 0], held[:-1, 0])[0, 1]) < 0.02  # new values are independent
    assert abs(np.corrcoef(g[:20_000], t[:20_000])[0, 1]) < 0.03
    assert N.SEGMENT_SAMPLES == 10                                    # Gaussian held 0.2 ms = 10 samples
    again = N.streams(123)
    assert np.array_equal(N.gaussian_values(again["gaussian"], 1000), g[:1000])


def test_pulse_train_is_specs():
    p = N.pulse_train(0, 2500, 1.6, 0.05)
    on = np.flatnonzero(p)
    assert on[0] * N.SEGMENT_S == pytest.approx(0.05)
    assert np.count_nonzero(p[:1250]) * N.SEGMENT_S == pytest.approx(0.06)
    assert np.array_equal(p[:1250], p[1250:])
    before = N.pulse_train(-1250, 1250, 1.6, 0.05)
    assert np.array_equal(before, p[:1250])                           # periodic backwards (the run-in)


def test_noisy_drive_has_four_onsets_and_four_returns_per_second():
    rec = make_recording(spec(width=0.0025, eta=0.05, n1=0.97, duration=2.0, noise=True, seed=160))
    ent = rec.true_entries()
    kinds = [k for _, k in ent]
    assert kinds.count("onset") == 8 and kinds.count("return") == 8
    assert all(a != b for a, b in zip(kinds, kinds[1:]))              # strictly alternating
    assert np.min(np.diff([k for k, _ in ent])) > C.WINDOW_SAMPLES   # no re-trigger inside a window


# ------------------------------------------------------------------------------------------- physics forms
def test_wheel_frictions_raise_the_mean_clutch_torque_by_their_torque():
    """Over whole pulse periods the wheel's and the mass's speeds return: mean T_c = r*F0 + mean friction."""
    base = nominal_drive()
    tc0 = np.mean(whole_periods(base.internal["clutch_torque_Nm"]))
    assert tc0 == pytest.approx(W * C.WORKING_RESISTANCE_N, rel=1e-3)
    cases = [(E("wheel_friction_tanh", {"torque_Nm": 2.5, "smoothing_speed_rad_s": 40.0}),
              lambda w2, f: 2.5 * np.tanh(w2 / 40.0)),
             (E("wheel_friction_load_dependent", {"base_torque_Nm": 0.3, "load_coefficient_m": 0.05}),
              lambda w2, f: 0.3 + 0.05 * np.abs(f)),
             (E("wheel_drag_power", {"coefficient": 3e-5, "exponent": 2.0}), lambda w2, f: 3e-5 * w2 ** 2),
             (E("wheel_friction_stribeck_power", {"coulomb_torque_Nm": 0.5, "excess_torque_Nm": 2.0,
                                                  "stribeck_speed_rad_s": 100.0, "exponent": 0.7}),
              lambda w2, f: 0.5 + 2.0 * np.exp(-(w2 / 100.0) ** 0.7)),
             (E("wheel_load_torque", {"torque_Nm": 1.1}), lambda w2, f: 1.1 + 0 * w2)]
    for eff, law in cases:
        rec = make_recording(spec([eff]))
        tc = whole_periods(rec.internal["clutch_torque_Nm"])
        tf = whole_periods(law(rec.signals["omega2"], rec.internal["rim_force_N"]))
        assert np.mean(tc) == pytest.approx(W * C.WORKING_RESISTANCE_N + np.mean(tf), rel=2e-3), eff.form
        eq = rec.truth.effects[0].equivalent or rec.truth.effects[0].also_accepted["wheel_coulomb_friction"]
        if "torque_Nm" in eq:                       # the equivalent dry torque is the mean friction torque
            assert eq["torque_Nm"] == pytest.approx(np.mean(tf), rel=0.03), eff.form


def test_motor_side_loads_raise_the_mean_electromagnetic_torque():
    """The motor's speed returns over a period: mean T_b*t_e = r*F0 + T_b*mean pulse + mean motor-side load."""
    pulse_mean = C.PULSE_AMPLITUDE_PU * C.PULSE_DURATION_S / C.PULSE_PERIOD_S
    cases = [(E("motor_friction_tanh", {"torque_Nm": 1.4, "smoothing_speed_rad_s": 5.0}),
              lambda w: 1.4 * np.tanh(w / 5)),
             (E("motor_friction_viscous", {"damping_Nms_per_rad": 0.01}), lambda w: 0.01 * w),
             (E("motor_fan_load", {"torque_Nm": 2.2, "reference_speed_rad_s": 150.0}), lambda w: 2.2 * (w / 150) ** 2),
             (E("motor_load_constant", {"torque_Nm": -0.8}), lambda w: -0.8 + 0 * w)]
    for eff, law in cases:
        rec = make_recording(spec([eff]))
        te = np.mean(whole_periods(rec.internal["te_pu"])) * C.BASE_TORQUE_NM
        load = np.mean(whole_periods(law(rec.signals["omega1"])))
        expected = W * C.WORKING_RESISTANCE_N + C.BASE_TORQUE_NM * pulse_mean + load
        assert te == pytest.approx(expected, rel=2e-3), eff.form


def test_forces_on_the_mass_move_the_mean_rim_force():
    """The mass's speed returns over a period: mean F = F0 - (force on the mass)."""
    v = lambda rec: rec.signals["omega2"] * W   # noqa: E731 (the mass follows the rim on average)
    cases = [(E("mass_force_constant", {"force_N": 7.0}), -7.0),
             (E("mass_rail_friction", {"force_N": 9.0, "smoothing_speed_m_s": 0.05}), 9.0),
             (E("mass_drag", {"coefficient_Ns2_per_m2": 0.02}), None)]
    for eff, add in cases:
        rec = make_recording(spec([eff]))
        f = np.mean(whole_periods(rec.internal["rim_force_N"]))
        if add is None:
            add = np.mean(whole_periods(0.02 * v(rec) ** 2))
        assert f == pytest.approx(C.WORKING_RESISTANCE_N + add, rel=2e-3), eff.form
        assert np.mean(whole_periods(rec.internal["clutch_torque_Nm"])) == pytest.approx(W * f, rel=2e-3)
        assert rec.truth.effects[0].equivalent["force_N"] == pytest.approx(-add, rel=0.02)


def _contact_samples(rec, side=-1):
    m = rec.internal["mode"]
    idx = np.flatnonzero(m == side)
    d = rec.internal["jaw_angle_difference"]
    beta = rec.truth.true_width_m / W
    pen = (d[idx] - beta) if side == 1 else (-d[idx] - beta)
    rate = rec.signals["omega1"][idx] - rec.signals["omega2"][idx]
    rate = rate if side == 1 else -rate
    return idx, pen, rate, np.abs(rec.internal["clutch_torque_Nm"][idx])


def test_contact_laws_are_the_stated_laws_and_a_softer_contact_is_compressed_deeper():
    kh = F.ClutchContactHertz.stiffness_for(-0.3, 1.5)
    laws = [(E("clutch_contact_hertz", {"stiffness": kh, "exponent": 1.5}), lambda p, r: kh * p ** 1.5 + 20 * r),
            (E("clutch_damping_hunt_crossley", {"lambda_Nms_per_rad2": 900.0}),
             lambda p, r: 3000 * p + (20 + 900 * p) * r),
            (E("clutch_contact_progressive", {"p0_rad": 0.03}), lambda p, r: 3000 * p * (1 + (p / 0.03) ** 2) + 20 * r),
            (E("clutch_contact_preload", {"preload_Nm": 8.0, "build_up_rad": 2e-4}),
             lambda p, r: 8.0 * (1 - np.exp(-p / 2e-4)) + 3000 * p + 20 * r),
            (E("clutch_contact_asymmetric", {"drive_relative_change": 0.2, "far_relative_change": -0.4}),
             lambda p, r: 1800 * p + 20 * r)]
    base = nominal_drive()
    peak0 = base.internal["clutch_torque_Nm"].min()                   # far-side impacts: negative torque
    for eff, law in laws:
        rec = make_recording(spec([eff]))
        idx, pen, rate, tc = _contact_samples(rec, -1)
        assert idx.size > 1000
        np.testing.assert_allclose(tc, law(pen, rate), rtol=1e-6, atol=1e-6 * tc.max(), err_msg=eff.form)
    asym = make_recording(spec([laws[4][0]]))
    idx, pen, rate, tc = _contact_samples(asym, 1)
    np.testing.assert_allclose(tc, 3600 * pen + 20 * rate, rtol=1e-6, atol=1e-6 * tc.max())  # drive side: +20 %
    # the far side 40 % softer: each far-side impact compresses it deeper (the same impact energy on a softer
    # spring); the impact's peak torque is the damper's jump at contact and stays
    assert _contact_samples(asym, -1)[1].max() > 1.08 * _contact_samples(base, -1)[1].max()   # 1.13 measured
    assert asym.internal["clutch_torque_Nm"].min() == pytest.approx(peak0, rel=0.1)


def test_more_contact_damping_stops_an_impact_at_a_smaller_penetration():
    """Hunt-Crossley damping and a drifted damping value: the far-side impact's relative motion is stopped
    sooner, so its deepest penetration falls (the energy dissipated per impact stays: an impact this damped
    dissipates all the relative motion's kinetic energy whatever the law, measured below)."""
    def deepest_and_dissipated(rec):
        idx, pen, rate, tc = _contact_samples(rec, -1)
        return pen.max(), np.sum((tc - 3000.0 * pen) * rate) * C.SAMPLE_PERIOD_S
    p0, e0 = deepest_and_dissipated(nominal_drive())
    for eff in (E("clutch_damping_hunt_crossley", {"lambda_Nms_per_rad2": 1800.0}),
                E("clutch_damping_value", {"relative_change": 0.6})):
        p, e = deepest_and_dissipated(make_recording(spec([eff])))
        assert p < 0.9 * p0, eff.form
        assert e == pytest.approx(e0, rel=0.05), eff.form


def test_shaft_with_hub_twists_by_the_torque_over_its_stiffness():
    """The encoders' angle difference (motor - wheel) = jaw angle + shaft twist; over whole periods the mean
    twist is the mean transmitted torque / k_s (the shaft's damping term averages out)."""
    rec = make_recording(spec([E("shaft_with_hub", {"stiffness_Nm_per_rad": 9000.0, "damping_Nms_per_rad": 40.0,
                                                    "hub_inertia_kgm2": 0.03})]))
    twist = whole_periods(rec.signals["angle_difference"] - rec.internal["jaw_angle_difference"])
    assert np.mean(twist) == pytest.approx(np.mean(whole_periods(rec.internal["clutch_torque_Nm"])) / 9000.0, rel=1e-3)
    assert rec.truth.effects[0].equivalent == {"compliance_rad_per_Nm": pytest.approx(1 / 9000.0)}


def _line_hz(a, b, fmin=20.0, fmax=3000.0):
    f, s = spectrum(a - b)
    band = (f > fmin) & (f < fmax)
    return f[band][np.argmax(s[band])]


def test_ripples_put_lines_at_order_times_the_rotation_frequency():
    base = nominal_drive(2.0)
    f_rot = np.mean(base.signals["omega1"]) / (2 * math.pi)
    for eff, order in [(E("ripple_motor_harmonics", {"orders": [7], "amplitudes_pu": [0.3], "phases_rad": [0.0]}), 7),
                       (E("ripple_electromagnetic", {"relative_amplitude": 0.4, "order": 19, "phase_rad": 0.2}), 19),
                       (E("ripple_wheel_mesh", {"amplitude_Nm": 8.0, "order": 11, "phase_rad": 1.0}), 11)]:
        rec = make_recording(spec([eff], duration=2.0))
        assert _line_hz(rec.signals["a1"], base.signals["a1"]) == pytest.approx(order * f_rot, rel=0.01), eff.form
    cog = make_recording(spec([E("ripple_motor_harmonics", {"orders": [4, 9], "amplitudes_pu": [0.3, 0.3],
                                                             "phases_rad": [0.0, 1.0]})], duration=2.0))
    f, s = spectrum(cog.signals["a1"] - base.signals["a1"])
    peaks = sorted(f[np.argsort(s)[-200:]])
    for order in (4, 9):
        assert any(abs(p - order * f_rot) < 0.01 * order * f_rot for p in peaks)
    with pytest.raises(ValueError, match="not an integer"):
        make_recording(spec([E("ripple_motor_harmonics", {"orders": [4.45], "amplitudes_pu": [0.3],
                                                          "phases_rad": [0.0]})]))


def test_a_fixed_frequency_vibration_stays_put_when_the_speed_changes_and_a_ripple_moves():
    """Outside effect: a line at 107 Hz whatever the motor's speed; a motor-angle ripple follows the speed."""
    lines = {}
    for volt in (0.0, -0.12):
        extra = [E("supply_voltage", {"relative_change": volt})] if volt else []
        base = make_recording(spec(extra, kind="one", duration=2.0)) if volt else nominal_drive(2.0)
        vib = make_recording(spec(extra + [E("structural_vibration", {"amplitude_pu": 0.3, "frequency_hz": 107.0,
                                                                      "phase_rad": 0.0})], duration=2.0))
        rip = make_recording(spec(extra + [E("ripple_motor_harmonics", {"orders": [5], "amplitudes_pu": [0.3],
                                                                        "phases_rad": [0.0]})],
                                  kind="two" if volt else "one", duration=2.0))
        lines[volt] = (_line_hz(vib.signals["a1"], base.signals["a1"]), _line_hz(rip.signals["a1"], base.signals["a1"]),
                       np.mean(base.signals["omega1"]))
    (v0, r0, w0), (v1, r1, w1) = lines[0.0], lines[-0.12]
    assert v0 == pytest.approx(107.0, abs=0.6) and v1 == pytest.approx(107.0, abs=0.6)
    assert w1 < w0 - 0.5                                              # the sag slows the motor
    assert r1 / r0 == pytest.approx(w1 / w0, rel=2e-3)                # the ripple follows the speed


def test_second_torsional_mode_rings_at_its_frequency():
    k = 30_000.0
    rec = make_recording(spec([E("second_torsional_mode", {"rim_fraction": 0.4, "stiffness_Nm_per_rad": k,
                                                           "damping_Nms_per_rad": 0.3})], duration=2.0))
    base = nominal_drive(2.0)
    f = _line_hz(rec.signals["a1"], base.signals["a1"], fmin=60.0)
    assert f == pytest.approx(F.SecondTorsionalMode.mode_hz(0.4, k), rel=0.1)


def test_drifts_change_what_they_name():
    base = nominal_drive()
    # width: the far-side impact comes later; the truth's width is the drifted one (the measurand)
    wide = make_recording(spec([E("drift_width", {"change": 0.001})]))
    assert wide.truth.true_width_m == pytest.approx(0.0085) and wide.truth.width_is_measurand
    assert np.mean(far_impacts_ms(wide)) > np.mean(far_impacts_ms(base)) + 1.5
    # working resistance: mean clutch torque = r*F0*(1+e)
    wr = make_recording(spec([E("drift_working_resistance", {"relative_change": 0.4})]))
    assert np.mean(whole_periods(wr.internal["clutch_torque_Nm"])) == pytest.approx(W * 42.0, rel=2e-3)
    # mass: m*a2 = F - F0 at every sample
    m = make_recording(spec([E("drift_mass", {"relative_change": 0.3})]))
    np.testing.assert_allclose(13.0 * m.signals["a2"], m.internal["rim_force_N"] - 30.0, atol=1e-9)
    # wheel inertia: in the gap (no clutch torque) J2*dOmega2/dt = -r*F
    j = make_recording(spec([E("drift_wheel_inertia", {"relative_change": 0.35})]))
    gap = np.flatnonzero(j.internal["mode"] == 0)
    gap = gap[(gap > 2) & (gap < j.n_samples - 3)]
    gap = gap[np.all(j.internal["mode"][gap[:, None] + np.arange(-2, 3)] == 0, axis=1)]
    dw = (j.signals["omega2"][gap + 1] - j.signals["omega2"][gap - 1]) / (2 * C.SAMPLE_PERIOD_S)
    np.testing.assert_allclose(-W * j.internal["rim_force_N"][gap] / dw, 0.2 * 1.35, rtol=1e-4)
    # pulse amplitude: a smaller pulse pulls the motor down less
    p = make_recording(spec([E("drift_pulse_amplitude", {"relative_change": -0.15})]))
    assert p.signals["omega1"].min() > base.signals["omega1"].min() + 0.3
    # spring, absorber: values in the parameter vector, and the mass's motion changes
    from foreign_drives.kernel import P_C, P_K, P_N1
    s = make_recording(spec([E("drift_spring", {"relative_change": 0.5})]))
    assert s.internal["parameters"][P_K] == pytest.approx(150.0)
    a = make_recording(spec([E("drift_eta_k", {"relative_change": 0.6})]))
    assert a.internal["parameters"][P_C] == pytest.approx(C.absorber_coefficient(0.04, 0.89))
    n = make_recording(spec([E("drift_n1", {"change": 0.05})]))
    assert n.internal["parameters"][P_N1] == pytest.approx(0.94)
    assert n.truth.true_n1 == pytest.approx(0.94) and a.truth.true_eta_k == pytest.approx(0.04)
    for rec in (s, a, n):
        assert np.max(np.abs(rec.signals["a2"] - base.signals["a2"])) > 0.01


def test_outside_motor_changes_move_the_slip():
    base = nominal_drive()
    rr = make_recording(spec([E("motor_rotor_resistance", {"relative_change": 0.6})]))
    assert np.mean(rr.signals["omega1"]) < np.mean(base.signals["omega1"]) - 1.0     # slip ~ r_r at a given torque


# ------------------------------------------------------------------------------------------- sensor chain
def test_gain_and_bias_are_exact_and_drifting_ones_average_to_their_equivalent():
    effects = [E("gain_constant", {"signal": "a2", "relative_change": 0.15}),
               E("bias_constant", {"signal": "a1", "bias_m_s2": -1.7})]
    rec = make_recording(spec(effects, kind="two", noise=True))
    np.testing.assert_allclose(rec.signals["a2"], 1.15 * rec.internal["a2_physical"], rtol=1e-14)
    np.testing.assert_allclose(rec.signals["a1"], rec.internal["a1_physical"] - 1.7, atol=1e-12)
    assert rec.truth.effects[0].equivalent == {"a2_relative_change": 0.15}
    assert rec.truth.effects[1].equivalent == {"a1_m_s2": -1.7}
    drift = make_recording(spec([E("bias_drifting", {"signal": "a2", "start_m_s2": 1.0, "end_m_s2": 3.0})]))
    assert np.mean(drift.signals["a2"] - drift.internal["a2_physical"]) == pytest.approx(2.0, abs=1e-3)
    assert drift.truth.effects[0].equivalent == {"a2_m_s2": 2.0}
    g = make_recording(spec([E("gain_drifting", {"signal": "a1", "start_relative_change": -0.1,
                                                 "end_relative_change": -0.14})]))
    ratio = g.signals["a1"][[0, -1]] / g.internal["a1_physical"][[0, -1]]
    np.testing.assert_allclose(ratio, [0.9, 0.86], rtol=1e-4)


@pytest.mark.parametrize("eff,response", [
    (E("lowpass_butterworth", {"signal": "a1", "order": 4, "corner_hz": 800.0}),
     lambda f: 1 / np.sqrt(1 + (f / 800.0) ** 8)),
    (E("lowpass_bessel", {"signal": "a1", "order": 2, "corner_hz": 600.0}), None),
    (E("lowpass_moving_average", {"signal": "a1", "taps": 25}),
     lambda f: np.abs(np.sinc(25 * f / C.SAMPLE_RATE_HZ) / np.sinc(f / C.SAMPLE_RATE_HZ))),
    (E("lowpass_fir", {"signal": "a1", "taps": 101, "cutoff_hz": 900.0}), None)])
def test_lowpass_forms_remove_the_power_above_their_corner(eff, response):
    """Measured response |Y/X| (cross spectrum of the sensed and the physical a1 of one noisy run): 1 well below
    the corner, -3 dB (-6 dB for the FIR's cutoff) at it, the analog prototype's attenuation above it."""
    from scipy.signal import csd, welch
    rec = make_recording(spec([eff], noise=True, duration=2.0))
    x, y = rec.internal["a1_physical"], rec.signals["a1"]
    f, pxy = csd(x, y, fs=C.SAMPLE_RATE_HZ, nperseg=8192)
    _, pxx = welch(x, fs=C.SAMPLE_RATE_HZ, nperseg=8192)
    h = np.abs(pxy / pxx)
    at = lambda fr: float(np.interp(fr, f, h))   # noqa: E731
    tau = rec.truth.effects[0].equivalent["a1_time_constant_s"]
    corner = 1 / (2 * math.pi * tau)
    assert at(0.1 * corner) == pytest.approx(1.0, abs=0.02)
    target = 0.5 if eff.form == "lowpass_fir" else 1 / math.sqrt(2)
    if eff.form != "lowpass_fir":
        assert at(corner) == pytest.approx(target, abs=0.03)
    else:
        assert at(900.0) == pytest.approx(target, abs=0.04)
    if response is not None:
        for fr in (1.5 * corner, 2.5 * corner):
            assert at(fr) == pytest.approx(float(response(fr)), abs=0.02)
    assert at(4 * corner) < 0.25


def test_sensor_nuisance_adds_white_noise_and_quantises():
    lsb = 0.05
    rec = make_recording(spec(noise=True, sensor=SensorNuisance(a1_noise_rms_m_s2=0.2, a2_lsb_m_s2=lsb,
                                                                 encoder_counts_per_rev=4096, angle_offset_rad=0.5)))
    assert np.std(rec.signals["a1"] - rec.internal["a1_physical"]) == pytest.approx(0.2, rel=0.02)
    q = rec.signals["a2"] / lsb
    np.testing.assert_allclose(q, np.round(q), atol=1e-9)
    assert np.max(np.abs(rec.signals["a2"] - rec.internal["a2_physical"])) <= lsb / 2 + 1e-12
    count = 2 * math.pi / 4096
    d = rec.signals["angle_difference"] - 0.5
    np.testing.assert_allclose(d / count, np.round(d / count), atol=1e-6)
    assert np.max(np.abs(d - rec.internal["angle_difference_exact"])) < count * (1 + 1e-9)
    assert rec.truth.families == () and rec.truth.effects == ()        # nuisance, not an effect


# ------------------------------------------------------------------------------------------- specs, truth
def test_spec_checks_refuse_bad_input_with_one_line():
    bad = [(dict(kind="one", effects=()), "kind 'one'"),
           (dict(kind="clean", effects=(E("drift_mass", {"relative_change": 0.3}),)), "kind 'clean'"),
           (dict(effects=(E("wheel_frition_tanh", {}),)), "nearest: 'wheel_friction_tanh'"),
           (dict(effects=(E("drift_mass", {"relative_change": 20.0}),)), "outside"),
           (dict(effects=(E("drift_mass", {"relative_chnage": 0.2}),)), "unknown parameter"),
           (dict(duration_s=1.00001), "multiple of"),
           (dict(namespace="bad name"), "namespace"),
           (dict(pulse_first_s=0.3), "pulse_first_s")]
    for kw, msg in bad:
        kw.setdefault("kind", "one")
        s = RecordingSpec("x", kw.pop("kind"), 0.005, 0.025, 0.89, **kw)
        with pytest.raises(ValueError, match=msg.replace("(", r"\(").replace(")", r"\)")) as ei:
            s.check()
        assert "\n" not in str(ei.value)


def test_truth_equivalents():
    kh = F.ClutchContactHertz.stiffness_for(-0.3, 1.5)
    t = spec([E("clutch_contact_hertz", {"stiffness": kh, "exponent": 1.5})]).truth()
    assert t.effects[0].equivalent["relative_change"] == pytest.approx(-0.3, abs=1e-9)
    t = spec([E("lowpass_butterworth", {"signal": "a2", "order": 2, "corner_hz": 600.0})]).truth()
    assert t.effects[0].equivalent == {"a2_time_constant_s": pytest.approx(1 / (2 * math.pi * 600.0))}
    t = spec([E("structural_vibration", {"amplitude_pu": 0.3, "frequency_hz": 107.0, "phase_rad": 0.0})]).truth()
    assert t.families == () and t.outside == ("structural_vibration",) and t.effects[0].family is None
    t = spec([E("drift_width", {"change": -0.001})], width=0.005).truth()
    assert t.true_width_m == pytest.approx(0.004) and t.nominal["width_m"] == 0.005
    t = spec([E("wheel_friction_stribeck_power", {"coulomb_torque_Nm": 0.6, "excess_torque_Nm": 1.4,
                                                  "stribeck_speed_rad_s": 120.0, "exponent": 1.0})]).truth()
    assert t.effects[0].also_accepted["wheel_coulomb_friction"]["torque_Nm"] == pytest.approx(
        0.6 + 1.4 * math.exp(-F.OPERATING_POINT["speed_rad_s"] / 120.0))


def test_operating_point_is_the_nominal_drives():
    rec = nominal_drive()
    assert np.mean(whole_periods(rec.signals["omega1"])) == pytest.approx(F.OPERATING_POINT["speed_rad_s"], rel=5e-4)
    assert np.mean(whole_periods(rec.internal["te_pu"])) == pytest.approx(F.OPERATING_POINT["mean_te_pu"], rel=1e-3)
    deepest = _contact_samples(rec, -1)[1].max()                     # the far-side impacts' elastic torque spans
    t_ref = F.OPERATING_POINT["impact_reference_torque_Nm"]           # 0 .. 3000*deepest: the reference is half of it
    assert 1.6 * t_ref < C.CONTACT_STIFFNESS_NM_PER_RAD * deepest < 2.4 * t_ref


def test_suites_are_well_formed():
    from foreign_drives.suites import BENCH, TEST, WIDTH_LOOP
    assert all(100 <= s.seed <= 199 for s in TEST)
    assert all(s.seed >= 5000 for s in BENCH + WIDTH_LOOP)
    assert len(BENCH) >= 30 and all(s.duration_s == 4.0 for s in BENCH + WIDTH_LOOP)
    kinds = [s.kind for s in BENCH]
    assert kinds.count("clean") >= 10 and 3 <= kinds.count("two") <= 4 and kinds.count("outside") >= 3
    assert {f for s in BENCH if s.kind == "one" for f in s.truth().families} == set(F.CATALOGUE_FAMILIES)
    clean = [s for s in BENCH if s.kind == "clean"]
    assert min(s.width_m for s in clean) == 0.0025 and max(s.width_m for s in clean) == 0.01
    assert min(s.eta_k for s in clean) == 0.0125 and max(s.eta_k for s in clean) == 0.05
    assert min(s.n1 for s in clean) == 0.89 and max(s.n1 for s in clean) == 0.97
    assert len({s.chunk_samples for s in BENCH}) >= 5 and len({s.namespace for s in BENCH}) >= 5
    wl = {f for s in WIDTH_LOOP for f in s.truth().families}
    assert {"backlash_width_drift", "clutch_contact_damping", "accelerometer_gain"} <= wl
    assert any("friction" in f for f in wl) and 4 <= len(WIDTH_LOOP) <= 6
    labels = [s.label for s in BENCH + WIDTH_LOOP + TEST]
    assert len(labels) == len(set(labels))
    used_by_tests = {json.dumps(e.parameters, sort_keys=True) for s in TEST for e in s.effects}
    assert not used_by_tests & {json.dumps(e.parameters, sort_keys=True) for s in BENCH for e in s.effects}


def test_test_suite_recordings_have_their_entries():
    from foreign_drives.suites import TEST
    for s in TEST:
        rec = make_recording(s)
        kinds = [k for _, k in rec.true_entries()]
        assert kinds.count("onset") >= 4, s.label
        assert np.min(np.diff([k for k, _ in rec.true_entries()])) > C.WINDOW_SAMPLES


# ------------------------------------------------------------------------------------------- files
@pytest.fixture(scope="module")
def test_recording():
    from foreign_drives.suites import TEST
    s = dataclasses.replace(TEST[3], namespace="line9/drive4", chunk_samples=777, drive_name="drive4")
    return s, make_recording(s)


def test_bag_reads_back_through_the_projects_reader_and_mcap(tmp_path, test_recording):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory
    from backlash_monitor.bag.schema import full_definition
    from backlash_monitor.workbench.measurement import load_measurement
    from foreign_drives.files import write_bag
    s, rec = test_recording
    path = write_bag(s, tmp_path / "rec.mcap", recording=rec)
    m = load_measurement(path)                                    # namespace found by the topics' tail
    assert m.sample_period_s == C.SAMPLE_PERIOD_S
    for name in C.SIGNAL_UNITS:
        assert np.array_equal(m.signals[name], rec.signals[name]), name
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        summ = reader.get_summary()
        (sch,) = summ.schemas.values()
        assert sch.name == "backlash_monitor_msgs/msg/SignalChunk" and sch.encoding == "ros2msg"
        assert sch.data.decode() == full_definition("backlash_monitor_msgs/msg/SignalChunk")
        got = {n: [] for n in C.SIGNAL_UNITS}
        last_log = {}
        for schema, channel, message, ros in reader.iter_decoded_messages():
            name = channel.topic.rsplit("/", 1)[1]
            assert channel.topic == f"/line9/drive4/plant/{name}" and channel.message_encoding == "cdr"
            assert ros.signal_name == name and ros.unit == C.SIGNAL_UNITS[name]
            assert ros.sample_period_s == C.SAMPLE_PERIOD_S and ros.header.frame_id == "drive4"
            assert ros.first_sample_index == sum(len(x) for x in got[name])
            assert len(ros.samples) <= 777
            stamp = ros.header.stamp.sec * 10 ** 9 + ros.header.stamp.nanosec
            assert stamp == s.start_time_ns + round(ros.first_sample_index * C.SAMPLE_PERIOD_S * 1e9)
            assert message.log_time > stamp and message.log_time > last_log.get(name, 0)
            last_log[name] = message.log_time
            got[name].append(np.asarray(ros.samples))
    for name in C.SIGNAL_UNITS:
        assert np.array_equal(np.concatenate(got[name]), rec.signals[name])


def test_npz_and_csv_read_back_through_the_workbench(tmp_path, test_recording):
    from backlash_monitor.workbench.measurement import load_measurement
    from foreign_drives.files import write_csv, write_npz
    s, rec = test_recording
    for writer, name in ((write_npz, "r.npz"), (write_csv, "r.csv")):
        m = load_measurement(writer(s, tmp_path / name, recording=rec))
        assert m.sample_period_s == pytest.approx(C.SAMPLE_PERIOD_S, rel=1e-9)
        for k in C.SIGNAL_UNITS:
            assert np.array_equal(m.signals[k], rec.signals[k]), (name, k)
    with pytest.raises(FileExistsError):
        write_npz(s, tmp_path / "r.npz", recording=rec)


def test_manifest_round_trip(tmp_path):
    from foreign_drives.suites import BENCH, TEST
    specs = TEST + BENCH[:12]
    write_manifest(tmp_path / "m.json", specs, {s.label: f"{s.label}.mcap" for s in specs})
    back = read_manifest(tmp_path / "m.json")
    assert [b[0] for b in back] == specs
    for (s2, truth, file), s in zip(back, specs):
        assert truth == json.loads(json.dumps(s.truth().to_json())) and file == f"{s.label}.mcap"


# ------------------------------------------------------------------------------------------- CLI
def _cli(*args, cwd=REPO):
    return subprocess.run([sys.executable, "-m", "foreign_drives", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300)


@pytest.mark.process
def test_cli_help_explains_every_option():
    r = _cli("--help")
    assert r.returncode == 0 and "write" in r.stdout and "list" in r.stdout and "forms" in r.stdout
    r = _cli("write", "--help")
    for opt in ("--suite", "--out", "--only", "--format", "--overwrite", "--quiet"):
        assert opt in r.stdout


@pytest.mark.process
def test_cli_bad_input_is_one_line_and_exit_2(tmp_path):
    for args in (("write", "--suite", "nope", "--out", str(tmp_path)),
                 ("write", "--suite", "test", "--out", str(tmp_path), "--only", "no_such_label"),
                 ("write", "--out", str(tmp_path)),
                 ("bogus",)):
        r = _cli(*args)
        assert r.returncode == 2, args
        assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.stderr, (args, r.stderr)


@pytest.mark.process
def test_cli_writes_a_bag_and_its_manifest_and_refuses_to_overwrite(tmp_path):
    out = tmp_path / "suite"
    r = _cli("write", "--suite", "test", "--out", str(out), "--only", "t_clean_w5")
    assert r.returncode == 0, r.stderr
    assert "1/1" in r.stderr                                           # the progress bar
    assert sorted(p.name for p in out.iterdir()) == ["manifest.json", "t_clean_w5.mcap"]
    man = json.loads((out / "manifest.json").read_text())
    (rec,) = man["recordings"]
    assert rec["spec"]["label"] == "t_clean_w5" and rec["truth"]["true_width_m"] == 0.005
    assert len(rec["made"]["onset_entries"]) >= 4
    r = _cli("write", "--suite", "test", "--out", str(out), "--only", "t_clean_w5")
    assert r.returncode == 2 and "exists" in r.stderr
