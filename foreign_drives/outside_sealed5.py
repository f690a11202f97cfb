"""Outside mechanisms, fifth SEALED half (issue 31 part 4, set 5).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed5``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first four sets
nor the fifth development half (:mod:`outside_dev5`) has, and the suite's rows (seeds 8300+). The split rule is in
:mod:`outside_dev5` (written as one list of fourteen; the even numbers are here). Written before any diagnose,
analyze or proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed5")``), not listed in
``suites.SUITES``.

2. motor load moment x a PRODUCT of the load pulse and the motor speed: the stroke's forming load is strain-rate
   sensitive (a viscoplastic material: its flow stress rises with the ram's speed), so during a stroke the load grows
   with the motor speed, pulse*c*(Omega1 - Omega_ref);
4. wheel torque x the spring extension SAMPLED AT EACH STROKE: a strip-tension control (a dancer) reads the spring's
   extension once per stroke, at the pulse's rising edge, and sets the wheel's feed brake for the whole stroke period
   from it, -K*(z_k - z_ref), held until the next stroke;
6. clutch torque x the motor speed SQUARED times the sign of the slip: centrifugal friction shoes in the coupling, in
   parallel with the jaw; their normal force grows with Omega1^2 and they pass a dry friction torque from the faster
   half to the slower, in the gap too, c*Omega1^2*tanh((Omega1 - Omega2)/eps);
8. mass force x the carriage's own POSITION (spatially periodic, locked to neither shaft): the carriage's rail has a
   joint every L metres; each time the carriage's wheel rolls over one, over a length l, it is braked with F;
10. a1 sensor x a1 UNDERSAMPLED (aliasing): a1 comes from a module that samples at fs/M with no anti-alias filter; the
    recorder interpolates its samples linearly up to 50 kHz;
12. motor load moment x the motor speed QUANTISED (encoder counts per scan): a PLC reads the motor speed as an
    encoder's count per scan (steps of q rad/s), sampled every scan, and puts a regenerative load on the motor of K
    per whole step above a set speed;
14. wheel torque x the wheel speed TIMES the pulse through an inductor's LAG: an eddy-current brake on the wheel
    energised for each stroke; its field current follows the pulse with the coil's L/R, -c*Omega2*i, i' = (pulse - i)/tau.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory


# 2. motor load moment x the pulse times the motor speed
class MotorViscoplasticStroke(OutsideForm):
    name = "motor_viscoplastic_stroke"
    half = "sealed5"
    balance = "motor_load_moment"
    depends_on = ("load_pulse", "motor_speed")
    description = ("the stroke's forming load is strain-rate sensitive (a viscoplastic material): during a stroke it "
                   "grows with the ram's speed, pulse*c*(Omega1 - Omega_ref) on the motor's load, pulse = 1 while on")
    parameters = (Param("coefficient_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("reference_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_ref: the speed at the nominal load"))

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["coefficient_Nms_per_rad"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_OMEGA1, K.XF_CLIP, 1e9, -p["reference_speed_rad_s"], 0.0))

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nms_per_rad']:.6g} N*m*s/rad * pulse * (Omega1 - "
                f"{p['reference_speed_rad_s']:.6g} rad/s)")


# 4. wheel torque x the spring extension sampled at each stroke
class WheelStrokeTensionControl(OutsideForm):
    name = "wheel_stroke_tension_control"
    half = "sealed5"
    balance = "wheel_torque"
    depends_on = ("spring_extension", "load_pulse")
    description = ("a strip-tension control (a dancer) reads the spring's extension once per stroke, at the 0.2 ms scan "
                   "at which the load pulse begins, and sets the wheel's feed brake for the whole stroke period from "
                   "it: -K*(z_k - z_ref), held until the next stroke")
    parameters = (Param("gain_Nm_per_m", "N*m/m", (0.0, 5000.0), "K"),
                  Param("reference_extension_m", "m", (0.0, 1.0), "z_ref"))

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_STROKE_SAMPLE, K.XS_SPRING_EXTENSION, 0.0)
        add_term(b, "wheel_torque", -p["gain_Nm_per_m"],
                 (K.XS_MEMORY, K.XF_CLIP, 1e9, -p["reference_extension_m"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['gain_Nm_per_m']:.6g} N*m/m * (z_k - {p['reference_extension_m']:.6g} m), z_k the "
                "spring extension at the start of the latest load pulse (scanned every 0.2 ms), held")


# 6. clutch torque x the motor speed squared times the sign of the slip
class ClutchCentrifugalShoes(OutsideForm):
    name = "clutch_centrifugal_shoes"
    half = "sealed5"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("centrifugal friction shoes in the coupling, in parallel with the jaw: their normal force grows with "
                   "Omega1^2 and they pass a dry friction torque from the faster half to the slower, in the gap too: "
                   "c*Omega1^2*tanh((Omega1 - Omega2)/eps)")
    parameters = (Param("coefficient_Nms2", "N*m*s^2/rad^2", (0.0, 0.01), "c"),
                  Param("smoothing_rad_s", "rad/s", (0.01, 10.0), "eps"))

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["coefficient_Nms2"], (K.XS_OMEGA1, K.XF_POWER, 2.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_TANH, p["smoothing_rad_s"], 0.0, 0.0))

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nms2']:.6g} N*m*s^2/rad^2 * Omega1^2 * tanh((Omega1 - Omega2) / "
                f"{p['smoothing_rad_s']:.6g} rad/s)")


# 8. mass force x the carriage's own position
class MassRailJoints(OutsideForm):
    name = "mass_rail_joints"
    half = "sealed5"
    balance = "mass_force"
    depends_on = ("wheel_angle", "spring_extension")
    description = ("the carriage's rail has a joint every L metres: while the carriage's wheel rolls over one, "
                   "(x - x_0) mod L < l, it is braked with -F*sign(v); x the carriage's position on the simulator's "
                   "coordinate (r*theta2 - z, theta2 the wheel angle unwrapped from the run-in's start)")
    parameters = (Param("force_N", "N", (0.0, 200.0), "F"),
                  Param("spacing_m", "m", (0.1, 10.0), "L"),
                  Param("length_m", "m", (1e-3, 1.0), "l"),
                  Param("offset_m", "m", (0.0, 10.0), "x_0"))

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_N"],
                 (K.XS_MASS_POSITION, K.XF_PERIODIC_GATE, p["spacing_m"], p["offset_m"], p["length_m"]),
                 (K.XS_MASS_SPEED, K.XF_TANH, 0.01, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * sign(v) while (x - {p['offset_m']:.6g}) mod "
                f"{p['spacing_m']:.6g} < {p['length_m']:.6g} m, x the carriage's position (simulator's coordinate, "
                "unwrapped)")


# 10. a1 sensor x a1 undersampled
class A1UndersampledModule(OutsideForm):
    name = "a1_undersampled_module"
    half = "sealed5"
    stage = "sensor"
    order = 1                      # the module's sampler, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1 comes from a module that samples every M-th recorder sample (fs/M) with no anti-alias filter; "
                   "the recorder interpolates its samples linearly (from the pre-roll's first sample)")
    parameters = (Param("decimation", "samples", (1, 100), "M (1: no module)", "int"),)

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.resampled(sig["a1"], t, int(p["decimation"]))

    @staticmethod
    def resampled(a, t, m):
        a, t = np.asarray(a, dtype=np.float64), np.asarray(t, dtype=np.float64)
        if m == 1:
            return a.copy()
        return np.interp(t, t[::m], a[::m])

    def law(self, p):
        return f"a1 sensor = a1 taken every {int(p['decimation'])} samples, linearly interpolated"


# 12. motor load moment x the motor speed quantised
class MotorEncoderCountRegen(OutsideForm):
    name = "motor_encoder_count_regen"
    half = "sealed5"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a PLC reads the motor speed as an encoder's count per scan (steps of q rad/s), sampled every scan "
                   "T_s, and puts a regenerative load on the motor of K*q per whole step above Omega_set: "
                   "K*q*floor((Omega1_s - Omega_set)/q) above Omega_set, held over the scan")
    parameters = (Param("gain_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "K"),
                  Param("step_rad_s", "rad/s", (0.1, 50.0), "q"),
                  Param("set_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_set"),
                  Param("scan_s", "s", (2e-4, 0.01), "T_s (a multiple of 0.2 ms)"))

    def apply(self, b, p):
        scan = segments(p["scan_s"], f"{self.name}: scan_s")
        set_memory(b, self.name, K.MK_DELAY, K.XS_OMEGA1, float(scan), 0.0)
        add_term(b, "motor_load_moment", p["gain_Nms_per_rad"],
                 (K.XS_MEMORY, K.XF_STAIRS, p["step_rad_s"], p["set_speed_rad_s"], 0.0), nonperiodic=True)

    def law(self, p):
        q = p["step_rad_s"]
        return (f"motor load moment += {p['gain_Nms_per_rad']:.6g} N*m*s/rad * {q:.6g} * floor((Omega1_s - "
                f"{p['set_speed_rad_s']:.6g})/{q:.6g}) rad/s above {p['set_speed_rad_s']:.6g}, Omega1_s sampled every "
                f"{p['scan_s']:.6g} s")


# 14. wheel torque x the wheel speed times the pulse through a lag
class WheelEddyBrakeFieldLag(OutsideForm):
    name = "wheel_eddy_brake_field_lag"
    half = "sealed5"
    balance = "wheel_torque"
    depends_on = ("wheel_speed", "load_pulse")
    description = ("an eddy-current brake on the wheel energised for each stroke: its field current follows the pulse "
                   "with the coil's L/R, -c*Omega2*i, i -> pulse with tau (advanced every 0.2 ms)")
    parameters = (Param("coefficient_Nms_per_rad", "N*m*s/rad", (0.0, 5.0), "c"),
                  Param("time_constant_s", "s", (1e-4, 1.0), "tau = L/R"))

    def apply(self, b, p):
        tau = p["time_constant_s"]
        set_memory(b, self.name, K.MK_LAG, K.XS_PULSE, tau, tau, 0.0)
        add_term(b, "wheel_torque", -p["coefficient_Nms_per_rad"], (K.XS_OMEGA2, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nms_per_rad']:.6g} N*m*s/rad * Omega2 * i, i -> pulse with "
                f"{p['time_constant_s']:.6g} s (every 0.2 ms)")


FORM_CLASSES = (MotorViscoplasticStroke, WheelStrokeTensionControl, ClutchCentrifugalShoes, MassRailJoints,
                A1UndersampledModule, MotorEncoderCountRegen, WheelEddyBrakeFieldLag)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 8300+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        ("os5_motor_viscoplastic_stroke", "outside", 0.0075, 0.035, 0.90,
         [E("motor_viscoplastic_stroke", {"coefficient_Nms_per_rad": 4.03, "reference_speed_rad_s": 150.0})]),
        ("os5_wheel_stroke_tension_control", "outside", 0.0052, 0.0225, 0.94,
         [E("wheel_stroke_tension_control", {"gain_Nm_per_m": 200.0, "reference_extension_m": 0.305})]),
        ("os5_clutch_centrifugal_shoes", "outside", 0.0088, 0.0175, 0.92,
         [E("clutch_centrifugal_shoes", {"coefficient_Nms2": 2e-4, "smoothing_rad_s": 0.5})]),
        ("os5_mass_rail_joints", "outside", 0.0045, 0.04, 0.96,
         [E("mass_rail_joints", {"force_N": 10.0, "spacing_m": 1.3, "length_m": 0.03, "offset_m": 0.4})]),
        ("os5_clean_w6.6_eta0.0275_n0.89", "clean", 0.0066, 0.0275, 0.89, []),
        ("os5_a1_undersampled_module", "outside", 0.0095, 0.025, 0.93, [E("a1_undersampled_module", {"decimation": 8})]),
        ("os5_motor_encoder_count_regen", "outside", 0.0065, 0.045, 0.91,
         [E("motor_encoder_count_regen", {"gain_Nms_per_rad": 0.5, "step_rad_s": 6.136, "set_speed_rad_s": 145.0,
                                          "scan_s": 0.001})]),
        ("os5_wheel_eddy_brake_field_lag", "outside", 0.0038, 0.03, 0.95,
         [E("wheel_eddy_brake_field_lag", {"coefficient_Nms_per_rad": 0.02, "time_constant_s": 0.02})]),
    ]
