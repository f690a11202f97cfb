"""Outside mechanisms, fifteenth SEALED half (issue 31 part 4, set 15): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev15`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the motor speed through a PI CONTROLLER with a BRAKE-ONLY output: a speed-limiting eddy-current
   brake on the motor's shaft under a digital PI controller, u = K_p*e + I, e = Omega1 - Omega_ref, I += K_i*e*dt
   unless u is at a limit and e pushes it further (clamping anti-windup), u limited to [0, T_max], scanned every 0.2 ms
   (I = 0 at the run-in's start); u on the motor's load (the sixth set's PI brake reads the wheel speed for the
   wheel; the earlier memories of the motor speed on the motor are lags, a play, a relay, a rate limit, a moving
   mean, a peak, a one-shot, a step controller, an unloader, a heat, a slip hub, a magnetic coupling, an absorber);
4. wheel torque x the jaw's DRIVE-FACE CONTACT through a FILL: a hydraulic drag brake on the wheel whose cylinder a
   pump fills while a contact switch on the jaw's drive faces is closed and which empties through a return orifice
   otherwise: -T*m, m += dt/T_f while the drive faces touch, m -= dt/T_d otherwise, clamped to [0, 1] (scanned every
   0.2 ms; m = 0 at the run-in's start) (a level integrated up and down by the jaw's own contact: the tenth set's
   interlock brake rises afresh from each contact's start and drops in the gap, the fourteenth sealed half's run-on
   coupling is held on for a set time after each contact, the eleventh sealed half's fill follows the load pulse);
6. clutch torque x the slip through a THERMAL memory of its own dissipation: a viscous (silicone) coupling beside the
   jaw whose fluid thins as it heats, Reynolds' law: c*(Omega1 - Omega2)*exp(-theta/theta_c), theta += dt*(a*(Omega1 -
   Omega2)^2 - theta/tau) every 0.2 ms (theta = 0 at the run-in's start) (the first set's gap drag is this coupling
   cold; the earlier memories of the slip are a lag, a delay, a tank, an on- and an off-delay, a fill; the fifth set's
   insert heating softens the contact law with the contact's power, the seventh sealed half's warm-up thins the motor
   bearings' grease with the motor speed, the tenth set's cut-out switches a wheel brake);
8. mass force x the spring extension through a DAHL element: the spring's cable is a stranded wire rope whose strands
   rub on each other as it stretches and slackens (taken at the cable guide on the carriage): F_f*s along x, s ->
   sign(dz) - (sign(dz) - s)*exp(-|dz|/z_c) for each change dz of the extension over a 0.2 ms scan (s = 0 at the
   run-in's start) (a rate-independent friction of the extension's direction: the sixth set's Dahl ring is across the
   jaw, the twelfth set's lost-motion link is a play with a linear slot, the ninth set's cable friction follows the
   carriage's speed);
10. a1 sensor x a1's own past through a FIXED LATENCY: a1's rotating telemetry buffers d samples before it sends
    them, so the recorded a1 is the signal d samples earlier: y[n] = x[n - d] (x[0] before the pre-roll's first
    sample) (a pure delay of one channel: the sixth sealed half's jitter is random, the fourth's clock lag grows,
    the twelfth set's echo adds a delayed copy to the signal);
12. a2 sensor x the MOTOR SPEED, additive: a2's signal return shares a wire with the motor's tacho-generator, whose
    output (zeroed by the drive's bias at Omega_0) drops across it: y = x + k*(Omega1 - Omega_0) (the thirteenth set's
    magnet pickup is locked to the motor's angle and only scaled by its speed; the fourteenth set's velocity
    sensitivity reads the carriage's speed; the first sealed half's centripetal term is a1's, of Omega1 squared);
14. motor load moment x the jaw's GAP DISTANCE through a CUSHION: an approach brake: an inductive gap sensor between
    the jaw faces feeds an eddy-current brake on the motor while the halves are apart, the harder the nearer a face:
    c*(h_0/(h + h_0))^n, h the distance to the nearer face, 0 while the faces touch (the third sealed half's squeeze
    film is a clutch torque of the slip times such a factor; no earlier motor load reads the jaw's geometry but through
    the contact torque).

Visibility, measured as for the development half (4 s, against the same spec without the mechanism, same seed;
criterion a2 >= 0.05, a1 >= 0.25 for an a1 row): 2 a2 0.0399 at its a-priori strength, scaled once x1.88 (a2 0.0590
after); 4 a2 0.107; 6 a2 0.119; 8 a2 0.180; 10 a1 7.54; 12 a2 0.0488, scaled once x1.54 (a2 0.0750 after); 14 a2 0.0419,
scaled once x1.79 (a2 0.0749 after) -- the others as written.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 2. motor load moment x the motor speed through a PI controller with a brake-only output
class MotorPiSpeedLimitBrake(OutsideForm):
    name = "motor_pi_speed_limit_brake"
    half = "sealed15"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a speed-limiting eddy-current brake on the motor's shaft under a digital PI controller: u = K_p*e + "
                   "I, e = Omega1 - Omega_ref, I += K_i*e*dt unless u is at a limit and e pushes it further (clamping "
                   "anti-windup), u limited to [0, T_max]; u on the motor's load (scanned every 0.2 ms from the run-in's "
                   "start, I = 0 there)")
    parameters = (Param("proportional_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "K_p"),
                  Param("integral_Nm_per_rad", "N*m/rad", (0.0, 500.0), "K_i"),
                  Param("max_torque_Nm", "N*m", (0.0, 50.0), "T_max"),
                  Param("reference_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_ref: the speed it limits to"))
    note = "a brake-only PI controller of the motor's own speed"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PI_SAT, K.XS_OMEGA1, p["proportional_Nms_per_rad"], p["integral_Nm_per_rad"],
                   p["max_torque_Nm"])
        set_extra(b, p["reference_speed_rad_s"])
        add_term(b, "motor_load_moment", 1.0, (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += u, u = clip({p['proportional_Nms_per_rad']:.6g}*e + I, 0, "
                f"{p['max_torque_Nm']:.6g} N*m), e = Omega1 - {p['reference_speed_rad_s']:.6g} rad/s, I += "
                f"{p['integral_Nm_per_rad']:.6g}*e*dt unless saturated further (every 0.2 ms)")


# 4. wheel torque x the jaw's drive-face contact through a fill
class WheelDriveContactFillBrake(OutsideForm):
    name = "wheel_drive_contact_fill_brake"
    half = "sealed15"
    balance = "wheel_torque"
    depends_on = ("clutch_penetration",)
    description = ("a hydraulic drag brake on the wheel whose cylinder a pump fills while a contact switch on the jaw's "
                   "drive faces is closed and which empties through a return orifice otherwise: -T*m, m += dt/T_f while "
                   "the drive faces are in contact, m -= dt/T_d otherwise, clamped to [0, 1] (scanned every 0.2 ms; m = "
                   "0 at the run-in's start)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("fill_time_s", "s", (2e-4, 10.0), "T_f"),
                  Param("drain_time_s", "s", (2e-4, 10.0), "T_d"))
    note = "a brake level integrated up and down by the jaw's own contact"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_FILL, K.XS_MODE, p["fill_time_s"], p["drain_time_s"])
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * m, m += 0.2 ms/{p['fill_time_s']:.6g} s at a scan with the "
                f"drive faces in contact, else m -= 0.2 ms/{p['drain_time_s']:.6g} s, m in [0, 1]")


# 6. clutch torque x the slip through a thermal memory of its own dissipation
class ClutchHeatThinnedViscousCoupling(OutsideForm):
    name = "clutch_heat_thinned_viscous_coupling"
    half = "sealed15"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a viscous (silicone) coupling beside the jaw whose fluid thins as it heats (Reynolds' law): "
                   "c*(Omega1 - Omega2)*exp(-theta/theta_c) from the motor to the wheel, in the gap and in contact, "
                   "theta += dt*(a*(Omega1 - Omega2)^2 - theta/tau) every 0.2 ms (theta = 0 at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c (cold)"),
                  Param("heating_K_s_per_rad2", "K*s/rad^2", (0.0, 1000.0), "a"),
                  Param("cooling_time_s", "s", (1e-3, 100.0), "tau"),
                  Param("thinning_K", "K", (0.1, 1000.0), "theta_c"))
    note = "a viscous coupling of the slip thinned by the heat its slip makes"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_HEAT, K.XS_JAW_SPEED, p["heating_K_s_per_rad2"], p["cooling_time_s"])
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_MEMORY, K.XF_DECAY_AFTER, p["thinning_K"], 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) * exp(-theta/"
                f"{p['thinning_K']:.6g} K), theta += 0.2 ms*({p['heating_K_s_per_rad2']:.6g}*(Omega1 - Omega2)^2 - "
                f"theta/{p['cooling_time_s']:.6g} s) every 0.2 ms")


# 8. mass force x the spring extension through a Dahl element
class MassWireRopeStrandFriction(OutsideForm):
    name = "mass_wire_rope_strand_friction"
    half = "sealed15"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("the spring's cable is a stranded wire rope whose strands rub as it stretches and slackens (taken at "
                   "the cable guide on the carriage): F_f*s along x, s -> sign(dz) - (sign(dz) - s)*exp(-|dz|/z_c) for "
                   "each change dz of the spring's extension over a 0.2 ms scan (s = 0 at the run-in's start)")
    parameters = (Param("friction_force_N", "N", (0.0, 100.0), "F_f"),
                  Param("presliding_m", "m", (1e-5, 0.1), "z_c"))
    note = "a rate-independent (Dahl) friction of the extension's direction"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_DAHL, K.XS_SPRING_EXTENSION, p["presliding_m"])
        add_term(b, "mass_force", p["friction_force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['friction_force_N']:.6g} N * s, s -> sign(dz) - (sign(dz) - s)*exp(-|dz|/"
                f"{p['presliding_m']:.6g} m) for each change dz of the spring's extension over a 0.2 ms scan")


# 10. a1 sensor x a1's own past through a fixed latency
class A1TelemetryBufferLatency(OutsideForm):
    name = "a1_telemetry_buffer_latency"
    half = "sealed15"
    stage = "sensor"
    order = 1                      # the telemetry link, after the sensing element
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1's rotating telemetry buffers d samples before it sends them: the recorded a1 is the signal d "
                   "samples earlier, y[n] = x[n - d] (x[0] before the pre-roll's first sample)")
    parameters = (Param("latency_samples", "samples", (0, 1000), "d", "int"),)
    note = "a pure delay of one channel"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        x = np.asarray(a, dtype=np.float64)
        d = int(p["latency_samples"])
        if d <= 0:
            return x.copy()
        return np.concatenate([np.full(min(d, x.size), x[0]), x[:max(0, x.size - d)]])

    def law(self, p):
        return f"a1 sensor: y[n] = a1[n - {int(p['latency_samples'])}] (a1[0] before the first sample)"


# 12. a2 sensor x the motor speed, additive
class A2TachoSharedReturn(OutsideForm):
    name = "a2_tacho_shared_return"
    half = "sealed15"
    stage = "sensor"
    order = 1                      # the cable, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "motor_speed")
    description = ("a2's signal return shares a wire with the motor's tacho-generator, whose output (zeroed by the "
                   "drive's bias at Omega_0) drops across it: y = x + k*(Omega1 - Omega_0)")
    parameters = (Param("gain_m_s2_per_rad_s", "(m/s^2)/(rad/s)", (-1.0, 1.0), "k"),
                  Param("zero_speed_rad_s", "rad/s", (0.0, 300.0), "Omega_0"))
    note = "a reading that carries the motor's speed besides the carriage's acceleration"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], states["omega1"], p)

    @staticmethod
    def read(a, omega1, p):
        return (np.asarray(a, dtype=np.float64)
                + p["gain_m_s2_per_rad_s"] * (np.asarray(omega1, dtype=np.float64) - p["zero_speed_rad_s"]))

    def law(self, p):
        return (f"a2 sensor += {p['gain_m_s2_per_rad_s']:.6g} (m/s^2)/(rad/s) * (Omega1 - {p['zero_speed_rad_s']:.6g} "
                "rad/s)")


# 14. motor load moment x the jaw's gap distance through a cushion
class MotorJawGapApproachBrake(OutsideForm):
    name = "motor_jaw_gap_approach_brake"
    half = "sealed15"
    balance = "motor_load_moment"
    depends_on = ("clutch_penetration",)
    description = ("an approach brake: an inductive gap sensor between the jaw faces feeds an eddy-current brake on the "
                   "motor while the halves are apart: c*(h_0/(h + h_0))^n on the motor's load, h the distance to the "
                   "nearer face, 0 while the faces touch")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "c (at a face)"),
                  Param("scale_rad", "rad", (1e-4, 0.1), "h_0"),
                  Param("exponent", "-", (0.5, 6.0), "n"))
    note = "a load on the motor of the jaw's geometry in the gap"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"],
                 (K.XS_GAP_DISTANCE, K.XF_CUSHION, p["scale_rad"], p["exponent"], 0.0))

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * ({p['scale_rad']:.6g} rad/(h + {p['scale_rad']:.6g} "
                f"rad))^{p['exponent']:.6g} while the jaw is free, h the distance to the nearer face; 0 in contact")


FORM_CLASSES = (MotorPiSpeedLimitBrake, WheelDriveContactFillBrake, ClutchHeatThinnedViscousCoupling,
                MassWireRopeStrandFriction, A1TelemetryBufferLatency, A2TachoSharedReturn, MotorJawGapApproachBrake)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 15100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # brake-only PI above 152 rad/s; K_p 1 N*m*s/rad, K_i 20 N*m/rad, up to 5 N*m a priori, a2 0.0399: the three
        # scaled once x1.88
        ("os15_motor_pi_speed_limit_brake", "outside", 0.0061, 0.0285, 0.93,
         [E("motor_pi_speed_limit_brake", {"proportional_Nms_per_rad": 1.880, "integral_Nm_per_rad": 37.60,
                                           "max_torque_Nm": 9.399, "reference_speed_rad_s": 152.0})]),
        # 3 N*m when full, filled in 0.1 s of drive-face contact, emptied in 0.2 s
        ("os15_wheel_drive_contact_fill_brake", "outside", 0.0079, 0.0245, 0.91,
         [E("wheel_drive_contact_fill_brake", {"torque_Nm": 3.0, "fill_time_s": 0.1, "drain_time_s": 0.2})]),
        # 1.5 N*m*s/rad cold, 10 K*s/rad^2, cooling in 0.1 s, thinned by e per 10 K
        ("os15_clutch_heat_thinned_viscous_coupling", "outside", 0.0056, 0.0335, 0.94,
         [E("clutch_heat_thinned_viscous_coupling", {"coefficient_Nm_s_per_rad": 1.5, "heating_K_s_per_rad2": 10.0,
                                                     "cooling_time_s": 0.1, "thinning_K": 10.0})]),
        # 2 N, pre-sliding over 2 mm of extension
        ("os15_mass_wire_rope_strand_friction", "outside", 0.0071, 0.0265, 0.90,
         [E("mass_wire_rope_strand_friction", {"friction_force_N": 2.0, "presliding_m": 0.002})]),
        ("os15_clean_w8.2_eta0.0315_n0.92", "clean", 0.0082, 0.0315, 0.92, []),
        # 5 samples (0.1 ms)
        ("os15_a1_telemetry_buffer_latency", "outside", 0.0064, 0.0355, 0.95,
         [E("a1_telemetry_buffer_latency", {"latency_samples": 5})]),
        # about 151 rad/s; 0.03 (m/s^2)/(rad/s) a priori, a2 0.0488: scaled once x1.54
        ("os15_a2_tacho_shared_return", "outside", 0.0087, 0.0225, 0.93,
         [E("a2_tacho_shared_return", {"gain_m_s2_per_rad_s": 0.04609, "zero_speed_rad_s": 151.0})]),
        # h_0 5 mrad, n 2; 8 N*m at a face a priori, a2 0.0419: scaled once x1.79
        ("os15_motor_jaw_gap_approach_brake", "outside", 0.0068, 0.0205, 0.96,
         [E("motor_jaw_gap_approach_brake", {"torque_Nm": 14.34, "scale_rad": 0.005, "exponent": 2.0})]),
    ]
