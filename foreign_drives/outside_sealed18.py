"""Outside mechanisms, eighteenth SEALED half (issue 31 part 4, set 18): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev18`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the spring extension through a MOVING AVERAGE (a boxcar): a tension load cell's weighing
   indicator averages its reading over the last n 0.2 ms scans and drives an eddy-current brake on the motor's free
   shaft end with the average's excess over z_r: c*max(0, m - z_r), m the mean of z over the last n scans (all n = z at
   the run-in's start) (the tenth sealed half's boxcar is of the motor's speed, on the motor; the earlier motor loads
   of the extension are a linear excess, a staircase, the extension times the motor speed and a peak held since the
   stroke began; the earlier memories of the extension on other balances include a one-shot, a toggle, a play, a rate
   limiter, a Dahl element, a delay, a latch and a stroke sample, none an average over a window);
4. wheel torque x the wheel's angle LESS A CLOCK'S ANGLE through a SINE (a pole-slipping synchronous machine): a
   small synchronous motor, fed from the mains, is geared 1:1 to the wheel's shaft (it drives a timing unit); the wheel
   runs below its synchronous speed Omega_s, so its poles slip and its torque swings at the slip frequency:
   T*sin(p*(alpha2_u - Omega_s*(t - t_0)) + phi), alpha2_u the wheel's angle unwrapped from the run-in's start, p its
   pole pairs (the fourth sealed half's phase-lock trim reads the same angle difference through a clip, a correction
   that never slips a pole; the eleventh sealed half's magnetic coupling drives a hidden rotor on the motor; the cam
   follower and the ripples are sines of the angle alone, the floor vibration of the time alone);
6. clutch torque x the slip through a ONE-SHOT TIMER: an anti-clatter damper coupling beside the jaw, engaged by a
   solenoid that a timer holds for T_h after the slip rises through s_t (the drive half closing on the jaw fast): c*s*m,
   m -> 1 at a 0.2 ms scan where s rose through s_t (at or below it at the scan before) while m = 0, back to 0 T_h later
   (m = 0 at the run-in's start), s = Omega1 - Omega2 (the thirteenth sealed half's slip-monitored coupling is an
   on-delay of the slip, on only while the slip stays above its threshold; the earlier one-shots are of the extension,
   the motor's and the wheel's speeds, the penetration and the wheel's angle, never of the slip);
8. mass force x the jaw's CONTACT AGE through a DECAYING RINGING: each contact from the gap sends a shock along the
   cable into the carriage's tow bracket, which rings: F*exp(-a/tau)*sin(2*pi*f*a), a the time since the current
   contact began (0 in the gap) (a ringing re-started by the jaw's contacts: the tenth set's stroke torsional ring and
   the third set's stroke ringing of a2 restart at each load pulse, the tenth sealed half's neighbour press's shocks
   at a period of their own; the fourth sealed half's hydraulic cushion decays with the contact's age on the clutch,
   without ringing);
10. a1 sensor x the motor's electromagnetic torque SQUARED through a HIGH-PASS (a pyroelectric output): a1's piezo
    element sits on the motor's housing, which the stator's copper losses (~ the torque squared) warm through a thermal
    time constant tau; the element's pyroelectric charge follows the rate of its temperature: y = x + k*(e - theta)/tau,
    theta' = (e - theta)/tau, e = t_e^2 (t_e the motor's electromagnetic torque, p.u.; theta = e at the recording's
    pre-roll start) (a1 read with a part of the rate of the motor's heating: the fourth sealed half's piezo zero shift
    steps with the shocks, the catalogue's bias drifts in time, the seventh sealed half's bearing warm-up is a motor
    load; no earlier sensor reads the motor's current or torque);
12. motor load moment x the jaw's CONTACT SIDE: an inductive proximity switch at the jaw's far face switches a motor-side
    dynamic brake on while the far face is in contact (the wheel overrunning the motor): T while the contact is on the
    far side, else 0 (a motor load of the contact's side: the fifteenth sealed half's gap-approach brake reads the
    distance to the nearer face in the gap, the third sealed half's thrust bearing the contact's torque, the fifteenth
    sealed half's fill brake a fill level of the drive-side contact on the wheel, the tenth set's interlock brake the
    contact's age on the wheel);
14. wheel torque x the spring extension through an ASYMMETRIC LAG (a check valve with a bleed): a tension cylinder on
    the cable's guide sheave feeds a wheel brake's caliper through a check valve (it fills with a rise time tau_r) and a
    bleed orifice (it drains with a fall time tau_f > tau_r): -c*max(0, m - z_r), m -> z + (m - z)*exp(-dt/tau_r) while
    z > m, else z + (m - z)*exp(-dt/tau_f), every 0.2 ms (m = z at the run-in's start) (the sixteenth sealed half's
    tension-proportional brake on the wheel has no memory; the earlier memories of the extension on the wheel are a
    latch, a stroke sample, a play and a peak held since the stroke began; the earlier asymmetric lags are of the
    wheel's speed, on the motor, and of the carriage's speed, on the carriage).

Visibility, measured as for the development half (4 s, against the same spec without the mechanism, same seed;
criterion a2 >= 0.05, a1 >= 0.25 for an a1 row): 2 a2 0.0444 at its a-priori strength, scaled once x1.69 (a2 0.0706
after); 4 a2 0.227; 6 a2 0.0428, scaled once x1.75 (a2 0.0695 after); 8 a2 0.0502; 10 a1 0.145, scaled once x2.59 (a1
0.375 after); 12 a2 0.0668; 14 a2 0.0556 -- the others as written.

Thin (read off the laws and the documented clean drive, no diagnose; recorded here only): the averaged tension brake
(2) and the check-valve brake (14) read the extension (0.274-0.321 m) above 0.29 m, smoothed, so part of each is a
constant load (their means); the synchronous motor (4) slips its poles at about p*(Omega_s - Omega2), some 12 rad/s
(about 2 Hz, below the 4 Hz pulse train), a slow swing whose phase wanders with the wheel's speed; the far-side brake
(12) acts only during the far face's short contacts at the onsets, so its load is brief pulses; the ringing (8) is
barely above the criterion (a2 0.0502); the pyroelectric term (10) is a high-pass of t_e^2, zero on average, locked to
the strokes.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term
from .outside_dev4 import set_memory


# 2. motor load moment x the spring extension through a moving average
class MotorAveragedTensionBrake(OutsideForm):
    name = "motor_averaged_tension_brake"
    half = "sealed18"
    balance = "motor_load_moment"
    depends_on = ("spring_extension",)
    description = ("a tension load cell's weighing indicator averages its reading over the last n 0.2 ms scans and "
                   "drives an eddy-current brake on the motor's free shaft end with the average's excess over z_r: "
                   "c*max(0, m - z_r), m the mean of the extension over the last n scans (all n = z at the run-in's "
                   "start)")
    parameters = (Param("coefficient_Nm_per_m", "N*m/m", (0.0, 1000.0), "c"),
                  Param("reference_m", "m", (0.0, 1.0), "z_r"),
                  Param("window_scans", "-", (1.0, float(K.MEMORY_RING)), "n (a whole number of 0.2 ms scans)"))
    note = "a motor brake on the extension averaged over a window"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_MOVING_MEAN, K.XS_SPRING_EXTENSION, float(int(p["window_scans"])))
        add_term(b, "motor_load_moment", p["coefficient_Nm_per_m"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["reference_m"], 1.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_per_m']:.6g} N*m/m * max(0, m - {p['reference_m']:.6g} m), m "
                f"the mean of the spring's extension over the last {int(p['window_scans'])} 0.2 ms scans")


# 4. wheel torque x the wheel's angle less a clock's angle through a sine
class WheelPoleSlippingSynchronousMotor(OutsideForm):
    name = "wheel_pole_slipping_synchronous_motor"
    half = "sealed18"
    balance = "wheel_torque"
    depends_on = ("wheel_angle", "time")
    description = ("a small mains-fed synchronous motor geared 1:1 to the wheel's shaft (it drives a timing unit); the "
                   "wheel runs off its synchronous speed, so its poles slip: T*sin(p*(alpha2_u - Omega_s*(t - t_0)) + "
                   "phi) on the wheel, alpha2_u the wheel's angle unwrapped from the run-in's start t_0")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("pole_pairs", "-", (1.0, 12.0), "p (a whole number)"),
                  Param("synchronous_speed_rad_s", "rad/s", (100.0, 200.0), "Omega_s"),
                  Param("phase_rad", "rad", (-np.pi, np.pi), "phi"))
    note = "a torque swinging with the wheel's angle against a clock's (a pole-slipping synchronous machine)"

    def apply(self, b, p):
        if b.P[K.P_CLKRATE] != 0.0:
            raise ValueError(f"{self.name}: a second clock in one recording; allowed: one")
        b.P[K.P_CLKRATE] = p["synchronous_speed_rad_s"]
        add_term(b, "wheel_torque", p["torque_Nm"],
                 (K.XS_ALPHA2_MINUS_CLOCK, K.XF_SIN, float(int(p["pole_pairs"])), p["phase_rad"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += {p['torque_Nm']:.6g} N*m * sin({int(p['pole_pairs'])}*(alpha2_u - "
                f"{p['synchronous_speed_rad_s']:.6g} rad/s * (t + 2 s)) + {p['phase_rad']:.6g}), alpha2_u the wheel's "
                "angle unwrapped from the run-in's start (t = -2 s), t from sample 0")


# 6. clutch torque x the slip through a one-shot timer
class ClutchSlipTimedDamperCoupling(OutsideForm):
    name = "clutch_slip_timed_damper_coupling"
    half = "sealed18"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an anti-clatter damper coupling beside the jaw, engaged by a solenoid that a timer holds for T_h "
                   "after the slip rises through s_t: c*s*m, m -> 1 at a 0.2 ms scan where s rose through s_t while "
                   "m = 0, back to 0 T_h later (m = 0 at the run-in's start), s = Omega1 - Omega2")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "c"),
                  Param("trigger_slip_rad_s", "rad/s", (-50.0, 50.0), "s_t"),
                  Param("hold_s", "s", (0.0002, 10.0), "T_h"))
    note = "a slip coupling engaged for a set time after the slip rises through a threshold"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_ONESHOT, K.XS_JAW_SPEED, p["trigger_slip_rad_s"], p["hold_s"])
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * (Omega1 - Omega2) * m, m on for "
                f"{p['hold_s']:.6g} s after the slip rises through {p['trigger_slip_rad_s']:.6g} rad/s (scanned every "
                "0.2 ms), in the gap and in contact")


# 8. mass force x the jaw's contact age through a decaying ringing
class MassJawImpactRinging(OutsideForm):
    name = "mass_jaw_impact_ringing"
    half = "sealed18"
    balance = "mass_force"
    depends_on = ("clutch_penetration",)
    description = ("each contact of the jaw from the gap sends a shock along the cable into the carriage's tow "
                   "bracket, which rings: F*exp(-a/tau)*sin(2*pi*f*a), a the time since the current contact began "
                   "(0 in the gap)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("decay_s", "s", (1e-4, 1.0), "tau"),
                  Param("frequency_hz", "Hz", (1.0, 2000.0), "f"))
    note = "a decaying ringing on the carriage restarted by each of the jaw's contacts"

    def apply(self, b, p):
        add_term(b, "mass_force", p["force_N"], (K.XS_CONTACT_AGE, K.XF_DECAY_AFTER, p["decay_s"], 0.0, 0.0),
                 (K.XS_CONTACT_AGE, K.XF_SIN, 2.0 * np.pi * p["frequency_hz"], 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += {p['force_N']:.6g} N * exp(-a/{p['decay_s']:.6g} s) * sin(2*pi*"
                f"{p['frequency_hz']:.6g} Hz*a), a the time since the current contact began, 0 in the gap")


# 10. a1 sensor x the motor's torque squared through a high-pass
class A1PyroelectricMotorHeat(OutsideForm):
    name = "a1_pyroelectric_motor_heat"
    half = "sealed18"
    stage = "sensor"
    order = 0                      # the sensing element
    uses_states = True
    balance = "sensor"
    channel = "a1"
    depends_on = ("motor_acceleration", "motor_speed")
    description = ("a1's piezo element sits on the motor's housing, which the stator's copper losses (~ the torque "
                   "squared) warm through a thermal time constant tau; its pyroelectric charge follows the rate of its "
                   "temperature: y = x + k*(e - theta)/tau, theta' = (e - theta)/tau, e = t_e^2 (t_e the motor's "
                   "electromagnetic torque, p.u.; theta = e at the recording's first sample, the pre-roll's)")
    parameters = (Param("coefficient_m_s", "m/s", (-10.0, 10.0), "k (per p.u.^2)"),
                  Param("thermal_time_s", "s", (1e-3, 100.0), "tau"))
    note = "a1 read with a part of the rate of the motor's heating"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.read(sig["a1"], states["te_pu"], p, fs)

    @staticmethod
    def read(a, te, p, fs):
        from scipy.signal import lfilter
        e = np.asarray(te, dtype=np.float64) ** 2
        alpha = np.exp(-1.0 / (fs * p["thermal_time_s"]))
        theta, _ = lfilter([1.0 - alpha], [1.0, -alpha], e, zi=[alpha * e[0]])
        return np.asarray(a, dtype=np.float64) + p["coefficient_m_s"] * (e - theta) / p["thermal_time_s"]

    def law(self, p):
        return (f"a1 sensor = a1 + {p['coefficient_m_s']:.6g} m/s * (e - theta)/{p['thermal_time_s']:.6g} s, theta a "
                f"first-order lag of e = t_e^2 (time constant {p['thermal_time_s']:.6g} s), t_e the motor's "
                "electromagnetic torque (p.u.)")


# 12. motor load moment x the jaw's contact side
class MotorFarContactDynamicBrake(OutsideForm):
    name = "motor_far_contact_dynamic_brake"
    half = "sealed18"
    balance = "motor_load_moment"
    depends_on = ("clutch_penetration",)
    description = ("an inductive proximity switch at the jaw's far face switches a motor-side dynamic brake on while "
                   "the far face is in contact (the wheel overrunning the motor): T while the contact is on the far "
                   "side, else 0")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),)
    note = "a motor load switched by the jaw's far-side contact"

    def apply(self, b, p):
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_MODE, K.XF_SIGMOID, -0.05, -0.5, 0.0))

    def law(self, p):
        return f"motor load moment += {p['torque_Nm']:.6g} N*m while the jaw's contact is on the far side, else 0"


# 14. wheel torque x the spring extension through an asymmetric lag
class WheelCheckValveTensionBrake(OutsideForm):
    name = "wheel_check_valve_tension_brake"
    half = "sealed18"
    balance = "wheel_torque"
    depends_on = ("spring_extension",)
    description = ("a tension cylinder on the cable's guide sheave feeds a wheel brake's caliper through a check valve "
                   "(it fills with a rise time tau_r) and a bleed orifice (it drains with a fall time tau_f): "
                   "-c*max(0, m - z_r), m -> z + (m - z)*exp(-dt/tau_r) while z > m, else z + (m - z)*exp(-dt/tau_f), "
                   "every 0.2 ms (m = z at the run-in's start)")
    parameters = (Param("coefficient_Nm_per_m", "N*m/m", (0.0, 1000.0), "c"),
                  Param("reference_m", "m", (0.0, 1.0), "z_r"),
                  Param("rise_time_s", "s", (1e-4, 10.0), "tau_r"),
                  Param("fall_time_s", "s", (1e-4, 10.0), "tau_f"))
    note = "a wheel brake on the extension through a fast-filling, slow-bleeding lag"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_LAG, K.XS_SPRING_EXTENSION, p["rise_time_s"], p["fall_time_s"], 0.0)
        add_term(b, "wheel_torque", -p["coefficient_Nm_per_m"],
                 (K.XS_MEMORY, K.XF_EXCESS_POWER, p["reference_m"], 1.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_per_m']:.6g} N*m/m * max(0, m - {p['reference_m']:.6g} m), m a "
                f"lag of the spring's extension rising with {p['rise_time_s']:.6g} s and falling with "
                f"{p['fall_time_s']:.6g} s (scanned every 0.2 ms)")


FORM_CLASSES = (MotorAveragedTensionBrake, WheelPoleSlippingSynchronousMotor, ClutchSlipTimedDamperCoupling,
                MassJawImpactRinging, A1PyroelectricMotorHeat, MotorFarContactDynamicBrake,
                WheelCheckValveTensionBrake)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 18100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 60 N*m/m of the extension's 10 ms mean above 0.29 m (up to about 2 N*m) a priori, a2 0.0444: scaled once
        # x1.69
        ("os18_motor_averaged_tension_brake", "outside", 0.0072, 0.0255, 0.93,
         [E("motor_averaged_tension_brake", {"coefficient_Nm_per_m": 101.3, "reference_m": 0.29,
                                              "window_scans": 50.0})]),
        # 2 N*m, 2 pole pairs at 157.08 rad/s (a 50 Hz mains, four poles)
        ("os18_wheel_pole_slipping_synchronous_motor", "outside", 0.0064, 0.0300, 0.95,
         [E("wheel_pole_slipping_synchronous_motor", {"torque_Nm": 2.0, "pole_pairs": 2.0,
                                                       "synchronous_speed_rad_s": 157.08, "phase_rad": 0.0})]),
        # 1 N*m*s/rad of the slip for 30 ms after it rises through 2 rad/s a priori, a2 0.0428: scaled once x1.75
        ("os18_clutch_slip_timed_damper_coupling", "outside", 0.0084, 0.0230, 0.91,
         [E("clutch_slip_timed_damper_coupling", {"coefficient_Nm_s_per_rad": 1.754, "trigger_slip_rad_s": 2.0,
                                                   "hold_s": 0.03})]),
        # 3 N ringing at 60 Hz, decaying over 15 ms
        ("os18_mass_jaw_impact_ringing", "outside", 0.0067, 0.0290, 0.92,
         [E("mass_jaw_impact_ringing", {"force_N": 3.0, "decay_s": 0.015, "frequency_hz": 60.0})]),
        ("os18_clean_w7.6_eta0.0245_n0.97", "clean", 0.0076, 0.0245, 0.97, []),
        # 0.05 m/s per p.u.^2 through a 50 ms thermal lag a priori, a1 0.145: scaled once x2.59
        ("os18_a1_pyroelectric_motor_heat", "outside", 0.0079, 0.0320, 0.94,
         [E("a1_pyroelectric_motor_heat", {"coefficient_m_s": 0.1296, "thermal_time_s": 0.05})]),
        # 4 N*m while the far side is in contact
        ("os18_motor_far_contact_dynamic_brake", "outside", 0.0069, 0.0235, 0.96,
         [E("motor_far_contact_dynamic_brake", {"torque_Nm": 4.0})]),
        # 60 N*m/m above 0.29 m, filling over 5 ms, bleeding over 80 ms
        ("os18_wheel_check_valve_tension_brake", "outside", 0.0085, 0.0275, 0.90,
         [E("wheel_check_valve_tension_brake", {"coefficient_Nm_per_m": 60.0, "reference_m": 0.29,
                                                 "rise_time_s": 0.005, "fall_time_s": 0.08})]),
    ]
