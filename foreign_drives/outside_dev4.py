"""Outside mechanisms, fourth DEVELOPMENT half (issue 31 part 4, set 4): seven more mechanisms outside the catalogue,
of kinds neither the catalogue, the forms of :mod:`forms`, nor the first three sets (:mod:`outside_dev`,
:mod:`outside_sealed`, :mod:`outside_dev2`, :mod:`outside_sealed2`, :mod:`outside_dev3`, :mod:`outside_sealed3`)
have, with their laws in the open. The fourth sealed half is :mod:`outside_sealed4`.

THE SPLIT RULE, fixed in writing before any of the fourteen was simulated: they were written as a list of fourteen,
two per balance in turn (motor load moment, wheel torque, clutch torque, mass force, sensor), then four more; in
that order, the odd ones (1st, 3rd, ...) are this development half, the even ones (2nd, 4th, ...) the sealed half.
Numbers 1-14 of the list below are that order; the even numbers are in :mod:`outside_sealed4` (their balances only
here: 2 motor load moment, 4 wheel torque, 6 clutch torque, 8 mass force, 10 sensor, 12 sensor, 14 wheel torque).
Written before any diagnose, analyze or proposal ran on them (the commit history is the proof); each strength was set
by one quick simulation against the clean drive of the same seed, for visibility, and not changed after.

Kinds (balance x what it reads, and how), the development half -- things a real press line has that nobody wrote
down:

1. motor load moment x the STROKE COUNT (a sub-harmonic of the pulse train): a progressive die whose piercing
   station works on every N-th part only; an extra load T during the strokes k = m (mod N), k the stroke's number;
3. wheel torque x the wheel speed through a ONE-WAY MEMORY: a feed roll's flywheel on the wheel shaft behind an
   overrunning (sprag) clutch with a compliant coupling; it is dragged up, -c*(Omega2 - w_f), whenever the wheel runs
   faster than it, and coasts down on its bearing drag otherwise (a hidden speed w_f that rises fast and falls slowly);
5. clutch torque x the penetration through a RELAXATION (a memory of the contact): the jaw's elastomer insert is
   viscoelastic (a standard linear solid); its contact law gains a Maxwell branch k_m*(p - q), q the branch's relaxed
   penetration, dq/dt = (p - q)/tau (written first as an outside term beside the law: when the jaw released with the
   branch still pushing, its torque jumped and the integrator chattered there, so the branch is part of the law whose
   sign decides the release -- changed after its first visibility simulation, before any diagnose; its strength then
   set by one new simulation);
7. mass force x the spring extension through a ONE-SHOT TIMER: a proximity switch on the spring's bracket fires a
   pneumatic rail clamp on the carriage for a fixed time each time the extension rises through a set value (a PLC
   one-shot, not retriggered while it runs): -F*sign(v) for T_h after the trigger;
9. a1 sensor x a1's own RATE: the rotating a1 channel passes an isolation amplifier whose output slews at most S
   (a slew-rate limit: a memory of the signal's last value, not a filter of fixed dynamics);
11. a1 sensor x the MOTOR ANGLE as a gate on a HOLD: a1's rotating telemetry loses its radio link while its antenna
    passes behind the motor frame, once per revolution, over an angle window; the receiver holds the last value;
13. mass force x the mass speed SAMPLED and DELAYED: a linear motor on the carriage holds the carriage's speed under a
    digital speed loop: it samples v every scan and applies, some scans later, -K*(v_sampled - v_ref), held between
    scans.

Angles: as in :mod:`outside_dev` (a law locked to an angle is stated on the simulator's angle; the manifest has its
value at sample 0). Memory elements (the one-way flywheel, the Maxwell branch, the one-shot, the sampled loop; one
per recording) are advanced once per 0.2 ms input segment from the state at the segment's start (kernel.py
"memory"), like the third set's relay; they act in the run with every term, from the run-in's start (2 s before
sample 0), not in the settled start's period map.
"""
from __future__ import annotations

import math

import numpy as np

from . import kernel as K
from . import noise as N
from .forms import Param
from .outside import OutsideForm, add_term


def set_memory(b, name: str, kind: int, selector: int, a: float, bb: float = 0.0, c: float = 0.0) -> None:
    """Give the recording's one memory element (kernel.memory_scan) to a mechanism: its kind (K.MK_*), the quantity it
    reads (K.XS_*) and its parameters."""
    if b.P[K.P_MEMKIND] != 0.0:
        raise ValueError(f"{name}: a second mechanism with a memory element in one recording; allowed: one")
    b.P[K.P_MEMKIND], b.P[K.P_MEMSEL] = float(kind), float(selector)
    b.P[K.P_MEMA], b.P[K.P_MEMB], b.P[K.P_MEMC] = a, bb, c


def segments(seconds: float, what: str) -> int:
    """A time that must be a whole number of 0.2 ms input segments, in segments."""
    n = seconds / N.SEGMENT_S
    if abs(n - round(n)) > 1e-6:
        raise ValueError(f"{what} = {seconds:g} s is not a whole number of 0.2 ms segments; allowed: a multiple of "
                         "0.0002 s")
    return int(round(n))


def oneshot_reference(x_at_scans, threshold: float, hold_scans: int, state0=None) -> np.ndarray:
    """The one-shot memory element (K.MK_ONESHOT) re-run scan by scan in Python, for the tests: on at a scan whose value
    rises through ``threshold`` from the scan before while off, off again ``hold_scans`` scans after it fired. ``state0``
    = (on, scans since it fired, the value at the scan before the first); None: off, no value before the first scan
    (the run-in's start). -> the state after each scan."""
    x = np.asarray(x_at_scans, dtype=np.float64).tolist()
    m, since, prev = (0.0, 0, None) if state0 is None else state0
    out = np.zeros(len(x))
    for i, v in enumerate(x):
        if m and since >= hold_scans:
            m = 0.0
        if prev is not None and not m and prev <= threshold < v:
            m, since = 1.0, 0
        since += 1
        prev = v
        out[i] = m
    return out


# 1. motor load moment x the stroke count
class MotorNthStrokePierce(OutsideForm):
    name = "motor_nth_stroke_pierce"
    half = "dev4"
    balance = "motor_load_moment"
    depends_on = ("load_pulse",)
    description = ("a progressive die whose piercing station works on every N-th part only (a hole every N parts): an "
                   "extra load T on the motor while the pulse of the strokes k = m (mod N) is on, k the stroke's number "
                   "(0: the first pulse at or after sample 0)")
    parameters = (Param("torque_Nm", "N*m", (0.0, 50.0), "T"),
                  Param("every_n", "strokes", (2, 8), "N", "int"),
                  Param("station", "-", (0, 7), "m (below N): which stroke of each N", "int"))
    note = "a sub-harmonic of the pulse train: period N*0.25 s; the other strokes are the nominal pulse"

    def apply(self, b, p):
        n, m = int(p["every_n"]), int(p["station"])
        if m >= n:
            raise ValueError(f"{self.name}: station {m} is not below every_n {n}; allowed: 0 .. every_n - 1")
        add_term(b, "motor_load_moment", p["torque_Nm"], (K.XS_PULSE, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_PULSE_COUNT, K.XF_PERIODIC_GATE, float(n), float(m), 0.5), nonperiodic=True)

    @staticmethod
    def torque(stroke_number, pulse, p):
        k = np.asarray(stroke_number)
        return p["torque_Nm"] * np.asarray(pulse) * (np.mod(k - p["station"], p["every_n"]) == 0)

    def law(self, p):
        return (f"motor load moment += {p['torque_Nm']:.6g} N*m * pulse while k mod {p['every_n']} = {p['station']}, "
                "k the stroke's number (0: the first pulse at or after sample 0), pulse = 1 while it is on")


# 3. wheel torque x the wheel speed through a one-way memory
class WheelFreewheelFlywheel(OutsideForm):
    name = "wheel_freewheel_flywheel"
    half = "dev4"
    balance = "wheel_torque"
    depends_on = ("wheel_speed",)
    description = ("a feed roll's flywheel on the wheel shaft behind an overrunning (sprag) clutch with a compliant "
                   "coupling: whenever the wheel runs faster than the flywheel it drags it up, -c*(Omega2 - w_f) on the "
                   "wheel, dw_f/dt = (Omega2 - w_f)/tau_l; otherwise the flywheel coasts on its bearing drag, "
                   "dw_f/dt = -w_f/tau_c (w_f advanced once per 0.2 ms from Omega2 at the segment's start)")
    parameters = (Param("coefficient_Nms_per_rad", "N*m*s/rad", (0.0, 50.0), "c: the coupling's torque per rad/s"),
                  Param("lock_time_s", "s", (1e-3, 1.0), "tau_l = J_f/c"),
                  Param("coast_time_s", "s", (0.1, 1000.0), "tau_c: the flywheel's coast-down time constant"))
    note = "a memory: the flywheel keeps the highest recent wheel speed, and brakes the wheel only above it"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_LAG, K.XS_OMEGA2, p["lock_time_s"], p["coast_time_s"], 1.0)
        add_term(b, "wheel_torque", -p["coefficient_Nms_per_rad"],
                 (K.XS_MEMORY_EXCESS, K.XF_EXCESS_POWER, 0.0, 1.0, 0.0), nonperiodic=True)

    @staticmethod
    def flywheel_speed(omega2_at_segments, p):
        """w_f at each segment's start, from Omega2 at the segments' starts (the first: w_f = Omega2)."""
        dt = N.SEGMENT_S
        up, down = math.exp(-dt / p["lock_time_s"]), math.exp(-dt / p["coast_time_s"])
        x = np.asarray(omega2_at_segments, dtype=np.float64).tolist()
        out = np.empty(len(x))
        m = x[0]
        for i, v in enumerate(x):
            if i:
                m = v + (m - v) * up if v > m else m * down
            out[i] = m
        return out

    def law(self, p):
        return (f"wheel torque += -{p['coefficient_Nms_per_rad']:.6g} N*m*s/rad * max(0, Omega2 - w_f); w_f -> Omega2 "
                f"with {p['lock_time_s']:.6g} s while Omega2 > w_f, else w_f decays with {p['coast_time_s']:.6g} s "
                "(advanced every 0.2 ms)")


# 5. clutch torque x the penetration through a relaxation
class ClutchViscoelasticInsert(OutsideForm):
    name = "clutch_viscoelastic_insert"
    half = "dev4"
    balance = "clutch_torque"
    depends_on = ("clutch_penetration",)
    description = ("the jaw's elastomer insert is viscoelastic (a standard linear solid): its contact law gains a "
                   "Maxwell branch, k_c*p + d_c*p' + k_m*(p - q), p the penetration, q the branch's relaxed "
                   "penetration, dq/dt = (p - q)/tau (q advanced once per 0.2 ms; p = 0 in the gap, where q relaxes to "
                   "0); the contact holds while this whole law's torque is positive")
    parameters = (Param("stiffness_Nm_per_rad", "N*m/rad", (0.0, 10000.0), "k_m: the branch's stiffness"),
                  Param("relaxation_time_s", "s", (1e-3, 1.0), "tau"))
    note = "stiffer in a fast impact than while pressing steadily: the branch relaxes to 0 under a constant penetration"

    def apply(self, b, p):
        tau = p["relaxation_time_s"]
        set_memory(b, self.name, K.MK_LAG, K.XS_PENETRATION_DEPTH, tau, tau, 0.0)
        b.P[K.P_MAXK] = p["stiffness_Nm_per_rad"]

    def law(self, p):
        return (f"clutch: the contact law is k_c*p + d_c*p' + {p['stiffness_Nm_per_rad']:.6g} N*m/rad * (p - q), q -> p "
                f"with {p['relaxation_time_s']:.6g} s (advanced every 0.2 ms; p = 0 in the gap), in contact while it "
                "is positive; p the penetration on either side")


# 7. mass force x the spring extension through a one-shot timer
class MassSpringSwitchClamp(OutsideForm):
    name = "mass_spring_switch_clamp"
    half = "dev4"
    balance = "mass_force"
    depends_on = ("spring_extension",)
    description = ("a proximity switch on the spring's bracket fires a pneumatic rail clamp on the carriage for a fixed "
                   "time T_h each time the spring's extension rises through z_on (a PLC one-shot scanned every 0.2 ms, "
                   "not retriggered while it runs): -F*sign(v) while it runs")
    parameters = (Param("force_N", "N", (0.0, 200.0), "F"),
                  Param("trigger_extension_m", "m", (0.0, 1.0), "z_on"),
                  Param("hold_s", "s", (1e-3, 1.0), "T_h"))
    note = "a memory with its own clock: the clamp's duration does not depend on how long the spring stays stretched"

    def apply(self, b, p):
        set_memory(b, self.name, K.MK_ONESHOT, K.XS_SPRING_EXTENSION, p["trigger_extension_m"], p["hold_s"])
        add_term(b, "mass_force", -p["force_N"], (K.XS_MEMORY, K.XF_X, 0.0, 0.0, 0.0),
                 (K.XS_MASS_SPEED, K.XF_TANH, 0.01, 0.0, 0.0), nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['force_N']:.6g} N * sign(v) for {p['hold_s']:.6g} s from each scan (0.2 ms) at "
                f"which z has risen through {p['trigger_extension_m']:.6g} m, not retriggered while it runs; z the "
                "spring extension")


# 9. a1 sensor x a1's own rate
class A1IsolationAmpSlew(OutsideForm):
    name = "a1_isolation_amp_slew"
    half = "dev4"
    stage = "sensor"
    order = 1                      # the isolation amplifier, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration",)
    description = ("the rotating a1 channel passes an isolation amplifier whose output slews at most S: from one sample "
                   "to the next it moves towards the input by at most S*T_s")
    parameters = (Param("slew_rate_m_s3", "m/s^3", (1e3, 1e9), "S"),)
    note = "the jaw's impacts (the fastest edges of a1) read slower and lower; slow content passes"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.limited(sig["a1"], p["slew_rate_m_s3"] / fs)

    @staticmethod
    def limited(a, step):
        x = np.asarray(a, dtype=np.float64).tolist()
        out = np.empty(len(x))
        y = x[0]
        for k, v in enumerate(x):
            d = v - y
            y = y + (step if d > step else (-step if d < -step else d))
            out[k] = y
        return out

    def law(self, p):
        return (f"a1 sensor: a1[k] = a1[k-1] + clip(a[k] - a1[k-1], +-{p['slew_rate_m_s3']:.6g} m/s^3 * T_s), a the "
                "input (a slew-rate limit)")


# 11. a1 sensor x the motor angle as a gate on a hold
class A1TelemetryShadowHold(OutsideForm):
    name = "a1_telemetry_shadow_hold"
    half = "dev4"
    stage = "sensor"
    order = 1                      # the radio link, after the sensing element
    uses_states = True
    balance = "sensor"
    depends_on = ("motor_acceleration", "motor_angle")
    description = ("a1's rotating telemetry loses its radio link while its antenna passes behind the motor frame, once "
                   "per revolution, while (alpha1 - alpha_s) mod 2*pi < w; the receiver holds the last value it got")
    parameters = (Param("window_rad", "rad", (0.0, math.pi), "w"),
                  Param("start_rad", "rad", (-math.pi, math.pi), "alpha_s (on the simulator's angle)"))
    note = "held steps once per revolution (about 24 Hz), their length w/Omega1"

    def apply_signal(self, sig, p, t, fs, states=None):
        sig["a1"] = self.held(sig["a1"], states["alpha1"], p)

    @staticmethod
    def shadowed(alpha1, p):
        return np.mod(np.asarray(alpha1) - p["start_rad"], 2.0 * math.pi) < p["window_rad"]

    @classmethod
    def held(cls, a, alpha1, p):
        a = np.asarray(a, dtype=np.float64)
        inside = cls.shadowed(alpha1, p)
        last = np.where(inside, 0, np.arange(a.size))
        np.maximum.accumulate(last, out=last)
        return a[last]

    def law(self, p):
        return (f"a1 sensor = the last a1 received: none while (alpha1 - {p['start_rad']:.6g}) mod 2*pi < "
                f"{p['window_rad']:.6g} rad")


# 13. mass force x the mass speed sampled and delayed
class MassServoAssistSampled(OutsideForm):
    name = "mass_servo_assist_sampled"
    half = "dev4"
    balance = "mass_force"
    depends_on = ("mass_speed",)
    description = ("a linear motor on the carriage holds the carriage's speed under a digital speed loop: it samples v "
                   "every scan T_s and applies, L scans later, -K*(v_sampled - v_ref), held until the next scan")
    parameters = (Param("gain_Ns_per_m", "N*s/m", (0.0, 1000.0), "K"),
                  Param("reference_speed_m_s", "m/s", (0.0, 40.0), "v_ref"),
                  Param("scan_s", "s", (2e-4, 0.01), "T_s (a multiple of 0.2 ms)"),
                  Param("latency_scans", "scans", (0, 63), "L", "int"))
    note = "a sampled-data loop with a dead time: piecewise constant, L*T_s behind the speed it corrects"

    def apply(self, b, p):
        scan = segments(p["scan_s"], f"{self.name}: scan_s")
        set_memory(b, self.name, K.MK_DELAY, K.XS_MASS_SPEED, float(scan), float(p["latency_scans"]))
        add_term(b, "mass_force", -p["gain_Ns_per_m"], (K.XS_MEMORY, K.XF_CLIP, 1e9, -p["reference_speed_m_s"], 0.0),
                 nonperiodic=True)

    def law(self, p):
        return (f"mass force += -{p['gain_Ns_per_m']:.6g} N*s/m * (v_s - {p['reference_speed_m_s']:.6g} m/s), v_s the "
                f"mass speed sampled every {p['scan_s']:.6g} s and applied {p['latency_scans']} scan(s) later, held")


FORM_CLASSES = (MotorNthStrokePierce, WheelFreewheelFlywheel, ClutchViscoelasticInsert, MassSpringSwitchClamp,
                A1IsolationAmpSlew, A1TelemetryShadowHold, MassServoAssistSampled)
