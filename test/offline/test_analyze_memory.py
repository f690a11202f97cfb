"""analyze keeps freed memory in the process (glibc mallopt): a freed and reallocated large array
no longer costs a page fault per 4 KiB page (process/memory.py)."""
import platform
import resource
import sys

import numpy as np
import pytest

from backlash_monitor.process.memory import reuse_freed_memory

glibc = sys.platform.startswith("linux") and platform.libc_ver()[0] == "glibc"


@pytest.mark.skipif(not glibc, reason="glibc's mallopt")
def test_reallocated_blocks_do_not_fault_again():
    assert reuse_freed_memory() and reuse_freed_memory()     # once, then a no-op
    for _ in range(3):                                         # warm: the heap holds the blocks
        blocks = [np.ones(1 << 17) for _ in range(4)]          # 4 x 1 MiB
        del blocks
    before = resource.getrusage(resource.RUSAGE_THREAD).ru_minflt
    for _ in range(20):
        blocks = [np.ones(1 << 17) for _ in range(4)]
        del blocks
    faults = resource.getrusage(resource.RUSAGE_THREAD).ru_minflt - before
    assert faults < 20 * 4 * 256 // 10      # without reuse: 256 faults per MiB, every time


def test_other_c_libraries_are_left_alone(monkeypatch):
    import backlash_monitor.process.memory as memory

    monkeypatch.setattr(memory, "_done", False)
    monkeypatch.setattr(memory.sys, "platform", "darwin")
    assert memory.reuse_freed_memory() is False
