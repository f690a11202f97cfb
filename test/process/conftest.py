"""The process tests' machine: idle, or every core kept busy by a CPU hog (issue 34)."""
import pytest

from process_fault_helpers import CpuHog

# A hog that nobody stops still ends after this long [s]: longer than any one process test under
# load, short enough that a killed pytest leaves no busy loop behind for long.
HOG_MAX_S = 600.0


@pytest.fixture(params=["idle", "hog"])
def machine_load(request):
    """'idle', or 'hog': one busy loop per core at normal priority beside the test, killed when
    the test ends (passed, failed or interrupted)."""
    if request.param == "idle":
        yield "idle"
        return
    with CpuHog(max_s=HOG_MAX_S):
        yield "hog"
