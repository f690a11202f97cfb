"""The recording's sensor chain in the spectral view (workbench/spectral.py sensor_chain, analysis.sensor_noise_floor):
a white noise floor, then an ADC's quantiser.

Physics: a quantiser's error is white with variance step^2/12 only when the input moves by many steps between samples
at random (Widrow's condition; a noise of a few steps, or dither, makes it so). The error of a deterministic, slowly
varying signal is not: between two steps it is a sawtooth whose rate follows the signal's slope, so its power sits
where the signal crosses steps fastest, not spread evenly. The workbench therefore quantises the model's own events at
the recording's step instead of adding a white step^2/12. Checked on a foreign drive (foreign_drives/: an independent
generator) behind an undithered 16-bit ADC on a2 -- a case where the white floor had the spectral shape ~100 T^2
outside the band on a clean drive (docs/model_watch.md, Limits).
"""
import os

import numpy as np
import pytest

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from foreign_drives.drive import make_recording                       # noqa: E402
from foreign_drives.spec import RecordingSpec                         # noqa: E402
from foreign_drives.suites import ADC16                               # noqa: E402

from backlash_monitor.workbench import analysis, diagnose, spectral   # noqa: E402
from backlash_monitor.workbench.events import POST_SAMPLES, PRE_SAMPLES   # noqa: E402
from backlash_monitor.workbench.measurement import Measurement        # noqa: E402
from backlash_monitor.workbench.model import load_model               # noqa: E402

DT = 2e-5
L = PRE_SAMPLES + POST_SAMPLES
STEP = 2 * 4 * 9.81 / 2 ** 16            # a 16-bit ADC over +-4 g [m/s^2]


def _error_band_ratio(x):
    """Band powers (the spectral view's bands) of the quantisation error of segments x, over a white step^2/12's."""
    e = spectral.quantise(x, [STEP]) - x
    return spectral.band_powers(e, DT).mean(axis=0)[0] / spectral.noise_power([STEP ** 2 / 12 * 2 * DT], L, DT)[0]


def test_the_quantisation_error_of_a_slow_signal_is_not_white_and_of_a_noisy_one_is():
    """A ramp that crosses a step every 1/f_c s has an error that is a sawtooth of period 1/f_c: its power sits at
    f_c and its harmonics (61 % at the fundamental, 6/pi^2), none below. With f_c = 5 kHz, in the view's top band
    (4.0-6.4 kHz): several times a white step^2/12 there, almost nothing below 2.5 kHz. With a white noise of 3
    steps added the error is white: step^2/12 in every band."""
    rng = np.random.default_rng(3)
    t = np.arange(L) * DT
    crossing_hz = 5000.0
    slow = np.stack([o + crossing_hz * STEP * t for o in rng.uniform(0, 1, 64)])[:, None]
    noisy = slow + 3 * STEP * rng.standard_normal(slow.shape)
    r_slow, r_noisy = _error_band_ratio(slow), _error_band_ratio(noisy)
    assert np.all(np.abs(r_noisy - 1) < 0.15), r_noisy            # white: step^2/12 in every band
    top = spectral.BAND_EDGES_HZ[-2]
    assert top < crossing_hz < spectral.BAND_EDGES_HZ[-1]
    assert r_slow[-1] > 3, r_slow                                  # the sawtooth's fundamental
    assert np.all(r_slow[:4] < 0.1), r_slow                        # below 2.5 kHz: nothing


def test_without_a_step_the_chain_is_the_white_floor_as_before():
    """No quantiser: the model's noisy events and the added power are the white floor's (noisy_event_features,
    noise_power) to the last bit -- unquantised recordings are compared as they were."""
    rng = np.random.default_rng(5)
    raw = [rng.standard_normal((4, 2, L)) for _ in range(3)]
    psd = np.array([1e-6, 2e-9])
    feats, power = spectral.sensor_chain(raw, DT, psd, np.zeros(2))
    for k, r in enumerate(raw):
        assert np.array_equal(feats[k], spectral.noisy_event_features(r, DT, psd, seed=k))
    assert np.array_equal(power, spectral.noise_power(psd, L, DT))


@pytest.fixture(scope="module")
def adc_drive():
    """A clean foreign drive at 5 mm behind an undithered 16-bit ADC (the bench's ADC16: quantisation and no other
    noise), 4 s, and the comparison diagnose builds for it (3 seeds)."""
    spec = RecordingSpec(label="clean_adc16", kind="clean", width_m=0.005, eta_k=0.025, n1=0.89, sensor=ADC16,
                         seed=331, duration_s=4.0).check()
    rec = make_recording(spec)
    meas = Measurement("foreign:clean_adc16", rec.sample_period_s, {k: np.asarray(v) for k, v in rec.signals.items()})
    model = load_model(None, width_m=0.005, eta_k=0.025, n1=0.89)
    return meas, model


def test_the_model_quantised_at_the_recordings_step_predicts_its_spectral_shape(adc_drive):
    """The step is read off the samples; the noise floor before the quantiser is ~0 (there is no other noise); the
    model's events quantised at the step predict the drive's spectral shape within the events' noise in every
    feature, where the model plus a white step^2/12 is many noise floors off in a2's top band (4.0-6.4 kHz against
    2.5-4.0 kHz: the undithered error of a2 is concentrated there)."""
    meas, model = adc_drive
    comp = analysis.build_comparison(meas, model, seeds=[0, 1, 2])
    assert comp.quant_step[1] == pytest.approx(ADC16.a2_lsb_m_s2, rel=1e-6)
    assert comp.quant_step[0] == pytest.approx(ADC16.a1_lsb_m_s2, rel=1e-6)
    white_q = analysis.quantisation_psd(comp.quant_step, DT)
    assert comp.noise_psd[1] < 0.1 * white_q[1]
    measured = spectral.event_features(comp.events.raw, DT).mean(axis=0)
    bands = np.concatenate(comp.ensemble.seed_bands[0], axis=0)
    chain = spectral.features_from_bands(bands, comp.segment_noise).mean(axis=0)
    white = spectral.features_from_bands(bands, spectral.noise_power(comp.noise_psd + white_q, L, DT)).mean(axis=0)
    z_chain, z_white = (measured - chain) * comp.spec_weights, (measured - white) * comp.spec_weights
    assert np.all(np.abs(z_chain) < 4), z_chain
    assert abs(z_white[-1]) > 10 and abs(z_white[-1]) > 5 * abs(z_chain[-1]), (z_white, z_chain)


@pytest.mark.slow
def test_diagnose_finds_a_clean_drive_behind_an_undithered_adc_consistent(adc_drive):
    """diagnose's consistency test (the one the model watch runs) on that drive: the spectral shape inside its band
    (with the white floor: T^2 ~90-120 against a limit of ~17)."""
    meas, model = adc_drive
    run = diagnose.prepare(meas, model, seeds=[0, 1, 2])
    diagnose.screen_step(run)
    spec = run.before.views["spectral_shape"]
    assert not spec.outside_band, (spec.t2, spec.limit)
