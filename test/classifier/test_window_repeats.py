"""A window delivered twice is recognised; a new run of the same drive is not a repeat."""
import pytest

from backlash_monitor.classifier.repeats import RepeatedWindows


def test_the_same_window_twice_is_a_repeat():
    seen = RepeatedWindows()
    assert not seen.is_repeat(1_000, 2700, "onset", "drive")
    assert not seen.is_repeat(1_000, 2700, "return", "drive")     # the other entry kind
    assert not seen.is_repeat(1_000, 2700, "onset", "drive8")     # another drive
    assert seen.is_repeat(1_000, 2700, "onset", "drive")
    assert seen.repeats == 1


def test_a_new_run_from_sample_zero_has_new_stamps_and_is_not_a_repeat():
    seen = RepeatedWindows()
    period_ns = 20_000
    for start_ns in (10**18, 10**18 + 60 * 10**9):               # the same drive restarted
        for entry in (2700, 15200, 27700):
            assert not seen.is_repeat(start_ns + entry * period_ns, entry, "onset")
    assert seen.repeats == 0


def test_memory_is_bounded_to_the_last_windows():
    seen = RepeatedWindows(capacity=3)
    for entry in range(5):
        seen.is_repeat(entry, entry, "onset")
    assert not seen.is_repeat(0, 0, "onset")    # forgotten: older than the last 3
    assert seen.is_repeat(4, 4, "onset")
    with pytest.raises(ValueError, match="allowed"):
        RepeatedWindows(capacity=0)
