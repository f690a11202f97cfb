"""Outside mechanisms, third DEVELOPMENT half (issue 31 part 4, set 3): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first two sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2`, :mod:`outside_sealed2`) have, with their laws in the open. The third
sealed half is :mod:`outside_sealed3`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed3` (its balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 wheel torque, 14 sensor).
Written before any diagnose or proposal ran on them (the commit history is the proof); no strength was changed after
a diagnose (each was set by one quick simulation against the clean drive of the same seed, for visibility).

Kinds (balance x what it reads), the development half:

1. motor load moment x the load pulse's FALLING edge, decaying: a hydraulic pump on the motor shaft recharges the
   press's accumulator after each stroke (its load starts as the stroke ends and falls off as the accumulator fills);
3. wheel torque x a gate on the jaw's angle difference (the load side ahead of the motor): a Weston-type load brake
   that holds the load whenever it overruns its drive;
5. clutch torque x the motor angle at order 2 (the backlash's boundaries move): a Cardan shaft at an angle between
   the motor and the jaw, whose kinematic error makes the jaw's angle difference D - e*sin(2*alpha1 + phi);
7. mass force x the load pulse DELAYED, with a lag: a pneumatic hold-back cylinder on the carriage, switched by the
   press's valve and reaching its force a transport delay and a lag after each edge of the stroke;
9. a2 sensor x a2 with MEMORY: the a2 transmitter's deadband (report by exception): it sends a new value only when
   the reading has moved by more than the deadband from the last one sent (a hysteresis, not a quantiser);
11. motor load moment x the motor SPEED through a relay with hysteresis: a PLC switches an auxiliary consumer onto the
    motor shaft when the speed rises above one threshold and off when it falls below a lower one (scanned every
    0.2 ms);
13. a2 sensor x the load pulse's RISING edge, ringing: each stroke rings the frame the a2 sensor stands on; the sensor
    reads that frame's decaying vibration as acceleration.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle; the manifest has its
value at sample 0). The pulse phase phi_p = the time since the latest load pulse began, on or off (0 <= phi_p < 0.25 s).
"""
from __future__ import annotations

import math

import numpy as np

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term, set_relay

_PHASE = Param("phase_rad", "rad", (-math.pi, math.pi), "phi (relative to the simulator's angle)")
_SIGN_SPEED = 1.0      # rad/s: the speed below which a brake's sign(Omega) is smoothed (tanh); the drive runs > 140


def pulse_phase_s(t: np.ndarray, pulse: np.ndarray) -> np.ndarray:
    """The time since the latest load pulse began [s], from the held pulse indicator at the sample times ``t``: the
    pulse train is periodic (C.PULSE_PERIOD_S), so one rising edge fixes every start."""
    rise = np.flatnonzero((pulse[1:] > 0) & (pulse[:-1] == 0)) + 1
    if rise.size == 0:
        raise ValueError("the pulse indicator has no rising edge; a recording needs at least one load pulse")
    return np.mod(t - t[rise[0]], C.PULSE_PERIOD_S)


class MotorAccumulatorRecharge(OutsideForm):
    name = "motor_accumulator_recharge"
    half = "dev3"
    balance = "motor_load_moment"
    depends_on = ("load_pulse",)
    description = ("a hydraulic pump on the motor shaft recharges the press's accumulator after each stroke: a load "
                   "T*exp(-(phi_p - D)/tau) from the pulse's end (phi_p = D, D = 60 ms) until the next pulse begins, "
                   "phi_p the time since the latest pulse began")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T: the pump's load as the stroke ends"),
                  Param("decay_s", "s", (1e-3, 1.0), "tau: how fast the accumulator fills"))
    note = "a term of the pulse's FALLING edge (the catalogue's pulse load and the first set's brake act while it is on)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"],
                 (K.XS_PULSE_PHASE, K.XF_DECAY_AFTER, p["decay_s"], C.PULSE_DURATION_S, 0.0))

    @staticmethod
    def torque(phase_s, p):
        x = np.asarray(phase_s) - C.PULSE_DURATION_S
        return np.where(x >= 0.0, p["torque_Nm"] * np.exp(-np.maximum(x, 0.0) / p["decay_s"]), 0.0)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * exp(-(phi_p - 0.06 s) / {p['decay_s']:.6g} s) for "
                "phi_p >= 0.06 s (after the pulse's end), else 0; phi_p the time since the latest pulse began")


class WheelWestonBrake(OutsideForm):
    name = "wheel_weston_brake"
    half = "dev3"
    balance = "wheel_torque"
    depends_on = ("clutch_penetration",)
    description = ("a Weston-type load brake (as in a hoist): it clamps whenever the load side runs ahead of its "
                   "drive, i.e. while the jaw's angle difference D = alpha1 - alpha2 is negative (the far side "
                   "pushing or the jaw on its way there): -T*(1 - tanh(D/eps))/2*sign(Omega2) on the wheel")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T: the brake's torque when engaged"),
                  Param("engage_width_rad", "rad", (1e-4, 0.05), "eps: the angle difference over which it engages"))
    note = ("a gate on the jaw's angle difference (the argument of the penetration), centred mid-gap; it never drives "
            "the wheel")

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_JAW_ANGLE, K.XF_SIGMOID, -p["engage_width_rad"], 0.0, 0.0),
                 (K.XS_OMEGA2, K.XF_TANH, _SIGN_SPEED, 0.0, 0.0))

    @staticmethod
    def torque(jaw_angle_rad, omega2, p):
        return (-p["torque_Nm"] * 0.5 * (1.0 - np.tanh(np.asarray(jaw_angle_rad) / p["engage_width_rad"]))
                * np.tanh(np.asarray(omega2) / _SIGN_SPEED))

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * (1 - tanh(D / {p['engage_width_rad']:.6g} rad)) / 2 * "
                "sign(Omega2), D = alpha1 - alpha2 the jaw's angle difference (engaged while D < 0)")


class ClutchCardanError(OutsideForm):
    name = "clutch_cardan_error"
    half = "dev3"
    balance = "clutch_torque"
    depends_on = ("motor_angle", "clutch_penetration")
    description = ("a Cardan shaft at an angle between the motor and the jaw: its kinematic error turns the jaw's "
                   "drive half by e*sin(n*alpha1 + phi) against the motor (n = 2 for a Cardan joint, e = beta_u^2/4), "
                   "so the contact sees the angle difference D - e*sin(n*alpha1 + phi): the backlash's boundaries "
                   "move with the motor angle; the jaw's torque reaches the motor times 1 + n*e*cos(n*alpha1 + phi)")
    parameters = (Param("amplitude_rad", "rad", (0.0, 0.02), "e (8e-4 rad: a joint at 3.2 degrees)"),
                  Param("order", "per revolution", (1, 3), "n (2: a Cardan joint; 1: a parallel offset)", "int"),
                  _PHASE)
    note = ("not an additive torque: the contact's geometry moves (the penetration is D - beta - e*sin(...)); the "
            "recorded angle difference is alpha1 - alpha2 without it")

    def apply(self, b, p):
        if b.P[K.P_TEA] != 0.0:
            raise ValueError(f"{self.name}: a second transmission error in one recording; allowed: one")
        b.P[K.P_TEA], b.P[K.P_TEN], b.P[K.P_TEP] = p["amplitude_rad"], float(p["order"]), p["phase_rad"]

    def law(self, p):
        return (f"clutch: the jaw's angle difference is D - {p['amplitude_rad']:.6g} rad * sin({p['order']}*alpha1 + "
                f"{p['phase_rad']:.6g}) (penetration and its rate from it); the motor feels the jaw's torque times "
                f"1 + {p['order'] * p['amplitude_rad']:.6g} * cos({p['order']}*alpha1 + {p['phase_rad']:.6g})")


class MassPneumaticHoldback(OutsideForm):
    name = "mass_pneumatic_holdback"
    half = "dev3"
    balance = "mass_force"
    depends_on = ("load_pulse",)
    description = ("a pneumatic hold-back cylinder on the carriage, switched by the press's valve: it follows the "
                   "stroke a transport delay d later and reaches its force with a lag tau, "
                   "-F*[r(phi_p - d) - r(phi_p - d - D)], r(x) = 1 - exp(-x/tau) for x >= 0 (else 0), D = 60 ms")
    parameters = (Param("force_N", "N", (0.0, 200.0), "F"),
                  Param("delay_s", "s", (0.0, 0.1), "d: the valve's and the line's transport delay"),
                  Param("lag_s", "s", (1e-4, 0.05), "tau: the cylinder's filling time constant"))
    note = "both edges of the pulse, delayed; within a pulse period (the tail of one stroke is gone before the next)"

    def apply(self, b, p):
        d, tau = p["delay_s"], p["lag_s"]
        add_term(b, "mass_force", -p["force_N"], (K.XS_PULSE_PHASE, K.XF_RISE_AFTER, tau, d, 0.0))
        add_term(b, "mass_force", p["force_N"], (K.XS_PULSE_PHASE, K.XF_RISE_AFTER, tau, d + C.PULSE_DURATION_S, 0.0))

    @staticmethod
    def force(phase_s, p):
        def r(x):
            return np.where(x >= 0.0, 1.0 - np.exp(-np.maximum(x, 0.0) / p["lag_s"]), 0.0)
        x = np.asarray(phase_s) - p["delay_s"]
        return -p["force_N"] * (r(x) - r(x - C.PULSE_DURATION_S))

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * [r(phi_p - {p['delay_s']:.6g} s) - r(phi_p - "
                f"{p['delay_s'] + C.PULSE_DURATION_S:.6g} s)], r(x) = 1 - exp(-x / {p['lag_s']:.6g} s) for x >= 0, "
                "else 0; phi_p the time since the latest pulse began")


class A2TransmitterDeadband(OutsideForm):
    name = "a2_transmitter_deadband"
    half = "dev3"
    stage = "sensor"
    order = 1                      # the transmitter, after the sensing element (and its filter)
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("the a2 transmitter reports by exception: it sends a new value only when the reading differs from "
                   "the last value sent by more than the deadband, and holds the last one otherwise (a memory: "
                   "the same input reads differently rising and falling)")
    parameters = (Param("deadband_m_s2", "m/s^2", (0.0, 10.0), "delta (0: every value is sent)"),)
    note = "held steps of up to delta, their timing set by the signal's own history"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.reported(sig["a2"], p["deadband_m_s2"])

    @staticmethod
    def reported(a, delta):
        if delta <= 0.0:
            return np.asarray(a, dtype=np.float64)
        x = np.asarray(a, dtype=np.float64).tolist()
        out = np.empty(len(x))
        last = x[0]
        for k, v in enumerate(x):
            if abs(v - last) > delta:
                last = v
            out[k] = last
        return out

    def law(self, p):
        return (f"a2 sensor = the last value sent, a new one sent when |a2 - last| > {p['deadband_m_s2']:.6g} m/s^2 "
                "(report by exception)")


class MotorSpeedRelayLoad(OutsideForm):
    name = "motor_speed_relay_load"
    half = "dev3"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("a PLC switches an auxiliary consumer (a pump, a blower) onto the motor shaft when the motor runs "
                   "fast, above Omega_on, and off again below Omega_off < Omega_on (a two-point switch with "
                   "hysteresis, scanned every 0.2 ms): a load T while it is on")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("on_above_rad_s", "rad/s", (100.0, 170.0), "Omega_on"),
                  Param("off_below_rad_s", "rad/s", (100.0, 170.0), "Omega_off (below Omega_on)"))
    note = "a memory in the drive: at the same speed the load is on or off depending on where the speed came from"

    def apply(self, b, p):
        set_relay(b, self.name, K.XS_OMEGA1, p["on_above_rad_s"], p["off_below_rad_s"], "on_above_rad_s",
                  "off_below_rad_s")
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_RELAY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * s, s switched to 1 when Omega1 rises above "
                f"{p['on_above_rad_s']:.6g} rad/s and to 0 when it falls below {p['off_below_rad_s']:.6g} rad/s "
                "(checked every 0.2 ms)")


class A2StrokeRinging(OutsideForm):
    name = "a2_stroke_ringing"
    half = "dev3"
    stage = "sensor"
    order = 0                      # the sensing element: it senses the frame's vibration too
    uses_states = True
    balance = "sensor"
    depends_on = ("load_pulse",)
    description = ("each press stroke rings the frame the a2 sensor stands on; the sensor reads the frame's decaying "
                   "vibration: a2 += A*exp(-phi_p/tau)*sin(2*pi*f*phi_p), phi_p the time since the latest pulse began")
    parameters = (Param("amplitude_m_s2", "m/s^2", (0.0, 50.0), "A"),
                  Param("frequency_hz", "Hz", (10.0, 2000.0), "f: the frame's mode"),
                  Param("decay_s", "s", (1e-3, 0.2), "tau"))

    def apply_signal(self, sig, p, t, fs, states=None):
        ph = pulse_phase_s(t, states["pulse"])
        sig["a2"] = sig["a2"] + p["amplitude_m_s2"] * np.exp(-ph / p["decay_s"]) * np.sin(
            2.0 * math.pi * p["frequency_hz"] * ph)

    def law(self, p):
        return (f"a2 sensor += {p['amplitude_m_s2']:.6g} m/s^2 * exp(-phi_p / {p['decay_s']:.6g} s) * "
                f"sin(2*pi*{p['frequency_hz']:.6g} Hz * phi_p), phi_p the time since the latest pulse began")


FORM_CLASSES = (MotorAccumulatorRecharge, WheelWestonBrake, ClutchCardanError, MassPneumaticHoldback,
                A2TransmitterDeadband, MotorSpeedRelayLoad, A2StrokeRinging)
