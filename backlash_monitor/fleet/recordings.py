"""Simulated recordings of several drives at several times (no rclpy): what `analyze FOLDER` takes,
for the fleet tests and bench/fleet.py (each bag as a live recording of that drive would be)."""
from __future__ import annotations

from pathlib import Path

from backlash_monitor.bag.simulated import SimulationBagWriter
from backlash_monitor.plant import PlantSimulator, Scenario
from backlash_monitor.signals import SIGNAL_UNITS

DAY_NS = 86400 * 10**9
T0_NS = 1_760_000_000 * 10**9


def write_fleet_bags(directory, recordings, duration_s: float = 1.0) -> list[Path]:
    """``recordings``: [(drive, day, width_m, seed)]; one bag each, stamped T0 + day days.
    The drives are simulated together in one batch (one lane each)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    sim = PlantSimulator([Scenario(width_m=w, eta_k=0.025, n1=0.89, seed=s)
                          for _, _, w, s in recordings], outputs=tuple(SIGNAL_UNITS))
    paths = [directory / f"{drive.replace('/', '_')}_day{day:03d}.mcap"
             for drive, day, _, _ in recordings]
    writers = [SimulationBagWriter(p, drive_name=drive, true_width_m=w,
                                   start_time_ns=T0_NS + int(day * DAY_NS))
               for p, (drive, day, w, _) in zip(paths, recordings)]
    n_total = int(round(duration_s / sim.sample_period_s))
    done = 0
    while done < n_total:
        chunk = sim.run(min(1000, n_total - done))
        for lane, writer in enumerate(writers):
            writer.write_chunk(chunk.first_sample_index, chunk.sample_period_s,
                               {n: getattr(chunk, n)[lane] for n in SIGNAL_UNITS})
        done += chunk.a1.shape[1]
    for writer in writers:
        writer.close()
    return paths
