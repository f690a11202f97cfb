"""Bad parameters of denoise_sym5 raise ValueError naming the parameter."""
import numpy as np
import pytest

from backlash_monitor.denoise import denoise_sym5, max_level


@pytest.mark.parametrize("kwargs, match", [
    ({"level": 8}, r"level=8: too deep.*1\.\.7"),
    ({"level": 0}, "level=0"),
    ({"level": 2.0}, "level"),
    ({"mode": "mirror"}, "mode='mirror'"),
    ({"wavelet": "sym55"}, "wavelet"),
    ({"details_removed": (7,)}, "details_removed"),
    ({"details_removed": (0,)}, "details_removed"),
])
def test_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        denoise_sym5(np.zeros(2048), **kwargs)


def test_level_too_deep_for_short_window():
    assert max_level(256) == 4
    with pytest.raises(ValueError, match="level=6"):
        denoise_sym5(np.zeros(256))


def test_scalar_rejected():
    with pytest.raises(ValueError, match="window"):
        denoise_sym5(1.0)
