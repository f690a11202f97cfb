"""Outside mechanisms, second SEALED half (issue 31 part 4, set 2).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed2``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first halves
(:mod:`outside_dev`, :mod:`outside_sealed`) nor the second development half (:mod:`outside_dev2`) has, and the
suite's rows (seeds 7400+). The suite is made on first use (``suites.suite("outside_sealed2")``), not listed in
``suites.SUITES``.
"""
from __future__ import annotations

import math

import numpy as np

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (relative to the simulator's angle)")


class WheelRatchetPawl(OutsideForm):
    name = "wheel_ratchet_pawl"
    half = "sealed2"
    balance = "wheel_torque"
    depends_on = ("wheel_angle",)
    description = ("an anti-reverse ratchet on the wheel shaft: the spring-loaded pawl rides up each of the n teeth "
                   "and drops off, a braking torque in sharp pulses at the tooth rate, -T*max(0, sin(n*alpha2 + "
                   "phi))^c")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("teeth", "-", (1.0, 64.0), "n (integer)"),
                  Param("sharpness", "-", (1.0, 16.0), "c"), _PHASE)
    note = "a mean braking torque and all harmonics of the tooth order n at once"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"],
                 (K.XS_ALPHA2, K.XF_SIN_POSITIVE, float(round(p["teeth"])), p["phase_rad"], p["sharpness"]),
                 nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * max(0, sin({round(p['teeth'])}*alpha2 + "
                f"{p['phase_rad']:.6g}))^{p['sharpness']:.6g}")


class MassBaseTilt(OutsideForm):
    name = "mass_base_tilt"
    half = "sealed2"
    balance = "mass_force"
    depends_on = ("clutch_penetration",)
    description = ("the drive and the carriage's rail share a soft base: the torque the clutch transmits reacts on "
                   "the base and tilts the rail, and gravity pulls the carriage along it, kappa*T_c")
    parameters = (Param("gain_N_per_Nm", "N/(N*m)", (0.0, 10.0), "kappa = m*g x the rail's tilt per N*m"),)

    def apply(self, b, p):
        add_term(b, "mass_force", p["gain_N_per_Nm"], (K.XS_CONTACT_TORQUE, K.XF_X, 0.0, 0.0, 0.0))

    def law(self, p):
        return f"mass force += {p['gain_N_per_Nm']:.6g} N/(N*m) * T_c, T_c the contact law's torque (0 in the gap)"


class WheelDrumStop(OutsideForm):
    name = "wheel_drum_stop"
    half = "sealed2"
    balance = "wheel_torque"
    depends_on = ("spring_extension",)
    description = ("the spring's cable runs over a drum on the wheel shaft; past an extension z0 its clamp presses a "
                   "rubber stop against the drum, braking the wheel as the square of the overtravel, "
                   "-c*max(0, z - z0)^2")
    parameters = (Param("coefficient_Nm_per_m2", "N*m/m^2", (0.0, 1e6), "c"),
                  Param("threshold_m", "m", (0.0, 1.0), "z0"))

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["coefficient_Nm_per_m2"],
                 (K.XS_SPRING_EXTENSION, K.XF_EXCESS_POWER, p["threshold_m"], 2.0, 0.0))

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_per_m2']:.6g} N*m/m^2 * max(0, z - {p['threshold_m']:.6g} m)^2, "
                "z the spring extension")


class MotorStrokeCrank(OutsideForm):
    name = "motor_stroke_crank"
    half = "sealed2"
    balance = "motor_load_moment"
    depends_on = ("load_pulse", "motor_angle")
    description = ("the press's tool is driven from the motor shaft through a 2:1 crank: during a stroke its load "
                   "follows the crank's geometry, A*pulse*sin(2*alpha1 + phi) on the load moment [p.u.], nothing "
                   "between strokes")
    parameters = (Param("amplitude_pu", "p.u.", (0.0, 2.0), "A"), _PHASE)

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["amplitude_pu"] * C.BASE_TORQUE_NM, (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_ALPHA1, K.XF_SIN, 2.0, p["phase_rad"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['amplitude_pu']:.6g} p.u. * pulse * sin(2*alpha1 + {p['phase_rad']:.6g}), "
                "pulse = 1 while the load pulse is on")


class A1SolenoidPickup(OutsideForm):
    name = "a1_solenoid_pickup"
    half = "sealed2"
    stage = "sensor"
    order = 0
    uses_states = True
    balance = "sensor"
    depends_on = ("load_pulse",)
    description = ("the press's solenoid valve, energised for each stroke, couples into the a1 cable: an offset "
                   "while it is on, a1 += A*pulse")
    parameters = (Param("amplitude_m_s2", "m/s^2", (-100.0, 100.0), "A"),)

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = sig["a1"] + p["amplitude_m_s2"] * states["pulse"]

    def law(self, p):
        return f"a1 sensor += {p['amplitude_m_s2']:.6g} m/s^2 * pulse, pulse = 1 while the load pulse is on"


class A2MainsHum(OutsideForm):
    name = "a2_mains_hum"
    half = "sealed2"
    stage = "sensor"
    order = 0
    uses_states = True
    balance = "sensor"
    depends_on = ("time",)
    description = ("the a2 channel picks up the supply's field (a ground loop with the motor's supply): a hum at "
                   "the supply frequency, a2 += A*sin(2*pi*f*t + phi), f = 50 Hz")
    parameters = (Param("amplitude_m_s2", "m/s^2", (0.0, 10.0), "A"), _PHASE)

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = sig["a2"] + p["amplitude_m_s2"] * np.sin(
            2.0 * math.pi * C.SUPPLY_FREQUENCY_HZ * np.asarray(t) + p["phase_rad"])

    def law(self, p):
        return (f"a2 sensor += {p['amplitude_m_s2']:.6g} m/s^2 * sin(2*pi*{C.SUPPLY_FREQUENCY_HZ:g} Hz * t + "
                f"{p['phase_rad']:.6g}), t from sample 0")


class ClutchStrokeSlipCoupling(OutsideForm):
    name = "clutch_stroke_slip_coupling"
    half = "sealed2"
    balance = "clutch_torque"
    depends_on = ("load_pulse", "motor_speed", "wheel_speed")
    description = ("an eddy-current slip coupling beside the jaw, energised with each stroke to share its load: a "
                   "torque c*(Omega1 - Omega2) from the motor to the wheel while the load pulse is on, in and out of "
                   "contact")
    parameters = (Param("damping_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),)

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["damping_Nms_per_rad"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += {p['damping_Nms_per_rad']:.6g} N*m*s/rad * pulse * (Omega1 - Omega2), pulse = 1 "
                "while the load pulse is on")


FORM_CLASSES = (WheelRatchetPawl, MassBaseTilt, WheelDrumStop, MotorStrokeCrank, A1SolenoidPickup, A2MainsHum,
                ClutchStrokeSlipCoupling)


def suite_rows():
    """The sealed suite's rows: (label, kind, nominal width, eta_k, n1, effects) as suites.py takes them."""
    from .spec import EffectSpec as E
    return [
        ("os2_clean_w5.4_eta0.035_n0.93", "clean", 0.0054, 0.035, 0.93, []),
        ("os2_wheel_ratchet_pawl", "outside", 0.0065, 0.025, 0.90,
         [E("wheel_ratchet_pawl", {"torque_Nm": 3.0, "teeth": 8, "sharpness": 4.0, "phase_rad": 0.7})]),
        ("os2_mass_base_tilt", "outside", 0.0085, 0.03, 0.92, [E("mass_base_tilt", {"gain_N_per_Nm": 0.08})]),
        ("os2_wheel_drum_stop", "outside", 0.0055, 0.02, 0.95,
         [E("wheel_drum_stop", {"coefficient_Nm_per_m2": 15000.0, "threshold_m": 0.30})]),
        ("os2_motor_stroke_crank", "outside", 0.0075, 0.045, 0.89,
         [E("motor_stroke_crank", {"amplitude_pu": 0.12, "phase_rad": 1.3})]),
        ("os2_a1_solenoid_pickup", "outside", 0.0045, 0.025, 0.91, [E("a1_solenoid_pickup", {"amplitude_m_s2": 5.0})]),
        ("os2_a2_mains_hum", "outside", 0.007, 0.015, 0.96,
         [E("a2_mains_hum", {"amplitude_m_s2": 0.25, "phase_rad": -0.4})]),
        ("os2_clutch_stroke_slip", "outside", 0.006, 0.03, 0.89,
         [E("clutch_stroke_slip_coupling", {"damping_Nms_per_rad": 0.8})]),
        ("os2_width_6.5_to_7.6+drum_stop", "outside", 0.0065, 0.025, 0.90,
         [E("drift_width", {"change": 0.0011}),
          E("wheel_drum_stop", {"coefficient_Nm_per_m2": 12000.0, "threshold_m": 0.30})]),
        ("os2_width_4.5_to_5.4+stroke_crank", "outside", 0.0045, 0.03, 0.93,
         [E("drift_width", {"change": 0.0009}), E("motor_stroke_crank", {"amplitude_pu": 0.15, "phase_rad": -2.4})]),
        ("os2_clean_w9.1_eta0.02_n0.90", "clean", 0.0091, 0.02, 0.90, []),
    ]
