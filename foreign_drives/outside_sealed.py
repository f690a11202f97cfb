"""Outside mechanisms, SEALED half (issue 31 part 4).

SEALED: whoever builds or tunes the workbench's proposal of a missing term does not read this file, the suite it
makes (``python -m foreign_drives write --suite outside_sealed``), or its manifest, until the final, once-only
run. docs/foreign_drives.md lists these mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue nor the development half
(:mod:`outside_dev`) has, and the sealed suite's rows (seeds 7100+).
"""
from __future__ import annotations

import math

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (relative to the simulator's angle)")


class ClutchAntiBacklashSpring(OutsideForm):
    name = "clutch_anti_backlash_spring"
    half = "sealed"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("a torsion spring bridging the jaw halves (an anti-backlash coupling, or a rubber boot): a torque "
                   "k_a*D from the motor to the wheel at ALL times, D the jaw's angle difference (the penetration "
                   "measured from the gap's centre); in the gap it pulls the halves together")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 1000.0), "k_a"),)
    note = ("a potential torque (k_a*D^2/2): it stores energy, it does not dissipate; stiffer than ~60 N*m/rad it "
            "bounces the jaw back into the gap and re-triggers entries (measured: 80 N*m/rad, 17 onsets in 4 s)")

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["stiffness_Nm_per_rad"], (K.XS_JAW_ANGLE, K.XF_X, 0.0, 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += {p['stiffness_Nm_per_rad']:.6g} N*m/rad * D, D = alpha1 - alpha2 at the jaw, in "
                "and out of contact")


class MassPulseKick(OutsideForm):
    name = "mass_pulse_kick"
    half = "sealed"
    balance = "mass_force"
    depends_on = ("load_pulse",)
    description = ("the process that loads the motor also strikes the carriage at each stroke's start: a force "
                   "against the motion decaying from the pulse's start, -F*exp(-(t - t_pulse)/tau) while the pulse is on")
    parameters = (Param("force_N", "N", (0.0, 1000.0), "F"), Param("decay_s", "s", (1e-4, 1.0), "tau"))

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_N"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0))
        add_term(b, "mass_force", p["force_N"], (K.XS_PULSE_AGE, K.XF_RISE, p["decay_s"], 0.0, 0.0))

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * exp(-(t - t_pulse) / {p['decay_s']:.6g} s) while the load "
                "pulse is on (t_pulse: its start), else 0")


class A2ChannelCrosstalk(OutsideForm):
    name = "a2_channel_crosstalk"
    half = "sealed"
    stage = "sensor"
    order = 0
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("the two accelerometer channels share a cable and an ADC multiplexer: a fraction of the motor "
                   "side's acceleration leaks into the mass's channel, a2 += k*a1")
    parameters = (Param("gain_a1_to_a2", "-", (0.0, 0.1), "k"),)

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = sig["a2"] + p["gain_a1_to_a2"] * states["a1_physical"]

    def law(self, p):
        return f"a2 sensor += {p['gain_a1_to_a2']:.6g} * a1 (the motor side's physical acceleration)"


class MassOverspeedBrake(OutsideForm):
    name = "mass_overspeed_brake"
    half = "sealed"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("a centrifugal governor on the carriage's guide roller brakes it above a set speed: "
                   "-c*max(0, v - v0)^2, v the mass speed")
    parameters = (Param("coefficient_Ns2_per_m2", "N*s^2/m^2", (0.0, 1e5), "c"),
                  Param("set_speed_m_s", "m/s", (0.0, 100.0), "v0"))

    def apply(self, b, p):
        add_term(b, "mass_force", -p["coefficient_Ns2_per_m2"],
                 (K.XS_MASS_SPEED, K.XF_EXCESS_POWER, p["set_speed_m_s"], 2.0, 0.0))

    def law(self, p):
        return f"mass force += -{p['coefficient_Ns2_per_m2']:.6g} N*s^2/m^2 * max(0, v - {p['set_speed_m_s']:.6g})^2"


class WheelGuardRub(OutsideForm):
    name = "wheel_guard_rub"
    half = "sealed"
    balance = "wheel_torque"
    depends_on = ("wheel_angle", "wheel_speed")
    description = ("the load wheel runs slightly out of true and rubs its guard over part of each revolution: a "
                   "friction torque -T*max(0, sin(alpha2 + phi))^2*sign(Omega2)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), _PHASE)

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_ALPHA2, K.XF_SIN_POSITIVE, 1.0, p["phase_rad"], 2.0),
                 (K.XS_SIGN_OMEGA2, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * max(0, sin(alpha2 + {p['phase_rad']:.6g}))^2 * "
                "sign(Omega2)")


class MotorCloggingLoad(OutsideForm):
    name = "motor_clogging_load"
    half = "sealed"
    balance = "motor_load_moment"
    depends_on = ("time",)
    description = ("an auxiliary on the motor shaft (a pump behind a filter) whose load rises as the filter clogs "
                   "during the recording: A*(1 - exp(-t/tau)) on the load moment from sample 0 (t = 0)")
    parameters = (Param("amplitude_pu", "p.u.", (0.0, 1.0), "A"), Param("time_constant_s", "s", (0.05, 1000.0), "tau"))

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["amplitude_pu"] * C.BASE_TORQUE_NM,
                 (K.XS_TIME, K.XF_RISE, p["time_constant_s"], 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['amplitude_pu']:.6g} p.u. * (1 - exp(-t / {p['time_constant_s']:.6g} s)), "
                "t from sample 0")


class A1CentripetalCrossAxis(OutsideForm):
    name = "a1_centripetal_cross_axis"
    half = "sealed"
    stage = "sensor"
    order = 0
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_speed",)
    description = ("the a1 accelerometer on the motor's rim feels the centripetal acceleration r*Omega1^2 "
                   "(~3400 m/s^2) through its cross-axis sensitivity: a1 += k*r*Omega1^2")
    parameters = (Param("gain_cross_axis", "-", (0.0, 0.05), "k (MEMS data sheets: 1-5 %)"),)

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = sig["a1"] + p["gain_cross_axis"] * C.WHEEL_RADIUS_M * states["omega1"] ** 2

    def law(self, p):
        return f"a1 sensor += {p['gain_cross_axis']:.6g} * r * Omega1^2"


FORM_CLASSES = (ClutchAntiBacklashSpring, MassPulseKick, A2ChannelCrosstalk, MassOverspeedBrake, WheelGuardRub,
                MotorCloggingLoad, A1CentripetalCrossAxis)


def suite_rows():
    """The sealed suite's rows: (label, kind, nominal width, eta_k, n1, effects) as suites.py takes them."""
    from .spec import EffectSpec as E
    return [
        ("os_clean_w7.0_eta0.022_n0.95", "clean", 0.007, 0.022, 0.95, []),
        ("os_clutch_anti_backlash_40", "outside", 0.006, 0.03, 0.90,
         [E("clutch_anti_backlash_spring", {"stiffness_Nm_per_rad": 40.0})]),
        ("os_mass_pulse_kick_25N", "outside", 0.0085, 0.04, 0.93,
         [E("mass_pulse_kick", {"force_N": 25.0, "decay_s": 0.02})]),
        ("os_a2_crosstalk_0.006", "outside", 0.005, 0.015, 0.89,
         [E("a2_channel_crosstalk", {"gain_a1_to_a2": 0.006})]),
        ("os_mass_overspeed_brake", "outside", 0.0075, 0.025, 0.89,
         [E("mass_overspeed_brake", {"coefficient_Ns2_per_m2": 30000.0, "set_speed_m_s": 22.69})]),
        ("os_wheel_guard_rub_3.5Nm", "outside", 0.0045, 0.035, 0.96,
         [E("wheel_guard_rub", {"torque_Nm": 3.5, "phase_rad": -0.6})]),
        ("os_motor_clogging_0.25pu", "outside", 0.0095, 0.02, 0.91,
         [E("motor_clogging_load", {"amplitude_pu": 0.25, "time_constant_s": 1.5})]),
        ("os_a1_cross_axis_0.01", "outside", 0.0035, 0.045, 0.92,
         [E("a1_centripetal_cross_axis", {"gain_cross_axis": 0.01})]),
        ("os_width_6.0_to_7.2+guard_rub", "outside", 0.006, 0.025, 0.90,
         [E("drift_width", {"change": 0.0012}), E("wheel_guard_rub", {"torque_Nm": 3.0, "phase_rad": 2.5})]),
        ("os_width_8.0_to_9.0+pulse_kick", "outside", 0.008, 0.03, 0.89,
         [E("drift_width", {"change": 0.001}), E("mass_pulse_kick", {"force_N": 20.0, "decay_s": 0.03})]),
        ("os_width_5.0_to_5.9+anti_backlash", "outside", 0.005, 0.02, 0.94,
         [E("drift_width", {"change": 0.0009}), E("clutch_anti_backlash_spring", {"stiffness_Nm_per_rad": 35.0})]),
        ("os_clean_w4.2_eta0.04_n0.90", "clean", 0.0042, 0.04, 0.90, []),
    ]

