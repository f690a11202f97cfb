"""The check of the both-accelerometer width against the motor side's (classifier/signal_check.py): the rule itself,
then on drives of the independent simulator (foreign_drives/, not our plant): a drive whose load side carries a
mechanism outside the catalogue, where both together extrapolate, and a clean drive, where both together are the
more precise and the check must not spoil them."""
import math

import numpy as np
import pytest

from backlash_monitor.classifier.signal_check import (BOTH_SIGNALS, MIN_DEPARTURE_M, MOTOR_SIDE_SIGNAL,
                                                      SCATTER_RATIO, SIGNAL_CHECK_SIGMAS, checked_width)


def test_widths_that_agree_within_the_check_keep_both_together():
    c = checked_width(5.00e-3, 0.05e-3, 5.10e-3, 0.05e-3)
    assert c.signal == BOTH_SIGNALS and c.width_m == 5.00e-3 and c.uncertainty_m == 0.05e-3
    assert c.departure_sigmas == pytest.approx(0.1 / math.hypot(0.05, 0.05))


def test_a_departure_beyond_the_check_takes_the_motor_side_with_its_own_uncertainty():
    # 0.5 mm apart with standard errors of 0.1 mm each: 3.5 combined standard errors
    c = checked_width(6.0e-3, 0.1e-3, 5.5e-3, 0.1e-3)
    assert c.departure_sigmas > SIGNAL_CHECK_SIGMAS
    assert c.signal == MOTOR_SIDE_SIGNAL and c.width_m == 5.5e-3 and c.uncertainty_m == 0.1e-3


def test_the_threshold_is_on_the_combined_standard_error():
    se = 0.1e-3
    just_inside = SIGNAL_CHECK_SIGMAS * math.hypot(se, se) * 0.99
    assert checked_width(5e-3 + just_inside, se, 5e-3, se).signal == BOTH_SIGNALS
    assert checked_width(5e-3 + just_inside / 0.98, se, 5e-3, se).signal == MOTOR_SIDE_SIGNAL


def test_a_departure_smaller_than_the_regressions_own_disagreement_keeps_both_together():
    """0.15 mm apart at 5 combined standard errors: beyond the error, but within the 0.2 mm the two regressions differ
    by on clean drives; 0.3 mm apart at the same errors: taken."""
    se = 0.15e-3 / 5 / math.sqrt(2)
    kept = checked_width(5.15e-3, se, 5.0e-3, se)
    assert kept.departure_sigmas == pytest.approx(5.0) and 0.15e-3 < MIN_DEPARTURE_M and kept.signal == BOTH_SIGNALS
    assert checked_width(5.3e-3, se, 5.0e-3, se).signal == MOTOR_SIDE_SIGNAL


def test_both_together_scattering_far_more_than_the_motor_side_takes_the_motor_side():
    """On the library's own model both together scatter less than a1 alone; 1 mm of scatter beside 0.12 mm says the
    load side is not that model, even where the medians lie within 2 combined errors of each other."""
    c = checked_width(6.7e-3, 1.0e-3, 5.75e-3, 0.12e-3)
    assert c.departure_sigmas < SIGNAL_CHECK_SIGMAS and c.scatter_ratio > SCATTER_RATIO
    assert c.signal == MOTOR_SIDE_SIGNAL and c.width_m == 5.75e-3
    assert checked_width(6.7e-3, 0.2e-3, 6.6e-3, 0.12e-3).signal == BOTH_SIGNALS     # 1.7x: kept


@pytest.mark.parametrize("values", [(5e-3, math.nan, 6e-3, 1e-4), (5e-3, 1e-4, math.nan, 1e-4),
                                    (5e-3, math.inf, 9e-3, 1e-4), (5e-3, 1e-4, 9e-3, math.inf),
                                    (5e-3, 1e-4, 9e-3, 0.0)])
def test_widths_without_a_finite_uncertainty_are_not_checked(values):
    """Fewer than 3 events (NaN), a width censored at the range's top (+inf), or a motor side whose events gave one
    width exactly (a stuck or clipped input, not a precision): nothing to test against."""
    c = checked_width(*values)
    assert c.signal == BOTH_SIGNALS and c.width_m == values[0] and math.isnan(c.departure_sigmas)


def test_both_together_at_the_top_of_the_range_beside_a_motor_side_inside_it_takes_the_motor_side():
    """A censored fused width (uncertainty +inf: the windows' median at the 20 mm clip, so the width is at least that)
    beside a motor side read at 6.9 +- 0.1 mm departs by at least 13.1 mm, 131 of the motor side's errors: the motor
    side's is taken (before, not checked: the drive read >= 20 mm). A motor side near the top itself keeps both (a
    drive wider than the range); a censored motor side, or one above the censored value, leaves it unchecked."""
    c = checked_width(20e-3, math.inf, 6.9e-3, 0.1e-3)
    assert c.signal == MOTOR_SIDE_SIGNAL and c.width_m == 6.9e-3 and c.uncertainty_m == 0.1e-3
    assert c.departure_sigmas == pytest.approx(131.0) and c.reason.startswith("read at the top of the range")
    near = checked_width(20e-3, math.inf, 19.9e-3, 0.2e-3)     # 0.1 mm below it at 0.5 sigma: a wide drive
    assert near.signal == BOTH_SIGNALS and near.width_m == 20e-3 and near.departure_sigmas == pytest.approx(0.5)
    floor = checked_width(20e-3, math.inf, 19.85e-3, 0.01e-3)  # 15 sigma but 0.15 mm: within the regressions' floor
    assert floor.signal == BOTH_SIGNALS
    for motor in [(6.9e-3, math.inf), (6.9e-3, math.nan), (math.nan, 0.1e-3), (6.9e-3, 0.0)]:
        kept = checked_width(20e-3, math.inf, *motor)
        assert kept.signal == BOTH_SIGNALS and kept.width_m == 20e-3 and math.isnan(kept.departure_sigmas)


def _traces(label: str, suite_name: str = "outside_sealed9"):
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import suite

    from backlash_monitor.estimation import DEFAULT_FUSION_EVENTS
    from backlash_monitor.workbench.measurement import Measurement
    from backlash_monitor.workbench.width import monitor_widths
    spec = next(s for s in suite(suite_name) if s.label == label)
    rec = make_recording(spec)
    meas = Measurement(f"foreign:{label}", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    both, motor = monitor_widths(meas, signal=BOTH_SIGNALS), monitor_widths(meas, signal=MOTOR_SIDE_SIGNAL)
    full = both.fused_events >= DEFAULT_FUSION_EVENTS
    n = DEFAULT_FUSION_EVENTS
    # the unchecked fusion of both together: the median of the last n windows' continuous widths (fusion.py)
    unchecked = np.array([np.median(both.continuous_m[max(0, i - n + 1):i + 1]) for i in range(both.continuous_m.size)])
    return rec.truth.true_width_m, both, motor, unchecked, full


def test_a_load_side_mechanism_outside_the_catalogue_gives_the_motor_sides_width():
    """A load wheel with a blower sail (a drag the catalogue has no law for; spent set 9): both together read the
    width off by extrapolating a2's features, the motor side does not. Every full fusion is one of the two, the
    checked width lies on the motor side's where it departs, and it is closer to the truth than both together."""
    truth, both, motor, unchecked, full = _traces("os9_mass_wheel_blower_sail")
    assert full.sum() >= 5
    took_motor = np.isclose(both.fused_continuous_m, motor.fused_continuous_m, rtol=0, atol=1e-12)
    kept_both = np.isclose(both.fused_continuous_m, unchecked, rtol=0, atol=1e-12)
    assert np.all((took_motor | kept_both)[full])
    assert took_motor[full].sum() >= 1
    err_checked = np.mean(np.abs(both.fused_continuous_m[full] - truth))
    err_unchecked = np.mean(np.abs(unchecked[full] - truth))
    assert err_checked < err_unchecked, (err_checked, err_unchecked)


def test_a_load_side_sensor_that_drives_both_together_to_the_top_of_the_range_gives_the_motor_sides_width():
    """An a2 whose conditioning restores its baseline (spent set 20; the other simulator's law, not ours): both
    together read 20 mm, the top of the range, on most full fusions of a 6.9 mm drive (censored: +inf), the motor
    side 6.9 mm. Checked, every full fusion is finite and the motor side's where both together were censored: the
    live classifier's level no longer reads an ERROR of at least 20 mm on a drive below its warning."""
    truth, both, motor, unchecked, full = _traces("os20_a2_baseline_restorer", "outside_sealed20")
    assert full.sum() >= 5
    top = np.isclose(unchecked, np.max(unchecked), rtol=0, atol=1e-9) & (np.max(unchecked) >= 19.9e-3)
    assert top[full].sum() >= 2, unchecked[full]         # the case: both together censored at the top
    took_motor = np.isclose(both.fused_continuous_m, motor.fused_continuous_m, rtol=0, atol=1e-12)
    assert np.all(took_motor[full & top])
    assert np.all(both.fused_continuous_m[full] < 19.9e-3)
    assert np.max(np.abs(both.fused_continuous_m[full] - truth)) < 0.5e-3
    assert np.mean(np.abs(unchecked[full] - truth)) > 3e-3


def test_on_a_clean_drive_the_check_keeps_the_width_within_a_tenth_of_a_millimetre():
    """A clean drive of the other simulator (width 6.3 mm, damping and n1 of its own): both together and the motor
    side agree within their noise, so the checked width stays as close as the resolution goal asks."""
    truth, both, _, unchecked, full = _traces("os9_clean_w6.3_eta0.0215_n0.91")
    assert full.sum() >= 5
    err_checked = np.mean(np.abs(both.fused_continuous_m[full] - truth))
    assert err_checked <= 0.1e-3, err_checked
    assert err_checked <= np.mean(np.abs(unchecked[full] - truth)) + 0.05e-3


def test_the_message_says_which_test_took_the_motor_side_and_nothing_when_it_did_not():
    from backlash_monitor.classifier.signal_check import rule_text, source_text
    departed = checked_width(6.0e-3, 0.1e-3, 5.5e-3, 0.1e-3)        # 0.5 mm at 3.5 sigma, the same scatter
    scattered = checked_width(6.7e-3, 1.0e-3, 5.75e-3, 0.12e-3)     # 8.3x the scatter, within 2 sigma
    both = checked_width(7.0e-3, 1.0e-3, 5.0e-3, 0.12e-3)           # 2.0 mm at 2.0 sigma is not beyond 2; 8.3x
    kept = checked_width(5.0e-3, 0.05e-3, 5.1e-3, 0.05e-3)
    assert departed.reason == "departed by 3.5 sigma (0.50 mm)"
    assert scattered.reason == "scattered 8.3x as much"
    assert both.reason == "scattered 8.3x as much" and kept.reason == ""
    far = checked_width(8.0e-3, 0.3e-3, 5.0e-3, 0.12e-3)            # 3 mm at 9.3 sigma and 2.5x the scatter
    assert far.reason == "departed by 9.3 sigma (3.00 mm) and scattered 2.5x as much"
    assert source_text("a1", BOTH_SIGNALS, departed.reason) == "a1's: a1+a2 departed by 3.5 sigma (0.50 mm)"
    assert source_text(BOTH_SIGNALS, BOTH_SIGNALS, kept.reason) == "" and source_text("", BOTH_SIGNALS, "") == ""
    # the rule in words names all three thresholds (the floor too)
    assert all(part in rule_text() for part in (f"{SIGNAL_CHECK_SIGMAS:g} combined standard errors",
                                                f"{MIN_DEPARTURE_M * 1e3:g} mm", f"{SCATTER_RATIO:g}x"))
