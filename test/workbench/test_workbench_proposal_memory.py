"""The proposal's terms with a memory (candidate_terms.memory_terms on the plant's first-order lags, plant/lags.py)."""
import math

import numpy as np
import pytest

from backlash_monitor.plant import lags
from backlash_monitor.plant.effects import MODEL_VARIABLES
from backlash_monitor.workbench import candidate_terms

H = 2e-5


def _run_lags(q_of_t, n):
    """The lags of every quantity driven by q_of_t(t) (the same series for every quantity) over n steps."""
    coef = lags.coefficients(H)
    t = np.arange(n + 1) * H
    q = q_of_t(t)
    L = [np.array([q[0]]) for _ in lags.LAGS]
    out = [dict(zip(lags.LAG_NAMES, (float(v[0]) for v in L)))]
    for k in range(n):
        L = lags.update(L, [np.array([q[k]])] * len(lags.QUANTITIES), [np.array([q[k + 1]])] * len(lags.QUANTITIES),
                        coef)
        out.append(dict(zip(lags.LAG_NAMES, (float(v[0]) for v in L))))
    return t, q, out


def _value(term, state, lag_values):
    ns = {"wheel_radius_m": 0.15, **state, **lag_values}
    return eval(term.expression, {"__builtins__": {}}, ns)      # noqa: S307 - the library's own expressions


def test_memory_terms_are_lags_of_their_balances_own_state_at_the_plants_time_constants():
    mem = candidate_terms.memory_terms()
    assert mem and all(t in candidate_terms.library(memory=True) for t in mem)
    assert not any(t in candidate_terms.library(memory=False) for t in mem)
    own = {"motor_load_moment_pu": "omega1", "wheel_torque_Nm": "omega2", "mass_force_N": "xdot",
           "clutch_torque_Nm": "penetration"}
    for group, names in candidate_terms.groups(mem).items():
        terms = [t for t in mem if t.name in names]
        assert len(terms) == len(lags.LAG_TIMES_S)            # one coefficient per time constant, one group
        assert len({t.balance for t in terms}) == 1
        for t, tau in zip(terms, lags.LAG_TIMES_S):
            assert set(t.variables) <= set(MODEL_VARIABLES)
            lag = [v for v in t.variables if v in lags.LAG_NAMES]
            assert len(lag) == 1 and lag[0].endswith(f"_lag_{tau * 1e3:g}ms")
            if t.state == "load pulse":
                assert lag[0].startswith("load_moment_lag")
            else:                                               # the loaded body's own state
                assert t.state == own[t.balance] and lag[0].startswith(own[t.balance] + "_lag")


def test_a_speed_memory_term_is_the_torque_of_a_hidden_body_on_a_viscous_coupling():
    """After a speed step dq the term (q - L_tau(q))/scale is dq/scale * exp(-t/tau): the coupling's torque of a body
    left at the old speed that catches up with tau = J/c; at a constant speed it is 0 (no operating point in it)."""
    dq = 0.9
    t, q, L = _run_lags(lambda t: 150.0 + dq * (t > 0), 20000)
    for term in candidate_terms.memory_terms():
        if term.state not in ("omega1", "omega2"):
            continue
        tau = float(term.name.rsplit("_", 1)[1][:-2]) * 1e-3
        got = np.array([_value(term, {term.state: q[k]}, L[k]) for k in range(len(t))])
        assert got[0] == 0.0
        k = np.arange(1, len(t))
        # the ODE's solution for the step taken as a ramp over the first sample step (a state is continuous):
        # q - L = dq * (tau/h) * (1 - exp(-h/tau)) * exp(-(t - h)/tau) from t = h on
        exact = (dq / candidate_terms.SPEED_DEVIATION_SCALE_RAD_S * tau / H * (1.0 - math.exp(-H / tau))
                 * np.exp(-(t[k] - H) / tau))
        assert np.allclose(got[1:], exact, rtol=1e-9, atol=1e-9), term.name   # atol: 150 rad/s rounded


def test_a_pulse_memory_term_is_the_stroke_through_a_first_order_lag():
    """The load moment's lag: a pulse of 1.6 p.u. held from t = 0 reads 1 - exp(-t/tau) (by the pulse's 1.6 p.u.)."""
    t, q, L = _run_lags(lambda t: 1.6 * np.ones_like(t), 0)
    assert all(_value(term, {}, L[0]) == 1.0 for term in candidate_terms.memory_terms() if term.state == "load pulse")
    coef = lags.coefficients(H)
    n = 15000
    Ls = [np.zeros(1) for _ in lags.LAGS]
    for _ in range(n):
        Ls = lags.update(Ls, [np.array([1.6])] * len(lags.QUANTITIES), [np.array([1.6])] * len(lags.QUANTITIES),
                         coef)
    values = dict(zip(lags.LAG_NAMES, (float(v[0]) for v in Ls)))
    for term in candidate_terms.memory_terms():
        if term.state == "load pulse":
            tau = float(term.name.rsplit("_", 1)[1][:-2]) * 1e-3
            assert _value(term, {}, values) == pytest.approx(1.0 - math.exp(-n * H / tau), rel=1e-12)


@pytest.mark.heavy      # make test-all (CI time); ~3 min CPU
@pytest.mark.slow
def test_an_eddy_brake_whose_field_follows_the_stroke_through_a_lag_is_proposed_on_the_lagged_pulse_in_the_wheel(
        monkeypatch):
    """foreign_drives' eddy-current brake on the wheel (the spent fifth sealed half, os5 #8): -c*Omega2*i, its field
    current i following the stroke with the coil's L/R = 20 ms, c = 0.02 N*m*s/rad (Omega2 ~ 151 rad/s: -3 N*m while
    the field is up). No term of the instantaneous states expresses it (before the lags: a motor load gated by the
    jaw's side, the wrong balance). The proposal names the wheel torque on the load pulse through its lags, a brake
    (negative), its settled size sum(c_tau) within a factor 2 of -c*mean(Omega2), and the model with it consistent."""
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite

    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    from backlash_monitor.workbench.model import load_model
    monkeypatch.setattr(candidate_terms, "MEMORY_IN_LIBRARY", True)     # the library with its terms with a memory
    spec = next(s for s in suite("outside_sealed5") if s.label == "os5_wheel_eddy_brake_field_lag")
    (eff,) = spec.effects
    assert eff.form == "wheel_eddy_brake_field_lag" and eff.parameters["time_constant_s"] == 0.02
    rec = make_recording(spec)
    meas = Measurement("foreign:eddy", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    d = diagnose(meas, load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1)).to_json()
    prop = d["proposal"]
    assert prop and prop["proposed"], d["message"]
    term = [t for t in prop["terms"] if t["group"] == "wheel_pulse_memory"]
    assert term and term[0]["balance"] == "wheel_torque_Nm" and term[0]["state"] == "load pulse", prop["law"]
    settled = sum(term[0]["coefficients"])            # each lag of the 1.6 p.u. pulse settles at 1 (by its scale)
    expected = -eff.parameters["coefficient_Nms_per_rad"] * float(np.mean(rec.signals["omega2"]))
    assert 0.5 * expected > settled > 2.0 * expected, (term[0]["coefficients"], expected)
    assert prop["consistent"], prop["reason"]
