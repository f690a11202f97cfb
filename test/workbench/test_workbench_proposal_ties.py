"""Which of a tied set of alike groups the proposal names (proposal._preferred, TIE_KEEPS_BALANCE; docs/workbench.md
"The sixth set's misses"). On a drive that never reverses, a near-constant load anywhere in the train (a wheel torque,
a mass force on the carriage's speed, a motor load) changes the events alike: the events cannot tell the balances
apart, only the largest held-out gain hints at one. The own-state preference picks the state within that balance; with
TIE_KEEPS_BALANCE it does not move the term to another body."""
import os

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.workbench import candidate_terms, proposal      # noqa: E402


def _tied_design():
    """16 events' whitened responses (8 coordinates each) to a constant wheel brake; a mass force on ẋ|ẋ| and a wheel
    torque on Ω₂ respond within a few per cent of it (ẋ and Ω₂ are near-constant at the operating point); the
    recording's residual is the wheel brake's response plus noise."""
    rng = np.random.default_rng(3)
    base = rng.normal(size=(16, 8))
    by = candidate_terms.by_name()
    terms = [by["cand_wheel_const"], by["cand_mass_xdot_2"], by["cand_wheel_omega2_1"]]
    G = np.stack([base, base + 0.05 * rng.normal(size=base.shape), base + 0.08 * rng.normal(size=base.shape)], axis=-1)
    Y = base + 0.3 * rng.normal(size=base.shape)
    return G, Y, [[0], [1], [2]], terms


def _named(flag, monkeypatch):
    G, Y, groups, terms = _tied_design()
    monkeypatch.setattr(proposal, "TIE_KEEPS_BALANCE", flag)
    alike = proposal.alike_groups(G, groups)
    GG, Gy, yy = proposal.gram(G, Y)
    sel, _ = proposal._forward_gram(GG, Gy, yy, groups, proposal.CV_Z, proposal.MAX_GROUPS, alike)
    gains = {terms[g[0]].group: float((proposal.cv_errors_gram(GG, Gy, yy, [])
                                       - proposal.cv_errors_gram(GG, Gy, yy, g)).mean()) for g in groups}
    named = proposal._preferred(GG, Gy, yy, groups, sel, alike, terms)
    return alike, [terms[groups[g][0]].group for g in sel], gains, [terms[groups[g][0]].group for g in named]


def test_the_own_state_preference_without_the_balance_rule_moves_a_wheel_brake_to_the_carriage(monkeypatch):
    """The three groups are alike (one tied set); the wheel's constant has the largest held-out gain and is selected;
    without the rule the own-state preference names the mass force on ẋ (the carriage's own state, the larger gain of
    the two own-state groups): the term leaves the balance the events' best gain put it in."""
    alike, sel, gains, named = _named(False, monkeypatch)
    assert alike == [[0, 1, 2]] * 3 and sel == ["wheel_const"]
    assert gains["wheel_const"] > gains["mass_xdot_2"] > gains["wheel_omega2_1"]
    assert named == ["mass_xdot_2"]


def test_with_the_balance_rule_the_own_state_is_chosen_within_the_selected_balance(monkeypatch):
    _, sel, _, named = _named(True, monkeypatch)
    assert sel == ["wheel_const"] and named == ["wheel_omega2_1"]
    term = candidate_terms.by_name()["cand_" + named[0]]
    assert term.balance == "wheel_torque_Nm" and term.state in proposal.OWN_STATES["wheel_torque_Nm"]


@pytest.mark.heavy      # make test-all (CI time); ~3 min CPU
@pytest.mark.slow
def test_a_pwm_wheel_brake_is_proposed_in_the_wheel_on_its_speed_with_the_balance_rule(monkeypatch):
    """foreign_drives' chopper-driven eddy-current brake (the sixth development half, od6 #13): -T for a duty
    d = clip((Ω₂ - Ω₀)/ΔΩ, 0, 1) of each 5 ms carrier period, d from Ω₂ sampled at the period's start. Its carrier
    mean, -T·d, is a wheel brake that grows with the wheel's speed. With the rule, the proposal names a wheel torque on
    Ω₂ (before: a mass force on ẋ|ẋ|, the own-state preference across balances), a brake (negative), its size at the
    operating point within a factor 2 of the carrier mean -T·mean(d) over the recording."""
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite

    from backlash_monitor.plant import load_plant_config
    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    from backlash_monitor.workbench.model import load_model
    monkeypatch.setattr(proposal, "TIE_KEEPS_BALANCE", True)
    spec = next(s for s in suite("outside_dev6") if s.label == "od6_wheel_pwm_brake")
    (eff,) = spec.effects
    p = eff.parameters
    rec = make_recording(spec)
    omega2 = np.asarray(rec.signals["omega2"])
    per = int(round(p["carrier_period_s"] / rec.sample_period_s))
    duty = np.clip((omega2[::per] - p["zero_duty_speed_rad_s"]) / p["full_duty_span_rad_s"], 0.0, 1.0)
    mean_brake_Nm = -p["torque_Nm"] * float(duty.mean())
    meas = Measurement("foreign:pwm", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    d = diagnose(meas, load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)).to_json()
    prop = d["proposal"]
    assert prop and prop["proposed"], d["message"]
    wheel = [t for t in prop["terms"] if t["balance"] == "wheel_torque_Nm"]
    assert wheel and wheel[0]["state"] == "omega2", prop["law"]
    assert not any(t["balance"] == "mass_force_N" for t in prop["terms"]), prop["law"]
    by = candidate_terms.by_name()
    ns = {"omega2": omega2, "fabs": np.abs, "smooth_sign": lambda x, eps: x / np.sqrt(x * x + eps * eps),
          "base_mechanical_speed_rad_s": load_plant_config().motor.base_mechanical_speed_rad_s}
    at_operating_point = sum(c * float(np.mean(eval(candidate_terms.with_center(by[name], float(omega2.mean()))  # noqa: S307
                                                    .expression, {"__builtins__": {}}, ns)))
                             for name, c in zip(wheel[0]["terms"], wheel[0]["coefficients"]))
    assert 2.0 * mean_brake_Nm < at_operating_point < 0.5 * mean_brake_Nm, (at_operating_point, mean_brake_Nm)
