"""What the outside-mechanism test files (test/foreign_drives/test_foreign_drives_outside*.py, one per set) share: the
short noise-free recordings they check a set's laws on -- one outside form at given parameters, or the clean drive --
each made once per file (every file keeps a cache of its own, on its own drive spec), a suite's use of a mechanism
(its parameters at the suite's strength) and the outside bench module (bench/_workbench/outside.py) loaded from its
file."""
from __future__ import annotations

import dataclasses
import functools
import importlib.util
import json
from pathlib import Path

import numpy as np
from foreign_balance_terms import contact_law_Nm, mass_term_N, motor_term_Nm, wheel_term_Nm

from foreign_drives import constants as C
from foreign_drives import forms as F
from foreign_drives import noise as N
from foreign_drives import suites
from foreign_drives.drive import make_recording
from foreign_drives.spec import EffectSpec

OUTSIDE_BENCH = Path(__file__).resolve().parents[1] / "bench" / "_workbench" / "outside.py"


class Recordings:
    """The recordings of one test file's drive, each made once. ``make_spec(effects, duration_s)``: the file's
    RecordingSpec with those effects (the clean drive when there are none), ``duration_s`` long; ``duration_s``: the
    file's recording length [s] when a call names none."""

    def __init__(self, make_spec, duration_s: float):
        self.make_spec = make_spec
        self.duration_s = duration_s
        self._made = functools.lru_cache(maxsize=None)(self._make)       # this file's cache

    def _make(self, form, params_json: str, duration_s: float):
        effects = () if form is None else (EffectSpec(form, json.loads(params_json)),)
        return make_recording(self.make_spec(effects, duration_s))

    def rec_of(self, form: str, duration: float | None = None, **parameters):
        """The drive with the outside ``form`` at ``parameters`` (the form's own names and units)."""
        return self._made(form, json.dumps(parameters, sort_keys=True),
                          self.duration_s if duration is None else duration)

    def clean(self, duration: float | None = None):
        """The drive without any effect."""
        return self._made(None, "{}", self.duration_s if duration is None else duration)


def suite_effect(name: str, suite_names) -> EffectSpec:
    """The first use of mechanism ``name`` in the suites ``suite_names`` (its parameters at the suite's strength)."""
    for suite_name in suite_names:
        for spec in suites.suite(suite_name):
            for effect in spec.effects:
                if effect.form == name:
                    return effect
    raise AssertionError(f"{name} is in none of the suites {', '.join(suite_names)}")


class OutsideSet:
    """Set ``number`` of the outside mechanisms as its test file uses it: its halves' forms (``dev``, ``sealed``: name
    -> OutsideForm, from foreign_drives.forms), the file's drive -- noise-free, ``duration_s`` long, width 6.5 mm,
    eta_k 0.025, n1 0.9, at the file's own ``seed`` -- with one mechanism (``rec_of``) or none (``clean``), and a
    mechanism's use in the set's suites (``effect``; ``params``: its parameters at the suite's strength)."""

    def __init__(self, number: int, seed: int, duration_s: float = 0.6):
        from foreign_drives import outside as O
        from foreign_drives.spec import RecordingSpec
        outside = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
        self.number, self.seed, self.duration_s = number, seed, duration_s
        self.dev = {n: f for n, f in outside.items() if f.half == f"dev{number}"}
        self.sealed = {n: f for n, f in outside.items() if f.half == f"sealed{number}"}
        self.suites = (f"outside_dev{number}", f"outside_sealed{number}")
        self.recordings = Recordings(
            lambda effects, duration: RecordingSpec(f"t{number}", "outside" if effects else "clean", 0.0065, 0.025,
                                                    0.9, effects=tuple(effects), seed=seed, duration_s=duration,
                                                    noise=False), duration_s)
        self.rec_of, self.clean = self.recordings.rec_of, self.recordings.clean

    def effect(self, name: str) -> EffectSpec:
        """The set's suites' use of mechanism ``name``."""
        return suite_effect(name, self.suites)

    def params(self, name: str) -> dict:
        """Mechanism ``name``'s parameters at its suite's strength."""
        return self.effect(name).parameters


def outside_bench(module_name: str):
    """bench/_workbench/outside.py loaded from its file as the module ``module_name``."""
    spec = importlib.util.spec_from_file_location(module_name, OUTSIDE_BENCH)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def assert_set_registry(set_number: int) -> None:
    """Set N's registry and truth vocabulary: seven mechanisms in each half (outside_devN, outside_sealedN), each half
    over every balance; each one outside the catalogue and new to this set, in a balance and on states the outside
    bench has words for, a sensor stage exactly when its balance is a sensor, every parameter's bounds finite and
    ordered."""
    import math

    from foreign_drives import outside as O
    outside = {n: f for n, f in F.FORMS.items() if isinstance(f, O.OutsideForm)}
    dev = {n: f for n, f in outside.items() if f.half == f"dev{set_number}"}
    sealed = {n: f for n, f in outside.items() if f.half == f"sealed{set_number}"}
    dev_module = importlib.import_module(f"foreign_drives.outside_dev{set_number}")
    sealed_module = importlib.import_module(f"foreign_drives.outside_sealed{set_number}")
    assert {c.name for c in dev_module.FORM_CLASSES} == set(dev) and len(dev) == 7
    assert {c.name for c in sealed_module.FORM_CLASSES} == set(sealed) and len(sealed) == 7
    for half in (dev, sealed):
        assert {f.balance for f in half.values()} == set(O.BALANCES)
    bench = outside_bench(f"outside_bench_under_test{set_number}")
    known_states = {w for ws in bench.STATE_WORDS.values() for w in ws}
    known_balances = set(bench.BALANCE_WORDS.values())
    earlier = {n for n, f in outside.items() if f.half not in (f"dev{set_number}", f"sealed{set_number}")}
    for name, f in {**dev, **sealed}.items():
        assert f.family is None and name not in F.CATALOGUE_FAMILIES and name not in earlier
        assert f.balance in O.BALANCES and f.balance in known_balances, name
        assert f.depends_on and set(f.depends_on) <= set(O.STATES) and set(f.depends_on) <= known_states, name
        assert (f.stage == "sensor") == (f.balance == "sensor"), name
        for p in f.parameters:
            lo, hi = p.bounds
            assert math.isfinite(lo) and math.isfinite(hi) and lo < hi, (name, p.name)


def assert_acts_in_its_balance_only(name: str, balance: str, rec, base) -> None:
    """A sealed mechanism ``name`` (its recording ``rec``, the clean drive ``base`` of the same spec) acts in its
    recorded ``balance`` only: a sensor's leaves every balance and a1's physical signal untouched and moves a1 or a2
    by > 0.05 m/s^2; a clutch-torque one leaves the three balances and moves the contact torque by > 0.5 N*m; any other
    moves its own balance by > 0.5 (N*m or N) and no other by 1e-6."""
    off = {"motor_load_moment": np.max(np.abs(motor_term_Nm(rec))),
           "wheel_torque": np.max(np.abs(wheel_term_Nm(rec))), "mass_force": np.max(np.abs(mass_term_N(rec)))}
    if balance == "sensor":
        assert max(off.values()) < 1e-6
        assert any(np.max(np.abs(rec.signals[k] - base.signals[k])) > 0.05 for k in ("a1", "a2"))
        assert np.array_equal(rec.internal["a1_physical"], base.internal["a1_physical"])
        return
    if balance == "clutch_torque":
        assert max(off.values()) < 1e-6
        assert np.max(np.abs(rec.internal["clutch_torque_Nm"] - base.internal["clutch_torque_Nm"])) > 0.5
        return
    for bal, v in off.items():
        assert (v > 0.5) if bal == balance else (v < 1e-6), (name, bal, v)


def assert_acts_in_its_balance_only_on_its_suite_row(name: str, balance: str, suite_name: str, params: dict,
                                                     strength: str) -> None:
    """A mechanism that acts now and then (in bursts, at times), which a set's short test drive hardly starts: checked
    on its suite row's own drive without noise, at twice its suite strength (``params[strength]`` doubled), against
    the same drive without it (assert_acts_in_its_balance_only)."""
    p = dict(params)
    p[strength] *= 2.0
    row = next(s for s in suites.suite(suite_name) if any(e.form == name for e in s.effects))
    rec = make_recording(dataclasses.replace(row, noise=False, effects=(EffectSpec(name, p),)))
    base = make_recording(dataclasses.replace(row, noise=False, effects=(), kind="clean"))
    assert_acts_in_its_balance_only(name, balance, rec, base)


def assert_suite_writes_one_recording(out_dir: Path, suite_name: str) -> None:
    """``python -m foreign_drives write --suite SUITE --only LABEL --format npz`` on the suite's first outside row
    writes its recording (4 s at 50 kHz: 200,000 samples of a1, a2) and a manifest naming the suite, the label, the
    half and the onsets made."""
    from foreign_drives.cli import main
    label = next(s.label for s in suites.suite(suite_name) if s.kind == "outside")
    assert main(["write", "--suite", suite_name, "--out", str(out_dir), "--only", label, "--format", "npz",
                 "--quiet"]) == 0
    doc = json.loads((out_dir / "manifest.json").read_text())
    (r,) = doc["recordings"]
    assert doc["suite"] == suite_name and r["spec"]["label"] == label and (out_dir / r["file"]).is_file()
    assert r["made"]["onset_entries"] and r["truth"]["effects"][0]["half"] == suite_name.replace("outside_", "")
    with np.load(out_dir / r["file"]) as z:
        assert {"a1", "a2"} <= set(z.files) and z["a1"].size == 200_000


def assert_forms_withholds_sealed(out: str, sealed: dict, dev: dict) -> None:
    """``python -m foreign_drives forms``'s output ``out`` names each sealed form, its balance and no law (neither its
    description nor its parameters' longer descriptions), and shows each development form's description."""
    for name, f in sealed.items():
        assert f"{name}  family=None  outside (sealed)  balance={f.balance}" in out
        assert f.description not in out and all(p.description not in out for p in f.parameters if len(p.description) > 8)
    for f in dev.values():
        assert f.description in out


def assert_set_suites(set_number: int, dev: dict, sealed: dict, dev_first_seed: int, sealed_first_seed: int) -> None:
    """Set ``set_number``'s two suites (outside_devN, outside_sealedN): the development one listed, the sealed one only
    named; each one row per mechanism of its half (``dev``, ``sealed``: name -> form) plus one clean drive, 4 s, each
    row at its own conditions, every truth of its half in its form's balance with a law; seeds from the first seed up,
    none and no label shared with any other suite."""
    dev_name, sealed_name = f"outside_dev{set_number}", f"outside_sealed{set_number}"
    dev_rows, sealed_rows = suites.suite(dev_name), suites.suite(sealed_name)
    assert dev_name in suites.SUITES and sealed_name not in suites.SUITES
    assert sealed_name in suites.SUITE_NAMES
    others = [s for n in suites.SUITE_NAMES if n not in (dev_name, sealed_name) for s in suites.suite(n)]
    for rows, names, half in ((dev_rows, dev, f"dev{set_number}"), (sealed_rows, sealed, f"sealed{set_number}")):
        assert [s.kind for s in rows].count("clean") == 1 and len(rows) == len(names) + 1
        outside = [s for s in rows if s.kind == "outside"]
        assert sorted(e.form for s in outside for e in s.effects) == sorted(names)    # one mechanism per row
        assert all(s.duration_s == 4.0 for s in rows)
        assert len({(s.width_m, s.eta_k, s.n1) for s in rows}) == len(rows)        # each at its own conditions
        for s in outside:
            for e in s.truth().effects:
                assert e.half == half and e.balance == F.get(e.form).balance and e.law
    assert [s.seed for s in dev_rows] == list(range(dev_first_seed, dev_first_seed + len(dev_rows)))
    assert [s.seed for s in sealed_rows] == list(range(sealed_first_seed, sealed_first_seed + len(sealed_rows)))
    assert not {s.seed for s in dev_rows + sealed_rows} & {s.seed for s in others}
    labels = [s.label for s in dev_rows + sealed_rows + others]
    assert len(labels) == len(set(labels))


# the visibility criterion each outside set's strengths were set by (docs/foreign_drives.md): the rms difference of
# the recorded signal against the same spec without the mechanism over 4 s [m/s^2], five times NOISY_ADC16's sensor
# noise
CRITERION_M_S2 = {"a2": 0.05, "a1": 0.25}


def assert_rows_visible(suite_names, below=frozenset(), invisible=frozenset()) -> None:
    """The visibility simulation of docs/foreign_drives.md, repeated: each outside row of ``suite_names`` against the
    same spec without its mechanism (same seed, its full length); a sensor row of a1 on a1, every other on a2. A row
    its module leaves below the criterion (``below``, labels) is below it, and visible (above a tenth of it); one it
    leaves below a tenth of it (``invisible``, labels: set 20's) stays there, but not at 0."""
    for s in [row for name in suite_names for row in suites.suite(name)]:
        if s.kind != "outside":
            continue
        (e,) = s.effects
        rec, base = make_recording(s), make_recording(dataclasses.replace(s, effects=(), kind="clean"))
        f = F.get(e.form)
        signal = getattr(f, "channel", None) or (    # a sensor form may name the signal it changes (set 18 on)
            "a1" if f.balance == "sensor" and "motor_acceleration" in f.depends_on else "a2")
        rms = float(np.sqrt(np.mean((rec.signals[signal] - base.signals[signal]) ** 2)))
        if s.label in below:
            assert 0.1 * CRITERION_M_S2[signal] < rms < CRITERION_M_S2[signal], (s.label, signal, rms)
        elif s.label in invisible:
            assert 0.0 < rms < 0.1 * CRITERION_M_S2[signal], (s.label, signal, rms)
        else:
            assert rms >= CRITERION_M_S2[signal], (s.label, signal, rms)


def assert_recordings_repeat(suite_names, rows=(0, 1, 5, 6)) -> None:
    """A recording is the same each time it is made: ``rows`` of each suite, 0.4 s, made twice, equal sample by sample."""
    for name in suite_names:
        specs = suites.suite(name)
        for s in [specs[i] for i in rows if i < len(specs)]:
            short = dataclasses.replace(s, duration_s=0.4)
            one, two = make_recording(short), make_recording(short)
            for k in ("a1", "a2", "omega1", "omega2", "angle_difference"):
                assert np.array_equal(one.signals[k], two.signals[k]), (s.label, k)


def assert_bench_guards_unspent_sealed(set_number: int, capsys, monkeypatch) -> None:
    """bench/_workbench/outside.py knows the set; sets 1..set_number are spent (each sealed half ran once: development
    data, in the loop's default suites); the loop refuses a sealed half while it is unspent (the guard, tested with
    this set's half monkeypatched unspent); each row's truth names a balance and a state exactly when it is outside."""
    import pytest
    dev, sealed = f"outside_dev{set_number}", f"outside_sealed{set_number}"
    bench = outside_bench(f"outside_bench_under_test{set_number}")
    assert [s.label for s in bench.suite_rows(False, set_number)] == [s.label for s in suites.suite(dev)]
    assert bench.suite_name(True, set_number) == sealed
    spent = {"outside_sealed"} | {f"outside_sealed{k}" for k in range(2, set_number + 1)}
    assert spent <= set(bench.LOOP_DEVELOPMENT_SUITES) and not spent & set(bench.UNSPENT_SEALED)
    assert dev in bench.LOOP_DEVELOPMENT_SUITES
    monkeypatch.setattr(bench, "UNSPENT_SEALED", (sealed,))
    with pytest.raises(SystemExit) as e:
        bench.main(["--loop", "--loop-suites", f"{dev},{sealed}"])
    assert e.value.code == 2 and f"{sealed} is an unspent sealed half" in capsys.readouterr().err
    _assert_truths_name_balance_and_state(bench, dev, sealed)


def assert_bench_refuses_the_unspent_sealed_half(set_number: int, capsys) -> None:
    """bench/_workbench/outside.py knows the set, whose sealed half is UNSPENT until its one run (one of the
    UNSPENT_SEALED: set 24's now): the loop's default suites hold its development half
    only and no unspent sealed half, and the loop refuses the sealed half without --sealed; each row's truth names a
    balance and a state exactly when it is outside."""
    import pytest
    dev, sealed = f"outside_dev{set_number}", f"outside_sealed{set_number}"
    bench = outside_bench(f"outside_bench_under_test{set_number}")
    assert [s.label for s in bench.suite_rows(False, set_number)] == [s.label for s in suites.suite(dev)]
    assert bench.suite_name(True, set_number) == sealed and sealed in bench.UNSPENT_SEALED
    assert not set(bench.UNSPENT_SEALED) & set(bench.LOOP_DEVELOPMENT_SUITES)
    assert dev in bench.LOOP_DEVELOPMENT_SUITES
    assert sealed not in bench.LOOP_DEVELOPMENT_SUITES
    with pytest.raises(SystemExit) as e:
        bench.main(["--loop", "--loop-suites", f"{dev},{sealed}"])
    assert e.value.code == 2 and f"{sealed} is an unspent sealed half" in capsys.readouterr().err
    _assert_truths_name_balance_and_state(bench, dev, sealed)


def _assert_truths_name_balance_and_state(bench, dev: str, sealed: str) -> None:
    for s in suites.suite(dev) + suites.suite(sealed):
        bal, st = bench._truth_of(s, s.truth())
        assert bool(bal) == (s.kind == "outside") and (not bal or st)


def _alarm_suites(set_number: int) -> set:
    """The suites bench/_workbench/width_caveat.py's alarm check covers (the module loaded under a name of its own)."""
    spec = importlib.util.spec_from_file_location(f"width_caveat_under_test{set_number}",
                                                  OUTSIDE_BENCH.parent / "width_caveat.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return set(module.alarm_suites())


def assert_alarm_check_covers_both_halves(set_number: int) -> None:
    """bench/_workbench/width_caveat.py's alarm check covers the set's development half and its spent sealed half."""
    assert {f"outside_dev{set_number}", f"outside_sealed{set_number}"} <= _alarm_suites(set_number)


def assert_alarm_check_leaves_out_the_unspent_sealed_half(set_number: int) -> None:
    """The alarm check covers the set's development half and not its sealed half while that is unspent."""
    names = _alarm_suites(set_number)
    assert f"outside_dev{set_number}" in names and f"outside_sealed{set_number}" not in names


def assert_a_row_of_each_half_crosses_the_backlash(set_number: int, duration_s: float) -> None:
    """The first outside row of each half simulates at its own conditions: finite signals, at least two onsets."""
    for name in (f"outside_dev{set_number}", f"outside_sealed{set_number}"):
        spec = dataclasses.replace(next(s for s in suites.suite(name) if s.kind == "outside"), duration_s=duration_s)
        rec = make_recording(spec)
        assert all(np.all(np.isfinite(rec.signals[k])) for k in rec.signals)
        assert sum(k == "onset" for _, k in rec.true_entries()) >= 2


# ------------------------------------------------------------------ small readings of a recording the sets' tests share
def others_zero(rec, *terms) -> None:
    """Each of ``terms`` (a balance term of the recording: foreign_balance_terms) is 0 on ``rec``: the mechanism acts
    in no other balance."""
    for term in terms:
        assert np.max(np.abs(term(rec))) < 1e-6, term.__name__


def held_per_segment(x):
    """The spread of x within each whole 0.2 ms segment, the memory elements' scan (0 where it is held)."""
    seg = N.SEGMENT_SAMPLES
    n = x.size // seg
    return np.ptp(x[:n * seg].reshape(n, seg), axis=1)


def extra_clutch_Nm(rec):
    """The clutch torque beyond the nominal contact law's [N*m]."""
    return rec.internal["clutch_torque_Nm"] - contact_law_Nm(rec)


def sample_times_s(rec):
    """Each sample's time in the recording [s]."""
    return np.arange(rec.n_samples) * C.SAMPLE_PERIOD_S


def slip_rad_s(rec):
    """The speed across the clutch, motor minus wheel [rad/s]."""
    return rec.signals["omega1"] - rec.signals["omega2"]
