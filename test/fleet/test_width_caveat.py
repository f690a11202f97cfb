"""The width's model-fit caveat (fleet/caveat.py): one core, read live (the model watch's ModelFit) and
offline (analyze FOLDER's model fit of the same bag). A width alarm never stands alone when the fit fails."""
import math

import pytest

from backlash_monitor.fleet.folder_analysis import add_trends
from backlash_monitor.fleet.caveat import (FitVerdict, caveat, says_model_fails, width_line, width_text,
                                           with_caveat)
from backlash_monitor.fleet.trend import TrendRule

RULE = TrendRule(warn_growth_m_per_day=5e-5, warn_width_m=0.0075, error_width_m=0.009)


def test_the_caveat_names_the_model_its_residual_and_what_to_do():
    fit = FitVerdict.from_watch("WARN", "drive7 v1", 2.5)
    assert width_line(0.0108, 5e-5, fit) == ("width 10.80 ± 0.05 mm — model drive7 v1 does not explain this "
                                             "drive (residual 2.5× its floor): run diagnose before acting")
    assert says_model_fails(width_line(0.0108, 5e-5, fit))


def test_a_model_that_explains_or_no_fit_at_all_leaves_the_width_alone():
    assert caveat(None) == "" and caveat(FitVerdict.from_watch("OK", "drive7 v1", 0.9)) == ""
    assert width_line(0.005, math.nan, None) == "width 5.00 mm"
    assert with_caveat("ERROR", FitVerdict("m", True, 0.8)) == "ERROR"
    assert width_text(math.nan) == "-" and width_text(0.0) == "-"       # 0: a publisher that sets none


def test_a_censored_width_says_it_is_at_the_top_of_the_range_and_keeps_the_caveat():
    """+inf uncertainty (classifier/fusion.py: the fused median at the continuous range's clip) reads as a bound,
    never as '20.00 ± 0.00 mm', and the model's caveat still follows in the same line."""
    assert width_text(0.02, math.inf) == "≥ 20.00 mm (the top of the classifier's range)"
    line = width_line(0.02, math.inf, FitVerdict.from_watch("WARN", "v1", 6.0))
    assert line.startswith("width ≥ 20.00 mm (the top") and says_model_fails(line) and "±" not in line


def test_bad_levels_are_refused_and_a_fit_that_is_a_reason_gives_no_verdict():
    with pytest.raises(ValueError, match="allowed: OK, WARN"):
        FitVerdict.from_watch("ERROR", "m", 1.0)
    assert FitVerdict.from_recording("no reference") is None
    assert FitVerdict.from_recording(None) is None
    assert FitVerdict.from_recording({"level": "WARN", "model": "default v1",
                                      "residual_over_noise": 3.14}).explains is False


def _row(bag, width_m, fit):
    return {"bag": bag, "drive": "line1/drive7", "time_s": 1.0e9, "width_m": width_m,
            "fused_width_m": width_m, "error": "", "model_fit": fit}


def test_a_fleet_width_alarm_on_a_drive_its_model_does_not_explain_carries_the_caveat():
    """A healthy 5 mm drive read as 10.8 mm: ERROR by the width, and the same reason says the model does not
    explain the recording (the issue's set-3 drive)."""
    rows = [_row("a.mcap", 0.0108, {"level": "WARN", "model": "default v1", "residual_over_noise": 2.5})]
    _, trends = add_trends(rows, RULE)
    assert rows[0]["level"] == "ERROR"
    assert rows[0]["reason"].startswith("width 10.80 mm >= 9 mm — model default v1 does not explain")
    ok = [_row("b.mcap", 0.0108, {"level": "OK", "model": "default v1", "residual_over_noise": 0.9})]
    add_trends(ok, RULE)
    assert ok[0]["level"] == "ERROR" and not says_model_fails(ok[0]["reason"])
