"""What measurement would tell two candidate effects apart, from where each acts on the drive.

Two candidates that explain a recording's residual about equally produce the same a1/a2 signature
there; what separates them is a quantity on which they act differently. That follows from *where*
each acts (its balance, or for a parameter drift the parameter it changes): the motor side, the
coupling, the load wheel, the rim-mass link, the mass, or the accelerometer itself.
"""
from __future__ import annotations

# where an effect acts, by balance (plant/effects.py BALANCES) ...
LOCATION_OF_BALANCE = {
    "motor_load_moment_pu": "motor",
    "clutch_torque_Nm": "coupling",
    "coupling_torque_Nm": "coupling",
    "wheel_torque_Nm": "wheel",
    "rim_mass_force_N": "rim_mass",
    "mass_force_N": "mass",
    "sensor_a1_a2": "sensor",
}
# ... and, for a parameter drift, by the parameter it changes (effects.DRIFTS' targets)
LOCATION_OF_DRIFT_TARGET = {
    "width_m": "coupling",
    "eta_k": "rim_mass",
    "n1": "rim_mass",
    "spring.stiffness_N_per_m": "rim_mass",
    "mass_kg": "mass",
    "wheel_inertia_kgm2": "wheel",
    "working_resistance.force_N": "mass",
    "pulse_load.amplitude_pu": "motor",
    "rotor_resistance_pu": "motor",
    "supply_voltage_scale": "motor",
}
PLACE = {"motor": "the motor side", "coupling": "the clutch (coupling)", "wheel": "the load wheel",
         "rim_mass": "the spring/absorber between rim and mass", "mass": "the mass",
         "sensor": "the accelerometer itself"}

_BETWEEN = {
    frozenset({"motor", "wheel"}): "the load wheel's speed Omega2 (an encoder on the load side) or the "
    "shaft torque (a torque sensor): while the clutch is open a motor-side term changes omega1 only and "
    "a wheel term Omega2 only",
    frozenset({"motor", "coupling"}): "the angle difference alpha1 - alpha2 under load (encoders on both "
    "shafts): a coupling change moves the deflection in contact, a motor-side load does not",
    frozenset({"motor", "rim_mass"}): "the load wheel's speed Omega2 or the spring force (a load cell): a "
    "motor-side term reaches the load only through the clutch",
    frozenset({"motor", "mass"}): "the shaft torque (a torque sensor) or the spring force (a load cell): "
    "a motor-side load changes the torque the motor delivers, a force on the mass the force in the spring",
    frozenset({"wheel", "mass"}): "the load wheel's speed Omega2 during the gap traversal (an encoder on "
    "the load side) or the spring force (a load cell): inside the gap a wheel torque decelerates the "
    "wheel directly, a force on the mass reaches the wheel only through the spring",
    frozenset({"wheel", "rim_mass"}): "the load wheel's speed Omega2 together with the mass position x "
    "(an encoder and a displacement sensor): a wheel term acts on Omega2, a spring/absorber change on "
    "the extension between rim and mass",
    frozenset({"rim_mass", "mass"}): "the spring extension or the mass position x (a displacement "
    "sensor): a constant force on the mass shifts it statically, a spring/absorber change alters its "
    "dynamics",
    frozenset({"wheel", "coupling"}): "the angle difference alpha1 - alpha2 in contact (encoders on both "
    "shafts): a coupling change moves the deflection under load, a wheel term does not",
    frozenset({"coupling", "rim_mass"}): "the angle difference alpha1 - alpha2 in contact (encoders on "
    "both shafts) against the spring extension",
    frozenset({"coupling", "mass"}): "the angle difference alpha1 - alpha2 in contact (encoders on both "
    "shafts) against the spring force (a load cell)",
}


def location(effect_name: str, balance: str, drift_target: str | None = None) -> str:
    """'motor', 'coupling', 'wheel', 'rim_mass', 'mass', 'sensor' or 'unknown'."""
    if drift_target is not None and drift_target in LOCATION_OF_DRIFT_TARGET:
        return LOCATION_OF_DRIFT_TARGET[drift_target]
    return LOCATION_OF_BALANCE.get(balance, "unknown")


def separating_measurement(name_a: str, where_a: str, name_b: str, where_b: str) -> str:
    """One sentence: what recording or sensor would separate candidate A (acting at ``where_a``)
    from candidate B (at ``where_b``)."""
    a, b = PLACE.get(where_a, where_a), PLACE.get(where_b, where_b)
    if where_a == "sensor" and where_b == "sensor":
        return (f"{name_a} and {name_b} are both sensor effects: a calibration of the accelerometer "
                "separates them (a static tilt for a bias, a known sine for a gain, a swept sine for a "
                "roll-off)")
    if "sensor" in (where_a, where_b):
        sensor, physical = (name_a, name_b) if where_a == "sensor" else (name_b, name_a)
        return (f"{sensor} changes only what that accelerometer reports, {physical} the motion every "
                "sensor sees: a second accelerometer beside it (or its calibration) separates them")
    both = f"{name_a} {name_b}"
    if where_a == where_b == "motor" and any(d in both for d in MOTOR_DEFICIT_DRIFTS):
        if any(t in both for t in MOTOR_SLIP_EFFECTS + ("pulse_amplitude_drift", "torque_ripple")):
            return (f"{name_a} and {name_b} both slow the motor; the stator current and the supply voltage separate a "
                    "weaker motor from a load on it: a load or friction draws more current at the nominal voltage, "
                    "a hot rotor slips more at the same current, a low supply shows in the voltage itself")
        return (f"{name_a} and {name_b} are both a weaker motor: the supply voltage at its terminals separates them "
                "(a hot rotor leaves it nominal)")
    if where_a == where_b:
        return (f"{name_a} and {name_b} both act on {a} and differ only in how they depend on speed, "
                "deflection or load: a recording at another operating point (another motor speed, "
                "pulse amplitude or working load) changes one and not the other")
    between = _BETWEEN.get(frozenset({where_a, where_b}))
    if between is None:
        return (f"{name_a} acts on {a}, {name_b} on {b}: a sensor between the two places, or a "
                "recording at another operating point, separates them")
    return f"{name_a} acts on {a}, {name_b} on {b}: measure {between}"


# a load or friction on the motor shaft and a motor that makes less torque than the model's (a hot rotor, a low supply
# voltage) both slow the motor by more slip. The catalogue fits both (rotor_resistance_drift, supply_voltage_drift),
# and they often differ in how the slip follows the pulses (a hot rotor's torque-slip curve is flatter), but not
# always: a foreign supply voltage -15 % was fitted better by a motor Coulomb friction of 4.7 N*m (delta_ic -123 vs
# -115). So a motor-side torque named without a weaker motor beside it carries this caveat.
MOTOR_TORQUE_DEFICIT = (
    "a motor that makes less torque than the model's (a low supply voltage, a hot rotor: more slip at the same "
    "load) slows the drive the same way on one recording; the stator current and the supply voltage separate "
    "them: a load or friction draws more current at the nominal voltage, a hot rotor slips more at the same "
    "current, a low supply shows in the voltage itself")


# the catalogue's constant torques on the motor shaft: what shifts the motor's mean slip as a weaker motor does (a
# pulse-amplitude drift or a ripple acts on the motor side too, but changes the load's swing, not its mean)
MOTOR_SLIP_EFFECTS = ("motor_coulomb_friction", "motor_load_offset")
# ... and the weaker motor's own drifts
MOTOR_DEFICIT_DRIFTS = ("rotor_resistance_drift", "supply_voltage_drift")


# a hot rotor and a low supply differ only in how the slip follows fast load changes (the rotor's time constant):
# measured on a foreign rotor resistance +45 %, the supply drift was named at delta_ic -133.2, the rotor's -131.1 (a
# 2.02 gap, just beyond DELTA_IC_TIE); so either one named alone carries this note
WEAKER_MOTOR_CAUSES = ("a hot rotor and a low supply voltage weaken the motor alike on one recording (they differ only "
                       "in how its slip follows fast load changes); the supply voltage at the motor's terminals "
                       "separates them")


def motor_side_note(effect: str, twins=()) -> str:
    """The caveat to a discovery on the motor's torque: for a constant motor-shaft torque, that a weaker motor looks
    the same; for one weaker-motor drift, that the other one may be the cause ('' for any other effect, and when the
    alternative is already named beside it in ``twins``: the separating sentence then says it)."""
    name, named = effect.split("[")[0], {t.split("[")[0] for t in twins}
    if name in MOTOR_SLIP_EFFECTS and not named & set(MOTOR_DEFICIT_DRIFTS):
        return MOTOR_TORQUE_DEFICIT
    if name in MOTOR_DEFICIT_DRIFTS and not named & (set(MOTOR_DEFICIT_DRIFTS) - {name}):
        return WEAKER_MOTOR_CAUSES
    return ""
