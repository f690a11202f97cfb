"""Shared fixtures. Every test process keeps DDS on loopback and on a domain of its own."""
import itertools
import os
import pathlib
import resource
import sys
import time

import pytest

REPO_ROOT = pathlib.Path(__file__).resolve().parent.parent
# The tests live in folders mirroring the packages (test/bag/, test/plant/, ...); their shared helpers
# (bag_helpers, fuzz_cores, mcap_conformance, ...) stay here in test/, importable from every folder.
_TEST_DIR = str(pathlib.Path(__file__).resolve().parent)
if _TEST_DIR not in sys.path:
    sys.path.insert(0, _TEST_DIR)

# Set before any test imports rclpy: loopback discovery and a domain of this pytest run's own.
os.environ["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
os.environ.setdefault("ROS_DOMAIN_ID", str(os.getpid() % 100 + 1))
# pytest-xdist's workers (make test: `-n 2` over the tests not marked ros) inherit one ROS_DOMAIN_ID; each
# worker gwN moves to a domain block of its own, so two workers' tests never meet on a topic.
_WORKER = os.environ.get("PYTEST_XDIST_WORKER", "")
if _WORKER.startswith("gw") and _WORKER[2:].isdigit():
    os.environ["ROS_DOMAIN_ID"] = str((int(os.environ["ROS_DOMAIN_ID"]) - 1 + 25 * int(_WORKER[2:])) % 101 + 1)

_domain_ids = itertools.count(int(os.environ["ROS_DOMAIN_ID"]))


def fresh_domain_id() -> int:
    """A domain ID for one test's processes, distinct from the other tests of this run (1..101)."""
    return (next(_domain_ids) % 101) + 1


@pytest.fixture
def ros_env():
    """Environment for child processes that use DDS: loopback only, a domain of this test's own."""
    from backlash_monitor.ros.fast_dds import profile_env
    env = dict(os.environ)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env["ROS_DOMAIN_ID"] = str(fresh_domain_id())
    env["PYTHONUNBUFFERED"] = "1"
    profile_env(env)     # the project's Fast DDS profile for a test's own rclpy scripts too (ros/fast_dds.py)
    return env


@pytest.fixture
def repo_root():
    return REPO_ROOT


# A CPU hog that nobody stops still ends after this long [s]: longer than any one process test under
# load, short enough that a killed pytest leaves no busy loop behind for long.
HOG_MAX_S = 600.0


@pytest.fixture(params=["idle", "hog"])
def machine_load(request):
    """The machine a process test runs on (issue 34): 'idle', or 'hog': one busy loop per core at
    normal priority beside the test, killed when the test ends (passed, failed or interrupted)."""
    if request.param == "idle":
        yield "idle"
        return
    from process_fault_helpers import CpuHog
    with CpuHog(max_s=HOG_MAX_S):
        yield "hog"


def pytest_addoption(parser):
    parser.addoption(
        "--run-slow", action="store_true", default=False,
        help="also run the tests marked slow (whole diagnoses, the watch's references, the handoff's training: "
             "minutes of CPU). `make test` and CI pass it; without it they are skipped, so "
             "`pytest -m \"not ros and not process\"` runs the cores' other tests alone in well under a minute.")


    parser.addoption(
        "--cpu-log", default=None, metavar="FILE",
        help="append one line per test to FILE: its node id, the CPU seconds of the test process and of the child "
             "processes it waited for (setup, call and teardown), and its wall seconds -- a test's cost that does "
             "not grow with the machine's load, as --durations' wall times do --, then the peak resident memory [MB] "
             "so far of the test process and of its largest waited-for child (make test writes log/test-cpu.tsv).")


_CPU_LOG: list = []          # the --cpu-log file, absolute (a test may change the working directory)


def pytest_configure(config):
    if config.getoption("--cpu-log"):
        _CPU_LOG[:] = [os.path.abspath(config.getoption("--cpu-log"))]


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    if not _CPU_LOG:
        yield
        return
    before, wall = os.times(), time.monotonic()
    yield
    after = os.times()
    own = (after.user - before.user) + (after.system - before.system)
    children = (after.children_user - before.children_user) + (after.children_system - before.children_system)
    # and the peak resident memory so far [MB] of the test process and of its largest waited-for child: a step in
    # it names the test that raised it (a worker killed by the kernel for memory leaves no trace of its own)
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    child_peak_mb = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024.0
    line = (f"{item.nodeid}\t{own:.2f}\t{children:.2f}\t{time.monotonic() - wall:.2f}\t{peak_mb:.0f}"
            f"\t{child_peak_mb:.0f}\n")
    with open(_CPU_LOG[0], "a") as log:          # one short append per test: the xdist workers' lines do not interleave
        log.write(line)


def _slow_tests_wanted(config) -> bool:
    """--run-slow, or a marker expression that names `slow` itself (`-m slow`, `-m "slow and not ros"`)."""
    return bool(config.getoption("--run-slow")) or "slow" in (config.getoption("markexpr") or "").replace(
        "not slow", "")


def pytest_collection_modifyitems(config, items):
    _skip_slow_unless_wanted(config, items)
    _order_files_with_slow_tests_first(items)


def _skip_slow_unless_wanted(config, items) -> None:
    if _slow_tests_wanted(config):
        return
    skip = pytest.mark.skip(reason="marked slow: run with --run-slow (make test does)")
    for item in items:
        if item.get_closest_marker("slow") is not None:
            item.add_marker(skip)


def _order_files_with_slow_tests_first(items) -> None:
    """Files with the most ``slow`` tests first, each file's own order kept. pytest-xdist (make test: --dist loadfile
    --no-loadscope-reorder; by default xdist re-sorts the files by their number of tests) hands whole files to its
    workers in this order, so the long workbench files start early and do not end the run on one worker while the
    other idles; a run on one process only changes its order of files."""
    slow_per_file: dict = {}
    for item in items:
        slow_per_file.setdefault(item.path, 0)
        if item.get_closest_marker("slow") is not None:
            slow_per_file[item.path] += 1
    first_index = {}
    for i, item in enumerate(items):
        first_index.setdefault(item.path, i)
    items.sort(key=lambda item: (-slow_per_file[item.path], first_index[item.path]))
