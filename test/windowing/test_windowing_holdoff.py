"""A bouncing contact must not re-trigger an entry inside its window (hold-off + settle re-arm)."""
import numpy as np
import pytest

from backlash_monitor.windowing import BacklashEntryDetector
from backlash_monitor.windowing.synthetic import synthetic_period, tile_record


@pytest.mark.parametrize("holdoff", [2048, 300])
@pytest.mark.parametrize("trigger", ["contact_loss", "paper"])
def test_bounce_does_not_retrigger(trigger, holdoff):
    """holdoff=300 ends before the bounce: the apex + settle re-arm alone must hold."""
    width = 0.005
    p = synthetic_period(width_m=width, bounce_rad=0.004, bounce_s=0.004)
    d, w, dep, ent = tile_record(p, 4)
    # the bounce really re-enters the zone (so eq. 1 alone would fire twice per traverse)
    assert (np.diff((np.abs(d) < p.beta).astype(int)) == 1).sum() > len(ent)
    kw = {"width_m": width} if trigger == "paper" else {}
    got = BacklashEntryDetector(trigger, holdoff_samples=holdoff, **kw).feed(0, {"angle_difference": d})
    assert len(got) == len(ent)
    assert [e.kind for e in got] == [k for _, k in ent]
    assert np.all(np.diff([e.sample_index for e in got]) >= 2048)  # the traverses are > 2048 apart


def test_holdoff_is_respected_even_when_shorter_windows_requested():
    d, w, dep, ent = tile_record(synthetic_period(width_m=0.005), 2)
    got = BacklashEntryDetector("contact_loss", holdoff_samples=4000).feed(0, {"angle_difference": d})
    assert np.all(np.diff([e.sample_index for e in got]) >= 4000)
