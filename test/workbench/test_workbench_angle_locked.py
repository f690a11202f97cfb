"""A user's plug-in locked to a shaft's angle (issue 31): fitted as a sine/cosine pair with its phase lined up with
the recording. Before: screened at amplitude 0, where the phase has no derivative and the model's wheel angle does
not line up with the recording's; the amplitude went to its bound 0 (7e-20) and it explained 0 %.
The recording is made by foreign_drives (an independent implementation): a gear-mesh torque A*sin(alpha2 + phi)."""
import os
import types
from pathlib import Path

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.plant.catalogue import builtin_catalogue          # noqa: E402
from backlash_monitor.workbench import fitting, plant_adapter           # noqa: E402
from backlash_monitor.workbench.model import load_model                  # noqa: E402
from backlash_monitor.plant.effects import Effect, Parameter              # noqa: E402
from backlash_monitor.plant.mathlib import cos, sin                       # noqa: E402
from backlash_monitor.workbench import angle_locked as al                 # noqa: E402
from backlash_monitor.workbench import event_design                       # noqa: E402
from backlash_monitor.workbench.plant_adapter import CandidateEffect, EffectParameter, angle_phase_index   # noqa: E402

PLUGIN = Path(__file__).resolve().parents[2] / "docs" / "examples" / "wheel_angle_torque.py"
MY_EFFECTS = Path(__file__).resolve().parents[2] / "docs" / "examples" / "my_effects.py"


def test_a_term_naming_a_shaft_angle_with_a_phase_is_screened_as_a_sine_cosine_pair():
    cat = builtin_catalogue().with_files([PLUGIN, MY_EFFECTS])
    assert plant_adapter.angle_phase_index(cat["wheel_angle_torque"]) == 1
    assert plant_adapter.angle_phase_index(cat["torque_ripple"]) == 2          # alpha1, phase_rad
    assert plant_adapter.angle_phase_index(cat["wheel_drag"]) == -1            # no angle
    assert plant_adapter.angle_phase_index(cat["wheel_coulomb_friction"]) == -1
    model = load_model(None, effect_files=[PLUGIN])
    eff = plant_adapter.effect_by_name(model, "wheel_angle_torque")
    assert fitting.angle_pair(eff)
    pts = fitting.pair_points(eff)
    # one amplitude: stepped at the model's phase and a quarter turn on
    assert [i for i, _ in pts] == [0, 0]
    assert pts[0][1][0] > 0 and pts[1][1][0] == pts[0][1][0]
    assert pts[1][1][1] - pts[0][1][1] == pytest.approx(np.pi / 2)


def test_the_pair_estimate_recovers_amplitude_and_phase_of_a_sine_law():
    """On an exactly linear response (columns R0, R90 of a law A*sin(alpha + phi)): A and phi back."""
    model = load_model(None, effect_files=[PLUGIN])
    eff = plant_adapter.effect_by_name(model, "wheel_angle_torque")

    class P:                                  # the identity metric of a problem before its views are known
        views = None

        def project(self, r):
            return r

        def residual(self, pred):
            return self.target - pred

        def explained_share(self, a, b):
            return 1.0 - float(a @ a) / float(b @ b)

    rng = np.random.default_rng(3)
    r0, r90 = rng.normal(size=40), rng.normal(size=40)
    h = fitting._pair_steps(eff)
    a_true, phi_true = 2.9, 0.31
    prob = P()
    prob.target = (a_true / h[0]) * (np.cos(phi_true) * r0 + np.sin(phi_true) * r90)
    out = fitting.pair_estimate(prob, eff, np.stack([r0, r90], axis=1), h, np.zeros(40))
    assert out.x_lin[0] == pytest.approx(a_true, rel=1e-9)
    assert out.x_lin[1] == pytest.approx(phi_true, abs=1e-9)
    assert out.explained_lin == pytest.approx(1.0)


# the event-by-event fit (angle_locked.py): the law's harmonics, the responses, the fit at the recorded angles

class Cam(Effect):
    """A cam's torque: two harmonics that depend on the lift ratio, the amplitude linear."""
    name = "test_cam"
    balance = "wheel_torque_Nm"
    description = "A*sin(a2+phi)*(1+q*(1-cos(a2+phi)))"
    parameters = (Parameter("amplitude_Nm", "N*m", 0.0, (0.0, 50.0), "A"),
                  Parameter("lift_ratio", "-", 0.0, (0.0, 5.0), "q"),
                  Parameter("phase_rad", "rad", 0.0, (-np.pi, np.pi), "phi"))

    @staticmethod
    def term(alpha2, amplitude_Nm, lift_ratio, phase_rad):
        return -amplitude_Nm * sin(alpha2 + phase_rad) * (1.0 + lift_ratio * (1.0 - cos(alpha2 + phase_rad)))


class Rubbing(Effect):
    """Locked to the angle, but read with the wheel's speed too: not fitted here."""
    name = "test_rubbing"
    balance = "wheel_torque_Nm"
    description = "A*sin(a2+phi)*omega2"
    parameters = (Parameter("amplitude_Nm", "N*m", 0.0, (0.0, 50.0), "A"),
                  Parameter("phase_rad", "rad", 0.0, (-np.pi, np.pi), "phi"))

    @staticmethod
    def term(alpha2, omega2, amplitude_Nm, phase_rad):
        return amplitude_Nm * sin(alpha2 + phase_rad) * omega2


def _candidate(cls):
    params = tuple(EffectParameter(p.name, p.unit, p.default, p.bounds[0], p.bounds[1], f"{cls.name}.{p.name}")
                   for p in cls.parameters)
    return CandidateEffect(cls.name, cls.name, cls.balance, cls.description, params,
                           phase_index=angle_phase_index(cls))


def _model(cls):
    return types.SimpleNamespace(catalogue={cls.name: cls})


def test_the_laws_harmonics_come_from_its_own_source():
    """sin(b)(1 + q(1 - cos b)) = (1 + q) sin b - (q/2) sin 2b: the cam's harmonics at A = 2, q = 0.6, phi = 0."""
    eff = _candidate(Cam)
    assert al.angle_variable(_model(Cam), eff) == "alpha2"
    law = al.Law(_model(Cam), eff, "alpha2")
    a0, b, a = law.harmonics(np.array([2.0, 0.6, 0.0]))
    assert abs(a0) < 1e-12
    assert np.allclose(b[:2], [-2.0 * 1.6, 2.0 * 0.3], atol=1e-12) and np.allclose(b[2:], 0.0, atol=1e-12)
    assert np.allclose(a, 0.0, atol=1e-12)
    assert al.law_orders(law, np.array([2.0, 0.6, 0.0])) == (1, 2)
    assert al.law_orders(law, np.array([2.0, 0.0, 0.0])) == (1,)
    # a phase moves sine into cosine: b_1 = -A(1+q) cos phi, a_1 = -A(1+q) sin phi
    _, b, a = law.harmonics(np.array([2.0, 0.6, 0.7]))
    assert np.allclose([b[0], a[0]], [-3.2 * np.cos(0.7), -3.2 * np.sin(0.7)], atol=1e-12)


def test_a_term_that_reads_another_state_is_not_fitted_by_its_angle_alone():
    assert al.angle_variable(_model(Rubbing), _candidate(Rubbing)) is None


def test_the_fit_recovers_the_laws_parameters_at_the_recorded_angles():
    """Synthetic events from the linear picture (no simulator): per order k a response U_k, V_k and a constant's R0;
    the probes c sin(k alpha) and c 'simulated' on 6 seeds x 20 events at their own angles; 30 recorded events at
    other angles with the cam at A = 3, q = 1.2, phi = -2.0 plus noise. The responses are solved back from the probes,
    and the fit at the recorded angles finds the cam's parameters within 3 of their jackknife uncertainties."""
    rng = np.random.default_rng(5)
    n = 40
    U, V = rng.normal(size=(2, n)), rng.normal(size=(2, n))
    R0 = rng.normal(size=n)
    eff = _candidate(Cam)
    law = al.Law(_model(Cam), eff, "alpha2")
    truth = al.Responses((1, 2), U, V, R0)
    amps = al._probe_amplitudes("wheel_torque_Nm", (1, 2))
    assert amps == {0: 2.0, 1: 2.0, 2: 2.0}
    sim = []
    for probe in (0, 1, 2):
        ang = rng.uniform(0, 2 * np.pi, 120)
        unit = (np.broadcast_to(R0, (120, n)) if probe == 0 else
                np.cos(probe * ang)[:, None] * U[probe - 1] + np.sin(probe * ang)[:, None] * V[probe - 1])
        sim.append((amps[probe] * unit + 0.01 * rng.normal(size=(120, n)),
                    {"alpha2": ang, "seed": np.repeat(np.arange(6), 20)}))
    resp = al._solve_responses(sim, amps, "alpha2", (1, 2))
    assert np.allclose(resp.U, U, atol=0.02) and np.allclose(resp.V, V, atol=0.02)
    assert np.allclose(resp.R0, R0, atol=0.02)
    theta = rng.uniform(0, 200, 30)
    x_true = np.array([3.0, 1.2, -2.0])
    Y = al._columns(truth, theta) @ al._coefficients(law, x_true, (1, 2)) + 0.5 * rng.normal(size=(30, n))
    G = al._columns(resp, theta)
    from backlash_monitor.workbench.proposal import gram
    GG, Gy, _ = gram(G, Y)
    lo, hi = eff.bounds()
    x = al._fit_values(law, (1, 2), GG.sum(0), Gy.sum(0), np.array([7.5, 0.75, 0.0]), lo, hi, 2, multi=True)
    loo = np.array([al._fit_values(law, (1, 2), GG.sum(0) - GG[i], Gy.sum(0) - Gy[i], x, lo, hi, 2, multi=False)
                    for i in range(len(GG))])
    sigma = al._jackknife(al._unwrap_phase(loo, 2, x[2]))
    assert np.all(np.abs(x - x_true) < 3 * sigma + 1e-9), (x, sigma)
    assert np.all(sigma < [0.5, 0.5, 0.3]), sigma


def test_the_probes_are_a_plugin_of_the_documented_form():
    """The probes' file (generated) loads as plug-ins: c sin(k alpha2) for each order and a constant, in the balance."""
    from backlash_monitor.plant.catalogue import builtin_catalogue
    path = al.harmonics_file("wheel_torque_Nm", "alpha2", (1, 2))
    cat = builtin_catalogue().with_files([path])
    for k in (0, 1, 2):
        cls = cat[al.probe_name("wheel_torque_Nm", "alpha2", k)]
        assert cls.balance == "wheel_torque_Nm" and cls.parameters[0].default == 0.0


def test_recorded_angles_and_fourier_basis_agree():
    """The Fourier basis evaluated at the angle integrated from a constant speed is the harmonic of time it should
    be (event_design.recorded_angles, fourier_basis)."""
    dt, w = 1e-3, 3.0
    ang = event_design.recorded_angles({"omega2": np.full(1000, w)}, dt)["alpha2"]
    X = event_design.fourier_basis(ang, (2,))
    t = np.arange(1000) * dt
    assert np.allclose(X[:, 1], np.cos(2 * w * t)) and np.allclose(X[:, 2], np.sin(2 * w * t))


@pytest.mark.heavy      # make test-all (CI time); bench/_workbench/outside.py measures this row by row
@pytest.mark.slow
def test_a_users_exact_law_plugin_is_named_on_a_foreign_wheel_angle_torque():
    """foreign_drives: A = 8 N*m sin(alpha2 + 0.31) on the wheel, 3 s. Among the whole catalogue, the plug-in
    -A*sin(alpha2 + phi) is the discovery, fitted event by event (angle_locked.py), its amplitude within 3 of its
    uncertainties of 8 N*m (the phase: the foreign angle's origin is its own), the model with it consistent."""
    from foreign_drives.drive import make_recording
    from foreign_drives.spec import EffectSpec as E
    from foreign_drives.spec import RecordingSpec, SensorNuisance

    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    spec = RecordingSpec(label="wheel_angle", kind="one", width_m=0.006, eta_k=0.025, n1=0.89,
                         effects=(E("ripple_wheel_mesh", {"amplitude_Nm": 8.0, "order": 1, "phase_rad": 0.31}),),
                         sensor=SensorNuisance(), seed=311, duration_s=3.0).check()
    rec = make_recording(spec)
    meas = Measurement("foreign:wheel_angle", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    model = load_model(None, width_m=0.006, eta_k=0.025, n1=0.89, effect_files=[PLUGIN])
    d = diagnose(meas, model, propose=False).to_json()
    assert d["verdict"] == "discovery" and d["discovery"] == "wheel_angle_torque", d["message"]
    fit = d["discovery_parameters"]
    a, s = fit["parameters"]["amplitude_Nm"], fit["uncertainty"]["amplitude_Nm"]
    assert 0 < s < a / 3
    assert abs(a - 8.0) <= 3 * s


class Mesh20(Effect):
    """A gear mesh at 20 per revolution: beyond the harmonics fitted here."""
    name = "test_mesh20"
    balance = "wheel_torque_Nm"
    description = "A*sin(20*a2+phi)"
    parameters = (Parameter("amplitude_Nm", "N*m", 0.0, (0.0, 50.0), "A"),
                  Parameter("phase_rad", "rad", 0.0, (-np.pi, np.pi), "phi"))

    @staticmethod
    def term(alpha2, amplitude_Nm, phase_rad):
        return amplitude_Nm * sin(20.0 * alpha2 + phase_rad)


class Branchy(Effect):
    """A term written with a Python branch: it runs compiled per sample, not on numpy arrays."""
    name = "test_branchy"
    balance = "wheel_torque_Nm"
    description = "A if sin(a2+phi) > 0 else 0"
    parameters = (Parameter("amplitude_Nm", "N*m", 0.0, (0.0, 50.0), "A"),
                  Parameter("phase_rad", "rad", 0.0, (-np.pi, np.pi), "phi"))

    @staticmethod
    def term(alpha2, amplitude_Nm, phase_rad):
        if sin(alpha2 + phase_rad) > 0.0:
            return amplitude_Nm
        return 0.0


def test_a_law_beyond_the_fitted_harmonics_or_not_on_arrays_is_left_to_the_average():
    """A mesh at 20 per revolution has no power in orders 1-4 (Parseval): not fitted here; a term with a Python
    branch does not run on arrays: the fit returns None instead of failing the diagnosis."""
    law = al.Law(_model(Mesh20), _candidate(Mesh20), "alpha2")
    assert al.law_orders(law, np.array([2.0, 0.0])) == ()
    with pytest.raises(ValueError):
        al.Law(_model(Branchy), _candidate(Branchy), "alpha2").values(np.array([2.0, 0.0]))
    problem = types.SimpleNamespace(n_events=20, dt=1e-3, events=types.SimpleNamespace(entries=np.arange(0, 1000, 50)))
    run = types.SimpleNamespace(model=_model(Branchy), problem=problem,
                                meas=types.SimpleNamespace(signals={"omega2": np.full(1000, 3.0)}))
    assert al.fit(run, _candidate(Branchy)) is None


def test_events_that_all_enter_at_one_angle_cannot_tell_sine_from_cosine():
    assert al.spread_enough(np.linspace(0, 40, 30), (1, 2))
    assert not al.spread_enough(np.full(30, 1.3) + 2 * np.pi * np.arange(30), (1,))
    # recorded events on an arc of 0.85 rad (0.97 on order 1, measured beside a width change): fitted, the responses'
    # shapes tell sine from cosine and the jackknife says how well; all at one angle: not
    arc = np.linspace(5.16, 6.01, 16)
    assert not al.spread_enough(arc, (1,)) and al.spread_enough(arc, (1,), al.RECORDED_CONCENTRATION)
    assert not al.spread_enough(np.full(16, 5.5), (1,), al.RECORDED_CONCENTRATION)


class TwoPart(Effect):
    """A phase that moves one part of the law and not the other: not a shift of the law's angle."""
    name = "test_two_part"
    balance = "wheel_torque_Nm"
    description = "A*sin(a2) + A*sin(2*a2+phi)"
    parameters = (Parameter("amplitude_Nm", "N*m", 0.0, (0.0, 50.0), "A"),
                  Parameter("phase_rad", "rad", 0.0, (-np.pi, np.pi), "phi"))

    @staticmethod
    def term(alpha2, amplitude_Nm, phase_rad):
        return amplitude_Nm * (sin(alpha2) + sin(2.0 * alpha2 + phase_rad))


def test_a_phase_step_is_a_shift_of_the_laws_angle_or_none():
    """The cam's phase shifts its angle (f(alpha; phi + s) = f(alpha + s)); a phase that moves one part of a law
    only is no shift of it. The phases the law is simulated at: a prime above the largest order over the orders'
    common divisor, so that each order's circle gets as many distinct points."""
    law = al.Law(_model(Cam), _candidate(Cam), "alpha2")
    x = np.array([3.0, 1.2, -2.0])
    grid = law._grid
    for ph in (-2.0, -0.5, 1.0, 3.0):
        tau = al.angle_shift(law, x, 2, ph)
        xs = x.copy()
        xs[2] = ph
        shifted = np.interp(grid + tau, grid, law.values(x), period=2 * np.pi)
        assert np.max(np.abs(law.values(xs) - shifted)) < 2e-3 * np.max(np.abs(law.values(x)))
    two = al.Law(_model(TwoPart), _candidate(TwoPart), "alpha2")
    assert al.angle_shift(two, np.array([2.0, 0.0]), 1, 1.0) is None
    assert [al.phase_steps(o) for o in [(1,), (1, 2), (1, 2, 4), (2,), (2, 4), (3,)]] == [3, 3, 5, 3, 3, 3]


def test_the_whole_law_is_predicted_at_recorded_angles_its_simulated_events_never_reached(monkeypatch):
    """The model's events enter on an arc (-1.0 .. 1.3 rad) at every phase; the recording's on the other side of
    the circle. A nonlinear per-event change h(angle + phase) (harmonics 0..2 of the law's angle): the law simulated
    at phase_steps phases, each event taken at its angle plus the phase's shift, gives h at the recorded angles."""
    rng = np.random.default_rng(11)
    eff = _candidate(Cam)
    law = al.Law(_model(Cam), eff, "alpha2")
    x = np.array([3.0, 1.2, -2.0])

    def h(u):
        return np.stack([np.cos(u), np.sin(u) + 0.4 * np.cos(2 * u), 0.3 + 0.2 * np.sin(2 * u)], axis=-1)

    def sim(u):                                      # with a little beyond the fitted orders, and noise
        return h(u) + 0.05 * np.cos(4 * u)[:, None] + 0.02 * rng.normal(size=(len(u), 3))

    def fake_changes(problem, sets):
        out = []
        for s in sets:
            phase = s["test_cam.phase_rad"]
            ang = rng.uniform(-1.0, 1.3, 60)
            out.append((sim(ang + phase), {"alpha2": ang, "seed": np.arange(60) % 6}))
        return out
    monkeypatch.setattr(event_design, "matched_changes", fake_changes)
    theta = rng.uniform(2.0, 4.5, 16)
    P = al.law_prediction(None, eff, law, x, "alpha2", theta, (1, 2))
    assert np.max(np.abs(P - h(theta + x[2]))) < 0.1
    # one phase only (the arc): the same regression extrapolates off the arc and misses
    ang = rng.uniform(-1.0, 1.3, 180)
    C, *_ = np.linalg.lstsq(event_design.fourier_basis(ang, (1, 2)), sim(ang + x[2]), rcond=None)
    assert np.max(np.abs(event_design.fourier_basis(theta, (1, 2)) @ C - h(theta + x[2]))) > 0.3


def test_a_law_step_is_kept_only_when_it_lowers_the_events_error():
    """Defect correction (law_steps) of a linear model whose gain is off by 40 %: the steps converge on the truth of a
    nonlinear law (a step that overshoots is halved). A refit that steps away (a wrong linear model's sign) raises the
    error at every step: the start is kept."""
    t = np.linspace(0.0, 1.0, 50)
    truth = 2.0

    def law(a):                                      # the whole law: not linear in its amplitude
        return a * np.sin(3 * t) + 0.1 * a ** 2 * np.cos(t)
    y = law(truth)

    def error(P):
        return float(np.sum((y - P) ** 2))

    def refit(gain):
        def f(x, P):
            lin = gain * np.sin(3 * t)
            defect = P - lin * x[0]
            return np.array([float(lin @ (y - defect) / (lin @ lin))])
        return f
    x0 = np.array([1.2])
    x, P = al.law_steps(x0, lambda x: law(x[0]), refit(0.6), error, np.array([10.0]), iterations=8)
    assert abs(x[0] - truth) < 0.05 and error(P) < 1e-3 * error(law(x0[0]))
    x, P = al.law_steps(x0, lambda x: law(x[0]), refit(-1.0), error, np.array([10.0]), iterations=8)
    assert x[0] == x0[0] and error(P) == error(law(x0[0]))
    assert al.law_steps(x0, lambda x: None, refit(0.6), error, np.array([10.0])) is None


def test_a_shared_effect_beside_the_term_is_fitted_with_it_on_the_events():
    """Synthetic events (the linear picture): the cam at A = 3, q = 0.3, phi = -2.0 at each event's own angle and a
    shared effect (a width change: one column, the same on every event) at 0.8 of its unit. Fitted together (the
    coefficient vector the law's harmonics, then the shared effect's values: angle_locked.Beside) both come back (the
    first harmonic A(1 + q); A and q apart only as the second harmonic allows). Their significance: the term's
    parameters together, by its harmonics' size (a lift ratio at its nominal 0 is no evidence against the term)."""
    from backlash_monitor.workbench.decisions import significant
    from backlash_monitor.workbench.proposal import gram
    rng = np.random.default_rng(8)
    n, e = 30, 40
    U, V = rng.normal(size=(2, n)), rng.normal(size=(2, n))
    resp = al.Responses((1, 2), U, V, rng.normal(size=n))
    js = rng.normal(size=(n, 1))
    eff = _candidate(Cam)
    law = al.Law(_model(Cam), eff, "alpha2")
    theta = rng.uniform(0, 200, e)
    G = al._columns(resp, theta)
    x_true = np.array([3.0, 0.3, -2.0, 0.8])
    Y = G @ al._coefficients(law, x_true[:3], (1, 2)) + js[:, 0] * 0.8 + 0.3 * rng.normal(size=(e, n))
    Gj = np.concatenate([G, np.broadcast_to(js[None], (e, n, 1))], axis=-1)

    def coef(xv):
        return np.concatenate([al._coefficients(law, xv[:3], (1, 2)), xv[3:]])
    GG, Gy, _ = gram(Gj, Y)
    lo, hi = np.r_[eff.bounds()[0], -5.0], np.r_[eff.bounds()[1], 5.0]
    x = al._fit_values(law, (1, 2), GG.sum(0), Gy.sum(0), np.array([7.5, 0.75, 0.0, 0.0]), lo, hi, 2, multi=True,
                       coef=coef)
    assert abs(x[3] - 0.8) < 0.1 and abs(x[0] * (1 + x[1]) - 3.9) < 0.3, x
    # the lift ratio's own uncertainty may be wide, the term's size decides
    fit = types.SimpleNamespace(values=np.array([3.0, 0.01, -2.0, 0.8]), nominal=np.zeros(4),
                                uncertainty=np.array([0.5, 0.3, 0.05, 0.1]), groups=((0, 3, 12.0),))
    assert significant(fit)
    assert not significant(types.SimpleNamespace(**{**vars(fit), "groups": ()}))
    assert not significant(types.SimpleNamespace(**{**vars(fit), "groups": ((0, 3, 1.5),)}))


def test_a_term_locked_to_an_angle_is_evidence_on_the_events_when_decisive_and_significant():
    """The views look at the event average, where such a term washes out: its event-by-event fit decides whether the
    model is consistent with its events (diagnose.events_evidence). Decisive (delta_ic <= -10) and its harmonics' size
    significant: the model is inconsistent, that term first; weak or insignificant ones are not evidence."""
    from backlash_monitor.workbench.diagnose import events_evidence

    def fit(name, dic, z):
        return types.SimpleNamespace(effect=name, delta_ic=dic, values=np.array([4.7, -1.8]), nominal=np.zeros(2),
                                     uncertainty=np.array([0.3, 0.08]), groups=((0, 2, z),))
    assert events_evidence([fit("mesh2", -104.0, 16.4), fit("cam", -30.0, 5.0)]) == "mesh2"
    assert events_evidence([fit("mesh2", 3.9, 1.9)]) is None           # measured on a clean foreign recording
    assert events_evidence([fit("mesh2", -40.0, 1.5)]) is None         # decisive but its size not significant
    assert events_evidence([fit("mesh2", -8.0, 9.0)]) is None          # not decisive
    assert events_evidence([]) is None


def test_a_shared_width_is_searched_on_the_whole_law_where_its_linear_column_stops_short():
    """A wider gap delays every crossing's impact by (extra width) / (closing speed): an event's impact pulse moves in
    time, which no column linear in the width follows far. The whole law's error, searched along the width by a
    parabola through width -+ h (whole_law_search), comes from a width 10 % short to the truth (within 2 % of it)
    and never rises; the term's parameter is left where it was; a step of 0, or a law that cannot be predicted,
    changes nothing."""
    t = np.linspace(0.0, 0.02, 400)                      # s, one crossing
    v_mps, width_m, tau_s = 0.5, 0.001, 1.5e-3           # closing speed, true extra width, impact pulse's length

    def law(x):                                          # x = (the term's amplitude, the extra width)
        t_impact = 0.005 + x[1] / v_mps
        return x[0] * np.exp(-((t - t_impact) / tau_s) ** 2)
    y = law(np.array([3.0, width_m]))

    def error(P):
        return float(np.sum((y - P) ** 2))
    x0 = np.array([3.0, 0.9 * width_m])
    P0 = law(x0)
    lo, hi = np.array([0.0, -0.01]), np.array([10.0, 0.01])
    x, P, err = al.whole_law_search(x0, P0, error(P0), law, error, [1], np.array([0.0, 1.5e-4]), lo, hi)
    assert abs(x[1] - width_m) < 0.02 * width_m and x[0] == x0[0]
    assert err == error(P) < 0.05 * error(P0)
    # nothing lowers the error at the truth itself; a zero step or an unpredictable law: the inputs back
    xt = np.array([3.0, width_m])
    assert np.array_equal(al.whole_law_search(xt, y, 0.0, law, error, [1], np.array([0.0, 1e-4]), lo, hi)[0], xt)
    assert al.whole_law_search(x0, P0, error(P0), law, error, [1], np.zeros(2), lo, hi)[1] is P0
    assert al.whole_law_search(x0, P0, error(P0), lambda x: None, error, [1], np.array([0.0, 1e-4]), lo, hi)[1] is P0


@pytest.mark.heavy      # make test-all (CI time); bench/_workbench/outside.py's angle rows measure this row
@pytest.mark.slow
def test_a_users_crank_plugin_is_named_beside_a_width_change_on_a_foreign_drive(tmp_path):
    """foreign_drives' od_width_4.0_to_5.0+crank_pump: the gap grown 4.0 -> 5.0 mm and a single-acting pump on the
    motor's crank, 0.25 p.u. * max(0, sin(alpha1 + 1.7)). With the user's exact-law plug-in (the manifest's), the
    pair is fitted event by event and its width searched on the whole law: the width is measured within 3 of its
    uncertainties of 5.0 mm and the crank is the second effect, its amplitude within 3 of its uncertainties of 0.25
    (before: the width's linear column left the pair at +0.90 mm, the event average outside its band: partial)."""
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite

    from backlash_monitor.workbench.diagnose import diagnose
    from backlash_monitor.workbench.measurement import Measurement
    spec = next(s for s in suite("outside_dev") if s.label == "od_width_4.0_to_5.0+crank_pump")
    crank = next(e for e in spec.truth().effects if getattr(e, "plugin", None) and "motor_angle" in e.depends_on)
    plugin = tmp_path / "crank.py"
    plugin.write_text(crank.plugin)
    rec = make_recording(spec)
    meas = Measurement(f"foreign:{spec.label}", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    d = diagnose(meas, load_model(None, width_m=spec.width_m, eta_k=spec.eta_k, n1=spec.n1, effect_files=[plugin]),
                 propose=False).to_json()
    assert d["verdict"] == "discovery", d["message"]
    w = d["measured_width"]
    assert abs(w["width_m"] - 0.005) <= 3 * w["uncertainty_m"], w
    sec = d["second_effect"]
    assert sec is not None and sec["effect"] == "motor_crank_pump", d["message"]
    a, s = sec["parameters"]["amplitude_pu"], sec["uncertainty"]["amplitude_pu"]
    assert 0 < s < a / 2 and abs(a - crank.parameters["amplitude_pu"]) <= 3 * s
