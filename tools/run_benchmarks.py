"""Run every bench/*.py (each prints one JSON object) and collect them into one JSON file.

    python tools/run_benchmarks.py bench/results.json [name ...]

Benchmarks report ratios measured side by side in one run; timings on these machines are noisy.
"""
import json
import os
import pathlib
import subprocess
import sys
import time


def main(argv):
    if not argv:
        print("usage: run_benchmarks.py OUTPUT.json [name ...]", file=sys.stderr)
        return 2
    out_path = pathlib.Path(argv[0])
    wanted = set(argv[1:])
    bench_dir = pathlib.Path(__file__).resolve().parent.parent / "bench"
    # Running a subset updates those entries and keeps the others of an earlier full run, except
    # entries of benchmarks that no longer exist (a renamed bench, e.g. mcap -> bags).
    results = json.loads(out_path.read_text()) if wanted and out_path.is_file() else {}
    names = {p.stem for p in bench_dir.glob("*.py") if not p.stem.startswith("_")}
    unknown = sorted(wanted - names)
    if unknown:
        print(f"no benchmark {', '.join(unknown)}; there are: {', '.join(sorted(names))}",
              file=sys.stderr)
        return 2
    # entries of benches that are gone are dropped; a part a bench's run stored under its own key (e.g.
    # workbench_foreign: bench/workbench.py --parts foreign, hours on its own) is kept with its bench
    results = {k: v for k, v in results.items() if k in names or k.split("_", 1)[0] in names}
    failed = []
    for script in sorted(bench_dir.glob("*.py")):
        name = script.stem
        if name.startswith("_") or (wanted and name not in wanted):
            continue
        print(f"bench {name} ...", file=sys.stderr, flush=True)
        started = time.monotonic()
        proc = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                              env=dict(os.environ))
        elapsed = time.monotonic() - started
        lines = [line for line in proc.stdout.splitlines() if line.strip()]
        try:
            results[name] = json.loads(lines[-1]) if proc.returncode == 0 and lines else None
        except json.JSONDecodeError:
            results[name] = None
        if results[name] is None:
            failed.append(name)
            results[name] = {"error": f"exit {proc.returncode}", "stderr_tail": proc.stderr[-2000:]}
        print(f"bench {name}: {elapsed:.1f} s {'FAILED' if name in failed else 'ok'}",
              file=sys.stderr, flush=True)
    out_path.write_text(json.dumps(results, indent=2, sort_keys=True) + "\n")
    print(json.dumps(results, indent=2, sort_keys=True))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
