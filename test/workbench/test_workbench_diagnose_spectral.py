"""The raw spectral block of the workbench's evidence (workbench/spectral.py) and what it lets diagnose find.

A first-order sensor low-pass tau*y' = a - y multiplies the power spectrum by 1/(1 + (2 pi f tau)^2): the
spectral-shape features (ln power of adjacent bands, differenced) of low-passed white noise must shift by
the band means of that factor; a gain must not move them at all (it scales every band alike). A hidden
a2 roll-off at ~530 Hz, invisible in the sym5-denoised event average (the denoising removes that band),
must be named and its time constant fitted through the spectral block.
"""
import numpy as np
import pytest
from scipy.signal import lfilter

from backlash_monitor.workbench import spectral
from backlash_monitor.workbench.decisions import significant
from backlash_monitor.workbench.diagnose import diagnose, public
from backlash_monitor.workbench.fitting import FitResult
from backlash_monitor.workbench.model import load_model
from backlash_monitor.workbench.synthetic import hidden_effect_recording

DT = 2e-5
LOWPASS_TAU_S = 3.0e-4        # a2 roll-off at 1 / (2 pi tau) = 530 Hz
TAU_TOLERANCE = 0.15          # relative error of the fitted time constant


def _band_means(fn):
    e = spectral.BAND_EDGES_HZ
    return np.array([np.mean(fn(np.linspace(lo, hi, 2001))) for lo, hi in zip(e[:-1], e[1:])])


def test_lowpass_tilts_the_spectral_shape_as_its_transfer_function():
    rng = np.random.default_rng(0)
    n_events, length = 400, 2298
    white = rng.standard_normal((n_events, 1, length))
    tau = 2e-4
    alpha = -np.expm1(-DT / tau)
    filtered = lfilter([alpha], [1.0, alpha - 1.0], white, axis=-1)
    shift = spectral.event_features(filtered, DT).mean(axis=0) - spectral.event_features(white, DT).mean(axis=0)
    # the exact discrete filter's power response |H(f)|^2, band-averaged, differenced
    z = lambda f: np.exp(-2j * np.pi * f * DT)                                   # noqa: E731
    h2 = _band_means(lambda f: np.abs(alpha / (1 - (1 - alpha) * z(f))) ** 2)
    expected = np.diff(np.log(h2))
    np.testing.assert_allclose(shift, expected, atol=0.08)
    assert np.all(shift < -0.2)        # a roll-off tilts every step down


def test_a_gain_does_not_move_the_spectral_shape():
    rng = np.random.default_rng(1)
    x = rng.standard_normal((8, 2, 2298))
    np.testing.assert_allclose(spectral.event_features(1.7 * x, DT), spectral.event_features(x, DT), atol=1e-9)


def _fit(values, uncertainty):
    v = np.array(values, float)
    return FitResult("e", ["p"] * len(v), ["-"] * len(v), v, np.array(uncertainty, float), np.zeros(len(v)),
                     (np.full(len(v), -1.0), np.full(len(v), 1.0)), 0.9, -10.0, 0.0, np.zeros((2, 3)), 0.9, 1)


def test_a_fitted_value_within_two_uncertainties_of_the_model_is_not_significant():
    assert significant(_fit([0.3], [0.1]))
    assert not significant(_fit([0.15], [0.1]))
    assert not significant(_fit([0.3, 0.05], [0.1, 0.1]))     # every parameter of the effect must stand out


@pytest.fixture(scope="module")
def lowpass_diagnosis():
    model = load_model(None)
    meas = hidden_effect_recording(model, 3.0, seed=53, config_overrides={
        "effects.accelerometer_lowpass": True, "accelerometer_lowpass.a2_time_constant_s": LOWPASS_TAU_S})
    return public(diagnose(meas, model, propose=False))


@pytest.mark.slow
def test_hidden_a2_lowpass_is_named_and_fitted_through_the_raw_spectra(lowpass_diagnosis):
    res = lowpass_diagnosis
    assert res["discovery_candidate"] == "accelerometer_lowpass[a2]", res["message"]
    tau = res["discovery_parameters"]["parameters"]["a2_time_constant_s"]
    assert abs(tau - LOWPASS_TAU_S) / LOWPASS_TAU_S < TAU_TOLERANCE, tau
    blocks = res["subspace"]["blocks"]
    # the evidence is mostly in the spectral block: a 0.3 ms lag (15 samples) also shows a little in the
    # denoised event average, but the lowpass's loss of power above its ~530 Hz corner is what stands out
    spectral = blocks["spectral_shape"]["T2"] / blocks["spectral_shape"]["T2_limit_p01"]
    event = blocks["event_average"]["T2"] / blocks["event_average"]["T2_limit_p01"]
    assert spectral > 10 and spectral > 3 * event, (spectral, event)
    shape = res["spectral_shape"]["measured_minus_model"]
    assert all(v < 0 for k, v in shape.items() if k.startswith("a2_"))
