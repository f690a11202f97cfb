"""Proposing a missing term (issue 31) on a foreign drive whose wheel carries a torque locked to its own angle: the
proposal's per-event design lines the term up with the recording's angle (workbench/event_design.py). Its own file, so
that pytest-xdist (--dist loadfile) runs it beside test_workbench_proposal.py's other foreign drive."""
import os

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.workbench import proposal                          # noqa: E402
from test_workbench_proposal import _run_steps                            # noqa: E402


@pytest.mark.heavy      # make test-all (CI time); bench/_workbench/outside.py measures this row by row
@pytest.mark.slow
def test_a_wheel_torque_locked_to_the_wheel_angle_is_proposed_with_its_amplitude_on_a_foreign_drive():
    """Issue 31's law on a drive made by foreign_drives (another simulator, its own angles and phase): a torque
    8 N*m * sin(alpha2 + 0.31) on the wheel, 4 s. Forced through the proposal as if nothing explained it, the proposal
    names a harmonic of a shaft's angle in the wheel's balance, lined up with the recording's angle, its amplitude
    within 3 of its uncertainties (and 25 %) of the truth."""
    from foreign_drives.spec import EffectSpec
    meas = _foreign_s("wheel_angle_propose", "one", 7203,
                      (EffectSpec("ripple_wheel_mesh", {"amplitude_Nm": 8.0, "order": 1, "phase_rad": 0.31}),), 0.006)
    run, up = _run_steps(meas, 0.006)
    found = proposal.propose(run, up, "nothing_explains")
    assert found.proposed, found.reason
    wheel = [p for p in found.pieces if p.balance == "wheel_torque_Nm" and p.harmonic]
    assert wheel, found.law
    a, _, sigma = wheel[0].amplitude_phase()
    assert wheel[0].terms[0].harmonic[1] == 1
    assert abs(a - 8.0) < 3 * sigma and abs(a - 8.0) < 0.25 * 8.0, (a, sigma)


def _foreign_s(label, kind, seed, effects, width, duration_s=4.0):
    from foreign_drives.drive import make_recording
    from foreign_drives.spec import RecordingSpec, SensorNuisance

    from backlash_monitor.workbench.measurement import Measurement
    spec = RecordingSpec(label=label, kind=kind, width_m=width, eta_k=0.025, n1=0.89, effects=tuple(effects),
                         sensor=SensorNuisance(), seed=seed, duration_s=duration_s).check()
    rec = make_recording(spec)
    return Measurement(f"foreign:{label}", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
