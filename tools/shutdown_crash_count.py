"""Count how a node process ends on a signal, for one or more source trees run alternately.

    python tools/shutdown_crash_count.py [--scenario record|idle|idle-starve] [--runs N]
                                         [--signal SIGINT|SIGTERM] TREE [TREE ...]

TREE is a repository's root (e.g. this worktree and a `git archive` of an older commit); its code
is what runs. Scenarios, N runs per tree:

- ``record``: test/bag/test_bag_record_replay.py::test_signal_closes_the_bag_properly:
  ``python -m backlash_monitor.nodes.record`` started in TREE, 1 s of the five plant topics at x2
  from bench/bags.py, 0.3 s, then the signal; also counts the bags that are complete with every
  published message;
- ``idle``: an idle node on TREE's process shell (test/shutdown_probe.py), the signal once it
  spins;
- ``idle-starve``: the same with rclpy's signal thread held off the CPU (``--starve``).

Runs of the trees alternate, so that the load of the shared machine falls on them alike. Prints
one JSON object: per tree, the exit codes counted (-11 is SIGSEGV) (docs/graph.md "Shutdown").
DDS stays on loopback, on the shell's ROS_DOMAIN_ID (env.sh gives each shell its own); the runs
are one after the other.
"""
from __future__ import annotations

import argparse
import collections
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]


def one_record_run(tree: Path, out: Path, env: dict, sig: signal.Signals) -> tuple[int, bool]:
    """The recorder's exit code, and whether its bag is complete with every published message."""
    rec = subprocess.Popen(
        [sys.executable, "-m", "backlash_monitor.nodes.record", "--ros-args",
         "-p", f"output:={out}", "-p", "discovery_period_s:=0.05", "-p", "topics:=plant/*",
         "-p", "chunk_duration_s:=0.2"],
        env=env, cwd=tree, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    published = None
    try:
        pub = subprocess.run(
            [sys.executable, str(REPO / "bench" / "bags.py"), "--role", "publish",
             "--seconds", "1.0", "--factor", "2.0"],
            env=env, cwd=REPO, capture_output=True, text=True, timeout=120)
        if pub.returncode == 0:
            published = json.loads(pub.stdout.strip().splitlines()[-1])["published"]
        time.sleep(0.3)
    finally:
        if rec.poll() is None:
            rec.send_signal(sig)
        try:
            rec.wait(timeout=30)
        except subprocess.TimeoutExpired:
            rec.kill()
            rec.wait()
    from backlash_monitor.bag import BagError, BagReader
    try:
        with BagReader(out) as bag:    # strict: footer and summary present
            complete = bag.recovery.complete and published is not None and \
                {t: i.count for t, i in bag.topics.items()} == published
    except (BagError, OSError):
        complete = False
    return rec.returncode, complete


def one_idle_run(tree: Path, env: dict, sig: signal.Signals, starve: bool) -> int:
    """The exit code of test/shutdown_probe.py's idle node on TREE's code, signalled once it spins."""
    env = dict(env, PYTHONPATH=os.pathsep.join([str(tree), env.get("PYTHONPATH", "")]))
    probe = subprocess.Popen(
        [sys.executable, str(REPO / "test" / "shutdown_probe.py"), *(["--starve"] if starve else []),
         "idle"], env=env, cwd=tree, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    for line in probe.stdout:
        if line.strip() == "READY":
            probe.send_signal(sig)
            break
    try:
        probe.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        probe.kill()
        probe.communicate()
    return probe.returncode


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("trees", nargs="+", type=Path, help="source trees (a repository's root)")
    ap.add_argument("--runs", type=int, default=40, help="runs per tree (default 40)")
    ap.add_argument("--signal", default="SIGINT", choices=["SIGINT", "SIGTERM"])
    ap.add_argument("--scenario", default="record", choices=["record", "idle", "idle-starve"])
    a = ap.parse_args(argv)
    sig = signal.Signals[a.signal]
    trees = [t.resolve() for t in a.trees]
    codes = {str(t): collections.Counter() for t in trees}
    complete = {str(t): 0 for t in trees}
    started = time.monotonic()
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(a.runs):
            for j, tree in enumerate(trees):
                env = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST",
                           PYTHONUNBUFFERED="1")
                if a.scenario == "record":
                    out = Path(tmp) / f"rec_{i}_{j}.mcap"
                    rc, ok = one_record_run(tree, out, env, sig)
                    out.unlink(missing_ok=True)
                else:
                    rc, ok = one_idle_run(tree, env, sig, a.scenario == "idle-starve"), None
                codes[str(tree)][rc] += 1
                complete[str(tree)] += bool(ok)
                print(f"run {i + 1}/{a.runs} {tree}: exit {rc}"
                      + ("" if ok is None else f", bag complete {ok}"),
                      file=sys.stderr, flush=True)
    print(json.dumps({"scenario": a.scenario, "signal": a.signal, "runs_per_tree": a.runs,
                      "wall_s": round(time.monotonic() - started, 1),
                      "trees": {t: {"exit_codes": {str(k): v for k, v in sorted(codes[t].items())},
                                    "sigsegv": codes[t][-11],
                                    **({"bags_complete": complete[t]} if a.scenario == "record"
                                       else {})} for t in codes}}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
