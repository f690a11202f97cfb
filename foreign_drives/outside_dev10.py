"""Outside mechanisms, tenth DEVELOPMENT half (issue 31 part 4, set 10): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first nine sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev9`, :mod:`outside_sealed9`) have, with their laws in
the open. The tenth sealed half is :mod:`outside_sealed10`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (clutch
torque, sensor, wheel torque, mass force); in that order, the odd ones (1st, 3rd, ...) are this development half, the
even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed10` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 mass force). About half of the fourteen are plain memoryless laws of new kinds, half have a
memory or a limit of their own (here: 1, 5, 9, 13 memoryless; 3, 7, 11 with a memory). Written before any diagnose,
analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation against the
clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the time since each stroke's start as a DAMPED RING: the press's crank train rings torsionally
   at each strike and the ringing torque reaches the motor's shaft: A*exp(-phi_p/tau)*sin(2*pi*f*phi_p) while the pulse
   is on, phi_p the time since the pulse began (a decaying oscillation locked to the stroke's start, in a balance: the
   catalogue's pulse is a rectangle, the third set's accumulator recharge decays from the falling edge without
   ringing, the third set's ringing is a2's reading of the frame, not a torque);
3. wheel torque x the wheel speed through a THERMAL CUT-OUT: an eddy-current brake on the wheel, -c*Omega2 while on,
   heats with its power c*Omega2^2 and cools with tau; a bimetal switch cuts it out when its heat passes H_off and
   back in below H_on < H_off (heat' = on*c*Omega2^2 - heat/tau, scanned every 0.2 ms): a relaxation oscillation of
   its own period, set by the heat's thresholds (a thermal integrator behind a hysteresis switch that it drives
   itself);
5. clutch torque x the jaw's angle difference TIMES the load pulse: during each stroke the press's valve also
   energises a magnet that presses an anti-rattle leaf spring across the jaw halves: pulse*k*D from the motor to the
   wheel, D the jaw's angle difference from the gap's centre, in the gap and in contact (a stiffness across the
   backlash switched by the process: neither always there nor a damping);
7. mass force x the spring extension through an IMPULSE (LATCHING) RELAY: a rail brake on the carriage switched by an
   impulse relay; a limit switch on the spring's bracket pulses its coil each time the extension rises past z_on
   (re-armed once it has fallen below z_off < z_on), and each pulse toggles the brake: -F while on (a binary divider
   of the drive's own events, scanned every 0.2 ms: a sub-harmonic made by the state, not by the stroke count);
9. a1 sensor x a1 through a mu-LAW COMPANDING codec: a1's rotating telemetry sends 8-bit mu-law codes (mu = 255, full
   scale A): c = round(127*sign(a)*ln(1 + mu*min(|a|, A)/A)/ln(1 + mu)), y = sign(c)*A*((1 + mu)^(|c|/127) - 1)/mu (a
   non-uniform quantiser: fine steps near zero, coarse ones near full scale);
11. clutch torque x the jaw's slip speed through a LAG: a viscous coupling beside the jaw filled with a viscoelastic
    (silicone) fluid: its torque c*m from the motor to the wheel at all times, m the slip Omega1 - Omega2 relaxed with
    the fluid's time tau (a first-order lag, advanced every 0.2 ms from m = the slip at the run-in's start; the first
    set's gap drag is the instantaneous viscous law);
13. wheel torque x the TIME SINCE THE JAW'S CONTACT BEGAN: a holding brake on the wheel interlocked with the coupling:
    a proximity switch across the jaw energises it while the jaw is in contact (either face), its field rising with
    the coil's L/R: -T*(1 - exp(-t_c/tau)), t_c the time since the contact began from the gap, 0 in the gap (a brake
    gated and timed by the jaw's own contact).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed;
no diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2
0.0115 at 5 N*m, scaled once x6.54 (32.7 N*m) -> 0.0687; 3 a2 0.299; 5 a2 0.0392 at 60 N*m/rad, scaled once x1.91 (115
N*m/rad) -> 0.0683; 7 a2 0.0460 at 3 N, scaled once x1.63 (4.89 N) -> 0.147; 9 a1 0.309; 11 a2 0.0301 at 1 N*m*s/rad,
scaled once x2.49 -> 0.0696; 13 a2 0.118 (docs/foreign_drives.md "The tenth set"). Before it, a 0.4 s run of each row
only checked that it simulates.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory",
the tenth set's kinds in _memory_scan10), as in the fourth to ninth sets; the memory starts afresh at the run-in's first
scan, 2 s before sample 0.
"""
from __future__ import annotations

import math

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 1. motor load moment x the time since each stroke's start as a damped ring
class MotorStrokeTorsionalRing(OutsideForm):
    name = "motor_stroke_torsional_ring"
    half = "dev10"
    balance = "motor_load_moment"
    depends_on = ("load_pulse",)
    description = ("the press's crank train rings torsionally at each strike and the ringing reaches the motor's shaft: "
                   "A*exp(-phi_p/tau)*sin(2*pi*f*phi_p) on the motor's load while the pulse is on, phi_p the time since "
                   "the pulse began")
    parameters = (Param("amplitude_Nm", "N*m", (0.0, 50.0), "A"),
                  Param("frequency_hz", "Hz", (1.0, 2000.0), "f"),
                  Param("decay_time_s", "s", (1e-4, 1.0), "tau"))
    note = "a decaying oscillation locked to the stroke's start, in the motor's balance (not a reading of the frame)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["amplitude_Nm"], (K.XS_PULSE_AGE, K.XF_DECAY_AFTER, p["decay_time_s"], 0.0, 0.0),
                 (K.XS_PULSE_AGE, K.XF_SIN, 2.0 * math.pi * p["frequency_hz"], 0.0, 0.0))

    @staticmethod
    def torque(phase_s, pulse_on, p):
        x = np.asarray(phase_s, dtype=np.float64)
        return (p["amplitude_Nm"] * np.asarray(pulse_on, dtype=np.float64) * np.exp(-x / p["decay_time_s"])
                * np.sin(2.0 * math.pi * p["frequency_hz"] * x))

    def law(self, p):
        return (f"motor load moment += {p['amplitude_Nm']:.6g} N*m * exp(-phi_p/{p['decay_time_s']:.6g} s) * sin(2*pi*"
                f"{p['frequency_hz']:.6g} Hz*phi_p) while the pulse is on, phi_p the time since the pulse began")

    def plugin(self, p):
        return _plugin("MotorStrokeTorsionalRing", self.name, "motor_load_moment_pu", self.description, [
            ("amplitude_pu", "p.u.", (0.0, 2.5), "A / T_b (T_b = 20 N*m)"),
            ("frequency_hz", "Hz", (0.0, 2000.0), "f"),
            ("decay_rate_per_s", "1/s", (0.0, 10000.0), "1/tau")],
            "pulse_time_s, pulse_off_time_s, amplitude_pu, frequency_hz, decay_rate_per_s",
            "where(pulse_off_time_s > pulse_time_s, amplitude_pu * exp(-fmin(pulse_time_s * decay_rate_per_s, 600.0)) * "
            "sin(6.283185307179586 * frequency_hz * pulse_time_s), 0.0)", "exp, fmin, sin, where")


# 3. wheel torque x the wheel speed through a thermal cut-out
class WheelThermalCutoutBrake(OutsideForm):
    name = "wheel_thermal_cutout_brake"
    half = "dev10"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("an eddy-current brake on the wheel, -c*Omega2 while on, heats with its power c*Omega2^2 and cools "
                   "with tau; a bimetal switch cuts it out when its heat H passes H_off and back in below H_on: H += "
                   "dt*(on*c*Omega2^2 - H/tau), scanned every 0.2 ms (H = 0, on, at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c"),
                  Param("cooling_time_s", "s", (1e-3, 100.0), "tau"),
                  Param("off_above_J", "J", (1.0, 1e5), "H_off"),
                  Param("on_below_J", "J", (0.0, 1e5), "H_on (< H_off)"))
    note = "a heat integrator behind a hysteresis switch it drives itself: a relaxation oscillation of its own period"

    def apply(self, b, p):
        c = p["coefficient_Nm_s_per_rad"]
        set_memory(b, self.name, K.MK_THERMOSTAT, K.XS_OMEGA2, c, p["cooling_time_s"], p["off_above_J"])
        set_extra(b, p["on_below_J"])
        add_term(b, "wheel_torque", -c, (K.XS_OMEGA2, K.XF_X, 0.0, 0.0, 0.0), (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def switched(omega2_at_scans, p, dt, on=1.0, heat_J=0.0):
        """(on, heat) after each scan from the wheel speed at the scans' starts; ``on``, ``heat_J``: the state at the
        first scan (the run-in's start: on, 0 J)."""
        w = np.asarray(omega2_at_scans, dtype=np.float64).tolist()
        c, tau = p["coefficient_Nm_s_per_rad"], p["cooling_time_s"]
        on_out, h_out = np.empty(len(w)), np.empty(len(w))
        h = heat_J
        for i, x in enumerate(w):
            if i:
                h = h + dt * (on * c * x * x - h / tau)
                if on and h > p["off_above_J"]:
                    on = 0.0
                elif not on and h < p["on_below_J"]:
                    on = 1.0
            on_out[i], h_out[i] = on, h
        return on_out, h_out

    def law(self, p):
        c = p["coefficient_Nm_s_per_rad"]
        return (f"wheel torque += -{c:.6g} N*m*s/rad * Omega2 * on, on -> 0 when H > {p['off_above_J']:.6g} J, -> 1 when "
                f"H < {p['on_below_J']:.6g} J, H += dt*(on*{c:.6g}*Omega2^2 - H/{p['cooling_time_s']:.6g} s) every 0.2 ms")


# 5. clutch torque x the jaw's angle difference times the load pulse
class ClutchStrokeLeafSpring(OutsideForm):
    name = "clutch_stroke_leaf_spring"
    half = "dev10"
    balance = "clutch_torque"
    depends_on = ("load_pulse", "clutch_penetration")
    description = ("during each stroke the press's valve energises a magnet that presses an anti-rattle leaf spring "
                   "across the jaw halves: pulse*k*D from the motor to the wheel, D the jaw's angle difference from the "
                   "gap's centre, in the gap and in contact")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 1000.0), "k"),)
    note = "a stiffness across the backlash switched by the process: neither always there nor a damping"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["stiffness_Nm_per_rad"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_ANGLE, K.XF_X, 0.0, 0.0, 0.0))

    @staticmethod
    def torque(d, pulse_on, p):
        return p["stiffness_Nm_per_rad"] * np.asarray(pulse_on, dtype=np.float64) * np.asarray(d, dtype=np.float64)

    def law(self, p):
        return f"clutch torque += {p['stiffness_Nm_per_rad']:.6g} N*m/rad * pulse * D, D the jaw's angle difference"


# 7. mass force x the spring extension through an impulse (latching) relay
class MassImpulseRelayBrake(OutsideForm):
    name = "mass_impulse_relay_brake"
    half = "dev10"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("a rail brake on the carriage switched by an impulse relay: each time the spring's extension rises "
                   "past z_on (re-armed once below z_off) its limit switch toggles the brake; -F while on (scanned every "
                   "0.2 ms; off at the run-in's start, armed if z < z_off there)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("on_above_m", "m", (0.0, 1.0), "z_on"),
                  Param("rearm_below_m", "m", (0.0, 1.0), "z_off (< z_on)"))
    note = "a binary divider of the drive's own events: a sub-harmonic made by the state, not by the stroke count"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_TOGGLE, K.XS_SPRING_EXTENSION, p["on_above_m"], p["rearm_below_m"])
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def toggled(z_at_scans, p, on=0.0, armed=None):
        """The brake's state after each scan from the extension at the scans' starts; ``on``, ``armed``: the state at
        the first scan (the run-in's start: off, armed if z < z_off)."""
        z = np.asarray(z_at_scans, dtype=np.float64).tolist()
        out = np.empty(len(z))
        armed = z[0] < p["rearm_below_m"] if armed is None else armed
        for i, x in enumerate(z):
            if i:
                if armed and x > p["on_above_m"]:
                    on, armed = 1.0 - on, False
                elif not armed and x < p["rearm_below_m"]:
                    armed = True
            out[i] = on
        return out

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N while on; on toggles each time z rises past {p['on_above_m']:.6g} m "
                f"(re-armed below {p['rearm_below_m']:.6g} m), z the spring's extension, scanned every 0.2 ms")


# 9. a1 sensor x a1 through a mu-law companding codec
class A1MuLawCodec(OutsideForm):
    name = "a1_mu_law_codec"
    half = "dev10"
    stage = "sensor"
    order = 1                      # the telemetry's codec, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("a1's rotating telemetry sends 8-bit mu-law codes (mu = 255, full scale A): c = round(127*sign(a)*"
                   "ln(1 + mu*min(|a|, A)/A)/ln(1 + mu)), y = sign(c)*A*((1 + mu)^(|c|/127) - 1)/mu")
    parameters = (Param("full_scale_m_s2", "m/s^2", (1.0, 5000.0), "A"),)
    note = "a non-uniform quantiser: fine steps near zero, coarse ones near full scale"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], p)

    @staticmethod
    def read(a, p):
        a = np.asarray(a, dtype=np.float64)
        full, mu = p["full_scale_m_s2"], 255.0
        c = np.round(127.0 * np.sign(a) * np.log1p(mu * np.minimum(np.abs(a), full) / full) / math.log1p(mu))
        return np.sign(c) * full * ((1.0 + mu) ** (np.abs(c) / 127.0) - 1.0) / mu

    def law(self, p):
        return (f"a1 sensor = an 8-bit mu-law codec (mu = 255) of full scale {p['full_scale_m_s2']:.6g} m/s^2 on a1: c = "
                "round(127*sign(a1)*ln(1 + mu*min(|a1|, A)/A)/ln(1 + mu)), y = sign(c)*A*((1 + mu)^(|c|/127) - 1)/mu")


# 11. clutch torque x the jaw's slip speed through a lag
class ClutchViscoelasticCoupling(OutsideForm):
    name = "clutch_viscoelastic_coupling"
    half = "dev10"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a viscous coupling beside the jaw filled with a viscoelastic (silicone) fluid: c*m from the motor to "
                   "the wheel at all times, m the slip Omega1 - Omega2 relaxed with the fluid's time tau (m -> s + (m - "
                   "s)*exp(-dt/tau) every 0.2 ms, m = s at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),
                  Param("relaxation_time_s", "s", (1e-4, 1.0), "tau"))
    note = "a first-order lag of the slip between the halves: the first set's gap drag is its instantaneous limit"

    def apply(self, b, p):
        tau = p["relaxation_time_s"]
        set_memory(b, self.name, K.MK_LAG, K.XS_JAW_SPEED, tau, tau, 0.0)
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 nonperiodic=True)

    @staticmethod
    def relaxed(slip_at_scans, p, dt):
        s = np.asarray(slip_at_scans, dtype=np.float64).tolist()
        k = math.exp(-dt / p["relaxation_time_s"])
        out, m = np.empty(len(s)), s[0]
        for i, x in enumerate(s):
            if i:
                m = x + (m - x) * k
            out[i] = m
        return out

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * m, m -> (Omega1 - Omega2) with time "
                f"constant {p['relaxation_time_s']:.6g} s, every 0.2 ms")


# 13. wheel torque x the time since the jaw's contact began
class WheelContactInterlockBrake(OutsideForm):
    name = "wheel_contact_interlock_brake"
    half = "dev10"
    balance = "wheel_torque"
    depends_on = ("clutch_penetration", "time")
    description = ("a holding brake on the wheel interlocked with the coupling: energised while the jaw is in contact "
                   "(either face), its field rising with the coil's L/R: -T*(1 - exp(-t_c/tau)), t_c the time since the "
                   "contact began from the gap; 0 in the gap")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("rise_time_s", "s", (1e-4, 1.0), "tau"))
    note = "a brake gated and timed by the jaw's own contact"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_CONTACT_AGE, K.XF_RISE, p["rise_time_s"], 0.0, 0.0))

    @staticmethod
    def torque(contact_age_s, p):
        x = np.asarray(contact_age_s, dtype=np.float64)
        return np.where(x >= 0.0, -p["torque_Nm"] * (1.0 - np.exp(-np.maximum(x, 0.0) / p["rise_time_s"])), 0.0)

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * (1 - exp(-t_c/{p['rise_time_s']:.6g} s)) in contact, t_c "
                "the time since the contact began from the gap; 0 in the gap")


FORM_CLASSES = (MotorStrokeTorsionalRing, WheelThermalCutoutBrake, ClutchStrokeLeafSpring, MassImpulseRelayBrake,
                A1MuLawCodec, ClutchViscoelasticCoupling, WheelContactInterlockBrake)
