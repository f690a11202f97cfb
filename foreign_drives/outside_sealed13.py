"""Outside mechanisms, thirteenth SEALED half (issue 31 part 4, set 13).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed13``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first twelve sets
nor the thirteenth development half (:mod:`outside_dev13`) has, and the suite's rows (seeds 13100+). The split rule is
in :mod:`outside_dev13` (written as one list of fourteen; the even numbers are here; 2, 4, 6, 8, 10 with a memory, 12,
14 memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed13")``), not listed in ``suites.SUITES``.

Visibility, measured as for the development half (4 s against the same spec without the mechanism, same seed; criterion
a2 >= 0.05 m/s^2, a1 >= 0.25): 2 a2 0.0289 -> scaled once x2.60 (0.0700 after); 4 a2 0.156; 6 a2 0.0625; 8 a2 0.128;
10 a1 11.4; 12 a2 0.00379 -> the gain into the rails (1/R) scaled once x19.8 (0.552 after); 14 a2 0.141 (0.140 once marked
non-periodic: its ripple of z stalled the settled start's Newton iteration at a test's own conditions, so it is left to
the run-in; strength unchanged); the others as written.

2. motor load moment x the motor speed through a TUNED TORSIONAL ABSORBER: a ring (inertia J_a) on a rubber spring and
   damper on the motor's free shaft end, tuned to w_a with damping ratio zeta: its angle d relative to the shaft obeys
   d'' = -w_a^2*d - 2*zeta*w_a*d' - dOmega1/dt (at rest at the run-in's start), the motor loaded with
   -J_a*(w_a^2*d + 2*zeta*w_a*d') (a hidden spring-coupled inertia on the motor: the fourth set's flywheel is coupled
   viscously, the sixth set's by friction, the eleventh set's magnetically; the fifth set's absorber is on the mass);
4. wheel torque x the wheel speed through an IMPULSE RELAY: an overspeed switch on the wheel's shaft pulses a latching
   (impulse) relay that switches a brake: each time Omega2 rises past Omega_on (re-armed below Omega_off) the brake
   toggles on or off, -T while on (off at the run-in's start) (a brake that alternates between overspeeds: the tenth
   set's impulse relay reads the spring's extension for the mass);
6. clutch torque x the slip speed through an ON-DELAY: a slip monitor engages an electromagnetic coupling beside the
   jaw once the motor has overrun the wheel by more than s_on for longer than T_on (reset at once below): c*(Omega1 -
   Omega2) while engaged (a damping of the slip switched by its own persistence: the seventh set's on-delay reads the
   mass speed for a rail brake);
8. mass force x the mass speed through a FRICTION-HELD PAYLOAD: a coil of strip (mass m_p) lies on the carriage's bed
   and is carried along by friction up to mu*m_p*g; a larger acceleration lets it slide: the carriage feels the force
   that brings the payload's speed to its own over each 0.2 ms scan, passed whole within +-F_s, else +-F_s (the payload
   slides), reversed in sign (a hidden mass on a friction contact with the carriage: the sixth set's slip hub is on the
   motor, its tow chain a slack, not a friction);
10. a1 sensor x a1's own past through an INTEGRATING ADC WITH HOLD: a1's module integrates its input over blocks of N
    samples (a dual-slope converter) and holds each block's mean through the next block: y over block k = the mean of
    x over block k - 1 (blocks counted from the pre-roll's first sample; x[0] before it) (a decimation with an average
    and a one-block latency; the fifth set's undersampling has no average, the ninth set's smoothing no hold);
12. a2 sensor x a2 itself through an ASYMMETRIC HARD CLIP: a2's amplifier runs from a single supply with its
    zero off centre, so it rails at +R_p and -R_n, R_p != R_n: y = clip(x, -R_n, R_p) (a hard limit, different each
    side: the second set's a1 saturation is soft and symmetric, the eighth set's wrap-around wraps, the eleventh set's
    dual range stitches);
14. mass force x the SPRING EXTENSION, spatially periodic: the spring's cable carries crimped ferrules every lambda
    that pass a spring-loaded detent roller on the carriage's cable guide: F*sin(2*pi*z/lambda + phi), z the spring's
    extension (a force periodic in the extension: the fifth set's rail is periodic in the carriage's position, the
    eighth set's detent in the jaw's angle).
"""
from __future__ import annotations

import math

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory


# 2. motor load moment x the motor speed through a tuned torsional absorber
class MotorTunedTorsionalAbsorber(OutsideForm):
    name = "motor_tuned_torsional_absorber"
    half = "sealed13"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a tuned torsional vibration absorber (a ring of inertia J_a on a rubber spring and damper) on the "
                   "motor's free shaft end: its angle d relative to the shaft obeys d'' = -w_a^2*d - 2*zeta*w_a*d' - "
                   "dOmega1/dt and it drives the shaft with J_a*(w_a^2*d + 2*zeta*w_a*d') (advanced once per 0.2 ms: "
                   "dOmega1/dt the motor speed's change over the last 0.2 ms; at rest at the run-in's start)")
    parameters = (Param("inertia_kgm2", "kg*m^2", (0.0, 0.1), "J_a"),
                  Param("frequency_hz", "Hz", (1.0, 500.0), "w_a/(2*pi)"),
                  Param("damping_ratio", "-", (0.001, 1.0), "zeta"))
    note = "a hidden spring-coupled inertia on the motor: a resonance of its own excited by the shaft's motion"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_RESONATOR, K.XS_OMEGA1, 2.0 * math.pi * p["frequency_hz"], p["damping_ratio"])
        add_term(b, "motor_load_moment", -p["inertia_kgm2"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += -{p['inertia_kgm2']:.6g} kg*m^2 * (w^2*d + 2*{p['damping_ratio']:.6g}*w*d'), "
                f"d'' = -w^2*d - 2*{p['damping_ratio']:.6g}*w*d' - dOmega1/dt, w = 2*pi*{p['frequency_hz']:.6g} Hz "
                "(every 0.2 ms)")


# 4. wheel torque x the wheel speed through an impulse relay
class WheelImpulseRelayBrake(OutsideForm):
    name = "wheel_impulse_relay_brake"
    half = "sealed13"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a brake on the wheel switched by an impulse (latching) relay that an overspeed switch pulses: each "
                   "time Omega2 rises past Omega_on (re-armed once below Omega_off) the brake toggles; -T while on "
                   "(scanned every 0.2 ms; off at the run-in's start, armed if Omega2 < Omega_off there)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("on_above_rad_s", "rad/s", (1.0, 300.0), "Omega_on"),
                  Param("rearm_below_rad_s", "rad/s", (1.0, 300.0), "Omega_off (< Omega_on)"))
    note = "a brake that alternates between overspeeds"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_TOGGLE, K.XS_OMEGA2, p["on_above_rad_s"], p["rearm_below_rad_s"])
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * s, s toggled each time Omega2 rises past "
                f"{p['on_above_rad_s']:.6g} rad/s (re-armed below {p['rearm_below_rad_s']:.6g} rad/s), scanned every "
                "0.2 ms, off at the run-in's start")


# 6. clutch torque x the slip speed through an on-delay
class ClutchSlipMonitoredCoupling(OutsideForm):
    name = "clutch_slip_monitored_coupling"
    half = "sealed13"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a slip monitor engages an electromagnetic coupling beside the jaw once Omega1 - Omega2 has been "
                   "above s_on at every 0.2 ms scan for T_on, and releases it at the first scan at or below: c*(Omega1 "
                   "- Omega2) from the motor to the wheel while engaged")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("slip_on_rad_s", "rad/s", (0.0, 50.0), "s_on"),
                  Param("delay_s", "s", (2e-4, 0.1), "T_on (a multiple of 0.2 ms)"))
    note = "a damping of the slip switched by its own persistence"

    def apply(self, b, p):
        segments(p["delay_s"], f"{self.name}: delay_s")
        set_memory(b, self.name, K.MK_ON_DELAY, K.XS_JAW_SPEED, p["slip_on_rad_s"], p["delay_s"])
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) while engaged: "
                f"engaged once Omega1 - Omega2 > {p['slip_on_rad_s']:.6g} rad/s at every 0.2 ms scan for "
                f"{p['delay_s']:.6g} s, released at the first scan at or below")


# 8. mass force x the mass speed through a friction-held payload
class MassFrictionHeldPayload(OutsideForm):
    name = "mass_friction_held_payload"
    half = "sealed13"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("a coil of strip (mass m_p) lies on the carriage's bed, carried by friction up to F_s: every 0.2 ms "
                   "the bed passes the force m_p*(v - v_p)/dt that brings the payload to the carriage's speed when it "
                   "is within +-F_s (it sticks, v_p = v), else +-F_s (it slides, v_p moving by +-F_s/m_p*dt); the "
                   "carriage feels minus that force over the next 0.2 ms")
    parameters = (Param("payload_kg", "kg", (1e-3, 100.0), "m_p"),
                  Param("friction_force_N", "N", (0.0, 500.0), "F_s = mu*m_p*g"))
    note = "a hidden mass on a friction contact: stuck it adds m_p to the carriage, sliding it passes +-F_s"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_SLIP_HUB, K.XS_MASS_SPEED, p["payload_kg"], p["friction_force_N"])
        add_term(b, "mass_force", -1.0, (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -F_b, F_b = {p['payload_kg']:.6g} kg * (v - v_p)/0.2 ms while within "
                f"+-{p['friction_force_N']:.6g} N (v_p = v), else +-{p['friction_force_N']:.6g} N (v_p += F_b/"
                f"{p['payload_kg']:.6g} kg * 0.2 ms), every 0.2 ms, v the mass speed")


# 10. a1 sensor x a1's own past through an integrating ADC with hold
class A1IntegratingAdcHold(OutsideForm):
    name = "a1_integrating_adc_hold"
    half = "sealed13"
    stage = "sensor"
    order = 1                      # the acquisition module, after the sensing element
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1's module integrates its input over blocks of N samples and holds each block's mean through the "
                   "next block: y over block k = the mean of x over block k - 1 (blocks from the pre-roll's first "
                   "sample; x[0] over the first block)")
    parameters = (Param("block_samples", "samples", (2, 1000), "N", "int"),)
    note = "a decimation by the block's average with a one-block latency"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        x = np.asarray(a, dtype=np.float64)
        n = int(p["block_samples"])
        k = -(-x.size // n)
        padded = np.concatenate([x, np.full(k * n - x.size, x[-1])]) if k * n > x.size else x
        means = padded.reshape(k, n).mean(axis=1)
        held = np.concatenate([[x[0]], means[:-1]])
        return np.repeat(held, n)[:x.size]

    def law(self, p):
        return (f"a1 sensor over block k of {int(p['block_samples'])} samples (at 50 kHz, from the pre-roll's first) = "
                "the mean of a1 over block k - 1 (a1[0] over the first)")


# 12. a2 sensor x a2 itself through an asymmetric hard clip
class A2AsymmetricRailClip(OutsideForm):
    name = "a2_asymmetric_rail_clip"
    half = "sealed13"
    stage = "sensor"
    order = 1                      # the amplifier, after the sensing element
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's single-supply amplifier has its zero off centre and rails at +R_p and -R_n: y = clip(x, -R_n, "
                   "R_p)")
    parameters = (Param("positive_rail_m_s2", "m/s^2", (0.01, 100.0), "R_p"),
                  Param("negative_rail_m_s2", "m/s^2", (0.01, 100.0), "R_n"))
    note = "a hard limit, different on each side"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def read(a, p):
        return np.clip(np.asarray(a, dtype=np.float64), -p["negative_rail_m_s2"], p["positive_rail_m_s2"])

    def law(self, p):
        return (f"a2 sensor = clip(a2, -{p['negative_rail_m_s2']:.6g} m/s^2, {p['positive_rail_m_s2']:.6g} m/s^2)")


# 14. mass force x the spring extension, spatially periodic
class MassCableFerruleDetent(OutsideForm):
    name = "mass_cable_ferrule_detent"
    half = "sealed13"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("the spring's cable carries crimped ferrules every lambda that pass a spring-loaded detent roller on "
                   "the carriage's cable guide: F*sin(2*pi*z/lambda + phi) along x, z the spring's extension")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("pitch_m", "m", (1e-4, 0.5), "lambda"),
                  Param("phase_rad", "rad", (-3.1416, 3.1416), "phi"))
    note = "a force periodic in the spring's extension"

    def apply(self, b, p):
        add_term(b, "mass_force", p["force_N"],
                 (K.XS_SPRING_EXTENSION, K.XF_SIN, 2.0 * math.pi / p["pitch_m"], p["phase_rad"], 0.0),
                 nonperiodic=True)     # left to the run-in: its ripple of z can stall the settled start's Newton

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * sin(2*pi*z/{p['pitch_m']:.6g} m + {p['phase_rad']:.6g} rad), z "
                "the spring's extension")


FORM_CLASSES = (MotorTunedTorsionalAbsorber, WheelImpulseRelayBrake, ClutchSlipMonitoredCoupling,
                MassFrictionHeldPayload, A1IntegratingAdcHold, A2AsymmetricRailClip, MassCableFerruleDetent)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 13100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # a ring tuned to 100 Hz, zeta 0.05; 0.005 kg*m^2 a priori, a2 0.0289: scaled once x2.60
        ("os13_motor_tuned_torsional_absorber", "outside", 0.0061, 0.0285, 0.92,
         [E("motor_tuned_torsional_absorber", {"inertia_kgm2": 0.013, "frequency_hz": 100.0, "damping_ratio": 0.05})]),
        # 3 N*m toggled at each rise past 152 rad/s, re-armed below 150 rad/s (a clean drive's Omega: 147.6-153.7)
        ("os13_wheel_impulse_relay_brake", "outside", 0.0081, 0.0215, 0.94,
         [E("wheel_impulse_relay_brake", {"torque_Nm": 3.0, "on_above_rad_s": 152.0, "rearm_below_rad_s": 150.0})]),
        # 2 N*m*s/rad engaged after 1 ms above 1 rad/s of slip (a clean drive's slip: -5..5 rad/s)
        ("os13_clutch_slip_monitored_coupling", "outside", 0.0054, 0.0345, 0.90,
         [E("clutch_slip_monitored_coupling", {"coefficient_Nm_s_per_rad": 2.0, "slip_on_rad_s": 1.0,
                                               "delay_s": 0.001})]),
        # a 2 kg coil held by 5 N of friction
        ("os13_mass_friction_held_payload", "outside", 0.0071, 0.0245, 0.93,
         [E("mass_friction_held_payload", {"payload_kg": 2.0, "friction_force_N": 5.0})]),
        ("os13_clean_w7.7_eta0.0315_n0.91", "clean", 0.0077, 0.0315, 0.91, []),
        # blocks of 25 samples (0.5 ms)
        ("os13_a1_integrating_adc_hold", "outside", 0.0058, 0.0375, 0.95,
         [E("a1_integrating_adc_hold", {"block_samples": 25})]),
        # rails at +0.8 and -1.2 m/s^2 a priori (a clean drive's a2: -1.61..1.12 m/s^2 for 99 %), a2 0.00379: the
        # gain into the rails (1/R) scaled once x19.8 (rails at +0.0404 and -0.0607 m/s^2)
        ("os13_a2_asymmetric_rail_clip", "outside", 0.0087, 0.0235, 0.91,
         [E("a2_asymmetric_rail_clip", {"positive_rail_m_s2": 0.04045, "negative_rail_m_s2": 0.06067})]),
        # 2 N every 5 mm of extension (a clean drive's z: 0.284-0.322 m)
        ("os13_mass_cable_ferrule_detent", "outside", 0.0066, 0.0205, 0.96,
         [E("mass_cable_ferrule_detent", {"force_N": 2.0, "pitch_m": 0.005, "phase_rad": 0.0})]),
    ]
