"""Our CDR bytes are what rclpy (rmw_fastrtps / Fast CDR) produces for the same message.

Fast CDR leaves alignment padding bytes uninitialised and rclpy's buffer may carry up to 7 trailing
bytes of padding (its size estimate), so the comparison is byte-for-byte on every byte that is not
padding: the padding positions are found by encoding once with 0x00 and once with 0xFF padding.
"""
from __future__ import annotations

import numpy as np
import pytest

rclpy_serialization = pytest.importorskip("rclpy.serialization")
msgs = pytest.importorskip("backlash_monitor_msgs.msg")
from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue  # noqa: E402
from std_msgs.msg import Float64, String, UInt8  # noqa: E402

from backlash_monitor.bag import Codec  # noqa: E402


def _type_name(msg) -> str:
    mod = type(msg).__module__.split(".")[0]
    return f"{mod}/msg/{type(msg).__name__}"


def _check(msg):
    codec = Codec.for_type(_type_name(msg))
    ours = codec.encode(msg)
    codec_ff = Codec.for_type(_type_name(msg))
    codec_ff.pad_byte = 0xFF
    ours_ff = codec_ff.encode(msg)
    theirs = rclpy_serialization.serialize_message(msg)
    assert len(ours) == len(ours_ff)
    assert 0 <= len(theirs) - len(ours) < 8, (len(theirs), len(ours))
    data = [i for i in range(len(ours)) if ours[i] == ours_ff[i]]
    assert bytes(ours[i] for i in data) == bytes(theirs[i] for i in data)
    # both directions decode to the same message
    again = rclpy_serialization.deserialize_message(ours, type(msg))
    assert codec.decode(rclpy_serialization.serialize_message(again)) == codec.decode(ours)
    assert codec.decode(theirs) == codec.decode(ours)
    return codec.decode(theirs)


@pytest.mark.ros
@pytest.mark.parametrize("n, frame", [(0, ""), (1, "d"), (3, "drv"), (1000, "drive_0"), (7, "ü")])
def test_signal_chunk_bytes_match_rclpy(n, frame):
    m = msgs.SignalChunk()
    m.header.stamp.sec = -3
    m.header.stamp.nanosec = 999_999_999
    m.header.frame_id = frame
    m.signal_name = "angle_difference"[: n % 17]
    m.unit = "rad"
    m.sample_period_s = 2e-5
    m.first_sample_index = 2**63 + 5
    m.samples = np.random.default_rng(n).standard_normal(n).tolist()
    dec = _check(m)
    np.testing.assert_array_equal(dec.samples, np.array(m.samples))
    assert dec.first_sample_index == 2**63 + 5 and dec.header.stamp.sec == -3


@pytest.mark.ros
def test_window_estimate_and_diagnostics_bytes_match_rclpy():
    w = msgs.BacklashWindow(entry_sample_index=42, entry_kind="return", trigger="contact_loss",
                            sample_period_s=2e-5, denoising="sym5 level 6, details 1-6 removed",
                            a1=np.linspace(0, 1, 2048).tolist(), a2=[], true_width_m=float("nan"))
    _check(w)
    e = msgs.BacklashEstimate(signal_name="a1+a2", mode="paper", entry_sample_index=7,
                              entry_kind="onset", candidate_widths_m=[0.0025, 0.005], b_vector=[3.0],
                              width_index=1, width_m=0.005, b_margin=1.25,
                              continuous_width_m=float("nan"), fused_width_m=0.004, fused_events=9,
                              true_width_m=0.005)
    _check(e)
    d = DiagnosticArray()
    d.header.frame_id = "x"
    d.status = [DiagnosticStatus(level=DiagnosticStatus.WARN, name="n" * k, message="m",
                                 hardware_id="", values=[KeyValue(key="k" * k, value="v")] * k)
                for k in range(4)]
    dec = _check(d)
    assert dec.status[1].level == 1 and dec.status[3].values[2].key == "kkk"


@pytest.mark.ros
@pytest.mark.parametrize("msg", [String(data=""), String(data="abcde"), UInt8(data=255),
                                 Float64(data=-1.5)])
def test_std_msgs_bytes_match_rclpy(msg):
    _check(msg)
