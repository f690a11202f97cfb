"""Start-up cost of one drive's monitor: import time of each node module (fresh interpreter,
median of N runs), which heavy libraries the import loads, and the resident memory of a running
`chain` process (the three nodes of one drive in one process) once it is up.

    python bench/_fleet/startup.py [--runs 5]     # prints one JSON object
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

MODULES = ("backlash_monitor.nodes.classifier", "backlash_monitor.nodes.windowing",
           "backlash_monitor.nodes.denoise", "backlash_monitor.nodes.chain_container")
HEAVY = ("numba", "scipy", "matplotlib", "llvmlite")

PROBE = """
import sys, time
t = time.perf_counter()
import {module}
dt = time.perf_counter() - t
import json
print(json.dumps({{"s": dt, "heavy": sorted(m for m in {heavy!r} if m in sys.modules)}}))
"""


def import_cost(module: str, runs: int) -> dict:
    times, heavy = [], []
    for _ in range(runs):
        out = subprocess.run([sys.executable, "-c", PROBE.format(module=module, heavy=HEAVY)],
                             capture_output=True, text=True, check=True).stdout
        result = json.loads(out.strip().splitlines()[-1])
        times.append(result["s"])
        heavy = result["heavy"]
    return {"import_s_median": round(statistics.median(times), 3), "loads": heavy}


def rss_mb(pid: int) -> float:
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


def chain_start(timeout_s: float = 60.0) -> dict:
    """Start the `chain` executable; time until its classifier logs that it is up; RSS then."""
    from ament_index_python.packages import get_package_prefix
    exe = os.path.join(get_package_prefix("backlash_monitor"), "lib", "backlash_monitor", "chain")
    env = dict(os.environ, PYTHONUNBUFFERED="1", RCUTILS_LOGGING_BUFFERED_STREAM="0")
    t0 = time.perf_counter()
    child = subprocess.Popen([exe, "--ros-args", "-p", "qos:=reliable"], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    up_s = None
    try:
        for line in child.stdout:
            if "windowing" in line and "trigger" in line:   # the last node built logs this
                up_s = time.perf_counter() - t0
                break
            if time.perf_counter() - t0 > timeout_s:
                break
        time.sleep(1.0)
        rss = rss_mb(child.pid)
    finally:
        child.terminate()
        child.wait(timeout=10)
    return {"chain_up_s": None if up_s is None else round(up_s, 2), "chain_rss_mb": round(rss, 1)}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--runs", type=int, default=5)
    args = parser.parse_args()
    os.environ.setdefault("ROS_AUTOMATIC_DISCOVERY_RANGE", "LOCALHOST")
    result = {m.rsplit(".", 1)[1]: import_cost(m, args.runs) for m in MODULES}
    result.update(chain_start())
    print(json.dumps(result))


if __name__ == "__main__":
    main()
