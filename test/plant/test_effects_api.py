"""The effect API: the catalogue's names and declarations, config switches and --set, nearest-key errors,
plug-ins from a file (--effects) and from an entry point, per-scenario parameters, common random numbers."""
from pathlib import Path

import numpy as np
import pytest

from backlash_monitor.__main__ import main
from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.plant.effects import CATALOGUE, Effect, Parameter

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "my_effects.py"
ALL_ON = {f"effects.{c.name}": True for c in CATALOGUE}
CFG = load_plant_config(overrides={"simulation.run_in_s": 0.0, **ALL_ON})


def test_catalogue_names_and_declarations():
    names = {"wheel_coulomb_friction", "wheel_viscous_friction", "wheel_stribeck_friction", "motor_coulomb_friction",
             "clutch_contact_stiffness", "clutch_contact_damping", "shaft_compliance", "mass_force_offset",
             "motor_load_offset", "torque_ripple", "accelerometer_bias", "accelerometer_gain", "accelerometer_lowpass",
             "backlash_width_drift", "absorber_consistency_drift", "absorber_flow_index_drift",
             "spring_stiffness_drift", "load_mass_drift", "wheel_inertia_drift", "working_resistance_drift",
             "pulse_amplitude_drift", "rotor_resistance_drift", "supply_voltage_drift"}
    cat = builtin_catalogue()
    assert {c.name for c in CATALOGUE} == names and names <= set(cat)
    for name in names:
        cls = cat[name]
        assert cls.description and cls.balance and cls.parameters
        for p in cls.parameters:
            assert p.unit and p.bounds[0] <= p.default <= p.bounds[1]
    for n in ("backlash_clutch", "spring", "absorber_power_law", "working_resistance", "pulse_load",
              "gaussian_disturbance", "pulse_disturbance"):
        assert cat[n].nominal and load_plant_config().effects[n]


@pytest.mark.parametrize("key, nearest", [
    ("wheel_colomb_friction.torque_Nm", "wheel_coulomb_friction.torque_Nm"),
    ("effects.wheel_colomb_friction", "effects.wheel_coulomb_friction"),
    ("wheel_coulomb_friction.torqe_Nm", "wheel_coulomb_friction.torque_Nm"),
    ("load.mas_kg", "load.mass_kg"),
])
def test_unknown_key_names_the_nearest_valid_one(key, nearest):
    with pytest.raises(ValueError) as err:
        load_plant_config(overrides={key: True if key.startswith("effects.") else 1.0})
    msg = str(err.value)
    assert key.split(".")[-1] in msg and f"nearest valid key: {nearest}" in msg and "\n" not in msg


def test_parameter_out_of_bounds_is_refused():
    with pytest.raises(ValueError, match="wheel_coulomb_friction.torque_Nm.*allowed: 0.0 <= value <= 50.0"):
        load_plant_config(overrides={"wheel_coulomb_friction.torque_Nm": -1.0})
    with pytest.raises(ValueError, match="switched off"):
        PlantSimulator([Scenario(0.005)], config=load_plant_config(overrides={"simulation.run_in_s": 0.0}),
                       parameters={"wheel_coulomb_friction.torque_Nm": 1.0})
    with pytest.raises(ValueError, match="nearest: 'wheel_coulomb_friction.torque_Nm'"):
        PlantSimulator([Scenario(0.005)], config=CFG, parameters={"wheel_coulomb_friction.torque": 1.0})
    with pytest.raises(ValueError, match="one value per scenario"):
        PlantSimulator([Scenario(0.005)], config=CFG, parameters={"wheel_coulomb_friction.torque_Nm": [1.0, 2.0]})


def test_per_scenario_parameters_equal_separate_runs():
    torques = np.array([0.0, 0.7, 1.5])
    batch = PlantSimulator([Scenario(0.005, seed=1)] * 3, config=CFG, noise=True,
                           parameters={"wheel_coulomb_friction.torque_Nm": torques}).run(3000)
    for i, t in enumerate(torques):
        cfg = CFG.with_overrides({"wheel_coulomb_friction.torque_Nm": float(t)})
        alone = PlantSimulator([Scenario(0.005, seed=1)], config=cfg, noise=True).run(3000)
        assert np.array_equal(batch.a1[i], alone.a1[0]) and np.array_equal(batch.a2[i], alone.a2[0])
    assert not np.array_equal(batch.a1[0], batch.a1[2])


def test_common_random_numbers_share_the_noise():
    scen = [Scenario(0.005, seed=1), Scenario(0.005, seed=2), Scenario(0.01, seed=3)]
    crn = PlantSimulator(scen, config=CFG, noise=True, noise_seed=42)
    load = crn.motor_load_pu(0, 20000)
    assert np.array_equal(load[0], load[1]) and np.array_equal(load[0], load[2])
    ch = PlantSimulator(scen, config=CFG, noise=True, noise_seed=42).run(2000)
    assert np.array_equal(ch.a1[0], ch.a1[1])                # same parameters, same noise: same signals
    default = PlantSimulator(scen, config=CFG, noise=True)      # default: each scenario its own noise
    load_d = default.motor_load_pu(0, 20000)
    assert not np.array_equal(load_d[0], load_d[1])
    other = PlantSimulator(scen, config=CFG, noise=True, noise_seed=43).motor_load_pu(0, 20000)
    assert not np.array_equal(other[0], load[0])
    # one seed per scenario: equal seeds share a realisation, the 43 one equals the batch-wide 43
    per = PlantSimulator(scen, config=CFG, noise=True, noise_seed=[42, 43, 42]).motor_load_pu(0, 20000)
    assert np.array_equal(per[0], load[0]) and np.array_equal(per[1], other[1]) and np.array_equal(per[2], load[0])
    with pytest.raises(ValueError, match="one per scenario"):
        PlantSimulator(scen, config=CFG, noise_seed=[1, 2])


def test_simulate_set_switches_a_catalogue_effect(tmp_path):
    out = tmp_path / "s.npz"
    args = ["simulate", "--widths", "0.005", "--eta-k", "0.025", "--n1", "0.89", "--duration", "0.02",
            "--no-noise", "--no-progress", "--overwrite", "--set", "simulation.run_in_s=0", "-o", str(out)]
    assert main(args + ["--set", "effects.mass_force_offset=true", "--set", "mass_force_offset.force_N=5"]) == 0
    with_effect = np.load(out)["a2"]
    assert main(args) == 0
    nominal = np.load(out)["a2"]
    assert with_effect[0, 0] - nominal[0, 0] == pytest.approx(5.0 / 10.0, rel=1e-9)     # F/m
    assert main(args + ["--set", "effects.mass_force_ofset=true"]) == 2                  # one-line error


def test_users_effect_from_a_file_runs_like_the_same_built_in_term(tmp_path):
    """docs/examples/my_effects.py via --effects: its copy of wheel_viscous_friction gives the built-in's
    signals bit for bit, and its own wheel_drag works from the command line."""
    mine = builtin_catalogue().copy()
    assert set(mine.load_effects_file(EXAMPLE)) == {"wheel_drag", "my_viscous_wheel"}
    scen = [Scenario(0.005, seed=2)]
    base = {"simulation.run_in_s": 0.0}
    builtin = PlantSimulator(scen, config=load_plant_config(overrides={
        **base, "effects.wheel_viscous_friction": True, "wheel_viscous_friction.damping_Nms_per_rad": 0.01}),
        noise=True).run(3000)
    plugin = PlantSimulator(scen, config=load_plant_config(overrides={
        **base, "effects.my_viscous_wheel": True, "my_viscous_wheel.damping_Nms_per_rad": 0.01}, catalogue=mine),
        noise=True).run(3000)
    assert np.array_equal(builtin.a1, plugin.a1) and np.array_equal(builtin.a2, plugin.a2)
    out = tmp_path / "d.npz"
    assert main(["simulate", "--effects-file", str(EXAMPLE), "--set", "effects.wheel_drag=true",
                 "--set", "wheel_drag.coefficient_Nms2_per_rad2=1e-4", "--widths", "0.005", "--eta-k", "0.025",
                 "--n1", "0.89", "--duration", "0.01", "--no-noise", "--no-progress", "--set", "simulation.run_in_s=0",
                 "-o", str(out)]) == 0
    assert np.load(out)["a1"].shape == (1, 500)


def test_entry_point_plugin_and_bad_terms(monkeypatch):
    import importlib.metadata as md

    from backlash_monitor.plant import effects as E

    class EpEffect(Effect):
        name = "ep_test_effect"
        balance = "mass_force_N"
        description = "a test force from an entry point"
        parameters = (Parameter("force_N", "N", 0.0, (-1.0, 1.0)),)

        @staticmethod
        def term(force_N):
            return force_N

    class FakeEP:
        def load(self):
            return EpEffect

    mine = builtin_catalogue().copy()      # built before the fake entry point exists: it stays without it
    monkeypatch.setattr(md, "entry_points", lambda group=None: [FakeEP()] if group == E.ENTRY_POINT_GROUP else [])
    assert mine.load_entry_points() == ["ep_test_effect"]
    assert "ep_test_effect" in mine and "ep_test_effect" not in builtin_catalogue()

    class Bad(Effect):
        name = "bad_effect"
        balance = "wheel_torque_Nm"
        description = "names a variable that does not exist"
        parameters = ()

        @staticmethod
        def term(omega_2):
            return -omega_2

    with pytest.raises(ValueError, match="nearest: 'omega2'"):
        mine.register(Bad)


@pytest.mark.process
@pytest.mark.ros
def test_live_node_publishes_the_same_effects_as_a_batch_run(ros_env):
    """plant_simulator with plant_set (a compiled term and sensor stages) and effects_files: the published a1/a2
    equal a batch PlantSimulator run with the same config (sensor effects applied the same way live and batch)."""
    import os

    import rclpy
    from rclpy.parameter import Parameter as RosParameter

    from backlash_monitor.ros.conversions import from_float64_field
    from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
    from backlash_monitor_msgs.msg import SignalChunk
    sets = ("simulation.run_in_s=0.1;effects.wheel_coulomb_friction=true;wheel_coulomb_friction.torque_Nm=0.5;"
            "effects.accelerometer_bias=true;accelerometer_bias.a2_m_s2=0.25;effects.accelerometer_lowpass=true;"
            "accelerometer_lowpass.a1_time_constant_s=1e-4;effects.wheel_drag=true;"
            "wheel_drag.coefficient_Nms2_per_rad2=1e-5")
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    rclpy.init()
    received = {"a1": [], "a2": []}
    try:
        plant = PlantSimulatorNode(parameter_overrides=[
            RosParameter("rate_factor", value=0.0), RosParameter("duration_s", value=0.04),
            RosParameter("qos", value="reliable"), RosParameter("chunk_samples", value=1000),
            RosParameter("plant_set", value=sets), RosParameter("effects_files", value=str(EXAMPLE))])
        listener = rclpy.create_node("listener")
        for name in received:
            listener.create_subscription(SignalChunk, f"plant/{name}", lambda msg, n=name: received[n].append(msg), 100)
        executor = rclpy.executors.SingleThreadedExecutor()
        executor.add_node(plant)
        executor.add_node(listener)
        for _ in range(400):
            executor.spin_once(timeout_sec=0.05)
            if all(len(v) == 2 for v in received.values()):
                break
    finally:
        rclpy.try_shutdown()
    from backlash_monitor.plant.config import parse_override
    cfg = load_plant_config(overrides=dict(parse_override(t) for t in sets.split(";")),
                            catalogue=builtin_catalogue().with_files([EXAMPLE]))
    batch = PlantSimulator([Scenario(0.005, 0.025, 0.89, seed=0)], config=cfg, noise=True).run(2000)
    for name in received:
        live = np.concatenate([from_float64_field(m.samples) for m in received[name]])
        ref = getattr(batch, name)[0]
        assert live.shape == ref.shape
        assert np.allclose(live, ref, rtol=1e-9, atol=1e-9 * np.max(np.abs(ref))), name


def test_a_term_that_does_not_compile_is_one_line_error(tmp_path):
    f = tmp_path / "bad_term.py"
    f.write_text("from backlash_monitor.plant.effects import Effect, Parameter\n"
                 "class BadTerm(Effect):\n"
                 "    name = 'bad_term_effect'\n"
                 "    balance = 'wheel_torque_Nm'\n"
                 "    description = 'adds a dict to a number (not allowed in a term)'\n"
                 "    parameters = (Parameter('k', '-', 0.0, (0.0, 1.0)),)\n"
                 "    @staticmethod\n"
                 "    def term(omega2, k):\n"
                 "        return k * omega2 + {}\n")
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0, "effects.bad_term_effect": True},
                            catalogue=builtin_catalogue().with_files([f]))
    with pytest.raises(ValueError, match="does not compile.*allowed in a term"):
        PlantSimulator([Scenario(0.005)], config=cfg, backend="numba-scalar").run(2)


def test_sensor_plugin_stage_acts_on_the_published_signal():
    """A user's sensor stage (kind 'sensor', apply(signal, a, values, state, h)): an accelerometer range limit."""
    from backlash_monitor.plant import effects as E

    class AccelerometerRange(Effect):
        name = "test_accelerometer_range"
        balance = E.SENSOR_BALANCE
        kind = "sensor"
        order = 3                    # after the built-in low-pass (0), gain (1), bias (2)
        description = "the accelerometer saturates at +-limit"
        parameters = (Parameter("a1_limit_m_s2", "m/s^2", 1000.0, (0.0, 1e4)),
                      Parameter("a2_limit_m_s2", "m/s^2", 1000.0, (0.0, 1e4)))

        @staticmethod
        def apply(signal, a, values, state, h):
            lim = values[f"{signal}_limit_m_s2"][:, None]
            return np.clip(a, -lim, lim)

    mine = builtin_catalogue().copy()
    mine.register(AccelerometerRange)
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0, "effects.test_accelerometer_range": True,
                                       "test_accelerometer_range.a1_limit_m_s2": 5.0}, catalogue=mine)
    base = PlantSimulator([Scenario(0.005)], config=load_plant_config(overrides={"simulation.run_in_s": 0.0}),
                          noise=True).run(4000)
    ch = PlantSimulator([Scenario(0.005)], config=cfg, noise=True).run(4000)
    assert np.array_equal(ch.a1, np.clip(base.a1, -5.0, 5.0)) and np.max(np.abs(base.a1)) > 5.0
    assert np.array_equal(ch.a2, base.a2) and np.array_equal(ch.omega1, base.omega1)
