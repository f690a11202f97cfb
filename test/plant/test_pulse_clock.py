"""The pulse clock (model variables pulse_time_s, pulse_off_time_s): the time since the latest load pulse's rising and
falling edge, held over each step, in every backend. The expected times are read off the held pulse load itself (its
edges found in pulse_load_pu's samples), not from the clock's own formula."""
import numpy as np
import pytest

from backlash_monitor.plant import load_plant_config
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.disturbances import NO_PULSE_S, pulse_clock_s, pulse_load_pu
from backlash_monitor.plant.effects import Effect, Parameter
from backlash_monitor.plant.scenarios import Scenario
from backlash_monitor.plant.simulate import PlantSimulator


class PulseClockProbe(Effect):
    """A motor load moment linear in the two clocks, so that the motor's balance gives them back."""
    name = "pulse_clock_probe"
    balance = "motor_load_moment_pu"
    description = "a load a*t_rise + b*t_fall (a test probe of the pulse clock)"
    parameters = (Parameter("on_gain_pu_per_s", "p.u./s", 0.0, (-10.0, 10.0), "a"),
                  Parameter("off_gain_pu_per_s", "p.u./s", 0.0, (-10.0, 10.0), "b"))

    @staticmethod
    def term(pulse_time_s, pulse_off_time_s, on_gain_pu_per_s, off_gain_pu_per_s):
        return on_gain_pu_per_s * pulse_time_s + off_gain_pu_per_s * pulse_off_time_s


def _time_since_edges(k0, n, cfg):
    """(since the latest rise, since the latest fall) [s] at samples k0..k0+n-1, from the held pulse's own edges (a
    span one period long before k0 is included, so that every sample has both edges behind it)."""
    fs = cfg.simulation.sample_rate_hz
    span = int(round(2 * cfg.pulse_load.period_s * fs))
    p = pulse_load_pu(k0 - span, n + span, cfg) > 0
    k = np.arange(k0 - span, k0 + n)
    out = []
    for edges in (np.flatnonzero(p[1:] & ~p[:-1]) + 1, np.flatnonzero(~p[1:] & p[:-1]) + 1):
        latest = np.maximum.accumulate(np.where(np.isin(np.arange(p.size), edges), np.arange(p.size), -1))
        assert np.all(latest[span:] >= 0)
        out.append((k[span:] - k[latest[span:]]) / fs)
    return out


def test_pulse_clock_is_the_time_since_each_edge_of_the_held_pulse():
    cfg = load_plant_config()
    fs = cfg.simulation.sample_rate_hz
    for k0 in (int(0.3 * fs), int(1.7 * fs), -int(0.9 * fs)):        # after the first pulse, later, in the run-in
        rise, fall = _time_since_edges(k0, 30_000, cfg)
        clock = pulse_clock_s(k0, 30_000, cfg)
        assert np.allclose(clock[:, 0], rise, atol=1e-12) and np.allclose(clock[:, 1], fall, atol=1e-12)
    off = load_plant_config(overrides={"effects.pulse_load": False})
    assert np.all(pulse_clock_s(0, 100, off) == NO_PULSE_S)


@pytest.mark.parametrize("backend", ["numba", "numba-scalar", "numpy"])
def test_every_backend_holds_the_time_since_the_edge_in_its_motor_balance(backend):
    """A plug-in load a*t_rise + b*t_fall; the motor balance T_m dw1/dt = te - T_c/T_b - T_L - load gives the load
    back at every sample (from the recorded a1, T_c and fluxes): a/b times the time since the pulse's edge."""
    cat = builtin_catalogue().copy()
    cat.register(PulseClockProbe)
    cfg = load_plant_config(overrides={"effects.pulse_clock_probe": True, "simulation.run_in_s": 0.0},
                            catalogue=cat)
    gain = 0.5
    n = 40_000 if backend != "numpy" else 8_000        # 100 kHz: past the first rise at 50 ms
    sim = PlantSimulator([Scenario(0.005, seed=1)] * 2, config=cfg, noise=False, backend=backend, record_states=True,
                         parameters={"pulse_clock_probe.on_gain_pu_per_s": [gain, 0.0],
                                     "pulse_clock_probe.off_gain_pu_per_s": [0.0, gain]})
    ch = sim.run(n)
    m = cfg.motor
    st = ch.states
    iw = 1.0 / m.w_pu
    isa = (m.x_r_pu * st["psi_sa"] - m.x_m_pu * st["psi_ra"]) * iw
    isb = (m.x_r_pu * st["psi_sb"] - m.x_m_pu * st["psi_rb"]) * iw
    te = st["psi_sa"] * isb - st["psi_sb"] * isa
    dw1 = ch.a1 / (cfg.load.wheel_radius_m * m.base_mechanical_speed_rad_s)
    pulse = pulse_load_pu(0, n, cfg)
    probe = te - ch.transmitted_torque_Nm / m.base_torque_Nm - pulse[None, :] - m.mechanical_time_constant_s * dw1
    rise, fall = _time_since_edges(0, n, cfg)
    k = np.arange(n)
    first = int(round(cfg.pulse_load.first_s * cfg.simulation.sample_rate_hz))
    later = k >= first          # before the first pulse the settled start has cut the run-in's train (docstring)
    assert np.allclose(probe[0, later] / gain, rise[later], atol=1e-7)
    assert np.allclose(probe[1, later] / gain, fall[later], atol=1e-7)
    assert probe[0, later].max() / gain > 0.025 and probe[0, later].min() / gain < 1e-4   # a rise was crossed
