"""The monitor's width against constant accelerometer offsets (issue 20, item 4; docs/windowing.md
"Sensor offsets").

From physics: the offsets are built into the recording by the plant's own ``accelerometer_bias``
effect (a -> a + b on the published samples) on the same scenario and noise as the clean recording,
and the chain runs as ``analyze`` runs it. An acceleration's mean over a stretch is the speed change
over the stretch's length plus the offset; the estimate over whole load periods is checked against
exactly that (the motor speed is in the simulation)."""
import math
import os
import subprocess
import sys

import numpy as np
import pytest

from backlash_monitor.chain.joiner import JoinedRange

from backlash_monitor.chain.record import estimate_record

from backlash_monitor.chain.stage import WindowingStage
from backlash_monitor.classifier.patterns import load_library
from backlash_monitor.estimation import OFFSET_UNKNOWN, DriveEstimator
from backlash_monitor.plant import PlantSimulator, Scenario, load_plant_config
from backlash_monitor.windowing import DEFAULTS, WindowCapture
from backlash_monitor.windowing.offset import SensorOffsetEstimator

SEED = 4711                       # no other test or bench uses it
RADIUS_M = 0.15                   # drive-wheel radius r (SPEC 3): a1 = r dOmega1/dt
# (a1 offset, a2 offset) [m/s^2]: none, beyond a MEMS sensor's range on each, both at once
BIASES = ((0.0, 0.0), (4.0, 0.0), (0.0, -1.5), (-3.0, 1.8))


@pytest.fixture(scope="module")
def records():
    """One 9 mm drive (eta_k 0.0375, n1 0.89) 4.5 s, once per BIASES entry, same noise."""
    config = load_plant_config().with_overrides({"effects.accelerometer_bias": True})
    scenarios = [Scenario(width_m=0.009, eta_k=0.0375, n1=0.89, seed=SEED) for _ in BIASES]
    sim = PlantSimulator(scenarios, config=config, noise=True,
                         parameters={"accelerometer_bias.a1_m_s2": np.array([b[0] for b in BIASES]),
                                     "accelerometer_bias.a2_m_s2": np.array([b[1] for b in BIASES])},
                         outputs=("a1", "a2", "omega1", "angle_difference"))
    chunk = sim.run(int(4.5 / sim.sample_period_s))
    return [{s: np.ascontiguousarray(getattr(chunk, s)[i]) for s in ("a1", "a2", "omega1", "angle_difference")}
            for i in range(len(BIASES))], chunk.sample_period_s


@pytest.fixture(scope="module")
def library():
    return load_library(None, trigger="contact_loss")


def _widths(record, period, library):
    """Per classified onset window (entry index): (continuous, fused continuous, fused events) of a1+a2,
    and every window with its estimates."""
    estimator = DriveEstimator(library)
    out = estimate_record({k: record[k] for k in ("a1", "a2", "angle_difference")}, period, estimator)
    widths = {w.entry_sample_index: (e.continuous_width_m, e.fused_continuous_width_m, e.fused_events)
              for w, estimates in out for e in estimates if e.signal_name == "a1+a2"}
    return widths, out, estimator


def test_the_width_does_not_move_with_a_constant_offset_on_either_signal(records, library):
    recs, period = records
    clean, _, _ = _widths(recs[0], period, library)
    assert len(clean) >= 16 and max(n for _, _, n in clean.values()) == 8
    for bias, rec in zip(BIASES[1:], recs[1:]):
        biased, _, _ = _widths(rec, period, library)
        assert biased.keys() == clean.keys(), bias          # the same onset windows classified
        for entry, (w, fused, events) in clean.items():
            bw, bfused, bevents = biased[entry]
            assert bevents == events
            # exact but for rounding: (a + b) - (estimate + b) against a - estimate
            assert abs(bw - w) < 1e-9 and abs(bfused - fused) < 1e-9, (bias, entry, w, bw)
    # and the width is right: the drive's published fused continuous width at the end
    assert abs(list(clean.values())[-1][1] - 0.009) < 0.15e-3


def test_the_offset_estimate_is_the_offset_plus_the_speed_change_over_the_periods(records, library):
    """mean(a1) over [s, e) = r (Omega1(e) - Omega1(s)) / T + b: the estimate over whole load periods
    minus the speed term is the offset; the speed term itself is small (the speed returns)."""
    recs, period = records
    _, clean_windows, _ = _widths(recs[0], period, library)
    onset_ends = [w.end_sample_index for w, _ in clean_windows if w.kind == "onset"]
    periods = DEFAULTS["sensor_offset"]["periods"]
    for bias, rec in zip(BIASES, recs):
        _, windows, estimator = _widths(rec, period, library)
        onsets = [w for w, _ in windows if w.kind == "onset"]
        assert onsets[0].offset_periods == 0 and math.isnan(onsets[0].sensor_offsets["a1"])
        assert estimator.waiting_for_offset == 1 and estimator.faults.total == 0
        for k, w in enumerate(onsets[1:], start=1):
            m = min(k, periods)
            assert w.offset_periods == m
            start, end = onset_ends[k - m], onset_ends[k]
            omega1 = rec["omega1"]
            speed_term = RADIUS_M * (omega1[end] - omega1[start]) / ((end - start) * period)
            # the sample mean of the derivative is a Riemann sum of its integral (the speed change):
            # they differ by up to 0.008 m/s^2 over one period here, by less over more
            assert w.sensor_offsets["a1"] - speed_term == pytest.approx(bias[0], abs=0.015 / m), (bias, k)
            # the speed term is what the estimate gets wrong: small over whole periods
            assert abs(speed_term) < 0.5 / m
            # a2: no mass-speed sensor; the same physics bounds the error (measured std 0.065/m)
            assert w.sensor_offsets["a2"] == pytest.approx(bias[1], abs=0.35 / m), (bias, k)


def test_offsets_cancel_exactly_in_the_estimate(records, library):
    """The estimate is linear with weights summing to one: biased - clean = the bias, window by window."""
    recs, period = records
    _, clean, _ = _widths(recs[0], period, library)
    for bias, rec in zip(BIASES[1:], recs[1:]):
        _, biased, _ = _widths(rec, period, library)
        for (w0, _), (w1, _) in zip(clean, biased):
            if w0.offset_periods:
                assert w1.sensor_offsets["a1"] - w0.sensor_offsets["a1"] == pytest.approx(bias[0], abs=1e-12)
                assert w1.sensor_offsets["a2"] - w0.sensor_offsets["a2"] == pytest.approx(bias[1], abs=1e-12)


def test_a_window_without_an_offset_estimate_is_not_classified_and_is_no_fault(library):
    estimator = DriveEstimator(library)
    window = np.zeros(2048)
    assert estimator.estimate(window, window, "onset", 2e-5, sensor_offsets=(math.nan, 0.0)) == []
    assert estimator.last_reasons == [OFFSET_UNKNOWN]
    assert estimator.waiting_for_offset == 1 and estimator.faults.total == 0
    assert all(len(f) == 0 for f in estimator.fusion.values())
    # a return window is not classified anyway: not counted as waiting
    assert estimator.estimate(window, window, "return", 2e-5, sensor_offsets=(math.nan, math.nan)) == []
    assert estimator.waiting_for_offset == 1


def test_a_library_trained_without_offset_removal_is_refused(library):
    old = type(library)(**{**library.__dict__, "settings": {k: v for k, v in library.settings.items()
                                                           if k != "sensor_offset"}})
    with pytest.raises(ValueError, match="without the sensor offset removed.*retrain"):
        DriveEstimator(old)


def _periodic(n, period, bias, amplitude=30.0):
    """A signal whose true part averages to zero over every whole period, plus a constant offset."""
    k = np.arange(n)
    return bias + amplitude * np.sin(2 * np.pi * k / period) + 5.0 * np.sin(6 * np.pi * k / period)


def test_a_gap_drops_the_period_under_way_and_keeps_the_closed_ones():
    """Synthetic stream, onset windows once per 'load period' of 5000 samples: the estimate is the
    offset; a gap discards the windows spanning it and the period under way, the closed periods stay,
    and the count of periods grows again from the next onset pair."""
    period, n, bias = 5000, 60_000, 1.25
    a1, a2 = _periodic(n, period, bias), _periodic(n, period, -0.5, 2.0)
    capture = WindowCapture(window_length=2048, signals=("a1", "a2"), window_offset_samples=0)
    from backlash_monitor.windowing import BacklashEntry
    entries = [BacklashEntry(j * period + 700, "onset", "contact_loss", j * period + 700) for j in range(12)]
    got = []
    gap = (31_000, 32_000)                      # lost samples: inside the 7th onset's window
    for lo in range(0, n, 1000):
        if gap[0] <= lo < gap[1]:
            continue
        hi = lo + 1000
        new = [e for e in entries if lo <= e.sample_index < hi]
        windows, _ = capture.feed(lo, {"a1": a1[lo:hi], "a2": a2[lo:hi]}, entries=new)
        got += windows
    periods = [w.offset_periods for w in got]
    assert periods[0] == 0
    # the 7th window (spanning the gap) is discarded; the one after it keeps the closed periods,
    # and the period across the gap is never closed
    assert len(got) == len(entries) - 1
    assert periods == [0, 1, 2, 3, 4, 5, 5, 6, 7, 8, 8]
    for w in got[1:]:
        assert w.sensor_offsets["a1"] == pytest.approx(bias, abs=1e-9)
        assert w.sensor_offsets["a2"] == pytest.approx(-0.5, abs=1e-9)


def test_the_estimator_is_chunk_invariant_bit_for_bit():
    rng = np.random.default_rng(3)
    n, period = 40_000, 4000
    x = {"a1": _periodic(n, period, 0.3) + rng.normal(0, 3, n), "a2": _periodic(n, period, -0.1, 1.0)}
    ends = list(range(3100, n, period))

    def run(sizes):
        est = SensorOffsetEstimator(("a1", "a2"), periods=4)
        out, lo, i = [], 0, 0
        while lo < n:
            hi = min(n, lo + sizes[i % len(sizes)])
            est.feed(lo, {s: x[s][lo:hi] for s in x})
            for e in [e for e in ends if lo < e <= hi]:
                b = est.block_start(e)
                est.close_period(e, {s: float(np.sum(x[s][b:e])) for s in x})
                out.append(est.estimate())
            lo, i = hi, i + 1
        return out

    ref = run([n])
    assert ref[-1][1] == 4 and ref[-1][0]["a1"] == pytest.approx(0.3, abs=0.05)
    for sizes in ([1000], [7, 999, 4096, 1], [63, 65, 64]):
        assert run(sizes) == ref, sizes


def test_windowing_stage_windows_carry_offsets_the_classifier_removes(records, library):
    """The live path (WindowingStage, range by range) gives the windows the offsets estimate_record
    gives, and the classifier node's message fields carry them (checked in test_node_classifier)."""
    recs, period = records
    rec = recs[3]
    stage = WindowingStage()
    live = []
    for lo in range(0, rec["a1"].size, 1000):
        joined = JoinedRange(lo, period, {s: rec[s][lo:lo + 1000] for s in ("a1", "a2", "angle_difference")})
        live += stage.feed(joined)[0]
    _, offline, _ = _widths(rec, period, library)
    assert [(w.entry_sample_index, w.sensor_offsets, w.offset_periods) for w in live] == \
        [(w.entry_sample_index, w.sensor_offsets, w.offset_periods) for w, _ in offline]


@pytest.fixture(scope="module")
def biased_bag(tmp_path_factory):
    """As a user makes one: a 3 s recording with a 3 m/s^2 a1 offset (beyond a MEMS sensor's +-2)."""
    rec = tmp_path_factory.mktemp("biased") / "rec"
    sim = subprocess.run([sys.executable, "-m", "backlash_monitor", "simulate", "--widths", "0.0075",
                          "--seeds", str(SEED), "--duration", "3", "--no-npz", "--mcap", str(rec),
                          "--set", "effects.accelerometer_bias=true", "--set", "accelerometer_bias.a1_m_s2=3"],
                         env=dict(os.environ), capture_output=True, text=True, timeout=300)   # no DDS
    assert sim.returncode == 0, sim.stderr
    return next(rec.glob("*.mcap"))


@pytest.mark.process
@pytest.mark.ros
def test_fleet_analyze_lists_the_offsets_and_warns_for_the_bag(biased_bag, tmp_path, ros_env):
    """The offsets are the windowing's, not the model fit's (--no-model-fit: the fit would build the default model's
    watch reference at 7.5 mm, ~60 s of CPU that no other test needs; test/watch/test_folder_model_fit.py tests it)."""
    out = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(biased_bag.parent),
                          "--out", str(tmp_path / "fleet"), "--jobs", "1", "--no-plots", "--no-model-fit"],
                         env=dict(ros_env), capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr
    assert f"{biased_bag.name}: WARN: sensor offset a1 +" in out.stdout, out.stdout
    import csv
    with open(tmp_path / "fleet" / "fleet.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert float(rows[0]["a1_offset_m_s2"]) == pytest.approx(3.0, abs=0.1)
    assert abs(float(rows[0]["a2_offset_m_s2"])) < 0.1


@pytest.mark.process
@pytest.mark.ros
def test_analyze_reports_the_offsets_and_warns_beyond_the_plausible_range(biased_bag, tmp_path, ros_env):
    env = dict(ros_env)
    bag = biased_bag
    # --no-model-fit: as the folder's test above (the default model's reference at 7.5 mm: ~48 s of CPU, measured)
    out = subprocess.run([sys.executable, "-m", "backlash_monitor", "analyze", str(bag), "--out",
                          str(tmp_path / "est"), "--no-model-fit"], env=env, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    import re
    warned = re.search(r"WARN: sensor offset a1 ([+-][0-9.]+) m/s\^2 is beyond \+-2 m/s\^2", out.stdout)
    assert warned and float(warned.group(1)) == pytest.approx(3.0, abs=0.1), out.stdout
    assert "WARN: sensor offset a2" not in out.stdout
    import json
    result = json.loads((tmp_path / "est.json").read_text())
    info = result["sensor_offsets"]
    assert info["a1_m_s2"] == pytest.approx(3.0, abs=0.1) and info["periods"] == 8
    assert abs(info["a2_m_s2"]) < 0.1 and list(info["implausible"]) == ["a1_m_s2"]
    assert info["onset_windows_before_offset_known"] == 1
    rows = [r for r in result["estimates"] if r["signal"] == "a1+a2"]
    assert all(r["offset_periods"] >= 1 for r in rows)
    assert rows[-1]["a1_offset_m_s2"] == pytest.approx(3.0, abs=0.1)


@pytest.mark.process
@pytest.mark.ros
def test_the_windowing_node_warns_for_an_implausible_offset(records, ros_env):
    import rclpy
    os.environ["ROS_DOMAIN_ID"] = ros_env["ROS_DOMAIN_ID"]
    sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    from fuzz_nodes_checks import attach, chunk
    from backlash_monitor.nodes.windowing import WindowingNode
    recs, period = records
    rclpy.init()
    try:
        results = {}
        for label, rec in (("plausible", recs[2]), ("implausible", recs[1])):   # a2 -1.5; a1 +4.0
            node = attach(WindowingNode())
            for lo in range(0, rec["a1"].size, 5000):
                for name in ("a1", "a2", "angle_difference"):
                    node.on_chunk(name, chunk(name, lo, period, rec[name][lo:lo + 5000]))
            node.update_diagnostics(publish_now=True)
            status = node.diagnostics.publisher.messages[-1].status[0]
            values = {kv.key: kv.value for kv in status.values}
            window = node.publisher.messages[-1]
            results[label] = (status, values, window)
            node.destroy_node()
    finally:
        rclpy.try_shutdown()
    status, values, window = results["implausible"]
    assert _level(status) == 1, status.message     # WARN
    assert "sensor offset a1 +4.0" in status.message and "check the sensor" in status.message
    assert float(values["a1_offset_m_s2"]) == pytest.approx(4.0, abs=0.1)
    assert window.a1_offset_m_s2 == pytest.approx(4.0, abs=0.1) and window.offset_periods == 8
    # -1.5 m/s^2 on a2 is within a MEMS sensor's range (|b| <= 2): OK, the estimate shown
    status, values, window = results["plausible"]
    assert _level(status) == 0, status.message
    assert float(values["a2_offset_m_s2"]) == pytest.approx(-1.5, abs=0.05)
    assert "sensor offsets a1" in status.message


def _level(status) -> int:
    return status.level if isinstance(status.level, int) else ord(status.level)


def test_the_bench_figure_takes_recordings_of_another_generator(records):
    """bench/_workbench/sensor_offset.py: recordings handed in as arrays (the lead's foreign drives)
    get the offsets and gains added to their samples; the offset shift is rounding, the gain's is
    reported; a recording too short for a full fusion is an error naming it."""
    import importlib.util
    import pathlib
    path = pathlib.Path(__file__).resolve().parents[2] / "bench" / "_workbench" / "sensor_offset.py"
    spec = importlib.util.spec_from_file_location("bench_sensor_offset", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    recs, period = records
    foreign = {"name": "foreign 9 mm", "sample_period_s": period, "true_width_m": 0.009,
               "signals": {k: recs[0][k] for k in ("a1", "a2", "angle_difference")}}
    result = module.measure(own=False, extra_recordings=[foreign])
    assert result["recordings"] == 1 and result["per_recording"][0]["source"] == "extra"
    assert result["sensor_offset_width_shift_mm"] < 1e-6
    assert 0.0 < result["sensor_gain_width_shift_mm"] < 2.0
    estimated = result["per_recording"][0]["estimated_offsets_m_s2"]
    assert estimated["a1 offset +5"] == pytest.approx(5.0, abs=0.1)
    assert estimated["a2 offset -2"] == pytest.approx(-2.0, abs=0.1)
    short = {**foreign, "signals": {k: v[:50_000] for k, v in foreign["signals"].items()}}
    with pytest.raises(ValueError, match="'foreign 9 mm': no onset window with a full fusion"):
        module.measure(own=False, extra_recordings=[short])
