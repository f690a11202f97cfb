"""Outside mechanisms, eleventh DEVELOPMENT half (issue 31 part 4, set 11): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first ten sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev10`, :mod:`outside_sealed10`) have, with their laws in
the open. The eleventh sealed half is :mod:`outside_sealed11`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (mass
force, sensor, wheel torque, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this development half, the
even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the even numbers are in
:mod:`outside_sealed11` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force,
10 sensor, 12 sensor, 14 clutch torque). About half of the fourteen are plain memoryless laws of new kinds, half have a
memory or a limit of their own (here: 1, 5, 7, 13 memoryless; 3, 9, 11 with a memory). Written before any diagnose,
analyze or proposal ran on them (the commit history is the proof); each strength is set by one simulation against the
clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the WHEEL speed beyond a limit (a CROSS-SHAFT governor): a runaway guard; a centrifugal governor
   on the wheel shaft pulls, by a rod, a band brake on the motor's shaft when the load side overspeeds: K*max(0, Omega2 -
   Omega_0) on the motor's load (the motor braked by the other shaft's speed: every earlier motor-load term reads the
   motor's own states, the pulse, the spring, the carriage or the contact torque, none the wheel speed);
3. wheel torque x the wheel speed through an OFF-DELAY timer: an overspeed brake on the wheel that a PLC switches on
   whenever Omega2 exceeds Omega_trip (scanned every 0.2 ms) and releases only once Omega2 has stayed at or below it for
   T_off (a TOF timer, retriggered by every scan above): -T while on (the seventh set's guard is an ON-delay, which
   delays the switching on; this one holds the brake on after the cause has gone);
5. clutch torque x the jaw's slip speed, ONE-WAY: an overrunning (sprag) clutch in series with a viscous coupling,
   beside the jaw: it passes c*max(0, Omega1 - Omega2) from the motor to the wheel while the motor half runs faster and
   freewheels while the wheel half overruns (a half-wave law of the slip: the first set's gap drag is two-way, the
   second set's stroke coupling is switched by the pulse);
7. mass force x the mass speed through a DEAD-BAND (three-level) switch, memoryless: a linear drive on the carriage
   under a two-contact speed switch: it pushes the carriage with +F below v_ref - b, brakes it with -F above v_ref + b
   and does nothing in between, each contact's edge smoothed over w: -F*(S((v - v_ref - b)/w) + S((v - v_ref + b)/w) -
   1), S(q) = (1 + tanh(q))/2 (a ternary law of the speed: neither a threshold's excess nor a relay with a memory);
9. a2 sensor x a2's own past through a MAINS NOTCH FILTER: a2's data-acquisition module has its 50 Hz notch switched on:
   a second-order IIR notch at f_0 of quality Q (y'' + (w0/Q)*y' + w0^2*y = a'' + w0^2*a, discretised as
   scipy.signal.iirnotch at the recorder's 50 kHz), started at rest on the pre-roll's first sample (a band-stop: the
   catalogue's sensor filters are low-passes, the third set's AC coupling is a high-pass);
11. mass force x the spring extension's change SINCE EACH STROKE'S START through a POLYTROPIC gas law: a pneumatic
    cushion cylinder between the carriage and the spring's cable; the press's valve closes its ports at each stroke's
    start, trapping its air column of length L0, so until the next stroke it pushes the carriage along x with F0*((L0/(L0 -
    dz))^gamma - 1), dz = z - z_k, z_k the extension at the first 0.2 ms scan of the latest pulse (a stiffness whose
    zero is re-set by every stroke, hardening as the air is squeezed: the fifth set's dancer holds a sample of z, not a
    spring from it);
13. wheel torque x the time as a RANDOM STAIRCASE: the uncoiler upstream hands the strip's tension down through its own
    controller, which moves to a new level at each of its updates, every T_s seconds: T*u_k, k = floor((t - t_0)/T_s),
    u_k pseudo-random in [-1, 1) of k and a seed (a piecewise-constant random torque locked to no shaft, no stroke and
    no event of this drive: the tenth set's chain pattern is locked to the wheel angle, the sixth set's blanks to the
    stroke count, the fourth set's kicker is a Poisson train of pulses).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed;
no diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2
0.0852; 3 a2 0.0867; 5 a2 0.0521; 7 a2 0.161; 9 a2 0.104; 11 a2 0.0552; 13 a2 0.148 -- each at its a-priori strength,
none scaled (docs/foreign_drives.md "The eleventh set"). Before it, a 0.4 s run of each row only checked that it
simulates.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle). Memory elements (one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py "memory"),
as in the fourth to tenth sets; the memory starts afresh at the run-in's first scan, 2 s before sample 0.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev import _plugin
from .outside_dev4 import set_memory


# 1. motor load moment x the wheel speed beyond a limit (a cross-shaft governor)
class MotorWheelRunawayGovernor(OutsideForm):
    name = "motor_wheel_runaway_governor"
    half = "dev11"
    balance = "motor_load_moment"
    depends_on = ("wheel_speed",)
    description = ("a runaway guard: a centrifugal governor on the wheel shaft pulls, by a rod, a band brake on the "
                   "motor's shaft when the load side overspeeds: K*max(0, Omega2 - Omega_0) on the motor's load")
    parameters = (Param("gain_Nm_s_per_rad", "N*m*s/rad", (0.0, 50.0), "K"),
                  Param("set_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_0"))
    note = "the motor braked by the other shaft's speed (a cross-shaft law)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["gain_Nm_s_per_rad"],
                 (K.XS_OMEGA2, K.XF_EXCESS_POWER, p["set_speed_rad_s"], 1.0, 0.0))

    @staticmethod
    def torque(omega2, p):
        return p["gain_Nm_s_per_rad"] * np.maximum(0.0, np.asarray(omega2, dtype=np.float64) - p["set_speed_rad_s"])

    def law(self, p):
        return (f"motor load moment += {p['gain_Nm_s_per_rad']:.6g} N*m*s/rad * max(0, Omega2 - "
                f"{p['set_speed_rad_s']:.6g} rad/s), Omega2 the wheel speed")

    def plugin(self, p):
        return _plugin("MotorWheelRunawayGovernor", self.name, "motor_load_moment_pu", self.description, [
            ("gain_pu_s_per_rad", "p.u.*s/rad", (0.0, 2.5), "K / T_b (T_b = 20 N*m)"),
            ("set_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_0")],
            "omega2, gain_pu_s_per_rad, set_speed_rad_s", "gain_pu_s_per_rad * fmax(0.0, omega2 - set_speed_rad_s)",
            "fmax")


# 3. wheel torque x the wheel speed through an off-delay timer
class WheelOffDelayOverspeedBrake(OutsideForm):
    name = "wheel_off_delay_overspeed_brake"
    half = "dev11"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("an overspeed brake on the wheel: a PLC switches it on at every 0.2 ms scan with Omega2 above "
                   "Omega_trip and releases it once Omega2 has stayed at or below Omega_trip for T_off (a TOF timer, "
                   "retriggered): -T while on (on at the run-in's start if Omega2 > Omega_trip there)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("trip_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_trip"),
                  Param("off_delay_s", "s", (2e-4, 1.0), "T_off"))
    note = "the brake held on after its cause has gone (an off-delay), not delayed on"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_OFF_DELAY, K.XS_OMEGA2, p["trip_speed_rad_s"], p["off_delay_s"])
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def held(omega2_at_scans, p, dt, on=None, since_s=0.0):
        """The brake's state after each scan from the wheel speed at the scans' starts; ``on``: the state at the first
        scan (None: the run-in's start, on if above the trip speed there); ``since_s``: the time from the last scan
        above the trip speed to the first scan."""
        w = np.asarray(omega2_at_scans, dtype=np.float64).tolist()
        trip, hold = p["trip_speed_rad_s"], p["off_delay_s"]
        out = np.empty(len(w))
        on = float(w[0] > trip) if on is None else on
        last = -since_s
        for i, x in enumerate(w):
            if i:
                if x > trip:
                    on, last = 1.0, i * dt
                elif on and i * dt - last >= hold - 1e-12:
                    on = 0.0
            out[i] = on
        return out

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * on; on -> 1 at a scan with Omega2 > "
                f"{p['trip_speed_rad_s']:.6g} rad/s, -> 0 once {p['off_delay_s']:.6g} s have passed since the last "
                "such scan (every 0.2 ms)")


# 5. clutch torque x the jaw's slip speed, one-way
class ClutchOverrunningViscousCoupling(OutsideForm):
    name = "clutch_overrunning_viscous_coupling"
    half = "dev11"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an overrunning (sprag) clutch in series with a viscous coupling beside the jaw: c*max(0, Omega1 - "
                   "Omega2) from the motor to the wheel while the motor half runs faster, nothing while the wheel half "
                   "overruns; in the gap and in contact")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 20.0), "c"),)
    note = "a half-wave law of the slip: two-way viscous drag is the first set's"

    def apply(self, b, p):
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_JAW_SPEED, K.XF_EXCESS_POWER, 0.0, 1.0, 0.0))

    @staticmethod
    def torque(slip, p):
        return p["coefficient_Nm_s_per_rad"] * np.maximum(0.0, np.asarray(slip, dtype=np.float64))

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * max(0, Omega1 - Omega2), in the gap "
                "and in contact")


# 7. mass force x the mass speed through a dead-band (three-level) switch
class MassDeadBandSpeedSwitch(OutsideForm):
    name = "mass_dead_band_speed_switch"
    half = "dev11"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("a linear drive on the carriage under a two-contact speed switch: +F below v_ref - b, -F above "
                   "v_ref + b, nothing between, each contact's edge smoothed over w: -F*(S((v - v_ref - b)/w) + S((v - "
                   "v_ref + b)/w) - 1), S(q) = (1 + tanh(q))/2")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("reference_speed_m_s", "m/s", (0.0, 50.0), "v_ref"),
                  Param("half_band_m_s", "m/s", (0.0, 1.0), "b"),
                  Param("edge_width_m_s", "m/s", (1e-4, 0.1), "w"))
    note = "a ternary law of the speed, memoryless: neither a threshold's excess nor a relay"

    def apply(self, b, p):
        f, v0, hb, w = p["force_N"], p["reference_speed_m_s"], p["half_band_m_s"], p["edge_width_m_s"]
        add_term(b, "mass_force", -f, (K.XS_MASS_SPEED, K.XF_SIGMOID, w, v0 + hb, 0.0))
        add_term(b, "mass_force", -f, (K.XS_MASS_SPEED, K.XF_SIGMOID, w, v0 - hb, 0.0))
        add_term(b, "mass_force", f)

    @staticmethod
    def force(v, p):
        v = np.asarray(v, dtype=np.float64)
        f, v0, hb, w = p["force_N"], p["reference_speed_m_s"], p["half_band_m_s"], p["edge_width_m_s"]
        s1, s2 = 0.5 * (1.0 + np.tanh((v - v0 - hb) / w)), 0.5 * (1.0 + np.tanh((v - v0 + hb) / w))
        return -f * (s1 + s2 - 1.0)

    def law(self, p):
        f, v0, hb, w = p["force_N"], p["reference_speed_m_s"], p["half_band_m_s"], p["edge_width_m_s"]
        return (f"mass force += -{f:.6g} N * (S((v - {v0 + hb:.6g} m/s)/{w:.6g} m/s) + S((v - {v0 - hb:.6g} m/s)/"
                f"{w:.6g} m/s) - 1), S(q) = (1 + tanh(q))/2, v the mass speed")

    def plugin(self, p):
        return _plugin("MassDeadBandSpeedSwitch", self.name, "mass_force_N", self.description, [
            ("force_N", "N", (0.0, 100.0), "F"), ("reference_speed_m_s", "m/s", (0.0, 50.0), "v_ref"),
            ("half_band_m_s", "m/s", (0.0, 1.0), "b"), ("edge_width_m_s", "m/s", (1e-4, 0.1), "w")],
            "xdot, force_N, reference_speed_m_s, half_band_m_s, edge_width_m_s",
            "-force_N * (1.0 - 1.0 / (exp(fmin(2.0 * (xdot - reference_speed_m_s - half_band_m_s) / edge_width_m_s, "
            "600.0)) + 1.0) - 1.0 / (exp(fmin(2.0 * (xdot - reference_speed_m_s + half_band_m_s) / edge_width_m_s, "
            "600.0)) + 1.0))", "exp, fmin")


# 9. a2 sensor x a2's own past through a mains notch filter
class A2MainsNotchFilter(OutsideForm):
    name = "a2_mains_notch_filter"
    half = "dev11"
    stage = "sensor"
    order = 1                      # the module's digital filter, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("mass_acceleration",)
    description = ("a2's data-acquisition module has its mains notch switched on: a second-order IIR notch at f_0 of "
                   "quality Q (scipy.signal.iirnotch at the recorder's rate), started at rest on the pre-roll's first "
                   "sample")
    parameters = (Param("notch_hz", "Hz", (1.0, 5000.0), "f_0"), Param("quality", "-", (0.1, 100.0), "Q"))
    note = "a band-stop: the catalogue's sensor filters are low-passes"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a2"] = self.read(sig["a2"], p, fs)

    @staticmethod
    def read(a, p, fs):
        from scipy.signal import iirnotch, lfilter, lfilter_zi
        x = np.asarray(a, dtype=np.float64)
        b, aa = iirnotch(p["notch_hz"], p["quality"], fs)
        y, _ = lfilter(b, aa, x, zi=lfilter_zi(b, aa) * x[0])
        return y

    def law(self, p):
        return (f"a2 sensor = a second-order IIR notch at {p['notch_hz']:.6g} Hz of quality {p['quality']:.6g} "
                "(scipy.signal.iirnotch at 50 kHz) of a2, at rest on the pre-roll's first sample")


# 11. mass force x the spring extension's change since each stroke's start through a polytropic gas law
class MassStrokeTrappedAirCushion(OutsideForm):
    name = "mass_stroke_trapped_air_cushion"
    half = "dev11"
    balance = "mass_force"
    depends_on = ("spring_extension", "load_pulse")
    description = ("a pneumatic cushion cylinder between the carriage and the spring's cable; the press's valve closes "
                   "its ports at each stroke's start, trapping an air column of length L0: until the next stroke it "
                   "pushes the carriage along x with F0*((L0/(L0 - dz))^gamma - 1), dz = z - z_k, z_k the extension at "
                   "the first 0.2 ms scan of the latest pulse (dz taken at most 0.9*L0: the cylinder's stop)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F0 = p0*A"),
                  Param("column_m", "m", (1e-3, 10.0), "L0"),
                  Param("exponent", "-", (1.0, 1.67), "gamma"))
    note = "a stiffness whose zero is re-set by every stroke, hardening as the air is squeezed"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_STROKE_SAMPLE, K.XS_SPRING_EXTENSION, 0.0)
        add_term(b, "mass_force", p["force_N"],
                 (K.XS_MEMORY_EXCESS, K.XF_POLYTROPIC, p["column_m"], p["exponent"], 0.0), nonperiodic=True)

    @staticmethod
    def force(dz, p):
        q = np.minimum(np.asarray(dz, dtype=np.float64) / p["column_m"], 0.9)
        return p["force_N"] * ((1.0 / (1.0 - q)) ** p["exponent"] - 1.0)

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * (({p['column_m']:.6g} m/({p['column_m']:.6g} m - dz))^"
                f"{p['exponent']:.6g} - 1), dz = z - z_k, z_k the spring's extension at the first 0.2 ms scan of the "
                "latest load pulse")


# 13. wheel torque x the time as a random staircase
class WheelUpstreamTensionSteps(OutsideForm):
    name = "wheel_upstream_tension_steps"
    half = "dev11"
    balance = "wheel_torque"
    depends_on = ("time",)
    description = ("the uncoiler upstream hands the strip's tension down through its own controller, which moves to a "
                   "new level every T_s: T*u_k, k = floor((t - t_0)/T_s), u_k in [-1, 1) pseudo-random of k and a seed s "
                   "(kernel.XF_HASH_STEP: q = 7919*k^2 + 40503*k + 104729*s, u = 2*(q mod 65521)/65521 - 1), t the "
                   "generator's time (0 at sample 0)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"), Param("step_s", "s", (1e-3, 10.0), "T_s"),
                  Param("first_step_s", "s", (-10.0, 10.0), "t_0"), Param("seed", "-", (0, 1000), "s", "int"))
    note = "a piecewise-constant random torque locked to no shaft, no stroke and no event of this drive"

    def apply(self, b, p):
        add_term(b, "wheel_torque", p["torque_Nm"],
                 (K.XS_TIME, K.XF_HASH_STEP, float(p["seed"]), p["step_s"], p["first_step_s"]), nonperiodic=True)

    @staticmethod
    def torque(t, p):
        k = np.floor((np.asarray(t, dtype=np.float64) - p["first_step_s"]) / p["step_s"])
        q = k * k * 7919.0 + k * 40503.0 + p["seed"] * 104729.0
        return p["torque_Nm"] * (2.0 * np.mod(q, 65521.0) / 65521.0 - 1.0)

    def law(self, p):
        return (f"wheel torque += {p['torque_Nm']:.6g} N*m * u_k, k = floor((t - {p['first_step_s']:.6g} s)/"
                f"{p['step_s']:.6g} s), u_k = 2*((7919*k^2 + 40503*k + 104729*{int(p['seed'])}) mod 65521)/65521 - 1")


FORM_CLASSES = (MotorWheelRunawayGovernor, WheelOffDelayOverspeedBrake, ClutchOverrunningViscousCoupling,
                MassDeadBandSpeedSwitch, A2MainsNotchFilter, MassStrokeTrappedAirCushion, WheelUpstreamTensionSteps)
