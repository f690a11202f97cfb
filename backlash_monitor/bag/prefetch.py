"""Chunks decompressed ahead of the reader, in a worker thread.

zstd/lz4 decompression and the CRC release the GIL (or are short): on a second core a chunk is
decompressed and checked while the caller decodes and processes the messages of the one before.
How far ahead is each reader's own setting: ``BagReader(path, chunks_ahead=N)`` makes its
ChunkPrefetcher; 0 decompresses in the caller's thread (a process with no core to spare, e.g. one
of a pool with a worker per core, where the thread would only take turns with it). The default
(None) is a thread when a core is free when the reader opens: more than one CPU, and a load
average that leaves one (:func:`default_chunks_ahead`). Nothing here is set from outside.

The worker thread is this process's one ``bag-decompress`` thread, started on first use and kept
for the next reader: a new thread per reader would cost ~2 ms a bag here (its start, and fresh
memory for its zstd context and its malloc arena, page-faulted at ~3 us per 4 KiB). A forked child
starts its own (the parent's thread is not copied by fork).
"""
from __future__ import annotations

import os
import threading
from collections import deque
from functools import partial
from concurrent.futures import ThreadPoolExecutor

DEFAULT_CHUNKS_AHEAD = 6   # ~6 MiB of decompressed chunks at the default 1 MiB chunk size
# The thread pays only with a core to run on: with every core busy it takes turns with the caller
# and the other processes, and the caller waits for the GIL whenever the thread is descheduled
# holding it. analyze of bench/bags.py's 10 s bag on this 2-core machine (medians of 12-20
# alternated rosbags/analyze pairs, the ratio with the thread against without): load average ~1.1
# 1.22 against 1.03; ~1.7 (one other busy process) 1.12 against 0.98; ~2.2 0.96 against 0.95;
# ~3 (two) 0.99 against 1.07 and 1.05 against 1.07. bench/bags.py at load 1.4-2.0 with the
# thread: 1.09-1.27 in one series, 0.995-0.998 in another; without it at 1.9-2.8: 1.007-1.055 in 7
# of 7. Between ~1.5 and 2 it depends on what the other processes do; without the thread the
# figure is steadier. So the default is no thread when the load average (1 min; it counts this
# process while it runs) is within FREE_CORE_MARGIN of the machine's CPU count.
FREE_CORE_MARGIN = 0.5      # [runnable processes]

_POOL = None
_POOL_LOCK = threading.Lock()


def _forget_pool() -> None:
    global _POOL, _POOL_LOCK
    _POOL = None                      # the parent's thread does not exist in the child
    _POOL_LOCK = threading.Lock()


os.register_at_fork(after_in_child=_forget_pool)


def _executor():
    global _POOL
    with _POOL_LOCK:
        if _POOL is None:
            _POOL = ThreadPoolExecutor(max_workers=1, thread_name_prefix="bag-decompress")
        return _POOL


def default_chunks_ahead() -> int:
    """DEFAULT_CHUNKS_AHEAD where this process may run on two CPUs or more and the machine's
    load average (1 min) is below its CPU count less FREE_CORE_MARGIN, else 0."""
    try:
        cpus = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        cpus = os.cpu_count() or 1
    if cpus <= 1:
        return 0
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # pragma: no cover - no load average
        return DEFAULT_CHUNKS_AHEAD
    return DEFAULT_CHUNKS_AHEAD if load < (os.cpu_count() or cpus) - FREE_CORE_MARGIN else 0


class ChunkPrefetcher:
    """``map(fn, items)`` yields, for each item in order, a callable returning ``fn(item)`` (or
    raising its error), ``fn`` running up to ``chunks_ahead`` items ahead in the worker thread
    (None: :func:`default_chunks_ahead`)."""

    def __init__(self, chunks_ahead: int | None = None):
        ahead = default_chunks_ahead() if chunks_ahead is None else int(chunks_ahead)
        if ahead < 0:
            raise ValueError(f"chunks_ahead = {chunks_ahead}; allowed: 0 (no thread) or more")
        self.chunks_ahead = ahead
        self.started = False          # this prefetcher has handed work to the thread

    def map(self, fn, items):
        """Same results and errors as calling ``fn`` item by item. Closing the generator (or
        exhausting it) waits for the work still running: the items (views of the reader's map)
        are not used after that."""
        ahead = self.chunks_ahead
        if ahead <= 0:
            for item in items:
                yield partial(fn, item)
            return
        pending = deque()
        try:
            for item in items:
                self.started = True
                pending.append(_executor().submit(fn, item))
                if len(pending) > ahead:
                    yield pending.popleft().result
            while pending:
                yield pending.popleft().result
        finally:
            for future in pending:
                future.cancel()
            for future in pending:
                if not future.cancelled():
                    try:
                        future.result()
                    except Exception:  # noqa: BLE001 - its chunk is not read any more
                        pass
