"""process/blas.py: a process's OpenBLAS thread count set at run time; a product's result changes at most in its last
bits (the order of a sum)."""
import json
import subprocess
import sys
import textwrap

import pytest

CHILD = textwrap.dedent("""
    import json
    import numpy as np
    import scipy.signal  # noqa: F401  (scipy's own OpenBLAS, as the watch loads it)
    from backlash_monitor.process.blas import blas_threads, limit_blas_threads
    rng = np.random.default_rng(3)
    basis, r = rng.standard_normal((4596, 300)), rng.standard_normal(4596)   # the watch's sizes: basis.T @ r
    events = rng.standard_normal((16, 4596))
    before = blas_threads()
    default = (basis.T @ r, events @ basis)
    limited = limit_blas_threads(1)
    one = (basis.T @ r, events @ basis)
    print(json.dumps({"before": before, "limited": limited, "after": blas_threads(),
                      "close": all(bool(np.allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(a).max()))
                                   for a, b in zip(default, one))}))
""")


@pytest.mark.process
def test_every_loaded_openblas_runs_on_one_thread_and_the_products_stay_to_rounding():
    # in a child: the thread count is the process's own
    out = json.loads(subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True, timeout=120,
                                    check=True).stdout)
    if not out["before"]:
        pytest.skip("no OpenBLAS loaded (numpy built with another BLAS)")
    assert sorted(out["limited"]) == sorted(out["before"])
    assert set(out["after"].values()) == {1}
    assert out["close"]
