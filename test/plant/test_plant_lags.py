"""The first-order lags the plant carries (plant/lags.py) against the exact solution of their ODE tau*dL/dt = q - L."""
import math

import numpy as np
import pytest
from scipy.signal import lsim

from backlash_monitor.plant import load_plant_config
from backlash_monitor.plant import codegen, lags
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.disturbances import pulse_load_pu
from backlash_monitor.plant.scenarios import Scenario
from backlash_monitor.plant.simulate import PlantSimulator

H = 2e-5       # the plant's sample step at 50 kHz [s]


def _index(quantity, tau):
    return lags.LAG_NAMES.index(lags.lag_name(quantity, tau))


@pytest.mark.parametrize("tau", lags.LAG_TIMES_S)
def test_update_is_the_odes_exact_solution_for_a_step_and_a_ramp(tau):
    """A held step (the load input, zero-order hold): L = A*(1 - exp(-t/tau)); a ramp q = r*t of a state (the
    first-order hold): L = r*(t - tau*(1 - exp(-t/tau))), both from L(0) = 0."""
    coef = lags.coefficients(H)
    n = 4000
    t = np.arange(n + 1) * H
    step_amp, rate = 1.6, 3.0
    L = [np.zeros(1) for _ in lags.LAGS]
    got_step, got_ramp = [0.0], [0.0]
    for k in range(n):
        q_old = [np.array([rate * t[k]])] * 4 + [np.array([step_amp])]      # speeds and penetration ramp; load held
        q_new = [np.array([rate * t[k + 1]])] * 4 + [np.array([step_amp])]
        L = lags.update(L, q_old, q_new, coef)
        got_step.append(float(L[_index("load_moment", tau)][0]))
        got_ramp.append(float(L[_index("omega1", tau)][0]))
    exact_step = step_amp * (1.0 - np.exp(-t / tau))
    exact_ramp = rate * (t - tau * (1.0 - np.exp(-t / tau)))
    assert np.max(np.abs(np.array(got_step) - exact_step)) < 1e-12 * step_amp
    assert np.max(np.abs(np.array(got_ramp) - exact_ramp)) < 1e-12 * rate * t[-1]


def _sim(backend, effects=None, catalogue=None, record_states=True):
    over = {"simulation.run_in_s": 0.0}
    over.update(effects or {})
    cfg = load_plant_config(overrides=over, catalogue=catalogue)
    return PlantSimulator([Scenario(0.005, 0.025, 0.89, seed=1)], config=cfg, noise=False, backend=backend,
                          record_states=record_states), cfg


def _flywheel_catalogue(tmp_path):
    """The built-in catalogue with HIDDEN_FLYWHEEL (below), a term that names a lag: its kernel advances the lags."""
    path = tmp_path / "flywheel.py"
    path.write_text(HIDDEN_FLYWHEEL)
    return builtin_catalogue().with_files([path])


def _sim_carrying_lags(backend, tmp_path):
    """A model whose kernel advances the lags: the flywheel's term names one, at c = 0 (the drive unchanged)."""
    return _sim(backend, {"effects.test_hidden_flywheel": True}, _flywheel_catalogue(tmp_path))


@pytest.mark.parametrize("backend", ["numba", "numpy"])
def test_plant_lag_of_the_load_step_is_exact(backend, tmp_path):
    """Without noise the load moment input is the pulse train: a held step at the pulse's rise. The plant's lags of
    it, carried across chunks, are A*(1 - exp(-t/tau)) from the rise (the ODE's solution for a held input)."""
    sim, cfg = _sim_carrying_lags(backend, tmp_path)
    n = 8000
    load = np.asarray(pulse_load_pu(0, n, cfg), dtype=float).reshape(-1)
    rise = int(np.flatnonzero(load > 0)[0])
    amp = float(load[rise])
    sim.run(rise)                                     # to the rise: the lags of a zero load stay 0
    assert np.all(sim.lags[0, [_index("load_moment", tau) for tau in lags.LAG_TIMES_S]] == 0.0)
    for m in (1, 37, 400, 1200):                      # chunks of several lengths: the lags carry over
        sim.run(m)
        k = sim.sample_index - rise                   # steps taken with the pulse held on
        assert np.all(load[rise:sim.sample_index] == amp)
        for tau in lags.LAG_TIMES_S:
            exact = amp * (1.0 - math.exp(-k * H / tau))
            assert sim.lags[0, _index("load_moment", tau)] == pytest.approx(exact, rel=1e-12, abs=1e-14)


@pytest.mark.parametrize("backend", ["numba", "numba-scalar", "numpy"])
def test_plant_lags_of_the_states_are_their_odes_solution(backend, tmp_path):
    """The speeds and the penetration of a run, their lags at its end against scipy's lsim of tau*L' = q - L on the
    recorded samples (linear between samples), each started at its quantity's first value."""
    sim, cfg = _sim_carrying_lags(backend, tmp_path)
    n = 6000                                          # over the first pulse: speeds swing, the jaw impacts
    chunk = sim.run(n)
    st = chunk.states
    beta = float(sim.parameter_values("beta")[0])
    q = {"omega1": st["w1"][0] * cfg.motor.base_mechanical_speed_rad_s, "omega2": st["omega2"][0],
         "xdot": st["xdot"][0], "penetration": np.maximum(np.abs(st["delta"][0]) - beta, 0.0)}
    # the state after the last step, which the lags have seen too
    x_end = sim.state[0]
    q_end = {"omega1": x_end[4] * cfg.motor.base_mechanical_speed_rad_s, "omega2": x_end[8], "xdot": x_end[10],
             "penetration": max(abs(x_end[5]) - beta, 0.0)}
    t = np.arange(n + 1) * H
    assert np.ptp(q["penetration"]) > 1e-4 and np.ptp(q["omega1"]) > 0.1     # the run does exercise them
    for name, series in q.items():
        u = np.append(series, q_end[name])
        for tau in lags.LAG_TIMES_S:
            _, y, _ = lsim(([1.0], [tau, 1.0]), u, t, X0=[u[0] * tau], interp=True)
            got = sim.lags[0, _index(name, tau)]
            scale = max(np.ptp(u), 1e-12)
            assert abs(got - y[-1]) < 1e-7 * scale, (name, tau, got, y[-1])


HIDDEN_FLYWHEEL = '''
from backlash_monitor.plant.effects import Effect, Parameter


class HiddenFlywheel(Effect):
    name = "test_hidden_flywheel"
    balance = "motor_load_moment_pu"
    description = "a flywheel on a creeping belt: c*(Omega1 - L_100ms(Omega1))/T_b on the motor's load"
    parameters = (Parameter("c_Nms", "N*m*s/rad", 0.0, (0.0, 100.0), "c"),)

    @staticmethod
    def term(omega1, omega1_lag_100ms, base_torque_Nm, c_Nms):
        return c_Nms * (omega1 - omega1_lag_100ms) / base_torque_Nm
'''


def test_a_term_of_a_lag_runs_alike_on_every_backend(tmp_path):
    """A plug-in whose term names a lag (a hidden flywheel on the motor) gives the same recording on the compiled and
    the numpy backends, and a different one from the model without it."""
    cat = _flywheel_catalogue(tmp_path)
    out = {}
    for backend in ("numba", "numba-scalar", "numpy"):
        cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0, "effects.test_hidden_flywheel": True},
                                catalogue=cat)
        sim = PlantSimulator([Scenario(0.005, 0.025, 0.89, seed=1)], config=cfg, noise=False, backend=backend,
                             parameters={"test_hidden_flywheel.c_Nms": 5.0})
        out[backend] = sim.run(6000).a1
    for backend in ("numba", "numba-scalar"):
        assert np.allclose(out[backend], out["numpy"], rtol=1e-9, atol=1e-9 * np.abs(out["numpy"]).max())
    sim0, _ = _sim("numba")
    a1_without = sim0.run(6000).a1
    assert np.max(np.abs(out["numba"] - a1_without)) > 1e-3 * np.abs(a1_without).max()


@pytest.mark.parametrize("backend", ["numba", "numba-scalar", "numpy"])
def test_a_model_whose_terms_name_no_lag_runs_alike_without_advancing_them(backend, tmp_path):
    """The lags are advanced only in a kernel whose terms name one (codegen.lags_used): without such a term the run
    is the same recording as the model with the flywheel's lag term at c = 0 (which advances them), and the lags stay
    settled at their first state's quantities."""
    sim, _ = _sim(backend, record_states=False)
    carrying, _ = _sim(backend, {"effects.test_hidden_flywheel": True}, _flywheel_catalogue(tmp_path),
                       record_states=False)
    assert not codegen.lags_used(sim.kernel.effects) and codegen.lags_used(carrying.kernel.effects)
    a, b = sim.run(3000), carrying.run(3000)
    first = sim.lags.copy()
    for name in ("a1", "a2", "omega1", "angle_difference"):
        x, y = getattr(a, name), getattr(b, name)
        assert np.allclose(x, y, rtol=1e-9, atol=1e-9 * np.abs(y).max()), name
    sim.run(3000)
    assert np.array_equal(sim.lags, first)                            # not advanced
    assert np.max(np.abs(carrying.lags - first)) > 0.0                # advanced where a term names one
