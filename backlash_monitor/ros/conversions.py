"""Messages <-> numpy, shared by the nodes, the recorder and the offline analysis.

float64[] fields are handed to the generated message classes as ``array.array('d')`` (their fast
path: no per-element type check) and read back without a copy through the buffer protocol.
"""
from __future__ import annotations

import array
import math

import numpy as np

from backlash_monitor.stream_time import sample_time_s
from backlash_monitor.windowing.a1_chain import A1ChainResult

from builtin_interfaces.msg import Time

from backlash_monitor.signals import SIGNAL_UNITS  # noqa: F401  (re-exported for the nodes)


def to_float64_array(values) -> array.array:
    """A float64 sequence for a message field (fast path of the generated setters)."""
    return array.array("d", np.ascontiguousarray(values, dtype=np.float64).tobytes())


def from_float64_field(field) -> np.ndarray:
    """A message's float64[] field as a numpy array (no copy for array.array fields)."""
    if isinstance(field, array.array):
        return np.frombuffer(field, dtype=np.float64)
    return np.asarray(field, dtype=np.float64)


def time_from_seconds(seconds: float) -> Time:
    sec = math.floor(seconds)
    return Time(sec=int(sec), nanosec=int(round((seconds - sec) * 1e9)) % 1_000_000_000)


def stamp_of_sample(start_time_s: float, sample_index: int, sample_period_s: float) -> Time:
    """The time stamp of sample ``sample_index`` of a stream that started at ``start_time_s``."""
    return time_from_seconds(sample_time_s(start_time_s, sample_index, sample_period_s))


def set_window_a1_chain(msg, chain: A1ChainResult | None) -> None:
    """Put a window's check of a1 against the motor speed into a BacklashWindow's ``a1_chain_*`` fields (left at 0,
    "not checked", when ``chain`` is None or has not compared any of the stream yet); read back by
    :func:`a1_chain_from_window`."""
    if chain is not None and chain.checked:
        msg.a1_chain_seconds, msg.a1_chain_mismatch = chain.seconds, chain.mismatch
        msg.a1_chain_gain, msg.a1_chain_lag, msg.a1_chain_radius_m = chain.gain, chain.lag, chain.radius_m


def a1_chain_from_window(msg) -> A1ChainResult | None:
    """A BacklashWindow's check of a1 against the motor speed (its ``a1_chain_*`` fields, set by the windowing node
    with ``check_a1_chain``); None when the window carries none (0 seconds compared, or a mismatch that is not a
    number)."""
    seconds, mismatch = float(msg.a1_chain_seconds), float(msg.a1_chain_mismatch)
    if not (seconds > 0 and math.isfinite(seconds) and math.isfinite(mismatch)):
        return None
    return A1ChainResult(mismatch, float(msg.a1_chain_gain), msg.a1_chain_lag, seconds, float(msg.a1_chain_radius_m))
