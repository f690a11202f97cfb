"""Outside mechanisms, sixth SEALED half (issue 31 part 4, set 6).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed6``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first five sets
nor the sixth development half (:mod:`outside_dev6`) has, and the suite's rows (seeds 8500+). The split rule is in
:mod:`outside_dev6` (written as one list of fourteen; the even numbers are here). Written before any diagnose,
analyze or proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed6")``), not listed in
``suites.SUITES``.

2. motor load moment x the load pulse times a STROKE-TO-STROKE random variation: the blanks of a batch vary in
   thickness, so each stroke's forming load differs from the last: pulse*T*u_k, u_k a pseudo-random number in [-1, 1]
   drawn from the stroke's number k (a cycle-to-cycle variation locked to nothing but the count);
4. wheel torque x the wheel speed through a PI CONTROLLER with a SATURATED actuator: a web-speed controller brakes the
   wheel with an eddy-current brake, u = K_p*e + I, e = Omega2 - Omega_ref, I' = K_i*e, u limited to [0, T_max] and I
   frozen while u is at a limit and e pushes it further (clamping anti-windup); -u on the wheel (scanned every 0.2 ms);
6. clutch torque x the jaw's angle difference through a DAHL friction element: a preloaded friction ring (an O-ring
   damper) between the jaw halves; for small relative turns it is a spring, beyond it slides at T_f, with a memory of
   where it last slid: T_f*s, s -> sign(dD) - (sign(dD) - s)*exp(-|dD|/theta_c) for each change dD of the jaw's angle
   difference (rate-independent, smooth);
8. mass force x the spring extension through a RATE LIMITER: a pneumatic balancer on the carriage whose pressure
   regulator follows the spring's extension, K*(m - z_ref) towards the rim like a second spring, m -> z but moving at
   most R (m/s) (a proportional valve that slews: the force lags only where the extension changes fast; first written
   with the sign of a force against the spring, -K*(m - z_ref): with K above the spring's stiffness that pushed the
   carriage away from its equilibrium -- changed after its first visibility simulation, before any diagnose, and its
   visibility simulated once more at the same K);
10. a1 sensor x a1 at RANDOM LATENCIES: a1's rotating telemetry sends packets whose latency varies; the recorder stamps
    them on arrival, so each recorded a1 sample is the signal at t - d_n, d_n pseudo-random in [0, D] for each sample
    (linear interpolation): a timing jitter;
12. motor load moment x the motor speed through a HIDDEN INTEGRATOR and an UNLOADER: a pump on the motor shaft charges
    the press's accumulator; its pressure p integrates the pump's flow (proportional to Omega1 while loading) less the
    press's use at each stroke; an unloader valve switches the pump off (idling) when p rises above p_high and back
    on below p_low; while on it loads the motor with D*p (a limit cycle of its own period);
14. mass force x the mass speed through a SLACK TOW CHAIN: the carriage tows a trailer cart by a chain with slack L;
    the cart's rolling resistance slows it until the chain snatches taut (a stiff, damped one-sided contact), pulls
    it up to speed and goes slack again: the carriage feels the chain's snatch loads only.

Visibility, measured (as in :mod:`outside_dev6`: one simulation of each row, 4 s, against the same spec without the
mechanism, same seed): 2 a2 0.109; 4 a2 0.135; 6 a2 0.0525; 8 a2 0.309 with the first sign, 0.0734 with the final
one (same K); 10 a1 5.38; 12 a2 0.290; 14 a2 0.0954. None was scaled.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 2. motor load moment x the pulse times a stroke-to-stroke random variation
class MotorBatchBlankThickness(OutsideForm):
    name = "motor_batch_blank_thickness"
    half = "sealed6"
    balance = "motor_load_moment"
    depends_on = ("load_pulse",)
    description = ("the blanks of a batch vary in thickness, so each stroke's forming load differs: pulse*T*u_k, u_k in "
                   "[-1, 1) a pseudo-random number of the stroke's number k and a seed s (kernel.XF_HASH: q = 7919*k^2 + "
                   "40503*k + 104729*s, u = 2*(q mod 65521)/65521 - 1)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("seed", "-", (0, 1000), "s", "int"))

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_PULSE_COUNT, K.XF_HASH, float(p["seed"]), 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def u(k, seed):
        k = np.floor(np.asarray(k, dtype=np.float64))
        q = k * k * 7919.0 + k * 40503.0 + seed * 104729.0
        return 2.0 * np.mod(q, 65521.0) / 65521.0 - 1.0

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * pulse * u_k, u_k = 2*((7919*k^2 + 40503*k + "
                f"104729*{int(p['seed'])}) mod 65521)/65521 - 1, k the stroke's number")


# 4. wheel torque x the wheel speed through a PI controller with a saturated actuator
class WheelPiSpeedBrake(OutsideForm):
    name = "wheel_pi_speed_brake"
    half = "sealed6"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a web-speed controller brakes the wheel with an eddy-current brake: u = K_p*e + I, e = Omega2 - "
                   "Omega_ref, I += K_i*e*dt unless u is at a limit and e pushes it further (clamping anti-windup), u "
                   "limited to [0, T_max]; -u on the wheel (scanned every 0.2 ms from the run-in's start, I = 0 there)")
    parameters = (Param("proportional_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "K_p"),
                  Param("integral_Nm_per_rad", "N*m/rad", (0.0, 500.0), "K_i"),
                  Param("max_torque_Nm", "N*m", (0.0, 50.0), "T_max"),
                  Param("reference_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_ref: the web speed it holds"))

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PI_SAT, K.XS_OMEGA2, p["proportional_Nms_per_rad"], p["integral_Nm_per_rad"],
                   p["max_torque_Nm"])
        set_extra(b, p["reference_speed_rad_s"])
        add_term(b, "wheel_torque", -1.0, (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -u, u = clip({p['proportional_Nms_per_rad']:.6g}*e + I, 0, {p['max_torque_Nm']:.6g} "
                f"N*m), e = Omega2 - {p['reference_speed_rad_s']:.6g} rad/s, I += {p['integral_Nm_per_rad']:.6g}*e*dt "
                "unless saturated further (every 0.2 ms)")


# 6. clutch torque x the jaw's angle difference through a Dahl friction element
class ClutchDahlFrictionRing(OutsideForm):
    name = "clutch_dahl_friction_ring"
    half = "sealed6"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("a preloaded friction ring between the jaw halves (Dahl's pre-sliding friction): T_f*s from the motor "
                   "to the wheel, in the gap too; s -> sign(dD) - (sign(dD) - s)*exp(-|dD|/theta_c) for each change dD "
                   "of the jaw's angle difference D over a 0.2 ms scan (s = 0 at the run-in's start)")
    parameters = (Param("friction_torque_Nm", "N*m", (0.0, 50.0), "T_f"),
                  Param("presliding_rad", "rad", (1e-5, 0.1), "theta_c"))

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_DAHL, K.XS_JAW_ANGLE, p["presliding_rad"])
        add_term(b, "clutch_torque", p["friction_torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['friction_torque_Nm']:.6g} N*m * s, s -> sign(dD) - (sign(dD) - s)*exp(-|dD|/"
                f"{p['presliding_rad']:.6g} rad) every 0.2 ms, D the jaw's angle difference")


# 8. mass force x the spring extension through a rate limiter
class MassRateLimitedBalancer(OutsideForm):
    name = "mass_rate_limited_balancer"
    half = "sealed6"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("a pneumatic balancer on the carriage, beside the spring, whose pressure regulator follows the "
                   "spring's extension through a valve that slews at most R: it pulls the carriage towards the rim like "
                   "a second spring, K*(m - z_ref), m moving towards z by at most R*0.2 ms per 0.2 ms scan (m = z at the "
                   "run-in's start)")
    parameters = (Param("gain_N_per_m", "N/m", (0.0, 5000.0), "K"),
                  Param("rate_m_s", "m/s", (1e-4, 10.0), "R"),
                  Param("reference_extension_m", "m", (0.0, 1.0), "z_ref"))

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RATE_LIMIT, K.XS_SPRING_EXTENSION, p["rate_m_s"])
        add_term(b, "mass_force", p["gain_N_per_m"],
                 (K.XS_MEMORY, K.XF_CLIP, 1e9, -p["reference_extension_m"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['gain_N_per_m']:.6g} N/m * (m - {p['reference_extension_m']:.6g} m), m -> z at most "
                f"{p['rate_m_s']:.6g} m/s (every 0.2 ms), z the spring extension")


# 10. a1 sensor x a1 at random latencies
class A1TelemetryJitter(OutsideForm):
    name = "a1_telemetry_jitter"
    half = "sealed6"
    stage = "sensor"
    order = 1                      # the telemetry, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1's rotating telemetry delivers its samples with a varying latency and the recorder stamps them on "
                   "arrival: each recorded a1 sample is the signal at t - D*u_n, u_n uniform in [0, 1) from numpy's "
                   "default_rng(seed), one per sample from the pre-roll's first (linear interpolation)")
    parameters = (Param("max_latency_s", "s", (0.0, 0.01), "D"),
                  Param("seed", "-", (0, 1000), "the generator's seed", "int"))

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], t, p)

    @staticmethod
    def read(a, t, p):
        a, t = np.asarray(a, dtype=np.float64), np.asarray(t, dtype=np.float64)
        d = p["max_latency_s"] * np.random.default_rng(int(p["seed"])).random(a.size)
        return np.interp(t - d, t, a)

    def law(self, p):
        return f"a1 sensor = a1(t - {p['max_latency_s']:.6g} s * u_n), u_n uniform in [0, 1) per sample"


# 12. motor load moment x the motor speed through a hidden integrator and an unloader
class MotorAccumulatorUnloader(OutsideForm):
    name = "motor_accumulator_unloader"
    half = "sealed6"
    balance = "motor_load_moment"
    depends_on = ("motor_speed", "load_pulse")
    description = ("a pump on the motor shaft charges the press's accumulator: its pressure p [bar] integrates "
                   "on*q*Omega1 - c*pulse (p >= 0); an unloader switches the pump off when p rises above p_high and on "
                   "when it falls below p_low; while on it loads the motor with D*p (scanned every 0.2 ms from the "
                   "run-in's start, p = p_low and on there)")
    parameters = (Param("displacement_Nm_per_bar", "N*m/bar", (0.0, 1.0), "D"),
                  Param("fill_bar_per_rad", "bar/rad", (0.0, 10.0), "q"),
                  Param("use_bar_per_s", "bar/s", (0.0, 1000.0), "c: the press's use while a pulse is on"),
                  Param("low_bar", "bar", (0.0, 400.0), "p_low"),
                  Param("high_bar", "bar", (0.0, 400.0), "p_high"))

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_UNLOADER, K.XS_OMEGA1, p["fill_bar_per_rad"], p["use_bar_per_s"], p["high_bar"])
        set_extra(b, p["low_bar"])
        add_term(b, "motor_load_moment", p["displacement_Nm_per_bar"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['displacement_Nm_per_bar']:.6g} N*m/bar * on * p, p' = on*"
                f"{p['fill_bar_per_rad']:.6g}*Omega1 - {p['use_bar_per_s']:.6g}*pulse bar/s, on -> 0 above "
                f"{p['high_bar']:.6g} bar, -> 1 below {p['low_bar']:.6g} bar (every 0.2 ms)")


# 14. mass force x the mass speed through a slack tow chain
class MassSlackTowChain(OutsideForm):
    name = "mass_slack_tow_chain"
    half = "sealed6"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("the carriage tows a cart of mass m_c by a chain with slack L: the cart's position d behind its taut "
                   "point obeys d'' = c_a - lambda*(v + d') - dv/dt, the chain's pull c_a = -w_c^2*(d + L) - 2*zeta*w_c*d' "
                   "while d < -L (never pushing), and the carriage feels -m_c*c_a (kernel MK_RATTLE one-sided, eight "
                   "steps per 0.2 ms; from rest on the taut chain)")
    parameters = (Param("cart_mass_kg", "kg", (0.0, 20.0), "m_c"),
                  Param("slack_m", "m", (1e-4, 0.5), "L"),
                  Param("chain_frequency_hz", "Hz", (1.0, 1000.0), "w_c/(2*pi)"),
                  Param("chain_damping_ratio", "-", (0.0, 1.0), "zeta"),
                  Param("drag_per_s", "1/s", (0.0, 10.0), "lambda: the cart's rolling drag over m_c"))

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RATTLE, K.XS_MASS_SPEED, p["slack_m"], 2.0 * np.pi * p["chain_frequency_hz"],
                   p["drag_per_s"])
        set_extra(b, p["chain_damping_ratio"], 1.0)
        add_term(b, "mass_force", p["cart_mass_kg"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['cart_mass_kg']:.6g} kg * c_a, c_a = -w^2*(d + {p['slack_m']:.6g}) - "
                f"2*{p['chain_damping_ratio']:.6g}*w*d' while d < -{p['slack_m']:.6g} m (never pushing), d'' = c_a - "
                f"{p['drag_per_s']:.6g}/s*(v + d') - dv/dt, w = 2*pi*{p['chain_frequency_hz']:.6g} Hz (every 0.2 ms)")


FORM_CLASSES = (MotorBatchBlankThickness, WheelPiSpeedBrake, ClutchDahlFrictionRing, MassRateLimitedBalancer,
                A1TelemetryJitter, MotorAccumulatorUnloader, MassSlackTowChain)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 8500+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        ("os6_motor_batch_blank_thickness", "outside", 0.0073, 0.033, 0.91,
         [E("motor_batch_blank_thickness", {"torque_Nm": 4.0, "seed": 17})]),
        ("os6_wheel_pi_speed_brake", "outside", 0.0056, 0.0215, 0.95,
         [E("wheel_pi_speed_brake", {"proportional_Nms_per_rad": 1.0, "integral_Nm_per_rad": 5.0, "max_torque_Nm": 6.0,
                                     "reference_speed_rad_s": 150.5})]),
        ("os6_clutch_dahl_friction_ring", "outside", 0.0084, 0.027, 0.90,
         [E("clutch_dahl_friction_ring", {"friction_torque_Nm": 1.5, "presliding_rad": 0.003})]),
        ("os6_mass_rate_limited_balancer", "outside", 0.0049, 0.043, 0.93,
         [E("mass_rate_limited_balancer", {"gain_N_per_m": 300.0, "rate_m_s": 0.05, "reference_extension_m": 0.30})]),
        ("os6_clean_w6.4_eta0.0235_n0.92", "clean", 0.0064, 0.0235, 0.92, []),
        ("os6_a1_telemetry_jitter", "outside", 0.0093, 0.0175, 0.94,
         [E("a1_telemetry_jitter", {"max_latency_s": 1e-4, "seed": 5})]),
        ("os6_motor_accumulator_unloader", "outside", 0.0067, 0.0375, 0.97,
         [E("motor_accumulator_unloader", {"displacement_Nm_per_bar": 0.027, "fill_bar_per_rad": 0.265,
                                           "use_bar_per_s": 100.0, "low_bar": 100.0, "high_bar": 120.0})]),
        ("os6_mass_slack_tow_chain", "outside", 0.0041, 0.029, 0.89,
         [E("mass_slack_tow_chain", {"cart_mass_kg": 2.0, "slack_m": 0.005, "chain_frequency_hz": 30.0,
                                     "chain_damping_ratio": 0.2, "drag_per_s": 0.044})]),
    ]
