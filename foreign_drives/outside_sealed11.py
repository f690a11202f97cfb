"""Outside mechanisms, eleventh SEALED half (issue 31 part 4, set 11).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed11``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first ten sets
nor the eleventh development half (:mod:`outside_dev11`) has, and the suite's rows (seeds 11100+). The split rule is in
:mod:`outside_dev11` (written as one list of fourteen; the even numbers are here; 2, 6, 8, 14 with a memory, 4, 10, 12
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed11")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a MAGNETIC COUPLING to a HIDDEN ROTOR (a periodic, pole-slipping
   spring): an auxiliary pump hangs on the motor's shaft end behind a permanent-magnet (canned) coupling of n pole pairs
   and pull-out torque T_m; its rotor (inertia J_r, viscous load c_r) follows through the magnets' torque
   T_m*sin(n*phi), phi the angle of the motor's half ahead of the rotor: phi' = Omega1 - w_r, J_r*w_r' = T_m*sin(n*phi) -
   c_r*w_r, the motor loaded with T_m*sin(n*phi) (advanced every 0.2 ms; w_r = Omega1 and n*phi = asin(c_r*Omega1/T_m)
   at the run-in's start) (a hidden degree of freedom through a sinusoidal spring that slips a pole when overloaded:
   the fourth set's belts are a viscous lag, the sixth set's hub a dry friction, the fifth set's absorber a linear
   spring);
4. wheel torque x the jaw's CONTACT TORQUE beyond a PRELOAD: a torque-sensing (ball-ramp) brake in the wheel's hub; the
   torque the jaw passes on its drive face pushes balls up one-way ramps against a preload spring and presses a brake
   pack on the wheel: -k*max(0, T_c - T_0), T_c the contact torque (+ motor to wheel) (a brake set by the transmitted
   torque: the third set's thrust bearing puts |T_c| on the motor, without a preload);
6. clutch torque x the slip speed TIMES a FILL LEVEL that ramps with the pulse: a fill-controlled fluid coupling beside
   the jaw; the press's valve fills it at a fixed rate while the pulse is on and it drains at another rate otherwise:
   c*f*(Omega1 - Omega2), f += dt/T_fill while the pulse is on, f -= dt/T_drain otherwise, f clamped to [0, 1] (every
   0.2 ms, f = 0 at the run-in's start) (a clamped integrator: straight ramps between hard limits, not an exponential
   lag);
8. mass force x the mass speed through RATE-AND-STATE FRICTION: the carriage's polymer slideway follows the Dieterich-
   Ruina law: -(a*ln(v/v_0) + b*ln(v_0*theta/D_c)), theta' = 1 - v*theta/D_c (the contact's age: over each 0.2 ms scan
   theta -> D_c/v + (theta - D_c/v)*exp(-v*dt/D_c); theta = D_c/v at the run-in's start) (a friction with a state
   that evolves over a slip distance D_c: a speed step gives a direct jump a*ln, then a relaxation to (a - b)*ln over
   D_c of travel: neither a viscous, a Coulomb, nor a lag of the speed);
10. a1 sensor x a1 through RANDOM BIT ERRORS: a1's rotating telemetry has no error check; a sample's 16-bit two's-
    complement code c = clip(round(32767*a/R), -32768, 32767) has, at a rate p, one bit b (of 16, at random) flipped: y
    = a + (c' - c)*R/32767 for a corrupted sample, y = a otherwise (u_n, b_n from numpy's default_rng(seed).random((N,
    2)) row n, n the sample from the pre-roll's first; corrupted where u_n < p, b = floor(16*v_n)) (sparse impulsive
    errors whose size is a power of two of the code step: not a noise, not a quantiser);
12. a2 sensor x a2 through a STITCHED DUAL-RANGE: a2's module has two ADCs, a fine one up to R and a coarse one above,
    stitched with a gain mismatch g: y = a for |a| <= R, sign(a)*(R + (1 + g)*(|a| - R)) beyond (a kink in the gain at
    +-R: not a saturation, not a range switch with a memory);
14. clutch torque x the jaw's angle difference through a BISTABLE (over-centre) TOGGLE SPRING: a snap spring between the
    jaw halves flips over its centre when the angle difference D passes +d (towards the drive face) and back when it
    passes -d (towards the far face), and pushes the halves towards the face they last went past: T*(2*s - 1), s -> 1
    when D > d, s -> 0 when D < -d (scanned every 0.2 ms; s = 0 at the run-in's start) (a two-state, rate-independent
    hysteresis of the relative angle with a jump: the sixth set's Dahl ring is smooth, the seventh set's magnets
    memoryless).

Visibility, measured as for the development half (4 s, same spec without the mechanism, same seed; criterion a2 >=
0.05 m/s^2, a1 >= 0.25): 2 a2 0.0706; 4 a2 0.0456, scaled once x1.65 -> 0.0823; 6 a2 0.0711; 8 a2 0.0145, scaled once
(a and b both) x5.16 -> 0.0711; 10 a1 0.692; 12 a2 0.0848; 14 a2 0.107.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term, set_relay
from .outside_dev import _plugin
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 2. motor load moment x the motor speed through a magnetic coupling to a hidden rotor
class MotorMagneticCouplingRotor(OutsideForm):
    name = "motor_magnetic_coupling_rotor"
    half = "sealed11"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("an auxiliary pump on the motor's shaft end behind a permanent-magnet coupling of n pole pairs and "
                   "pull-out torque T_m; its rotor (inertia J_r, viscous load c_r) follows through T_m*sin(n*phi): phi' = "
                   "Omega1 - w_r, J_r*w_r' = T_m*sin(n*phi) - c_r*w_r, the motor loaded with T_m*sin(n*phi) (every 0.2 "
                   "ms; w_r = Omega1, n*phi = asin(c_r*Omega1/T_m) at the run-in's start)")
    parameters = (Param("pull_out_torque_Nm", "N*m", (0.0, 50.0), "T_m"),
                  Param("pole_pairs", "-", (1, 12), "n", "int"),
                  Param("rotor_inertia_kg_m2", "kg*m^2", (1e-4, 1.0), "J_r"),
                  Param("rotor_load_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c_r"))
    note = "a hidden degree of freedom through a sinusoidal spring that slips a pole when overloaded"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_MAG_COUPLING, K.XS_OMEGA1, p["pull_out_torque_Nm"], float(int(p["pole_pairs"])),
                   p["rotor_inertia_kg_m2"])
        set_extra(b, p["rotor_load_Nm_s_per_rad"])
        add_term(b, "motor_load_moment", 1.0, (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def coupled(omega1_at_scans, p, dt, phi=None, w_r=None):
        """(load, phi, w_r) after each scan from the motor speed at the scans' starts; ``phi``, ``w_r``: the state at
        the first scan (None: the run-in's start)."""
        w = np.asarray(omega1_at_scans, dtype=np.float64).tolist()
        tm, n, j, c = p["pull_out_torque_Nm"], float(int(p["pole_pairs"])), p["rotor_inertia_kg_m2"], \
            p["rotor_load_Nm_s_per_rad"]
        if phi is None:
            phi = float(np.arcsin(np.clip(c * w[0] / tm, -1.0, 1.0))) / n if tm > 0 else 0.0
        wr = w[0] if w_r is None else w_r
        out = np.empty((3, len(w)))
        for i, x in enumerate(w):
            if i:
                wr += dt * (tm * np.sin(n * phi) - c * wr) / j
                phi += dt * (x - wr)
            out[:, i] = tm * np.sin(n * phi), phi, wr
        return out

    def law(self, p):
        tm, n = p["pull_out_torque_Nm"], int(p["pole_pairs"])
        return (f"motor load moment += {tm:.6g} N*m * sin({n}*phi), phi' = Omega1 - w_r, {p['rotor_inertia_kg_m2']:.6g} "
                f"kg*m^2 * w_r' = {tm:.6g} N*m * sin({n}*phi) - {p['rotor_load_Nm_s_per_rad']:.6g} N*m*s/rad * w_r "
                "(every 0.2 ms)")


# 4. wheel torque x the jaw's contact torque beyond a preload
class WheelTorqueSensingRampBrake(OutsideForm):
    name = "wheel_torque_sensing_ramp_brake"
    half = "sealed11"
    balance = "wheel_torque"
    depends_on = ("clutch_penetration",)
    description = ("a torque-sensing (ball-ramp) brake in the wheel's hub: the torque the jaw passes on its drive face "
                   "pushes balls up one-way ramps against a preload and presses a brake pack on the wheel: -k*max(0, "
                   "T_c - T_0), T_c the jaw's contact torque (+ motor to wheel)")
    parameters = (Param("gain", "N*m/(N*m)", (0.0, 2.0), "k"), Param("preload_Nm", "N*m", (0.0, 200.0), "T_0"))
    note = "a brake set by the transmitted torque beyond a preload"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["gain"], (K.XS_CONTACT_TORQUE, K.XF_EXCESS_POWER, p["preload_Nm"], 1.0, 0.0))

    def law(self, p):
        return (f"wheel torque += -{p['gain']:.6g} * max(0, T_c - {p['preload_Nm']:.6g} N*m), T_c the jaw's contact "
                "torque")

    def plugin(self, p):
        return _plugin("WheelTorqueSensingRampBrake", self.name, "wheel_torque_Nm", self.description, [
            ("gain", "N*m/(N*m)", (0.0, 2.0), "k"), ("preload_Nm", "N*m", (0.0, 200.0), "T_0")],
            "contact_torque_Nm, gain, preload_Nm", "-gain * fmax(0.0, contact_torque_Nm - preload_Nm)", "fmax")


# 6. clutch torque x the slip speed times a fill level that ramps with the pulse
class ClutchFillControlledCoupling(OutsideForm):
    name = "clutch_fill_controlled_coupling"
    half = "sealed11"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed", "load_pulse")
    description = ("a fill-controlled fluid coupling beside the jaw: c*f*(Omega1 - Omega2) from the motor to the wheel, "
                   "f the fill level: f += dt/T_fill while the pulse is on, f -= dt/T_drain otherwise, clamped to [0, 1] "
                   "(every 0.2 ms, f = 0 at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("fill_time_s", "s", (1e-3, 10.0), "T_fill"),
                  Param("drain_time_s", "s", (1e-3, 10.0), "T_drain"))
    note = "a clamped integrator: straight ramps between hard limits, not an exponential lag"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_FILL, K.XS_PULSE, p["fill_time_s"], p["drain_time_s"])
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * f * (Omega1 - Omega2), f += dt/"
                f"{p['fill_time_s']:.6g} s while the pulse is on, -= dt/{p['drain_time_s']:.6g} s otherwise, in [0, 1]")


# 8. mass force x the mass speed through rate-and-state friction
class MassRateStateSlideway(OutsideForm):
    name = "mass_rate_state_slideway"
    half = "sealed11"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("the carriage's polymer slideway follows the Dieterich-Ruina law: -(a*ln(v/v_0) + b*ln(v_0*theta/"
                   "D_c)), theta' = 1 - v*theta/D_c (over each 0.2 ms scan theta -> D_c/v + (theta - D_c/v)*exp(-v*dt/"
                   "D_c); theta = D_c/v at the run-in's start)")
    parameters = (Param("direct_N", "N", (0.0, 5000.0), "a = N*A"),
                  Param("evolution_N", "N", (0.0, 5000.0), "b = N*B"),
                  Param("slip_distance_m", "m", (1e-3, 100.0), "D_c"),
                  Param("reference_speed_m_s", "m/s", (1.0, 50.0), "v_0"))
    note = "a friction with a state evolving over a slip distance: a direct jump, then a relaxation"

    def apply(self, b, p):
        v0, dc = p["reference_speed_m_s"], p["slip_distance_m"]
        set_memory(b, self.name, K.MK_RATE_STATE, K.XS_MASS_SPEED, dc)
        add_term(b, "mass_force", -p["direct_N"], (K.XS_MASS_SPEED, K.XF_LOG, v0, 0.0, 0.0), nonperiodic=True)
        add_term(b, "mass_force", -p["evolution_N"], (K.XS_MEMORY, K.XF_LOG, dc / v0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        v0, dc = p["reference_speed_m_s"], p["slip_distance_m"]
        return (f"mass force += -({p['direct_N']:.6g} N * ln(v/{v0:.6g} m/s) + {p['evolution_N']:.6g} N * ln({v0:.6g} "
                f"m/s * theta/{dc:.6g} m)), theta' = 1 - v*theta/{dc:.6g} m (every 0.2 ms)")


# 10. a1 sensor x a1 through random bit errors
class A1TelemetryBitErrors(OutsideForm):
    name = "a1_telemetry_bit_errors"
    half = "sealed11"
    stage = "sensor"
    order = 1                      # the telemetry, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1's rotating telemetry has no error check: a sample's 16-bit code c = clip(round(32767*a/R), "
                   "-32768, 32767) has, at a rate p, one bit b flipped: y = a + (c' - c)*R/32767 where corrupted, else "
                   "y = a (u_n, v_n = row n of numpy default_rng(seed).random((N, 2)), n from the pre-roll's first "
                   "sample; corrupted where u_n < p, b = floor(16*v_n))")
    parameters = (Param("full_scale_m_s2", "m/s^2", (1.0, 5000.0), "R"),
                  Param("error_rate", "-", (0.0, 0.01), "p"),
                  Param("seed", "-", (0, 1000), "seed", "int"))
    note = "sparse impulsive errors, a power of two of the code step each"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        r = np.random.default_rng(int(p["seed"])).random((a.size, 2))
        full = p["full_scale_m_s2"]
        c = np.clip(np.round(32767.0 * a / full), -32768, 32767).astype(np.int64)
        bit = np.floor(16.0 * r[:, 1]).astype(np.int64)
        u16 = (c & 0xFFFF) ^ (np.int64(1) << bit)
        flipped = np.where(u16 >= 32768, u16 - 65536, u16)
        return np.where(r[:, 0] < p["error_rate"], a + (flipped - c) * full / 32767.0, a)

    def law(self, p):
        return (f"a1 sensor = a1, and at a rate {p['error_rate']:.6g} a sample's 16-bit code (full scale "
                f"{p['full_scale_m_s2']:.6g} m/s^2) with one random bit flipped (seed {int(p['seed'])})")


# 12. a2 sensor x a2 through a stitched dual range
class A2StitchedDualRange(OutsideForm):
    name = "a2_stitched_dual_range"
    half = "sealed11"
    stage = "sensor"
    order = 1                      # the module's ADCs, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's module has two ADCs, a fine one up to R and a coarse one beyond, stitched with a gain mismatch "
                   "g: y = a for |a| <= R, sign(a)*(R + (1 + g)*(|a| - R)) beyond")
    parameters = (Param("range_m_s2", "m/s^2", (0.0, 100.0), "R"), Param("gain_mismatch", "-", (-0.9, 5.0), "g"))
    note = "a kink in the gain at +-R"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        e = np.maximum(0.0, np.abs(a) - p["range_m_s2"])
        return a + np.sign(a) * p["gain_mismatch"] * e

    def law(self, p):
        return (f"a2 sensor = a2 + sign(a2) * {p['gain_mismatch']:.6g} * max(0, |a2| - {p['range_m_s2']:.6g} m/s^2)")


# 14. clutch torque x the jaw's angle difference through a bistable toggle spring
class ClutchOverCentreToggleSpring(OutsideForm):
    name = "clutch_over_centre_toggle_spring"
    half = "sealed11"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("a snap spring between the jaw halves flips over its centre when the angle difference D passes +d and "
                   "back when it passes -d, pushing the halves towards the face they last went past: T*(2*s - 1), s -> 1 "
                   "when D > d, s -> 0 when D < -d (every 0.2 ms; s = 0 at the run-in's start)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("switch_angle_rad", "rad", (0.0, 0.2), "d"))
    note = "a two-state, rate-independent hysteresis of the relative angle, with a jump"

    def apply(self, b, p):
        set_relay(b, self.name, K.XS_JAW_ANGLE, p["switch_angle_rad"], -p["switch_angle_rad"])
        add_term(b, "clutch_torque", 2.0 * p["torque_Nm"], (K.XS_RELAY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)
        add_term(b, "clutch_torque", -p["torque_Nm"], nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['torque_Nm']:.6g} N*m * (2*s - 1), s -> 1 when D > {p['switch_angle_rad']:.6g} rad, "
                f"-> 0 when D < -{p['switch_angle_rad']:.6g} rad, D the jaw's angle difference (every 0.2 ms)")


FORM_CLASSES = (MotorMagneticCouplingRotor, WheelTorqueSensingRampBrake, ClutchFillControlledCoupling,
                MassRateStateSlideway, A1TelemetryBitErrors, A2StitchedDualRange, ClutchOverCentreToggleSpring)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 11100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # a 4-pole-pair coupling of 10 N*m pull-out to a 0.02 kg*m^2 rotor loaded with 0.03 N*m*s/rad (~4.5 N*m)
        ("os11_motor_magnetic_coupling_rotor", "outside", 0.0062, 0.0280, 0.91,
         [E("motor_magnetic_coupling_rotor", {"pull_out_torque_Nm": 10.0, "pole_pairs": 4, "rotor_inertia_kg_m2": 0.02,
                                              "rotor_load_Nm_s_per_rad": 0.03})]),
        # per N*m of contact torque beyond 5 N*m; 0.2 a priori, a2 0.0456: scaled once x1.65
        ("os11_wheel_torque_sensing_ramp_brake", "outside", 0.0082, 0.0210, 0.93,
         [E("wheel_torque_sensing_ramp_brake", {"gain": 0.329, "preload_Nm": 5.0})]),
        # 2 N*m*s/rad when full; filling over 50 ms of each 60 ms stroke, draining over 100 ms
        ("os11_clutch_fill_controlled_coupling", "outside", 0.0053, 0.0340, 0.91,
         [E("clutch_fill_controlled_coupling", {"coefficient_Nm_s_per_rad": 2.0, "fill_time_s": 0.05,
                                                "drain_time_s": 0.1})]),
        # over 0.5 m of slip at 22.71 m/s (a clean drive's v: 22.67-22.77 m/s); a = 200 N, b = 150 N a priori, a2
        # 0.0145: both scaled once x5.16
        ("os11_mass_rate_state_slideway", "outside", 0.0070, 0.0240, 0.94,
         [E("mass_rate_state_slideway", {"direct_N": 1031.0, "evolution_N": 773.5, "slip_distance_m": 0.5,
                                         "reference_speed_m_s": 22.71})]),
        ("os11_clean_w7.6_eta0.0320_n0.92", "clean", 0.0076, 0.0320, 0.92, []),
        # one sample in 10^4 with a bit of its 16-bit code (full scale 200 m/s^2) flipped
        ("os11_a1_telemetry_bit_errors", "outside", 0.0059, 0.0380, 0.96,
         [E("a1_telemetry_bit_errors", {"full_scale_m_s2": 200.0, "error_rate": 1e-4, "seed": 5})]),
        # a 30 % gain step beyond 0.3 m/s^2 (a clean drive's a2: -1.03..0.79 m/s^2 for 99 %)
        ("os11_a2_stitched_dual_range", "outside", 0.0088, 0.0230, 0.90,
         [E("a2_stitched_dual_range", {"range_m_s2": 0.3, "gain_mismatch": 0.3})]),
        # 3 N*m flipping at D = +-0.01 rad (the gap's half-width at these widths: ~0.04 rad)
        ("os11_clutch_over_centre_toggle_spring", "outside", 0.0065, 0.0200, 0.95,
         [E("clutch_over_centre_toggle_spring", {"torque_Nm": 3.0, "switch_angle_rad": 0.01})]),
    ]
