"""train's check (retrain.judge): the retrained library is handed on only when it is not further from the diagnosis
than the previous one; and, when the diagnosed model does not explain its recording (a `partial` or
`nothing_explains` verdict: an approximate or proposed addition), only when it is closer to the diagnosis by more than
the diagnosis's own uncertainty -- that diagnosis's width carries its model's form error. The cases are the widths
measured on the loop rows of docs/workbench.md "Retraining the monitor" [mm]."""
import math

import pytest

from backlash_monitor.workbench.retrain import describe, judge

MM = 1e-3


def test_a_library_further_from_the_diagnosis_is_never_handed_on_whatever_the_verdict():
    for verdict in ("discovery", "width", "partial", "nothing_explains", None):
        j = judge(7.5 * MM, 0.05 * MM, 8.3 * MM, 7.52 * MM, verdict)
        assert j["worse"] and j["further"] and not j["not_shown_better"]


def test_on_an_unexplained_diagnosis_a_gain_within_its_uncertainty_is_not_a_reason_to_switch():
    # a rotary distributor valve (sealed9): nothing_explains, diagnosis 6.45 +- 0.26 mm; the retrained library (with a
    # proposed term) 6.76, the packaged 5.89 -- the truth was 5.90: the "closer" library was the wrong one
    j = judge(6.45 * MM, 0.26 * MM, 6.76 * MM, 5.89 * MM, "nothing_explains")
    assert j["worse"] and j["not_shown_better"] and not j["further"]
    assert any("no reference to switch on" in r for r in j["reasons"])
    # the same widths under a discovery (a model that explains the recording): handed on, as before
    assert not judge(6.45 * MM, 0.26 * MM, 6.76 * MM, 5.89 * MM, "discovery")["worse"]


def test_on_an_unexplained_diagnosis_a_gain_beyond_its_uncertainty_is_handed_on():
    # a PI speed brake (sealed6), partial: diagnosis 5.45 +- 0.36 mm, retrained 5.55, packaged 4.04 (truth 5.60)
    j = judge(5.45 * MM, 0.36 * MM, 5.55 * MM, 4.04 * MM, "partial")
    assert not j["worse"] and not j["not_shown_better"]


def test_an_unchanged_width_is_not_judged_worse_and_no_width_is_flagged():
    assert not judge(6.0 * MM, 0.3 * MM, 6.2 * MM, 6.2 * MM, "partial")["worse"]
    j = judge(6.0 * MM, 0.3 * MM, math.nan, 6.2 * MM, "partial")
    assert not j["worse"] and j["reasons"] == ["the retrained monitor gives no width on the diagnosed recording"]


@pytest.mark.parametrize("gain_over_unc", [0.5, 0.99])
def test_the_switch_needs_the_whole_uncertainty(gain_over_unc):
    unc = 0.4 * MM
    old = 7.0 * MM
    new = old + gain_over_unc * unc          # closer to the diagnosis at 8.0 mm by gain_over_unc * unc
    assert judge(8.0 * MM, unc, new, old, "partial")["not_shown_better"]
    assert not judge(8.0 * MM, unc, old + 1.01 * unc, old, "partial")["not_shown_better"]


def test_the_check_line_states_the_diagnosis_with_its_uncertainty():
    # the reference the check judges by is a measurement: the user reads its spread beside the two libraries' widths
    j = judge(6.45 * MM, 0.26 * MM, 6.76 * MM, 5.89 * MM, "nothing_explains")
    entry = {"model": "default v2", "measurement": "/x/drive.mcap", "retrained_width_m": 6.76 * MM,
             "packaged_width_m": 5.89 * MM, "diagnosed_width_m": 6.45 * MM, "diagnosed_width_uncertainty_m": 0.26 * MM,
             **j, "status": "flagged"}
    (line,) = describe({"checked": [entry]})
    assert "retrained monitor 6.760 mm, packaged 5.890 mm, diagnosis 6.450 ± 0.260 mm: FLAGGED" in line
    assert "no reference to switch on" in line


def test_a_version_whose_proposed_term_explains_the_recording_is_checked_as_after_a_discovery(monkeypatch, tmp_path):
    """check_library: the verdict was nothing_explains, but the version holds a proposed term with which the model
    is consistent (add-effect --accept-proposal writes proposal_consistent): a gain within the diagnosis's
    uncertainty is handed on, as after a discovery (set 24's a1 softening: diagnosis 8.66 +- 0.53 mm, retrained 8.47,
    packaged 8.94, truth 8.60). Without a consistent proposal the same widths are kept back."""
    from types import SimpleNamespace

    from backlash_monitor.workbench import retrain
    widths = {"new": 8.47 * MM, "old": 8.94 * MM}
    monkeypatch.setattr(retrain, "load_measurement", lambda path: path)
    monkeypatch.setattr(retrain, "_published_width", lambda meas, lib: widths[lib])
    prov = {"measurement": str(tmp_path / "drive.mcap"), "width_m": 8.66 * MM, "width_uncertainty_m": 0.53 * MM,
            "verdict": "nothing_explains"}
    for consistent, worse in ((True, False), (False, True)):
        model = SimpleNamespace(provenance={**prov, "proposal_consistent": consistent}, label=lambda: "default v2",
                                nominal={"width_m": 7.5 * MM})
        (checked,) = retrain.check_library("new", [model], previous="old")["checked"]
        assert checked["worse"] is worse
