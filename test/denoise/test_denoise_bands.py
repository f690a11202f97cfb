"""Level-6 sym5 approximation at fs = 50 kHz keeps ~0..390 Hz and removes d1..d6 (> ~780 Hz)."""
import numpy as np
import pytest

from backlash_monitor.denoise import denoise_sym5

FS = 50_000.0
T = np.arange(2048) / FS


def _rms(x):
    return np.sqrt(np.mean(x ** 2))


@pytest.mark.parametrize("f", [10.0, 20.0, 50.0])
def test_low_frequency_passes_within_1_percent(f):
    x = np.sin(2 * np.pi * f * T + 0.3)
    assert _rms(denoise_sym5(x) - x) / _rms(x) < 0.01


@pytest.mark.parametrize("f", [1000.0, 1500.0, 3000.0, 5000.0, 10000.0, 20000.0])
def test_detail_band_attenuated_over_90_percent(f):
    x = np.sin(2 * np.pi * f * T + 0.3)
    assert _rms(denoise_sym5(x)) / _rms(x) < 0.10


def test_only_d1_d2_removed_keeps_mid_band():
    """The paper's Gaussian-generator level (2): removing d1, d2 keeps 1.5 kHz, removes 15 kHz."""
    x3, x15 = (np.sin(2 * np.pi * f * T) for f in (1500.0, 15000.0))
    assert _rms(denoise_sym5(x3, details_removed=(1, 2)) - x3) / _rms(x3) < 0.05
    assert _rms(denoise_sym5(x15, details_removed=(1, 2))) / _rms(x15) < 0.10
