"""The recording's conditions (analysis.recover_conditions) as the model simulates them (plant_adapter.simulate_sets):
a recording cut from a running drive -- a model watch's snapshot, any bag that starts mid-stream -- must be simulated
with its pulse train as it was, also when a pulse is on at its first sample.

The plant's pulse train is periodic before sample 0 (the run-in) and starts at first_s after it (the paper's settled
start); a recovered first_s above period - duration means the recording starts inside a pulse, which the model would
otherwise stop at sample 0 (plant_adapter.pulse_lead_samples). Checked noise-free: the model under the recovered
conditions must reproduce the recording sample by sample (the same plant, in its periodic steady state)."""
import numpy as np
import pytest

from backlash_monitor.workbench import analysis, plant_adapter
from backlash_monitor.workbench.measurement import Measurement
from backlash_monitor.workbench.model import load_model

FS = 50_000
PERIOD = 12_500
SIGNALS = ("a1", "a2", "omega1", "angle_difference")


@pytest.fixture(scope="module")
def model():
    return load_model(None, width_m=0.005)


@pytest.fixture(scope="module")
def stream(model):
    """3.3 s of the model's drive, noise-free, from its settled start (first pulse at 0.05 s)."""
    runs = plant_adapter.simulate_sets(model, [{}], [0], int(3.3 * FS), noise=False, signals=SIGNALS)
    return {k: v[0, 0] for k, v in runs.items()}


def _cut(stream, start: int, n: int = int(2.0 * FS)) -> Measurement:
    return Measurement(f"cut at {start}", 1.0 / FS, {k: v[start:start + n].copy() for k, v in stream.items()})


@pytest.mark.parametrize("offset_s", [0.0004, 0.03, 0.12])
def test_a_recording_cut_from_a_running_drive_is_simulated_with_its_pulse_train(model, stream, offset_s):
    """Cut 0.4 ms and 30 ms after a pulse's start (a pulse on at the first sample: a watch snapshot starts ~there)
    and 120 ms after it (none on): the model under the recovered conditions is the recording, sample by sample (rms
    error under 5 % of each signal's spread; measured 0.1-2 %: an impact a sample apart is the largest part of
    a1's. Without the lead the first two were 47-95 %)."""
    start = int(round((0.05 + 4 * 0.25 + offset_s) * FS))
    meas = _cut(stream, start)
    cond = analysis.recover_conditions(meas, model)
    first = cond["pulse_load.first_s"] * FS
    assert first == pytest.approx((PERIOD - offset_s * FS) % PERIOD, abs=8)
    runs = plant_adapter.simulate_sets(model, [{}], [0], meas.n_samples, conditions=cond, noise=False, signals=SIGNALS)
    for s in ("a1", "a2", "omega1"):
        err = np.sqrt(np.mean((runs[s][0, 0] - meas.signals[s]) ** 2)) / meas.signals[s].std()
        assert err < 0.05, (s, err)


def test_without_the_lead_a_pulse_on_at_the_first_sample_would_be_lost(model, stream, monkeypatch):
    """The same cut 0.4 ms after a pulse's start without pulse_lead_samples: the model drops that pulse and its motor
    runs off -- the reason for the lead."""
    start = int(round((0.05 + 4 * 0.25 + 0.0004) * FS))
    meas = _cut(stream, start)
    cond = analysis.recover_conditions(meas, model)
    monkeypatch.setattr(plant_adapter, "pulse_lead_samples", lambda cfg: 0)
    runs = plant_adapter.simulate_sets(model, [{}], [0], meas.n_samples, conditions=cond, noise=False, signals=SIGNALS)
    w = meas.signals["omega1"]
    err = np.sqrt(np.mean((runs["omega1"][0, 0] - w) ** 2)) / w.std()
    assert err > 0.3, err
