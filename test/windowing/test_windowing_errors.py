"""Bad parameters raise ValueError naming the parameter (and the allowed values)."""
import numpy as np
import pytest

from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture, extract_windows


@pytest.mark.parametrize("kwargs, match", [
    ({"trigger": "eq1"}, r"trigger='eq1'.*contact_loss.*paper"),
    ({"trigger": "paper"}, r"width_m=None"),
    ({"trigger": "paper", "width_m": 0.0}, r"width_m=0.0"),
    ({"trigger": "paper", "width_m": -0.005}, r"width_m"),
    ({"trigger": "contact_loss", "width_m": -1.0}, r"width_m"),
    ({"angle_source": "gyro"}, r"angle_source='gyro'.*auto"),
    ({"integration": "simpson"}, r"integration='simpson'.*trapezoid"),
    ({"holdoff_samples": 0}, r"holdoff_samples"),
    ({"holdoff_samples": 2048.0}, r"holdoff_samples"),
    ({"radius_m": 0}, r"radius_m"),
    ({"sample_period_s": -2e-5}, r"sample_period_s"),
    ({"confirm_rad": float("nan")}, r"confirm_rad"),
    ({"fit_samples": 10}, r"fit_samples"),
    ({"initial_contact_side": 0}, r"initial_contact_side"),
])
def test_detector_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        BacklashEntryDetector(**kwargs)


@pytest.mark.parametrize("kwargs, match", [
    ({"window_length": 0}, "window_length"),
    ({"window_length": 2048.5}, "window_length"),
    ({"window_length": True}, "window_length"),
    ({"signals": "a1"}, "signals"),
    ({"signals": ()}, "signals"),
    ({"history_samples": -1}, "history_samples"),
])
def test_capture_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        WindowCapture(**kwargs)


def test_missing_angle_signals():
    with pytest.raises(ValueError, match="signals"):
        BacklashEntryDetector().feed(0, {"a1": np.zeros(5)})


def test_extract_windows_needs_1d():
    with pytest.raises(ValueError, match="extract_windows_batch"):
        extract_windows({"a1": np.zeros((2, 10)), "a2": np.zeros((2, 10)), "angle_difference": np.zeros((2, 10))})


def test_finite_inputs_whose_integral_overflows_still_reset_the_detector():
    """``finite=True`` (the caller checked the samples, as WindowingStage does) skips only the test
    of a measured angle difference given as is: speeds that are finite but whose difference
    overflows to inf still reset the integrated detector instead of poisoning its tracker."""
    speeds = {"omega1": np.full(1000, 1.5e308), "omega2": np.full(1000, -1.5e308)}
    det = BacklashEntryDetector(angle_source="integrated")
    with np.errstate(over="ignore"):
        assert det.feed(0, speeds, finite=True) == []
    assert any("non-finite" in event for _, event in det.events)
    measured = BacklashEntryDetector()
    measured.feed(0, {"angle_difference": np.zeros(1000)}, finite=True)
    assert measured.events == []
