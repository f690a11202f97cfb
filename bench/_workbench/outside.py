"""Proposing the missing term on drives with mechanisms outside the catalogue (issue 31), and a user's exact-law plug-in
on drives with a torque locked to a shaft's angle.

    python bench/_workbench/outside.py [--set N] [--sealed] [--only LABEL ...] [--skip-explained]
    python bench/_workbench/outside.py --loop [--loop-suites SUITE,...] [--only LABEL ...] [--jobs N] [--keep DIR]
    (or: python bench/workbench.py --parts outside [--sealed])

Goals (docs/workbench.md "Proposing a missing term"):
- outside_proposal_consistent_rate: on the outside recordings, the model with the proposed term passes diagnose's
  consistency test (a recording without a proposal counts as a failure; ``outside_visible_*``: the same rates over the
  recordings the nominal model does not explain, verdict not ``consistent`` -- an invisible mechanism leaves nothing
  to propose);
- outside_proposal_right_balance_rate: the proposed term acts in the truth's balance and depends on its state (the
  manifest's ``balance`` and ``state`` of the outside effect; for the forms of foreign_drives/forms.py, OUTSIDE_TRUTH);
- proposals_on_explained: terms proposed on a clean drive or a drive one catalogue effect explains (the foreign
  bench's clean and one-effect rows);
- angle_locked_plugin_named_rate: on every foreign drive with a torque locked to a shaft's angle, a user's plug-in with
  the exact law is named, its amplitude within 3 uncertainties of the truth;
- proposal_cpu_seconds: the proposal's own CPU time per recording (on top of diagnose), one core; the library kernel's
  one-time first call in a process (its compile on a cold kernel cache, ~40 s once after a change of the library or
  the plant's generator) is not in it, but beside it (proposal_kernel_first_call_cpu_seconds_max).

The development suite is ``foreign_drives.suites.suite("outside_dev")`` when it exists, else DEV_ROWS below; the
sealed one only with ``--sealed`` (run once, by others, at the end). ``--set 2``: the second set, outside_dev2 and
(with ``--sealed``) outside_sealed2; ``--set 3``: the third, outside_dev3 and (with ``--sealed``) outside_sealed3;
``--set 4``: the fourth, outside_dev4 and (with ``--sealed``) outside_sealed4; ``--set 5``: the fifth, outside_dev5 and
(with ``--sealed``) outside_sealed5; ``--set 6``: the sixth, outside_dev6 and (with ``--sealed``) outside_sealed6;
``--set 7``: the seventh, outside_dev7 and (with ``--sealed``) outside_sealed7; ``--set 8``: the eighth, outside_dev8 and
(with ``--sealed``) outside_sealed8; ``--set 9``: the ninth, outside_dev9 and (with ``--sealed``) outside_sealed9;
``--set 10``: the tenth, outside_dev10 and (with ``--sealed``) outside_sealed10; ``--set 11``: the eleventh, outside_dev11
and (with ``--sealed``) outside_sealed11; ``--set 12``: the twelfth, outside_dev12 and (with ``--sealed``)
outside_sealed12; ``--set 13``: the thirteenth, outside_dev13 and (with ``--sealed``) outside_sealed13; ``--set 14``: the
fourteenth, outside_dev14 and (with ``--sealed``) outside_sealed14; ``--set 15``: the fifteenth, outside_dev15 and (with
``--sealed``) outside_sealed15; ``--set 16``: the sixteenth, outside_dev16 and (with ``--sealed``) outside_sealed16;
``--set 17``: the seventeenth, outside_dev17 and (with ``--sealed``) outside_sealed17; ``--set 18``: the eighteenth,
outside_dev18 and (with ``--sealed``) outside_sealed18; ``--set 19``: the nineteenth, outside_dev19 and (with
``--sealed``) outside_sealed19; ``--set 20``: the twentieth, outside_dev20 and (with ``--sealed``) outside_sealed20;
``--set 21``: the twenty-first, outside_dev21 and (with ``--sealed``) outside_sealed21; ``--set 22``: the
twenty-second, outside_dev22 and (with ``--sealed``) outside_sealed22; ``--set 23``: the twenty-third, outside_dev23 and
(with ``--sealed``) outside_sealed23; ``--set 24``: the twenty-fourth, outside_dev24 and (with ``--sealed``)
outside_sealed24. The sealed halves of sets 1-23 have been run once and are development data now
(set 11's on 30 Nov, stop 48; set 12's at stop 49; set 13's at stop 50; set 14's at stop 51; set 15's on 1 Dec,
stop 52; set 16's at stop 53; set 17's at stop 54; set 18's at stop 55; set 19's on 2 Dec, stop 57; set 20's and set
21's at stop 58; set 22's at stop 59; set 23's at stop 60); the sealed half of set 24 is UNSPENT (UNSPENT_SEALED names
it until its one run).

The outside loop (``--loop``, goals outside_loop_width_error_after_mm and outside_loop_worse_count): the README's
loop through the CLI on each development outside recording (the development halves of sets 1-24 and the spent sealed
halves of sets 1-23; never an unspent sealed half unless ``--sealed``), the width error |fused width - true width|
before and after; *worse*: after > before + the after's stated uncertainty. Its rows carry the proposal's fields too
(verdict, law, right balance, consistent), from the CLI's diagnosis at the nominal conditions. Each recording is
diagnosed in this process at the drive's nominal values (NUMBA_NUM_THREADS=1); the proposal's CPU time is its own
(proposal.Proposal.cpu_seconds).
"""
from __future__ import annotations

import json
import os
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))          # _workbench.foreign (the loop's CLI runner) when run as a script

import numpy as np                                                      # noqa: E402

from foreign_drives.drive import make_recording                         # noqa: E402
from foreign_drives.spec import EffectSpec as E                         # noqa: E402
from foreign_drives.spec import RecordingSpec, SensorNuisance           # noqa: E402

from backlash_monitor.workbench.diagnose import diagnose                # noqa: E402
from backlash_monitor.workbench.measurement import Measurement          # noqa: E402
from backlash_monitor.workbench.model import load_model                 # noqa: E402

# where the forms outside the catalogue that foreign_drives/forms.py has act: (balance(s), state(s)) -- the
# library's balance names and states (candidate_terms.Term.state)
OUTSIDE_TRUTH = {
    "spring_hardening": (("rim_mass_force_N",), ("z",)),
    "clutch_contact_preload": (("clutch_torque_Nm",), ("penetration", "penetration rate")),
    "clutch_contact_progressive": (("clutch_torque_Nm",), ("penetration", "penetration rate")),
    "ripple_wheel_mesh": (("wheel_torque_Nm",), ("alpha2",)),
    "structural_vibration": (("motor_load_moment_pu",), ("time",)),
    "second_torsional_mode": (("wheel_torque_Nm", "clutch_torque_Nm"), ("omega2", "rel_speed")),
}


def _spec(label, kind, seed, effects, width=0.0075, eta=0.025, n1=0.89):
    return RecordingSpec(label=label, kind=kind, width_m=width, eta_k=eta, n1=n1, effects=tuple(effects),
                         sensor=SensorNuisance(), seed=seed, duration_s=4.0).check()


# the development rows while the mech developer's outside_dev suite is not there: forms of foreign_drives outside the
# catalogue, or outside its laws (seeds 7100+: no other suite uses them)
DEV_ROWS = [
    _spec("dev_spring_hardening_z0_0.35", "one", 7101, [E("spring_hardening", {"z0_m": 0.35})], width=0.0045),
    _spec("dev_contact_preload_20Nm", "outside", 7102,
          [E("clutch_contact_preload", {"preload_Nm": 20.0, "build_up_rad": 1e-3})], width=0.006),
    _spec("dev_wheel_angle_6Nm", "one", 7103,
          [E("ripple_wheel_mesh", {"amplitude_Nm": 6.0, "order": 1, "phase_rad": 0.31})], width=0.006),
    _spec("dev_second_mode", "outside", 7104, [E("second_torsional_mode", {
        "rim_fraction": 0.3, "stiffness_Nm_per_rad": 2e4, "damping_Nms_per_rad": 2.0})]),
]

# drives with a torque locked to a shaft's angle: (spec, the user's exact-law plug-in: balance, angle, order, unit)
ANGLE_ROWS = [
    (_spec("angle_wheel_order1_8Nm", "one", 7201,
           [E("ripple_wheel_mesh", {"amplitude_Nm": 8.0, "order": 1, "phase_rad": 0.31})], width=0.006),
     "amplitude_Nm"),
    (_spec("angle_wheel_order2_5Nm", "one", 7202,
           [E("ripple_wheel_mesh", {"amplitude_Nm": 5.0, "order": 2, "phase_rad": -1.1})], width=0.0075),
     "amplitude_Nm"),
]


def log(*a):
    print(*a, file=sys.stderr, flush=True)


def _measurement(spec):
    rec = make_recording(spec)
    return Measurement(f"foreign:{spec.label}", rec.sample_period_s,
                       {k: np.asarray(v) for k, v in rec.signals.items()}), rec.truth


def exact_law_source(order: int) -> str:
    """A user's plug-in with the exact law of foreign_drives' wheel mesh: A*sin(n*alpha2 + phi) on the wheel."""
    arg = "alpha2" if order == 1 else f"{order} * alpha2"
    return (
        "from backlash_monitor.plant.effects import Effect, Parameter\n"
        "from backlash_monitor.plant.mathlib import sin\n\n\n"
        "class WheelMesh(Effect):\n"
        f"    name = 'user_wheel_mesh{order}'\n"
        "    balance = 'wheel_torque_Nm'\n"
        f"    description = 'a torque locked to the wheel angle, A*sin({order}*alpha2 + phi)'\n"
        "    parameters = (Parameter('amplitude_Nm', 'N*m', 0.0, (0.0, 20.0), 'A'),\n"
        "                  Parameter('phase_rad', 'rad', 0.0, (-3.141592653589793, 3.141592653589793), 'phi'))\n\n"
        "    @staticmethod\n"
        "    def term(alpha2, amplitude_Nm, phase_rad):\n"
        f"        return amplitude_Nm * sin({arg} + phase_rad)\n")


# the proposal's balances and states (candidate_terms.Term) in the manifest's words (foreign_drives/outside.py
# BALANCES, STATES); the rim force (between wheel and mass) is neither of the manifest's balances
BALANCE_WORDS = {"motor_load_moment_pu": "motor_load_moment", "wheel_torque_Nm": "wheel_torque",
                 "clutch_torque_Nm": "clutch_torque", "mass_force_N": "mass_force", "sensor_a1_m_s2": "sensor",
                 # the torque beside the jaw, in and out of contact: the foreign simulator's clutch balance is that
                 # (kernel.py: the outside terms' clutch slot added to the jaw's torque, ungated)
                 "coupling_torque_Nm": "clutch_torque",
                 "sensor_a2_m_s2": "sensor"}
STATE_WORDS = {"omega1": ("motor_speed",), "omega2": ("wheel_speed",), "xdot": ("mass_speed",), "v": ("rim_speed",),
               "rel_speed": ("motor_speed", "wheel_speed"), "penetration": ("clutch_penetration",),
               "penetration rate": ("clutch_penetration",), "z": ("spring_extension",), "alpha1": ("motor_angle",),
               "alpha2": ("wheel_angle",), "delta": ("motor_angle", "wheel_angle"), "te": (), "time": ("time",), "constant": (), "load pulse": ("load_pulse",),
               "a1": ("motor_acceleration",), "a2": ("mass_acceleration",)}   # a1 = r dOmega1/dt, a2 = dv/dt


def _truth_of(spec, truth) -> tuple[set, set]:
    """(balances, states) of the recording's effects outside the catalogue, in the manifest's words (its ``balance``
    and ``depends_on``; for the forms of foreign_drives/forms.py, OUTSIDE_TRUTH)."""
    bal, st = set(), set()
    for e in truth.effects:
        b = getattr(e, "balance", None)
        if b:
            bal.add(b)
            st |= set(getattr(e, "depends_on", ()) or ())
        elif e.form in OUTSIDE_TRUTH:
            bal |= {BALANCE_WORDS.get(x, x) for x in OUTSIDE_TRUTH[e.form][0]}
            st |= {w for x in OUTSIDE_TRUTH[e.form][1] for w in STATE_WORDS.get(x, (x,))}
    return bal, st


ANGLES = ("alpha1", "alpha2")


def right_balance(terms, bal: set, st: set) -> bool:
    """A proposed term acts in the truth's balance and depends on one of its states. A harmonic of one shaft's angle
    also counts for the other's when the proposal names that one as fitting the events as well (``alike``, in the
    same balance): the two angles differ by at most the gap, no recording tells them apart. No other alike term
    counts."""
    def states(t):
        out = set(STATE_WORDS.get(t["state"], ()))
        for a in t.get("alike", ()):
            if a["balance"] == t["balance"] and t["state"] in ANGLES and a["state"] in ANGLES:
                out |= set(STATE_WORDS.get(a["state"], ()))
        return out
    return any(BALANCE_WORDS.get(t["balance"]) in bal and states(t) & st for t in terms)


def _proposal_cpu(prop: dict) -> dict:
    """A row's proposal CPU fields [s]: ``proposal_cpu_seconds``, this recording's own (without the library kernel's
    one-time first call in the process), and ``proposal_kernel_first_call_cpu_seconds``, that first call (its compile on
    a cold cache after a change of the library or the generator; None when the kernel was already loaded)."""
    return {"proposal_cpu_seconds": prop.get("per_recording_cpu_seconds", prop.get("cpu_seconds")),
            "proposal_kernel_first_call_cpu_seconds": prop.get("kernel_first_call_cpu_seconds")}


def run_outside(specs) -> list:
    rows = []
    for spec in specs:
        meas, truth = _measurement(spec)
        model = load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)
        t0 = time.process_time()
        d = diagnose(meas, model).to_json()
        cpu = time.process_time() - t0
        prop = d.get("proposal") or {}
        bal, st = _truth_of(spec, truth)
        terms = prop.get("terms") or []
        right = bool(prop.get("proposed")) and right_balance(terms, bal, st)
        row = {"label": spec.label, "kind": spec.kind, "outside": bool(bal), "verdict": d["verdict"],
               "proposed": bool(prop.get("proposed")),
               "law": prop.get("law"), "consistent": bool(prop.get("consistent")), "right_balance": right,
               "truth_balance": sorted(bal), "truth_state": sorted(st),
               "terms": [(t["balance"], t["state"], t["group"]) for t in terms],
               "stability": prop.get("stability"), "reason": prop.get("reason"),
               "explained_fraction": prop.get("explained_fraction"),
               **_proposal_cpu(prop), "diagnose_cpu_seconds": cpu,
               "message": d["message"]}
        log(json.dumps(row, default=float))
        rows.append(row)
    return rows


def run_explained(specs) -> list:
    rows = []
    for spec in specs:
        meas, _ = _measurement(spec)
        model = load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)
        d = diagnose(meas, model).to_json()
        prop = d.get("proposal") or {}
        # a row that reached the proposal (verdict partial / nothing_explains) carries why it proposed or did not: the
        # selection's steps, the groups' stability over the event resamples, diagnose's message
        row = {"label": spec.label, "kind": spec.kind, "verdict": d["verdict"],
               "proposed": bool(prop.get("proposed")), "law": prop.get("law")}
        if prop:
            row.update({"reason": prop.get("reason"), "stability": prop.get("stability"),
                        "selection": prop.get("selection"), "explained_fraction": prop.get("explained_fraction"),
                        "terms": [(t["balance"], t["state"], t["group"]) for t in prop.get("terms") or []],
                        "message": d["message"]})
        log(json.dumps(row))
        rows.append(row)
    return rows


def angle_rows(specs) -> list:
    """(spec, plug-in source, effect name, amplitude parameter, true amplitude) of every drive with a torque locked to a
    shaft's angle: the suite's (the manifest's exact-law plug-in) and ANGLE_ROWS (a plug-in written here)."""
    import re
    out = []
    for spec in specs:
        for e in spec.truth().effects:
            src = getattr(e, "plugin", None)
            if src and {"motor_angle", "wheel_angle"} & set(getattr(e, "depends_on", ()) or ()):
                name = re.search(r"name = ['\"]([A-Za-z_0-9]+)['\"]", src).group(1)
                amp = next(k for k in e.parameters if k.startswith("amplitude"))
                out.append((spec, src, name, amp, float(e.parameters[amp])))
    for spec, pname in ANGLE_ROWS:
        eff = next(e for e in spec.effects if e.form == "ripple_wheel_mesh")
        order = int(eff.parameters["order"])
        out.append((spec, exact_law_source(order), f"user_wheel_mesh{order}", pname,
                    float(eff.parameters["amplitude_Nm"])))
    return out


def run_angle_locked(rows) -> list:
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for spec, src, name, pname, truth in rows:
            plugin = Path(tmp) / f"{spec.label}_{name}.py"
            plugin.write_text(src)
            meas, _ = _measurement(spec)
            model = load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1, effect_files=[plugin])
            d = diagnose(meas, model, propose=False).to_json()
            named = name in (d.get("indistinguishable") or []) or d.get("discovery") == name or any(
                name == (e or {}).get("effect") for e in [d.get("second_effect")])
            # the plug-in's fit as the diagnosis names it (the discovery's or the second effect's: in a pair, fitted
            # beside the other), else its single fit in the ranking
            fit = next((r for r in [d.get("discovery_parameters"), d.get("second_effect")] + list(d["ranked"])
                        if r and r.get("effect") == name), None)
            a = fit["parameters"][pname] if fit else None
            s = (fit.get("uncertainty") or {}).get(pname) if fit else None
            within = a is not None and s is not None and abs(a - truth) <= 3 * s
            row = {"label": spec.label, "plugin": name, "verdict": d["verdict"], "named": bool(named), "amplitude": a,
                   "uncertainty": s, "truth": truth, "within_3_sigma": bool(within), "message": d["message"]}
            log(json.dumps(row, default=float))
            out.append(row)
    return out


# the outside suites by set: (development, sealed). The sealed halves of sets 1-23 have each been run once (their labels
# and results are known; set 4's on 29 Nov, 18:19-18:50, set 5's on main d26fbff, set 6's as in 412d392, set 7's on
# 30 Nov, main ca708e3, set 8's on 30 Nov, lead eb9735e, set 9's on 30 Nov, lead 3ad5e4f, set 10's on 30 Nov, lead
# 75dcaf0, set 11's at stop 48, lead 47813e6, set 12's at stop 49, lead 40a5676, set 13's at stop 50, lead 0ba8c22,
# set 14's at stop 51, lead a6051f3, set 15's at stop 52, lead e663230, set 16's at stop 53, main 29e77a6, set 17's at
# stop 54, main a303c1a, set 18's at stop 55, main 593d8c9, set 19's at stop 57, main 5798d58, set 20's at stop
# 58, main beecf27, set 21's at stop 58, main dc2aa43, set 22's at stop 59, main ca3a15b, set 23's at stop 60, main
# da35d4d): they are development data now. A new set's sealed half goes into UNSPENT_SEALED until its run (set 24's now).
SETS = {1: ("outside_dev", "outside_sealed"), 2: ("outside_dev2", "outside_sealed2"), 3: ("outside_dev3", "outside_sealed3"),
        4: ("outside_dev4", "outside_sealed4"), 5: ("outside_dev5", "outside_sealed5"),
        6: ("outside_dev6", "outside_sealed6"), 7: ("outside_dev7", "outside_sealed7"),
        8: ("outside_dev8", "outside_sealed8"), 9: ("outside_dev9", "outside_sealed9"),
        10: ("outside_dev10", "outside_sealed10"), 11: ("outside_dev11", "outside_sealed11"),
        12: ("outside_dev12", "outside_sealed12"), 13: ("outside_dev13", "outside_sealed13"),
        14: ("outside_dev14", "outside_sealed14"), 15: ("outside_dev15", "outside_sealed15"),
        16: ("outside_dev16", "outside_sealed16"), 17: ("outside_dev17", "outside_sealed17"),
        18: ("outside_dev18", "outside_sealed18"), 19: ("outside_dev19", "outside_sealed19"),
        20: ("outside_dev20", "outside_sealed20"), 21: ("outside_dev21", "outside_sealed21"),
        22: ("outside_dev22", "outside_sealed22"), 23: ("outside_dev23", "outside_sealed23"),
        24: ("outside_dev24", "outside_sealed24")}
# the sealed halves not to be run but once, at the end (only with --sealed); sets 1-23 are spent, set 24's is not
UNSPENT_SEALED: tuple[str, ...] = ("outside_sealed24",)
# the suites the outside loop runs on by default: every development one and the spent sealed halves, set by set (SETS
# without UNSPENT_SEALED), never an unspent sealed half
LOOP_DEVELOPMENT_SUITES = tuple(name for pair in SETS.values() for name in pair if name not in UNSPENT_SEALED)


def suite_name(sealed: bool, set_: int = 1) -> str:
    if set_ not in SETS:
        raise ValueError(f"--set {set_!r}: unknown set of outside mechanisms; allowed: {', '.join(map(str, SETS))}")
    return SETS[set_][1 if sealed else 0]


def suite_rows(sealed: bool, set_: int = 1) -> list:
    from foreign_drives import suites
    name = suite_name(sealed, set_)
    if sealed:          # made on first use from foreign_drives/outside_sealed*.py (not in SUITES)
        return suites.suite(name)
    if name in getattr(suites, "SUITES", {}):
        return suites.suite(name)
    return list(DEV_ROWS)


def summary(rows, explained, angle) -> dict:
    """The goals; the suite's rows without an outside mechanism (its clean drives) count with the explained ones."""
    def rate(rows, key):
        return float(np.mean([bool(r[key]) for r in rows])) if rows else None
    outside = [r for r in rows if r.get("outside", True)]
    explained = list(explained) + [r for r in rows if not r.get("outside", True)]
    cpu = [r["proposal_cpu_seconds"] for r in rows if r["proposal_cpu_seconds"] is not None]
    # a mechanism the nominal model already explains within its noise band and form tolerance (verdict consistent)
    # leaves nothing to propose: the goals count it as a failure; beside them, the rates over the others
    visible = [r for r in outside if r["verdict"] != "consistent"]
    return {"outside_recordings": len(outside),
            "outside_proposed_rate": rate(outside, "proposed"),
            "outside_proposal_consistent_rate": rate(outside, "consistent"),
            "outside_proposal_right_balance_rate": rate(outside, "right_balance"),
            "outside_visible_recordings": len(visible),
            "outside_visible_proposal_consistent_rate": rate(visible, "consistent"),
            "outside_visible_right_balance_rate": rate(visible, "right_balance"),
            "proposals_on_explained": int(sum(r["proposed"] for r in explained)) if explained else None,
            "explained_recordings": len(explained),
            "angle_locked_plugin_named_rate": (float(np.mean([r["named"] and r["within_3_sigma"] for r in angle]))
                                               if angle else None),
            "proposal_cpu_seconds": float(np.max(cpu)) if cpu else None,
            "proposal_kernel_first_call_cpu_seconds_max": max(
                (r["proposal_kernel_first_call_cpu_seconds"] for r in rows
                 if r.get("proposal_kernel_first_call_cpu_seconds") is not None), default=None),
            "outside_per_recording": outside, "explained_per_recording": explained,
            "angle_locked_per_recording": angle}


def run_all(sealed: bool = False, only=(), skip_explained: bool = False, skip_angle: bool = False,
            skip_outside: bool = False, explained_every: int = 1, set_: int = 1):
    """(outside rows, explained rows, angle-locked rows) of the chosen suite."""
    specs = [s for s in suite_rows(sealed, set_) if not only or s.label in only]
    outside = [] if skip_outside else run_outside(specs)
    explained = []
    if not skip_explained:
        from foreign_drives.suites import suite
        explained = run_explained([s for s in suite("bench") if s.kind in ("clean", "one")
                                   and (not only or s.label in only)][::max(1, explained_every)])
    angle = [] if skip_angle else run_angle_locked([r for r in angle_rows(suite_rows(sealed, set_))
                                                    if not only or r[0].label in only])
    return outside, explained, angle


# ------------------------------------------------------------------------------------------------- the outside loop
# The README's loop as a user runs it, through the CLI, on each outside recording (bench/_workbench/foreign.py runs
# the same commands): diagnose BAG at the drive's nominal conditions -> add-effect --accept-proposal when diagnose
# proposes a term (and --accept-partial after it when the term has no plug-in form and the verdict is `partial`: the
# refusal names it), else add-effect --accept-partial when its verdict is `partial` (the nearer model: README), else
# add-effect when diagnose names a catalogue effect (its ``additions``), else nothing (the monitor keeps the packaged
# library) -> train --model -> analyze BAG --library, against analyze BAG before.
# Training kept short (LOOP_TRAIN_SEEDS, LOOP_TRAIN_DURATION_S) so that a row costs a few CPU-minutes: one seed of the
# 120-scenario grid is 8 windows per scenario at --duration 2.25 (the default); 1.25 s gives 4 per scenario.
LOOP_TRAIN_SEEDS = "1000,1001"
LOOP_TRAIN_DURATION_S = 1.25


def _width_error(analyze_json: Path, truth_m: float) -> dict:
    """|fused continuous width (a1+a2) - true width| over the onset windows whose fusion is full (foreign.py's
    measure), and its uncertainty: the mean of the fused widths' own stated uncertainties over the same windows
    (analyze's ``fused_width_uncertainty_m``: the spread of the windows each fuses)."""
    from _workbench.foreign import full_fusions, fused_width_error_mm
    doc = json.loads(analyze_json.read_text())
    est = full_fusions(doc)
    out = fused_width_error_mm(est, truth_m)
    u = [e.get("fused_width_uncertainty_m") for e in est]
    u = [x for x in u if x is not None and np.isfinite(x)]
    out["uncertainty_mm"] = float(np.mean(u) * 1e3) if u else None
    # each accelerometer's own fused width too (recorded, not a goal: docs/workbench.md "One signal against both")
    out["per_signal_mean_abs_mm"] = {sig: fused_width_error_mm(full_fusions(doc, sig), truth_m)["mean_abs_mm"]
                                     for sig in ("a1", "a2")}
    out["model_fit_level"] = (doc.get("summary") or {}).get("model_fit_level")
    return out


def loop_row(spec, workdir: Path, suite: str) -> dict:
    """One outside recording through the README's loop (module comment above); also the proposal's row fields."""
    from _workbench.foreign import _cli
    from foreign_drives.files import write_bag
    rec = make_recording(spec)
    truth = rec.truth
    d = workdir / spec.label
    d.mkdir(parents=True, exist_ok=True)
    bag = d / "drive.mcap"
    write_bag(spec, bag, recording=rec)
    bal, st = _truth_of(spec, truth)
    row = {"label": spec.label, "suite": suite, "kind": spec.kind, "outside": bool(bal),
           "true_width_mm": truth.true_width_m * 1e3, "truth_balance": sorted(bal), "truth_state": sorted(st)}
    cpu = {}
    rc, out, _, cpu["diagnose"] = _cli(["diagnose", bag, "--width-m", spec.width_m, "--eta-k", spec.eta_k, "--n1",
                                        spec.n1, "--json", d / "d.json", "--no-history"], d)
    if rc != 0:
        row["error"] = "diagnose: " + out[-1500:]
        return row
    diag = json.loads((d / "d.json").read_text())
    prop = diag.get("proposal") or {}
    terms = prop.get("terms") or []
    row.update({"verdict": diag["verdict"], "proposed": bool(prop.get("proposed")), "law": prop.get("law"),
                "consistent": bool(prop.get("consistent")),
                "right_balance": bool(prop.get("proposed")) and right_balance(terms, bal, st),
                "terms": [(t["balance"], t["state"], t["group"]) for t in terms],
                "additions": [(a["candidate"], a["role"]) for a in diag.get("additions") or []],
                **_proposal_cpu(prop), "diagnose_message": diag["message"][:400]})
    rc, out, _, cpu["analyze_before"] = _cli(["analyze", bag, "--out", d / "before"], d)
    if rc != 0:
        row["error"] = "analyze before: " + out[-1000:]
        return row
    row["before"] = _width_error(d / "before.json", truth.true_width_m)
    if row["proposed"]:
        row["added"] = "proposal"
        rc, out, _, cpu["add_effect"] = _cli(["add-effect", d / "d.json", "--accept-proposal", "-o", d / "v2.yaml"], d)
    elif row["verdict"] == "partial":
        row["added"] = "partial"
        rc, out, _, cpu["add_effect"] = _cli(["add-effect", d / "d.json", "--accept-partial", "-o", d / "v2.yaml"], d)
    else:
        row["added"] = "catalogue"
        rc, out, _, cpu["add_effect"] = _cli(["add-effect", d / "d.json", "-o", d / "v2.yaml"], d)
    if rc != 0 and row["added"] == "proposal" and row["verdict"] == "partial":
        # a proposed term with no plug-in form (a sensor's): the refusal names --accept-partial, the README's step
        row["added"] = "partial"
        rc, out, _, cpu["add_effect_partial"] = _cli(["add-effect", d / "d.json", "--accept-partial", "-o",
                                                      d / "v2.yaml"], d)
    elif rc != 0 and row["added"] == "proposal" and row["verdict"] == "discovery":
        # the same beside a discovery: the refusal names the discovered effect alone (add-effect without the flag)
        row["added"] = "catalogue"
        rc, out, _, cpu["add_effect_discovery"] = _cli(["add-effect", d / "d.json", "-o", d / "v2.yaml"], d)
    if rc != 0:          # nothing to add (or refused): the monitor keeps its library
        row["added"] = "nothing"
        row["add_effect_said"] = (out.strip().splitlines() or [""])[-1][:300]
        row["after"] = dict(row["before"])
    else:
        rc, out, _, cpu["train"] = _cli(["train", "--model", d / "v2.yaml", "--output", d / "lib.npz", "--seeds",
                                         LOOP_TRAIN_SEEDS, "--duration", LOOP_TRAIN_DURATION_S, "--no-progress"], d)
        if rc != 0:
            # train writes the library before the live model watch's reference; when only the reference fails (seen:
            # "the model does not cross its backlash" on an accepted proposal) the user has the library: go on, say so
            row["train_error"] = out.strip().splitlines()[-1][:400] if out.strip() else f"exit {rc}"
            if not (d / "lib.npz").exists():
                row["error"] = "train: " + out[-1000:]
                return row
        rc, out, _, cpu["analyze_after"] = _cli(["analyze", bag, "--library", d / "lib.npz", "--out", d / "after"], d)
        if rc != 0:
            row["error"] = "analyze after: " + out[-1000:]
            return row
        row["after"] = _width_error(d / "after.json", truth.true_width_m)
    b, a = row["before"]["mean_abs_mm"], row["after"]["mean_abs_mm"]
    u = row["after"].get("uncertainty_mm") or 0.0
    row["worse"] = bool(a is not None and b is not None and a > b + u)
    row["cpu_seconds"] = cpu
    row["row_cpu_seconds"] = float(sum(cpu.values()))
    return row


def _loop_row_in_worker(task) -> tuple[int, dict]:
    """A pool worker's row: (its place in the run, loop_row's row); the spec made again from its suite and label (a
    sealed half's rows are made on first use, in each process)."""
    from foreign_drives import suites as S
    place, name, label, workdir = task
    spec = next(s for s in S.suite(name) if s.label == label)
    return place, loop_row(spec, Path(workdir), name)


def run_loop(suites=LOOP_DEVELOPMENT_SUITES, only=(), workdir=None, jobs: int = 1, keep=None) -> list:
    """loop_row on each recording of ``suites`` (``only``: these labels), in the suites' order. ``jobs`` > 1: that many
    rows at once, each in a worker process of its own (the CLI's commands are its children: each row's CPU figures
    are its own); ``keep``: the rows' folders (bag, diagnosis, v2.yaml, library, analyze output) under this directory,
    kept (else a temporary directory, removed)."""
    import contextlib
    from foreign_drives import suites as S
    todo = [(name, spec) for name in suites for spec in S.suite(name) if not only or spec.label in only]
    if keep is not None:
        Path(keep).mkdir(parents=True, exist_ok=True)
    place = contextlib.nullcontext(str(keep)) if keep is not None else tempfile.TemporaryDirectory(dir=workdir)
    with place as tmp:
        if jobs <= 1 or len(todo) <= 1:
            rows = []
            for name, spec in todo:
                row = loop_row(spec, Path(tmp), name)
                log(json.dumps(row, default=float))
                rows.append(row)
            return rows
        import multiprocessing
        tasks = [(i, name, spec.label, tmp) for i, (name, spec) in enumerate(todo)]
        done = {}
        # fork: the workers inherit sys.path (this script's ROOT and bench/); nothing compiled runs before the pool
        with multiprocessing.get_context("fork").Pool(min(jobs, len(todo))) as pool:
            for i, row in pool.imap_unordered(_loop_row_in_worker, tasks):
                log(json.dumps(row, default=float))
                done[i] = row
        return [done[i] for i in range(len(todo))]


def loop_summary(rows) -> dict:
    """The loop's goals: outside_loop_width_error_after_mm (mean over the outside recordings), outside_loop_worse_count
    (every recording, the clean ones too)."""
    def mean(rs, key):
        v = [r[key]["mean_abs_mm"] for r in rs if key in r and r[key]["mean_abs_mm"] is not None]
        return float(np.mean(v)) if v else None
    done = [r for r in rows if "after" in r]
    outside = [r for r in done if r["outside"]]
    by_suite = {}
    for name in dict.fromkeys(r["suite"] for r in rows):
        rs = [r for r in outside if r["suite"] == name]
        by_suite[name] = {"recordings": len(rs), "before_mm": mean(rs, "before"), "after_mm": mean(rs, "after"),
                          "worse": int(sum(r["worse"] for r in done if r["suite"] == name))}
    return {"outside_loop_recordings": len(outside), "outside_loop_clean_recordings": len(done) - len(outside),
            "outside_loop_errors": [r["label"] for r in rows if "error" in r],
            "outside_loop_width_error_before_mm": mean(outside, "before"),
            "outside_loop_width_error_after_mm": mean(outside, "after"),
            "outside_loop_worse_count": int(sum(r["worse"] for r in done)),
            "outside_loop_worse_labels": [r["label"] for r in done if r["worse"]],
            "outside_loop_added": {k: int(sum(r.get("added") == k for r in done))
                                   for k in ("proposal", "partial", "catalogue", "nothing")},
            "outside_loop_by_suite": by_suite,
            "outside_loop_row_cpu_seconds_max": max((r["row_cpu_seconds"] for r in done if "row_cpu_seconds" in r),
                                                    default=None),
            "outside_loop_train": {"seeds": LOOP_TRAIN_SEEDS, "duration_s": LOOP_TRAIN_DURATION_S},
            "outside_loop_per_recording": rows}


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--sealed", action="store_true", help="run the sealed outside suite (once, at the end)")
    ap.add_argument("--set", dest="set_", type=int, default=1, choices=sorted(SETS),
                    help="the set of outside mechanisms: " + ", ".join(
                        f"{k} = {dev} / {sealed}" + (" (its sealed half UNSPENT: run once, at the end)"
                                                     if sealed in UNSPENT_SEALED else "")
                        for k, (dev, sealed) in SETS.items())
                    + "; every other set spent: both halves development data now; default 1")
    ap.add_argument("--loop", action="store_true",
                    help="instead of the proposal rows: the README's loop through the CLI (diagnose, add-effect "
                         "[--accept-proposal | --accept-partial], train --model, analyze --library) on every development "
                         "outside suite "
                         f"({', '.join(LOOP_DEVELOPMENT_SUITES)}); with --loop-suites, on those")
    ap.add_argument("--loop-suites", default=None, metavar="SUITE[,SUITE...]",
                    help="with --loop: these suites (an unspent sealed half -- "
                         f"{', '.join(UNSPENT_SEALED) or 'none now'}: UNSPENT_SEALED -- only together with --sealed: "
                         "once, at the end)")
    ap.add_argument("--only", action="append", default=[], metavar="LABEL", help="only these rows (repeatable)")
    ap.add_argument("--jobs", type=int, default=1, metavar="N",
                    help="with --loop: N recordings at once, each in a process of its own (default 1; 2 on this "
                         "project's 2-core machines: a set's 14 rows in ~16 min instead of ~30)")
    ap.add_argument("--keep", default=None, metavar="DIR",
                    help="with --loop: keep each row's folder (bag, d.json, v2.yaml, lib.npz, analyze output) under "
                         "DIR/LABEL (default: a temporary directory, removed)")
    ap.add_argument("--skip-explained", action="store_true",
                    help="skip the foreign bench's clean and one-effect rows (proposals_on_explained: null)")
    ap.add_argument("--explained-every", type=int, default=1, metavar="K",
                    help="only every K-th of the foreign bench's clean and one-effect rows (default 1: all 38)")
    ap.add_argument("--skip-angle", action="store_true", help="skip the angle-locked plug-in rows")
    ap.add_argument("--skip-outside", action="store_true", help="skip the proposals on the outside rows")
    args = ap.parse_args(argv)
    t0 = time.perf_counter()
    if args.jobs < 1:
        ap.error(f"--jobs {args.jobs}: the number of recordings at once must be 1 or more")
    if (args.jobs != 1 or args.keep is not None) and not args.loop:
        ap.error("--jobs and --keep go with --loop (the proposal rows run in this process)")
    if args.loop:
        from foreign_drives.suites import SUITE_NAMES
        names = tuple(x.strip() for x in args.loop_suites.split(",") if x.strip()) if args.loop_suites else \
            LOOP_DEVELOPMENT_SUITES
        bad = [n for n in names if n not in SUITE_NAMES or not n.startswith("outside")]
        if bad:
            ap.error(f"--loop-suites: unknown outside suite {bad[0]!r}; allowed: "
                     + ", ".join(n for n in SUITE_NAMES if n.startswith("outside")))
        unspent = [n for n in names if n in UNSPENT_SEALED]
        if unspent and not args.sealed:
            ap.error(f"--loop-suites: {unspent[0]} is an unspent sealed half; allowed only with --sealed (once, "
                     "at the end)")
        rows = run_loop(names, args.only, jobs=args.jobs, keep=args.keep)
        out = loop_summary(rows)
        # the proposal's goals over the same rows (loop_row carries its fields: the CLI's diagnosis at the nominal
        # conditions), per suite and over all of them: a set's run is one command
        diagnosed = [r for r in rows if "verdict" in r]
        strip = ("outside_per_recording", "explained_per_recording", "angle_locked_per_recording")

        def goals(rs) -> dict:      # summary's figures without its per-recording lists (the loop's rows hold them)
            return {k: v for k, v in summary(rs, [], []).items() if k not in strip}
        out["proposal"] = goals(diagnosed)
        out["proposal_by_suite"] = {name: goals([r for r in diagnosed if r["suite"] == name])
                                    for name in dict.fromkeys(r["suite"] for r in rows)}
        out["jobs"] = args.jobs
        out["wall_seconds"] = time.perf_counter() - t0
        print(json.dumps(out, default=float))
        return
    out = summary(*run_all(args.sealed, args.only, args.skip_explained, args.skip_angle, args.skip_outside,
                           args.explained_every, args.set_))
    out["explained_every"] = args.explained_every
    out["suite"] = suite_name(args.sealed, args.set_)
    out["wall_seconds"] = time.perf_counter() - t0
    print(json.dumps(out, default=float))


if __name__ == "__main__":
    main()
