"""The screening's steps (fitting.screen) where a step leaves the model's regime: a parameter stepped 15 % of its range
can turn a term's sign of damping, and the simulated drive then runs away and crosses no backlash (seen: a proposed
speed-proportional motor load at +0.071 p.u. per 1.5 rad/s, stepped by -0.3, ran to 7e4 rad/s and `train` could not
build the model watch's reference). Such a step is tried again shorter; the other sets are kept; a parameter no step
of which stays in the regime is named."""
import numpy as np
import pytest

from backlash_monitor.workbench import diagnose as dg, fitting
from backlash_monitor.workbench.events import NoOnsetWindow
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.plant_adapter import apply_values
from backlash_monitor.workbench.synthetic import hidden_effect_recording

SPEED_LOAD = '''
from backlash_monitor.plant.effects import Effect, Parameter


class SpeedLoad(Effect):
    name = "speed_load"
    balance = "motor_load_moment_pu"
    description = "a motor load proportional to the speed's deviation from 150 rad/s"
    parameters = (Parameter("c_pu", "p.u.", 0.0, (-1.0, 1.0), "per 1.5 rad/s"),)

    @staticmethod
    def term(omega1, c_pu):
        return c_pu * ((omega1 - 150.0) / 1.5)
'''


@pytest.fixture(scope="module")
def speed_load_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("plugin") / "speed_load.py"
    path.write_text(SPEED_LOAD)
    model = load_model(None, effect_files=[path], sets=["effects.speed_load=true", "speed_load.c_pu=0.07"])
    meas = hidden_effect_recording(model, 1.5, seed=5101)
    run = dg.prepare(meas, model, [0, 1, 2])
    return run, run.by_name["speed_load"]


@pytest.mark.slow
def test_a_step_that_makes_the_drive_run_away_is_taken_shorter_and_gives_the_same_derivative(speed_load_run):
    run, cand = speed_load_run
    p = run.problem
    x0 = cand.default_vector()
    first = fitting._step(cand)
    assert first[0] == pytest.approx(-0.3)          # into the interior: the nearer bound is the upper one
    # the physics the test stands on: at c = 0.07 - 0.3 the load's slope beats the speed controller's and the motor
    # runs away: no onset window at all
    with pytest.raises(NoOnsetWindow):
        p.evaluate([apply_values(cand, x0 + first)])
    one_sided = fitting.screen(p, [cand], run.base_pred, two_sided=False)["speed_load"]
    h = float(one_sided.step[0])
    assert -0.3 < h < 0 and h == pytest.approx(-0.3 * fitting.STEP_BACK_FACTOR ** round(np.log(h / -0.3)
                                                                                        / np.log(0.25)))
    # the step taken stays in the regime: its set crosses the backlash
    assert p.evaluate([apply_values(cand, x0 + one_sided.step)]).n_events.min() > 0
    # a secant is a derivative: the shortened one points where the derivative does (a central difference of a 64th
    # of the first step; measured: cos 0.96, norm 0.93 of it at h = -0.075 -- the load's response bends as the
    # damping falls, the longer the secant the more: cos 0.72 at 0.2)
    d = abs(first[0]) / 64
    ens = p.evaluate([apply_values(cand, x0 + d), apply_values(cand, x0 - d)])
    j_ref = (p.pred_of(ens, 0) - p.pred_of(ens, 1)) / (2 * d)
    j_down = one_sided.jacobian[:, 0]
    cos = float(j_ref @ j_down / np.linalg.norm(j_ref) / np.linalg.norm(j_down))
    assert cos > 0.9, cos
    assert 0.8 < np.linalg.norm(j_down) / np.linalg.norm(j_ref) < 1.25
    # both sides stepped: the screening keeps both and returns without error
    two_sided = fitting.screen(p, [cand], run.base_pred)["speed_load"]
    assert np.all(np.isfinite(two_sided.jacobian)) and abs(two_sided.step[0]) <= 0.3


class _Ens:
    def __init__(self, n_events, xs):
        self.n_events = np.asarray(n_events)
        self.xs = xs


class _Problem:
    """Evaluates sets of one parameter 'k.x': a set with x below ``runaway`` gives no onset window on every seed;
    the prediction is x itself (a model linear in x)."""

    def __init__(self, runaway):
        self.runaway = runaway
        self.calls = []

    def evaluate(self, sets, empty_ok=False):
        xs = [s["k.x"] for s in sets]
        self.calls.append(xs)
        assert empty_ok
        return _Ens([[0, 0] if x < self.runaway else [5, 5] for x in xs], xs)

    def pred_of(self, ens, j):
        return np.array([ens.xs[j]])


class _Param:
    key, default = "k.x", 0.5


class _Cand:
    name = "k"
    parameters = (_Param(),)

    def default_vector(self):
        return np.array([0.5])


def test_only_the_sets_that_crossed_no_backlash_are_simulated_again(monkeypatch):
    monkeypatch.setattr(fitting, "angle_pair", lambda eff: False)
    monkeypatch.setattr(fitting.plant_adapter, "apply_values", lambda eff, x: {"k.x": float(x[0])})
    steps = {("k", 0, 1.0): -0.3, ("k", 0, -1.0): 0.3}
    prob = _Problem(runaway=0.45)
    ens_of = fitting._stepped_predictions(prob, [_Cand()], steps)
    assert steps[("k", 0, -1.0)] == 0.3                        # the upper side kept, simulated once
    assert steps[("k", 0, 1.0)] == pytest.approx(-0.3 * 0.25 ** 2)   # 0.5 - 0.075 < 0.45; 0.5 - 0.01875 crosses
    assert prob.calls[0] == pytest.approx([0.2, 0.8]) and all(len(c) == 1 for c in prob.calls[1:])
    assert ens_of[("k", 0, 1.0)][0] == pytest.approx(0.5 - 0.01875)


def test_a_parameter_no_step_of_which_crosses_the_backlash_is_named(monkeypatch):
    monkeypatch.setattr(fitting, "angle_pair", lambda eff: False)
    monkeypatch.setattr(fitting.plant_adapter, "apply_values", lambda eff, x: {"k.x": float(x[0])})
    with pytest.raises(fitting.ScreeningStepError, match=r"k\.x = 0\.5: .*stepped by -0\.00469 .*does not cross"):
        fitting._stepped_predictions(_Problem(runaway=0.499), [_Cand()], {("k", 0, 1.0): -0.3})


@pytest.mark.slow
def test_refine_started_beyond_the_run_away_goes_back_into_the_regime_and_fits(speed_load_run):
    """The bounded least squares on the simulator started where the drive runs away (a linear estimate of -0.25 on a
    recording the model made of itself at +0.07): a wall there, not an error; the fit comes back to the truth."""
    run, cand = speed_load_run
    p = run.problem
    start = fitting.Linearisation(np.zeros((run.base_pred.size, 1)), np.array([-0.075]), np.array([-0.25]), 0.0)
    fit = fitting.refine(p, cand, start, run.base_pred, p.ic(run.base_pred, 0))
    assert np.all(np.isfinite(fit.values)) and np.all(np.isfinite(fit.uncertainty))
    assert p.evaluate([apply_values(cand, fit.values)]).n_events.min() > 0
    assert abs(fit.values[0] - 0.07) <= max(3 * fit.uncertainty[0], 0.01), (fit.values, fit.uncertainty)
