"""Outside mechanisms, fourth SEALED half (issue 31 part 4, set 4).

SEALED: whoever builds or tunes the workbench's proposal of a missing term (workbench/proposal.py,
event_design.py, candidate_terms.py, and the model's variables they use) does not read this file, the suite it makes
(``python -m foreign_drives write --suite outside_sealed4``), its manifest or its recordings' diagnoses, until the
final, once-only run. ``python -m foreign_drives forms`` withholds these laws; docs/foreign_drives.md lists these
mechanisms by name and balance only.

Seven mechanisms outside the catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, the first three
sets nor the fourth development half (:mod:`outside_dev4`) has, and the suite's rows (seeds 8100+). The split rule is
in :mod:`outside_dev4` (written as one list of fourteen; the even numbers are here). Written before any diagnose,
analyze or proposal ran on them. The suite is made on first use (``suites.suite("outside_sealed4")``), not listed in
``suites.SUITES``.

2. motor load moment x the motor speed through a LAG (a hidden state): an auxiliary flywheel (a feed pump's rotor,
   a large fan impeller) driven from the motor shaft by V-belts whose creep is proportional to the torque they pass:
   the belts load the motor with c*(Omega1 - w_f), the flywheel's speed w_f following Omega1 with tau = J_f/c;
4. wheel torque x the wheel speed DELAYED, beyond a limit: an overspeed guard; a PLC reads the wheel speed over a
   fieldbus and applies an eddy-current brake -k*max(0, Omega2(t - d) - Omega_lim), d the bus's and the PLC's dead
   time;
6. clutch torque x the TIME SINCE THE CONTACT BEGAN: hydraulic cushions behind the jaw faces; at each contact their
   chambers are compressed and empty through an orifice, so they stiffen and damp the contact at first and fade as
   they empty, T_c*(1 + g*exp(-t_c/tau)); they refill in the gap (written first as k_h*p*exp(-t_c/tau): that law
   jumps when the jaw releases with the faces still pressed and made the integrator chatter there -- changed before any
   visibility simulation);
8. mass force x RANDOM INSTANTS (a Poisson process, locked to nothing of this drive): the neighbouring station's
   pneumatic kicker, on the same rail and air supply, fires on its own irregular cycle; each firing pushes the
   carriage back with F for T_p;
10. a1 sensor x a1's OVERLOADS with memory: a1 is piezoelectric; accelerations beyond its linear range leave a
    residual charge (a zero shift, signed with the overload) that the charge amplifier bleeds off with its time
    constant: b' = kappa*(max(0, a - a_s) - max(0, -a - a_s)) - b/tau, a1 += b;
12. a2 sensor x TIME as a growing lag: a2 is digitised by a separate I/O module whose sample clock runs slow against
    the recorder's: the recorded a2 at t is the signal at t - g*t (a lag growing by g per second);
14. wheel torque x the wheel ANGLE against a CLOCK, saturating: an electronic line shaft; a trim drive keeps the wheel
    in phase with the line's master clock, -K*sat(theta2 - Omega_ref*t - theta0, T_max/K), theta2 the wheel angle
    unwrapped from the run-in's start.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.signal import lfilter

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import segments, set_memory

_KICK_WINDOW_S = (-2.2, 10.0)    # the kicker's firings are drawn over the run-in and the first 10 s of a recording


# 2. motor load moment x the motor speed through a lag
class MotorBeltFlywheel(OutsideForm):
    name = "motor_belt_flywheel"
    half = "sealed4"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("an auxiliary flywheel (a feed pump's rotor, a large fan impeller) driven from the motor shaft by "
                   "V-belts whose creep is proportional to the torque they pass: c*(Omega1 - w_f) on the motor's load, "
                   "dw_f/dt = (Omega1 - w_f)/tau, tau = J_f/c (w_f advanced once per 0.2 ms)")
    parameters = (Param("coefficient_Nms_per_rad", "N*m*s/rad", (0.0, 50.0), "c"),
                  Param("time_constant_s", "s", (1e-3, 10.0), "tau"))

    def apply(self, b, p):
        tau = p["time_constant_s"]
        set_memory(b, self.name, K.MK_LAG, K.XS_OMEGA1, tau, tau, 0.0)
        add_term(b, "motor_load_moment", p["coefficient_Nms_per_rad"], (K.XS_MEMORY_EXCESS, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nms_per_rad']:.6g} N*m*s/rad * (Omega1 - w_f), w_f -> Omega1 "
                f"with {p['time_constant_s']:.6g} s (advanced every 0.2 ms)")


# 4. wheel torque x the wheel speed delayed, beyond a limit
class WheelFieldbusOverspeedBrake(OutsideForm):
    name = "wheel_fieldbus_overspeed_brake"
    half = "sealed4"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("an overspeed guard: a PLC reads the wheel speed over a fieldbus and applies an eddy-current brake "
                   "-k*max(0, Omega2(t - d) - Omega_lim), d the bus's and the PLC's dead time (the speed taken every "
                   "0.2 ms)")
    parameters = (Param("gain_Nms_per_rad", "N*m*s/rad", (0.0, 20.0), "k"),
                  Param("limit_rad_s", "rad/s", (100.0, 170.0), "Omega_lim"),
                  Param("delay_s", "s", (0.0, 0.0126), "d (a multiple of 0.2 ms)"))

    def apply(self, b, p):
        d = segments(p["delay_s"], f"{self.name}: delay_s")
        set_memory(b, self.name, K.MK_DELAY, K.XS_OMEGA2, 1.0, float(d))
        add_term(b, "wheel_torque", -p["gain_Nms_per_rad"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["limit_rad_s"], 1.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['gain_Nms_per_rad']:.6g} N*m*s/rad * max(0, Omega2(t - {p['delay_s']:.6g} s) - "
                f"{p['limit_rad_s']:.6g} rad/s), Omega2 taken every 0.2 ms")


# 6. clutch torque x the time since the contact began
class ClutchHydraulicCushion(OutsideForm):
    name = "clutch_hydraulic_cushion"
    half = "sealed4"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("hydraulic cushions behind the jaw faces: at each contact their chambers are compressed and empty "
                   "through an orifice, so they stiffen and damp the contact at first and fade as they empty: the "
                   "contact law's torque T_c times 1 + g*exp(-t_c/tau), t_c the time since this contact began from the "
                   "gap (a re-touch with the faces still pressed continues it); they refill in the gap")
    parameters = (Param("gain", "-", (0.0, 5.0), "g: the full cushion's share of the contact torque"),
                  Param("empty_time_s", "s", (1e-3, 1.0), "tau"))
    note = "zero in the gap and wherever the contact law's torque is zero (it releases with the jaw)"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["gain"], (K.XS_CONTACT_TORQUE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_CONTACT_AGE, K.XF_DECAY_AFTER, p["empty_time_s"], 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['gain']:.6g} * T_c * exp(-t_c / {p['empty_time_s']:.6g} s) in contact, T_c the "
                "contact law's torque, t_c the time since this contact began from the gap")


# 8. mass force x random instants
class MassAirKicker(OutsideForm):
    name = "mass_air_kicker"
    half = "sealed4"
    balance = "mass_force"
    depends_on = ("time",)
    description = ("the neighbouring station's pneumatic kicker, on the same rail and air supply, fires on its own "
                   "irregular cycle (a Poisson process of rate lambda, drawn from the sequence number): each firing "
                   "pushes the carriage back, -F for T_p (on the 0.2 ms grid)")
    parameters = (Param("force_N", "N", (0.0, 200.0), "F"),
                  Param("rate_per_s", "1/s", (0.01, 2.5), "lambda"),
                  Param("push_s", "s", (1e-3, 0.2), "T_p"),
                  Param("sequence", "-", (0, 1_000_000), "the random sequence's number", "int"))
    note = "locked to nothing of this drive: neither the pulse, nor an angle, nor a period"

    @staticmethod
    def firings(p) -> np.ndarray:
        """The firing instants [s] from sample 0 (t < 0: the run-in), over _KICK_WINDOW_S, on the 0.2 ms grid."""
        rng = np.random.default_rng(int(p["sequence"]))
        t, out = _KICK_WINDOW_S[0], []
        while True:
            t += rng.exponential(1.0 / p["rate_per_s"])
            if t >= _KICK_WINDOW_S[1]:
                break
            out.append(round(t / 2e-4) * 2e-4)
        return np.array(out)

    def apply(self, b, p):
        ts = self.firings(p)
        if ts.size > K.MEMORY_RING:
            raise ValueError(f"{self.name}: {ts.size} firings in {_KICK_WINDOW_S} s; allowed: at most "
                             f"{K.MEMORY_RING} (a lower rate_per_s)")
        set_memory(b, self.name, K.MK_SCHEDULE, K.XS_ONE, 0.0, p["push_s"])
        b.P[K.P_MEMN] = float(ts.size)
        b.P[K.P_MEMR0:K.P_MEMR0 + ts.size] = ts
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        ts = [f"{x:.4f}" for x in self.firings(p) if x >= 0.0]
        return (f"mass force += -{p['force_N']:.6g} N for {p['push_s']:.6g} s from each firing at t = "
                f"{', '.join(ts)} s (t from sample 0)")


# 10. a1 sensor x a1's overloads with memory
class A1PiezoZeroShift(OutsideForm):
    name = "a1_piezo_zero_shift"
    half = "sealed4"
    stage = "sensor"
    order = 0                      # the sensing element (its crystal)
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1 is piezoelectric: accelerations beyond its linear range a_s leave a residual charge, a zero "
                   "shift signed with the overload, that the charge amplifier bleeds off with its time constant: "
                   "b' = kappa*(max(0, a - a_s) - max(0, -a - a_s)) - b/tau, a1 += b (running since long before)")
    parameters = (Param("threshold_m_s2", "m/s^2", (0.0, 1000.0), "a_s"),
                  Param("gain_per_s", "1/s", (0.0, 1000.0), "kappa"),
                  Param("bleed_time_s", "s", (1e-3, 100.0), "tau"))

    def apply_signal(self, sig, p, t, fs, states=None):
        a = np.asarray(sig["a1"], dtype=np.float64)
        a_s = p["threshold_m_s2"]
        u = np.maximum(0.0, a - a_s) - np.maximum(0.0, -a - a_s)
        n_per = int(round(C.PULSE_PERIOD_S * fs))
        pad = np.tile(u[:n_per], 8)              # the sensor ran through 2 s of the same periodic drive before
        dt = 1.0 / fs
        shift = lfilter([p["gain_per_s"] * dt], [1.0, -math.exp(-dt / p["bleed_time_s"])], np.concatenate([pad, u]))
        sig["a1"] = a + shift[pad.size:]

    def law(self, p):
        return (f"a1 sensor += b, db/dt = {p['gain_per_s']:.6g}/s * (max(0, a - {p['threshold_m_s2']:.6g}) - max(0, "
                f"-a - {p['threshold_m_s2']:.6g})) - b / {p['bleed_time_s']:.6g} s, a the acceleration")


# 12. a2 sensor x time as a growing lag
class A2ClockLagDrift(OutsideForm):
    name = "a2_clock_lag_drift"
    half = "sealed4"
    stage = "sensor"
    order = 1                      # the digitiser, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration", "time")
    description = ("a2 is digitised by a separate I/O module whose sample clock runs slow against the recorder's: the "
                   "recorded a2 at t is the signal at t - g*t (a lag growing by g per second from sample 0; linear "
                   "interpolation)")
    parameters = (Param("lag_growth", "s/s", (0.0, 0.01), "g"),)

    def apply_signal(self, sig, p, t, fs, states=None):
        t = np.asarray(t, dtype=np.float64)
        sig["a2"] = np.interp(t - p["lag_growth"] * t, t, np.asarray(sig["a2"], dtype=np.float64))

    def law(self, p):
        return f"a2 sensor (t) = a2(t - {p['lag_growth']:.6g} * t), t from sample 0"


# 14. wheel torque x the wheel angle against a clock, saturating
class WheelPhaseLockTrim(OutsideForm):
    name = "wheel_phase_lock_trim"
    half = "sealed4"
    balance = "wheel_torque"
    depends_on = ("wheel_angle", "time")
    description = ("an electronic line shaft: a trim drive keeps the wheel in phase with the line's master clock, "
                   "-K*sat(theta2 - Omega_ref*(t - t0) - theta0, T_max/K), theta2 the wheel angle unwrapped from the "
                   "run-in's start t0 (2 s before sample 0, theta2(t0) = 0)")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 100.0), "K"),
                  Param("reference_speed_rad_s", "rad/s", (100.0, 170.0), "Omega_ref: the master clock's rate"),
                  Param("phase_rad", "rad", (-math.pi, math.pi), "theta0"),
                  Param("limit_Nm", "N*m", (0.0, 50.0), "T_max"))

    def apply(self, b, p):
        if b.P[K.P_CLKRATE] != 0.0:
            raise ValueError(f"{self.name}: a second clock in one recording; allowed: one")
        b.P[K.P_CLKRATE] = p["reference_speed_rad_s"]
        k = p["stiffness_Nm_per_rad"]
        lim = p["limit_Nm"] / k if k > 0.0 else 1e9
        add_term(b, "wheel_torque", -k, (K.XS_ALPHA2_MINUS_CLOCK, K.XF_CLIP, lim, -p["phase_rad"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['stiffness_Nm_per_rad']:.6g} N*m/rad * sat(theta2 - "
                f"{p['reference_speed_rad_s']:.6g} rad/s * (t + 2 s) - {p['phase_rad']:.6g}, +-{p['limit_Nm']:.6g} N*m "
                f"/ {p['stiffness_Nm_per_rad']:.6g} N*m/rad), theta2 the wheel angle unwrapped from the run-in's start "
                "(t = -2 s, theta2 = 0), t from sample 0")


FORM_CLASSES = (MotorBeltFlywheel, WheelFieldbusOverspeedBrake, ClutchHydraulicCushion, MassAirKicker, A1PiezoZeroShift,
                A2ClockLagDrift, WheelPhaseLockTrim)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 8100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        ("os4_motor_belt_flywheel", "outside", 0.007, 0.0225, 0.90,
         [E("motor_belt_flywheel", {"coefficient_Nms_per_rad": 2.0, "time_constant_s": 0.1})]),
        ("os4_wheel_fieldbus_overspeed_brake", "outside", 0.0045, 0.03, 0.95,
         [E("wheel_fieldbus_overspeed_brake", {"gain_Nms_per_rad": 3.0, "limit_rad_s": 152.5, "delay_s": 0.008})]),
        ("os4_clutch_hydraulic_cushion", "outside", 0.008, 0.04, 0.92,
         [E("clutch_hydraulic_cushion", {"gain": 1.0, "empty_time_s": 0.015})]),
        ("os4_mass_air_kicker", "outside", 0.006, 0.0175, 0.89,
         [E("mass_air_kicker", {"force_N": 15.0, "rate_per_s": 1.5, "push_s": 0.03, "sequence": 4711})]),
        ("os4_clean_w8.8_eta0.045_n0.94", "clean", 0.0088, 0.045, 0.94, []),
        ("os4_a1_piezo_zero_shift", "outside", 0.0065, 0.02, 0.97,
         [E("a1_piezo_zero_shift", {"threshold_m_s2": 80.0, "gain_per_s": 14.0, "bleed_time_s": 0.2})]),
        ("os4_a2_clock_lag_drift", "outside", 0.0095, 0.03, 0.91, [E("a2_clock_lag_drift", {"lag_growth": 0.001})]),
        ("os4_wheel_phase_lock_trim", "outside", 0.0052, 0.025, 0.93,
         [E("wheel_phase_lock_trim", {"stiffness_Nm_per_rad": 10.0, "reference_speed_rad_s": 151.41, "phase_rad": 0.0,
                                      "limit_Nm": 10.0})]),
    ]
