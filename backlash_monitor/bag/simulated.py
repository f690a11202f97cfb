"""Simulated drives written straight into bags (batch mode, no DDS).

The bag has exactly what a live ``plant_simulator`` run recorded by ``record`` holds: the five
SignalChunk topics ``/plant/{a1,a2,omega1,omega2,angle_difference}`` (sensor-data QoS offered, one
message per chunk, stamped with the time of its first sample) and the latched
``/plant/true_width_m`` (std_msgs/Float64). So ``analyze``, ``replay`` and Foxglove take it as
they take a recording.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from backlash_monitor.bag.writer import BagWriter, qos_profile
from backlash_monitor.signals import SIGNAL_UNITS
SIGNAL_CHUNK = "backlash_monitor_msgs/msg/SignalChunk"
SENSOR_DATA_QOS = [qos_profile(depth=5, reliability="best_effort")]
LATCHED_QOS = [qos_profile(depth=1, durability="transient_local")]
DEFAULT_CHUNK_SAMPLES = 1000  # as the plant_simulator node publishes (20 ms at 50 kHz)


class SimulationBagWriter:
    """Writes one simulated drive's stream, chunk by chunk, into an MCAP bag."""

    def __init__(self, path, *, drive_name: str = "drive", true_width_m: float | None = None,
                 start_time_ns: int = 1_700_000_000_000_000_000, namespace: str = ""):
        self.path = Path(path)
        self.drive_name = drive_name
        self.start_time_ns = int(start_time_ns)
        ns = namespace.strip("/")
        self.prefix = f"/{ns}/plant" if ns else "/plant"
        self.writer = BagWriter(self.path)
        for name in SIGNAL_UNITS:
            self.writer.add_topic(f"{self.prefix}/{name}", SIGNAL_CHUNK,
                                  qos_profiles=SENSOR_DATA_QOS)
        if true_width_m is not None:
            self.writer.add_topic(f"{self.prefix}/true_width_m", "std_msgs/msg/Float64",
                                  qos_profiles=LATCHED_QOS)
            self.writer.write(f"{self.prefix}/true_width_m", {"data": float(true_width_m)},
                              log_time_ns=self.start_time_ns)

    def write_chunk(self, first_sample_index: int, sample_period_s: float, signals: dict) -> None:
        """One chunk: ``signals[name]`` 1-D arrays of equal length, first sample at the index."""
        stamp_ns = self.start_time_ns + int(round(first_sample_index * sample_period_s * 1e9))
        header = {"stamp": {"sec": stamp_ns // 1_000_000_000, "nanosec": stamp_ns % 1_000_000_000},
                  "frame_id": self.drive_name}
        for name, unit in SIGNAL_UNITS.items():
            self.writer.write(f"{self.prefix}/{name}", {
                "header": header, "signal_name": name, "unit": unit,
                "sample_period_s": float(sample_period_s),
                "first_sample_index": int(first_sample_index),
                "samples": np.ascontiguousarray(signals[name], dtype=np.float64)},
                log_time_ns=stamp_ns)

    def close(self) -> None:
        self.writer.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def write_simulation_bag(path, simulator, duration_s: float, scenario_index: int = 0, *,
                         chunk_samples: int = DEFAULT_CHUNK_SAMPLES, drive_name: str = "drive",
                         progress=None) -> Path:
    """Run ``simulator`` (a backlash_monitor.plant.PlantSimulator) for ``duration_s`` and write
    scenario ``scenario_index``'s stream into ``path``, chunked as the live node publishes it."""
    scenario = simulator.scenarios[scenario_index]
    n_total = int(round(duration_s / simulator.sample_period_s))
    with SimulationBagWriter(path, drive_name=drive_name, true_width_m=scenario.width_m) as bag:
        done = 0
        while done < n_total:
            n = min(chunk_samples, n_total - done)
            chunk = simulator.run(n)
            bag.write_chunk(chunk.first_sample_index, chunk.sample_period_s,
                            {name: getattr(chunk, name)[scenario_index] for name in SIGNAL_UNITS})
            done += n
            if progress is not None:
                progress(n)
    return Path(path)
