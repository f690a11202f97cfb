"""Outside mechanisms, twentieth DEVELOPMENT half (issue 31 part 4, set 20): seven more mechanisms outside the
catalogue, of kinds neither the catalogue, the forms of :mod:`forms`, nor the first nineteen sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2` ... :mod:`outside_dev19`, :mod:`outside_sealed19`) have, with their laws in
the open. The twentieth sealed half is :mod:`outside_sealed20`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more (wheel
torque, mass force, motor load moment, clutch torque); in that order, the odd ones (1st, 3rd, ...) are this
development half, the even ones (2nd, 4th, ...) the sealed half. Numbers 1-14 of the list below are that order; the
even numbers are in :mod:`outside_sealed20` (their balances only here: 2 motor load moment, 4 wheel torque, 6 clutch
torque, 8 mass force, 10 sensor, 12 mass force, 14 clutch torque). About half of the fourteen are plain memoryless
laws of new kinds, half have a memory or a limit of their own (here: 1, 3, 5, 7, 9 memoryless; 11, 13 with a memory).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength is set
by one simulation against the clean drive of the same seed, for visibility, and not changed after. Checked before the
list was committed, on the documented clean drive (Omega1 146.9-154.2, Omega2 148.2-153.9 rad/s, the slip about
+-3 rad/s, z 0.274-0.321 m, v 22.66-22.80 m/s, the pulse 60 ms every 0.25 s, the gap's half-width about 0.049 rad):
no row is a constant on this drive (each reads a quantity that moves with the strokes, the jaw's crossings of the
gap, the wheel's turns, the carriage's travel or the mains' cycle), and none is an earlier kind moved to another
balance or sensor.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the CARRIAGE's POSITION through a SAWTOOTH: a length marker: a pump on the motor's free shaft
   end works a marking cylinder on the carriage's strip whose return spring is wound in proportion to the carriage's
   travel since the last mark and released at each mark, one every L of travel: T*((x - x_0) mod L)/L, x the
   carriage's position unwrapped from the run-in's start (a motor load of the carriage's travel that rises and
   drops back: the earlier sawtooths are of the time (the seventeenth sealed half's timer-dumped pump), of the wheel's
   angle unwrapped (the eighth sealed half's snail cam) and of the stroke count (the sixth set's tray, on the
   carriage); the earlier laws of the carriage's position are a window times the motor's speed on the motor (the
   eighteenth set's dynamo), a window, a sine and a random pattern on the carriage, a half-wave sine on the wheel (the
   nineteenth set's rollers) and a2's tilt);
3. wheel torque x the SLIP through a SMOOTH STEP (a sigmoid): a gerotor pump whose two elements ride on the drive
   half and on the wheel's half pumps in proportion to the slip into a hydraulic motor on the wheel through a relief
   valve that opens once the drive half overruns the wheel by s_0: +T*(1 + tanh((s - s_0)/w))/2, s = Omega1 - Omega2
   (a wheel assist switched smoothly by the slip: the earlier laws of the slip on the wheel have a memory (the
   seventeenth set's impact sample, the nineteenth set's boxcar, the seventeenth sealed half's decaying peak); the
   earlier smooth steps are of the carriage's speed (the eleventh set), of the jaw's angle (the third set's Weston
   brake), of the extension (the sixteenth sealed half), of the motor's speed (the ninth set's blower, the twelfth
   sealed half's bypassed damper, which multiplies the slip) and of the contact mode (the eighteenth sealed half));
5. clutch torque x the jaw's ANGLE DIFFERENCE TIMES a HALF-WAVE RECTIFIED MAINS SINE, SQUARED: an electromagnetic
   centring latch across the jaw whose coil is fed from the 50 Hz mains through one diode: its pull, hence its
   centring stiffness, goes as the current's square, a half-wave rectified sine: -k*max(0, sin(2*pi*f*t + phi))^2*D,
   D the jaw's angle difference, in the gap and in contact, t the time (a centring stiffness across the jaw
   pulsating with a clock of its own: the earlier stiffnesses across the jaw are constant (the first sealed half),
   switched by the pulse (the tenth set), scheduled by the motor speed's square (the fourteenth set) or by the
   cable's extension (the nineteenth set), cubic (the fifteenth set), or re-anchored (the fourteenth, seventeenth and
   eighteenth sets); the earlier laws of the time at a fixed frequency are a sine on the carriage (the second set),
   a2's hum and a2's gain ripple (the second and seventh sealed halves));
7. mass force x the SPRING EXTENSION TIMES a SLOW COSINE of the WHEEL's UNWRAPPED ANGLE: the drum's level-wind lays
   the tow cable across the drum's width and back once every N turns, so the cable leaves the drum at a fleet angle
   that swings slowly with the turns; the pull along the track is the cable's pull times the cosine of that angle:
   -c*z*(1 - cos((theta - theta_0)/N)), theta the wheel's angle unwrapped from the run-in's start (the cable's pull
   modulated by the turns: the earlier laws of the wheel's unwrapped angle are on the wheel (the fifth set's rope
   layers, which multiply the extension into a wheel torque, the seventeenth set's lubricator crank, a sine, the
   third sealed half's spall, the eighth sealed half's snail cam, the tenth sealed half's chain links, the ninth set's
   Geneva drive); the earlier laws of the wheel's angle on the carriage are the second set's eccentric roller, a cosine,
   the seventh sealed half's stroke-gated sine and the nineteenth set's crossover window, none of the extension);
9. a1 sensor x the CLUTCH TORQUE TIMES the MOTOR SPEED's SQUARE: a1's sensing element sits on the web of the
   motor-side coupling flange, which twists with the torque it passes to the jaw; the twist tilts a1's tangential
   axis towards the radial, so that a1 reads that fraction of the centripetal acceleration: y = x + r*Omega1^2*e*T_c,
   e the web's twist per N*m, r = 0.15 m (a1's radius), T_c the jaw's torque (an additive a1 error of the jaw's
   torque: no earlier sensor term reads the jaw's torque; the first sealed half's cross-axis reading of the
   centripetal acceleration has a fixed tilt; the fifteenth set's ground loop reads the contact state, not its torque;
   the eighteenth sealed half's pyroelectric term reads the motor's torque through a heat lag);
11. wheel torque x the SPRING EXTENSION through a PI CONTROLLER with a SATURATED OUTPUT: a tension controller brakes
    the drum (a proportional valve on its disc brake) to hold the cable's extension at z_r: -u, u = K_p*e + I limited
    to [0, T_max], e = z - z_r, I += K_i*e*dt unless u is at a limit and e pushes it further (clamping anti-windup),
    scanned every 0.2 ms (I = 0 at the run-in's start) (the earlier PI controllers read the wheel's speed (the sixth
    sealed half, on the wheel) and the motor's speed (the fifteenth sealed half, on the motor); the earlier memories of
    the extension on the wheel are a latch, a stroke sample, a play, a peak held since the stroke began, a check
    valve's lag and an on-delay);
13. motor load moment x the SLIP through a RELAY FILLING a CYLINDER: a slip monitor's relay (a two-point switch with
    hysteresis: on above s_on, off below s_off, s = Omega1 - Omega2) opens a valve that fills a motor-side brake's
    cylinder over T_f and, released, drains it over T_e: T*m, m += dt/T_f while the relay is on, m -= dt/T_e while it
    is off, m in [0, 1], scanned every 0.2 ms (m = 0 at the run-in's start) (the earlier fills are of the pulse (the
    eleventh sealed half, across the jaw) and of the contact mode (the fifteenth sealed half, on the wheel); the
    earlier relays read the motor's speed (the third set), the jaw's angle (the eleventh sealed half) and the extension
    (the seventeenth sealed half), none behind a memory; the nineteenth sealed half's slip guard on the motor is a
    latch re-armed at each stroke, on or off at once).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2, a1 >= 0.25 for an a1 row): 1 a2 0.0131
at its a-priori strength, scaled once x5.73 (T 2 -> 11.46 N*m; a2 0.0730 after); 3 a2 0.0330, scaled once x2.27 (T 2
-> 4.545 N*m; a2 0.0764 after); 5 a2 0.0419, scaled once x1.79 (k 60 -> 107.4 N*m/rad; a2 0.0737 after); 7 a2 0.112;
9 a1 3.15; 11 a2 0.0621; 13 a2 0.0808 -- the others as written (docs/foreign_drives.md "The twentieth set"). Before
it, a 0.4 s run of each row only checked that it simulates. A check that each memory moves (the same specs without
noise, no figure used for a strength): the PI brake (11) is inside its limits 98 % of the recording (at most 0.51 of
T_max, above 0 over 72 %); the cylinder (13) fills to full and drains, above 0 over 35 % of the recording.

Memory elements (one per recording) are advanced once per 0.2 ms input segment from the state at the segment's start
(kernel.py "memory"), as in the fourth to nineteenth sets; the memory starts afresh at the run-in's first scan, 2 s
before sample 0. The PI brake (11) is the sixth set's MK_PI_SAT on the extension (its reference in the ring's extra
place); the cylinder (13) is the eleventh set's MK_FILL reading the third set's relay (XS_RELAY), which the kernel scans
on the slip just before the memory in each segment. The marker (1) is XF_MOD of the fifth set's XS_MASS_POSITION, the
gerotor (3) XF_SIGMOID of XS_JAW_SPEED, the magnet (5) XS_JAW_ANGLE times XF_SIN_POSITIVE (power 2) of XS_TIME, the
level-wind (7) two slots, -c*z and c*z*XF_COS of XS_ALPHA2_UNWRAPPED, the flange twist (9) a sensor form in numpy on
the jaw's torque and the motor's speed (the sensor chain's states gain the jaw's torque, clutch_torque_Nm). No kernel
change for this set.
"""
from __future__ import annotations

import numpy as np

from . import constants as C
from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term, set_relay
from .outside_dev import _plugin
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 1. motor load moment x the carriage's position through a sawtooth
class MotorTravelMarkerCylinder(OutsideForm):
    name = "motor_travel_marker_cylinder"
    half = "dev20"
    balance = "motor_load_moment"
    depends_on = ("wheel_angle", "spring_extension")     # x = r*alpha2 - z
    description = ("a pump on the motor's free shaft end works a marking cylinder whose return spring is wound in "
                   "proportion to the carriage's travel since the last mark and released at each mark, one every L of "
                   "travel: T*((x - x_0) mod L)/L, x the carriage's position unwrapped from the run-in's start")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T (just before a mark)"),
                  Param("pitch_m", "m", (0.01, 100.0), "L"),
                  Param("offset_m", "m", (-100.0, 100.0), "x_0"))
    note = "a motor load that rises with the carriage's travel and drops back at each mark (a sawtooth)"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"] / p["pitch_m"],
                 (K.XS_MASS_POSITION, K.XF_MOD, p["pitch_m"], p["offset_m"], 0.0), nonperiodic=True)

    @staticmethod
    def torque(x, p):
        return p["torque_Nm"] / p["pitch_m"] * np.mod(np.asarray(x, dtype=np.float64) - p["offset_m"], p["pitch_m"])

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * ((x - {p['offset_m']:.6g} m) mod "
                f"{p['pitch_m']:.6g} m)/{p['pitch_m']:.6g} m, x the carriage's position unwrapped from the run-in's "
                "start")


# 3. wheel torque x the slip through a smooth step
class WheelGerotorSlipAssist(OutsideForm):
    name = "wheel_gerotor_slip_assist"
    half = "dev20"
    balance = "wheel_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a gerotor pump whose elements ride on the drive half and on the wheel's half pumps with the slip "
                   "into a hydraulic motor on the wheel through a relief valve that opens once the drive half overruns "
                   "the wheel by s_0: +T*(1 + tanh((s - s_0)/w))/2, s = Omega1 - Omega2")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("onset_rad_s", "rad/s", (-50.0, 50.0), "s_0"),
                  Param("width_rad_s", "rad/s", (1e-3, 50.0), "w"))
    note = "a wheel assist switched smoothly by the slip (a sigmoid of the slip)"

    def apply(self, b, p):
        add_term(b, "wheel_torque", p["torque_Nm"], (K.XS_JAW_SPEED, K.XF_SIGMOID, p["width_rad_s"],
                                                      p["onset_rad_s"], 0.0))

    @staticmethod
    def torque(slip, p):
        q = (np.asarray(slip, dtype=np.float64) - p["onset_rad_s"]) / p["width_rad_s"]
        return p["torque_Nm"] * 0.5 * (1.0 + np.tanh(q))

    def law(self, p):
        return (f"wheel torque += {p['torque_Nm']:.6g} N*m * (1 + tanh((Omega1 - Omega2 - {p['onset_rad_s']:.6g} rad/s)"
                f"/{p['width_rad_s']:.6g} rad/s))/2")

    def plugin(self, p):
        return _plugin("WheelGerotorSlipAssist", self.name, "wheel_torque_Nm", self.description, [
            ("torque_Nm", "N*m", (0.0, 50.0), "T"),
            ("onset_rad_s", "rad/s", (-50.0, 50.0), "s_0"),
            ("width_rad_s", "rad/s", (1e-3, 50.0), "w")],
            "rel_speed, torque_Nm, onset_rad_s, width_rad_s",
            "torque_Nm / (1.0 + exp(-2.0 * (rel_speed - onset_rad_s) / width_rad_s))", "exp")


# 5. clutch torque x the jaw's angle difference times a half-wave rectified mains sine, squared
class ClutchHalfWaveMagnetCentring(OutsideForm):
    name = "clutch_half_wave_magnet_centring"
    half = "dev20"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration", "time")
    description = ("an electromagnetic centring latch across the jaw, its coil fed from the mains through one diode: "
                   "its pull, hence its centring stiffness, goes as the square of a half-wave rectified sine: "
                   "-k*max(0, sin(2*pi*f*t + phi))^2*D, D the jaw's angle difference, in the gap and in contact")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 1e4), "k (at the current's peak)"),
                  Param("mains_hz", "Hz", (1.0, 1000.0), "f"),
                  Param("phase_rad", "rad", (-np.pi, np.pi), "phi"))
    note = "a centring stiffness across the jaw pulsating with the mains (a half-wave rectified magnet)"

    def apply(self, b, p):
        add_term(b, "clutch_torque", -p["stiffness_Nm_per_rad"], (K.XS_JAW_ANGLE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_TIME, K.XF_SIN_POSITIVE, 2.0 * np.pi * p["mains_hz"], p["phase_rad"], 2.0), nonperiodic=True)

    @staticmethod
    def torque(d, t, p):
        s = np.sin(2.0 * np.pi * p["mains_hz"] * np.asarray(t, dtype=np.float64) + p["phase_rad"])
        return -p["stiffness_Nm_per_rad"] * np.where(s > 0.0, s, 0.0) ** 2 * np.asarray(d, dtype=np.float64)

    def law(self, p):
        return (f"clutch torque += -{p['stiffness_Nm_per_rad']:.6g} N*m/rad * max(0, sin(2*pi*{p['mains_hz']:.6g} Hz*t "
                f"+ {p['phase_rad']:.6g}))^2 * D, D the jaw's angle difference, in the gap and in contact")


# 7. mass force x the spring extension times a slow cosine of the wheel's unwrapped angle
class MassLevelWindFleetAngle(OutsideForm):
    name = "mass_level_wind_fleet_angle"
    half = "dev20"
    balance = "mass_force"
    depends_on = ("spring_extension", "wheel_angle")
    description = ("the drum's level-wind lays the tow cable across the drum and back once every N turns; the cable "
                   "leaves the drum at a fleet angle that swings with the turns, and the pull along the track is the "
                   "cable's times its cosine: -c*z*(1 - cos((theta - theta_0)/N)), theta the wheel's angle unwrapped "
                   "from the run-in's start")
    parameters = (Param("coefficient_N_per_m", "N/m", (0.0, 1000.0), "c"),
                  Param("turns_per_cycle", "-", (1.0, 1000.0), "N"),
                  Param("angle_rad", "rad", (-1e3, 1e3), "theta_0"))
    note = "the cable's pull on the carriage modulated slowly by the wheel's turns"

    def apply(self, b, p):
        c, n = p["coefficient_N_per_m"], p["turns_per_cycle"]
        add_term(b, "mass_force", -c, (K.XS_SPRING_EXTENSION, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)
        add_term(b, "mass_force", c, (K.XS_SPRING_EXTENSION, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_ALPHA2_UNWRAPPED, K.XF_COS, 1.0 / n, -p["angle_rad"] / n, 0.0), nonperiodic=True)

    @staticmethod
    def force(z, theta, p):
        n = p["turns_per_cycle"]
        q = np.asarray(theta, dtype=np.float64) / n - p["angle_rad"] / n
        return -p["coefficient_N_per_m"] * np.asarray(z, dtype=np.float64) * (1.0 - np.cos(q))

    def law(self, p):
        return (f"mass force += -{p['coefficient_N_per_m']:.6g} N/m * z * (1 - cos((theta - {p['angle_rad']:.6g})/"
                f"{p['turns_per_cycle']:.6g})), theta the wheel's angle unwrapped from the run-in's start")


# 9. a1 sensor x the clutch torque times the motor speed's square
class A1CouplingFlangeTwist(OutsideForm):
    name = "a1_coupling_flange_twist"
    half = "dev20"
    stage = "sensor"
    order = 0                      # the sensing element's axis
    uses_states = True
    balance = "sensor"
    channel = "a1"
    depends_on = ("motor_acceleration", "clutch_penetration", "motor_speed")
    description = ("a1's sensing element sits on the web of the motor-side coupling flange, which twists with the "
                   "torque it passes to the jaw; the twist tilts a1's tangential axis towards the radial, so that a1 "
                   "reads that fraction of the centripetal acceleration: y = x + r*Omega1^2*e*T_c, r = 0.15 m, T_c the "
                   "jaw's torque")
    parameters = (Param("twist_rad_per_Nm", "rad/(N*m)", (0.0, 1e-2), "e (the web's twist per N*m)"),)
    note = "an additive a1 error of the jaw's torque (a tilt into the centripetal acceleration)"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], states["clutch_torque_Nm"], states["omega1"], p)

    @staticmethod
    def read(a1, tc, omega1, p):
        a1 = np.asarray(a1, dtype=np.float64)
        if p["twist_rad_per_Nm"] == 0.0:
            return a1
        w = np.asarray(omega1, dtype=np.float64)
        return a1 + C.WHEEL_RADIUS_M * w * w * p["twist_rad_per_Nm"] * np.asarray(tc, dtype=np.float64)

    def law(self, p):
        return (f"a1 sensor = a1 + 0.15 m * Omega1^2 * {p['twist_rad_per_Nm']:.6g} rad/(N*m) * T_c, T_c the jaw's "
                "torque")


# 11. wheel torque x the spring extension through a PI controller with a saturated output
class WheelTensionPiBrake(OutsideForm):
    name = "wheel_tension_pi_brake"
    half = "dev20"
    balance = "wheel_torque"
    depends_on = ("spring_extension",)
    description = ("a tension controller brakes the drum through a proportional valve to hold the cable's extension at "
                   "z_r: -u, u = K_p*e + I limited to [0, T_max], e = z - z_r, I += K_i*e*dt unless u is at a limit "
                   "and e pushes it further, scanned every 0.2 ms (I = 0 at the run-in's start)")
    parameters = (Param("gain_Nm_per_m", "N*m/m", (0.0, 1e4), "K_p"),
                  Param("integral_Nm_per_m_s", "N*m/(m*s)", (0.0, 1e6), "K_i"),
                  Param("reference_m", "m", (0.0, 1.0), "z_r"),
                  Param("max_torque_Nm", "N*m", (0.0, 50.0), "T_max"))
    note = "a wheel brake of the extension through a PI controller with a saturated output"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PI_SAT, K.XS_SPRING_EXTENSION, p["gain_Nm_per_m"], p["integral_Nm_per_m_s"],
                   p["max_torque_Nm"])
        set_extra(b, p["reference_m"])
        add_term(b, "wheel_torque", -1.0, (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def outputs(z_at_scans, p, dt, integral0=0.0):
        """The controller's output u after each scan from the extension at the scans' starts (the integral before
        the first scan: integral0)."""
        kp, ki, top, ref = p["gain_Nm_per_m"], p["integral_Nm_per_m_s"], p["max_torque_Nm"], p["reference_m"]
        out, i = [], integral0
        for x in np.asarray(z_at_scans, dtype=np.float64).tolist():
            e = x - ref
            u = kp * e + i
            if not ((u >= top and e > 0.0) or (u <= 0.0 and e < 0.0)):
                i += ki * e * dt
                u = kp * e + i
            out.append(0.0 if u < 0.0 else (top if u > top else u))
        return np.array(out)

    def law(self, p):
        return (f"wheel torque += -u, u = {p['gain_Nm_per_m']:.6g} N*m/m * e + I limited to [0, "
                f"{p['max_torque_Nm']:.6g} N*m], e = z - {p['reference_m']:.6g} m, I += "
                f"{p['integral_Nm_per_m_s']:.6g} N*m/(m*s) * e * dt unless u is at a limit and e pushes it further "
                "(scanned every 0.2 ms)")


# 13. motor load moment x the slip through a relay filling a cylinder
class MotorSlipRelayCylinderBrake(OutsideForm):
    name = "motor_slip_relay_cylinder_brake"
    half = "dev20"
    balance = "motor_load_moment"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("a slip monitor's relay (on above s_on, off below s_off, s = Omega1 - Omega2) opens a valve that "
                   "fills a motor-side brake's cylinder over T_f and, released, drains it over T_e: T*m, m += dt/T_f "
                   "while the relay is on, m -= dt/T_e while it is off, m in [0, 1], scanned every 0.2 ms (m = 0 at "
                   "the run-in's start)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T (the cylinder full)"),
                  Param("on_above_rad_s", "rad/s", (-50.0, 50.0), "s_on"),
                  Param("off_below_rad_s", "rad/s", (-50.0, 50.0), "s_off (<= s_on)"),
                  Param("fill_time_s", "s", (1e-3, 100.0), "T_f"),
                  Param("drain_time_s", "s", (1e-3, 100.0), "T_e"))
    note = "a motor brake whose cylinder a slip relay fills and drains (a fill behind a relay)"

    def apply(self, b, p):
        set_relay(b, self.name, K.XS_JAW_SPEED, p["on_above_rad_s"], p["off_below_rad_s"], "on_above_rad_s",
                  "off_below_rad_s")
        set_memory(b, self.name, K.MK_FILL, K.XS_RELAY, p["fill_time_s"], p["drain_time_s"])
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    @staticmethod
    def fills(slip_at_scans, p, dt, on0=0.0, m0=0.0):
        """The relay's state and the cylinder's fill m after each scan from the slip at the scans' starts (the relay's
        state and the fill before the first: on0, m0)."""
        on, m, relay, fill = on0, m0, [], []
        for s in np.asarray(slip_at_scans, dtype=np.float64).tolist():
            if on == 0.0 and s > p["on_above_rad_s"]:
                on = 1.0
            elif on != 0.0 and s < p["off_below_rad_s"]:
                on = 0.0
            m += dt / p["fill_time_s"] if on > 0.5 else -dt / p["drain_time_s"]
            m = 0.0 if m < 0.0 else (1.0 if m > 1.0 else m)
            relay.append(on)
            fill.append(m)
        return np.array(relay), np.array(fill)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * m, m += 0.2 ms/{p['fill_time_s']:.6g} s while a "
                f"relay on Omega1 - Omega2 (on above {p['on_above_rad_s']:.6g} rad/s, off below "
                f"{p['off_below_rad_s']:.6g} rad/s) is on, -= 0.2 ms/{p['drain_time_s']:.6g} s while off, m in [0, 1] "
                "(scanned every 0.2 ms)")


FORM_CLASSES = (MotorTravelMarkerCylinder, WheelGerotorSlipAssist, ClutchHalfWaveMagnetCentring,
                MassLevelWindFleetAngle, A1CouplingFlangeTwist, WheelTensionPiBrake, MotorSlipRelayCylinderBrake)
