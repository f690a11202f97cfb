"""analysis.welch_psd is scipy.signal.welch (nperseg min(8192, samples)) to the last bit, on every shape the workbench
and the live watch give it; only its set-up is kept between calls."""
import numpy as np
import pytest
from scipy import signal as sps

from backlash_monitor.workbench import analysis


@pytest.mark.parametrize("shape", [(2, 12500), (200000,), (3, 5000), (5,), (1, 8192), (2, 8193), (4, 20001),
                                   (2, 16384), (2, 0)])
@pytest.mark.parametrize("fs", [50000.0, 1.0 / 2e-5, 48000.0])
def test_welch_psd_is_scipys_welch_to_the_last_bit(shape, fs):
    x = np.random.default_rng(sum(shape)).standard_normal(shape) * 3.0 + 1.0
    f, p = analysis.welch_psd(x, fs)
    f_ref, p_ref = sps.welch(x, fs=fs, nperseg=min(analysis.SPECTRUM_NPERSEG, max(shape[-1], 1)), axis=-1)
    assert p.shape == p_ref.shape and p.dtype == p_ref.dtype
    assert np.array_equal(f, f_ref) and np.array_equal(p, p_ref)


def test_welch_psd_again_and_after_another_length_gives_the_same():
    x = np.random.default_rng(1).standard_normal((2, 12500))
    first = analysis.welch_psd(x, 50000.0)[1]
    analysis.welch_psd(x[:, :3000], 50000.0)
    assert np.array_equal(analysis.welch_psd(x, 50000.0)[1], first)
