"""BLAS threads of a process: one, for a node whose matrices are small and whose cores are shared.

numpy's and scipy's wheels bundle OpenBLAS, which starts a worker thread per core and splits a
matrix-vector product of more than ~10,000 elements between them; after each such call the worker
spins, waiting for more, before it sleeps. The model watch multiplies vectors of ~4600 elements by
its views' bases after every onset event: its worker spun ~0.35 % of a core away (measured on the
2-core machine: the model_watch process's second busy thread, gone with OPENBLAS_NUM_THREADS=1;
docs/model_watch.md "Cost"), for products that take microseconds on one thread. The environment
variable acts only before numpy is imported; this sets the libraries' thread count at run time
(what threadpoolctl does, for OpenBLAS only). One thread may sum a product in another order than
two: its last bits can differ (test_blas.py: < 1e-15 relative on products of the watch's sizes;
on the watch's own products a recorded 40 s stream gave bit-identical model_fit messages either
way). Plain Python, no rclpy.
"""
from __future__ import annotations

import ctypes
import os
import sys

# OpenBLAS's setter as the known builds export it: plain, 64-bit-integer, and scipy's wheels' prefixed ones
SETTERS = ("openblas_set_num_threads", "openblas_set_num_threads64_", "scipy_openblas_set_num_threads",
           "scipy_openblas_set_num_threads64_")
GETTERS = tuple(name.replace("_set_", "_get_") for name in SETTERS)


def loaded_openblas() -> list[str]:
    """The OpenBLAS libraries mapped into this process (Linux: /proc/self/maps; elsewhere none)."""
    if not sys.platform.startswith("linux"):
        return []
    try:
        with open("/proc/self/maps") as f:
            paths = {line.split(None, 5)[-1].strip() for line in f if "openblas" in line.lower()}
    except OSError:
        return []
    return sorted(p for p in paths if p.startswith("/") and "openblas" in os.path.basename(p).lower())


def _call(path: str, names, *args):
    """The first of ``names`` that the library at ``path`` exports, called; None when it has none."""
    try:
        lib = ctypes.CDLL(path)
    except OSError:
        return None
    for name in names:
        fn = getattr(lib, name, None)
        if fn is not None:
            fn.argtypes = (ctypes.c_int,) * len(args)
            fn.restype = ctypes.c_int if not args else None
            result = fn(*args)
            return True if args else result
    return None


def blas_threads() -> dict[str, int]:
    """{library: the threads it uses} for every OpenBLAS loaded so far."""
    out = {}
    for path in loaded_openblas():
        n = _call(path, GETTERS)
        if n is not None:
            out[path] = int(n)
    return out


def limit_blas_threads(n: int = 1) -> list[str]:
    """Every OpenBLAS loaded so far uses ``n`` threads from now on; -> the libraries set (a library
    loaded later keeps its default: call this once the process has imported what it uses)."""
    return [path for path in loaded_openblas() if _call(path, SETTERS, int(n))]
