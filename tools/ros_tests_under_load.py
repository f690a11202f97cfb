"""Run the ros and process tests (make test's second part) N times in a row beside a CPU hog (issue 34).

    python tools/ros_tests_under_load.py --runs 5 --out runs.json [--stop-after-utc 23:45]

Each run is `python -m pytest test -q --run-slow -m ros` in this checkout, with one busy loop per
core at normal priority beside it (process_fault_helpers.CpuHog, started before the run and
killed after it). Writes {"runs", "passed", "results": [{"exit_code", "seconds", "failed": [...]}]}
to --out (bench/_reliability/under_load.py reads it through BENCH_ROS_TEST_RUNS_JSON) and prints
it. --stop-after-utc: start no new run after that time of day (UTC), so that a long measurement
reports the runs it finished.
"""
from __future__ import annotations

import argparse
import datetime
import json
import pathlib
import re
import subprocess
import sys
import time

REPO = pathlib.Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "test"))

from process_fault_helpers import CpuHog  # noqa: E402

FAILED = re.compile(r"^(?:FAILED|ERROR) (\S+)")


def _past(hhmm: str) -> bool:
    if not hhmm:
        return False
    now = datetime.datetime.now(datetime.timezone.utc)
    hour, minute = (int(x) for x in hhmm.split(":"))
    return (now.hour, now.minute) >= (hour, minute)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--out", required=True)
    parser.add_argument("--stop-after-utc", default="", help="HH:MM: start no run after it")
    args = parser.parse_args()
    results = []
    for k in range(args.runs):
        if _past(args.stop_after_utc):
            print(f"ros_tests_under_load: past {args.stop_after_utc} UTC, {k} runs done", file=sys.stderr)
            break
        started = time.monotonic()
        with CpuHog(max_s=3600.0):
            proc = subprocess.run([sys.executable, "-m", "pytest", "test", "-q", "--run-slow", "-m", "ros",
                                   "-p", "no:cacheprovider"], cwd=REPO, capture_output=True, text=True)
        tail = proc.stdout.strip().splitlines()[-1:] or [""]
        result = {"exit_code": proc.returncode, "seconds": round(time.monotonic() - started),
                  "failed": [m.group(1) for line in proc.stdout.splitlines() if (m := FAILED.match(line))],
                  "last_line": tail[0]}
        results.append(result)
        print(f"ros_tests_under_load: run {k + 1}: {json.dumps(result)}", file=sys.stderr, flush=True)
        with open(args.out + f".run{k + 1}.log", "w", encoding="utf-8") as f:
            f.write(proc.stdout[-200_000:] + "\n--- stderr\n" + proc.stderr[-50_000:])
        summary = {"runs": len(results), "passed": sum(r["exit_code"] == 0 for r in results),
                   "runs_asked": args.runs, "results": results}
        pathlib.Path(args.out).write_text(json.dumps(summary, indent=1))
    summary = {"runs": len(results), "passed": sum(r["exit_code"] == 0 for r in results),
               "runs_asked": args.runs, "results": results}
    pathlib.Path(args.out).write_text(json.dumps(summary, indent=1))
    print(json.dumps(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
