"""Outside mechanisms, twenty-first SEALED half (issue 31 part 4, set 21): NOT TO BE READ by whoever tunes the
workbench's proposal, and run ONCE by the lead. The split rule and the list's order are in :mod:`outside_dev21`: of the
list of fourteen, the even numbers are here.

Kinds (balance x what it reads, and how), the sealed half:

2. motor load moment x the WHEEL's SPEED through a RELAY, TIMES the MOTOR's SPEED: a wheel-overspeed relay (a two-point
   switch with hysteresis: on above Omega_on, off below Omega_off, Omega2 scanned every 0.2 ms) energises the field of
   an eddy-current brake on the motor's free shaft end, whose drag goes with the motor's speed: c*Omega1*r, r the
   relay's state (off at the run-in's start) (the earlier relays read the motor's speed (the third set), the jaw's
   angle (the eleventh sealed half), the extension (the seventeenth sealed half) and the slip (the twentieth set),
   none the wheel's speed; the earlier eddy brakes on the motor are excited by the extension, the jaw's gap, the
   carriage's position window and the motor's own speed);
4. wheel torque x the WHEEL's SPEED TIMES a FULL-WAVE MAINS SINE, SQUARED: an eddy-current brake on the drum fed from an
   unsmoothed full-wave rectifier: its field current is |sin| of the mains and its drag goes as the current's square
   times the drum's speed: -c*Omega2*sin(2*pi*f*t + phi)^2, t the time from sample 0 (the earlier wheel eddy brakes are
   constant, field-lagged behind the stroke, cut out thermally or pulse-width modulated; the earlier laws of the time
   at the mains' frequency are a2's hum, a2's gain ripple and the twentieth set's half-wave magnet across the jaw, none
   times a speed);
6. clutch torque x the SLIP through a PI CONTROLLER, TIMES the SLIP: an eddy-current slip coupling beside the jaw whose
   excitation a digital PI slip controller sets to hold the slip at s_r: c*u*(Omega1 - Omega2) from the motor to the
   wheel, u = K_p*e + I limited to [0, 1], e = s - s_r, I += K_i*e*dt unless u is at a limit and e pushes it further
   (clamping anti-windup), scanned every 0.2 ms (I = 0 at the run-in's start), in the gap and in contact (the earlier
   PI controllers read the wheel's speed (the sixth sealed half), the motor's speed (the fifteenth sealed half) and the
   extension (the twentieth set); the earlier slip-controlled couplings are a sampled delay (the twelfth sealed half)
   and a slew-limited current (the seventeenth sealed half));
8. mass force x the WHEEL's SPEED through a LORENTZIAN (a resonance): the tow cable's span between the drum and the
   carriage whirls when the drum's once-per-turn runout excites it near the span's natural frequency; the whirl's
   centrifugal pull adds to the cable's tension on the carriage, peaking at the resonant drum speed Omega_r:
   -F/(1 + ((Omega2 - Omega_r)/w)^2) (the earlier Lorentzians are of the motor's speed (the eighth set's fan flutter,
   on the motor), of the extension (the fourteenth sealed half's magnet) and of the stroke's time (the sixteenth set's
   shear); the earlier laws of the wheel's speed on the carriage are a blower's square (the ninth sealed half), a
   tracking conveyor and a timed rail brake);
10. a2 sensor x the SIGNAL through a PACKET LOSS CONCEALED BY REPETITION: a2 reaches the recorder over a wireless link
    in packets of L samples; a packet is lost at random at a rate p (u_j, the j-th of numpy default_rng(seed)'s uniform
    numbers, < p; packets counted from the pre-roll's first sample), and the receiver conceals a lost packet by
    repeating the last packet it received, sample for sample: y over packet j = y over packet j - 1 where lost, else x
    (the first packet is never lost) (the earlier random sensor errors are a1's telemetry bit errors and jitter (the
    eleventh and sixth sealed halves); the earlier holds repeat one value, never a block);
12. motor load moment x the MOTOR's SPEED through a KLOSS CURVE about a SYNCHRONOUS SPEED: an auxiliary asynchronous
    machine on the motor's free shaft end (a load machine fed by its own frequency converter at a fixed frequency, its
    synchronous speed Omega_s inside the drive's speed range) generates above Omega_s and motors below it: its braking
    torque follows Kloss's law in its own slip u = Omega1 - Omega_s: 2*T_k*(u/u_k)/(1 + (u/u_k)^2), T_k its pull-out
    torque at the slip u_k (the earlier Kloss laws are of the
    slip across the jaw (the eighteenth set's induction coupling) and of the carriage's speed (the eighth sealed half's
    rail brake), both about zero; none of the motor's speed);
14. wheel torque x the WHEEL's SPEED through a SMOOTH STEP (a sigmoid): a centrifugal speed-limiting brake on the drum
    (as on hoists): its shoes fly out against their springs around Omega_e and rest on the drum at a force their stops
    limit: -T*(1 + tanh((Omega2 - Omega_e)/w))/2 (the earlier smooth steps are of the carriage's speed, the jaw's angle,
    the extension, the motor's speed, the contact mode and the slip; the earlier laws of the wheel's speed on the
    wheel are viscous, staged, a relief valve's clip, a bypass's dead zone and, behind memories, an overspeed latch,
    an off-delay, a peak, a tank, a PWM, a PI, a period tacho and a squeal).

Visibility, measured (one simulation of each suite row, 4 s, against the same spec without the mechanism, same seed; no
diagnose; rms of the recorded signal's difference; criterion a2 >= 0.05 m/s^2): 2 a2 0.100; 4 a2 0.0864; 6 a2 0.0727;
8 a2 0.0917; 10 a2 0.0127, BELOW; 12 a2 0.140; 14 a2 0.0486 at its a-priori strength, scaled once x1.54 (T 2 -> 3.086
N*m; a2 0.0671 after) -- 2, 4, 6, 8 and 12 as written.

One row is left below the criterion, as written, and said so here rather than made visible by force: the packet loss
(10): at 5 % of 2 ms packets lost a2 differs by 0.0127 rms; its single scaling, x5.90 (29.5 % lost), reached only a2
0.0456, still below (a repeated packet differs from the lost one only by how much a2 moved over 2 ms, and the rms grows
as the square root of the rate), so the row was set back to its a-priori 5 % and left there: visible (above a tenth of
the criterion) but below it. No other condition was tried.

A check that each memory moves (the same specs without noise, no figure used for a strength): the relay (2) is on over
30 % of the scans; the PI coupling (6) passes torque over 30 % of the scans (up to 4.0 N*m); the packet loss (10)
replaces 5.8 % of a2's samples.

Implementation: the relay (2) is the third set's relay (XS_RELAY) on XS_OMEGA2, its term XS_OMEGA1 times XS_RELAY; the
drum's brake (4) two slots, -c/2*Omega2 and c/2*Omega2*XF_COS of XS_TIME (sin^2 u = (1 - cos 2u)/2), both time-locked;
the coupling (6) the sixth set's MK_PI_SAT of XS_JAW_SPEED (its reference in the ring's extra place, its output within
[0, 1]) times XS_JAW_SPEED; the whirl (8) XF_LORENTZ of XS_OMEGA2; the packet loss (10) a sensor form in numpy
(default_rng); the induction machine (12) XF_CLIP (a wide one: u itself) times XF_LORENTZ of XS_OMEGA1; the centrifugal
brake (14) XF_SIGMOID of XS_OMEGA2. No kernel change.
"""
from __future__ import annotations

import numpy as np

from . import kernel as K
from .forms import Param
from .outside import OutsideForm, add_term, set_relay
from .outside_dev4 import set_memory
from .outside_dev6 import set_extra


# 2. motor load moment x the wheel's speed through a relay, times the motor's speed
class MotorWheelOverspeedRelayEddyBrake(OutsideForm):
    name = "motor_wheel_overspeed_relay_eddy_brake"
    half = "sealed21"
    balance = "motor_load_moment"
    depends_on = ("wheel_speed", "motor_speed")
    description = ("a wheel-overspeed relay (on above Omega_on, off below Omega_off, Omega2 scanned every 0.2 ms) "
                   "energises an eddy-current brake on the motor's free shaft end, whose drag goes with the motor's "
                   "speed: c*Omega1*r, r the relay's state (off at the run-in's start)")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c"),
                  Param("on_above_rad_s", "rad/s", (0.0, 500.0), "Omega_on"),
                  Param("off_below_rad_s", "rad/s", (0.0, 500.0), "Omega_off (<= Omega_on)"))
    note = "a motor eddy brake switched by a relay on the wheel's speed"

    def apply(self, b, p):
        set_relay(b, self.name, K.XS_OMEGA2, p["on_above_rad_s"], p["off_below_rad_s"], "on_above_rad_s",
                  "off_below_rad_s")
        add_term(b, "motor_load_moment", p["coefficient_Nm_s_per_rad"], (K.XS_OMEGA1, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_RELAY, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"motor load moment += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * Omega1 * r, r a relay on Omega2 "
                f"(on above {p['on_above_rad_s']:.6g} rad/s, off below {p['off_below_rad_s']:.6g} rad/s, scanned every "
                "0.2 ms)")


# 4. wheel torque x the wheel's speed times a full-wave mains sine, squared
class WheelAcFedEddyBrake(OutsideForm):
    name = "wheel_ac_fed_eddy_brake"
    half = "sealed21"
    balance = "wheel_torque"
    depends_on = ("wheel_speed", "time")
    description = ("an eddy-current brake on the drum fed from an unsmoothed full-wave rectifier: its field current is "
                   "|sin| of the mains and its drag goes as the current's square times the drum's speed: "
                   "-c*Omega2*sin(2*pi*f*t + phi)^2, t the time from sample 0")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 1.0), "c (at the current's peak)"),
                  Param("mains_hz", "Hz", (1.0, 1000.0), "f"),
                  Param("phase_rad", "rad", (-np.pi, np.pi), "phi"))
    note = "a wheel eddy brake pulsating at twice the mains frequency"

    def apply(self, b, p):
        c, w = p["coefficient_Nm_s_per_rad"], 2.0 * np.pi * p["mains_hz"]
        # sin(u)^2 = (1 - cos(2u))/2
        add_term(b, "wheel_torque", -0.5 * c, (K.XS_OMEGA2, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)
        add_term(b, "wheel_torque", 0.5 * c, (K.XS_OMEGA2, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_TIME, K.XF_COS, 2.0 * w, 2.0 * p["phase_rad"], 0.0), nonperiodic=True)

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * Omega2 * sin(2*pi*"
                f"{p['mains_hz']:.6g} Hz*t + {p['phase_rad']:.6g})^2, t from sample 0")


# 6. clutch torque x the slip through a PI controller, times the slip
class ClutchPiSlipCoupling(OutsideForm):
    name = "clutch_pi_slip_coupling"
    half = "sealed21"
    balance = "clutch_torque"
    depends_on = ("motor_speed", "wheel_speed")
    description = ("an eddy-current slip coupling beside the jaw whose excitation a digital PI slip controller sets to "
                   "hold the slip at s_r: c*u*(Omega1 - Omega2) from the motor to the wheel, u = K_p*e + I limited to "
                   "[0, 1], e = s - s_r, I += K_i*e*dt unless u is at a limit and e pushes it further, scanned every "
                   "0.2 ms (I = 0 at the run-in's start), in the gap and in contact")
    parameters = (Param("coefficient_Nm_s_per_rad", "N*m*s/rad", (0.0, 100.0), "c (fully excited)"),
                  Param("gain_s_per_rad", "s/rad", (0.0, 1e3), "K_p"),
                  Param("integral_per_rad", "1/rad", (0.0, 1e5), "K_i"),
                  Param("reference_rad_s", "rad/s", (-50.0, 50.0), "s_r"))
    note = "a slip coupling across the jaw excited by a PI controller of the slip"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_PI_SAT, K.XS_JAW_SPEED, p["gain_s_per_rad"], p["integral_per_rad"], 1.0)
        set_extra(b, p["reference_rad_s"])
        add_term(b, "clutch_torque", p["coefficient_Nm_s_per_rad"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_JAW_SPEED, K.XF_X, 0.0, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"clutch torque += {p['coefficient_Nm_s_per_rad']:.6g} N*m*s/rad * u * (Omega1 - Omega2), u = "
                f"{p['gain_s_per_rad']:.6g} s/rad * e + I limited to [0, 1], e = Omega1 - Omega2 - "
                f"{p['reference_rad_s']:.6g} rad/s, I += {p['integral_per_rad']:.6g}/rad * e * dt unless u is at a limit "
                "and e pushes it further (scanned every 0.2 ms)")


# 8. mass force x the wheel's speed through a Lorentzian (a resonance)
class MassCableSpanWhirl(OutsideForm):
    name = "mass_cable_span_whirl"
    half = "sealed21"
    balance = "mass_force"
    depends_on = ("wheel_speed",)
    description = ("the tow cable's span whirls when the drum's once-per-turn runout excites it near the span's natural "
                   "frequency; the whirl's pull adds to the cable's tension on the carriage, peaking at the resonant "
                   "drum speed Omega_r: -F/(1 + ((Omega2 - Omega_r)/w)^2)")
    parameters = (Param("force_N", "N", (0.0, 100.0), "F"),
                  Param("resonance_rad_s", "rad/s", (0.0, 500.0), "Omega_r"),
                  Param("half_width_rad_s", "rad/s", (1e-3, 100.0), "w"))
    note = "a pull on the carriage peaking at a resonant wheel speed (a Lorentzian of the wheel's speed)"

    def apply(self, b, p):
        add_term(b, "mass_force", -p["force_N"],
                 (K.XS_OMEGA2, K.XF_LORENTZ, p["half_width_rad_s"], p["resonance_rad_s"], 0.0))

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N/(1 + ((Omega2 - {p['resonance_rad_s']:.6g} rad/s)/"
                f"{p['half_width_rad_s']:.6g} rad/s)^2)")


# 10. a2 sensor x the signal through a packet loss concealed by repetition
class A2PacketLossRepetition(OutsideForm):
    name = "a2_packet_loss_repetition"
    half = "sealed21"
    stage = "sensor"
    order = 1                      # the link, after the sensing element
    balance = "sensor"
    channel = "a2"
    depends_on = ("mass_acceleration",)
    description = ("a2 reaches the recorder over a wireless link in packets of L samples; a packet is lost at random at "
                   "a rate p (u_j, the j-th of numpy default_rng(seed)'s uniform numbers, < p; packets counted from the "
                   "pre-roll's first sample; the first never lost), and the receiver repeats the last packet it "
                   "received, sample for sample, in a lost one's place")
    parameters = (Param("packet_samples", "-", (1.0, 1e5), "L (a whole number)"),
                  Param("loss_rate", "-", (0.0, 1.0), "p"),
                  Param("seed", "-", (0.0, 1e6), "the generator's seed (a whole number)"))
    note = "a2 with lost packets replaced by the last received one (packet-loss concealment)"

    def apply_signal(self, sig, p, t, fs):
        sig["a2"] = self.read(sig["a2"], p)

    @staticmethod
    def lost(n_samples, p):
        """Which packets are lost (packet 0 never)."""
        n_packets = -(-n_samples // int(p["packet_samples"]))
        u = np.random.default_rng(int(p["seed"])).random(n_packets)
        lost = u < p["loss_rate"]
        lost[0] = False
        return lost

    @classmethod
    def read(cls, x, p):
        x = np.asarray(x, dtype=np.float64)
        if p["loss_rate"] == 0.0:
            return x
        n = int(p["packet_samples"])
        y = x.copy()
        for j in np.flatnonzero(cls.lost(x.size, p)):
            lo, hi = j * n, min((j + 1) * n, x.size)
            y[lo:hi] = y[lo - n:hi - n]
        return y

    def law(self, p):
        return (f"a2 sensor = a2 in packets of {int(p['packet_samples'])} samples, each lost at a rate "
                f"{p['loss_rate']:.6g} (seed {int(p['seed'])}) and replaced by the last received packet")


# 12. motor load moment x the motor's speed through a Kloss curve about a synchronous speed
class MotorConverterFedInductionMachine(OutsideForm):
    name = "motor_converter_fed_induction_machine"
    half = "sealed21"
    balance = "motor_load_moment"
    depends_on = ("motor_speed",)
    description = ("an auxiliary induction machine on the motor's free shaft end, fed by its own converter at a fixed "
                   "frequency (its synchronous speed Omega_s inside the drive's speed range): it generates above "
                   "Omega_s and motors below, after Kloss's law in its slip u = Omega1 - Omega_s: "
                   "2*T_k*(u/u_k)/(1 + (u/u_k)^2)")
    parameters = (Param("pull_out_torque_Nm", "N*m", (0.0, 50.0), "T_k"),
                  Param("synchronous_speed_rad_s", "rad/s", (0.0, 500.0), "Omega_s"),
                  Param("pull_out_slip_rad_s", "rad/s", (1e-3, 500.0), "u_k"))
    note = "a motor load after Kloss's curve about a synchronous speed inside the drive's speed range"

    def apply(self, b, p):
        uk, ws = p["pull_out_slip_rad_s"], p["synchronous_speed_rad_s"]
        add_term(b, "motor_load_moment", 2.0 * p["pull_out_torque_Nm"] / uk,
                 (K.XS_OMEGA1, K.XF_CLIP, 1e6, -ws, 0.0), (K.XS_OMEGA1, K.XF_LORENTZ, uk, ws, 0.0))

    def law(self, p):
        return (f"motor load moment += 2*{p['pull_out_torque_Nm']:.6g} N*m * (u/{p['pull_out_slip_rad_s']:.6g})/(1 + "
                f"(u/{p['pull_out_slip_rad_s']:.6g})^2), u = Omega1 - {p['synchronous_speed_rad_s']:.6g} rad/s")


# 14. wheel torque x the wheel's speed through a smooth step
class WheelCentrifugalSpeedBrake(OutsideForm):
    name = "wheel_centrifugal_speed_brake"
    half = "sealed21"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a centrifugal speed-limiting brake on the drum: its shoes fly out against their springs around "
                   "Omega_e and rest on the drum at a force their stops limit: -T*(1 + tanh((Omega2 - Omega_e)/w))/2")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("engage_rad_s", "rad/s", (0.0, 500.0), "Omega_e"),
                  Param("width_rad_s", "rad/s", (1e-3, 100.0), "w"))
    note = "a wheel brake switched smoothly by the wheel's own speed (a sigmoid)"

    def apply(self, b, p):
        add_term(b, "wheel_torque", -p["torque_Nm"], (K.XS_OMEGA2, K.XF_SIGMOID, p["width_rad_s"], p["engage_rad_s"],
                                                       0.0))

    def law(self, p):
        return (f"wheel torque += -{p['torque_Nm']:.6g} N*m * (1 + tanh((Omega2 - {p['engage_rad_s']:.6g} rad/s)/"
                f"{p['width_rad_s']:.6g} rad/s))/2")


FORM_CLASSES = (MotorWheelOverspeedRelayEddyBrake, WheelAcFedEddyBrake, ClutchPiSlipCoupling, MassCableSpanWhirl,
                A2PacketLossRepetition, MotorConverterFedInductionMachine, WheelCentrifugalSpeedBrake)


def suite_rows():
    """The sealed suite's rows (label, kind, nominal width, eta_k, n1, effects): one per mechanism and a clean control.
    Seeds 21100+ in this order (suites.SEALED_FIRST_SEED)."""
    from .spec import EffectSpec as E
    return [
        # 0.02 N*m*s/rad (3 N*m at 150 rad/s), the relay on above 152.5 rad/s and off below 151
        ("os21_motor_wheel_overspeed_relay_eddy_brake", "outside", 0.0071, 0.0250, 0.94,
         [E("motor_wheel_overspeed_relay_eddy_brake", {"coefficient_Nm_s_per_rad": 0.02, "on_above_rad_s": 152.5,
                                                      "off_below_rad_s": 151.0})]),
        # 0.02 N*m*s/rad at the current's peak (1.5 N*m mean at 150 rad/s, 100 Hz), 50 Hz mains
        ("os21_wheel_ac_fed_eddy_brake", "outside", 0.0083, 0.0275, 0.92,
         [E("wheel_ac_fed_eddy_brake", {"coefficient_Nm_s_per_rad": 0.02, "mains_hz": 50.0, "phase_rad": 0.0})]),
        # 1 N*m*s/rad fully excited, K_p 0.5 s/rad, K_i 20/rad, holding 0.5 rad/s
        ("os21_clutch_pi_slip_coupling", "outside", 0.0066, 0.0240, 0.96,
         [E("clutch_pi_slip_coupling", {"coefficient_Nm_s_per_rad": 1.0, "gain_s_per_rad": 0.5,
                                        "integral_per_rad": 20.0, "reference_rad_s": 0.5})]),
        # 3 N at a resonant wheel speed of 152 rad/s, a half-width of 1 rad/s
        ("os21_mass_cable_span_whirl", "outside", 0.0078, 0.0300, 0.91,
         [E("mass_cable_span_whirl", {"force_N": 3.0, "resonance_rad_s": 152.0, "half_width_rad_s": 1.0})]),
        ("os21_clean_w7.4_eta0.0265_n0.95", "clean", 0.0074, 0.0265, 0.95, []),
        # packets of 100 samples (2 ms), 5 % lost, seed 21; a2 0.0127 in the visibility run, scaled once x5.90 (29.5 %
        # lost) still below (a2 0.0456): left as written, BELOW the criterion (see the module's docstring)
        ("os21_a2_packet_loss_repetition", "outside", 0.0086, 0.0225, 0.93,
         [E("a2_packet_loss_repetition", {"packet_samples": 100.0, "loss_rate": 0.05, "seed": 21.0})]),
        # 2 N*m pull-out at a slip of 2 rad/s about 150.5 rad/s
        ("os21_motor_converter_fed_induction_machine", "outside", 0.0070, 0.0285, 0.97,
         [E("motor_converter_fed_induction_machine", {"pull_out_torque_Nm": 2.0, "synchronous_speed_rad_s": 150.5,
                                                      "pull_out_slip_rad_s": 2.0})]),
        # 2 N*m, engaging around 152 rad/s over 0.5 rad/s a priori, a2 0.0486: scaled once x1.54
        ("os21_wheel_centrifugal_speed_brake", "outside", 0.0080, 0.0235, 0.90,
         [E("wheel_centrifugal_speed_brake", {"torque_Nm": 3.086, "engage_rad_s": 152.0, "width_rad_s": 0.5})]),
    ]
