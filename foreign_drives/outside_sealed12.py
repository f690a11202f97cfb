"""Outside mechanisms, twelfth SEALED half (issue 31 part 4, set 12).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed12``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first eleven sets
nor the twelfth development half (:mod:`outside_dev12`) has, and the suite's rows (seeds 12100+). The split rule is in
:mod:`outside_dev12` (written as one list of fourteen; the even numbers are here; 2, 6, 8, 12 with a memory, 4, 10, 14
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed12")``), not listed in ``suites.SUITES``.

Visibility, measured as for the development half (4 s against the same spec without the mechanism, same seed; criterion
a2 >= 0.05 m/s^2, a1 >= 0.25): 2 a2 0.0472 -> scaled once x1.59 (0.0729 after); 4 a2 0.0950; 6 a2 0.0181 -> x4.15
(0.0796); 8 a2 0.490; 10 a1 15.2; 12 a2 0.000563 -> k/(1 - k) x133 (0.0750); 14 a2 0.0562; the others as written.

2. motor load moment x the motor speed through a RATE-LIMITED FOLLOWER: a conveyor on the motor's shaft end through a
   viscous coupling; the conveyor's own drive follows the line speed with a ramp limit R (its speed m moves towards
   Omega1 by at most R*dt every 0.2 ms, m = Omega1 at the run-in's start), the motor loaded with c*(Omega1 - m) (a
   load that appears only while the motor's speed changes faster than the follower may: the sixth set's rate limiter
   acts on the spring's extension and the mass);
4. wheel torque x the wheel speed through a STAIRCASE of stages: a multi-stage retarder on the wheel whose speed switch
   adds one stage of T per step of Omega_s above Omega_0: -T*floor((Omega2 - Omega_0)/Omega_s) (0 below Omega_0) (a
   quantised law of the speed itself: the fifth set's stairs act on a sampled tacho on the motor);
6. clutch torque x the slip speed through a DEAD TIME: an electronically slip-controlled eddy-current coupling beside
   the jaw, whose controller reads the two shafts' speeds over a fieldbus: c*(Omega1 - Omega2)(t - T_d), the slip
   sampled every 0.2 ms and applied T_d later (a damping of the slip that acts on its past: the earlier clutch terms
   read the slip, the angle or the contact now);
8. mass force x the mass speed INTEGRATED SINCE EACH STROKE'S START: a return spring on the carriage hooked at each
   stroke's start: its extension is the distance the carriage travelled since the latest pulse's first 0.2 ms scan
   (s = integral of v, reset to 0 there), the carriage pulled back with -k*s (the seventh set integrates the motor
   speed since the stroke for a motor term);
10. a1 sensor x a1 itself through an EVEN-ORDER distortion: a1's piezo element and its preamplifier bend the
    characteristic quadratically: y = x + x^2/a_q (a second harmonic of the signal and a shift of its mean: the
    earlier sensor nonlinearities are odd, bilinear, a dead zone or quantisations);
12. a2 sensor x a2's own last sample through a PRE-EMPHASIS: a2's digital transmitter boosts the high frequencies
    before sending and the receiver never undoes it: y[n] = (x[n] - k*x[n-1])/(1 - k) (a first-order FIR high shelf,
    unity gain at DC);
14. clutch torque x the slip speed GATED by the motor speed: a viscous torsional damper beside the jaw bypassed by a
    centrifugal valve above Omega_v: c*(Omega1 - Omega2)*(1 - S((Omega1 - Omega_v)/w)), S(q) = (1 + tanh(q))/2 (a
    damping switched off by the speed).
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory


# 2. motor load moment x the motor speed through a rate-limited follower
class MotorRateLimitedConveyor(OutsideForm):
    name = "motor_rate_limited_conveyor"
    half = "sealed12"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a conveyor on the motor's shaft end through a viscous coupling, its own drive following the line "
                   "speed with a ramp limit R: m moves towards Omega1 by at most R*0.2 ms every 0.2 ms (m = Omega1 at "
                   "the run-in's start); the motor loaded with c*(Omega1 - m)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("ramp_rad_s2", "rad/s^2", (1e-3, 1e4), "R"))
    note = "a load only while the motor's speed changes faster than the follower may"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RATE_LIMIT, K.XS_OMEGA1, p["ramp_rad_s2"])
        add_term(b, "motor_load_moment", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY_EXCESS, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def follower(omega1_at_scans, p, dt, m0=None):
        """The follower's speed after each scan from the motor speed at the scans' starts (m0 before the first; None:
        Omega1 at the first)."""
        w = np.asarray(omega1_at_scans, dtype=np.float64).tolist()
        m, step, out = (w[0] if m0 is None else m0), p["ramp_rad_s2"] * dt, []
        for x in w:
            m = m + min(max(x - m, -step), step)
            out.append(m)
        return np.array(out)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - m), m moving towards "
                f"Omega1 by at most {p['ramp_rad_s2']:.6g} rad/s^2 * 0.2 ms every 0.2 ms")


# 4. wheel torque x the wheel speed through a staircase of stages
class WheelStagedRetarder(OutsideForm):
    name = "wheel_staged_retarder"
    half = "sealed12"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a multi-stage retarder on the wheel whose speed switch adds one stage of T per step Omega_s above "
                   "Omega_0: -T*floor((Omega2 - Omega_0)/Omega_s) above Omega_0, 0 below")
    parameters = (Param("stage_torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("first_speed_rad_s", "rad/s", (0.0, 300.0), "Omega_0"),
                  Param("step_rad_s", "rad/s", (0.01, 100.0), "Omega_s"))
    note = "a quantised law of the wheel speed itself"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["stage_torque_Nm"] / p["step_rad_s"],
                 (K.XS_OMEGA2, K.XF_STAIRS, p["step_rad_s"], p["first_speed_rad_s"], 0.0),
                 nonperiodic=True)     # its jumps stall the settled start's Newton iteration: left to the run-in

    @staticmethod
    def torque(omega2, p):
        w = np.asarray(omega2, dtype=np.float64)
        n = np.floor((w - p["first_speed_rad_s"]) / p["step_rad_s"])
        return np.where(w > p["first_speed_rad_s"], -p["stage_torque_Nm"] * n, 0.0)

    def law(self, p):
        return (f"wheel torque += -{p['stage_torque_Nm']:.6g} N*m * floor((Omega2 - {p['first_speed_rad_s']:.6g} rad/s)/"
                f"{p['step_rad_s']:.6g} rad/s) above {p['first_speed_rad_s']:.6g} rad/s, else 0")


# 6. clutch torque x the slip speed through a dead time
class ClutchFieldbusSlipCoupling(OutsideForm):
    name = "clutch_fieldbus_slip_coupling"
    half = "sealed12"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an electronically slip-controlled eddy-current coupling beside the jaw, its controller reading the "
                   "shafts' speeds over a fieldbus: c*(Omega1 - Omega2)(t - T_d), the slip sampled every 0.2 ms and "
                   "applied T_d later (the slip at the run-in's start before then)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("dead_time_s", "s", (2e-4, 0.0126), "T_d"))
    note = "a damping of the slip that acts on its past"

    def apply(self, b, p):
        d = segments(p["dead_time_s"], f"{self.name}: dead_time_s")
        set_memory(b, self.name, K.MK_DELAY, K.XS_JAW_SPEED, 1.0, float(d))
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) sampled every "
                f"0.2 ms, {p['dead_time_s']:.6g} s earlier")


# 8. mass force x the mass speed integrated since each stroke's start
class MassStrokeHookedReturnSpring(OutsideForm):
    name = "mass_stroke_hooked_return_spring"
    half = "sealed12"
    balance = "mass_force"
    depends_on = ("mass_speed", "load_pulse")
    description = ("a return spring on the carriage hooked at each stroke's start: its extension s is the distance "
                   "travelled since the latest pulse's first 0.2 ms scan (s += v*0.2 ms every scan, s = 0 at that "
                   "scan and at the run-in's start); the carriage pulled back with -k*s")
    parameters = (Param("stiffness_N_per_m", "N/m", (0.0, 1000.0), "k"),)
    note = "a spring whose anchor is re-set by every stroke to the carriage's place"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_SINCE_STROKE, K.XS_MASS_SPEED, 0.0)
        add_term(b, "mass_force", -p["stiffness_N_per_m"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['stiffness_N_per_m']:.6g} N/m * s, s the distance travelled since the latest load "
                "pulse's first 0.2 ms scan")


# 10. a1 sensor x a1 through an even-order distortion
class A1QuadraticDistortion(OutsideForm):
    name = "a1_quadratic_distortion"
    half = "sealed12"
    stage = "sensor"
    order = 0                      # the sensing element itself
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = "a1's piezo element and preamplifier bend the characteristic quadratically: y = x + x^2/a_q"
    parameters = (Param("quadratic_scale_m_s2", "m/s^2", (1.0, 1e5), "a_q"),)
    note = "an even-order nonlinearity: a second harmonic and a shift of the mean"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        x = np.asarray(a, dtype=np.float64)
        return x + x * x / p["quadratic_scale_m_s2"]

    def law(self, p):
        return f"a1 sensor = a1 + a1^2/{p['quadratic_scale_m_s2']:.6g} m/s^2"


# 12. a2 sensor x a2's last sample through a pre-emphasis
class A2TransmitterPreEmphasis(OutsideForm):
    name = "a2_transmitter_pre_emphasis"
    half = "sealed12"
    stage = "sensor"
    order = 1                      # the transmitter, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's digital transmitter boosts the high frequencies and the receiver never undoes it: y[n] = "
                   "(x[n] - k*x[n-1])/(1 - k) at the recorder's rate (x[-1] = x[0])")
    parameters = (Param("coefficient", "-", (0.0, 0.999), "k"),)
    note = "a first-order FIR high shelf, unity gain at DC"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def read(a, p):
        x = np.asarray(a, dtype=np.float64)
        k = p["coefficient"]
        return (x - k * np.concatenate([x[:1], x[:-1]])) / (1.0 - k)

    def law(self, p):
        return f"a2 sensor = (a2[n] - {p['coefficient']:.6g}*a2[n-1])/(1 - {p['coefficient']:.6g}) at 50 kHz"


# 14. clutch torque x the slip speed gated by the motor speed
class ClutchCentrifugallyBypassedDamper(OutsideForm):
    name = "clutch_centrifugally_bypassed_damper"
    half = "sealed12"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a viscous torsional damper beside the jaw that a centrifugal valve bypasses above Omega_v: "
                   "c*(Omega1 - Omega2)*(1 - S((Omega1 - Omega_v)/w)), S(q) = (1 + tanh(q))/2")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("valve_speed_rad_s", "rad/s", (0.0, 300.0), "Omega_v"),
                  Param("valve_width_rad_s", "rad/s", (0.01, 50.0), "w"))
    note = "a damping switched off by the speed"

    def apply(self, b, p):
        c, wv, w = p["coefficient_Nm_s_per_rad"], p["valve_speed_rad_s"], p["valve_width_rad_s"]
        add_term(b, "clutch_torque", c, (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0))
        add_term(b, "clutch_torque", -c, (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_OMEGA1, K.XF_SIGMOID, w, wv, 0.0))

    @staticmethod
    def torque(omega1, omega2, p):
        w1, w2 = np.asarray(omega1, dtype=np.float64), np.asarray(omega2, dtype=np.float64)
        s = 0.5 * (1.0 + np.tanh((w1 - p["valve_speed_rad_s"]) / p["valve_width_rad_s"]))
        return p["coefficient_Nm_s_per_rad"] * (w1 - w2) * (1.0 - s)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) * (1 - S((Omega1 - "
                f"{p['valve_speed_rad_s']:.6g} rad/s)/{p['valve_width_rad_s']:.6g} rad/s)), S(q) = (1 + tanh(q))/2")


FORM_CLASSES = (MotorRateLimitedConveyor, WheelStagedRetarder, ClutchFieldbusSlipCoupling,
                MassStrokeHookedReturnSpring, A1QuadraticDistortion, A2TransmitterPreEmphasis,
                ClutchCentrifugallyBypassedDamper)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 12100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # behind a 50 rad/s^2 ramp limit (a clean drive's Omega: 147.6-153.7 rad/s); 1 N*m*s/rad a priori, a2 0.0472:
        # scaled once x1.59
        ("os12_motor_rate_limited_conveyor", "outside", 0.0062, 0.0280, 0.91,
         [E("motor_rate_limited_conveyor", {"coefficient_Nm_s_per_rad": 1.59, "ramp_rad_s2": 50.0})]),
        # 1 N*m per 2 rad/s above 146 rad/s
        ("os12_wheel_staged_retarder", "outside", 0.0082, 0.0210, 0.93,
         [E("wheel_staged_retarder", {"stage_torque_Nm": 1.0, "first_speed_rad_s": 146.0, "step_rad_s": 2.0})]),
        # 10 ms late; 1 N*m*s/rad a priori, a2 0.0181: scaled once x4.15
        ("os12_clutch_fieldbus_slip_coupling", "outside", 0.0053, 0.0340, 0.91,
         [E("clutch_fieldbus_slip_coupling", {"coefficient_Nm_s_per_rad": 4.15, "dead_time_s": 0.01})]),
        # 3 N/m (a stroke of 60 ms: about 1.4 m travelled)
        ("os12_mass_stroke_hooked_return_spring", "outside", 0.0070, 0.0240, 0.94,
         [E("mass_stroke_hooked_return_spring", {"stiffness_N_per_m": 3.0})]),
        ("os12_clean_w7.6_eta0.0320_n0.92", "clean", 0.0076, 0.0320, 0.92, []),
        # a 10 % second-order term at 10 m/s^2
        ("os12_a1_quadratic_distortion", "outside", 0.0059, 0.0380, 0.96,
         [E("a1_quadratic_distortion", {"quadratic_scale_m_s2": 100.0})]),
        # k = 0.5 (y - x = k/(1 - k)*(x[n] - x[n-1]), k/(1 - k) = 1) a priori, a2 0.000563: k/(1 - k) scaled once x133
        # (k = 133/134)
        ("os12_a2_transmitter_pre_emphasis", "outside", 0.0088, 0.0230, 0.90,
         [E("a2_transmitter_pre_emphasis", {"coefficient": 0.99255})]),
        # 2 N*m*s/rad bypassed above 150 rad/s over 1 rad/s
        ("os12_clutch_centrifugally_bypassed_damper", "outside", 0.0065, 0.0200, 0.95,
         [E("clutch_centrifugally_bypassed_damper", {"coefficient_Nm_s_per_rad": 2.0, "valve_speed_rad_s": 150.0,
                                                     "valve_width_rad_s": 1.0})]),
    ]
