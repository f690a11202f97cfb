"""What `analyze FOLDER` costs before its first bag, and what its forked workers inherit.

- The command's arguments are parsed without importing numpy: its thread pools are limited to one
  thread per worker (fleet/folder_analysis.limit_threads) before numpy's import, so the pool forks workers that
  inherit this process's modules and library; otherwise it falls back to a forkserver, whose workers
  import and load everything again (what a many-bag run did before this test: 0.1 s a worker, and the
  fork path never taken).
- The model-fit column's path (the watch's evaluation of a recording) imports neither scipy.stats (1 s
  of one core) nor scipy.signal (0.35 s) nor the simulator's numba: a fixed cost per process, paid by
  every worker, that the parallel speed-up cannot hide (docs/fleet.md "analyze FOLDER").
"""
import os
import subprocess
import sys

import pytest

ENV = dict(os.environ, ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST", ROS_DOMAIN_ID="42")


def _run(code: str) -> str:
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, env=ENV)
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout.strip()


def test_parsing_analyze_imports_no_numpy_so_the_threads_are_limited_first(tmp_path):
    out = _run(
        "import sys\n"
        "from backlash_monitor.__main__ import build_parser\n"
        f"args = build_parser('analyze').parse_args(['analyze', {str(tmp_path)!r}, '--jobs', '2'])\n"
        "from backlash_monitor.commands.analyze import fleet_options_from_args\n"
        "from backlash_monitor.fleet.folder_analysis import limit_threads, runs_parallel_here\n"
        "fleet = fleet_options_from_args(args)\n"
        "print('numpy' in sys.modules, runs_parallel_here(fleet))\n"
        "first = limit_threads()\n"
        "from backlash_monitor.commands.analyze import options_from_args\n"
        "options_from_args(args)\n"
        "import os\n"
        "print(first, 'numpy' in sys.modules, limit_threads(), os.environ['OPENBLAS_NUM_THREADS'])\n")
    before, after = out.splitlines()
    assert before == "False True"           # parsed, numpy not imported yet: the limits can still take effect
    # limit_threads answers as at its first call (before numpy) once the options have imported numpy
    assert after == "True True True 1"


def test_one_worker_or_dask_is_not_a_local_pool():
    from backlash_monitor.fleet.folder_analysis import FleetOptions, runs_parallel_here
    assert runs_parallel_here(FleetOptions(bags="x", jobs=2))
    assert not runs_parallel_here(FleetOptions(bags="x", jobs=1))
    assert not runs_parallel_here(FleetOptions(bags="x", jobs=2, engine="dask"))


@pytest.mark.parametrize("heavy", ["scipy.stats", "scipy.signal", "numba"])
def test_the_model_fit_path_does_not_import(heavy):
    out = _run(
        "import sys\n"
        "from backlash_monitor.watch.alarm import load_rule\n"
        "from backlash_monitor.watch.core import evaluate_recording\n"
        "from backlash_monitor.workbench import reference\n"
        "from backlash_monitor.workbench.measurement import load_measurement\n"
        "from backlash_monitor.workbench.analysis import welch_psd\n"
        "import numpy as np\n"
        "welch_psd(np.ones((2, 12500)), 50000.0)\n"
        "load_rule().limit('event_average', 8)\n"
        f"print({heavy!r} in sys.modules)\n")
    assert out == "False"
