"""Benchmark of the plant simulator on one core; prints ONE JSON object (not a test).

- realtime_factor: simulated seconds across all scenarios per wall second, for the 120 grid scenarios
  plus the 30 pattern scenarios (eta_k = 0.025, 5 n1 x 6 widths, seed 1), 1 s each with noise, the
  numba RK4 kernel (the settled start's run-in is timed separately: settle_wall_s), recording the
  outputs the pipeline uses (PIPELINE_OUTPUTS: a1, a2, omega1, omega2, angle_difference) and the entries;
  realtime_factor_all_outputs: the same with all eight outputs recorded (0.2 s, scaled).
- realtime_factor_numba_scalar / realtime_factor_numpy: the other two backends (short runs, scaled).
- speedup_vs_solve_ivp: the same model and the same noisy run integrated by scipy's solve_ivp RK45
  (rtol 1e-6, atol 1e-9, restarted at every change of the held inputs) on a sample of scenarios,
  compared per scenario-second with the numba kernel.
- max_rel_error: noise-free, max over every 2048-sample entry window and over a1 and a2 of
  max|RK4 - reference| / max|reference|, against solve_ivp DOP853 at rtol 1e-9 (widths x fluid corners).
- plugin_vs_builtin_speed: realtime factor of the numba kernel with a user's plug-in effect loaded from a file
  (docs/examples/my_effects.py: my_viscous_wheel) over the same term built in (wheel_viscous_friction),
  150 scenarios, 0.1 s chunks, interleaved, best of 3 each.
- catalogue_backend_max_rel_diff: every catalogue effect on with parameters away from neutral, 4 scenarios,
  0.5 s with noise: numba vs numba-scalar vs numpy, max over a1, a2, omega2, angle_difference of
  max|x - y| / max|y|.
- compile_seconds_*: generating and compiling the kernels (SIMD + scalar) of an effect set in a fresh
  process and a fresh cache (cold), and loading them again from numba's cache (warm);
  simd_stage_vector_ops: <8 x double> / <4 x double> operations in the compiled SIMD loop's LLVM IR (its stages inlined).
Goal: realtime_factor >= 200, speedup_vs_solve_ivp >= 50, max_rel_error <= 0.005, numba_vs_numpy >= 20,
plugin_vs_builtin_speed >= 0.5, catalogue_backend_max_rel_diff <= 1e-6.
"""
from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ[_var] = "1"

import json  # noqa: E402
import platform  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

import numpy as np  # noqa: E402

from backlash_monitor.plant import (K2_WIDTHS_M, PlantSimulator, Scenario, grid_scenarios,  # noqa: E402
                                    load_plant_config, pattern_scenarios)
from backlash_monitor.plant.reference import reference_run  # noqa: E402


PIPELINE_OUTPUTS = ("a1", "a2", "omega1", "omega2", "angle_difference")
ROOT = Path(__file__).resolve().parents[1]
EXAMPLE_EFFECTS = ROOT / "docs" / "examples" / "my_effects.py"

# parameters away from neutral for the catalogue agreement run (moderate: the drive still works)
CATALOGUE_PARAMETERS = {
    "wheel_coulomb_friction.torque_Nm": 0.5, "wheel_viscous_friction.damping_Nms_per_rad": 0.002,
    "wheel_stribeck_friction.excess_torque_Nm": 0.5, "wheel_stribeck_friction.stribeck_speed_rad_s": 150.0,
    "motor_coulomb_friction.torque_Nm": 0.3, "clutch_contact_stiffness.relative_change": 0.2,
    "clutch_contact_damping.relative_change": 0.3, "shaft_compliance.compliance_rad_per_Nm": 5e-5,
    "mass_force_offset.force_N": 3.0, "motor_load_offset.load_pu": 0.02, "torque_ripple.amplitude_pu": 0.02,
    "torque_ripple.order": 6.0, "torque_ripple.phase_rad": 0.5, "accelerometer_bias.a1_m_s2": 0.1,
    "accelerometer_gain.a2_relative_change": 0.05, "accelerometer_lowpass.a1_time_constant_s": 5e-5,
    "backlash_width_drift.change": 0.0005, "absorber_consistency_drift.relative_change": 0.1,
    "absorber_flow_index_drift.change": 0.02, "spring_stiffness_drift.relative_change": 0.1,
    "load_mass_drift.relative_change": 0.05, "wheel_inertia_drift.relative_change": 0.05,
    "working_resistance_drift.relative_change": 0.05, "pulse_amplitude_drift.relative_change": -0.05,
    "rotor_resistance_drift.relative_change": 0.1, "supply_voltage_drift.relative_change": -0.03,
}


def _probe(names, cache_dir, files=()):
    import subprocess
    env = dict(os.environ, BACKLASH_MONITOR_KERNEL_CACHE=str(cache_dir), PROBE_EFFECTS_FILES=";".join(map(str, files)))
    t0 = time.perf_counter()
    r = subprocess.run([sys.executable, str(ROOT / "bench" / "_effects" / "compile_probe.py"), ",".join(names)],
                       env=env, capture_output=True, text=True, check=True)
    out = json.loads(r.stdout.strip().splitlines()[-1])
    out["process_s"] = time.perf_counter() - t0
    return out


def effects_figures(scenarios) -> dict:
    """The plug-in/effect figures (docs/effects.md)."""
    import tempfile
    from backlash_monitor.plant.catalogue import builtin_catalogue
    from backlash_monitor.plant.effects import CATALOGUE
    with_plugins = builtin_catalogue().with_files([EXAMPLE_EFFECTS])
    base = {"simulation.run_in_s": 0.0}
    cfgs = {"builtin": load_plant_config(overrides={**base, "effects.wheel_viscous_friction": True,
                                                    "wheel_viscous_friction.damping_Nms_per_rad": 0.002}),
            "plugin": load_plant_config(overrides={**base, "effects.my_viscous_wheel": True,
                                                   "my_viscous_wheel.damping_Nms_per_rad": 0.002},
                                        catalogue=with_plugins)}
    sims = {k: PlantSimulator(scenarios, config=c, noise=True, backend="numba", outputs=PIPELINE_OUTPUTS)
            for k, c in cfgs.items()}
    for s_ in sims.values():
        s_.run(100)
    best = {k: float("inf") for k in sims}
    for _ in range(3):
        for k, s_ in sims.items():
            t0 = time.perf_counter()
            s_.run(5000)
            best[k] = min(best[k], time.perf_counter() - t0)
    plugin_speed = best["builtin"] / best["plugin"]

    # every catalogue effect on, parameters away from neutral: the three backends against each other
    all_on = {f"effects.{c.name}": True for c in CATALOGUE}
    cfg_all = load_plant_config(overrides={"simulation.run_in_s": 0.5, **all_on})
    scen4 = [Scenario(w, e, n1, seed=5) for (w, e, n1) in ((0.0025, 0.025, 0.89), (0.005, 0.0125, 0.93),
                                                            (0.0075, 0.05, 0.97), (0.01, 0.025, 0.91))]
    runs = {}
    for b in ("numba", "numba-scalar", "numpy"):
        sim = PlantSimulator(scen4, config=cfg_all, noise=True, backend=b, parameters=CATALOGUE_PARAMETERS,
                             noise_seed=7)
        runs[b] = sim.run(25_000)
    diffs = {}
    for a, b in (("numba", "numba-scalar"), ("numba", "numpy"), ("numba-scalar", "numpy")):
        diffs[f"{a}_vs_{b}"] = max(float(np.max(np.abs(getattr(runs[a], s) - getattr(runs[b], s)))
                                         / np.max(np.abs(getattr(runs[b], s))))
                                   for s in ("a1", "a2", "omega2", "angle_difference"))
    entries_equal = runs["numba"].entries == runs["numpy"].entries == runs["numba-scalar"].entries

    # compile cost of a new effect set, cold (fresh process + fresh cache) and warm (cache filled)
    nominal = []
    catalogue_terms = [c.name for c in CATALOGUE if c.kind == "term"]
    one_more = ["wheel_coulomb_friction"]
    comp = {}
    with tempfile.TemporaryDirectory() as d:
        for label, names, files in (("nominal", nominal, ()), ("nominal_plus_one", one_more, ()),
                                    ("catalogue", catalogue_terms, ()),
                                    ("plugin", ["my_viscous_wheel"], (EXAMPLE_EFFECTS,))):
            cold = _probe(names, Path(d) / label, files)
            warm = _probe(names, Path(d) / label, files)
            comp[label] = (cold, warm)
    return {
        "plugin_vs_builtin_speed": round(plugin_speed, 3),
        "plugin_run_s": round(best["plugin"], 3), "builtin_run_s": round(best["builtin"], 3),
        "catalogue_backend_max_rel_diff": float(f"{max(diffs.values()):.3g}"),
        "catalogue_backend_rel_diffs": {k: float(f"{v:.3g}") for k, v in diffs.items()},
        "catalogue_entries_equal": entries_equal,
        "compile_seconds": round(comp["nominal_plus_one"][0]["simd_s"] + comp["nominal_plus_one"][0]["scalar_s"], 2),
        "compile_seconds_detail": {k: {"cold_simd_s": round(c["simd_s"], 2), "cold_scalar_s": round(c["scalar_s"], 2),
                                       "warm_simd_s": round(w["simd_s"], 2), "warm_scalar_s": round(w["scalar_s"], 2),
                                       "cold_process_s": round(c["process_s"], 2)}
                                   for k, (c, w) in comp.items()},
        "simd_stage_vector_ops": {k: c["vector_ops"] for k, (c, _) in comp.items()},
    }


def main() -> dict:
    cfg = load_plant_config()
    fs = cfg.simulation.sample_rate_hz
    scenarios = grid_scenarios(seeds=(0,)) + pattern_scenarios(seeds=(1,))
    duration_s = 1.0
    n = int(duration_s * fs)

    # compile / load the cached kernel outside the timing
    PlantSimulator(scenarios[:1], config=cfg.with_overrides({"simulation.run_in_s": 0.0}), noise=True).run(10)

    t0 = time.perf_counter()
    sim = PlantSimulator(scenarios, config=cfg, noise=True, backend="numba", outputs=PIPELINE_OUTPUTS)
    settle_wall = time.perf_counter() - t0
    # streamed as the ROS node does it: 0.1 s chunks (bounded memory)
    run_wall = 0.0
    entries = [[] for _ in scenarios]
    for _ in range(10):
        t0 = time.perf_counter()
        ch = sim.run(n // 10)
        run_wall += time.perf_counter() - t0
        for i, e in enumerate(ch.entries):
            entries[i].extend(e)
    scen_seconds = len(scenarios) * duration_s
    rtf = scen_seconds / run_wall
    entries_ok = all(sorted(k for _, k in e) == ["onset"] * 4 + ["return"] * 4 for e in entries)

    cfg0 = cfg.with_overrides({"simulation.run_in_s": 0.0})
    # all eight outputs (alpha1, alpha2, transmitted_torque_Nm too): 0.2 s in 0.1 s chunks
    sim_all = PlantSimulator(scenarios, config=cfg0, noise=True, backend="numba")
    sim_all.run(10)
    t0 = time.perf_counter()
    for _ in range(2):
        sim_all.run(n // 10)
    rtf_all = len(scenarios) * 2 * (n // 10) / fs / (time.perf_counter() - t0)

    # numpy backend: same scheme vectorised over the scenarios, short run
    sim_np = PlantSimulator(scenarios, config=cfg0, noise=True, backend="numpy")
    n_np = 500
    t0 = time.perf_counter()
    sim_np.run(n_np)
    np_wall = time.perf_counter() - t0
    rtf_numpy = len(scenarios) * n_np / fs / np_wall

    # numba-scalar backend (scenarios outer, libm exp/log): 0.1 s
    sim_sc = PlantSimulator(scenarios, config=cfg0, noise=True, backend="numba-scalar")
    sim_sc.run(10)
    n_sc = 5000
    t0 = time.perf_counter()
    sim_sc.run(n_sc)
    sc_wall = time.perf_counter() - t0
    rtf_scalar = len(scenarios) * n_sc / fs / sc_wall

    # solve_ivp RK45 on the same noisy run, a sample of scenarios, 0.1 s each
    sample = [scenarios[i] for i in (2, 57, 119)]
    n_ivp = int(0.1 * fs)
    sim_s = PlantSimulator(sample, config=cfg, noise=True)
    x0 = sim_s.state.copy()
    load = sim_s.motor_load_pu(0, n_ivp)
    t0 = time.perf_counter()
    ivp = [reference_run(sim_s, i, load[i], method="RK45", rtol=1e-6, atol=1e-9, state0=x0[i]) for i in
           range(len(sample))]
    ivp_wall = time.perf_counter() - t0
    ivp_per_scen_s = ivp_wall / (len(sample) * n_ivp / fs)
    rk4_per_scen_s = run_wall / scen_seconds
    speedup = ivp_per_scen_s / rk4_per_scen_s
    # the RK45 run's own accuracy against the RK4 run on the same inputs
    sim_r = PlantSimulator(sample, config=cfg, noise=True)
    sim_r.state[:] = x0
    rk4_noisy = sim_r.run(n_ivp)
    rk45_vs_rk4 = max(float(np.max(np.abs(ivp[i][s] - getattr(rk4_noisy, s)[i])) / np.max(np.abs(ivp[i][s])))
                      for i in range(len(sample)) for s in ("a1", "a2"))

    # accuracy: noise-free against DOP853 rtol 1e-9, every entry window of 0.3 s (onset + return)
    acc_scen = [Scenario(w, e, n1) for (e, n1) in ((0.025, 0.89), (0.0125, 0.89), (0.05, 0.97)) for w in K2_WIDTHS_M]
    sim_a = PlantSimulator(acc_scen, config=cfg, noise=False)
    x0 = sim_a.state.copy()
    n_acc = 15_000
    load = sim_a.motor_load_pu(0, n_acc)
    t0 = time.perf_counter()
    refs = [reference_run(sim_a, i, load[i], method="DOP853", rtol=1e-9, atol=1e-12, state0=x0[i])
            for i in range(len(acc_scen))]
    ref_wall = time.perf_counter() - t0
    sim_a.state[:] = x0
    ch = sim_a.run(n_acc)
    errs = []
    for i, entries in enumerate(ch.entries):
        for k, _ in entries:
            for s in ("a1", "a2"):
                r = refs[i][s][k:k + 2048]
                errs.append(float(np.max(np.abs(getattr(ch, s)[i, k:k + 2048] - r)) / np.max(np.abs(r))))

    eff = effects_figures(scenarios)
    return {
        **eff,
        "scenarios": len(scenarios),
        "simulated_s_per_scenario": duration_s,
        "sample_rate_hz": fs,
        "backend": "numba",
        "run_wall_s": round(run_wall, 3),
        "settle_wall_s": round(settle_wall, 3),
        "settle_run_in_s": cfg.simulation.run_in_s,
        "outputs_recorded": list(PIPELINE_OUTPUTS),
        "realtime_factor": round(rtf, 1),
        "realtime_factor_incl_settle": round(len(scenarios) * (duration_s + cfg.simulation.run_in_s)
                                             / (run_wall + settle_wall), 1),
        "ns_per_scenario_step": round(run_wall / (len(scenarios) * n) * 1e9, 1),
        "realtime_factor_all_outputs": round(rtf_all, 1),
        "realtime_factor_numba_scalar": round(rtf_scalar, 1),
        "realtime_factor_numpy": round(rtf_numpy, 2),
        "numba_vs_numpy": round(rtf / rtf_numpy, 1),
        "speedup_vs_solve_ivp": round(speedup, 1),
        "solve_ivp_method": "RK45 rtol=1e-6 atol=1e-9, restarted at every held-input change (noise on)",
        "solve_ivp_scenarios": len(sample),
        "solve_ivp_s_per_scenario_second": round(ivp_per_scen_s, 3),
        "solve_ivp_rk45_vs_rk4_max_rel_diff": round(rk45_vs_rk4, 5),
        "max_rel_error": round(max(errs), 5),
        "max_rel_error_reference": "solve_ivp DOP853 rtol=1e-9 atol=1e-12, noise-free, 18 scenarios, "
                                   f"{len(errs) // 2} windows",
        "reference_wall_s": round(ref_wall, 2),
        "entries_8_per_s_all_scenarios": entries_ok,
        "goal_met": bool(rtf >= 200 and speedup >= 50 and max(errs) <= 0.005 and rtf / rtf_numpy >= 20
                         and eff["plugin_vs_builtin_speed"] >= 0.5 and eff["catalogue_backend_max_rel_diff"] <= 1e-6),
        "cpu": platform.processor() or platform.machine(),
        "load_average_1min": round(os.getloadavg()[0], 2),
    }


if __name__ == "__main__":
    # no options: --help says what it measures instead of starting the run
    import argparse
    argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter).parse_args()
    print(json.dumps(main()))
