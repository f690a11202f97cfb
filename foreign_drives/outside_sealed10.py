"""Outside mechanisms, tenth SEALED half (issue 31 part 4, set 10).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed10``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first nine sets
nor the tenth development half (:mod:`outside_dev10`) has, and the suite's rows (seeds 10100+). The split rule is in
:mod:`outside_dev10` (written as one list of fourteen; the even numbers are here; 2, 10, 14 with a memory, 4, 6, 8, 12
memoryless). Written before any diagnose, analyze or proposal ran on them. The suite is made on first use
(``suites.suite("outside_sealed10")``), not listed in ``suites.SUITES``.

2. motor load moment x the motor speed through a MOVING AVERAGE (a finite memory): a variable-displacement pump on
   the motor's shaft end whose displacement controller reads the motor speed through a PLC's moving-average filter
   over the last N scans (N*0.2 ms): a load K*max(0, mean_N(Omega1) - Omega_0) (every speed older than N scans
   forgotten at once: a boxcar, not an exponential lag);
4. wheel torque x the unwrapped wheel angle through a LINK-BY-LINK RANDOM pattern: a roller chain from an n-tooth
   sprocket on the wheel shaft to a conveyor; its links are unevenly worn, so each link's engagement passes a torque
   error of its own: T*u_k, u_k pseudo-random in [-1, 1) of the link count k = floor(n*theta2/(2*pi)), theta2 the wheel
   angle unwrapped from the run-in's start (a pattern as long as the chain, longer than the record: locked to the
   wheel angle, not periodic in a turn);
6. clutch torque x the motor angle at order 2, ADDITIVE: a diaphragm (disc) coupling in parallel with the jaw, mounted
   with an angular misalignment: its discs flex twice per turn and pass a torque A*sin(2*alpha1 + phi) from the motor to
   the wheel at all times (an angle-locked torque between the two halves, equal and opposite on the two shafts: not the
   catalogue's ripple on the motor, not a wheel mesh, not the third set's moving gap);
8. mass force x the time through a neighbour's STRIKES: a neighbouring press on the same floor strikes every T_n
   seconds (its own rate, not this press's); each strike rings the carriage's rail with a decaying shock at f_r:
   F*exp(-((t - t_0) mod T_n)/tau)*sin(2*pi*f_r*(t - t_0)), f_r*T_n a whole number (a train of decaying shocks of its
   own period: not a sine, not a window);
10. a2 sensor x a2's own past through a SMOOTH HYSTERESIS: a2's piezoceramic element has a ferroelectric hysteresis:
    y = a + H*s, s -> sign(da) - (sign(da) - s)*exp(-|da|/a_c) for each sample's change da of the acceleration (a
    Dahl-type, rate-independent loop of half-height H added to the reading; s = 0 at the pre-roll's first sample);
12. a1 sensor x a1 through a CROSSOVER DEAD ZONE: a1's line driver is a class-B output stage without bias: y =
    sign(a)*max(0, |a| - d) (small accelerations vanish, large ones read d short: a dead zone around zero);
14. mass force x the mass speed SAMPLED AT EACH JAW IMPACT: a knock sensor on the coupling's housing triggers the PLC to
    sample the carriage's speed at each contact from the gap (the first 0.2 ms scan after it begins) and a linear brake
    on the carriage is set from it, -K*(v_s - v_ref), held until the next impact (a sample-and-hold timed by the drive's
    own impacts, not by the stroke or an angle).

Visibility, measured as for the development half (4 s, same spec without the mechanism, same seed; criterion a2 >=
0.05 m/s^2, a1 >= 0.25): 2 a2 0.0571; 4 a2 0.0341, scaled once x2.20 -> 0.0748; 6 a2 0.0199, scaled once x3.76 ->
0.0714; 8 a2 0.0745; 10 a2 0.0842; 12 a1 0.983; 14 a2 0.223. Written once (``python -m foreign_drives write --suite
outside_sealed10``, on a fresh kernel cache): 16 onset entries in each row's manifest but 6's, 36 (the twice-per-turn
torque bounces the jaw back into its gap).
"""
from __future__ import annotations

import math

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory
from .outside_dev9 import _PHASE


# 2. motor load moment x the motor speed through a moving average
class MotorAveragedSpeedPump(OutsideForm):
    name = "motor_averaged_speed_pump"
    half = "sealed10"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a variable-displacement pump on the motor's shaft end whose displacement controller reads the motor "
                   "speed through a moving average over the last N scans of 0.2 ms: a load K*max(0, m - Omega_0), m the "
                   "mean of Omega1 at the starts of the last N scans (all N = Omega1 at the run-in's start)")
    parameters = (Param("gain_Nm_s_per_rad", "N*m*s/rad", (0.0, 50.0), "K"),
                  Param("set_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_0"),
                  Param("window_scans", "scans", (1, 64), "N", "int"))
    note = "a finite memory (a boxcar): every speed older than N scans forgotten at once, not an exponential lag"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_MOVING_MEAN, K.XS_OMEGA1, float(int(p["window_scans"])))
        add_term(b, "motor_load_moment", p["gain_Nm_s_per_rad"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["set_speed_rad_s"], 1.0, 0.0), nonperiodic=True)

    @staticmethod
    def averaged(omega1_at_scans, p):
        w = np.asarray(omega1_at_scans, dtype=np.float64)
        n = int(p["window_scans"])
        padded = np.concatenate((np.full(n - 1, w[0]), w))
        return np.convolve(padded, np.ones(n) / n, mode="valid")

    def law(self, p):
        return (f"motor load moment += {p['gain_Nm_s_per_rad']:.6g} N*m*s/rad * max(0, m - {p['set_speed_rad_s']:.6g} "
                f"rad/s), m the mean of Omega1 over the last {int(p['window_scans'])} scans of 0.2 ms")


# 4. wheel torque x the unwrapped wheel angle through a link-by-link random pattern
class WheelWornChainLinks(OutsideForm):
    name = "wheel_worn_chain_links"
    half = "sealed10"
    balance = "wheel_torque"
    depends_on = ("wheel_angle",)
    description = ("a roller chain from an n-tooth sprocket on the wheel shaft, its links unevenly worn: each link's "
                   "engagement passes a torque error of its own, T*u_k, k = floor(n*theta2/(2*pi)) the link count, theta2 "
                   "the wheel angle unwrapped from the run-in's start, u_k in [-1, 1) pseudo-random of k and a seed s "
                   "(kernel.XF_HASH_STEP: q = 7919*k^2 + 40503*k + 104729*s, u = 2*(q mod 65521)/65521 - 1)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("teeth", "-", (4, 60), "n", "int"),
                  Param("seed", "-", (0, 1000), "s", "int"))
    note = "a pattern as long as the chain, locked to the wheel angle, not periodic in a turn"

    def apply(self, b, p):
        add_term(b, "wheel_torque", p["torque_Nm"],
                 (K.XS_ALPHA2_UNWRAPPED, K.XF_HASH_STEP, float(p["seed"]), 2.0 * math.pi / p["teeth"], 0.0),
                 nonperiodic=True)

    @staticmethod
    def u(k, seed):
        k = np.floor(np.asarray(k, dtype=np.float64))
        q = k * k * 7919.0 + k * 40503.0 + seed * 104729.0
        return 2.0 * np.mod(q, 65521.0) / 65521.0 - 1.0

    def law(self, p):
        return (f"wheel torque += {p['torque_Nm']:.6g} N*m * u_k, k = floor({int(p['teeth'])}*theta2/(2*pi)), u_k = 2*((7919"
                f"*k^2 + 40503*k + 104729*{int(p['seed'])}) mod 65521)/65521 - 1, theta2 the wheel angle unwrapped")


# 6. clutch torque x the motor angle at order 2, additive
class ClutchMisalignedDiaphragm(OutsideForm):
    name = "clutch_misaligned_diaphragm"
    half = "sealed10"
    balance = "clutch_torque"
    depends_on = ("motor_angle",)
    description = ("a diaphragm coupling in parallel with the jaw, mounted with an angular misalignment: its discs flex "
                   "twice per turn and pass A*sin(2*alpha1 + phi) from the motor to the wheel at all times")
    parameters = (Param("amplitude_Nm", "N*m", (0.0, 50.0), "A"), _PHASE)
    note = "an angle-locked torque between the two halves, equal and opposite on the two shafts"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["amplitude_Nm"], (K.XS_ALPHA1, K.XF_SIN, 2.0, p["phase_rad"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return f"clutch torque += {p['amplitude_Nm']:.6g} N*m * sin(2*alpha1 + {p['phase_rad']:.6g} rad)"


# 8. mass force x the time through a neighbour's strikes
class MassNeighbourPressShocks(OutsideForm):
    name = "mass_neighbour_press_shocks"
    half = "sealed10"
    balance = "mass_force"
    depends_on = ("time",)
    description = ("a neighbouring press on the same floor strikes every T_n seconds; each strike rings the carriage's "
                   "rail with a decaying shock: F*exp(-((t - t_0) mod T_n)/tau)*sin(2*pi*f_r*(t - t_0)), f_r*T_n whole, "
                   "t the generator's time (0 at sample 0)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"), Param("period_s", "s", (0.01, 10.0), "T_n"),
                  Param("ring_hz", "Hz", (1.0, 2000.0), "f_r (f_r*T_n a whole number)"),
                  Param("decay_time_s", "s", (1e-4, 1.0), "tau"), Param("first_strike_s", "s", (0.0, 10.0), "t_0"))
    note = "a train of decaying shocks of its own period: not a sine, not a window, not this press's stroke"

    def apply(self, b, p):
        cycles = p["ring_hz"] * p["period_s"]
        if abs(cycles - round(cycles)) > 1e-9:
            raise ValueError(f"{self.name}: ring_hz*period_s = {cycles:g} is not a whole number; allowed: whole numbers")
        w = 2.0 * math.pi * p["ring_hz"]
        add_term(b, "mass_force", p["force_N"],
                 (K.XS_TIME, K.XF_PERIODIC_DECAY, p["period_s"], p["first_strike_s"], p["decay_time_s"]),
                 (K.XS_TIME, K.XF_SIN, w, -w * p["first_strike_s"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * exp(-((t - {p['first_strike_s']:.6g} s) mod {p['period_s']:.6g} s)/"
                f"{p['decay_time_s']:.6g} s) * sin(2*pi*{p['ring_hz']:.6g} Hz*(t - {p['first_strike_s']:.6g} s))")


# 10. a2 sensor x a2's own past through a smooth hysteresis
class A2PiezoHysteresis(OutsideForm):
    name = "a2_piezo_hysteresis"
    half = "sealed10"
    stage = "sensor"
    order = 0                      # the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's piezoceramic element has a ferroelectric hysteresis: y = a + H*s, s -> sign(da) - (sign(da) - "
                   "s)*exp(-|da|/a_c) for each sample's change da of the acceleration (s = 0 at the pre-roll's first "
                   "sample)")
    parameters = (Param("half_height_m_s2", "m/s^2", (0.0, 10.0), "H"),
                  Param("memory_scale_m_s2", "m/s^2", (1e-4, 10.0), "a_c"))
    note = "a Dahl-type, rate-independent loop added to the reading (smooth: not a play)"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def read(a, p):
        x = np.asarray(a, dtype=np.float64)
        d = np.diff(x, prepend=x[0]).tolist()
        ac = p["memory_scale_m_s2"]
        s, out = 0.0, np.empty(x.size)
        for i, da in enumerate(d):
            if da != 0.0:
                sg = 1.0 if da > 0.0 else -1.0
                s = sg - (sg - s) * math.exp(-abs(da) / ac)
            out[i] = s
        return x + p["half_height_m_s2"] * out

    def law(self, p):
        return (f"a2 sensor = a2 + {p['half_height_m_s2']:.6g} m/s^2 * s, s -> sign(da) - (sign(da) - s)*exp(-|da|/"
                f"{p['memory_scale_m_s2']:.6g} m/s^2) for each sample's change da of a2")


# 12. a1 sensor x a1 through a crossover dead zone
class A1CrossoverDeadZone(OutsideForm):
    name = "a1_crossover_dead_zone"
    half = "sealed10"
    stage = "sensor"
    order = 1                      # the line driver, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = "a1's line driver is a class-B output stage without bias: y = sign(a)*max(0, |a| - d)"
    parameters = (Param("dead_zone_m_s2", "m/s^2", (0.0, 100.0), "d"),)
    note = "small accelerations vanish, large ones read d short: a dead zone around zero"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        return np.sign(a) * np.maximum(0.0, np.abs(a) - p["dead_zone_m_s2"])

    def law(self, p):
        return f"a1 sensor = sign(a1)*max(0, |a1| - {p['dead_zone_m_s2']:.6g} m/s^2)"


# 14. mass force x the mass speed sampled at each jaw impact
class MassImpactSampledBrake(OutsideForm):
    name = "mass_impact_sampled_brake"
    half = "sealed10"
    balance = "mass_force"
    depends_on = ("mass_speed", "clutch_penetration")
    description = ("a knock sensor on the coupling's housing makes the PLC sample the carriage's speed at each contact "
                   "from the gap (the first 0.2 ms scan after it began); a linear brake on the carriage is set from it, "
                   "-K*(v_s - v_ref), held until the next impact (v_s = v at the run-in's start until the first)")
    parameters = (Param("gain_N_s_per_m", "N*s/m", (0.0, 5000.0), "K"),
                  Param("reference_speed_m_s", "m/s", (0.0, 50.0), "v_ref"))
    note = "a sample-and-hold timed by the drive's own impacts, not by the stroke or an angle"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_IMPACT_SAMPLE, K.XS_MASS_SPEED, 0.0)
        add_term(b, "mass_force", -p["gain_N_s_per_m"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)
        add_term(b, "mass_force", p["gain_N_s_per_m"] * p["reference_speed_m_s"], nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['gain_N_s_per_m']:.6g} N*s/m * (v_s - {p['reference_speed_m_s']:.6g} m/s), v_s the "
                "carriage's speed at the first 0.2 ms scan after each contact from the gap began, held")


FORM_CLASSES = (MotorAveragedSpeedPump, WheelWornChainLinks, ClutchMisalignedDiaphragm, MassNeighbourPressShocks,
                A2PiezoHysteresis, A1CrossoverDeadZone, MassImpactSampledBrake)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 10100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 2 N*m per rad/s of the 10 ms mean speed above 151 rad/s (a clean drive's Omega1: 147.6-153.7 rad/s)
        ("os10_motor_averaged_speed_pump", "outside", 0.0061, 0.0285, 0.92,
         [E("motor_averaged_speed_pump", {"gain_Nm_s_per_rad": 2.0, "set_speed_rad_s": 151.0, "window_scans": 50})]),
        # per link of a 20-tooth sprocket; +-3 N*m a priori, a2 0.0341: scaled once x2.20
        ("os10_wheel_worn_chain_links", "outside", 0.0083, 0.0205, 0.94,
         [E("wheel_worn_chain_links", {"torque_Nm": 6.60, "teeth": 20, "seed": 7})]),
        # twice per turn; 3 N*m a priori, a2 0.0199: scaled once x3.76
        ("os10_clutch_misaligned_diaphragm", "outside", 0.0052, 0.0335, 0.90,
         [E("clutch_misaligned_diaphragm", {"amplitude_Nm": 11.3, "phase_rad": 0.7})]),
        # 5 N strikes every 0.35 s ringing at 60 Hz, decaying over 30 ms
        ("os10_mass_neighbour_press_shocks", "outside", 0.0071, 0.0245, 0.93,
         [E("mass_neighbour_press_shocks", {"force_N": 5.0, "period_s": 0.35, "ring_hz": 60.0, "decay_time_s": 0.03,
                                            "first_strike_s": 0.1})]),
        ("os10_clean_w7.7_eta0.0315_n0.91", "clean", 0.0077, 0.0315, 0.91, []),
        # a loop of +-0.1 m/s^2 over changes of ~0.2 m/s^2 (a clean drive's a2: -1.03..0.79 m/s^2 for 99 %)
        ("os10_a2_piezo_hysteresis", "outside", 0.0058, 0.0375, 0.95,
         [E("a2_piezo_hysteresis", {"half_height_m_s2": 0.1, "memory_scale_m_s2": 0.2})]),
        # a dead zone of 1 m/s^2 (a clean drive's a1: -104..100 m/s^2 for 99 %)
        ("os10_a1_crossover_dead_zone", "outside", 0.0089, 0.0225, 0.89,
         [E("a1_crossover_dead_zone", {"dead_zone_m_s2": 1.0})]),
        # 50 N per m/s of the impact-sampled speed above 22.71 m/s (a clean drive's v: 22.67-22.77 m/s)
        ("os10_mass_impact_sampled_brake", "outside", 0.0066, 0.0195, 0.96,
         [E("mass_impact_sampled_brake", {"gain_N_s_per_m": 50.0, "reference_speed_m_s": 22.71})]),
    ]
