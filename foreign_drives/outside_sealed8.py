"""Outside mechanisms, eighth SEALED half (issue 31 part 4, set 8).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed8``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first seven sets
nor the eighth development half (:mod:`outside_dev8`) has, and the suite's rows (seeds 8900+). The split rule is in
:mod:`outside_dev8` (written as one list of fourteen; the even numbers are here; 8, 10, 12 with a memory, 2, 4, 6, 14
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed8")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed as a CONSTANT POWER: a generator on the motor's free shaft end feeds a
   regulated consumer (a DC bus with a constant-power load): T = P/Omega1 (a hyperbolic law: the load falls as the
   speed rises, a negative slope);
4. wheel torque x the wheel angle as a SAWTOOTH: a snail (drop) cam on the wheel shaft winds up a knock-out spring
   over each turn and lets it snap at the cam's drop: -T*((theta2 - phi) mod 2*pi)/(2*pi), theta2 the wheel angle
   unwrapped from the run-in's start (a torque rising linearly over a turn and falling at once: not a harmonic);
6. clutch torque x the contact torque GATED by the motor angle: one of the n jaw teeth on the motor's half is cracked
   and softer; while it is the one engaged (one n-th of each motor turn, from the motor angle phi on) the contact passes
   (1 - g) of its torque: -g*T_c*[(alpha1 - phi) mod 2*pi < 2*pi/n] (a tooth fault: the contact modulated by a
   rectangular window of the angle, once per turn);
8. mass force x the load pulse through a DRAINING TANK: each stroke's coolant runs into a tray on the carriage at a
   rate q while the pulse is on and drains through an orifice at c*sqrt(V) (Torricelli); the water's weight presses
   the carriage onto its rail: a friction -mu_g*V against its (forward) motion, V' = q*pulse - c*sqrt(V) (advanced
   every 0.2 ms from V = 0 at the run-in's start: a nonlinear store, not a linear lag);
10. a1 sensor x a1's own magnitude through an AUTO-RANGING with hysteresis: a1's module switches to its coarse range
    at the first sample with |a| > R_hi and back to its fine range at the first with |a| < R_lo; in the coarse range
    the reading has a gain error g and steps q: y = q*round((1 + g)*a/q), in the fine range y = a (the reading's
    error switched by the signal's own history);
12. motor load moment x the motor speed through a THREE-POINT STEP CONTROLLER: a motorised throttle on a pump on the
    motor's shaft end is driven by a step controller: while Omega1 has been above Omega_ref + b (below Omega_ref - b)
    for T_s since the last step, the throttle opens (closes) one step, within 0..N steps; the pump loads the motor with
    K per step open (scanned every 0.2 ms: a stepping integrator with a dead band);
14. mass force x the mass speed through an EDDY-BRAKE CHARACTERISTIC: a linear eddy-current rail brake on the carriage
    at its real speed characteristic, -2*F_m*(v/v_c)/(1 + (v/v_c)^2): a force that peaks at the critical speed v_c and
    FALLS above it (the carriage runs above v_c: a negative slope, not a viscous drag).

Visibility, measured (as in :mod:`outside_dev8`: one simulation of each row, 4 s, against the same spec without the
mechanism, same seed): 2 a2 0.0138 at 450 W, scaled once x5.45 (2452 W) -> 0.112; 4 a2 0.0807; 6 a2 0.0189 at g =
0.4: its scaling x3.96 would put g at 1.58, beyond its bound 1 (the cracked tooth pulling the halves apart), so it was
left at 0.4, BELOW the visibility criterion; 8 a2 0.0584; 10 a1 1.02; 12 a2 0.0193 at 0.3 N*m per step, scaled once
x3.89 (1.17 N*m) -> 0.0593; 14 a2 0.116.
"""
from __future__ import annotations

import math

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory
from .outside_dev6 import set_extra
from .outside_dev8 import _PHASE


# 2. motor load moment x the motor speed as a constant power
class MotorShaftGeneratorConstantPower(OutsideForm):
    name = "motor_shaft_generator_constant_power"
    half = "sealed8"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a generator on the motor's free shaft end feeds a regulated consumer (a DC bus with a constant-power "
                   "load): a load moment P/Omega1")
    parameters = (Param("power_W", "W", (0.0, 5000.0), "P"),)
    note = "a hyperbolic law of the speed: the load falls as the speed rises (a negative slope)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["power_W"], (K.XS_OMEGA1, K.XF_POWER, -1.0, 0.0, 0.0))

    def law(self, p):
        return f"motor load moment += {p['power_W']:.6g} W / Omega1"


# 4. wheel torque x the wheel angle as a sawtooth
class WheelSnailCamKnockout(OutsideForm):
    name = "wheel_snail_cam_knockout"
    half = "sealed8"
    balance = "wheel_torque"
    depends_on = ("wheel_angle",)
    description = ("a snail (drop) cam on the wheel shaft winds up a knock-out spring over each turn and lets it snap at "
                   "the cam's drop: -T*((theta2 - phi) mod 2*pi)/(2*pi), theta2 the wheel angle unwrapped from the "
                   "run-in's start")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T: the torque just before the drop"), _PHASE)
    note = "a sawtooth of the wheel angle: rising linearly over a turn, falling at once"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"] / (2.0 * math.pi),
                 (K.XS_ALPHA2_UNWRAPPED, K.XF_MOD, 2.0 * math.pi, p["phase_rad"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * ((theta2 - {p['phase_rad']:.6g}) mod 2*pi)/(2*pi), theta2 "
                "the wheel angle unwrapped from the run-in's start")


# 6. clutch torque x the contact torque gated by the motor angle
class ClutchCrackedJawTooth(OutsideForm):
    name = "clutch_cracked_jaw_tooth"
    half = "sealed8"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration", "motor_angle")
    description = ("one of the n jaw teeth on the motor's half is cracked and softer: while it is the one engaged (one "
                   "n-th of each motor turn, from the motor angle phi on) the contact passes (1 - g) of its torque: "
                   "-g*T_c*[(alpha1 - phi) mod 2*pi < 2*pi/n]")
    parameters = (Param("softening", "-", (0.0, 1.0), "g"), Param("teeth", "-", (1, 24), "n", "int"), _PHASE)
    note = "the contact modulated by a rectangular window of the motor angle, once per turn (a tooth fault)"

    def apply(self, b, p):
        add_term(b, "clutch_torque", -p["softening"], (K.XS_CONTACT_TORQUE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_ALPHA1, K.XF_PERIODIC_GATE, 2.0 * math.pi, p["phase_rad"], 2.0 * math.pi / int(p["teeth"])),
                 nonperiodic=True)

    def law(self, p):
        n = int(p["teeth"])
        return (f"clutch torque += -{p['softening']:.6g} * T_c while (alpha1 - {p['phase_rad']:.6g}) mod 2*pi < 2*pi/{n}, "
                "T_c the contact law's torque")


# 8. mass force x the load pulse through a draining tank
class MassCoolantTrayFriction(OutsideForm):
    name = "mass_coolant_tray_friction"
    half = "sealed8"
    balance = "mass_force"
    depends_on = ("load_pulse",)
    description = ("each stroke's coolant runs into a tray on the carriage at q while the pulse is on and drains through "
                   "an orifice at c*sqrt(V); its weight presses the carriage onto its rail: a friction -mu_g*V against "
                   "the (forward) motion, V -> max(0, V + 0.2 ms*(q*pulse - c*sqrt(V))) every 0.2 ms from V = 0 at the "
                   "run-in's start")
    parameters = (Param("inflow_kg_s", "kg/s", (0.0, 100.0), "q"),
                  Param("drain_kg_s_per_sqrt_kg", "kg^0.5/s", (0.0, 100.0), "c"),
                  Param("friction_N_per_kg", "N/kg", (0.0, 20.0), "mu_g: the rail friction per kg in the tray"))
    note = "a nonlinear store filled by the process (a Torricelli drain), not a linear lag"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_TANK, K.XS_PULSE, p["inflow_kg_s"], p["drain_kg_s_per_sqrt_kg"])
        add_term(b, "mass_force", -p["friction_N_per_kg"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['friction_N_per_kg']:.6g} N/kg * V, V -> max(0, V + 0.2 ms*({p['inflow_kg_s']:.6g} kg/s"
                f" * pulse - {p['drain_kg_s_per_sqrt_kg']:.6g}*sqrt(V))) every 0.2 ms from 0 at the run-in's start")


# 10. a1 sensor x a1's own magnitude through an auto-ranging with hysteresis
class A1AutoRanging(OutsideForm):
    name = "a1_auto_ranging"
    half = "sealed8"
    stage = "sensor"
    order = 1                      # the module, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1's module switches to its coarse range at the first sample with |a| > R_hi and back to its fine "
                   "range at the first with |a| < R_lo (fine at the pre-roll's first sample); coarse: y = q*round((1 + "
                   "g)*a/q), fine: y = a")
    parameters = (Param("up_m_s2", "m/s^2", (1.0, 10000.0), "R_hi"), Param("down_m_s2", "m/s^2", (0.1, 10000.0), "R_lo"),
                  Param("gain_error", "-", (-0.5, 0.5), "g"), Param("step_m_s2", "m/s^2", (1e-4, 100.0), "q"))
    note = "a reading whose error a relay on its own magnitude switches (a memory of the range)"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        coarse = np.zeros(a.size, dtype=bool)
        on = False
        for i, v in enumerate(np.abs(a).tolist()):
            if v > p["up_m_s2"]:
                on = True
            elif v < p["down_m_s2"]:
                on = False
            coarse[i] = on
        q = p["step_m_s2"]
        return np.where(coarse, q * np.round((1.0 + p["gain_error"]) * a / q), a)

    def law(self, p):
        return (f"a1 sensor = {p['step_m_s2']:.6g}*round({1.0 + p['gain_error']:.6g}*a1/{p['step_m_s2']:.6g}) from a "
                f"sample with |a1| > {p['up_m_s2']:.6g} until one with |a1| < {p['down_m_s2']:.6g} m/s^2, else a1")


# 12. motor load moment x the motor speed through a three-point step controller
class MotorStepControlledThrottle(OutsideForm):
    name = "motor_step_controlled_throttle"
    half = "sealed8"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a motorised throttle on a pump on the motor's shaft end is driven by a three-point step controller: "
                   "while Omega1 has been above Omega_ref + b (below Omega_ref - b) at every 0.2 ms scan for T_s since "
                   "the last step, the throttle opens (closes) one step, within 0..N steps (closed at the run-in's "
                   "start); the pump loads the motor with K per step open")
    parameters = (Param("torque_per_step_Nm", "N*m", (0.0, 10.0), "K"),
                  Param("reference_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_ref: the controller's set speed"),
                  Param("dead_band_rad_s", "rad/s", (0.0, 20.0), "b"),
                  Param("step_time_s", "s", (2e-4, 1.0), "T_s (a multiple of 0.2 ms)"),
                  Param("steps", "-", (1, 100), "N", "int"))
    note = "a stepping integrator with a dead band: the load moves in whole steps at most one per T_s"

    def apply(self, b, p):
        segments(p["step_time_s"], f"{self.name}: step_time_s")
        set_memory(b, self.name, K.MK_STEP, K.XS_OMEGA1, p["reference_speed_rad_s"], p["dead_band_rad_s"],
                   p["step_time_s"])
        set_extra(b, float(int(p["steps"])))
        add_term(b, "motor_load_moment", p["torque_per_step_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_per_step_Nm']:.6g} N*m * u, u -> u +- 1 (within 0..{int(p['steps'])}) "
                f"after {p['step_time_s']:.6g} s of scans with Omega1 above (below) {p['reference_speed_rad_s']:.6g} +- "
                f"{p['dead_band_rad_s']:.6g} rad/s since the last step")


# 14. mass force x the mass speed through an eddy-brake characteristic
class MassEddyRailBrakeCharacteristic(OutsideForm):
    name = "mass_eddy_rail_brake_characteristic"
    half = "sealed8"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("a linear eddy-current rail brake on the carriage at its real speed characteristic: "
                   "-2*F_m*(v/v_c)/(1 + (v/v_c)^2), peaking at the critical speed v_c and falling above it")
    parameters = (Param("peak_force_N", "N", (0.0, 200.0), "F_m"),
                  Param("critical_speed_m_s", "m/s", (0.1, 100.0), "v_c"))
    note = "a force with a maximum in the speed: above v_c a negative slope, not a viscous drag"

    def apply(self, b, p):
        vc = p["critical_speed_m_s"]
        add_term(b, "mass_force", -2.0 * p["peak_force_N"] / vc, (K.XS_MASS_SPEED, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_MASS_SPEED, K.XF_LORENTZ, vc, 0.0, 0.0))

    def law(self, p):
        vc = p["critical_speed_m_s"]
        return f"mass force += -2*{p['peak_force_N']:.6g} N * (v/{vc:.6g} m/s)/(1 + (v/{vc:.6g} m/s)^2)"


FORM_CLASSES = (MotorShaftGeneratorConstantPower, WheelSnailCamKnockout, ClutchCrackedJawTooth, MassCoolantTrayFriction,
                A1AutoRanging, MotorStepControlledThrottle, MassEddyRailBrakeCharacteristic)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 8900+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 450 W a priori (3 N*m at 150 rad/s), a2 0.0138: scaled once x5.45 (16 N*m at 150 rad/s)
        ("os8_motor_shaft_generator_constant_power", "outside", 0.0069, 0.0305, 0.92,
         [E("motor_shaft_generator_constant_power", {"power_W": 2452.0})]),
        # a knock-out spring wound to 4 N*m over each wheel turn
        ("os8_wheel_snail_cam_knockout", "outside", 0.0052, 0.0245, 0.95,
         [E("wheel_snail_cam_knockout", {"torque_Nm": 4.0, "phase_rad": 1.0})]),
        # one of six teeth passing 60 % of the contact's torque; BELOW the visibility criterion (a2 0.0189): its
        # scaling x3.96 would put g at 1.58, beyond its bound 1 (a tooth pulling), so it was left (module docstring)
        ("os8_clutch_cracked_jaw_tooth", "outside", 0.0084, 0.0175, 0.90,
         [E("clutch_cracked_jaw_tooth", {"softening": 0.4, "teeth": 6, "phase_rad": 0.3})]),
        # about 0.6 kg per stroke into the tray, about 1 kg in it on average, 4 N of friction per kg
        ("os8_mass_coolant_tray_friction", "outside", 0.0046, 0.0395, 0.93,
         [E("mass_coolant_tray_friction", {"inflow_kg_s": 10.0, "drain_kg_s_per_sqrt_kg": 2.4,
                                           "friction_N_per_kg": 4.0})]),
        ("os8_clean_w6.1_eta0.0225_n0.91", "clean", 0.0061, 0.0225, 0.91, []),
        # the coarse range above 60 m/s^2 until below 20 (a1 of a clean drive: within +-110 m/s^2 for 99 %)
        ("os8_a1_auto_ranging", "outside", 0.0093, 0.0285, 0.96,
         [E("a1_auto_ranging", {"up_m_s2": 60.0, "down_m_s2": 20.0, "gain_error": 0.05, "step_m_s2": 2.0})]),
        # 20 steps, one step per 20 ms outside 151.5 +- 0.5 rad/s; 0.3 N*m per step a priori, a2 0.0193: scaled once
        # x3.89
        ("os8_motor_step_controlled_throttle", "outside", 0.0057, 0.0215, 0.89,
         [E("motor_step_controlled_throttle", {"torque_per_step_Nm": 1.17, "reference_speed_rad_s": 151.5,
                                               "dead_band_rad_s": 0.5, "step_time_s": 0.02, "steps": 20})]),
        # 10 N at 15 m/s; the carriage at ~22.7 m/s on the falling side
        ("os8_mass_eddy_rail_brake_characteristic", "outside", 0.0078, 0.0335, 0.94,
         [E("mass_eddy_rail_brake_characteristic", {"peak_force_N": 10.0, "critical_speed_m_s": 15.0})]),
    ]
