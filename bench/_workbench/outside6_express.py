"""Can the proposal's library (its instantaneous terms of the truth's balance; the lags of MEMORY_IN_LIBRARY) express
the sixth set's true terms at all? (issue 31 part 2; docs/workbench.md "The sixth set's misses, measured")

    python bench/_workbench/outside6_express.py [OUT.json]

Both halves of set 6 are development data (the sealed half was run once, 30 Nov). As memory_express.py: the
generator's true term's signal, from its law on the foreign simulator's states at 50 kHz (its 0.2 ms scan approximated
on the samples), fitted by least squares over every sample (and a constant); R2 is a fit of a known signal, not a
selection: it says whether the library's kind of term can express the mechanism, not whether the proposal finds it on
16 events. The torque limiter's uncapped contact torque is read off the same drive without the limiter (same seed)."""
import dataclasses
import json
import sys

import numpy as np

from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _workbench.memory_express import lag, r2                          # noqa: E402
from foreign_drives.drive import make_recording, pulse_indicator      # noqa: E402
from foreign_drives.kernel import P_BETA                              # noqa: E402
from foreign_drives.suites import suite                               # noqa: E402
from foreign_drives.outside_sealed6 import MotorBatchBlankThickness   # noqa: E402

FS = 50000.0
SCAN = 10                                  # 0.2 ms at 50 kHz


def held(x, every):
    """x sampled at every ``every``-th sample and held."""
    return np.repeat(x[::every], every)[:x.size]


def rec_of(name, label):
    spec = next(s for s in suite(name) if s.label == label)
    return spec, make_recording(spec)


def states(spec, rec):
    s, it = rec.signals, rec.internal
    t = np.arange(s["omega1"].size) / FS
    pulse = pulse_indicator(t, spec.pulse_first_s).astype(float)
    pen = np.where(it["mode"] != 0, np.abs(it["jaw_angle_difference"]) - float(it["parameters"][P_BETA]), 0.0)
    return dict(t=t, w1=s["omega1"], w2=s["omega2"], xd=it["mass_speed"], z=it["spring_extension"], pulse=pulse,
                pen=pen, a2=it["a2_physical"], tc=it["clutch_torque_Nm"], jaw=it["jaw_angle_difference"])


def dev(x):
    return x - x.mean()


def lags(x, taus=(0.01, 0.1)):
    return [x - lag(x, tau) for tau in taus]


def plags(pulse, taus=(0.01, 0.1)):
    return [lag(pulse, tau, 0.0) for tau in taus]


out = {}


def report(label, true, sets):
    res = {"true_rms": float(true.std())}
    for name, cols in sets.items():
        if cols is not None:
            res[name] = round(r2(true, cols), 4)
    out[label] = res
    print(label, json.dumps(res), flush=True)


# 13 PWM brake (wheel, Omega2 sampled every 5 ms, duty over the period)
spec, rec = rec_of("outside_dev6", "od6_wheel_pwm_brake")
S = states(spec, rec)
p = spec.effects[0].parameters
per = int(round(p["carrier_period_s"] * FS))
w2s = held(S["w2"], per)
duty = np.clip((w2s - p["zero_duty_speed_rad_s"]) / p["full_duty_span_rad_s"], 0, 1)
phase = (np.arange(S["w2"].size) % per) / per
true = -p["torque_Nm"] * (phase < duty)
true_mean = -p["torque_Nm"] * duty
base = [dev(S["w2"]), S["pulse"], np.sign(S["w2"])]
report("od6_wheel_pwm_brake", true, {"instantaneous (Omega2 dev, pulse)": base, "+ lags": base + lags(S["w2"]) + plags(S["pulse"])})
report("od6_wheel_pwm_brake carrier mean", true_mean, {"instantaneous (Omega2 dev, pulse)": base,
                                                        "+ lags": base + lags(S["w2"]) + plags(S["pulse"])})

# 4 PI speed brake (wheel, PI with clamping anti-windup on [0, T_max], 0.2 ms scans)
spec, rec = rec_of("outside_sealed6", "os6_wheel_pi_speed_brake")
S = states(spec, rec)
p = spec.effects[0].parameters
kp, ki, tmax, ref = (p["proportional_Nms_per_rad"], p["integral_Nm_per_rad"], p["max_torque_Nm"],
                     p["reference_speed_rad_s"])
w2s = S["w2"][::SCAN]
u = np.empty_like(w2s)
integ = 0.0                    # started at the recording's first sample (the generator: the run-in's start)
dt = SCAN / FS
for i, w in enumerate(w2s.tolist()):
    e = w - ref
    v = kp * e + integ
    if not ((v >= tmax and e > 0) or (v <= 0 and e < 0)):
        integ += ki * e * dt
    u[i] = min(max(kp * e + integ, 0.0), tmax)
true = -np.repeat(u, SCAN)[:S["w2"].size]
half = slice(S["w2"].size // 4, None)      # after the integrator's start-up
base = [dev(S["w2"]), S["pulse"]]
report("os6_wheel_pi_speed_brake", true[half], {"instantaneous (Omega2 dev, pulse)": [c[half] for c in base],
                                                "+ lags": [c[half] for c in base + lags(S["w2"]) + plags(S["pulse"])]})
out["os6_wheel_pi_speed_brake"]["u_mean_Nm"] = float(u.mean())
out["os6_wheel_pi_speed_brake"]["u_at_limit_share"] = float(np.mean((u <= 0) | (u >= tmax)))

# 8 rate-limited balancer (mass, K*(m - z_ref), m -> z at most R)
spec, rec = rec_of("outside_sealed6", "os6_mass_rate_limited_balancer")
S = states(spec, rec)
p = spec.effects[0].parameters
zs = S["z"][::SCAN]
m = np.empty_like(zs)
cur = zs[0]
step = p["rate_m_s"] * SCAN / FS
for i, zz in enumerate(zs.tolist()):
    cur += min(max(zz - cur, -step), step)
    m[i] = cur
true = p["gain_N_per_m"] * (np.repeat(m, SCAN)[:S["z"].size] - p["reference_extension_m"])
base = [dev(S["xd"]), S["pulse"]]
report("os6_mass_rate_limited_balancer", true, {"mass terms (xdot dev, pulse)": base,
                                               "+ lags": base + lags(S["xd"]) + plags(S["pulse"]),
                                               "+ z (not in the mass balance)": base + [S["z"]]})
out["os6_mass_rate_limited_balancer"]["rate_limited_share"] = float(np.mean(np.abs(np.diff(zs)) > step))

# 12 accumulator unloader (motor, hidden integrator + two-point valve)
spec, rec = rec_of("outside_sealed6", "os6_motor_accumulator_unloader")
S = states(spec, rec)
p = spec.effects[0].parameters
w1s, ps = S["w1"][::SCAN], S["pulse"][::SCAN]
pr, on = p["low_bar"], 1.0
load = np.empty_like(w1s)
for i in range(w1s.size):
    pr = max(pr + (on * p["fill_bar_per_rad"] * w1s[i] - p["use_bar_per_s"] * ps[i]) * SCAN / FS, 0.0)
    if pr > p["high_bar"]:
        on = 0.0
    elif pr < p["low_bar"]:
        on = 1.0
    load[i] = p["displacement_Nm_per_bar"] * on * pr
true = np.repeat(load, SCAN)[:S["w1"].size]
base = [dev(S["w1"]), S["pulse"], S["t"] / S["t"][-1]]
report("os6_motor_accumulator_unloader", true, {"motor terms (Omega1 dev, pulse, t/T)": base,
                                               "+ lags": base + lags(S["w1"]) + plags(S["pulse"])})
out["os6_motor_accumulator_unloader"]["on_share"] = float(np.mean(load > 0))

# 2 batch blank thickness (motor, pulse * T * u_k)
spec, rec = rec_of("outside_sealed6", "os6_motor_batch_blank_thickness")
S = states(spec, rec)
p = spec.effects[0].parameters
k = np.cumsum(np.r_[0.0, np.diff(S["pulse"]) > 0])
true = S["pulse"] * p["torque_Nm"] * MotorBatchBlankThickness.u(k, p["seed"])
base = [dev(S["w1"]), S["pulse"], S["t"] / S["t"][-1]]
report("os6_motor_batch_blank_thickness", true, {"motor terms (Omega1 dev, pulse, t/T)": base,
                                                "+ lags": base + lags(S["w1"]) + plags(S["pulse"])})

# 9 one-sided a2 gain (sensor a2 += g*|a|)
spec, rec = rec_of("outside_dev6", "od6_a2_bilinear_gain")
S = states(spec, rec)
a = S["a2"]
true = spec.effects[0].parameters["asymmetry"] * np.abs(a)
report("od6_a2_bilinear_gain", true, {"a2's recorded terms (a, (a/50)^3, t/T)": [a, (a / 50) ** 3, S["t"]],
                                      "+ |a| (not in the library)": [a, (a / 50) ** 3, S["t"], np.abs(a)]})

# 5 torque limiter (clutch, -sign(T_c) max(0, |T_c| - T_lim)), T_c from the same drive without the limiter
spec = next(s for s in suite("outside_dev6") if s.label == "od6_clutch_torque_limiter")
spec0 = dataclasses.replace(spec, kind="clean", effects=[])
rec0 = make_recording(spec0)
S = states(spec0, rec0)
lim = spec.effects[0].parameters["limit_Nm"]
tc = S["tc"]
true = -np.sign(tc) * np.maximum(0, np.abs(tc) - lim)
pen = np.abs(S["jaw"]) - float(rec0.internal["parameters"][P_BETA])    # the model's penetration |D| - beta
gate = pen > 0
sgn = np.sign(S["jaw"]) * gate                 # the contact's side: the clutch torque's terms act along it
pn = np.where(gate, pen, 0.0)
pn = pn / max(float(np.percentile(pn[gate], 90)), 1e-12)
prn = np.gradient(pn) * FS
prn = prn / max(float(np.percentile(np.abs(prn[gate]), 90)), 1e-12)
cols = [sgn, sgn * pn, sgn * pn ** 2, sgn * prn, sgn * pn * prn]
report("od6_clutch_torque_limiter", true, {"clutch terms (1, p, p^2, p', p p', signed by the contact's side)": cols,
                                           "+ lags of p": cols + [c * sgn for c in lags(pn)],
                                           "the contact torque itself by the same (a check)": None})
out["od6_clutch_torque_limiter"]["the contact torque itself by the same (a check)"] = round(r2(tc, cols), 4)
out["od6_clutch_torque_limiter"]["limited_share_of_contact"] = float(np.mean(np.abs(tc[gate]) > lim))
if len(sys.argv) > 1:
    Path(sys.argv[1]).write_text(json.dumps(out, indent=1))
