"""Builders of small test bags shared by the test_bag_* tests (no rclpy needed)."""
from __future__ import annotations

import math

import numpy as np

from backlash_monitor.bag import (BACKLASH_ESTIMATE, BACKLASH_WINDOW, DIAGNOSTIC_ARRAY, SIGNAL_CHUNK,
                                  BagWriter, Codec)

T0 = 1_763_000_000_123_456_789
SIGNALS = {"a1": "m/s^2", "a2": "m/s^2", "omega1": "rad/s", "omega2": "rad/s",
           "angle_difference": "rad"}
CHUNK = 1000
PERIOD_NS = 20_000_000  # 1000 samples at 50 kHz


def signal_chunk(codec: Codec, name: str, i: int, rng) -> object:
    t = T0 + i * PERIOD_NS
    return codec.new(
        header=codec.new("std_msgs/msg/Header",
                         stamp=codec.new("builtin_interfaces/msg/Time", sec=t // 10**9,
                                         nanosec=t % 10**9),
                         frame_id="drive_ü"),
        signal_name=name, unit=SIGNALS[name], sample_period_s=2e-5,
        first_sample_index=i * CHUNK, samples=rng.standard_normal(CHUNK))


def write_sample_bag(path, n_chunks: int = 60, *, compression: str = "zstd",
                     chunk_size: int = 1 << 20, chunk_duration_s: float | None = 0.5, seed: int = 1):
    """A bag with every project topic. Returns {topic: [written messages in order]}."""
    rng = np.random.default_rng(seed)
    sig = Codec.for_type(SIGNAL_CHUNK)
    win = Codec.for_type(BACKLASH_WINDOW)
    est = Codec.for_type(BACKLASH_ESTIMATE)
    diag = Codec.for_type(DIAGNOSTIC_ARRAY)
    written: dict[str, list] = {}
    with BagWriter(path, compression=compression, chunk_size=chunk_size,
                   chunk_duration_s=chunk_duration_s) as w:
        for name in SIGNALS:
            w.add_topic(f"/plant/{name}", SIGNAL_CHUNK)
        w.add_topic("/windows/raw", BACKLASH_WINDOW)
        w.add_topic("/estimate", BACKLASH_ESTIMATE)
        w.add_topic("/diagnostics", DIAGNOSTIC_ARRAY)
        for i in range(n_chunks):
            t = T0 + i * PERIOD_NS
            for k, name in enumerate(SIGNALS):
                m = signal_chunk(sig, name, i, rng)
                w.write(f"/plant/{name}", m, log_time_ns=t + 1000 + k, publish_time_ns=t + k)
                written.setdefault(f"/plant/{name}", []).append(m)
            if i % 10 == 5:
                wm = win.new(entry_sample_index=i * CHUNK + 17, entry_kind="onset", trigger="paper",
                             sample_period_s=2e-5, denoising="", a1=rng.standard_normal(2048),
                             a2=rng.standard_normal(2048), true_width_m=float("nan"))
                w.write("/windows/raw", wm, log_time_ns=t + 5000)
                written.setdefault("/windows/raw", []).append(wm)
                em = est.new(signal_name="a1", mode="paper", entry_sample_index=i * CHUNK + 17,
                             entry_kind="onset",
                             candidate_widths_m=np.array([0.0025, 0.00375, 0.005, 0.0075, 0.009, 0.01]),
                             b_vector=np.array([]), width_index=2, width_m=0.005, b_margin=1.5,
                             continuous_width_m=math.nan, fused_width_m=0.005, fused_events=3,
                             true_width_m=0.005)
                w.write("/estimate", em, log_time_ns=t + 6000)
                written.setdefault("/estimate", []).append(em)
                dm = {"header": {"frame_id": "drive"},
                      "status": [{"level": 1, "name": "backlash_monitor: drive", "message": "ok",
                                  "hardware_id": "drive", "values": [{"key": "width_m",
                                                                      "value": "0.005"}]}]}
                w.write("/diagnostics", dm, log_time_ns=t + 7000)
                written.setdefault("/diagnostics", []).append(diag.decode(diag.encode(dm)))
    return written


def write_simulated_drive(path):
    """A 2 s project recording of one simulated 7.5 mm drive (seed 3), every stream signal: what analyze and the
    workbench read."""
    from backlash_monitor.bag.simulated import write_simulation_bag
    from backlash_monitor.plant import PlantSimulator, Scenario
    from backlash_monitor.signals import STREAM_SIGNALS

    write_simulation_bag(path, PlantSimulator([Scenario(width_m=0.0075, seed=3)], outputs=STREAM_SIGNALS), 2.0)
    return path


def analyze_outputs(result: dict) -> tuple:
    """What ``offline.bag_analysis.analyze_bag`` gave that two runs on the same samples must share: its
    result, its fault counts, the CSV, the estimates MCAP and the JSON, without the run's time and
    the bag's path."""
    import json
    result = dict(result)
    outputs = result.pop("outputs")
    result.pop("seconds")
    found = result.pop("faults")
    text = json.loads(outputs["json"].read_text())
    text.pop("seconds"), text.pop("bag")
    return (result, [f.counts for f in found], outputs["csv"].read_text(),
            outputs["mcap"].read_bytes(), text)
