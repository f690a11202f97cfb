"""A sample stream's clock: a chunk's header stamp in seconds, and the stream's time origin (the time of its
sample 0) from a stamped range of it. Written once here for the windowing stage, the nodes and the offline analysis
(no ROS import: a stamp is anything with ``sec`` and ``nanosec``, a ``(sec, nanosec)`` pair, or seconds)."""
from __future__ import annotations

import math


def stamp_seconds(stamp) -> float | None:
    """``stamp`` in seconds: a builtin_interfaces/Time or anything with ``sec`` and ``nanosec``, a ``(sec,
    nanosec)`` pair, or a number of seconds; None when there is none, it is not one of those, or not finite."""
    if stamp is None:
        return None
    try:
        if hasattr(stamp, "sec"):
            seconds = float(stamp.sec) + float(stamp.nanosec) * 1e-9
        elif isinstance(stamp, (tuple, list)):
            sec, nanosec = stamp
            seconds = float(sec) + float(nanosec) * 1e-9
        else:
            seconds = float(stamp)
    except (TypeError, ValueError, AttributeError):
        return None
    return seconds if math.isfinite(seconds) else None


def stream_origin_s(stamp_s: float, first_sample_index: int, sample_period_s: float) -> float:
    """The time [s] of sample 0 of a stream whose range starting at ``first_sample_index`` is stamped ``stamp_s``
    (a range's stamp is the time of its first sample)."""
    return float(stamp_s) - first_sample_index * float(sample_period_s)


def sample_time_s(origin_s: float, sample_index: int, sample_period_s: float) -> float:
    """The time [s] of sample ``sample_index`` of a stream whose sample 0 is at ``origin_s``."""
    return float(origin_s) + sample_index * float(sample_period_s)
