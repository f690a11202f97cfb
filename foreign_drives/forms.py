"""Effect forms: each a physical law of a catalogue FAMILY written in another functional form than the
catalogue's (backlash_monitor/plant/effects.py, docs/effects.md), or an effect OUTSIDE the catalogue
(family None). Every form has named, bounded parameters, a one-line physics description, the catalogue
family a user should be told about, the catalogue-equivalent parameter values where they exist, and the
other families that explain it as well on this drive (``also_accepted``).

Stages: ``drift`` (a nominal value changes; applied first), ``physics`` (a term of the right-hand side, through
the parameter vector of :mod:`physics`), ``sensor`` (on the recorded a1/a2, in the order of a real chain:
sensing element gain and bias, then the anti-alias low-pass; the white noise and the ADC after it are the
recording's sensor nuisance, not effects).

Catalogue-equivalent values are evaluated at the drive's operating point (OPERATING_POINT, measured on the
noise-free nominal drive, test_foreign_drives checks them).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import constants as C
from .kernel import (P_BETA, P_C, P_CEXP, P_CPRE, P_CPRS, P_CREF, P_DC, P_DS, P_DW, P_EME, P_EMN, P_EMP, P_F0, P_GMA,
                      P_GMN, P_GMP, P_HCL, P_J1, P_J2, P_JH, P_JR, P_K, P_KCD, P_KCF, P_KS, P_KW, P_M, P_MCF, P_MCT,
                      P_MDC, P_MFAN, P_MFANW, P_MFT, P_MFTW, P_MFV, P_N1, P_PROG, P_RAILF, P_RAILV, P_RA0, P_RN0,
                      P_RP0, P_RR, P_U, P_VIBA, P_VIBF, P_VIBP, P_WCT, P_WFDC, P_WFDP, P_WFL, P_WFT, P_WFTW, P_WSC,
                      P_WSD, P_WSE, P_WSW, P_Z0)

# measured on the noise-free nominal drive (7.5 mm, 0.025, 0.89; the grid's corners within 0.02 %)
OPERATING_POINT = {
    "speed_rad_s": 151.4,                    # mean Omega1 = mean Omega2 over the pulse period
    "mass_speed_m_s": 151.4 * C.WHEEL_RADIUS_M,
    "mean_te_pu": 0.609,                     # mean electromagnetic torque: 0.225 (r*F0/T_b) + 1.6*60/250
    "mean_rim_force_N": C.WORKING_RESISTANCE_N,
    "static_clutch_torque_Nm": C.WHEEL_RADIUS_M * C.WORKING_RESISTANCE_N,
    # an impact's reference ELASTIC torque: about half the largest elastic torque k_c*p of a far-side impact
    # (max penetration 0.013 rad at 7.5 mm: ~39 N*m; the impact's peak torque, 105..120 N*m, is mostly the
    # damper's d_c*p' at contact); the secant stiffness of a non-linear law and the penetration at which a
    # penetration-dependent damping is compared with the linear law's are taken there
    "impact_reference_torque_Nm": 20.0,
}
REFERENCE_PENETRATION_RAD = OPERATING_POINT["impact_reference_torque_Nm"] / C.CONTACT_STIFFNESS_NM_PER_RAD
SIGNALS = ("a1", "a2")
STAGES = ("drift", "physics", "sensor")


@dataclass(frozen=True)
class Param:
    name: str
    unit: str
    bounds: tuple = (-math.inf, math.inf)   # numbers; for kind "choice": the allowed values
    description: str = ""
    kind: str = "float"                     # float | int | choice | floats (a list of numbers)


class Build:
    """What the physics stages act on: the parameter vector and the values outside it."""

    def __init__(self, P: np.ndarray, width_m: float, eta_k: float, n1: float):
        self.P = P
        self.width_m = width_m
        self.eta_k = eta_k
        self.n1 = n1
        self.pulse_amplitude_pu = C.PULSE_AMPLITUDE_PU
        self.next_ripple = 0              # next free motor-angle ripple harmonic slot (4)

    def set_width(self, width_m):
        self.width_m = width_m
        self.P[P_BETA] = width_m / C.WHEEL_RADIUS_M

    def set_absorber(self, eta_k, n1):
        self.eta_k, self.n1 = eta_k, n1
        self.P[P_C] = C.absorber_coefficient(eta_k, n1)
        self.P[P_N1] = n1


class Form:
    """One effect form. Subclasses set the class attributes and implement apply (drift/physics) or
    apply_signal (sensor), and equivalent/also."""
    name = ""
    family = None            # a catalogue effect name, or None: outside the catalogue
    stage = "physics"
    description = ""
    parameters: tuple = ()
    note = ""

    def apply(self, b: Build, p: dict) -> None:
        raise NotImplementedError

    def apply_signal(self, sig: dict, p: dict, t: np.ndarray, fs: float) -> None:
        raise NotImplementedError

    def equivalent(self, p: dict):
        """Catalogue-equivalent parameters of ``family`` ({name: value}), or None when none exists."""
        return None

    def also(self, p: dict) -> dict:
        """{other catalogue family: its equivalent parameters or None} that explain this form as well here."""
        return {}


W_OP = OPERATING_POINT["speed_rad_s"]
V_OP = OPERATING_POINT["mass_speed_m_s"]


# ============================================================ wheel friction
class WheelFrictionTanh(Form):
    name = "wheel_friction_tanh"
    family = "wheel_coulomb_friction"
    description = "smooth dry friction on the wheel bearing, -T*tanh(Omega2/w_t)"
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "dry friction torque T"),
                  Param("smoothing_speed_rad_s", "rad/s", (0.01, 1000.0), "speed w_t of the tanh's ramp"))

    def apply(self, b, p):
        b.P[P_WFT] += p["torque_Nm"]
        b.P[P_WFTW] = p["smoothing_speed_rad_s"]

    def equivalent(self, p):
        return {"torque_Nm": p["torque_Nm"] * math.tanh(W_OP / p["smoothing_speed_rad_s"])}


class WheelFrictionLoadDependent(Form):
    name = "wheel_friction_load_dependent"
    family = "wheel_coulomb_friction"
    description = ("bearing friction growing with the bearing's radial load (the belt pull F of spring and "
                   "absorber): -(T0 + mu_r*|F|)*sign(Omega2)")
    parameters = (Param("base_torque_Nm", "N*m", (0.0, 50.0), "load-independent part T0"),
                  Param("load_coefficient_m", "N*m/N", (0.0, 1.0), "mu_r = friction coefficient x bearing radius"))

    def apply(self, b, p):
        b.P[P_WCT] += p["base_torque_Nm"]
        b.P[P_WFL] += p["load_coefficient_m"]

    def equivalent(self, p):
        return {"torque_Nm": p["base_torque_Nm"] + p["load_coefficient_m"] * OPERATING_POINT["mean_rim_force_N"]}


class WheelDragPower(Form):
    name = "wheel_drag_power"
    family = "wheel_viscous_friction"
    description = "speed-dependent drag on the wheel (windage, churning), -c*|Omega2|^p*sign(Omega2)"
    parameters = (Param("coefficient", "N*m*(s/rad)^p", (0.0, 10.0), "c"),
                  Param("exponent", "-", (0.2, 3.0), "p (1 = the catalogue's viscous law)"))

    def apply(self, b, p):
        b.P[P_WFDC] = p["coefficient"]
        b.P[P_WFDP] = p["exponent"]

    def equivalent(self, p):          # the same torque at the operating speed
        return {"damping_Nms_per_rad": p["coefficient"] * W_OP ** (p["exponent"] - 1.0)}

    def also(self, p):
        return {"wheel_coulomb_friction": {"torque_Nm": p["coefficient"] * W_OP ** p["exponent"]}}


class WheelFrictionStribeckPower(Form):
    name = "wheel_friction_stribeck_power"
    family = "wheel_stribeck_friction"
    description = ("Stribeck friction with another exponent, -(T_c + T_s*exp(-(|Omega2|/w_s)^delta))*sign(Omega2) "
                   "(the catalogue's: delta = 2 and no T_c)")
    parameters = (Param("coulomb_torque_Nm", "N*m", (0.0, 50.0), "T_c"),
                  Param("excess_torque_Nm", "N*m", (0.0, 50.0), "T_s"),
                  Param("stribeck_speed_rad_s", "rad/s", (0.01, 1000.0), "w_s"),
                  Param("exponent", "-", (0.2, 4.0), "delta"))
    note = ("at this drive's speeds (never below ~145 rad/s) the curve is a torque plus a slope: the wheel's "
            "Coulomb and viscous families explain it as well")

    def _torque(self, p, w):
        x = (w / p["stribeck_speed_rad_s"]) ** p["exponent"]
        return p["coulomb_torque_Nm"] + p["excess_torque_Nm"] * math.exp(-x)

    def apply(self, b, p):
        b.P[P_WSC] = p["coulomb_torque_Nm"]
        b.P[P_WSE] = p["excess_torque_Nm"]
        b.P[P_WSW] = p["stribeck_speed_rad_s"]
        b.P[P_WSD] = p["exponent"]

    def also(self, p):
        t = self._torque(p, W_OP)
        return {"wheel_coulomb_friction": {"torque_Nm": t}, "wheel_viscous_friction": {"damping_Nms_per_rad": t / W_OP}}


class WheelLoadTorque(Form):
    name = "wheel_load_torque"
    family = "wheel_coulomb_friction"
    description = "a constant load torque on the wheel (a brake drag, a process load at the wheel), -T_w"
    parameters = (Param("torque_Nm", "N*m", (-50.0, 50.0), "T_w (positive: against the rotation)"),)
    note = "at one rotation direction a constant wheel torque is a dry wheel friction"

    def apply(self, b, p):
        b.P[P_WCT] += p["torque_Nm"]

    def equivalent(self, p):
        return {"torque_Nm": p["torque_Nm"]} if p["torque_Nm"] >= 0 else None

    def also(self, p):
        return {"mass_force_offset": {"force_N": -p["torque_Nm"] / C.WHEEL_RADIUS_M}}


# ============================================================ motor-side loads
class MotorFrictionTanh(Form):
    name = "motor_friction_tanh"
    family = "motor_coulomb_friction"
    description = "smooth dry friction in the motor bearings, T*tanh(Omega1/w_t) on the motor's load"
    parameters = (Param("torque_Nm", "N*m", (0.0, 20.0), "T"),
                  Param("smoothing_speed_rad_s", "rad/s", (0.01, 1000.0), "w_t"))

    def apply(self, b, p):
        b.P[P_MFT] += p["torque_Nm"]
        b.P[P_MFTW] = p["smoothing_speed_rad_s"]

    def equivalent(self, p):
        return {"torque_Nm": p["torque_Nm"] * math.tanh(W_OP / p["smoothing_speed_rad_s"])}

    def also(self, p):
        return {"motor_load_offset": {"load_pu": self.equivalent(p)["torque_Nm"] / C.BASE_TORQUE_NM}}


class MotorFrictionViscous(Form):
    name = "motor_friction_viscous"
    family = "motor_coulomb_friction"
    description = "viscous losses of the motor (bearing grease, fan), b*Omega1 on the motor's load"
    parameters = (Param("damping_Nms_per_rad", "N*m*s/rad", (0.0, 1.0), "b"),)

    def apply(self, b, p):
        b.P[P_MFV] += p["damping_Nms_per_rad"]

    def equivalent(self, p):
        return {"torque_Nm": p["damping_Nms_per_rad"] * W_OP}

    def also(self, p):
        return {"motor_load_offset": {"load_pu": p["damping_Nms_per_rad"] * W_OP / C.BASE_TORQUE_NM}}


class MotorFanLoad(Form):
    name = "motor_fan_load"
    family = "motor_load_offset"
    description = "a speed-modulated load torque on the motor (a fan, a pump), T_ref*(Omega1/Omega_ref)^2"
    parameters = (Param("torque_Nm", "N*m", (-40.0, 40.0), "T_ref at the reference speed"),
                  Param("reference_speed_rad_s", "rad/s", (1.0, 1000.0), "Omega_ref"))

    def apply(self, b, p):
        b.P[P_MFAN] = p["torque_Nm"]
        b.P[P_MFANW] = p["reference_speed_rad_s"]

    def _t(self, p):
        return p["torque_Nm"] * (W_OP / p["reference_speed_rad_s"]) ** 2

    def equivalent(self, p):
        return {"load_pu": self._t(p) / C.BASE_TORQUE_NM}

    def also(self, p):
        return {"motor_coulomb_friction": {"torque_Nm": self._t(p)}} if self._t(p) > 0 else {}


class MotorLoadConstant(Form):
    name = "motor_load_constant"
    family = "motor_load_offset"
    description = "a constant extra load torque on the motor shaft, in N*m (a brake, an auxiliary drive)"
    parameters = (Param("torque_Nm", "N*m", (-40.0, 40.0), "T"),)

    def apply(self, b, p):
        b.P[P_MCT] += p["torque_Nm"]

    def equivalent(self, p):
        return {"load_pu": p["torque_Nm"] / C.BASE_TORQUE_NM}

    def also(self, p):
        return {"motor_coulomb_friction": {"torque_Nm": p["torque_Nm"]}} if p["torque_Nm"] > 0 else {}


# ============================================================ forces on the mass
class MassRailFriction(Form):
    name = "mass_rail_friction"
    family = "mass_force_offset"
    description = "dry friction of the mass on its rail, -F_r*tanh(v/v_s) (against the motion)"
    parameters = (Param("force_N", "N", (0.0, 1000.0), "F_r"),
                  Param("smoothing_speed_m_s", "m/s", (1e-4, 100.0), "v_s"))

    def apply(self, b, p):
        b.P[P_RAILF] = p["force_N"]
        b.P[P_RAILV] = p["smoothing_speed_m_s"]

    def equivalent(self, p):
        return {"force_N": -p["force_N"] * math.tanh(V_OP / p["smoothing_speed_m_s"])}

    def also(self, p):
        e = -self.equivalent(p)["force_N"] / C.WORKING_RESISTANCE_N
        return {"working_resistance_drift": {"relative_change": e}}


class MassDrag(Form):
    name = "mass_drag"
    family = "mass_force_offset"
    description = "quadratic (aerodynamic/hydraulic) drag on the mass, -c*v*|v|"
    parameters = (Param("coefficient_Ns2_per_m2", "N*s^2/m^2", (0.0, 10.0), "c"),)

    def apply(self, b, p):
        b.P[P_MDC] = p["coefficient_Ns2_per_m2"]

    def equivalent(self, p):
        return {"force_N": -p["coefficient_Ns2_per_m2"] * V_OP ** 2}

    def also(self, p):
        return {"working_resistance_drift": {"relative_change": p["coefficient_Ns2_per_m2"] * V_OP ** 2
                                             / C.WORKING_RESISTANCE_N}}


class MassForceConstant(Form):
    name = "mass_force_constant"
    family = "mass_force_offset"
    description = "a constant force on the mass (gravity on an incline, a preload), +F along x"
    parameters = (Param("force_N", "N", (-1000.0, 1000.0), "F"),)

    def apply(self, b, p):
        b.P[P_MCF] += p["force_N"]

    def equivalent(self, p):
        return {"force_N": p["force_N"]}

    def also(self, p):
        return {"working_resistance_drift": {"relative_change": -p["force_N"] / C.WORKING_RESISTANCE_N}}


# ============================================================ clutch contact
def _secant_stiffness(law) -> float:
    """Linear stiffness with the same penetration at the impact reference torque (OPERATING_POINT)."""
    t_ref = OPERATING_POINT["impact_reference_torque_Nm"]
    from scipy.optimize import brentq
    pen = brentq(lambda x: law(x) - t_ref, 1e-9, 1.0, xtol=1e-15)
    return t_ref / pen


class ClutchContactHertz(Form):
    name = "clutch_contact_hertz"
    family = "clutch_contact_stiffness"
    description = "a Hertz-like jaw contact, k_h*p^n (n = 1.5 for a line/point contact) + d_c*p'"
    parameters = (Param("stiffness", "N*m/rad^n", (1.0, 1e8), "k_h"),
                  Param("exponent", "-", (1.0, 2.5), "n"))
    note = "equivalent: the linear stiffness with the same penetration at 20 N*m (half an impact's elastic peak)"

    def apply(self, b, p):
        n, kh = p["exponent"], p["stiffness"]
        pref = b.P[P_CREF]
        b.P[P_CEXP] = n
        b.P[P_KCD] = b.P[P_KCF] = kh * pref ** (n - 1.0)     # k*p_ref*(p/p_ref)^n = k_h*p^n

    def equivalent(self, p):
        k = _secant_stiffness(lambda x: p["stiffness"] * x ** p["exponent"])
        return {"relative_change": k / C.CONTACT_STIFFNESS_NM_PER_RAD - 1.0}

    @staticmethod
    def stiffness_for(relative_change: float, exponent: float) -> float:
        """k_h whose secant stiffness at the reference torque is k_c*(1 + relative_change)."""
        t_ref = OPERATING_POINT["impact_reference_torque_Nm"]
        pen = t_ref / (C.CONTACT_STIFFNESS_NM_PER_RAD * (1.0 + relative_change))
        return t_ref / pen ** exponent


class ClutchContactAsymmetric(Form):
    name = "clutch_contact_asymmetric"
    family = "clutch_contact_stiffness"
    description = ("jaws of different stiffness on the two sides (one worn insert): k_c*(1+e_d) on the drive "
                   "side, k_c*(1+e_f) on the far side hit after each onset")
    parameters = (Param("drive_relative_change", "-", (-0.9, 10.0), "e_d"),
                  Param("far_relative_change", "-", (-0.9, 10.0), "e_f"))
    note = "equivalent: the far side's change (the onset windows' impact); the drive side shapes the return"

    def apply(self, b, p):
        b.P[P_KCD] *= 1.0 + p["drive_relative_change"]
        b.P[P_KCF] *= 1.0 + p["far_relative_change"]

    def equivalent(self, p):
        return {"relative_change": p["far_relative_change"]}


class ClutchDampingHuntCrossley(Form):
    name = "clutch_damping_hunt_crossley"
    family = "clutch_contact_damping"
    description = "Hunt-Crossley contact damping that grows with the penetration: (d_c + lambda*p)*p'"
    parameters = (Param("lambda_Nms_per_rad2", "N*m*s/rad^2", (0.0, 1e6), "lambda"),)
    note = "equivalent: lambda*p_ref/d_c at the linear law's penetration at 20 N*m (p_ref = 0.00667 rad)"

    def apply(self, b, p):
        b.P[P_HCL] += p["lambda_Nms_per_rad2"]

    def equivalent(self, p):
        return {"relative_change": p["lambda_Nms_per_rad2"] * REFERENCE_PENETRATION_RAD / C.CONTACT_DAMPING_NMS_PER_RAD}


class ClutchDampingValue(Form):
    name = "clutch_damping_value"
    stage = "drift"
    family = "clutch_contact_damping"
    description = "the jaw insert's damping drifted (ageing elastomer): d_c -> d_c*(1+e)"
    parameters = (Param("relative_change", "-", (-0.9, 10.0), "e"),)

    def apply(self, b, p):
        b.P[P_DC] *= 1.0 + p["relative_change"]

    def equivalent(self, p):
        return {"relative_change": p["relative_change"]}


class ShaftWithHub(Form):
    name = "shaft_with_hub"
    family = "shaft_compliance"
    description = ("a torsionally compliant shaft between the motor and the jaw hub, with the hub's own inertia "
                   "(an extra mode): k_s, d_s, J_h")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (10.0, 1e7), "k_s"),
                  Param("damping_Nms_per_rad", "N*m*s/rad", (0.0, 1e3), "d_s"),
                  Param("hub_inertia_kgm2", "kg*m^2", (1e-4, 1.0), "J_h (added to the drive train)"))
    note = "the catalogue's shaft is massless and quasi-static; a1 stays the motor's rim acceleration"

    def apply(self, b, p):
        b.P[P_KS] = p["stiffness_Nm_per_rad"]
        b.P[P_DS] = p["damping_Nms_per_rad"]
        b.P[P_JH] = p["hub_inertia_kgm2"]

    def equivalent(self, p):
        return {"compliance_rad_per_Nm": 1.0 / p["stiffness_Nm_per_rad"]}


# ============================================================ torque ripples (integer orders: locked to an angle)
class RippleMotorHarmonics(Form):
    name = "ripple_motor_harmonics"
    family = "torque_ripple"
    description = ("multi-harmonic cogging locked to the motor angle, sum_i A_i*sin(n_i*alpha1 + phi_i) on the "
                   "load moment (up to 4 integer orders)")
    parameters = (Param("orders", "per revolution", (1, 200), "integer orders n_i", "floats"),
                  Param("amplitudes_pu", "p.u.", (0.0, 2.0), "A_i", "floats"),
                  Param("phases_rad", "rad", (-math.pi, math.pi), "phi_i", "floats"))
    note = "equivalent: the largest harmonic"

    def apply(self, b, p):
        ords, amps, phs = p["orders"], p["amplitudes_pu"], p["phases_rad"]
        if not (len(ords) == len(amps) == len(phs)) or not 1 <= len(ords) <= 4 - b.next_ripple:
            raise ValueError(f"{self.name}: orders, amplitudes_pu, phases_rad need equal lengths 1..4 "
                             f"(got {len(ords)}, {len(amps)}, {len(phs)}; {b.next_ripple} of 4 slots used)")
        for n, a, ph in zip(ords, amps, phs):
            if float(n) != int(n):
                raise ValueError(f"{self.name}: order {n} is not an integer; allowed: whole orders (a ripple "
                                 "locked to the motor angle repeats every revolution)")
            i = b.next_ripple
            b.P[P_RN0 + 3 * i], b.P[P_RA0 + 3 * i], b.P[P_RP0 + 3 * i] = n, a, ph
            b.next_ripple += 1

    def equivalent(self, p):
        i = int(np.argmax(p["amplitudes_pu"]))
        return {"amplitude_pu": float(p["amplitudes_pu"][i]), "order": float(p["orders"][i])}


class RippleElectromagnetic(Form):
    name = "ripple_electromagnetic"
    family = "torque_ripple"
    description = ("a ripple of the electromagnetic torque itself (slot/permeance harmonics): "
                   "t_e*(1 + eps*sin(n*alpha1 + phi)), proportional to the torque the motor delivers")
    parameters = (Param("relative_amplitude", "-", (0.0, 1.0), "eps"),
                  Param("order", "per revolution", (1, 200), "n", "int"),
                  Param("phase_rad", "rad", (-math.pi, math.pi), "phi"))
    note = "equivalent amplitude: eps x the mean electromagnetic torque (0.609 p.u.)"

    def apply(self, b, p):
        b.P[P_EME], b.P[P_EMN], b.P[P_EMP] = p["relative_amplitude"], p["order"], p["phase_rad"]

    def equivalent(self, p):
        return {"amplitude_pu": p["relative_amplitude"] * OPERATING_POINT["mean_te_pu"], "order": float(p["order"])}


class RippleWheelMesh(Form):
    name = "ripple_wheel_mesh"
    family = "torque_ripple"
    description = "a gear-mesh torque on the load wheel locked to the WHEEL angle, A*sin(n*alpha2 + phi) [N*m]"
    parameters = (Param("amplitude_Nm", "N*m", (0.0, 100.0), "A"),
                  Param("order", "per revolution", (1, 200), "n", "int"),
                  Param("phase_rad", "rad", (-math.pi, math.pi), "phi"))
    note = ("the wheel turns with the motor (1:1 through the clutch), so the line is at n x the rotation "
            "frequency as a motor-angle ripple's; equivalent amplitude A/T_b (it reaches the motor through the jaw)")

    def apply(self, b, p):
        b.P[P_GMA], b.P[P_GMN], b.P[P_GMP] = p["amplitude_Nm"], p["order"], p["phase_rad"]

    def equivalent(self, p):
        return {"amplitude_pu": p["amplitude_Nm"] / C.BASE_TORQUE_NM, "order": float(p["order"])}


# ============================================================ drifts of the nominal physics
class _Drift(Form):
    stage = "drift"
    relative = True

    def equivalent(self, p):
        key = "relative_change" if self.relative else "change"
        return {key: p[self.parameters[0].name]}


def _drift(name_, family_, what, relative_, bounds, setter):
    pname = "relative_change" if relative_ else "change"
    unit = "-" if relative_ else ("m" if "width" in name_ else "-")
    desc = f"{what} drifted from nominal: " + ("value*(1 + change)" if relative_ else "value + change")
    return type("".join(w.title() for w in name_.split("_")), (_Drift,), dict(
        name=name_, family=family_, description=desc, relative=relative_,
        parameters=(Param(pname, unit, bounds, f"change of {what}"),),
        apply=lambda self, b, p: setter(b, p[pname])))


def _set_width(b, change):
    if b.width_m + change <= 0.0:
        raise ValueError(f"drift_width: width {b.width_m} + change {change} <= 0; allowed: a positive width")
    b.set_width(b.width_m + change)


def _scale(idx):
    def f(b, e):
        b.P[idx] *= 1.0 + e
    return f


DriftWidth = _drift("drift_width", "backlash_width_drift", "the backlash width (the MEASURAND: the recording's "
                    "true width is the drifted one)", False, (-0.01, 0.01), _set_width)
DriftMass = _drift("drift_mass", "load_mass_drift", "the mass m", True, (-0.9, 10.0), _scale(P_M))
DriftWheelInertia = _drift("drift_wheel_inertia", "wheel_inertia_drift", "the wheel inertia J2", True, (-0.9, 10.0),
                           _scale(P_J2))
DriftSpring = _drift("drift_spring", "spring_stiffness_drift", "the spring stiffness k", True, (-0.9, 10.0),
                     _scale(P_K))
DriftEtaK = _drift("drift_eta_k", "absorber_consistency_drift", "the absorber consistency eta_k", True, (-0.9, 10.0),
                   lambda b, e: b.set_absorber(b.eta_k * (1.0 + e), b.n1))
DriftN1 = _drift("drift_n1", "absorber_flow_index_drift", "the absorber flow index n1", False, (-0.5, 0.5),
                 lambda b, d: b.set_absorber(b.eta_k, b.n1 + d))
DriftWorkingResistance = _drift("drift_working_resistance", "working_resistance_drift", "the working resistance F0",
                                True, (-1.0, 10.0), _scale(P_F0))


def _pulse(b, e):
    b.pulse_amplitude_pu *= 1.0 + e


DriftPulseAmplitude = _drift("drift_pulse_amplitude", "pulse_amplitude_drift", "the pulse load's amplitude", True,
                             (-1.0, 10.0), _pulse)


# ============================================================ sensor chain (on a1 or a2)
_SIGNAL = Param("signal", "", SIGNALS, "the accelerometer: a1 (motor side) or a2 (mass)", "choice")


def _lowpass_tau(b, a, fs) -> float:
    """1/(2*pi*f_-3dB) of a digital filter (b, a) at fs: the first-order filter with the same corner."""
    from scipy.signal import freqz
    f = np.linspace(1.0, fs / 2, 200_001)
    _, h = freqz(b, a, worN=f, fs=fs)
    mag = np.abs(h) / abs(np.sum(b) / np.sum(a))
    i = int(np.argmax(mag < 1.0 / math.sqrt(2.0)))
    return 1.0 / (2.0 * math.pi * f[i])


class _Sensor(Form):
    stage = "sensor"
    order = 1                       # 0 gain/bias (sensing element), 1 filters


class LowpassButterworth(_Sensor):
    name = "lowpass_butterworth"
    family = "accelerometer_lowpass"
    description = "a Butterworth anti-alias low-pass of order N at f_c (maximally flat), discretised bilinearly"
    parameters = (_SIGNAL, Param("order", "-", (1, 8), "N", "int"), Param("corner_hz", "Hz", (10.0, 20_000.0), "f_c"))

    def _ba(self, p, fs):
        from scipy.signal import butter
        return butter(p["order"], p["corner_hz"], fs=fs)

    def apply_signal(self, sig, p, t, fs):
        sig[p["signal"]] = _filter(self._ba(p, fs), sig[p["signal"]])

    def equivalent(self, p):
        return {f"{p['signal']}_time_constant_s": 1.0 / (2.0 * math.pi * p["corner_hz"])}


class LowpassBessel(LowpassButterworth):
    name = "lowpass_bessel"
    description = "a Bessel low-pass of order N, -3 dB at f_c (flat group delay), discretised bilinearly"

    def _ba(self, p, fs):
        from scipy.signal import bessel
        return bessel(p["order"], p["corner_hz"], fs=fs, norm="mag")


class LowpassMovingAverage(_Sensor):
    name = "lowpass_moving_average"
    family = "accelerometer_lowpass"
    description = "a moving average over N samples (a decimating ADC's sinc^1 filter), -3 dB at ~0.443*fs/N"
    parameters = (_SIGNAL, Param("taps", "samples", (2, 2000), "N", "int"))

    def _ba(self, p, fs):
        n = p["taps"]
        return np.full(n, 1.0 / n), np.array([1.0])

    def apply_signal(self, sig, p, t, fs):
        sig[p["signal"]] = _filter(self._ba(p, fs), sig[p["signal"]])

    def equivalent(self, p):
        return {f"{p['signal']}_time_constant_s": _lowpass_tau(*self._ba(p, C.SAMPLE_RATE_HZ), C.SAMPLE_RATE_HZ)}


class LowpassFIR(LowpassMovingAverage):
    name = "lowpass_fir"
    description = "a linear-phase FIR anti-alias filter (Hamming-windowed sinc, N taps, cutoff f_c; delay (N-1)/2)"
    parameters = (_SIGNAL, Param("taps", "samples", (3, 2001), "N (odd)", "int"),
                  Param("cutoff_hz", "Hz", (10.0, 20_000.0), "f_c (-6 dB)"))

    def _ba(self, p, fs):
        from scipy.signal import firwin
        return firwin(p["taps"], p["cutoff_hz"], fs=fs, window="hamming"), np.array([1.0])


def _filter(ba, x):
    """Causal filtering, the filter's state settled on the first sample (a sensor that has been on)."""
    from scipy.signal import lfilter, lfilter_zi
    b, a = ba
    zi = lfilter_zi(b, a) * x[0]
    y, _ = lfilter(b, a, x, zi=zi)
    return y


class GainConstant(_Sensor):
    name = "gain_constant"
    family = "accelerometer_gain"
    order = 0
    description = "a scale error of the accelerometer: a -> a*(1 + g)"
    parameters = (_SIGNAL, Param("relative_change", "-", (-0.99, 10.0), "g"))

    def apply_signal(self, sig, p, t, fs):
        sig[p["signal"]] = sig[p["signal"]] * (1.0 + p["relative_change"])

    def equivalent(self, p):
        return {f"{p['signal']}_relative_change": p["relative_change"]}


class GainDrifting(_Sensor):
    name = "gain_drifting"
    family = "accelerometer_gain"
    order = 0
    description = "a scale error that drifts with the sensor's temperature: g(t) linear from g0 at t=0 to g1 at the end"
    parameters = (_SIGNAL, Param("start_relative_change", "-", (-0.99, 10.0), "g0"),
                  Param("end_relative_change", "-", (-0.99, 10.0), "g1"))
    note = "equivalent: the mean gain over the recording"

    def apply_signal(self, sig, p, t, fs):
        g = p["start_relative_change"] + (p["end_relative_change"] - p["start_relative_change"]) * t / max(t[-1], 1e-12)
        sig[p["signal"]] = sig[p["signal"]] * (1.0 + g)

    def equivalent(self, p):
        return {f"{p['signal']}_relative_change": 0.5 * (p["start_relative_change"] + p["end_relative_change"])}


class BiasConstant(_Sensor):
    name = "bias_constant"
    family = "accelerometer_bias"
    order = 0
    description = "a MEMS accelerometer's zero-g offset (up to about +-2 m/s^2): a -> a + b"
    parameters = (_SIGNAL, Param("bias_m_s2", "m/s^2", (-100.0, 100.0), "b"))

    def apply_signal(self, sig, p, t, fs):
        sig[p["signal"]] = sig[p["signal"]] + p["bias_m_s2"]

    def equivalent(self, p):
        return {f"{p['signal']}_m_s2": p["bias_m_s2"]}


class BiasDrifting(_Sensor):
    name = "bias_drifting"
    family = "accelerometer_bias"
    order = 0
    description = "a zero-g offset drifting with temperature: b(t) linear from b0 at t=0 to b1 at the end"
    parameters = (_SIGNAL, Param("start_m_s2", "m/s^2", (-100.0, 100.0), "b0"),
                  Param("end_m_s2", "m/s^2", (-100.0, 100.0), "b1"))
    note = "equivalent: the mean offset over the recording"

    def apply_signal(self, sig, p, t, fs):
        b = p["start_m_s2"] + (p["end_m_s2"] - p["start_m_s2"]) * t / max(t[-1], 1e-12)
        sig[p["signal"]] = sig[p["signal"]] + b

    def equivalent(self, p):
        return {f"{p['signal']}_m_s2": 0.5 * (p["start_m_s2"] + p["end_m_s2"])}


# ============================================================ a weaker motor (drifts of the motor's own physics)
class MotorRotorResistance(Form):
    name = "motor_rotor_resistance"
    family = "rotor_resistance_drift"
    description = ("the rotor resistance changed (a hot or a cracked rotor bar): r_r -> r_r*(1+e): slip and "
                   "breakdown slip move")
    parameters = (Param("relative_change", "-", (-0.5, 5.0), "e"),)
    note = "at one operating point the motor slips as it would under an extra load: a motor friction looks the same"

    def apply(self, b, p):
        b.P[P_RR] *= 1.0 + p["relative_change"]

    def equivalent(self, p):
        return {"relative_change": p["relative_change"]}


class SupplyVoltage(Form):
    name = "supply_voltage"
    family = "supply_voltage_drift"
    description = ("the supply voltage is not 1 p.u. (a weak grid, a sag): U -> U*(1+e); the breakdown torque "
                   "goes with U^2")
    parameters = (Param("relative_change", "-", (-0.3, 0.3), "e"),)
    note = "at one operating point the motor slips as it would under an extra load: a motor friction looks the same"

    def apply(self, b, p):
        b.P[P_U] *= 1.0 + p["relative_change"]

    def equivalent(self, p):
        return {"relative_change": p["relative_change"]}


# ============================================================ outside the catalogue (family None)


class ClutchContactProgressive(Form):
    name = "clutch_contact_progressive"
    family = None
    description = ("a strongly progressive jaw contact (an elastomer that stiffens as it fills): "
                   "k_c*p*(1 + (p/p0)^2) + d_c*p'")
    parameters = (Param("p0_rad", "rad", (1e-4, 1.0), "p0: at p = p0 the elastic torque is twice the linear law's"),)

    def apply(self, b, p):
        b.P[P_PROG] = p["p0_rad"]


class MotorRotorInertia(Form):
    name = "motor_rotor_inertia"
    family = None
    description = ("more inertia on the motor shaft than the model's (a brake disc, a flywheel, a heavier fan): "
                   "J1 -> J1*(1+e)")
    parameters = (Param("relative_change", "-", (-0.5, 5.0), "e"),)

    def apply(self, b, p):
        b.P[P_J1] *= 1.0 + p["relative_change"]


class ClutchContactPreload(Form):
    name = "clutch_contact_preload"
    family = None
    description = ("a preloaded jaw insert: the contact torque builds up to the preload T_pre within a small "
                   "penetration p_s, T_pre*(1 - exp(-p/p_s)) + k_c*p + d_c*p'")
    parameters = (Param("preload_Nm", "N*m", (0.0, 200.0), "T_pre"),
                  Param("build_up_rad", "rad", (1e-5, 1e-2), "p_s"))
    note = ("a step of T_pre at contact would be ill-posed with a penalty contact (below T_pre the jaw would "
            "chatter at p = 0); the build-up over p_s is a stiff initial segment, T_pre/p_s")

    def apply(self, b, p):
        b.P[P_CPRE] = p["preload_Nm"]
        b.P[P_CPRS] = p["build_up_rad"]


class SpringHardening(Form):
    name = "spring_hardening"
    family = "spring_stiffness_drift"
    description = "a hardening spring between rim and mass: k*z*(1 + (z/z0)^2)"
    parameters = (Param("z0_m", "m", (0.01, 100.0), "z0"),)
    note = ("a non-linear law of the spring family: around the static extension z_s = F0/k = 0.3 m its tangent "
            "stiffness is k*(1 + 3*(z_s/z0)^2) (measured: diagnose names spring_stiffness_drift +1.1 for z0 = 0.4 m, "
            "equivalent +1.69, with the model then consistent in every view)")

    def apply(self, b, p):
        b.P[P_Z0] = p["z0_m"]

    def equivalent(self, p):
        zs = C.WORKING_RESISTANCE_N / C.SPRING_STIFFNESS_N_PER_M
        return {"relative_change": 3.0 * (zs / p["z0_m"]) ** 2}


class StructuralVibration(Form):
    name = "structural_vibration"
    family = None
    description = ("a structural resonance excited from outside at a FIXED frequency (not locked to any shaft "
                   "angle): A*sin(2*pi*f*t + phi) on the motor's load moment")
    parameters = (Param("amplitude_pu", "p.u.", (0.0, 2.0), "A"), Param("frequency_hz", "Hz", (0.1, 20_000.0), "f"),
                  Param("phase_rad", "rad", (-math.pi, math.pi), "phi"))

    def apply(self, b, p):
        b.P[P_VIBA], b.P[P_VIBF], b.P[P_VIBP] = p["amplitude_pu"], p["frequency_hz"], p["phase_rad"]


class SecondTorsionalMode(Form):
    name = "second_torsional_mode"
    family = None
    description = ("the load wheel is not rigid: its rim (a fraction of J2, carrying the belt to the mass) sits "
                   "on a torsional spring k_w with damping d_w against its hub: a second torsional mode")
    parameters = (Param("rim_fraction", "-", (0.05, 0.95), "J_rim/J2"),
                  Param("stiffness_Nm_per_rad", "N*m/rad", (1.0, 1e7), "k_w"),
                  Param("damping_Nms_per_rad", "N*m*s/rad", (0.0, 1e3), "d_w"))

    def apply(self, b, p):
        j2 = b.P[P_J2]
        b.P[P_JR] = p["rim_fraction"] * j2
        b.P[P_J2] = (1.0 - p["rim_fraction"]) * j2
        b.P[P_KW] = p["stiffness_Nm_per_rad"]
        b.P[P_DW] = p["damping_Nms_per_rad"]

    @staticmethod
    def mode_hz(rim_fraction: float, stiffness: float) -> float:
        """Frequency of the rim against hub + motor (clutch engaged): sqrt(k_w*(1/J_r + 1/(J_h + J1)))/(2*pi)."""
        jr = rim_fraction * C.WHEEL_INERTIA_KGM2
        jh = (1.0 - rim_fraction) * C.WHEEL_INERTIA_KGM2 + C.MOTOR_INERTIA_KGM2
        return math.sqrt(stiffness * (1.0 / jr + 1.0 / jh)) / (2.0 * math.pi)


FORM_CLASSES = (WheelFrictionTanh, WheelFrictionLoadDependent, WheelDragPower, WheelFrictionStribeckPower,
                WheelLoadTorque, MotorFrictionTanh, MotorFrictionViscous, MotorFanLoad, MotorLoadConstant,
                MassRailFriction, MassDrag, MassForceConstant, ClutchContactHertz, ClutchContactAsymmetric,
                ClutchDampingHuntCrossley, ClutchDampingValue, ShaftWithHub, RippleMotorHarmonics,
                RippleElectromagnetic, RippleWheelMesh, DriftWidth, DriftMass, DriftWheelInertia, DriftSpring,
                DriftEtaK, DriftN1, DriftWorkingResistance, DriftPulseAmplitude, LowpassButterworth, LowpassBessel,
                LowpassMovingAverage, LowpassFIR, GainConstant, GainDrifting, BiasConstant, BiasDrifting,
                MotorRotorResistance, SupplyVoltage, MotorRotorInertia, ClutchContactProgressive, ClutchContactPreload, SpringHardening,
                StructuralVibration, SecondTorsionalMode)
FORMS = {cls.name: cls() for cls in FORM_CLASSES}


# the sets of mechanisms outside the catalogue (issue 31): foreign_drives.outside_dev, .outside_sealed, then
# .outside_devN, .outside_sealedN for N = 2 .. OUTSIDE_SETS, registered set by set, development half first
OUTSIDE_SETS = 24
OUTSIDE_MODULES = tuple(f"outside_{half}{'' if n == 1 else n}" for n in range(1, OUTSIDE_SETS + 1)
                        for half in ("dev", "sealed"))


def _register_outside() -> None:
    """The mechanisms outside the catalogue (OUTSIDE_MODULES, each module's FORM_CLASSES) join FORMS. Imported here,
    at the end, because they build on Form and Param above."""
    import importlib
    for name in OUTSIDE_MODULES:
        for cls in importlib.import_module(f".{name}", __package__).FORM_CLASSES:
            FORMS[cls.name] = cls()


_register_outside()

# the catalogue's families (backlash_monitor/plant/effects.py CATALOGUE, written out: this package does not
# import the plant); test_foreign_drives checks the list against the catalogue
CATALOGUE_FAMILIES = (
    "wheel_coulomb_friction", "wheel_viscous_friction", "wheel_stribeck_friction", "motor_coulomb_friction",
    "clutch_contact_stiffness", "clutch_contact_damping", "shaft_compliance", "mass_force_offset",
    "motor_load_offset", "torque_ripple", "accelerometer_bias", "accelerometer_gain", "accelerometer_lowpass",
    "backlash_width_drift", "absorber_consistency_drift", "absorber_flow_index_drift", "spring_stiffness_drift",
    "load_mass_drift", "wheel_inertia_drift", "working_resistance_drift", "pulse_amplitude_drift",
    "rotor_resistance_drift", "supply_voltage_drift")


def get(name: str) -> Form:
    if name not in FORMS:
        import difflib
        near = difflib.get_close_matches(name, list(FORMS), n=1)
        raise ValueError(f"unknown effect form {name!r}" + (f" (nearest: {near[0]!r})" if near else "")
                         + "; allowed: " + ", ".join(FORMS))
    return FORMS[name]


def check_parameters(form: Form, params: dict) -> dict:
    """The parameters of one use of a form, checked (every one given, none unknown, within bounds); returns a
    plain dict of JSON-able values. Raises ValueError with one line naming the problem."""
    names = [p.name for p in form.parameters]
    unknown = [k for k in params if k not in names]
    if unknown:
        raise ValueError(f"effect {form.name}: unknown parameter {unknown[0]!r}; allowed: {', '.join(names)}")
    missing = [n for n in names if n not in params]
    if missing:
        raise ValueError(f"effect {form.name}: parameter {missing[0]!r} is missing; needs {', '.join(names)}")
    out = {}
    for p in form.parameters:
        v = params[p.name]
        if p.kind == "choice":
            if v not in p.bounds:
                raise ValueError(f"effect {form.name}: {p.name} = {v!r}; allowed: {', '.join(map(str, p.bounds))}")
            out[p.name] = v
            continue
        vals = list(v) if p.kind == "floats" else [v]
        if p.kind == "floats" and not vals:
            raise ValueError(f"effect {form.name}: {p.name} is empty; allowed: a list of numbers")
        for x in vals:
            if isinstance(x, bool) or not isinstance(x, (int, float, np.integer, np.floating)) or not math.isfinite(x):
                raise ValueError(f"effect {form.name}: {p.name} = {x!r} is not a finite number")
            if p.kind == "int" and float(x) != int(x):
                raise ValueError(f"effect {form.name}: {p.name} = {x!r}; allowed: a whole number")
            lo, hi = p.bounds
            if not lo <= x <= hi:
                raise ValueError(f"effect {form.name}: {p.name} = {x!r} is outside {lo:g}..{hi:g} {p.unit}")
        if p.kind == "floats":
            out[p.name] = [float(x) for x in vals]
        elif p.kind == "int":
            out[p.name] = int(v)
        else:
            out[p.name] = float(v)
    return out
