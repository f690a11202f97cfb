"""A rail with noise on it (windowing/saturation.py ``_noisy_rail``; stop 61).

An accelerometer saturates in its analog stage (its amplifier's output, the charge amplifier), and the ADC reads that
level with its own noise: the recorded rail is a level +- noise, not one value repeated, which the exact rule (runs
of identical samples) never sees (bench/_reliability/saturation.py ``noisy_*``: 8 of 180 such clips found before).
Written before the rule, on the development drives; the chain here is written apart from the bench's: the clip by
np.minimum/np.maximum, the noise from its own generator, a 16-bit ADC by floor(x/q + 1/2).
"""
import numpy as np
import pytest

from backlash_monitor.windowing.saturation import SaturationCounter, assess_signal

from saturation_recordings import dev_drive_recordings                    # test/

G = 9.81
FULL_SCALE_M_S2 = {"a1": 50 * G, "a2": 4 * G}
DEV_FOREIGN = ("clean_w2.5_eta0.05_n0.97", "clean_w5.0_eta0.025_n0.89", "clean_w7.1_eta0.0125_n0.97")


@pytest.fixture(scope="module")
def recordings():
    return dev_drive_recordings(DEV_FOREIGN)


def read_with_noise(x, sd, rng, bits=None, signal="a1"):
    """The analog signal with white noise of ``sd``, then (bits) an ADC over the sensor's full scale."""
    y = np.asarray(x, dtype=float) + sd * rng.standard_normal(len(x))
    if bits is None:
        return y
    q = 2 * FULL_SCALE_M_S2[signal] / 2 ** bits
    return np.floor(y / q + 0.5) * q


def saturated(x, level):
    return np.maximum(np.minimum(x, level), -level)


def counted(signals):
    counter = SaturationCounter(("a1", "a2"))
    for k in range(0, len(signals["a1"]), 5000):
        counter.feed({s: v[k:k + 5000] for s, v in signals.items()})
    counter.flush()
    return counter


@pytest.mark.parametrize("bits", [None, 16])
@pytest.mark.parametrize("noise_of_peak", [3e-4, 2e-3])
def test_a_clean_drive_read_with_noise_is_not_at_a_rail(recordings, bits, noise_of_peak):
    rng = np.random.default_rng(7)
    for label, sig in recordings.items():
        noisy = {s: read_with_noise(v, noise_of_peak * np.abs(v).max(), rng, bits, s) for s, v in sig.items()}
        for r in counted(noisy).totals().values():
            assert not r.faulty, (label, bits, noise_of_peak, r.message())


@pytest.mark.parametrize("bits", [None, 16])
@pytest.mark.parametrize("fraction", [0.5, 0.75])
@pytest.mark.parametrize("signal", ["a1", "a2"])
def test_a_sensor_saturated_before_its_noise_is_at_its_rail(recordings, bits, fraction, signal):
    """Found at the level it saturated at (within a few noise sd), the other signal clean."""
    rng = np.random.default_rng(11)
    other = "a2" if signal == "a1" else "a1"
    for label, sig in recordings.items():
        peak = float(np.abs(sig[signal]).max())
        sd = 1e-3 * peak
        signals = {signal: read_with_noise(saturated(sig[signal], fraction * peak), sd, rng, bits, signal),
                   other: read_with_noise(sig[other], 1e-3 * np.abs(sig[other]).max(), rng, bits, other)}
        totals = counted(signals).totals()
        assert totals[signal].at_rail > 0, (label, bits, fraction, signal)
        assert not totals[other].at_rail, (label, totals[other].message())
        found = [abs(v) for v in (totals[signal].upper_rail, totals[signal].lower_rail) if v is not None]
        assert all(abs(v - fraction * peak) <= 4 * sd + 2 * FULL_SCALE_M_S2[signal] / 2 ** 16 for v in found), found


def test_a_window_at_a_noisy_rail_is_flagged(recordings):
    """The live path: a window's samples are checked against the rail the stream's blocks found, within its noise."""
    rng = np.random.default_rng(3)
    sig = recordings["plant_noise1"]
    peak = float(np.abs(sig["a1"]).max())
    signals = {"a1": read_with_noise(saturated(sig["a1"], 0.5 * peak), 1e-3 * peak, rng),
               "a2": read_with_noise(sig["a2"], 1e-3 * np.abs(sig["a2"]).max(), rng)}
    counter = counted(signals)
    assert counter.totals()["a1"].at_rail > 0
    on_rail = int(np.argmax(np.abs(signals["a1"]) >= 0.5 * peak - 2e-3 * peak))
    window = {s: v[max(0, on_rail - 1024):on_rail + 1024] for s, v in signals.items()}
    checked = counter.check_window(window)
    assert checked["a1"].at_rail > 0 and checked["a2"].at_rail == 0


def test_a_flat_level_hit_once_is_not_a_rail():
    """One visit is no evidence of a rail (a clip is hit by every event beyond it): a smooth signal held at its top
    once, with noise."""
    rng = np.random.default_rng(5)
    t = np.arange(50_000) / 50_000.0
    x = np.sin(2 * np.pi * 1.0 * t) * np.linspace(0.5, 1.0, t.size)
    x = np.minimum(x, 0.99) + 1e-3 * rng.standard_normal(t.size)        # only the last, largest swing reaches 0.99
    assert assess_signal(x, "a2").at_rail == 0
