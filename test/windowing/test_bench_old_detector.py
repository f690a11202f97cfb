"""bench/detector.py times the current onset detector against a frozen copy of the old one
(bench/_detector/reference_detector.py), both inside the offline chain. The chain calls the detector it
is given with the current detector's keywords, so the old copy must take every one of them: when the
chain began passing ``finite=True`` the bench stopped running and no test saw it."""
import importlib.util
import inspect
import sys

from backlash_monitor.windowing import BacklashEntryDetector

from conftest import REPO_ROOT


def _old_detector_class():
    path = REPO_ROOT / "bench" / "_detector" / "reference_detector.py"
    spec = importlib.util.spec_from_file_location("bench_old_reference_detector", path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module          # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module.BacklashEntryDetector


def test_the_benchs_old_detector_takes_every_argument_the_chain_can_pass():
    old = _old_detector_class()
    for method in ("feed", "__init__"):
        current = inspect.signature(getattr(BacklashEntryDetector, method)).parameters
        frozen = inspect.signature(getattr(old, method)).parameters
        assert set(current) <= set(frozen), (method, sorted(set(current) - set(frozen)))
