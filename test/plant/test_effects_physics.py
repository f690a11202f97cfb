"""One physics test per catalogue effect, from its equation (docs/effects.md): what it must do to the motion
or to the published signals. Noise off, settled start without run-in unless stated."""
import math

import numpy as np
import pytest

from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config

from backlash_monitor.plant.effects import CATALOGUE

# every catalogue effect switched on at its neutral defaults: all tests share one compiled kernel (two with the
# decoupled one), and each test sets only the parameters of the effect it tests
ALL_ON = {f"effects.{c.name}": True for c in CATALOGUE}
BASE = {"simulation.run_in_s": 0.0, **ALL_ON}
DECOUPLED = {**BASE, "effects.backlash_clutch": False, "effects.spring": False, "effects.absorber_power_law": False,
             "effects.working_resistance": False, "effects.pulse_load": False}   # a free wheel, a free motor
SCEN = [Scenario(0.005, 0.025, 0.89)]
CFG = load_plant_config(overrides=BASE)
J1 = CFG.motor.rotor_inertia_kgm2
J2 = CFG.load.wheel_inertia_kgm2
R = CFG.load.wheel_radius_m
T_B = CFG.motor.base_torque_Nm


def run(overrides, n, base=BASE, scen=SCEN, states=False, **kw):
    cfg = load_plant_config(overrides={**base, **overrides})
    sim = PlantSimulator(scen, config=cfg, noise=False, record_states=states, **kw)
    return sim, sim.run(n)


# ---------------------------------------------------------------- wheel friction on a free wheel
def test_wheel_coulomb_friction_decelerates_the_wheel_by_T_over_J2():
    T = 1.5
    _, ch = run({"effects.wheel_coulomb_friction": True, "wheel_coulomb_friction.torque_Nm": T}, 5000, DECOUPLED)
    t = np.arange(5000) * 2e-5
    w = ch.omega2[0]
    assert np.allclose(w, w[0] - T / J2 * t, rtol=1e-10, atol=0.0)       # Omega2 = Omega0 - T/J2 t


def test_wheel_viscous_friction_decays_the_speed_exponentially():
    b = 0.05
    _, ch = run({"effects.wheel_viscous_friction": True, "wheel_viscous_friction.damping_Nms_per_rad": b}, 5000,
                DECOUPLED)
    t = np.arange(5000) * 2e-5
    assert np.allclose(ch.omega2[0], ch.omega2[0, 0] * np.exp(-b / J2 * t), rtol=1e-10, atol=0.0)


def test_wheel_stribeck_friction_decelerates_by_its_curve_and_vanishes_far_above_the_stribeck_speed():
    Ts, ws = 2.0, 200.0
    _, ch = run({"effects.wheel_stribeck_friction": True, "wheel_stribeck_friction.excess_torque_Nm": Ts,
                 "wheel_stribeck_friction.stribeck_speed_rad_s": ws}, 2, DECOUPLED)
    w0 = ch.omega2[0, 0]
    slope = (ch.omega2[0, 1] - w0) / 2e-5
    assert slope == pytest.approx(-Ts / J2 * math.exp(-(w0 / ws) ** 2), rel=1e-6)
    _, far = run({"effects.wheel_stribeck_friction": True, "wheel_stribeck_friction.excess_torque_Nm": Ts,
                  "wheel_stribeck_friction.stribeck_speed_rad_s": 10.0}, 2, DECOUPLED)
    assert far.omega2[0, 1] == ch.omega2[0, 0] or abs(far.omega2[0, 1] - far.omega2[0, 0]) < 1e-12  # exp(-240) = 0


# ---------------------------------------------------------------- motor-side terms: first-sample acceleration
def _a1_jump(overrides):
    _, nominal = run({}, 1)
    _, with_effect = run(overrides, 1, states=True)
    return with_effect.a1[0, 0] - nominal.a1[0, 0], with_effect


def test_motor_coulomb_friction_decelerates_the_motor_by_T_over_J1():
    T = 0.8
    jump, _ = _a1_jump({"effects.motor_coulomb_friction": True, "motor_coulomb_friction.torque_Nm": T})
    assert jump == pytest.approx(-R * T / J1, rel=1e-9)                 # a1 = r dOmega1/dt


def test_motor_load_offset_decelerates_the_motor_by_its_moment():
    L = 0.1
    jump, _ = _a1_jump({"effects.motor_load_offset": True, "motor_load_offset.load_pu": L})
    assert jump == pytest.approx(-R * L * T_B / J1, rel=1e-9)


def test_torque_ripple_follows_the_motor_angle_at_its_order():
    A, order, phase = 0.05, 6.0, 0.3
    ov = {"effects.torque_ripple": True, "torque_ripple.amplitude_pu": A, "torque_ripple.order": order,
          "torque_ripple.phase_rad": phase}
    jump, ch = _a1_jump(ov)
    alpha1 = ch.alpha1[0, 0]
    assert jump == pytest.approx(-R * A * T_B / J1 * math.sin(order * alpha1 + phase), rel=1e-9)
    # on a free motor (decoupled): the ripple's frequency is order * Omega1 / 2pi
    _, free = run({}, 10000, DECOUPLED)
    _, rip = run(ov, 10000, DECOUPLED)
    d = rip.a1[0] - free.a1[0]
    crossings = np.count_nonzero(np.diff(np.sign(d)) != 0)
    expected = 2 * order * np.mean(free.omega1[0]) / (2 * math.pi) * 0.2
    assert abs(crossings - expected) <= 2


# ---------------------------------------------------------------- mass and contact
def test_mass_force_offset_accelerates_the_mass_by_F_over_m():
    F = 5.0
    _, nominal = run({}, 1)
    _, ch = run({"effects.mass_force_offset": True, "mass_force_offset.force_N": F}, 1)
    assert ch.a2[0, 0] - nominal.a2[0, 0] == pytest.approx(F / CFG.load.mass_kg, rel=1e-9)


def _contact_torque_jump(overrides, relative_speed=0.0):
    out = []
    for ov in ({}, overrides):
        sim = PlantSimulator(SCEN, config=CFG, noise=False, parameters={k: v for k, v in ov.items() if "." in k
                                                                         and not k.startswith("effects.")})
        sim.state[:, 8] -= relative_speed                    # Omega2 lowered: the contact closes at this speed
        out.append((sim.run(1).transmitted_torque_Nm[0, 0], sim))
    return out[1][0] - out[0][0], out[0][1]


def test_clutch_contact_stiffness_scales_the_contact_spring():
    e = 0.3
    jump, sim = _contact_torque_jump({"effects.clutch_contact_stiffness": True,
                                      "clutch_contact_stiffness.relative_change": e})
    k_c = CFG.clutch.contact_stiffness_Nm_per_rad
    penetration = sim.P[0, 0] * 0 + (4.5 / k_c)             # settled: Delta - beta = T_c/k_c, T_c = r*F0 = 4.5 N*m
    assert jump == pytest.approx(e * k_c * penetration, rel=1e-6)


def test_clutch_contact_damping_scales_the_contact_damper():
    e, speed = 0.5, 0.4
    jump, _ = _contact_torque_jump({"effects.clutch_contact_damping": True,
                                    "clutch_contact_damping.relative_change": e}, relative_speed=speed)
    assert jump == pytest.approx(e * CFG.clutch.contact_damping_Nms_per_rad * speed, rel=1e-9)


def test_shaft_compliance_puts_a_spring_in_series_with_the_contact():
    C = 1e-4
    jump, _ = _contact_torque_jump({"effects.shaft_compliance": True, "shaft_compliance.compliance_rad_per_Nm": C})
    k_c = CFG.clutch.contact_stiffness_Nm_per_rad
    k_series = 1.0 / (1.0 / k_c + C)                          # 1/k = 1/k_c + 1/k_s
    assert jump == pytest.approx((k_series - k_c) * 4.5 / k_c, rel=1e-6)


# ---------------------------------------------------------------- sensors
def test_accelerometer_bias_and_gain_act_on_the_published_signals():
    _, nominal = run({}, 3000)
    _, ch = run({"effects.accelerometer_bias": True, "accelerometer_bias.a1_m_s2": 0.5,
                 "accelerometer_bias.a2_m_s2": -0.2, "effects.accelerometer_gain": True,
                 "accelerometer_gain.a1_relative_change": 0.1, "accelerometer_gain.a2_relative_change": -0.05}, 3000)
    assert np.allclose(ch.a1, nominal.a1 * 1.1 + 0.5, rtol=1e-12, atol=1e-12)
    assert np.allclose(ch.a2, nominal.a2 * 0.95 - 0.2, rtol=1e-12, atol=1e-12)
    assert np.array_equal(ch.omega2, nominal.omega2)          # sensors change no motion


def test_accelerometer_lowpass_delays_a_step_by_its_time_constant():
    tau = 2e-3
    cfg = load_plant_config(overrides={**BASE, "effects.accelerometer_lowpass": True,
                                       "accelerometer_lowpass.a1_time_constant_s": tau})
    sim = PlantSimulator(SCEN, config=cfg, noise=False)
    step = np.zeros((1, 2000))
    step[0, 100:] = 1.0
    sig = {"a1": step.copy(), "a2": step.copy()}
    sim.sensor_stage(sig)
    k63 = np.argmax(sig["a1"][0] >= 1.0 - math.exp(-1.0))
    # 63 % after one time constant (y_k takes a_k as held over the step ending at k: within 1.5 samples)
    assert abs((k63 - 100) * 2e-5 - tau) <= 1.5 * 2e-5
    assert np.array_equal(sig["a2"], step)                      # a2's tau = 0: no filter
    # in the stream: chunked runs equal one run (the filter's state carries over)
    whole = PlantSimulator(SCEN, config=cfg, noise=False).run(3000)
    sim2 = PlantSimulator(SCEN, config=cfg, noise=False)
    parts = np.concatenate([sim2.run(m).a1 for m in (700, 1300, 1000)], axis=1)
    assert np.allclose(parts, whole.a1, rtol=0, atol=1e-12)


@pytest.mark.parametrize("sections", [1, 2, 4])
def test_accelerometer_lowpass_of_n_sections_attenuates_a_sine_by_the_nth_power(sections):
    """n identical first-order sections: |H(f)| = (1 + (2 pi f tau)^2)^(-n/2), measured on a steady sine."""
    tau, f = 2.65e-4, 1500.0
    cfg = load_plant_config(overrides={**BASE, "effects.accelerometer_lowpass": True,
                                       "accelerometer_lowpass.a2_time_constant_s": tau,
                                       "accelerometer_lowpass.a2_sections": float(sections)})
    sim = PlantSimulator(SCEN, config=cfg, noise=False)
    t = np.arange(20000) * 2e-5
    sine = np.sin(2 * np.pi * f * t)[None, :]
    sig = {"a1": sine.copy(), "a2": sine.copy()}
    sim.sensor_stage(sig)
    steady = sig["a2"][0, 10000:]
    gain = np.sqrt(2.0 * np.mean(steady ** 2))
    # each discrete section (input held over the step) follows the continuous one within 0.2 % at 1.5 kHz
    expected = (1 + (2 * np.pi * f * tau) ** 2) ** (-sections / 2)
    assert abs(gain - expected) < 2e-3 * sections * expected
    assert np.array_equal(sig["a1"], sine)                      # a1's tau = 0: no filter


# ---------------------------------------------------------------- drifts: equal to the changed parameter
@pytest.mark.parametrize("drift, change, direct, scenario", [
    ("backlash_width_drift", 0.001, {}, Scenario(0.006, 0.025, 0.89)),
    ("absorber_consistency_drift", 0.5, {}, Scenario(0.005, 0.0375, 0.89)),
    ("absorber_flow_index_drift", 0.04, {}, Scenario(0.005, 0.025, 0.93)),
    ("spring_stiffness_drift", 0.2, {"load.spring_stiffness_N_per_m": 120.0}, None),
    ("load_mass_drift", -0.1, {"load.mass_kg": 9.0}, None),
    ("wheel_inertia_drift", 0.5, {"load.wheel_inertia_kgm2": 0.3}, None),
    ("working_resistance_drift", 0.1, {"load.working_resistance_N": 33.0}, None),
    ("pulse_amplitude_drift", -0.25, {"pulse_load.amplitude_pu": 1.2}, None),
    ("rotor_resistance_drift", 0.5, {"motor.r_r_pu": 0.072}, None),
    ("supply_voltage_drift", -0.1, {"motor.supply_voltage_pu": 0.9}, None),
])
def test_drift_equals_the_changed_parameter(drift, change, direct, scenario):
    from backlash_monitor.plant.catalogue import builtin_catalogue
    pname = builtin_catalogue().get(drift).parameters[0].name
    _, drifted = run({f"effects.{drift}": True, f"{drift}.{pname}": change}, 4000)
    _, changed = run(direct, 4000, scen=[scenario] if scenario else SCEN)
    for sig in ("a1", "a2", "angle_difference"):
        a, b = getattr(drifted, sig), getattr(changed, sig)
        assert np.max(np.abs(a - b)) <= 1e-9 * np.max(np.abs(b)), sig
    _, nominal = run({}, 4000)
    assert np.max(np.abs(nominal.a2 - drifted.a2)) > 1e-6          # and it does change the signals


# ---------------------------------------------------------------- a weaker motor: the equivalent circuit's laws
@pytest.mark.parametrize("drift, change", [("rotor_resistance_drift", 0.6), ("supply_voltage_drift", -0.15)])
def test_a_weaker_motor_settles_where_the_equivalent_circuit_puts_it(drift, change):
    """Without the pulses the motor carries the constant torque T0 = r*F0/T_b. The rotor branch is r_r/s + j*x_r, so
    a rotor resistance k*r_r carries any torque at k times the slip; every current of the linear circuit goes with
    the supply voltage U, so the torque at a slip goes with U^2 and U carries T0 where 1 p.u. carries T0/U^2. The ODE,
    from the settled start and after 0.4 s, must sit there (and the settled start must already be that state)."""
    import dataclasses

    from backlash_monitor.plant.motor import steady_state_at_torque
    steady = {"effects.pulse_load": False}
    _, nominal = run(steady, 20000)
    _, weaker = run({**steady, f"effects.{drift}": True, f"{drift}.relative_change": change}, 20000)
    omb = CFG.motor.base_mechanical_speed_rad_s
    t0 = R * CFG.load.working_resistance_N / CFG.motor.base_torque_Nm
    s_nominal = steady_state_at_torque(t0, CFG.motor).slip
    if drift == "rotor_resistance_drift":
        expected = (1 + change) * s_nominal
    else:
        u = 1 + change
        expected = steady_state_at_torque(t0 / u ** 2, dataclasses.replace(CFG.motor, supply_voltage_pu=1.0)).slip
    assert abs((1 - nominal.omega1[0, -1] / omb) - s_nominal) < 1e-6 * s_nominal + 1e-9
    for k in (0, -1):                                    # the settled start and 0.4 s later
        assert abs((1 - weaker.omega1[0, k] / omb) - expected) < 1e-4 * expected, k
    assert expected > 1.2 * s_nominal                    # and it is a weaker motor: it slips more
