"""An exclusive lock between processes on one machine: work that several processes would do at once (compile a
kernel, build a cached file) is done by the first, the others wait and then read what it wrote.

``exclusive(path)`` holds an flock on ``path`` (created when missing): released when the block ends, and by the
operating system when the process ends, also when it is killed, so a crashed holder never leaves a stale lock.
Without fcntl (not POSIX) or where the file cannot be opened (a read-only directory) it holds nothing: each process
then does the work itself, which is slower, never wrong.
"""
from __future__ import annotations

import contextlib
from pathlib import Path

try:
    import fcntl
except ImportError:               # not POSIX: no lock
    fcntl = None


@contextlib.contextmanager
def exclusive(path):
    """Hold an exclusive lock on ``path`` for the block (module docstring)."""
    try:
        Path(path).parent.mkdir(parents=True, exist_ok=True)
        handle = open(path, "a")   # noqa: SIM115 (held for the block)
    except OSError:
        handle = None
    if fcntl is None or handle is None:
        yield
        return
    with handle:
        fcntl.flock(handle, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(handle, fcntl.LOCK_UN)
