"""Allocator setting for the batch commands: freed memory stays in the process for reuse.

glibc returns a freed block of 128 KiB or more to the operating system (``munmap``, or trimming
the heap top); the next array of that size then costs a page fault per 4 KiB page as it is first
written. ``analyze`` allocates such arrays all the time (a decompressed 1 MiB bag chunk, the 65536-
sample blocks of the windowing stage), so on a 10 s bag it took ~7000 page faults (~300 with this
setting), at ~3 us each on this machine (a VM): ~20 ms of a ~100 ms analysis (bench/bags.py). With
the thresholds raised, freed blocks are reused instead; memory is still freed, only kept in the
process until it exits (the command is a short-lived process), up to the trim threshold.
"""
from __future__ import annotations

import ctypes
import sys

M_TRIM_THRESHOLD = -1            # glibc mallopt parameters (malloc.h)
M_MMAP_THRESHOLD = -3
MMAP_THRESHOLD_BYTES = 32 << 20  # glibc's maximum: allocations up to it come from the heap
TRIM_THRESHOLD_BYTES = 256 << 20  # freed heap top kept for reuse up to this size

_done = False


def reuse_freed_memory() -> bool:
    """Raise glibc's mmap and trim thresholds for this process (once); False where the C library
    is not glibc (nothing changes: only slower)."""
    global _done
    if _done:
        return True
    if not sys.platform.startswith("linux"):
        return False
    try:
        mallopt = ctypes.CDLL("libc.so.6").mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    _done = bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD_BYTES)
                 and mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD_BYTES))
    return _done
