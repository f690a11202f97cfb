"""make_recording: a RecordingSpec -> the drive's five recorded signals at 50 kHz, its sample period, its truth."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import constants as C
from . import forms as F
from . import kernel as K
from . import noise as N
from .physics import nominal_parameters
from .simulation import DEFAULT_PRE_ROLL_S, simulate
from .spec import RecordingSpec, Truth

SIGNALS = tuple(C.SIGNAL_UNITS)


@dataclass
class Recording:
    """One made recording: ``signals`` {a1, a2, omega1, omega2, angle_difference} (float64, SI units of
    constants.SIGNAL_UNITS), sample 0 = the first sample after the settled start; ``internal`` holds what a
    real drive does not show (the accelerations before the sensor chain, the clutch torque, ...) for tests."""
    spec: RecordingSpec
    signals: dict
    sample_period_s: float
    truth: Truth
    internal: dict = field(default_factory=dict)
    stats: dict = field(default_factory=dict)

    @property
    def n_samples(self) -> int:
        return len(self.signals["a1"])

    def true_entries(self) -> list:
        """[(sample_index, "onset" | "return")]: the true backlash-zone entries, from the jaw's exact angle
        difference and the true width: |D_k| < beta after |D_k-1| >= beta; "onset" when D_k-1 > 0 (the load
        side overran the motor as a pulse began), "return" otherwise (the motor catches up after it)."""
        d = self.internal["jaw_angle_difference"]
        beta = self.truth.true_width_m / C.WHEEL_RADIUS_M
        inside = np.abs(d) < beta
        ks = np.flatnonzero(inside[1:] & ~inside[:-1]) + 1
        return [(int(k), "onset" if d[k - 1] > 0 else "return") for k in ks]

    def summary(self) -> dict:
        """What the made recording holds, for the manifest: true entries and their spacing, the run's figures."""
        ent = self.true_entries()
        ks = [k for k, _ in ent]
        return {"n_samples": self.n_samples, "sample_period_s": self.sample_period_s,
                "onset_entries": [k for k, kd in ent if kd == "onset"],
                "return_entries": [k for k, kd in ent if kd == "return"],
                "min_entry_spacing_samples": int(np.min(np.diff(ks))) if len(ks) > 1 else None,
                # the simulator's shaft angles at sample 0 (mod 2*pi): a law locked to an angle, stated in the
                # simulator's angle, has the phase phi + alpha(0) on the recording's own angle (integral of omega)
                "angles_at_sample0_rad": {k: float(np.mod(self.internal[k][0], 2.0 * math.pi))
                                          for k in ("alpha1", "alpha2") if k in self.internal},
                "integrator": {k: v for k, v in self.stats.items()}}


def build_parameters(spec: RecordingSpec):
    """(parameter vector, Build) of a spec's drive: nominal values, then the drifts, then the physics forms."""
    P = nominal_parameters(spec.width_m, spec.eta_k, spec.n1)
    b = F.Build(P, spec.width_m, spec.eta_k, spec.n1)
    checked = [e.checked() for e in spec.effects]
    for stage in ("drift", "physics"):
        for e in checked:
            form = F.get(e.form)
            if form.stage == stage:
                form.apply(b, e.parameters)
    return P, b


def apply_sensor_chain(spec: RecordingSpec, accel: dict, t: np.ndarray, fs: float, states: dict | None = None) -> dict:
    """The sensor forms on {a1, a2} (sensing element's gain and bias first, then the low-pass filters, each
    group in spec order), then the nuisance: white noise from the recording's sensor streams, the ADC's
    quantisation. ``accel`` arrays include the pre-roll; ``t`` their times [s] (t = 0 at sample 0)."""
    sig = {k: np.array(v, dtype=np.float64) for k, v in accel.items()}
    checked = [e.checked() for e in spec.effects]
    sensors = [(F.get(e.form), e.parameters) for e in checked if F.get(e.form).stage == "sensor"]
    for order in (0, 1):
        for form, p in sensors:
            if form.order == order:
                if getattr(form, "uses_states", False):      # an outside sensor mechanism reads the run's states
                    form.apply_signal(sig, p, t, fs, states=states)
                else:
                    form.apply_signal(sig, p, t, fs)
    s = spec.sensor
    rng = N.streams(spec.seed)
    for name in ("a1", "a2"):
        rms = getattr(s, f"{name}_noise_rms_m_s2")
        if rms > 0:
            sig[name] = sig[name] + rms * rng[f"sensor_{name}"].standard_normal(sig[name].size)
        lsb = getattr(s, f"{name}_lsb_m_s2")
        if lsb > 0:
            sig[name] = np.round(sig[name] / lsb) * lsb
    return sig


def pulse_indicator(t: np.ndarray, pulse_first_s: float) -> np.ndarray:
    """The load pulse's indicator (1 while a pulse is on, else 0) at the sample times ``t`` [s] (t = 0 at sample 0),
    on the inputs' 0.2 ms segment grid exactly as the kernel holds it."""
    seg = np.floor(np.asarray(t) / N.SEGMENT_S + 1e-9).astype(np.int64)
    s0 = int(seg.min())
    return N.pulse_train(s0, int(seg.max()) - s0 + 1, 1.0, pulse_first_s)[seg - s0]


def mass_position(alpha2: np.ndarray, z: np.ndarray, P: np.ndarray) -> np.ndarray:
    """The carriage's position unwrapped from the run-in's start [m] (the kernel's XS_MASS_POSITION) at each sample of
    a run: r*alpha2 - z on the wheel's angle unwrapped, with the whole turns the integrator took off by the run's end
    (P after the run: alpha2_turns) put back."""
    theta = np.unwrap(alpha2)
    end = alpha2[-1] + 2.0 * math.pi * P[K.P_A2TURNS]
    return P[K.P_R] * (end - (theta[-1] - theta)) - z


def measured_angle_difference(alpha1: np.ndarray, alpha2: np.ndarray, counts_per_rev: int, offset_rad: float):
    """alpha1 - alpha2 as two shaft encoders give it: each angle floored to its encoder's count (0 = exact),
    plus the encoders' zero offset. The angles come re-referenced by the same whole turns (integrator), which
    leaves the count difference unchanged."""
    if counts_per_rev > 0:
        q = 2.0 * math.pi / counts_per_rev
        d = (np.floor(alpha1 / q) - np.floor(alpha2 / q)) * q
    else:
        d = alpha1 - alpha2
    return d + offset_rad


def make_recording(spec: RecordingSpec, tol_scale: float = 1.0) -> Recording:
    """Simulate the spec's drive and record it (deterministic for a spec)."""
    spec.check()
    truth = spec.truth()
    P, b = build_parameters(spec)
    run = simulate(P, duration_s=spec.duration_s, seed=spec.seed, noise=spec.noise,
                   pulse_amplitude_pu=b.pulse_amplitude_pu, pulse_first_s=spec.pulse_first_s,
                   run_in_s=spec.run_in_s, pre_roll_s=DEFAULT_PRE_ROLL_S, tol_scale=tol_scale)
    fs = C.SAMPLE_RATE_HZ
    n_pre = -run.first_index
    t = (np.arange(run.out.shape[0]) - n_pre) / fs
    accel = {"a1": run.signal("a1", pre_roll=True), "a2": run.signal("a2", pre_roll=True)}
    states = {"alpha1": run.signal("alpha1", pre_roll=True), "alpha2": run.signal("alpha2", pre_roll=True),
              "omega1": run.signal("omega1", pre_roll=True),
              "a1_physical": accel["a1"], "a2_physical": accel["a2"],
              "spring_extension": run.signal("spring_extension", pre_roll=True),
              "mass_speed": run.signal("mass_speed", pre_roll=True), "mode": run.signal("mode", pre_roll=True),
              "te_pu": run.signal("te_pu", pre_roll=True), "pulse": pulse_indicator(t, spec.pulse_first_s),
              "mass_position": mass_position(run.signal("alpha2", pre_roll=True),
                                             run.signal("spring_extension", pre_roll=True), P),
              "clutch_torque_Nm": run.signal("clutch_torque_Nm", pre_roll=True)}
    sensed = apply_sensor_chain(spec, accel, t, fs, states=states)
    sig = {"a1": sensed["a1"][n_pre:], "a2": sensed["a2"][n_pre:],
           "omega1": run.signal("omega1").copy(), "omega2": run.signal("omega2").copy(),
           "angle_difference": measured_angle_difference(run.signal("alpha1"), run.signal("alpha2"),
                                                         int(spec.sensor.encoder_counts_per_rev),
                                                         spec.sensor.angle_offset_rad)}
    internal = {"a1_physical": accel["a1"][n_pre:].copy(), "a2_physical": accel["a2"][n_pre:].copy(),
                "angle_difference_exact": run.signal("angle_difference").copy(),
                "jaw_angle_difference": run.signal("jaw_angle_difference").copy(),
                "clutch_torque_Nm": run.signal("clutch_torque_Nm").copy(), "te_pu": run.signal("te_pu").copy(),
                "rim_force_N": run.signal("rim_force_N").copy(), "mode": run.signal("mode").copy(),
                "alpha1": run.signal("alpha1").copy(), "alpha2": run.signal("alpha2").copy(),
                "wheel_acceleration": run.signal("wheel_acceleration").copy(),
                "mass_speed": run.signal("mass_speed").copy(), "spring_extension": run.signal("spring_extension").copy(),
                "parameters": P, "pulse_amplitude_pu": b.pulse_amplitude_pu}
    return Recording(spec=spec, signals=sig, sample_period_s=C.SAMPLE_PERIOD_S, truth=truth, internal=internal,
                     stats=run.stats)
