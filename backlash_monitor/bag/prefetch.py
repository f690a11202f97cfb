"""Chunks decompressed ahead of the reader, in a worker thread of the reader's own.

zstd/lz4 decompression and the CRC release the GIL (or are short): on a second core a chunk is
decompressed and checked while the caller decodes and processes the messages of the one before.
Each BagReader has its own ChunkPrefetcher, configured by the reader's ``chunks_ahead`` argument
(nothing here is set from outside): ``chunks_ahead=0`` decompresses in the caller's thread (a
process with no core to spare, e.g. one of a pool with a worker per core, where the thread would
only take turns with it). The worker thread is started on first use and ended by ``close()``.
"""
from __future__ import annotations

import os
import threading
from collections import deque
from functools import partial

DEFAULT_CHUNKS_AHEAD = 6   # ~6 MiB of decompressed chunks at the default 1 MiB chunk size


def default_chunks_ahead() -> int:
    """DEFAULT_CHUNKS_AHEAD where this process may run on two CPUs or more, else 0."""
    try:
        cpus = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        cpus = os.cpu_count() or 1
    return DEFAULT_CHUNKS_AHEAD if cpus > 1 else 0


class ChunkPrefetcher:
    """``map(fn, items)`` yields, for each item in order, a callable returning ``fn(item)`` (or
    raising its error), ``fn`` running up to ``chunks_ahead`` items ahead in the worker thread."""

    def __init__(self, chunks_ahead: int | None = None):
        ahead = default_chunks_ahead() if chunks_ahead is None else int(chunks_ahead)
        if ahead < 0:
            raise ValueError(f"chunks_ahead = {chunks_ahead}; allowed: 0 (no thread) or more")
        self.chunks_ahead = ahead
        self._pool = None
        self._pid = None
        self._lock = threading.Lock()

    def _executor(self):
        with self._lock:
            if self._pool is None or self._pid != os.getpid():   # (a forked copy has no thread)
                from concurrent.futures import ThreadPoolExecutor

                self._pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="bag-decompress")
                self._pid = os.getpid()
            return self._pool

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
                pending.append(self._executor().submit(fn, item))
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

    def close(self) -> None:
        """End the worker thread (after the work it has)."""
        with self._lock:
            pool, self._pool = self._pool, None
        if pool is not None and self._pid == os.getpid():
            pool.shutdown(wait=True)
