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
Goal: realtime_factor >= 200, speedup_vs_solve_ivp >= 50, max_rel_error <= 0.005.
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

    return {
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
        "goal_met": bool(rtf >= 200 and speedup >= 50 and max(errs) <= 0.005),
        "cpu": platform.processor() or platform.machine(),
        "load_average_1min": round(os.getloadavg()[0], 2),
    }


if __name__ == "__main__":
    print(json.dumps(main()))
