"""Shared fixtures. Every test process keeps DDS on loopback and on a domain of its own."""
import itertools
import os
import pathlib
import sys

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

_domain_ids = itertools.count(int(os.environ["ROS_DOMAIN_ID"]))


def fresh_domain_id() -> int:
    """A domain ID for one test's processes, distinct from the other tests of this run (1..101)."""
    return (next(_domain_ids) % 101) + 1


@pytest.fixture
def ros_env():
    """Environment for child processes that use DDS: loopback only, a domain of this test's own."""
    env = dict(os.environ)
    env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = "LOCALHOST"
    env["ROS_DOMAIN_ID"] = str(fresh_domain_id())
    env["PYTHONUNBUFFERED"] = "1"
    return env


@pytest.fixture
def repo_root():
    return REPO_ROOT


@pytest.fixture(autouse=True)
def _effects_registry_isolated():
    """Effects a test registers (plug-in files, broken terms) stay with that test: the registry is
    process-wide, and the workbench switches on every registered effect."""
    import sys
    effects = sys.modules.get("backlash_monitor.plant.effects")
    saved = dict(effects._REGISTRY) if effects is not None else None
    yield
    effects = sys.modules.get("backlash_monitor.plant.effects")
    if effects is not None and saved is not None:
        effects._REGISTRY.clear()
        effects._REGISTRY.update(saved)
