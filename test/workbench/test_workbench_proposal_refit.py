"""The proposed terms' refit on the simulator (proposal.kept_gauss_newton with ``secant``): a motor load of the motor's
own size moves it along its torque-speed curve, which bends towards breakdown, so the tangent taken at the screening's
small step no longer holds at the fitted value. The refit corrects its Jacobian by each step's own change (Broyden)
and halves a refused step. The curve here is the model's own induction motor (plant.motor: the equivalent circuit's
steady state), the base load 0.6 p.u. (working resistance, absorber and the pulses' mean)."""
import numpy as np
import pytest

from backlash_monitor.plant import motor
from backlash_monitor.workbench import candidate_terms, proposal
from backlash_monitor.workbench.model import load_model

BASE_LOAD_PU = 0.6
SCREENING_STEP_PU = candidate_terms.BALANCES["motor_load_moment_pu"][1]


@pytest.fixture(scope="module")
def speed_at():
    m = load_model(None).plant_config().motor

    def speed(extra_pu):
        return motor.steady_state_at_torque(BASE_LOAD_PU + float(extra_pu), m).w1_pu * m.base_mechanical_speed_rad_s
    return speed


def _problem(speed, truth_pu):
    target = np.array([speed(truth_pu)])

    def residual_at(x):
        return target - np.array([speed(x[0])])
    tangent = np.array([[(speed(SCREENING_STEP_PU) - speed(0.0)) / SCREENING_STEP_PU]])
    return residual_at, tangent


def test_a_load_near_breakdown_is_reached_by_the_secant_refit_and_not_by_the_screening_tangent(speed_at):
    # an extra 1 p.u.: 1.6 of the motor's 1.75 p.u. breakdown torque; the drive slows from 151.5 to 134 rad/s (the
    # record-mean speeds of the heavily loaded outside drives: 136-137 rad/s)
    assert speed_at(0.0) == pytest.approx(151.5, abs=0.2) and speed_at(1.0) == pytest.approx(134.2, abs=0.2)
    residual_at, tangent = _problem(speed_at, 1.0)
    x0 = np.array([0.0])
    r0 = residual_at(x0)
    bound = candidate_terms.BALANCES["motor_load_moment_pu"][2]
    # the tangent at the screening step is too shallow there: its full step overshoots past breakdown and is refused
    x_old, _, _, _ = proposal.kept_gauss_newton(x0, [-bound], [bound], tangent, residual_at, r0, 2, scales=(1.0,))
    assert x_old[0] == 0.0
    x_fixed, _, _, _ = proposal.kept_gauss_newton(x0, [-bound], [bound], tangent, residual_at, r0,
                                                  proposal.REFIT_ITERATIONS, scales=proposal.REFIT_SCALES)
    x_new, r, norm, trials = proposal.kept_gauss_newton(x0, [-bound], [bound], tangent, residual_at, r0,
                                                        proposal.REFIT_ITERATIONS, scales=proposal.REFIT_SCALES,
                                                        secant=True)
    assert abs(x_new[0] - 1.0) < 1e-3 < abs(x_fixed[0] - 1.0)
    assert norm == pytest.approx(float(r @ r)) and norm < 1e-6 * float(r0 @ r0)


def test_the_secant_refit_never_raises_the_residual_and_stops_at_a_bound(speed_at):
    residual_at, tangent = _problem(speed_at, 1.0)
    x0 = np.array([0.3])
    r0 = residual_at(x0)
    # a bound below the truth: the refit ends there, the residual lower than at the start, no trial wasted at the bound
    x, _, norm, trials = proposal.kept_gauss_newton(x0, [-0.8], [0.8], tangent, residual_at, r0, 5,
                                                    scales=proposal.REFIT_SCALES, secant=True)
    assert x[0] == pytest.approx(0.8) and norm < float(r0 @ r0)
    assert len(trials) <= 5
    # a tangent of the wrong sign: every step is refused, x stays
    x, _, norm, _ = proposal.kept_gauss_newton(x0, [-2.5], [2.5], -tangent, residual_at, r0, 5,
                                               scales=proposal.REFIT_SCALES, secant=True)
    assert norm <= float(r0 @ r0)


def test_the_motor_terms_bound_lets_a_load_reach_the_motors_breakdown_torque():
    m = load_model(None).plant_config().motor
    breakdown = motor.equivalent_circuit(motor.breakdown_slip(m), m).torque_pu
    assert breakdown == pytest.approx(1.75, abs=0.01)
    bound = candidate_terms.BALANCES["motor_load_moment_pu"][2]
    # a constant load and a linear law of the speed reach it within the bound, a law of the speed's square too at 132
    # rad/s (a drive loaded near breakdown)
    assert bound > breakdown and bound * (132.0 / m.base_mechanical_speed_rad_s) ** 2 >= breakdown - 0.01
