"""The saturation tests' development drives (test/windowing/test_saturation_*.py): a1 and a2, 2 s each."""
import dataclasses

import numpy as np
import pytest



def dev_drive_recordings(foreign: tuple, plant_noises=(True,)) -> dict:
    """{label: {"a1": array, "a2": array}}: clean drives of the foreign bench (another implementation than the
    plant's; development drives of bench/_reliability/saturation.py) and the plant's seed-5 drive (keyed
    ``plant_noise0/1`` by its noise), 2 s each at 50 kHz, unquantised."""
    pytest.importorskip("foreign_drives")
    plant = pytest.importorskip("backlash_monitor.plant")
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import BENCH
    out = {}
    for spec in (s for s in BENCH if s.label in foreign):
        rec = make_recording(dataclasses.replace(spec, duration_s=2.0))
        out[spec.label] = {s: np.asarray(rec.signals[s], dtype=float) for s in ("a1", "a2")}
    for noise in plant_noises:
        sim = plant.PlantSimulator([plant.Scenario(width_m=0.006, eta_k=0.03, n1=0.93, seed=5)],
                                   config=plant.load_plant_config(), noise=noise)
        chunks = [sim.run(10_000) for _ in range(10)]
        out[f"plant_noise{int(noise)}"] = {s: np.concatenate([getattr(c, s)[0] for c in chunks]) for s in ("a1", "a2")}
    return out
