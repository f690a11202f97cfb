"""Energy balance without noise: input - copper losses - mechanical losses - load work - d(stored) ~ 0."""
import numpy as np

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.disturbances import pulse_load_pu
from backlash_monitor.plant.motor import currents


def test_energy_balance_over_a_pulse():
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.5})
    sc = Scenario(width_m=0.0075, eta_k=0.025, n1=0.89)
    sim = PlantSimulator([sc], config=cfg, noise=False, record_states=True)
    n = 10_000                                   # 0.2 s: the pulse at 0.05 s, onset, impact, return, impact
    ch = sim.run(n)
    assert len(ch.entries[0]) == 2
    st = {k: v[0] for k, v in ch.states.items()}
    m, ld, cl = cfg.motor, cfg.load, cfg.clutch
    fs = cfg.simulation.sample_rate_hz
    Pb = m.base_torque_Nm * m.base_mechanical_speed_rad_s   # base power [W]
    Omb, Ob = m.base_mechanical_speed_rad_s, m.base_angular_frequency_rad_s
    beta = sc.width_m / ld.wheel_radius_m
    c = sc.eta_k * ld.absorber_area_m2 / ld.absorber_gap_m ** sc.n1
    k = np.arange(n)
    ua, ub = np.cos(2 * np.pi * 50 * k / fs), np.sin(2 * np.pi * 50 * k / fs)
    isa, isb, ira, irb = currents(st["psi_sa"], st["psi_sb"], st["psi_ra"], st["psi_rb"], m.x_s_pu, m.x_r_pu,
                                  m.x_m_pu, m.w_pu)
    O1, O2, xd, z, d = st["w1"] * Omb, st["omega2"], st["xdot"], st["z"], st["delta"]
    v = ld.wheel_radius_m * O2 - xd
    gap = np.maximum(np.abs(d) - beta, 0.0)
    tc = ch.transmitted_torque_Nm[0]
    p_in = Pb * (ua * isa + ub * isb)
    p_cu = Pb * (m.r_s_pu * (isa ** 2 + isb ** 2) + m.r_r_pu * (ira ** 2 + irb ** 2))
    p_absorber = c * np.abs(v) ** (sc.n1 + 1)
    p_contact = tc * (O1 - O2) - cl.contact_stiffness_Nm_per_rad * gap * np.sign(d) * (O1 - O2)
    p_load = ld.working_resistance_N * xd + pulse_load_pu(0, n, cfg) * m.base_torque_Nm * O1
    e_stored = (Pb / Ob * 0.5 * (st["psi_sa"] * isa + st["psi_sb"] * isb + st["psi_ra"] * ira + st["psi_rb"] * irb)
                + 0.5 * m.rotor_inertia_kgm2 * O1 ** 2 + 0.5 * ld.wheel_inertia_kgm2 * O2 ** 2
                + 0.5 * ld.mass_kg * xd ** 2 + 0.5 * ld.spring_stiffness_N_per_m * z ** 2
                + 0.5 * cl.contact_stiffness_Nm_per_rad * gap ** 2)
    # the contact only dissipates (p_absorber = c|v|^(n1+1) is >= 0 by its formula: not a check)
    assert np.all(p_contact >= -1e-9)
    net = p_in - p_cu - p_absorber - p_contact - p_load
    h = 1.0 / fs
    residual = np.sum(0.5 * (net[1:] + net[:-1])) * h - (e_stored[-1] - e_stored[0])
    e_in = np.sum(0.5 * (p_in[1:] + p_in[:-1])) * h
    # trapezoid over 50 kHz samples; the clutch's damper engages with a jump, which costs O(h) per impact
    print("energy residual", residual, "J of", e_in, "J in")
    assert abs(residual) < 1e-4 * e_in, (residual, e_in)
