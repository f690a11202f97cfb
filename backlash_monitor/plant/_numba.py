"""Optional numba support: model functions stay plain Python (they run on numpy arrays) and are
also compilable into the numba kernel when numba is installed."""
from __future__ import annotations

try:  # pragma: no cover - depends on the environment
    import numba
    from numba.extending import register_jitable as jitable
    HAVE_NUMBA = True
except ImportError:  # pragma: no cover
    numba = None
    HAVE_NUMBA = False

    def jitable(func):
        return func
