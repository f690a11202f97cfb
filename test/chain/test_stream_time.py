"""A stream's clock (backlash_monitor/stream_time.py): stamps in seconds and the time of a stream's sample 0, the one
place the windowing stage, the nodes and the offline analysis take them from."""
import math
from collections import namedtuple

import pytest

from backlash_monitor.stream_time import sample_time_s, stamp_seconds, stream_origin_s

Time = namedtuple("Time", "sec nanosec")      # builtin_interfaces/Time's fields, without ROS


@pytest.mark.parametrize("stamp", [Time(1_714_000_123, 250_000_000), (1_714_000_123, 250_000_000),
                                   [1_714_000_123, 250_000_000], 1_714_000_123.25])
def test_every_stamp_form_reads_the_same_seconds(stamp):
    assert stamp_seconds(stamp) == pytest.approx(1_714_000_123.25, abs=1e-6)


@pytest.mark.parametrize("stamp", [None, "noon", (1, 2, 3), Time("a", 0), math.nan, math.inf, (math.inf, 0)])
def test_a_missing_or_unusable_stamp_is_none(stamp):
    assert stamp_seconds(stamp) is None


def test_the_origin_of_a_range_is_its_stamp_less_the_samples_before_it():
    # a stream at 50 kHz whose range at sample 125 000 (2.5 s in) is stamped 100.5 s: sample 0 was at 98.0 s
    period = 2e-5
    origin = stream_origin_s(100.5, 125_000, period)
    assert origin == pytest.approx(98.0, abs=1e-9)
    # every later range of the same stream points to the same origin, and the samples' times back to the stamps
    for first in (0, 1, 125_000, 3_000_017):
        stamp = 98.0 + first * period
        assert stream_origin_s(stamp, first, period) == pytest.approx(origin, abs=1e-9)
        assert sample_time_s(origin, first, period) == pytest.approx(stamp, abs=1e-9)


def test_a_restarted_stream_has_another_origin():
    # sample 0 again, 10 s later: its origin is its own stamp, not the old stream's
    period = 2e-5
    old = stream_origin_s(100.5, 125_000, period)
    new = stream_origin_s(110.5, 0, period)
    assert new - old == pytest.approx(12.5, abs=1e-9)
