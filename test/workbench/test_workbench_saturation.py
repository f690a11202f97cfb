"""The workbench's conditions name a saturated recording before any effect: a clipped a2 (foreign generator,
clipped after its sensor chain) is counted as analyze counts it, and diagnose's message starts with it."""
import dataclasses

import numpy as np
import pytest

pytest.importorskip("foreign_drives")

from backlash_monitor.workbench import diagnose  # noqa: E402
from backlash_monitor.workbench.measurement import Measurement  # noqa: E402


@pytest.fixture(scope="module")
def recording():
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import BENCH
    spec = dataclasses.replace(next(s for s in BENCH if s.label == "clean_w7.1_eta0.0125_n0.97"), duration_s=2.0)
    rec = make_recording(spec)
    return {k: rec.signals[k] for k in ("a1", "a2", "angle_difference", "omega1", "omega2")}, rec.sample_period_s


def test_a_clipped_recording_is_named_saturated_and_a_clean_one_not(recording):
    signals, dt = recording
    assert not Measurement("clean", dt, dict(signals)).saturation()["saturated"]
    clipped = dict(signals)
    rail = 0.75 * float(np.abs(signals["a2"]).max())
    clipped["a2"] = np.clip(signals["a2"], -rail, rail)
    sat = Measurement("clipped", dt, clipped).saturation()
    assert sat["saturated"] and sat["signals"]["a1"]["at_rail"] == 0 and sat["signals"]["a2"]["at_rail"] > 0
    assert len(sat["messages"]) == 1 and sat["messages"][0].startswith("a2 at its rail (")
    message = diagnose.saturated_first("a clutch damping explains 80 % of the residual", sat)
    assert message.startswith("the recording is saturated: a2 at its rail")
    assert message.index("range is too small") < message.index("clutch damping")
    assert diagnose.saturated_first("nothing to discover", {"saturated": False, "messages": []}) == \
        "nothing to discover"


def test_a_stuck_sensor_is_named_in_the_conditions(recording):
    signals, dt = recording
    stuck = dict(signals)
    stuck["a1"] = signals["a1"].copy()
    stuck["a1"][60_000:] = stuck["a1"][60_000]
    sat = Measurement("stuck", dt, stuck).saturation()
    assert sat["saturated"] and "a1 stuck" in sat["messages"][0] and "dead accelerometer" in sat["messages"][0]


def test_no_term_is_proposed_from_a_clipped_or_stuck_sensor_and_the_user_is_told_why(recording):
    # a clipped or held signal has lost what the drive did: no term of the drive's states reproduces it, so the
    # residual is the sensor's fault; the proposal says so instead of fitting a law to it (a spent sealed row, an a2
    # blanked during each stroke, got a rim force that made the model stop crossing its backlash)
    from backlash_monitor.workbench.proposal import sensor_fault_gate
    signals, dt = recording
    assert sensor_fault_gate(Measurement("clean", dt, dict(signals)).saturation()) is None
    assert sensor_fault_gate({}) is None
    for name, faulty in (("clipped", np.clip(signals["a2"], -0.75 * np.abs(signals["a2"]).max(),
                                             0.75 * np.abs(signals["a2"]).max())),
                         ("stuck", np.where(np.arange(signals["a2"].size) >= 60_000, signals["a2"][60_000],
                                            signals["a2"]))):
        gated = sensor_fault_gate(Measurement(name, dt, {**signals, "a2": faulty}).saturation())
        assert gated is not None and not gated.proposed and not gated.plugin_source and not gated.pieces
        assert gated.reason.startswith("not proposed: a2 ") and "faulty sensor" in gated.reason
        assert ("at its rail" if name == "clipped" else "stuck") in gated.reason
        assert gated.to_json()["proposed"] is False
