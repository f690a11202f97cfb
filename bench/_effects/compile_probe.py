"""Compile probe (run in a fresh process by bench/simulator.py): generate and compile the kernels of one
effect set in the kernel cache named by BACKLASH_MONITOR_KERNEL_CACHE, run one short step on both compiled
backends, and print one JSON line: seconds to compile (or load from numba's cache) and the vector width
found in the SIMD loop's LLVM IR (its stages are inlined there) (only when it was compiled, not loaded)."""
import json
import os
import re
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

import numpy as np  # noqa: E402, F401 (imported: the probe times numpy's import with the kernels)


def main():
    names = [n for n in sys.argv[1].split(",") if n]
    from backlash_monitor.plant import PlantSimulator, Scenario, builtin_catalogue, load_plant_config
    catalogue = builtin_catalogue().with_files(
        list(filter(None, os.environ.get("PROBE_EFFECTS_FILES", "").split(";"))))
    cfg = load_plant_config(overrides={"simulation.run_in_s": 0.0, **{f"effects.{n}": True for n in names}},
                            catalogue=catalogue)
    t0 = time.perf_counter()
    sim = PlantSimulator([Scenario(0.005)], config=cfg, noise=False, backend="numba")
    sim.run(2)
    t_simd = time.perf_counter() - t0
    t0 = time.perf_counter()
    PlantSimulator([Scenario(0.005)], config=cfg, noise=False, backend="numba-scalar").run(2)
    t_scalar = time.perf_counter() - t0
    stage = sim.kernel.module.rk4_simd
    widths = {}
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ir = stage.inspect_llvm(stage.signatures[0]) if stage.signatures else ""
    for w in (2, 4, 8):
        widths[w] = len(re.findall(rf"<{w} x double>", ir))
    print(json.dumps({"simd_s": t_simd, "scalar_s": t_scalar, "vector_ops": widths}))


if __name__ == "__main__":
    main()
