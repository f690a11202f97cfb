"""The drive's level follows the fused continuous width, not the class width (issue 31: never a confident wrong
width). The class width is the nearest of the pattern widths (2.5, 3.75, 5, 7.5, 9, 10 mm): a healthy 6.3 mm drive's
class is 7.5 mm, at the WARN threshold, and an 8.3 mm drive's is 9 mm, at the ERROR threshold (config/
diagnostics.yaml). Drives made by foreign_drives (another implementation of the physics: no inverse crime)."""
import math
from pathlib import Path

import numpy as np
import pytest
import yaml

from backlash_monitor.estimation import level_width, width_level
from backlash_monitor.workbench.measurement import Measurement
from backlash_monitor.workbench.width import monitor_widths
from foreign_drives.drive import make_recording
from foreign_drives.spec import RecordingSpec

THRESHOLDS = yaml.safe_load((Path(__file__).resolve().parents[2] / "config" / "diagnostics.yaml").read_text())["/**"]["ros__parameters"]


def test_the_level_width_is_the_continuous_one_where_the_mode_gives_it():
    assert level_width(0.0063, 0.0075) == 0.0063
    assert level_width(math.nan, 0.0075) == 0.0075          # a mode without continuous widths
    assert level_width(0.0, 0.005) == 0.005                 # the message default of a publisher that sets none
    assert [width_level(w, 0.0075, 0.009) for w in (0.0074, 0.0075, 0.0089, 0.009)] == ["OK", "WARN", "WARN", "ERROR"]


@pytest.mark.parametrize("true_width_m,class_m,level", [(0.0063, 0.0075, "OK"), (0.0083, 0.009, "WARN")])
def test_a_drive_between_pattern_widths_gets_the_level_of_its_width_not_of_its_class(true_width_m, class_m, level):
    spec = RecordingSpec(label=f"w{true_width_m}", kind="clean", width_m=true_width_m, eta_k=0.025, n1=0.89,
                         effects=(), seed=412, duration_s=3.0).check()
    rec = make_recording(spec)
    meas = Measurement("foreign", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    trace = monitor_widths(meas)
    assert trace.fused_m[-1] == class_m                     # the class: at or past the threshold
    width = level_width(trace.fused_continuous_m[-1], trace.fused_m[-1])
    assert abs(width - true_width_m) < 3e-4, width
    assert width_level(width, THRESHOLDS["warn_width_m"], THRESHOLDS["error_width_m"]) == level
    assert width_level(class_m, THRESHOLDS["warn_width_m"], THRESHOLDS["error_width_m"]) != level


def test_no_level_from_fewer_fused_events_than_the_check_needs():
    """One or two onset events give a width but no level: a fused width of fewer than 3 events has no standard error
    and the signal check cannot test it. From 3 events on (or from the whole fusion where it is set shorter) the
    level is the width's."""
    from backlash_monitor.estimation import LEVEL_MIN_EVENTS, estimate_level
    warn, error = THRESHOLDS["warn_width_m"], THRESHOLDS["error_width_m"]
    assert LEVEL_MIN_EVENTS == 3
    assert [estimate_level(0.016, n, warn, error) for n in (1, 2, 3, 8)] == ["OK", "OK", "ERROR", "ERROR"]
    assert estimate_level(0.008, 3, warn, error) == "WARN" and estimate_level(0.006, 8, warn, error) == "OK"
    # a drive whose fusion is set to 1 or 2 events still gets a level
    assert estimate_level(0.016, 1, warn, error, fusion_events=1) == "ERROR"
    assert estimate_level(0.016, 2, warn, error, fusion_events=2) == "ERROR"


@pytest.mark.parametrize("suite_name,label", [("outside_sealed", "os_a2_crosstalk_0.006"),
                                              ("outside_dev2", "od2_a2_bracket_tilt")])
def test_a_drive_below_its_warning_is_not_alarmed_by_its_first_windows(suite_name, label):
    """Drives of the other simulator (spent outside sets: an a2 crosstalk on a 5.0 mm drive, a tilted a2 bracket on a
    7.0 mm drive) whose first one or two onset windows read both accelerometers together past a threshold: the
    level of every estimate, as the classifier node sets it, stays below the alarm; judged on the width alone, the
    first windows raise it."""
    from backlash_monitor.estimation import estimate_level
    from foreign_drives.suites import suite
    spec = next(s for s in suite(suite_name) if s.label == label)
    rec = make_recording(spec)
    truth = rec.truth.true_width_m
    meas = Measurement("foreign", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    trace = monitor_widths(meas)
    warn, error = THRESHOLDS["warn_width_m"], THRESHOLDS["error_width_m"]
    assert truth < warn
    widths = [level_width(c, f) for c, f in zip(trace.fused_continuous_m, trace.fused_m)]
    alone = [width_level(w, warn, error) for w in widths]
    levels = [estimate_level(w, n, warn, error) for w, n in zip(widths, trace.fused_events)]
    assert any(level != "OK" for level, n in zip(alone, trace.fused_events) if n < 3), alone
    assert all(level == "OK" for level in levels), levels
