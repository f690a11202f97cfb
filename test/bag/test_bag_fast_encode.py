"""The straight-line BacklashEstimate encoder (the estimates analyze writes) gives the generic
encoder's bytes, byte for byte (padding included), for dicts, decoded messages and odd values;
what it does not take as is (defaults, bytes forms) goes to the generic encoder."""
import math

import numpy as np
import pytest

from backlash_monitor.bag import BACKLASH_ESTIMATE, SIGNAL_CHUNK, Codec


def generic(codec: Codec, msg) -> bytes:
    out = bytearray(b"\x00\x01\x00\x00")
    codec._enc(codec.specs[codec.type_name], msg, out)
    return bytes(out)


def estimate(**over):
    msg = {"header": {"stamp": {"sec": 1_700_000_123, "nanosec": 456_789},
                      "frame_id": "drive"},
           "signal_name": "a1+a2", "mode": "shape", "entry_sample_index": 123_456,
           "entry_kind": "onset",
           "candidate_widths_m": np.array([0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01]),
           "b_vector": np.array([3.5, 2.0, 0.1, 1e-300, math.inf, 7.0]),
           "width_index": 2, "width_m": 0.005, "b_margin": 20.0, "continuous_width_m": 0.0051,
           "fused_width_m": 0.005, "fused_events": 8, "true_width_m": math.nan,
           "fused_continuous_width_m": 0.00507, "fused_width_uncertainty_m": 2.1e-5}
    msg.update(over)
    return msg


CASES = [
    {},
    {"signal_name": "a1", "mode": "paper", "entry_kind": "return"},
    {"header": {"stamp": {"sec": -3, "nanosec": 0}, "frame_id": ""}},
    {"header": {"stamp": {"sec": 0, "nanosec": 1}, "frame_id": "línea_ü/drive7"}},
    {"candidate_widths_m": np.zeros(0), "b_vector": []},
    {"b_vector": [1, 2, 3], "candidate_widths_m": (0.1,)},
    {"b_vector": np.arange(6, dtype=np.float32)},
    {"entry_sample_index": np.uint64(2**64 - 1), "width_index": np.int64(5),
     "fused_events": np.uint32(0), "width_m": np.float64(0.0025), "true_width_m": 1},
    {"entry_kind": "x" * 7, "mode": "ab"},
    {"continuous_width_m": math.nan, "fused_width_m": -0.0, "fused_continuous_width_m": math.nan},
    {"fused_continuous_width_m": math.nan, "fused_width_uncertainty_m": math.nan},
]


@pytest.mark.parametrize("over", CASES)
@pytest.mark.parametrize("pad_byte", [0, 0xAB])
def test_fast_equals_generic_byte_for_byte(over, pad_byte):
    codec = Codec.for_type(BACKLASH_ESTIMATE)
    assert codec._fast_encode is not None
    codec.pad_byte = pad_byte
    msg = estimate(**over)
    fast = codec._enc_backlash_estimate(msg)
    assert fast == generic(codec, msg)
    assert codec.encode(msg) == fast
    decoded = codec.decode(fast)          # a message object encodes the same way
    assert codec._enc_backlash_estimate(decoded) == generic(codec, decoded) == fast


@pytest.mark.parametrize("over", [{"true_width_m": None}, {"mode": None}, {"b_vector": b"\x00" * 8},
                                  {"header": {"stamp": {"sec": 1, "nanosec": 2}}}])
def test_values_it_does_not_take_go_to_the_generic_encoder(over):
    codec = Codec.for_type(BACKLASH_ESTIMATE)
    msg = estimate(**over)
    if "header" in over:
        msg["header"] = dict(msg["header"], frame_id=None)
    assert codec.encode(msg) == generic(codec, msg)


def test_errors_are_the_generic_encoders():
    codec = Codec.for_type(BACKLASH_ESTIMATE)
    with pytest.raises(Exception) as fast_error:
        codec.encode(estimate(width_index=-1))
    with pytest.raises(Exception) as generic_error:
        generic(codec, estimate(width_index=-1))
    assert type(fast_error.value) is type(generic_error.value)


def test_only_backlash_estimate_shaped_types():
    assert Codec.for_type(SIGNAL_CHUNK)._fast_encode is None
    assert Codec.for_type("backlash_monitor_msgs/msg/BacklashWindow")._fast_encode is None
