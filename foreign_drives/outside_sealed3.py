"""Outside mechanisms, third SEALED half (issue 31 part 4, set 3).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed3``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first two sets
nor the third development half (:mod:`outside_dev3`) has, and the suite's rows (seeds 7900+). The split rule is in
:mod:`outside_dev3` (written as one list of fourteen; the even numbers are here). Written before any diagnose or
proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed3")``), not listed in
``suites.SUITES``.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import butter, lfilter

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (relative to the simulator's angle)")
_SIGN_SPEED = 1.0      # rad/s: the speed below which a brake's sign(Omega) is smoothed (tanh); the drive runs > 140


# 2. motor load moment x the contact torque's magnitude
class MotorThrustBearingDrag(OutsideForm):
    name = "motor_thrust_bearing_drag"
    half = "sealed3"
    balance = "motor_load_moment"
    depends_on = ("clutch_penetration",)
    description = ("the jaw's faces are cut at a pressure angle, so the torque they pass pushes the motor shaft "
                   "axially into its thrust bearing; the bearing's friction loads the motor in proportion to the "
                   "contact torque's magnitude: eps*|T_c|*sign(Omega1)")
    parameters = (Param("coefficient", "-", (0.0, 1.0), "eps = mu_b * tan(pressure angle) * r_bearing / r_jaw"),)
    note = "zero in the gap; a product of the contact (penetration and its rate) and the motor's direction"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["coefficient"], (K.XS_CONTACT_TORQUE, K.XF_ABS, 0.0, 0.0, 0.0),
                 (K.XS_OMEGA1, K.XF_TANH, _SIGN_SPEED, 0.0, 0.0))

    def law(self, p):
        return (f"motor load moment += {p['coefficient']:.6g} * |T_c| * sign(Omega1), T_c the jaw's contact torque "
                "(0 in the gap)")


# 4. wheel torque x the wheel angle at a NON-integer order
class WheelBearingSpall(OutsideForm):
    name = "wheel_bearing_spall"
    half = "sealed3"
    balance = "wheel_torque"
    depends_on = ("wheel_angle",)
    description = ("a spall on the outer race of the wheel's rolling bearing: each rolling element crossing it drags "
                   "the wheel briefly, at the ball-pass order k (not a whole number: the cage turns slower than the "
                   "shaft): -T*max(0, sin(k*theta2 + phi))^c*sign(Omega2), theta2 the wheel angle unwrapped from the "
                   "run-in's start")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T: the peak drag"),
                  Param("ball_pass_order", "per revolution", (1.5, 12.0), "k"),
                  Param("sharpness", "-", (1.0, 32.0), "c: the larger, the shorter each drag"),
                  _PHASE)
    note = "a non-integer order of the wheel angle: not periodic in one revolution"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"],
                 (K.XS_ALPHA2_UNWRAPPED, K.XF_SIN_POSITIVE, p["ball_pass_order"], p["phase_rad"], p["sharpness"]),
                 (K.XS_OMEGA2, K.XF_TANH, _SIGN_SPEED, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * max(0, sin({p['ball_pass_order']:.6g}*theta2 + "
                f"{p['phase_rad']:.6g}))^{p['sharpness']:.6g} * sign(Omega2), theta2 = alpha2 unwrapped from the "
                "run-in's start (2.1 s before sample 0)")


# 6. clutch torque x the distance to the jaw face and the approach rate, in the gap
class ClutchSqueezeFilm(OutsideForm):
    name = "clutch_squeeze_film"
    half = "sealed3"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("grease on the jaw faces: as a face approaches (or leaves) the other, the film between them is "
                   "squeezed and resists, more the thinner it is: c*(Omega1 - Omega2)*(h0/(h + h0))^n while the jaw "
                   "is free, h the distance to the nearer face (beta - |D|), h0 the faces' roughness; 0 in contact")
    parameters = (Param("damping_Nms_per_rad", "N*m*s/rad", (0.0, 200.0), "c: the film's damping at h = 0"),
                  Param("roughness_rad", "rad", (1e-4, 0.05), "h0"),
                  Param("exponent", "-", (0.5, 3.0), "n (3: a viscous squeeze film)"))
    note = "a cushion just before the impact (and a suction just after leaving a face): nothing in mid-gap"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["damping_Nms_per_rad"], (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_GAP_DISTANCE, K.XF_CUSHION, p["roughness_rad"], p["exponent"], 0.0))

    def law(self, p):
        return (f"clutch torque += {p['damping_Nms_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) * "
                f"({p['roughness_rad']:.6g} / (h + {p['roughness_rad']:.6g}))^{p['exponent']:.6g} while free, "
                "h = beta - |D| the distance to the nearer face; 0 in contact")


# 8. mass force x the motor angle at order 3
class MassMotorLobeCam(OutsideForm):
    name = "mass_motor_lobe_cam"
    half = "sealed3"
    balance = "mass_force"
    depends_on = ("motor_angle",)
    description = ("a lobed cam on the motor shaft's free end drives a vibratory feeder whose rail touches the "
                   "carriage: n pushes along x per motor revolution, F*sin(n*alpha1 + phi)")
    parameters = (Param("amplitude_N", "N", (0.0, 100.0), "F"),
                  Param("lobes", "per revolution", (1, 5), "n", "int"), _PHASE)

    def apply(self, b, p):
        add_term(b, "mass_force", p["amplitude_N"], (K.XS_ALPHA1, K.XF_SIN, float(p["lobes"]), p["phase_rad"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return f"mass force += {p['amplitude_N']:.6g} N * sin({p['lobes']}*alpha1 + {p['phase_rad']:.6g})"

    def plugin(self, p):
        n = int(p["lobes"])
        return _plugin("MassMotorLobeCam", self.name, "mass_force_N", self.description, [
            ("amplitude_N", "N", (0.0, 100.0), "F"), ("phase_rad", "rad", (-math.pi, math.pi), "phi")],
            "alpha1, amplitude_N, phase_rad", f"amplitude_N * sin({n} * alpha1 + phase_rad)", "sin")


# 10. a1 sensor x a1's slow content: AC coupling
class A1ChargeAmplifierHighpass(OutsideForm):
    name = "a1_charge_amplifier_highpass"
    half = "sealed3"
    stage = "sensor"
    order = 1                      # the conditioning amplifier, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1 is a piezoelectric accelerometer on a charge amplifier: AC coupled, it passes nothing below "
                   "its corner, a first-order high-pass s/(s + 2*pi*f_c) (bilinear), running since long before")
    parameters = (Param("corner_hz", "Hz", (0.0, 50.0), "f_c (0: DC coupled)"),)
    note = "the opposite of the catalogue's low-pass: the pulse train's slow content (4 Hz and its lowest harmonics)"

    def apply_signal(self, sig, p, t, fs, states=None):
        fc = p["corner_hz"]
        if fc <= 0.0:
            return
        b, a = butter(1, fc, btype="highpass", fs=fs)
        x = np.asarray(sig["a1"], dtype=np.float64)
        n_per = int(round(C.PULSE_PERIOD_S * fs))
        pad = np.tile(x[:n_per], 8)              # the amplifier ran through 2 s of the same periodic drive before
        y = lfilter(b, a, np.concatenate([pad, x]))
        sig["a1"] = y[pad.size:]

    def law(self, p):
        return (f"a1 sensor = first-order high-pass of a1, corner {p['corner_hz']:.6g} Hz (bilinear, settled on 2 s "
                "of the periodic drive)")


# 12. wheel torque x time in a periodic window
class WheelTimedBrush(OutsideForm):
    name = "wheel_timed_brush"
    half = "sealed3"
    balance = "wheel_torque"
    depends_on = ("time",)
    description = ("a cleaning brush on the wheel's rim, lowered by a timer for a window W every P seconds (a period "
                   "of its own, not the press's): -T*sign(Omega2) while (t - t0) mod P < W")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("period_s", "s", (0.05, 60.0), "P"),
                  Param("window_s", "s", (0.001, 30.0), "W"), Param("start_s", "s", (-60.0, 60.0), "t0"))

    def apply(self, b, p):
        if p["window_s"] >= p["period_s"]:
            raise ValueError(f"{self.name}: window_s {p['window_s']} is not below period_s {p['period_s']}; allowed: "
                             "a window shorter than the period")
        add_term(b, "wheel_torque", -p["torque_Nm"],
                 (K.XS_TIME, K.XF_PERIODIC_GATE, p["period_s"], p["start_s"], p["window_s"]),
                 (K.XS_OMEGA2, K.XF_TANH, _SIGN_SPEED, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * sign(Omega2) while (t - {p['start_s']:.6g} s) mod "
                f"{p['period_s']:.6g} s < {p['window_s']:.6g} s, else 0; t from sample 0")


# 14. a1 sensor x a1 x the motor angle: a multiplicative modulation
class A1SlipRingModulation(OutsideForm):
    name = "a1_slip_ring_modulation"
    half = "sealed3"
    stage = "sensor"
    order = 0                      # the signal path from the rotating sensor
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration", "motor_angle")
    description = ("a1's signal leaves the rotating rim through a slip ring with a worn track: its contact resistance, "
                   "and so the channel's gain, varies once per motor revolution, a1 = a*(1 + g*sin(alpha1 + phi))")
    parameters = (Param("relative_modulation", "-", (0.0, 0.9), "g"), _PHASE)
    note = "a product of the acceleration and the motor angle (an amplitude modulation), zero where a1 is zero"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = sig["a1"] * (1.0 + p["relative_modulation"] * np.sin(states["alpha1"] + p["phase_rad"]))

    def law(self, p):
        return f"a1 sensor = a1 * (1 + {p['relative_modulation']:.6g} * sin(alpha1 + {p['phase_rad']:.6g}))"


FORM_CLASSES = (MotorThrustBearingDrag, WheelBearingSpall, ClutchSqueezeFilm, MassMotorLobeCam,
                A1ChargeAmplifierHighpass, WheelTimedBrush, A1SlipRingModulation)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 7900+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        ("os3_motor_thrust_bearing_drag", "outside", 0.0065, 0.03, 0.91,
         [E("motor_thrust_bearing_drag", {"coefficient": 0.12})]),
        ("os3_wheel_bearing_spall", "outside", 0.008, 0.02, 0.93,
         [E("wheel_bearing_spall", {"torque_Nm": 5.0, "ball_pass_order": 3.57, "sharpness": 8.0, "phase_rad": 0.6})]),
        ("os3_clutch_squeeze_film", "outside", 0.0055, 0.035, 0.90,
         [E("clutch_squeeze_film", {"damping_Nms_per_rad": 10.0, "roughness_rad": 0.01, "exponent": 1.5})]),
        ("os3_mass_motor_lobe_cam", "outside", 0.0095, 0.025, 0.96,
         [E("mass_motor_lobe_cam", {"amplitude_N": 4.0, "lobes": 3, "phase_rad": -1.3})]),
        ("os3_clean_w6.8_eta0.022_n0.92", "clean", 0.0068, 0.022, 0.92, []),
        ("os3_a1_charge_amplifier_highpass", "outside", 0.0045, 0.04, 0.89,
         [E("a1_charge_amplifier_highpass", {"corner_hz": 1.5})]),
        ("os3_wheel_timed_brush", "outside", 0.007, 0.0155, 0.94,
         [E("wheel_timed_brush", {"torque_Nm": 2.5, "period_s": 1.3, "window_s": 0.3, "start_s": 0.4})]),
        ("os3_a1_slip_ring_modulation", "outside", 0.0085, 0.045, 0.90,
         [E("a1_slip_ring_modulation", {"relative_modulation": 0.12, "phase_rad": 2.4})]),
    ]
