"""The live model watch (issue 18, docs/model_watch.md): prints ONE JSON object; progress on stderr.

detection_onsets_median: onset events from the moment an effect switches on to WARN, per catalogue family at a
  strength the workbench's consistency test detects offline on a 4 s recording (checked here: the same test on a
  4 s recording of the drive with the effect, at diagnose's 1 % level), median over the families; on the
  project's simulator (the effect switched on at run time: PlantSimulator.set_parameters, 10 s after the start)
  and on the foreign drives (foreign_drives/, an independent simulator: the drive's clean recording, then the
  same drive with the effect, joined at an onset event). Families the offline test does not detect at that
  strength (and a torque ripple, which the consistency views cannot see: diagnose finds it in the raw spectrum)
  are listed, not counted.
false_alarms: WARNs over >= 1 hour of clean drives across the nominal grid, own simulator and foreign drives
  each (the watch's core on the stream; a clean drive's backlash width also wears: own runs with a width that
  grows 10 % over the run are part of it), with the evaluations' smallest p-values.
null_*: the model's own statistics under the test, the reason for the alarm rule (_model_watch/null_stats.py): the
  reference's events left out seed by seed against Hotelling's expectation, their autocorrelation, and the share of
  a model stream's single events beyond chi^2's 1e-4 radius.
snapshot_diagnose_agreement: the model_watch node in a pipeline with an effect switched on mid-run writes its
  snapshot; `diagnose` on the snapshot and on a full 4 s recording of the same drive with the effect must name the
  same effect (scored like bench/workbench.py: the discovery or a flagged twin).
cpu_per_drive: the model_watch node's CPU share of one core while a 50 kHz drive streams (pipeline --watch,
  the node in its own process; /proc/PID/stat), beside the windowing node's in the same run.

    python bench/model_watch.py [--parts null clean detect snapshot cpu] [--quick | --long]
    python bench/model_watch.py --parts clean detect --traces-out traces.json    # the calibration's raw data

The alarm rule is the packaged one (config/model_watch.yaml); --rule VIEW_P,RATIO,PERSISTENCE tries another on
the same evaluations (the evaluations do not depend on the rule).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from dataclasses import replace

import numpy as np

os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.setdefault("ROS_DOMAIN_ID", str(os.getpid() % 90 + 5))
os.environ.setdefault("NUMBA_NUM_THREADS", "1")

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))


def log(*args):
    print(*args, file=sys.stderr, flush=True)


# the nominal grid of the clean drives: corners and middle of the paper's grid (widths 2.5-10 mm, eta_k
# 0.0125-0.05 Pa*s^n, n1 0.89-0.97)
CLEAN_GRID = [(0.0025, 0.0125, 0.89), (0.0025, 0.05, 0.97), (0.00375, 0.025, 0.93), (0.005, 0.025, 0.89),
              (0.005, 0.05, 0.95), (0.0075, 0.0375, 0.91), (0.009, 0.0125, 0.97), (0.01, 0.05, 0.89)]
DETECT_GRID = [(0.005, 0.025, 0.89), (0.0075, 0.025, 0.89)]
# own simulator: per catalogue family a strength (the workbench bench's one-effect rows where it has one,
# else the foreign suite's strength of that family): {label: {"effect.param": value}}
OWN_FAMILIES = {
    "wheel_coulomb_friction_1.0Nm": {"wheel_coulomb_friction.torque_Nm": 1.0},
    "wheel_viscous_friction_0.008": {"wheel_viscous_friction.damping_Nms_per_rad": 0.008},
    "wheel_stribeck_friction_1.4Nm": {"wheel_stribeck_friction.excess_torque_Nm": 1.4},
    "motor_coulomb_friction_1.8Nm": {"motor_coulomb_friction.torque_Nm": 1.8},
    "motor_load_offset_0.1pu": {"motor_load_offset.load_pu": 0.1},
    "mass_force_offset_20N": {"mass_force_offset.force_N": 20.0},
    "clutch_contact_stiffness_-0.3": {"clutch_contact_stiffness.relative_change": -0.3},
    "clutch_contact_damping_+0.6": {"clutch_contact_damping.relative_change": 0.6},
    "shaft_compliance_1.1e-4": {"shaft_compliance.compliance_rad_per_Nm": 1.1e-4},
    "load_mass_drift_+0.2": {"load_mass_drift.relative_change": 0.2},
    "wheel_inertia_drift_+0.3": {"wheel_inertia_drift.relative_change": 0.3},
    "spring_stiffness_drift_+0.5": {"spring_stiffness_drift.relative_change": 0.5},
    "absorber_consistency_drift_+0.5": {"absorber_consistency_drift.relative_change": 0.5},
    "absorber_flow_index_drift_+0.05": {"absorber_flow_index_drift.change": 0.05},
    "working_resistance_drift_+0.4": {"working_resistance_drift.relative_change": 0.4},
    "pulse_amplitude_drift_-0.15": {"pulse_amplitude_drift.relative_change": -0.15},
    "accelerometer_gain_a2_-0.2": {"accelerometer_gain.a2_relative_change": -0.2},
    "accelerometer_bias_a2_+2": {"accelerometer_bias.a2_m_s2": 2.0},
    "accelerometer_lowpass_a2_600Hz": {"accelerometer_lowpass.a2_time_constant_s": 2.65e-4},
    "torque_ripple_0.25_x6": {"torque_ripple.amplitude_pu": 0.25, "torque_ripple.order": 6.0},
}
SWITCH_AT_S = 10.0          # own detection runs: the effect switches on here
TRACE_RULE = None           # set in main: view_p 1e-3, ratio 2.5, persistence never
AFTER_S = 30.0              # ... and the run goes on this long (120 onsets)
RECORD_MEAN = ("a1", "a2", "omega1")   # the watch's record-mean signals (the node's watch_omega1; --no-omega1: a1, a2)


def family_of(label: str) -> str:
    from backlash_monitor.plant.effects import CATALOGUE_NAMES
    return next(n for n in sorted(CATALOGUE_NAMES, key=len, reverse=True) if label.startswith(n))


def reference_for(width_m, eta_k, n1):
    from backlash_monitor.workbench import reference
    from backlash_monitor.workbench.model import load_model
    model = load_model(None, width_m=width_m, eta_k=eta_k, n1=n1)
    return reference.cached(model, log=log)


# ------------------------------------------------------------------------------------------------ traces

def trace_of(updates, switch_index=None) -> dict:
    """What the rule is applied to: per evaluation its entry, smallest alarm-view p-value and residual ratio, and
    for a window that exceeds the loose TRACE_RULE the same of each leave-one-out window (the robust rule)."""
    from backlash_monitor.watch.alarm import ALARM_VIEWS
    return {"entry": [int(u.entry_sample_index) for u in updates], "p_min": [float(u.p_min) for u in updates],
            "ratio": [float(u.evaluation.result.residual_over_noise) for u in updates],
            "loo": [[[float(p), float(r)] for p, r in u.loo] for u in updates],
            "views": [{n: round(v.t2, 2) for n, v in u.evaluation.result.views.items()} if u.exceeding else None
                      for u in updates],
            "width_m": [float(u.evaluation.width_m) for u in updates], "switch": switch_index,
            # every evaluation's T^2 per alarm view and the views' dimensions: the statistic's series (the rule's
            # calibration reads its distribution and its run lengths from these)
            "t2": {n: [float(u.evaluation.result.views[n].t2) for u in updates] for n in ALARM_VIEWS
                   if updates and n in updates[0].evaluation.result.views},
            "dims": {n: [int(u.evaluation.result.views[n].dimension) for u in updates] for n in ALARM_VIEWS
                     if updates and n in updates[0].evaluation.result.views}}


def tracing_watch(ref):
    """A watch whose evaluations the traces record: the rule loose enough that every window a rule to be scored
    could call exceeding gets its leave-one-out windows computed, and it never goes WARN (a WARN stops them)."""
    from backlash_monitor.watch.core import ModelWatch
    return ModelWatch(ref, rule=TRACE_RULE, record_mean=RECORD_MEAN)


def stream(watch, signals: dict, chunk: int = 1000) -> list:
    out = []
    n = len(signals["a1"])
    for k in range(0, n, chunk):
        out += watch.feed(k, signals["a1"][k:k + chunk], signals["a2"][k:k + chunk],
                          signals["angle_difference"][k:k + chunk], signals["omega1"][k:k + chunk])
    return out


def clean_own(seconds_per_point: float, widen: bool = True) -> list:
    """Own simulator, one batch: every CLEAN_GRID point on its own seed for ``seconds_per_point``; with
    ``widen`` a second batch whose backlash width grows by 10 % over the run (wear: the measurand)."""
    from backlash_monitor.plant import PlantSimulator, Scenario
    from backlash_monitor.workbench import plant_adapter
    from backlash_monitor.workbench.model import load_model
    traces = []
    for wear in ((False, True) if widen else (False,)):
        refs = [reference_for(*g) for g in CLEAN_GRID]
        watches = [tracing_watch(r) for r in refs]
        scen = [Scenario(width_m=w, eta_k=e, n1=n, seed=700 + i + 50 * wear) for i, (w, e, n) in enumerate(CLEAN_GRID)]
        cfg = load_model(None).plant_config({"effects.backlash_width_drift": True} if wear else None)
        sim = PlantSimulator(scen, config=cfg, outputs=("a1", "a2", "angle_difference", "omega1"))
        ups = [[] for _ in scen]
        n_chunks = int(round(seconds_per_point / 0.02))
        t0 = time.perf_counter()
        for c in range(n_chunks):
            if wear and c % 50 == 0:     # +10 % of the nominal width over the run, in 1 s steps
                frac = 0.1 * c / n_chunks
                sim.set_parameters({"backlash_width_drift.change": np.array([frac * s.width_m for s in scen])})
            ch = sim.run(1000)
            for i, w in enumerate(watches):
                ups[i] += w.feed(ch.first_sample_index, ch.a1[i], ch.a2[i], ch.angle_difference[i], ch.omega1[i])
            if c % 1500 == 0:
                log(f"clean own{' (wear)' if wear else ''}: {c * 0.02:.0f} of {seconds_per_point:.0f} s "
                    f"({time.perf_counter() - t0:.0f} s)")
        for g, u in zip(CLEAN_GRID, ups):
            traces.append({"source": "own", "grid": g, "wear": wear, **trace_of(u)})
    del plant_adapter
    return traces


FOREIGN_NUISANCE = ("none", "NOISY_ADC16", "ENCODERS_14BIT", "ADC16")


def foreign_spec(label, width, eta, n1, seed, duration_s, effects=(), sensor="none", first_s=0.05):
    from foreign_drives import suites
    from foreign_drives.spec import RecordingSpec, SensorNuisance
    nuisance = SensorNuisance() if sensor == "none" else getattr(suites, sensor)
    return RecordingSpec(label=label, kind="clean" if not effects else "one", width_m=width, eta_k=eta, n1=n1,
                         effects=tuple(effects), duration_s=duration_s, seed=seed, sensor=nuisance,
                         pulse_first_s=first_s).check()


def clean_foreign(recordings_per_point: int, seconds: float) -> list:
    """Foreign drives: per CLEAN_GRID point ``recordings_per_point`` clean recordings of ``seconds`` (the sensor
    nuisance varies: white noise + 16-bit ADC, 14-bit encoders, ADC only, none)."""
    from foreign_drives.drive import make_recording
    traces = []
    for gi, g in enumerate(CLEAN_GRID):
        ref = reference_for(*g)
        for j in range(recordings_per_point):
            sensor = FOREIGN_NUISANCE[(gi + j) % len(FOREIGN_NUISANCE)]
            spec = foreign_spec(f"clean_{gi}_{j}", *g, seed=8000 + 37 * gi + j, duration_s=seconds, sensor=sensor,
                                first_s=round((0.05 + 0.031 * j) % 0.25, 4))
            rec = make_recording(spec)
            u = stream(tracing_watch(ref), rec.signals)
            traces.append({"source": "foreign", "grid": g, "sensor": sensor, **trace_of(u)})
            del rec
        log(f"clean foreign: grid point {gi + 1} of {len(CLEAN_GRID)}")
    return traces


def detect_own(seeds=(0, 1)) -> list:
    """Own simulator: every OWN_FAMILIES effect switched on at SWITCH_AT_S (all effects on from the start at their
    neutral defaults, as the workbench runs them); per DETECT_GRID point and seed. Also the offline check: the
    consistency test at diagnose's 1 % level on a 4 s recording with the effect (the same nominal, another seed)."""
    from backlash_monitor.plant import PlantSimulator, Scenario
    from backlash_monitor.workbench import plant_adapter, reference, synthetic
    from backlash_monitor.workbench.model import load_model
    out = []
    labels = list(OWN_FAMILIES)
    for g in DETECT_GRID:
        ref = reference_for(*g)
        model = load_model(None, width_m=g[0], eta_k=g[1], n1=g[2])
        offline = {}
        for lab in labels:
            over = plant_adapter.config_overrides(OWN_FAMILIES[lab])
            meas = synthetic.hidden_effect_recording(model, 4.0, 9100 + labels.index(lab), over)
            ev = ref.evaluate(reference.evidence_from_measurement(meas, ref), profile_width=False)
            offline[lab] = {"detected_offline": not ev.consistent,
                            "views_outside": [n for n, v in ev.result.views.items() if v.outside_band],
                            "residual_over_noise": ev.result.residual_over_noise}
        switches = {f"effects.{n}": True for n in plant_adapter.candidate_effect_names(model.catalogue,
                                                                                         not_event_locked=True)}
        cfg = model.plant_config(switches)
        scen = [Scenario(width_m=g[0], eta_k=g[1], n1=g[2], seed=900 + s) for s in seeds for _ in labels]
        sim = PlantSimulator(scen, config=cfg, outputs=("a1", "a2", "angle_difference", "omega1"))
        watches = [tracing_watch(ref) for _ in scen]
        ups = [[] for _ in scen]
        switch = int(round(SWITCH_AT_S / sim.sample_period_s))
        for c in range(int(round((SWITCH_AT_S + AFTER_S) / 0.02))):
            if c * 1000 == switch:
                params = {}
                keys = sorted({k for v in OWN_FAMILIES.values() for k in v})
                for k in keys:
                    cur = sim.parameter_values(k)
                    params[k] = np.array([OWN_FAMILIES[labels[i % len(labels)]].get(k, cur[i])
                                          for i in range(len(scen))])
                sim.set_parameters(params)
            ch = sim.run(1000)
            for i, w in enumerate(watches):
                ups[i] += w.feed(ch.first_sample_index, ch.a1[i], ch.a2[i], ch.angle_difference[i], ch.omega1[i])
        for i, u in enumerate(ups):
            lab = labels[i % len(labels)]
            out.append({"source": "own", "grid": g, "label": lab, "family": family_of(lab),
                        "seed": seeds[i // len(labels)], **offline[lab], **trace_of(u, switch)})
        log(f"detect own: grid point {g} done")
    return out


def events_of(signals: dict, dt: float, period: int) -> list:
    from backlash_monitor.watch.events import LiveEvents
    live = LiveEvents(dt, period, dc_names=RECORD_MEAN)
    out = []
    n = len(signals["a1"])
    for k in range(0, n, 1000):
        out += live.feed(k, signals["a1"][k:k + 1000], signals["a2"][k:k + 1000],
                         signals["angle_difference"][k:k + 1000], signals["omega1"][k:k + 1000])
    return out


def detect_foreign() -> list:
    """Foreign drives: every one-effect row of the foreign bench suite (its form, strength, nominal and sensor
    chain): the clean drive's events (8 s), then the drive with the effect (8 s), joined at an onset event; and the
    offline check on the effect recording's first 4 s."""
    from foreign_drives import suites
    from foreign_drives.drive import make_recording
    from backlash_monitor.workbench import reference
    from backlash_monitor.workbench.measurement import Measurement
    out = []
    rows = [s for s in suites.BENCH if s.kind == "one"]
    for spec in rows:
        g = (spec.width_m, spec.eta_k, spec.n1)
        ref = reference_for(*g)
        clean = make_recording(replace(spec, label=spec.label + "_clean", kind="clean", effects=(), duration_s=8.0))
        eff = make_recording(replace(spec, duration_s=8.0, seed=spec.seed + 1))
        n4 = int(round(4.0 / eff.sample_period_s))
        meas = Measurement(spec.label, eff.sample_period_s, {k: v[:n4] for k, v in eff.signals.items()})
        ev = ref.evaluate(reference.evidence_from_measurement(meas, ref), profile_width=False)
        watch = tracing_watch(ref)
        ev_clean = events_of(clean.signals, clean.sample_period_s, ref.pulse_period_samples)
        ev_eff = events_of(eff.signals, eff.sample_period_s, ref.pulse_period_samples)
        ups = []
        for e in ev_clean:
            u = watch.add_event(e)
            if u is not None:
                ups.append(u)
        shift = (ev_clean[-1].entry_sample_index + ref.pulse_period_samples) - ev_eff[0].entry_sample_index
        switch = ev_eff[0].entry_sample_index + shift
        for e in ev_eff:
            e.entry_sample_index += shift
            u = watch.add_event(e)
            if u is not None:
                ups.append(u)
        fam = spec.truth().families[0]
        out.append({"source": "foreign", "grid": g, "label": spec.label, "family": fam,
                    "detected_offline": not ev.consistent,
                    "views_outside": [n for n, v in ev.result.views.items() if v.outside_band],
                    "residual_over_noise": ev.result.residual_over_noise, **trace_of(ups, switch)})
        log(f"detect foreign: {spec.label} ({fam}): offline {'detected' if not ev.consistent else 'not detected'}")
    return out


# ------------------------------------------------------------------------------------------------ the rule

def apply_rule(trace: dict, rule) -> dict:
    """The alarm rule over one trace: WARN transitions, and the onsets from the switch to the first WARN."""
    from backlash_monitor.watch.alarm import AlarmState
    state = AlarmState(rule)
    warns, first_warn = 0, None
    for i, (e, p, r, loo) in enumerate(zip(trace["entry"], trace["p_min"], trace["ratio"], trace["loo"])):
        exceeding = p < rule.view_p or r > rule.residual_ratio
        if exceeding and rule.robust and state.level == "OK":
            exceeding = bool(loo) and all(pl < rule.view_p or rl > rule.residual_ratio for pl, rl in loo)
        if state.update(exceeding, e) and state.level == "WARN":
            warns += 1
            if first_warn is None:
                first_warn = i
    out = {"warns": warns}
    if trace.get("switch") is not None:
        sw = trace["switch"]
        warned_before = first_warn is not None and trace["entry"][first_warn] < sw
        out["warned_before_switch"] = bool(warned_before)
        # onsets from the switch: every onset entry at or after it, up to the one whose evaluation said WARN
        out["onsets_to_warn"] = (None if first_warn is None or warned_before
                                 else sum(1 for e in trace["entry"][:first_warn + 1] if e >= sw))
    return out


def summarize(clean: list, detect: list, rule) -> dict:
    out = {}
    if clean:
        for src in ("own", "foreign"):
            tr = [t for t in clean if t["source"] == src]
            if not tr:
                continue
            n_eval = sum(len(t["entry"]) for t in tr)
            hours = n_eval * 0.25 / 3600.0
            res = [apply_rule(t, rule) for t in tr]
            out[f"false_alarms_{src}"] = int(sum(r["warns"] for r in res))
            out[f"clean_hours_{src}"] = round(hours, 3)
            out[f"clean_evaluations_{src}"] = n_eval
            pm = np.concatenate([t["p_min"] for t in tr])
            rr = np.concatenate([t["ratio"] for t in tr])
            out[f"clean_p_min_smallest_{src}"] = float(pm.min())
            out[f"clean_ratio_largest_{src}"] = float(rr.max())
            out[f"clean_exceeding_evaluations_{src}"] = int(np.sum((pm < rule.view_p) | (rr > rule.residual_ratio)))
            worn = [t for t in tr if t.get("wear")]
            if worn:
                out[f"false_alarms_{src}_width_wear"] = int(sum(apply_rule(t, rule)["warns"] for t in worn))
        out["false_alarms"] = int(sum(v for k, v in out.items() if k in ("false_alarms_own", "false_alarms_foreign")))
    if detect:
        for src in ("own", "foreign"):
            tr = [t for t in detect if t["source"] == src]
            if not tr:
                continue
            per = {}
            for t in tr:
                r = apply_rule(t, rule)
                per.setdefault(t["label"], []).append({"onsets": r["onsets_to_warn"], "offline": t["detected_offline"],
                                                       "before_switch": r["warned_before_switch"],
                                                       "family": t["family"]})
            counted, not_counted, per_family = [], {}, {}
            for lab, runs in per.items():
                fam = runs[0]["family"]
                ons = [r["onsets"] for r in runs]
                per_family[lab] = {"family": fam, "onsets_to_warn": ons,
                                   "detected_offline": all(r["offline"] for r in runs)}
                if fam == "torque_ripple":
                    not_counted[lab] = "a torque ripple is not locked to the events: the consistency views cannot see it"
                elif fam is None or fam == "backlash_width_drift":
                    not_counted[lab] = "the width is the measurand, not an effect"
                elif not all(r["offline"] for r in runs):
                    not_counted[lab] = "not detected offline on a 4 s recording at this strength"
                else:
                    counted += [o if o is not None else math.inf for o in ons]
            median = float(np.median(counted)) if counted else None
            out[f"detection_onsets_median_{src}"] = median if median is not None and math.isfinite(median) else None
            # the slowest detection among the runs that warned (a missed run is counted in detection_missed_*; an
            # infinity is not JSON)
            warned = [c for c in counted if c != math.inf]
            out[f"detection_onsets_max_{src}"] = float(np.max(warned)) if warned else None
            out[f"detection_missed_{src}"] = int(sum(1 for c in counted if c == math.inf))
            out[f"detection_runs_counted_{src}"] = len(counted)
            out[f"detection_per_effect_{src}"] = per_family
            out[f"detection_not_counted_{src}"] = not_counted
        meds = [out.get(f"detection_onsets_median_{s}") for s in ("own", "foreign")]
        meds = [m for m in meds if m is not None]
        out["detection_onsets_median"] = max(meds) if meds else None
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--parts", nargs="+", default=["null", "clean", "detect", "snapshot", "cpu"],
                    choices=["null", "clean", "detect", "snapshot", "cpu"])
    ap.add_argument("--quick", action="store_true", help="a smoke run: a few minutes of clean drives, one effect "
                                                          "per family and seed, one snapshot")
    ap.add_argument("--long", action="store_true", help="the goal's length: 2 h of clean own drives (8 grid points x "
                                                         "450 s, with and without width wear) and 64 min of clean "
                                                         "foreign drives, two seeds per effect (its clean part: ~7 "
                                                         "min at load ~1; the default: 32 + 16 min, one seed; "
                                                         "clean + detect ~8 min, the three snapshots ~6 min)")
    ap.add_argument("--traces-out", default="", help="write the per-evaluation traces (JSON)")
    ap.add_argument("--traces-in", default="", help="traces written by --traces-out: re-scored, and the parts they "
                                                    "hold are not simulated again")
    ap.add_argument("--rule", default="", metavar="VIEW_P,RATIO,PERSISTENCE[,ROBUST[,CLIP_P[,PREDICTIVE]]]",
                    help="score another alarm rule on the same evaluations (view_p >= 1e-3 and ratio >= 2.5: the "
                         "traces hold the leave-one-out windows of what exceeds those). CLIP_P ('none': no "
                         "clipping) and PREDICTIVE (0: chi^2 p-values) change the evaluations themselves: not with "
                         "--traces-in of other ones")
    ap.add_argument("--no-omega1", action="store_true", help="the watch's record mean without the motor speed omega1 "
                                                              "(a1 and a2 only: the node's watch_omega1 false)")
    args = ap.parse_args()
    from backlash_monitor.watch.alarm import AlarmRule, load_rule
    global TRACE_RULE, RECORD_MEAN
    if args.no_omega1:
        RECORD_MEAN = ("a1", "a2")
    rule = load_rule()
    if args.rule:
        parts = args.rule.split(",")
        rule = replace(rule, view_p=float(parts[0]), residual_ratio=float(parts[1]), persistence=int(parts[2]),
                       robust=(parts[3].lower() not in ("0", "false", "no")) if len(parts) > 3 else rule.robust
                       ).check()
        if len(parts) > 4:
            rule = replace(rule, event_clip_p=None if parts[4].lower() == "none" else float(parts[4])).check()
        if len(parts) > 5:
            rule = replace(rule, predictive=parts[5].lower() not in ("0", "false", "no")).check()
    # the traced evaluations: the rule's clipping and law, loose enough that every window a rule to be scored could
    # call exceeding has its leave-one-out windows, and never WARN (a WARN stops them)
    TRACE_RULE = replace(rule, view_p=1e-3, residual_ratio=2.5, persistence=10 ** 9, clear_after=1, robust=True)
    t0 = time.perf_counter()
    result = {"rule": {"view_p": rule.view_p, "residual_ratio": rule.residual_ratio,
                       "persistence": rule.persistence, "clear_after": rule.clear_after, "robust": rule.robust,
                       "event_clip_p": rule.event_clip_p, "predictive": rule.predictive},
              "record_mean": list(RECORD_MEAN)}
    data = {"clean": [], "detect": []}
    if args.traces_in:
        with open(args.traces_in) as f:
            data.update(json.load(f))

    def save():
        if args.traces_out:
            with open(args.traces_out, "w") as f:
                json.dump(data, f)
    size = "quick" if args.quick else "long" if args.long else "default"
    own_s, foreign_n, foreign_s, seeds = {"quick": (20.0, 1, 20.0, (0,)), "default": (120.0, 2, 60.0, (0,)),
                                          "long": (450.0, 8, 60.0, (0, 1))}[size]
    result["size"] = size
    runs = {"clean_own": lambda: clean_own(own_s),
            "clean_foreign": lambda: clean_foreign(foreign_n, foreign_s),
            "detect_own": lambda: detect_own(seeds=seeds),
            "detect_foreign": detect_foreign}
    for part, fn in runs.items():
        kind, source = part.split("_")
        if kind not in args.parts or any(t["source"] == source for t in data[kind]):
            continue               # not asked for, or already in --traces-in
        data[kind] += fn()
        save()
    clean, detect = data["clean"], data["detect"]
    result.update(summarize(clean, detect, rule))
    if "null" in args.parts:
        from _model_watch.null_stats import null_statistics
        result.update(null_statistics(CLEAN_GRID, reference_for, stream_s=20.0 if args.quick else 60.0, log=log))
    if "snapshot" in args.parts:
        from _model_watch.snapshot import snapshot_agreement
        result.update(snapshot_agreement(quick=args.quick, log=log))
    if "cpu" in args.parts:
        from _model_watch.cpu import cpu_per_drive
        result.update(cpu_per_drive(log=log))
    result["seconds"] = round(time.perf_counter() - t0, 1)
    print(json.dumps(result, default=float))
    del AlarmRule
    return 0


if __name__ == "__main__":
    sys.exit(main())
