"""The boundary-mode decision (docs/denoising.md): 'symmetric' is continuous at the ends and keeps
every tone of the removed bands below 10 %; 'smooth' extrapolates the end slope and leaks them,
'periodization' wraps end onto start and has the largest edge error on non-periodic windows."""
import numpy as np

from backlash_monitor.denoise import DEFAULT_MODE, boundary_mode_error, denoise_sym5

FS = 50_000.0


def _lowfreq_records(n_rec=40, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(3 * 2048) / FS
    f = rng.uniform(5, 300, (n_rec, 4, 1))
    ph = rng.uniform(0, 2 * np.pi, (n_rec, 4, 1))
    a = rng.normal(size=(n_rec, 4, 1))
    return (a * np.sin(2 * np.pi * f * t + ph)).sum(1) + rng.normal(size=(n_rec, 1)) * t * 50


def test_default_mode_is_symmetric():
    assert DEFAULT_MODE == "symmetric"


def test_edge_error_symmetric_beats_periodic_modes():
    err = boundary_mode_error(_lowfreq_records())
    for m in ("periodization", "periodic", "zero"):
        assert err["symmetric"]["start"] < err[m]["start"] and err["symmetric"]["end"] < err[m]["end"]
    assert err["symmetric"]["whole"] < 0.02


def test_smooth_leaks_high_frequency_at_edges_symmetric_does_not():
    x = np.sin(2 * np.pi * 10_000 * np.arange(2048) / FS + 0.3)
    rms = lambda v: np.sqrt(np.mean(v ** 2))  # noqa: E731
    assert rms(denoise_sym5(x, mode="symmetric")) / rms(x) < 0.05
    assert rms(denoise_sym5(x, mode="smooth")) / rms(x) > 0.3
