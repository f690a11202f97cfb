"""Property test of every compiled catalogue effect: random parameters inside its bounds (the others at their
neutral defaults, all compiled together: one kernel), the SIMD stage against the scalar right-hand side against
the numpy form, and the RK4 run against solve_ivp on the *nominal* model plus the effect's equation written
independently here (so an effect wrong in every generated backend is still caught)."""
import zlib

import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.codegen import kernel_for
from backlash_monitor.plant.drivetrain import clutch_torque
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.effects import CATALOGUE, NOMINAL
from backlash_monitor.plant.reference import reference_run

TERMS = [c for c in CATALOGUE if c.kind == "term"]
ALL_ON = {f"effects.{c.name}": True for c in CATALOGUE}
FLOORS = (("a1", 1.0), ("a2", 0.1), ("omega2", 1.0), ("angle_difference", 1e-3))   # signal scales
CFG = load_plant_config(overrides={"simulation.run_in_s": 0.0, **ALL_ON})
N = 4000        # 80 ms from the settled start: the first pulse (50 ms), its onset entry and far-side impact


def _sign(x):
    return np.sign(x)


def independent_form(name, values, cfg):
    """The effect's contribution to the 11 derivatives, from its equation (docs/effects.md), written here."""
    T_b, T_m = cfg.motor.base_torque_Nm, cfg.motor.mechanical_time_constant_s
    omb = cfg.motor.base_mechanical_speed_rad_s
    J2, m = cfg.load.wheel_inertia_kgm2, cfg.load.mass_kg
    kc, dc = cfg.clutch.contact_stiffness_Nm_per_rad, cfg.clutch.contact_damping_Nms_per_rad
    beta = values["beta"]
    p = {k.split(".", 1)[1]: v for k, v in values.items() if k.startswith(name + ".")}

    def wheel(torque):
        d = np.zeros(11)
        d[8] = torque / J2
        return d

    def motor(load_pu):
        d = np.zeros(11)
        d[4] = -load_pu / T_m
        return d

    def clutch(kc2, dc2):
        def f(y):
            rel = y[4] * omb - y[8]
            dT = clutch_torque(y[5], rel, beta, kc2, dc2) - clutch_torque(y[5], rel, beta, kc, dc)
            d = np.zeros(11)
            d[4] = -dT / T_b / T_m
            d[8] = dT / J2
            return d
        return f

    forms = {
        "wheel_coulomb_friction": lambda y: wheel(-p["torque_Nm"] * _sign(y[8])),
        "wheel_viscous_friction": lambda y: wheel(-p["damping_Nms_per_rad"] * y[8]),
        "wheel_stribeck_friction": lambda y: wheel(-p["excess_torque_Nm"]
                                                   * np.exp(-(y[8] / p["stribeck_speed_rad_s"]) ** 2) * _sign(y[8])),
        "motor_coulomb_friction": lambda y: motor(p["torque_Nm"] / T_b * _sign(y[4])),
        "motor_load_offset": lambda y: motor(p["load_pu"]),
        "torque_ripple": lambda y: motor(p["amplitude_pu"] * np.sin(p["order"] * y[6] + p["phase_rad"])),
        "mass_force_offset": lambda y: np.eye(11)[10] * p["force_N"] / m,
        "clutch_contact_stiffness": clutch(kc * (1 + p.get("relative_change", 0.0)), dc),
        "clutch_contact_damping": clutch(kc, dc * (1 + p.get("relative_change", 0.0))),
        "shaft_compliance": clutch(kc / (1 + kc * p.get("compliance_rad_per_Nm", 0.0)), dc),
    }
    return forms[name]


def test_every_compiled_catalogue_effect_has_an_independent_form_here():
    assert {c.name for c in TERMS} == {"wheel_coulomb_friction", "wheel_viscous_friction", "wheel_stribeck_friction",
                                       "motor_coulomb_friction", "motor_load_offset", "torque_ripple",
                                       "mass_force_offset", "clutch_contact_stiffness", "clutch_contact_damping",
                                       "shaft_compliance"}


def _random_parameters(effect) -> dict:
    rng = np.random.default_rng(zlib.crc32(effect.name.encode()))
    return {f"{effect.name}.{p.name}": float(rng.uniform(*p.bounds)) for p in effect.parameters}


@pytest.fixture(scope="module")
def runs():
    """Every term effect in one batch per backend: scenario i holds TERMS[i]'s random parameters, every other
    parameter at its neutral default. The parameters are per-scenario run-time values of the one kernel, so a
    scenario's run is the one it has alone (checked: bit for bit, on every backend); one batch costs the numpy
    backend, stepped in Python, what one scenario does."""
    scen = [Scenario(0.005, 0.025, 0.89)] * len(TERMS)
    neutral = PlantSimulator(scen[:1], config=CFG, noise=False)
    params = {}
    for i, effect in enumerate(TERMS):
        for key, value in _random_parameters(effect).items():
            params.setdefault(key, np.full(len(TERMS), neutral.parameter_values(key)[0]))[i] = value
    out = {}
    for backend in ("numba", "numba-scalar", "numpy"):
        sim = PlantSimulator(scen, config=CFG, noise=False, backend=backend, parameters=params)
        x0 = sim.state.copy()
        load = sim.motor_load_pu(0, N)
        out[backend] = sim.run(N)
    base = PlantSimulator(scen[:1], config=CFG, noise=False).run(N)
    return {"sim": sim, "x0": x0, "load": load, "out": out, "base": base}


@pytest.mark.parametrize("effect", TERMS, ids=lambda c: c.name)
def test_backends_and_solve_ivp_agree_with_random_parameters(effect, runs):
    i = TERMS.index(effect)
    params = _random_parameters(effect)
    sim, out = runs["sim"], runs["out"]
    for key, value in params.items():
        assert sim.parameter_values(key)[i] == value          # this scenario runs this effect's parameters
    for backend in ("numba-scalar", "numpy"):
        for sig, floor in FLOORS:
            a, b = getattr(out["numba"], sig)[i], getattr(out[backend], sig)[i]
            assert np.max(np.abs(a - b)) <= 1e-9 * max(np.max(np.abs(b)), floor), (backend, sig)
        assert out["numba"].entries[i] == out[backend].entries[i]
    values = {"beta": sim.beta[i], **{k: float(v) for k, v in params.items()}}
    nominal = kernel_for(tuple(c for c in NOMINAL if c.kind == "term"))
    ref = reference_run(sim, i, runs["load"][i], method="DOP853", rtol=1e-10, atol=1e-12, state0=runs["x0"][i],
                        rhs=nominal, extra=lambda t, y, der: independent_form(effect.name, values, CFG)(y))
    for sig, floor in FLOORS:     # the located zone crossing's accuracy (docs/model.md: <= 3e-5 of the peak)
        r, s = ref[sig], getattr(out["numba"], sig)[i]
        assert np.max(np.abs(s - r)) <= 2e-4 * max(np.max(np.abs(r)), floor), (sig, np.max(np.abs(s - r)))
    # the effect's own contribution (run minus nominal run) is matched to 2 % of its size: a wrong effect fails
    # even where it is small against the signal
    base = runs["base"]
    for sig in ("a1", "omega2"):
        size = np.max(np.abs(getattr(base, sig)[0] - ref[sig]))
        assert size > 1e-6, sig                                   # parameters away from neutral do something
        assert np.max(np.abs(getattr(out["numba"], sig)[i] - ref[sig])) <= 0.02 * size, sig


def test_whole_catalogue_at_neutral_defaults_is_the_nominal_model():
    """Every catalogue effect on at its defaults changes nothing (so a fit compiles the catalogue once)."""
    scen = [Scenario(0.005, 0.025, 0.89, seed=3), Scenario(0.01, 0.05, 0.97, seed=4)]
    cfg0 = load_plant_config(overrides={"simulation.run_in_s": 0.0})
    a = PlantSimulator(scen, config=cfg0, noise=True).run(3000)
    b = PlantSimulator(scen, config=CFG, noise=True).run(3000)
    for sig in ("a1", "a2", "omega2", "angle_difference"):
        x, y = getattr(a, sig), getattr(b, sig)
        assert np.max(np.abs(x - y)) <= 1e-9 * np.max(np.abs(x)), sig
    assert a.entries == b.entries
    assert set(builtin_catalogue()) >= {c.name for c in CATALOGUE}


DIRECT = {   # drift -> how the same change is made without it: (config key or scenario field, nominal value)
    "backlash_width_drift": ("width_m", 0.005), "absorber_consistency_drift": ("eta_k", 0.025),
    "absorber_flow_index_drift": ("n1", 0.89), "spring_stiffness_drift": ("load.spring_stiffness_N_per_m", 100.0),
    "load_mass_drift": ("load.mass_kg", 10.0), "wheel_inertia_drift": ("load.wheel_inertia_kgm2", 0.2),
    "working_resistance_drift": ("load.working_resistance_N", 30.0),
    "pulse_amplitude_drift": ("pulse_load.amplitude_pu", 1.6),
    "rotor_resistance_drift": ("motor.r_r_pu", 0.048), "supply_voltage_drift": ("motor.supply_voltage_pu", 1.0),
}


DRIFTS = [c for c in CATALOGUE if c.kind == "drift"]


def _random_change(drift) -> float:
    """Random change inside the bounds (kept where the drive still runs: width > 0, n1 > 0)."""
    rng = np.random.default_rng(zlib.crc32(drift.name.encode()))
    lo, hi = drift.parameters[0].bounds
    if drift.name == "backlash_width_drift":
        lo = -0.004
    if drift.name == "supply_voltage_drift":
        lo = -0.3                 # the breakdown torque goes with U^2: a deeper sag stalls the loaded motor
    return float(rng.uniform(lo, min(hi, 2.0)))


def _samples(backend: str) -> int:
    return 4000 if backend != "numpy" else 600


@pytest.fixture(scope="module")
def drifted_runs():
    """Every drift in one batch per backend: scenario i drifts by DRIFTS[i]'s random change, the others by 0 (their
    neutral default); each scenario's run is the one it has alone (per-scenario run-time parameters)."""
    n = len(DRIFTS)
    params = {f"{d.name}.{d.parameters[0].name}": np.where(np.arange(n) == i, _random_change(d), 0.0)
              for i, d in enumerate(DRIFTS)}
    return {backend: PlantSimulator([Scenario(0.005, 0.025, 0.89)] * n, config=CFG, noise=False, backend=backend,
                                    parameters=params).run(_samples(backend))
            for backend in ("numba", "numba-scalar", "numpy")}


@pytest.mark.parametrize("drift", DRIFTS, ids=lambda c: c.name)
def test_drift_with_a_random_change_equals_the_changed_model_on_every_backend(drift, drifted_runs):
    i = DRIFTS.index(drift)
    change = _random_change(drift)
    key, nominal = DIRECT[drift.name]
    value = nominal * (1 + change) if drift.relative else nominal + change
    scen = dict(width_m=0.005, eta_k=0.025, n1=0.89)
    if key in scen:
        scen[key] = value
        direct_cfg = CFG
    else:
        direct_cfg = CFG.with_overrides({key: value})
    for backend in ("numba", "numba-scalar", "numpy"):
        drifted = drifted_runs[backend]
        direct = PlantSimulator([Scenario(**scen)], config=direct_cfg, noise=False, backend=backend).run(
            _samples(backend))
        for sig, floor in FLOORS:
            a, b = getattr(drifted, sig)[i], getattr(direct, sig)[0]
            assert np.max(np.abs(a - b)) <= 1e-9 * max(np.max(np.abs(b)), floor), (backend, sig, change)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_sensor_stages_with_random_parameters_follow_their_equations(seed):
    """Random bias, gain, low-pass time constant and number of sections per signal: the published a1/a2 equal the
    equation applied here to the nominal run's signals (each of the n (rounded) low-pass sections the exact solution
    of tau*y' = a - y for a held over each step, y_k = e^(-h/tau)*y_(k-1) + (1 - e^(-h/tau))*a_k, by a plain loop
    here, the sections in series), on every backend."""
    rng = np.random.default_rng(seed)
    names = ("accelerometer_bias", "accelerometer_gain", "accelerometer_lowpass")
    params = {}
    for n in names:
        for p in builtin_catalogue()[n].parameters:
            hi = min(p.bounds[1], 1e-3 if "time_constant" in p.name else p.bounds[1])
            params[f"{n}.{p.name}"] = float(rng.uniform(p.bounds[0], hi))
    for backend in ("numba", "numba-scalar"):
        ch = PlantSimulator([Scenario(0.005)], config=CFG, noise=True, backend=backend, parameters=params).run(3000)
        base = PlantSimulator([Scenario(0.005)], config=CFG, noise=True, backend=backend).run(3000)
        for sig in ("a1", "a2"):
            a = base.__dict__[sig][0]
            tau = params[f"accelerometer_lowpass.{sig}_time_constant_s"]
            sections = int(np.clip(np.rint(params[f"accelerometer_lowpass.{sig}_sections"]), 1, 4))
            decay = np.exp(-2e-5 / tau)
            y = a
            for _ in range(sections):           # n identical first-order sections in series
                x, y = y, np.empty_like(a)
                prev = x[0]
                for k, xk in enumerate(x):
                    prev = decay * prev + (1.0 - decay) * xk
                    y[k] = prev
            expected = y * (1.0 + params[f"accelerometer_gain.{sig}_relative_change"]) \
                + params[f"accelerometer_bias.{sig}_m_s2"]
            assert np.allclose(ch.__dict__[sig][0], expected, rtol=1e-12, atol=1e-9), (backend, sig)


@pytest.mark.process
def test_generated_simd_stage_vectorises_with_every_catalogue_term(tmp_path):
    """The SIMD loop of the whole catalogue (sin, exp, power, smooth_sign, where ...) compiled afresh (new cache dir,
    new process: numba's inspection needs a compilation, not a cache load) holds the four stages' right-hand sides
    as vector double operations (a vector division is only in a stage) and no libm call: a helper that calls libm
    or branches would turn the loop back into scalar code. Two scenarios, one tile: the vector code is the only
    code the stages have (no scalar remainder, no minimum scenario count)."""
    import json
    import os
    import subprocess
    import sys
    code = (
        "import json, re, warnings, numpy as np\n"
        "from backlash_monitor.plant import load_plant_config\n"
        "from backlash_monitor.plant.codegen import kernel_for, global_vector, N_STATES\n"
        "from backlash_monitor.plant.effects import CATALOGUE\n"
        "cfg = load_plant_config(overrides={f'effects.{c.name}': True for c in CATALOGUE})\n"
        "k = kernel_for(tuple(cfg.catalogue.enabled(cfg, 'term')))\n"
        "S, n = 2, 3; P = np.ones((len(k.param_rows), S))\n"
        "k.module.rk4_simd(np.ones((S, N_STATES)), np.zeros((S, k.module.N_LAGS)), np.zeros((S, n)), np.zeros((n, 2)), np.zeros((n, 3)), np.zeros((n, 3)), np.zeros(n),"
        " 1.0, P, global_vector(cfg), 2e-5, np.zeros((1, S, n)), np.zeros((N_STATES, 0, 0)), False, True,"
        " np.zeros(1, dtype=np.int64))\n"
        "ir = k.module.rk4_simd.inspect_llvm(k.module.rk4_simd.signatures[0])\n"
        "calls = sorted(set(re.findall(r'call [^@]*@(llvm\\.[\\w.]+|[a-z]\\w*)\\(', ir)))\n"
        "print(json.dumps({'vec': len(re.findall(r'<[248] x double>', ir)),"
        " 'vdiv': len(re.findall(r'fdiv [^<]*<[248] x double>', ir)), 'calls': calls}))\n")
    env = dict(os.environ, BACKLASH_MONITOR_KERNEL_CACHE=str(tmp_path))
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    found = json.loads(r.stdout.strip().splitlines()[-1])
    assert found["vec"] > 100, found
    assert found["vdiv"] >= 4, found
    libm = [c for c in found["calls"] if c.split(".")[-1] in ("exp", "log", "pow", "sin", "cos") or
            c in ("exp", "log", "pow", "sin", "cos")]
    assert not libm, found["calls"]
