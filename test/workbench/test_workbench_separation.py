"""diagnose names what would separate two indistinguishable candidates, from where each acts."""
from backlash_monitor.plant import effects as plant_effects
from backlash_monitor.plant.catalogue import builtin_catalogue
from backlash_monitor.workbench import separation


def _where(name):
    cls = builtin_catalogue()[name]
    return separation.location(name, cls.balance, getattr(cls, "target", None))


def test_every_catalogue_effect_has_a_place_on_the_drive():
    for cls in plant_effects.CATALOGUE:
        assert _where(cls.name) in separation.PLACE, cls.name


def test_drifts_act_where_their_parameter_sits():
    assert _where("working_resistance_drift") == _where("mass_force_offset") == "mass"
    assert _where("backlash_width_drift") == _where("clutch_contact_stiffness") == "coupling"
    assert _where("wheel_inertia_drift") == _where("wheel_coulomb_friction") == "wheel"
    assert _where("pulse_amplitude_drift") == _where("motor_load_offset") == "motor"


def test_wheel_friction_against_working_resistance_needs_a_load_side_sensor():
    text = separation.separating_measurement("wheel_coulomb_friction", _where("wheel_coulomb_friction"),
                                             "working_resistance_drift", _where("working_resistance_drift"))
    assert "Omega2" in text and "load cell" in text


def test_a_sensor_effect_against_a_physical_one_needs_a_second_accelerometer():
    text = separation.separating_measurement("accelerometer_gain[a2]", "sensor", "load_mass_drift",
                                             _where("load_mass_drift"))
    assert "second accelerometer" in text


def test_two_effects_at_one_place_need_another_operating_point():
    text = separation.separating_measurement("wheel_coulomb_friction", "wheel",
                                             "wheel_viscous_friction", "wheel")
    assert "another operating point" in text


def test_every_pair_of_places_has_a_sentence():
    places = list(separation.PLACE)
    for a in places:
        for b in places:
            text = separation.separating_measurement("A", a, "B", b)
            assert "A" in text and "B" in text and len(text) > 40


def test_a_constant_motor_shaft_torque_carries_the_weaker_motor_caveat_and_nothing_else_does():
    """A load or friction on the motor shaft and a weaker motor (supply voltage, hot rotor) shift the motor's mean
    slip alike: the caveat names the measurement that separates them. A drift of the pulse amplitude or a ripple
    acts on the motor side too, but changes the load's swing, not its mean: no caveat."""
    for name in ("motor_coulomb_friction", "motor_load_offset"):
        note = separation.motor_side_note(name)
        assert "supply voltage" in note and "stator current" in note
    for name in ("pulse_amplitude_drift", "torque_ripple", "wheel_coulomb_friction", "accelerometer_gain[a1]"):
        assert separation.motor_side_note(name) == ""


def test_a_weaker_motor_named_beside_a_motor_torque_replaces_the_caveat_with_its_separating_sentence():
    """When the catalogue's weaker-motor drifts (rotor resistance, supply voltage) tie with a motor-side torque, the
    separating sentence names the stator current and the supply voltage, and the caveat is not said twice; two
    weaker-motor drifts are told apart by the supply voltage alone."""
    assert separation.motor_side_note("motor_coulomb_friction", ["motor_load_offset", "rotor_resistance_drift"]) == ""
    assert separation.motor_side_note("motor_load_offset", ["motor_coulomb_friction"]) != ""
    text = separation.separating_measurement("motor_coulomb_friction", "motor", "supply_voltage_drift", "motor")
    assert "stator current" in text and "supply voltage" in text
    text = separation.separating_measurement("rotor_resistance_drift", "motor", "supply_voltage_drift", "motor")
    assert "supply voltage" in text and "stator current" not in text
    assert "terminals" in separation.motor_side_note("supply_voltage_drift", ["motor_coulomb_friction"])
    assert separation.motor_side_note("supply_voltage_drift", ["rotor_resistance_drift"]) == ""
    assert "operating point" in separation.separating_measurement("motor_coulomb_friction", "motor",
                                                                  "motor_load_offset", "motor")
