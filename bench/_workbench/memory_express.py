"""Can first-order lags at fixed time constants express what the memory mechanisms of foreign_drives do? (issue 31
part 2; docs/workbench.md "Terms with memory")

    python bench/_workbench/memory_express.py [TAU_S,TAU_S,...]      (default 0.01,0.1: plant/lags.py LAG_TIMES_S)

On one recording of each memory row (development data: outside_dev4/5 and the spent sealed halves 4, 5): the
generator's true term's signal, from its law on the simulator's recorded and internal states at 50 kHz (its 0.2 ms
scan not reproduced), fitted by least squares over every sample with: the instantaneous terms of the library's kind
(the own state's deviation from its mean, the pulse), then with the class's lags added (q - lag_tau(q) of the own
state, lag_tau of the pulse). R2 is a fit of a known signal, not a selection: it says whether the class can express
the mechanism, not whether the proposal finds it on 16 events.
"""
import json
import math
import os
import sys
from pathlib import Path

import numpy as np
from scipy.signal import lfilter

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
from foreign_drives.drive import make_recording, pulse_indicator      # noqa: E402
from foreign_drives.kernel import P_BETA                              # noqa: E402
from foreign_drives.suites import suite                               # noqa: E402

FS = 50000.0

ROWS = (("outside_sealed4", "os4_motor_belt_flywheel", "motor_belt_flywheel"),
        ("outside_dev4", "od4_clutch_viscoelastic_insert", "clutch_viscoelastic_insert"),
        ("outside_dev4", "od4_wheel_freewheel_flywheel", "wheel_freewheel_flywheel"),
        ("outside_sealed5", "os5_wheel_eddy_brake_field_lag", "wheel_eddy_brake_field_lag"),
        ("outside_dev4", "od4_mass_servo_assist_sampled", "mass_servo_assist_sampled"),
        ("outside_dev5", "od5_motor_governor_linkage_play", "motor_governor_linkage_play"))


def lag(x, tau, x0=None):
    """The first-order lag of x at tau (x held over each sample), started at x0 (default x[0])."""
    a = math.exp(-1.0 / (FS * tau))
    m = x[0] if x0 is None else x0
    y, _ = lfilter([1 - a], [1, -a], x, zi=[a * m])
    return y


def r2(target, cols):
    """The share of target's variance a least-squares fit with cols (and a constant) explains."""
    A = np.column_stack(cols + [np.ones_like(target)])
    c, *_ = np.linalg.lstsq(A, target, rcond=None)
    return float(1 - (target - A @ c).var() / target.var())


def scan(x, step_of, m0):
    """A memory advanced sample by sample: m_k = step_of(m_{k-1}, x_k), m_0 = step_of(m0, x_0)."""
    out, m = np.empty_like(x), m0
    for i, v in enumerate(x.tolist()):
        m = step_of(m, v)
        out[i] = m
    return out


def true_term(form, p, w1, w2, xd, pulse, pen):
    """(the state the mechanism reads, its term's signal) from the law in foreign_drives (at 50 kHz)."""
    if form == "motor_belt_flywheel":
        return w1, p["coefficient_Nms_per_rad"] * (w1 - lag(w1, p["time_constant_s"]))
    if form == "clutch_viscoelastic_insert":
        return pen, p["stiffness_Nm_per_rad"] * (pen - lag(pen, p["relaxation_time_s"], 0.0)) * (pen > 0)
    if form == "wheel_freewheel_flywheel":
        up, down = math.exp(-1 / (FS * p["lock_time_s"])), math.exp(-1 / (FS * p["coast_time_s"]))
        wf = scan(w2, lambda m, v: v + (m - v) * up if v > m else m * down, w2[0])
        return w2, -p["coefficient_Nms_per_rad"] * np.maximum(0, w2 - wf)
    if form == "wheel_eddy_brake_field_lag":
        return w2, -p["coefficient_Nms_per_rad"] * w2 * lag(pulse, p["time_constant_s"], 0.0)
    if form == "mass_servo_assist_sampled":
        d, sc = int(round(p["scan_s"] * p["latency_scans"] * FS)), int(round(p["scan_s"] * FS))
        held = np.repeat(xd[::sc], sc)[:xd.size]
        delayed = np.concatenate([np.full(d, held[0]), held[:-d]])
        return xd, -p["gain_Ns_per_m"] * (delayed - p["reference_speed_m_s"])
    if form == "motor_governor_linkage_play":
        h = p["play_rad_s"]
        m = scan(w1, lambda m, v: min(max(m, v - h), v + h), w1[0])
        return w1, p["gain_Nms_per_rad"] * np.maximum(0, m - p["set_speed_rad_s"])
    raise ValueError(form)


def main(taus):
    out = {}
    for name, label, form in ROWS:
        spec = next(s for s in suite(name) if s.label == label)
        rec = make_recording(spec)
        s, it = rec.signals, rec.internal
        w1, w2, xd = s["omega1"], s["omega2"], it["mass_speed"]
        pulse = pulse_indicator(np.arange(w1.size) / FS, spec.pulse_first_s).astype(float)
        pen = np.where(it["mode"] != 0, np.abs(it["jaw_angle_difference"]) - float(it["parameters"][P_BETA]), 0.0)
        (eff,) = spec.effects
        x, true = true_term(form, eff.parameters, w1, w2, xd, pulse, pen)
        clutch = form.startswith("clutch")
        gate = (pen > 0) if clutch else np.ones_like(x, bool)         # a clutch term acts in contact only
        dev = (x - x.mean()) * gate                                  # the own state's deviation (tau = inf)
        hp = [(x - lag(x, tau, 0.0 if clutch else None)) * gate for tau in taus]
        lp_pulse = [lag(pulse, tau, 0.0) for tau in taus]
        out[label] = {"true_rms": float(true.std()), "taus_s": list(taus),
                      "r2_instantaneous": r2(true, [dev, pulse]),
                      "r2_with_state_lags": r2(true, [dev, pulse] + hp),
                      "r2_with_pulse_lags": r2(true, [dev, pulse] + lp_pulse),
                      "r2_with_both": r2(true, [dev, pulse] + hp + lp_pulse)}
        print(label, json.dumps(out[label]), flush=True)
    return out


if __name__ == "__main__":
    os.environ.setdefault("NUMBA_NUM_THREADS", "1")
    main(tuple(float(v) for v in sys.argv[1].split(",")) if len(sys.argv) > 1 else (0.01, 0.1))
