"""Motor steady state against the per-unit steady-state equivalent circuit (tolerance 1 %)."""
import numpy as np
import pytest

from backlash_monitor.plant import Scenario, PlantSimulator, load_plant_config
from backlash_monitor.plant.motor import currents

RS, RR, XS, XR, XM = 0.059, 0.048, 1.92, 1.92, 1.82   # paper values, restated here on purpose


def circuit(slip):
    """Equivalent circuit written independently of the package: T-circuit with r_r/s."""
    zm = 1j * XM
    zr = RR / slip + 1j * (XR - XM)
    zs = RS + 1j * (XS - XM)
    i_s = 1.0 / (zs + zm * zr / (zm + zr))
    i_r = -i_s * zm / (zm + zr)                   # rotor current (referred, with the motor convention)
    te = abs(i_r) ** 2 * RR / slip                 # air-gap power / synchronous speed, p.u.
    return te, abs(i_s)


@pytest.mark.parametrize("load_pu", [0.3, 0.8])
def test_motor_settles_to_equivalent_circuit(load_pu):
    cfg = load_plant_config(overrides={
        "effects": {"backlash_clutch": False, "pulse_load": False, "constant_motor_load": True},
        "constant_motor_load_pu": load_pu, "simulation.run_in_s": 0.0})
    sim = PlantSimulator([Scenario(0.005)], config=cfg, noise=False, record_states=True)
    # start far from the answer: rotor flux zero, 3 % below the no-load speed
    sim.state[0, 2:4] = 0.0
    sim.state[0, 4] = 0.97
    n_settle = 150_000            # 3 s: electrical and slip transients decay (slowest ~0.13 s)
    sim.run(n_settle)
    ch = sim.run(2000)            # 40 ms = two supply periods
    st = ch.states
    isa, isb, _, _ = currents(st["psi_sa"][0], st["psi_sb"][0], st["psi_ra"][0], st["psi_rb"][0], XS, XR, XM,
                              XS * XR - XM ** 2)
    te = st["psi_sa"][0] * isb - st["psi_sb"][0] * isa
    slip = 1.0 - st["w1"][0].mean()
    te_c, is_c = circuit(slip)
    # torque balance: the motor carries the constant load, and the circuit gives that torque at this slip
    assert te.mean() == pytest.approx(load_pu, rel=1e-3)
    assert te_c == pytest.approx(load_pu, rel=0.01)
    # stator current amplitude (alpha-beta magnitude) against the circuit
    assert np.hypot(isa, isb).mean() == pytest.approx(is_c, rel=0.01)
    # slip from the circuit's torque-slip relation (solve te_c(s) = load) against the simulated slip
    s_grid = np.linspace(1e-4, 0.05, 20001)
    s_c = s_grid[np.argmin([abs(circuit(s)[0] - load_pu) for s in s_grid])]
    assert slip == pytest.approx(s_c, rel=0.01)


def test_computed_steady_state_stays_put():
    """The settled start of the full plant (no pulse, no noise) is an equilibrium: nothing drifts."""
    cfg = load_plant_config(overrides={"effects.pulse_load": False, "simulation.run_in_s": 0.0})
    sim = PlantSimulator([Scenario(0.005)], config=cfg, noise=False)
    w0 = sim.state[0, 4]
    ch = sim.run(25_000)
    assert np.abs(ch.a1).max() < 1e-6 and np.abs(ch.a2).max() < 1e-6
    assert abs(sim.state[0, 4] - w0) < 1e-9
