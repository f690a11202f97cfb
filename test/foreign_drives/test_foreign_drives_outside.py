"""The mechanisms outside the catalogue (issue 31 part 4: foreign_drives.outside, .outside_dev, .outside_sealed):
each one's law checked on the drive's own balances (every term recovered exactly from the recorded states), its
sign/energy/limit, zero amplitude = the clean drive, the recorded truth (balance, states, law, plug-in), and the two
suites (well formed, writing valid bags).

This file names the sealed mechanisms only through the registry (FORMS, the suite); it states no sealed law."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import noise as N
from foreign_drives import outside as O
from foreign_drives.drive import make_recording
from foreign_drives.spec import RecordingSpec
from foreign_balance_terms import mass_term_N, motor_term_Nm, wheel_term_Nm   # test/: the balances solved for the outside term
from foreign_outside_recordings import Recordings                              # test/: each file's recordings, made once

W = C.WHEEL_RADIUS_M
T_B = C.BASE_TORQUE_NM

OUTSIDE = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
DEV = {n: f for n, f in OUTSIDE.items() if f.half == "dev"}
SEALED = {n: f for n, f in OUTSIDE.items() if f.half == "sealed"}


def spec(effects=(), width=0.0075, eta=0.025, n1=0.89, seed=151, duration=1.0, noise=False, **kw):
    kind = "outside" if any(F.get(e.form).family is None for e in effects) else ("clean" if not effects else "one")
    return RecordingSpec("t", kind, width, eta, n1, effects=tuple(effects), seed=seed, duration_s=duration,
                         noise=noise, **kw)


RECORDINGS = Recordings(lambda effects, duration_s: spec(effects, duration=duration_s), duration_s=1.0)
rec_of, clean = RECORDINGS.rec_of, RECORDINGS.clean


def pulse_per_sample(rec):
    """The held pulse load [p.u.] at every sample (noise off: the whole held load)."""
    n_seg = rec.n_samples // N.SEGMENT_SAMPLES
    return np.repeat(N.pulse_train(0, n_seg, rec.internal["pulse_amplitude_pu"], rec.spec.pulse_first_s),
                     N.SEGMENT_SAMPLES)


# --------------------------------------------------------------------------------------------- the registry
def test_outside_mechanisms_are_twelve_or_more_split_in_halves_with_their_truth_vocabulary():
    assert len(OUTSIDE) >= 12 and len(DEV) >= 6 and len(SEALED) >= 6
    assert abs(len(DEV) - len(SEALED)) <= 1
    for name, f in OUTSIDE.items():
        assert f.family is None and name not in F.CATALOGUE_FAMILIES
        assert f.balance in O.BALANCES, name
        assert f.depends_on and set(f.depends_on) <= set(O.STATES), name
        assert (f.stage == "sensor") == (f.balance == "sensor"), name
        for p in f.parameters:
            lo, hi = p.bounds
            assert math.isfinite(lo) and math.isfinite(hi) and lo < hi, (name, p.name)
    from foreign_drives import outside_dev, outside_sealed
    assert {c.name for c in outside_dev.FORM_CLASSES} == set(DEV)
    assert {c.name for c in outside_sealed.FORM_CLASSES} == set(SEALED)
    assert {f.balance for f in DEV.values()} >= {"motor_load_moment", "wheel_torque", "clutch_torque", "mass_force",
                                                  "sensor"}
    assert {f.balance for f in SEALED.values()} >= {"motor_load_moment", "wheel_torque", "clutch_torque",
                                                     "mass_force", "sensor"}


def _zero(form):
    """The form's parameters at zero amplitude (every other parameter at a value inside its bounds)."""
    p = {}
    for q in form.parameters:
        lo, hi = q.bounds
        if q.name.startswith(("amplitude", "torque", "force", "damping", "coefficient", "gain", "relative", "stiffness",
                              "deadband", "corner")):
            p[q.name] = 0.0
        else:
            p[q.name] = float(min(max(0.5 * (lo + hi) if math.isfinite(hi - lo) else 1.0, lo), hi))
    return p


# the first three sets' forms here; every later set's forms have their own test of it at their suite's parameters
# (test_foreign_drives_outside4.py, outside5.py, ...: whole numbers of scans and stations, neutral values that are not 0,
# strengths not named as here)
@pytest.mark.parametrize("name", sorted(n for n, f in OUTSIDE.items()
                                        if f.half in ("dev", "sealed", "dev2", "sealed2", "dev3", "sealed3")))
def test_zero_amplitude_is_the_clean_drive(name):
    rec = rec_of(name, **_zero(OUTSIDE[name]))
    base = clean()
    for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
        assert np.array_equal(rec.signals[k], base.signals[k]), (name, k)


# --------------------------------------------------------------------------------------------- dev physics
def test_wheel_cam_is_its_law_on_the_wheel_and_conservative():
    p = {"amplitude_Nm": 4.0, "lift_ratio": 0.6, "phase_rad": 0.4}
    rec = rec_of("wheel_cam_follower", **p)
    law = DEV["wheel_cam_follower"].torque(rec.internal["alpha2"], p)
    assert np.max(np.abs(wheel_term_Nm(rec) - law)) < 1e-6 * 4.0
    assert np.max(np.abs(motor_term_Nm(rec))) < 1e-6 and np.max(np.abs(mass_term_N(rec))) < 1e-6
    th = np.linspace(0.0, 2 * np.pi, 100_001)
    work = np.trapezoid(DEV["wheel_cam_follower"].torque(th, p), th)      # a potential force: no work per turn
    assert abs(work) < 1e-9
    assert np.max(np.abs(rec.signals["omega2"] - clean().signals["omega2"])) > 0.05    # rad/s: it matters


def test_crank_pump_loads_the_motor_on_its_pressure_stroke_only():
    p = {"amplitude_pu": 0.3, "phase_rad": -1.0}
    rec = rec_of("motor_crank_pump", **p)
    law = T_B * DEV["motor_crank_pump"].load_pu(rec.internal["alpha1"], p)
    tx = motor_term_Nm(rec)
    assert np.max(np.abs(tx - law)) < 1e-6 * T_B
    assert tx.min() > -1e-6 and tx.max() == pytest.approx(0.3 * T_B, rel=1e-3)   # never drives the motor
    # a mean load A/pi: the motor delivers it on average over whole revolutions
    assert np.mean(law) == pytest.approx(0.3 * T_B / np.pi, rel=0.03)


def test_creeping_resistance_grows_with_time_from_sample_0():
    p = {"force_N": 20.0, "creep_time_s": 0.5}
    rec = rec_of("mass_creeping_resistance", **p)
    t = np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S
    fx = mass_term_N(rec)
    assert np.max(np.abs(fx - DEV["mass_creeping_resistance"].force(t, p))) < 1e-6 * 20.0
    assert fx[0] == pytest.approx(0.0, abs=1e-9) and fx[-1] == pytest.approx(-20.0, rel=1e-9)
    # nothing before sample 0: the recording starts as the clean drive's
    assert rec.signals["a2"][0] == clean().signals["a2"][0] and rec.signals["a1"][0] == clean().signals["a1"][0]


def test_process_brake_acts_with_the_pulse_against_the_rotation():
    p = {"torque_Nm": 3.0, "build_up_s": 0.005}
    rec = rec_of("wheel_process_brake", **p)
    tx = wheel_term_Nm(rec)
    pulse = pulse_per_sample(rec) > 0
    assert np.max(np.abs(tx[~pulse])) < 1e-6
    # within a pulse: -T*(1 - exp(-age/tau)), the age from the pulse's first segment
    starts = np.flatnonzero(pulse[1:] & ~pulse[:-1]) + 1
    age = np.full(rec.n_samples, -1.0)
    for s in starts:
        end = s + np.argmin(pulse[s:]) if not pulse[s:].all() else rec.n_samples
        age[s:end] = np.arange(end - s) * C.SAMPLE_PERIOD_S
    on = age >= 0
    assert np.max(np.abs(tx[on] + 3.0 * (1 - np.exp(-age[on] / 0.005)))) < 1e-6 * 3.0
    assert np.all(tx * rec.signals["omega2"] <= 1e-9)          # a brake: never drives the wheel
    assert tx.min() < -2.9


def test_gap_drag_couples_the_shafts_inside_the_gap_and_dissipates():
    p = {"damping_Nms_per_rad": 0.6}
    rec = rec_of("clutch_gap_drag", **p)
    gap = rec.internal["mode"] == 0
    rel = rec.signals["omega1"] - rec.signals["omega2"]
    tc = rec.internal["clutch_torque_Nm"]
    assert gap.sum() > 1000
    assert np.max(np.abs(tc[gap] - 0.6 * rel[gap])) < 1e-9
    assert np.all(tc[gap] * rel[gap] >= 0.0)                   # its power: >= 0 (it dissipates)
    assert np.max(np.abs(tc[gap])) > 1.0                        # N*m: it matters in the gap
    assert np.max(np.abs(clean().internal["clutch_torque_Nm"][clean().internal["mode"] == 0])) == 0.0


def test_carriage_coupling_loads_the_motor_by_the_speed_difference():
    p = {"coefficient_Nms_per_m": 3.0}
    rec = rec_of("motor_carriage_coupling", **p)
    law = 3.0 * (W * rec.signals["omega1"] - rec.internal["mass_speed"])
    assert np.max(np.abs(motor_term_Nm(rec) - law)) < 1e-6 * 3.0
    assert abs(np.mean(law)) < 0.2 * np.std(law)                # about zero on average, not a constant load


def test_rotating_gravity_is_on_a1_only_and_locked_to_the_motor_angle():
    p = {"amplitude_m_s2": 9.81, "phase_rad": 0.9}
    rec = rec_of("a1_rotating_gravity", **p)
    i = rec.internal
    assert np.max(np.abs(rec.signals["a1"] - i["a1_physical"] - 9.81 * np.sin(i["alpha1"] + 0.9))) < 1e-9
    assert np.array_equal(rec.signals["a2"], clean().signals["a2"])
    assert np.array_equal(i["a1_physical"], clean().internal["a1_physical"])    # the drive itself unchanged


# --------------------------------------------------------------------------------------------- sealed physics
@pytest.mark.parametrize("name", sorted(SEALED))
def test_sealed_mechanism_acts_in_its_recorded_balance_only(name):
    """Every sealed mechanism, at its suite's strength, changes the balance its truth names and no other."""
    from foreign_drives.suites import suite
    (eff,) = [e for s in suite("outside_sealed") for e in s.effects if e.form == name][:1]
    rec = make_recording(spec([eff]))
    off = {"motor_load_moment": np.max(np.abs(motor_term_Nm(rec))), "wheel_torque": np.max(np.abs(wheel_term_Nm(rec))),
           "mass_force": np.max(np.abs(mass_term_N(rec)))}
    f = SEALED[name]
    if f.balance == "sensor":
        assert max(off.values()) < 1e-6
        assert any(np.max(np.abs(rec.signals[k] - rec.internal[f"{k}_physical"])) > 0.05 for k in ("a1", "a2"))
        assert np.array_equal(rec.internal["a1_physical"], clean().internal["a1_physical"])
        return
    if f.balance == "clutch_torque":
        assert max(off.values()) < 1e-6
        dtc = np.abs(rec.internal["clutch_torque_Nm"] - clean().internal["clutch_torque_Nm"])
        assert dtc.max() > 0.5
        return
    for bal, v in off.items():
        if bal == f.balance:
            assert v > 0.5, (name, bal, v)             # N*m or N: a term that matters
        else:
            assert v < 1e-6, (name, bal, v)


# --------------------------------------------------------------------------------------------- truth
def test_truth_records_balance_states_law_and_the_plugin_of_the_angle_locked_ones():
    from foreign_drives.suites import suite
    dev = suite("outside_dev")
    angle_locked = {"wheel_angle": 0, "motor_angle": 0}
    for s in dev:
        for e in s.truth().effects:
            if e.family is not None:
                continue
            assert e.balance in O.BALANCES and set(e.depends_on) <= set(O.STATES) and e.law and e.half == "dev"
            if e.plugin and e.balance != "sensor" and set(e.depends_on) & set(angle_locked):
                angle_locked[next(iter(set(e.depends_on) & set(angle_locked)))] += 1
    assert angle_locked["wheel_angle"] >= 1 and angle_locked["motor_angle"] >= 1
    for s in suite("outside_sealed"):
        for e in s.truth().effects:
            if e.family is None:
                assert e.half == "sealed" and e.balance in O.BALANCES


def test_the_plugins_are_the_laws_in_the_projects_plugin_form(tmp_path):
    """Each plug-in text loads into the project's catalogue and its term is the generator's law."""
    from backlash_monitor.plant import builtin_catalogue
    cases = [("wheel_cam_follower", {"amplitude_Nm": 4.0, "lift_ratio": 0.6, "phase_rad": 0.4}, "wheel_torque_Nm",
              lambda x, p: DEV["wheel_cam_follower"].torque(x, p), "alpha2"),
             ("motor_crank_pump", {"amplitude_pu": 0.3, "phase_rad": -1.0}, "motor_load_moment_pu",
              lambda x, p: DEV["motor_crank_pump"].load_pu(x, p), "alpha1")]
    for name, p, balance, law, var in cases:
        path = tmp_path / f"{name}.py"
        path.write_text(DEV[name].plugin(p))
        cls = builtin_catalogue().with_files([str(path)]).get(name)
        assert cls.balance == balance
        for x in np.linspace(-7.0, 7.0, 29):
            assert float(cls.term(**{var: float(x)}, **p)) == pytest.approx(float(law(np.array(x), p)), abs=1e-9)
    path = tmp_path / "coupling.py"
    path.write_text(DEV["motor_carriage_coupling"].plugin({"coefficient_Nms_per_m": 3.0}))
    cls = builtin_catalogue().with_files([str(path)]).get("motor_carriage_coupling")
    got = cls.term(omega1=150.0, xdot=22.0, wheel_radius_m=W, base_torque_Nm=T_B, coefficient_Nms_per_m=3.0)
    assert got == pytest.approx(3.0 * (W * 150.0 - 22.0) / T_B)


# --------------------------------------------------------------------------------------------- suites
def test_outside_suites_are_well_formed():
    from foreign_drives.suites import BENCH, TEST, WIDTH_LOOP, suite
    dev, sealed = suite("outside_dev"), suite("outside_sealed")
    others = BENCH + WIDTH_LOOP + TEST
    for s_, half, names in ((dev, "dev", DEV), (sealed, "sealed", SEALED)):
        assert all(s.duration_s == 4.0 for s in s_)
        kinds = [s.kind for s in s_]
        assert 1 <= kinds.count("clean") <= 3
        used = {e.form for s in s_ for e in s.effects if F.get(e.form).family is None}
        assert used == set(names), half                       # every mechanism of the half, and only those
        assert {e.form for s in s_ for e in s.effects if F.get(e.form).family is not None} <= {"drift_width"}
        width_plus = [s for s in s_ if s.truth().width_is_measurand and s.truth().outside]
        assert len(width_plus) >= 2
        assert len({(s.width_m, s.eta_k, s.n1) for s in s_}) >= 8          # varied nominal conditions
    seeds = [s.seed for s in dev + sealed + others]
    labels = [s.label for s in dev + sealed + others]
    assert len(set(seeds) - {s.seed for s in others}) == len(dev) + len(sealed)
    assert len(labels) == len(set(labels))


@pytest.mark.slow
def test_outside_suites_write_valid_bags_with_their_truth(tmp_path):
    import subprocess
    import sys
    from backlash_monitor.workbench.measurement import load_measurement
    from foreign_drives.suites import suite
    from pathlib import Path
    repo = Path(__file__).resolve().parents[2]
    for name in ("outside_dev", "outside_sealed"):
        row = next(s for s in suite(name) if s.kind == "outside" and not s.truth().width_is_measurand)
        out = tmp_path / name
        r = subprocess.run([sys.executable, "-m", "foreign_drives", "write", "--suite", name, "--out", str(out),
                            "--only", row.label, "--quiet"], cwd=repo, capture_output=True, text=True, timeout=600)
        assert r.returncode == 0, r.stderr
        man = json.loads((out / "manifest.json").read_text())
        (m,) = man["recordings"]
        assert man["suite"] == name and m["spec"]["label"] == row.label
        (eff,) = [e for e in m["truth"]["effects"] if e["family"] is None]
        assert eff["balance"] in O.BALANCES and eff["depends_on"] and eff["law"]
        assert len(m["made"]["onset_entries"]) >= 12 and set(m["made"]["angles_at_sample0_rad"]) == {"alpha1",
                                                                                                    "alpha2"}
        meas = load_measurement(out / m["file"])
        rec = make_recording(row)
        for k in C.SIGNAL_UNITS:
            assert np.array_equal(meas.signals[k], rec.signals[k]), (name, k)


def test_every_sets_plugin_loads_and_is_neutral_at_its_defaults(tmp_path):
    """Each outside mechanism's plug-in text (every set's) loads into the project's catalogue as a user's file would
    (its defaults inside its bounds: the project refuses one outside), in its stated balance, and its term at the
    defaults adds nothing (a plug-in added to a model changes it only once fitted)."""
    import inspect

    from backlash_monitor.plant import builtin_catalogue
    with_plugin = []
    for form in F.FORMS.values():
        if not isinstance(form, O.OutsideForm) or type(form).plugin is O.OutsideForm.plugin:
            continue
        # the mid-range values (the text takes the law's exact constants from them where it has any)
        p = {q.name: (round if q.kind == "int" else float)((q.bounds[0] + q.bounds[1]) / 2) for q in form.parameters
             if q.kind in ("float", "int") and all(math.isfinite(b) for b in q.bounds)}
        with_plugin.append((form.name, form.plugin(p)))
    assert len(with_plugin) >= 12
    for name, text in with_plugin:
        path = tmp_path / f"{name}.py"
        path.write_text(text)
        cls = builtin_catalogue().with_files([str(path)]).get(name)
        assert cls.balance in text
        args = inspect.signature(cls.term).parameters
        defaults = {q.name: q.default for q in cls.parameters}
        values = {a: defaults.get(a, 1.3) for a in args}
        assert float(np.max(np.abs(cls.term(**values)))) == 0.0, name
