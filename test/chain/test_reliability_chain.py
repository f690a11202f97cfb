"""The chain end to end on the simulated plant with input faults in the stream: a NaN chunk, a lost
chunk and a drive restart (the index back to 0). Every fault is counted with its reason, and after
each the windows come again: the same windows as in the clean stream (the detector re-arms on the
next settled contact), denoised and classified with the width the clean stream gives."""
import numpy as np
import pytest

from backlash_monitor.chain.joiner import ChunkJoiner

from backlash_monitor.chain.stage import WindowingStage

from backlash_monitor.denoise import denoise_checked
from backlash_monitor.classifier.patterns import load_library
from backlash_monitor.estimation import DriveEstimator
from backlash_monitor.plant import PlantSimulator, Scenario

CHUNK = 1000
SIGNALS = ("a1", "a2", "angle_difference")


@pytest.fixture(scope="module")
def record():
    chunk = PlantSimulator([Scenario(width_m=0.005, seed=3)]).run(int(3.0 * 50000))
    return {name: getattr(chunk, name)[0] for name in SIGNALS}


def run(record, faults):
    """Feeds the record chunk by chunk; faults: {chunk number: 'nan' | 'lose' | 'restart'}.
    Returns (stage, [(data position of the entry, window)], estimates by data position)."""
    stage = WindowingStage()
    joiner = ChunkJoiner(stage.input_signals, faults=stage.faults)
    estimator = DriveEstimator(load_library(), mode="shape")
    shift, out, estimates = 0, [], {}
    n = record["a1"].size
    for i, lo in enumerate(range(0, n, CHUNK)):
        fault = faults.get(i)
        if fault == "lose":
            continue
        if fault == "restart":
            shift = -lo
        arrays = {s: record[s][lo:lo + CHUNK].copy() for s in SIGNALS}
        if fault == "nan":
            arrays["angle_difference"][17] = np.nan
        for s in ("angle_difference", "a2", "a1"):
            joined = joiner.add(s, lo + shift, 2e-5, arrays[s])
            if joined is None:
                continue
            windows, _ = stage.feed(joined)
            for w in windows:
                position = w.entry_sample_index - shift      # where in the record
                out.append((position, w))
                clean, reason = denoise_checked(w.signals["a1"], w.signals["a2"])
                assert reason is None
                est = estimator.estimate(*clean, w.kind, w.sample_period_s)
                if est:
                    estimates[position] = {e.signal_name: e.width_m for e in est}
    return stage, out, estimates


def test_faults_in_a_plant_stream_are_counted_and_the_chain_resumes_as_if_clean(record):
    _, clean, clean_est = run(record, {})
    stage, faulty, faulty_est = run(record, {30: "nan", 60: "lose", 90: "restart"})
    assert stage.faults.counts["non_finite_samples"] == 1
    assert stage.faults.counts["gap"] == 1
    assert stage.faults.counts["stream_restart"] == 1
    assert stage.lost_samples == 2 * CHUNK
    clean_pos = {p for p, _ in clean}
    faulty_pos = {p for p, _ in faulty}
    # no window of an event the clean stream does not have; right after a restart the detector
    # has less history for its departure fit: the entry may move within its scatter (std ~21
    # samples, docs/windowing.md; here 7)
    for p in faulty_pos:
        assert min(abs(p - q) for q in clean_pos) <= 30, p
    # after each fault, the windows from the next-but-one onward are the clean stream's, sample
    # for sample (the first one may be lost while the detector re-arms)
    for start, end in ((31, 60), (61, 90), (91, 150)):
        expected = sorted(p for p in clean_pos if start * CHUNK + 12000 <= p < end * CHUNK - 2500)
        assert expected, (start, end)
        assert set(expected) <= faulty_pos, (start, sorted(faulty_pos))
    windows = dict(faulty)
    same = [p for p, _ in clean if p in windows]
    assert len(same) >= len(faulty_pos) - 3
    for p, w in clean:
        if p in windows:
            assert np.array_equal(w.signals["a1"], windows[p].signals["a1"])
    # and they are classified, with the clean stream's per-window widths
    after_restart = [p for p in faulty_est if p >= 91 * CHUNK]
    assert len(after_restart) >= 4
    for p in after_restart:
        assert faulty_est[p] == clean_est[p]
