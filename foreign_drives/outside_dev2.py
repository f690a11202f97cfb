"""Outside mechanisms, second DEVELOPMENT half (issue 31 part 4, set 2): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first halves (:mod:`outside_dev`,
:mod:`outside_sealed`) have, with their laws in the open. The second sealed half is :mod:`outside_sealed2`.

Written before any run of the proposal on them (the commit history is the proof). Kinds (balance x what it reads):

- clutch torque x penetration x the sign of its rate: dry friction on the jaw faces (a hysteresis, not a damping);
- mass force x cos(wheel angle): an eccentric guide roller driven off the wheel shaft;
- motor load moment x the spring extension beyond a threshold: an overload band brake pulled by the spring;
- wheel torque x time from a fixed instant: a brake applied by a timed sequence during the recording;
- mass force x time at a fixed frequency: a neighbouring machine shaking the floor under the rail;
- a1 sensor x a1 itself: a soft saturation of the motor-side accelerometer (a compression, not a gain);
- a2 sensor x the spring extension: the a2 sensor's bracket tilts in gravity as the spring pulls on it.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle; the manifest has its
value at sample 0).
"""
from __future__ import annotations

import math

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (relative to the simulator's angle)")


class ClutchJawDryFriction(OutsideForm):
    name = "clutch_jaw_dry_friction"
    half = "dev2"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("dry (Coulomb) friction on the jaw faces as they slide while they press: a torque mu*k*p in the "
                   "direction of the penetration's rate, c*p*tanh(p'/eps) -- more torque while the jaw presses in "
                   "than while it lets go at the same penetration (a hysteresis loop whose area does not depend on "
                   "the rate, unlike a damping)")
    parameters = (Param("coefficient_Nm_per_rad", "N*m/rad", (0.0, 3000.0), "c = mu x the contact stiffness"),
                  Param("sign_speed_rad_s", "rad/s", (1e-3, 10.0), "eps: the rate below which the sign is smoothed"))
    note = "zero in the gap (p = 0); odd in the rate: it dissipates c*p*|p'| per unit time"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["coefficient_Nm_per_rad"], (K.XS_PENETRATION, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_TANH, p["sign_speed_rad_s"], 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_per_rad']:.6g} N*m/rad * p * tanh(p' / "
                f"{p['sign_speed_rad_s']:.6g} rad/s), p the penetration, p' its rate (0 in the gap)")

    def plugin(self, p):
        return _plugin("ClutchJawDryFriction", self.name, "clutch_torque_Nm", self.description, [
            ("coefficient_Nm_per_rad", "N*m/rad", (0.0, 3000.0), "c"),
            ("sign_speed_rad_s", "rad/s", (1e-3, 10.0), "eps")],
            "penetration, approach_speed, coefficient_Nm_per_rad, sign_speed_rad_s",
            "coefficient_Nm_per_rad * penetration * (1.0 - 2.0 / (exp(2.0 * approach_speed / sign_speed_rad_s) + 1.0))",
            "exp")


class MassEccentricRoller(OutsideForm):
    name = "mass_eccentric_roller"
    half = "dev2"
    balance = "mass_force"
    depends_on = ("wheel_angle",)
    description = ("the carriage's pressure roller is driven off the wheel shaft and runs eccentric: its contact "
                   "force pushes the carriage along x once per wheel revolution, F*cos(alpha2 + phi)")
    parameters = (Param("amplitude_N", "N", (0.0, 100.0), "F = roller preload x eccentricity slope"), _PHASE)
    note = "a force locked to the WHEEL angle in the MASS balance (not a torque on the wheel)"

    def apply(self, b, p):
        add_term(b, "mass_force", p["amplitude_N"], (K.XS_ALPHA2, K.XF_COS, 1.0, p["phase_rad"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return f"mass force += {p['amplitude_N']:.6g} N * cos(alpha2 + {p['phase_rad']:.6g})"

    def plugin(self, p):
        return _plugin("MassEccentricRoller", self.name, "mass_force_N", self.description, [
            ("amplitude_N", "N", (0.0, 100.0), "F"), ("phase_rad", "rad", (-math.pi, math.pi), "phi")],
            "alpha2, amplitude_N, phase_rad", "amplitude_N * cos(alpha2 + phase_rad)", "cos")


class MotorOverloadBandBrake(OutsideForm):
    name = "motor_overload_band_brake"
    half = "dev2"
    balance = "motor_load_moment"
    depends_on = ("spring_extension",)
    description = ("an overload guard: a cable from the spring's bracket tightens a band brake on the motor shaft "
                   "once the spring stretches beyond z0, c*max(0, z - z0) on the motor's load moment")
    parameters = (Param("coefficient_Nm_per_m", "N*m/m", (0.0, 1e4), "c"),
                  Param("threshold_m", "m", (0.0, 1.0), "z0"))
    note = "a one-sided term of the spring extension in the MOTOR balance (the spring force itself is the rim force)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["coefficient_Nm_per_m"],
                 (K.XS_SPRING_EXTENSION, K.XF_EXCESS_POWER, p["threshold_m"], 1.0, 0.0))

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_per_m']:.6g} N*m/m * max(0, z - {p['threshold_m']:.6g} m) "
                "/ T_b [p.u.], z the spring extension")

    def plugin(self, p):
        return _plugin("MotorOverloadBandBrake", self.name, "motor_load_moment_pu", self.description, [
            ("coefficient_Nm_per_m", "N*m/m", (0.0, 1e4), "c"), ("threshold_m", "m", (0.0, 1.0), "z0")],
            "z, base_torque_Nm, coefficient_Nm_per_m, threshold_m",
            "coefficient_Nm_per_m * fmax(0.0, z - threshold_m) / base_torque_Nm", "fmax")


class WheelTimedBrake(OutsideForm):
    name = "wheel_timed_brake"
    half = "dev2"
    balance = "wheel_torque"
    depends_on = ("time",)
    description = ("a holding brake on the wheel applied by the line's sequence at a fixed instant t0 of the "
                   "recording, its hydraulics building up with a lag: -T*(1 - exp(-(t - t0)/tau)) for t >= t0")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("start_s", "s", (0.0, 120.0), "t0"),
                  Param("build_up_s", "s", (1e-3, 10.0), "tau"))

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"],
                 (K.XS_TIME, K.XF_RISE_AFTER, p["build_up_s"], p["start_s"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * (1 - exp(-(t - {p['start_s']:.6g} s) / "
                f"{p['build_up_s']:.6g} s)) for t >= {p['start_s']:.6g} s, else 0; t from sample 0")


class MassFloorVibration(OutsideForm):
    name = "mass_floor_vibration"
    half = "dev2"
    balance = "mass_force"
    depends_on = ("time",)
    description = ("a neighbouring machine shakes the floor the carriage's rail stands on at its own frequency, "
                   "locked to no shaft of this drive: a force on the carriage F*sin(2*pi*f*t + phi)")
    parameters = (Param("amplitude_N", "N", (0.0, 100.0), "F"), Param("frequency_hz", "Hz", (0.1, 1000.0), "f"),
                  _PHASE)
    note = "a fixed frequency in the MASS balance (the catalogue-outside vibration of forms.py is on the motor)"

    def apply(self, b, p):
        add_term(b, "mass_force", p["amplitude_N"],
                 (K.XS_TIME, K.XF_SIN, 2.0 * math.pi * p["frequency_hz"], p["phase_rad"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['amplitude_N']:.6g} N * sin(2*pi*{p['frequency_hz']:.6g} Hz * t + "
                f"{p['phase_rad']:.6g}), t from sample 0")


class A1SoftSaturation(OutsideForm):
    name = "a1_soft_saturation"
    half = "dev2"
    stage = "sensor"
    order = 0                      # the sensing element (before the anti-alias filter)
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("the a1 accelerometer's sensing element compresses large accelerations (a MEMS proof mass near "
                   "its stops, an amplifier near its rail): a1 = tanh(k*a)/k = L*tanh(a/L), L = 1/k, a the physical "
                   "acceleration")
    parameters = (Param("gain_inverse_limit_s2_per_m", "s^2/m", (0.0, 1.0), "k = 1/L (0: no compression)"),)
    note = "odd and amplitude-dependent: small accelerations read right, the jaw's impacts read low"

    def apply_signal(self, sig, p, t, fs, states=None):
        k = p["gain_inverse_limit_s2_per_m"]
        if k > 0.0:
            a = states["a1_physical"]
            sig["a1"] = sig["a1"] + (np.tanh(k * a) / k - a)

    def law(self, p):
        lim = 1.0 / p["gain_inverse_limit_s2_per_m"] if p["gain_inverse_limit_s2_per_m"] > 0 else math.inf
        return f"a1 sensor = {lim:.6g} m/s^2 * tanh(a1 / {lim:.6g} m/s^2)"


class A2BracketTilt(OutsideForm):
    name = "a2_bracket_tilt"
    half = "dev2"
    stage = "sensor"
    order = 0
    uses_states = True
    balance = "sensor"
    depends_on = ("spring_extension",)
    description = ("the a2 accelerometer sits on the bracket the spring pulls on; the bracket bends and tilts the "
                   "sensing axis in gravity by (z - z_c)/L: a2 += k*(z - z_c), k = g/L, z the spring extension")
    parameters = (Param("gain_m_s2_per_m", "m/s^2/m", (0.0, 1000.0), "k = g / L (L: the extension that tilts the "
                        "bracket by one radian)"),
                  Param("centre_m", "m", (0.0, 1.0), "z_c: the extension at which the axis is level"))

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = sig["a2"] + p["gain_m_s2_per_m"] * (states["spring_extension"] - p["centre_m"])

    def law(self, p):
        return f"a2 sensor += {p['gain_m_s2_per_m']:.6g} m/s^2/m * (z - {p['centre_m']:.6g} m), z the spring extension"


FORM_CLASSES = (ClutchJawDryFriction, MassEccentricRoller, MotorOverloadBandBrake, WheelTimedBrake, MassFloorVibration,
                A1SoftSaturation, A2BracketTilt)
