"""A codec whose step grows with |x| is not a rail (windowing/saturation.py ``_step_at``; stop 61).

A recorder that stores float16, a block floating-point codec (a block's samples share one exponent) and a companding
ADC (mu-law) all quantise an impact's top coarsely while the signal's smallest change, far from the top, is fine.
With the signal's smallest change as its step, the rule read the coarse top level's hold as a rail on nearly every
drive (bench/_reliability/saturation.py ``codec_*``: 69 of 210 clean signals, nearly every a2 behind the block codec
and mu-law; set 23's block floating-point a1, spent, "at its rail" in 45 of 200000 samples). The step near each
extreme is now read from the occupied values there. The codecs here are written apart from the bench's (no shared
code): float16 by numpy's cast, the block codec by frexp, mu-law by its table of levels.
"""
import numpy as np
import pytest

from backlash_monitor.windowing.saturation import SaturationCounter, assess_signal

from saturation_recordings import dev_drive_recordings                    # test/

G = 9.81
DEV_FOREIGN = ("clean_w2.5_eta0.05_n0.97", "clean_w5.0_eta0.025_n0.89", "clean_w10_eta0.05_n0.89")


def float16(x):
    return np.asarray(x, dtype=np.float16).astype(float)


def block_floating_point(x, block=64, mantissa_bits=10):
    """Each block of samples: one exponent (frexp of its largest |x|), signed mantissas of ``mantissa_bits``."""
    x = np.asarray(x, dtype=float)
    out = np.zeros_like(x)
    for k in range(0, x.size, block):
        part = x[k:k + block]
        _, exponent = np.frexp(np.max(np.abs(part)))
        step = np.ldexp(1.0, int(exponent) - (mantissa_bits - 1))
        out[k:k + block] = np.round(part / step) * step
    return out


def mu_law(x, full_scale, bits=12):
    """A mu-law ADC (mu = 255): the nearest of its 2^bits levels, read back."""
    codes = np.arange(-(2 ** (bits - 1) - 1), 2 ** (bits - 1))
    y = codes / (2 ** (bits - 1) - 1)
    table = np.sign(y) * full_scale * ((1 + 255.0) ** np.abs(y) - 1) / 255.0
    idx = np.clip(np.searchsorted(table, x), 1, table.size - 1)
    lower, upper = table[idx - 1], table[idx]
    return np.where(np.abs(x - lower) <= np.abs(upper - x), lower, upper)


CODECS = {"float16": lambda x, s: float16(x),
          "block_floating_point": lambda x, s: block_floating_point(x),
          "mu_law_12_bit": lambda x, s: mu_law(x, (200 if s == "a1" else 4) * G)}


@pytest.fixture(scope="module")
def recordings():
    return dev_drive_recordings(DEV_FOREIGN)


def counted(signals):
    """As the windowing stage counts a stream: blocks of 1 s, fed in chunks."""
    counter = SaturationCounter(("a1", "a2"))
    for k in range(0, len(signals["a1"]), 5000):
        counter.feed({s: v[k:k + 5000] for s, v in signals.items()})
    counter.flush()
    return counter.totals()


@pytest.mark.parametrize("codec", sorted(CODECS))
def test_a_clean_drive_behind_a_codec_is_neither_at_a_rail_nor_stuck(recordings, codec):
    for label, sig in recordings.items():
        coded = {s: CODECS[codec](sig[s], s) for s in ("a1", "a2")}
        assert np.unique(coded["a2"]).size < np.unique(sig["a2"]).size     # the codec did quantise
        for r in counted(coded).values():
            assert not r.faulty, (label, codec, r.message())


@pytest.mark.parametrize("codec", sorted(CODECS))
@pytest.mark.parametrize("signal", ["a1", "a2"])
def test_a_signal_clipped_at_half_its_peak_behind_a_codec_is_at_its_rail(recordings, codec, signal):
    """A clip is hit by every excursion beyond it: the codec's coarse top does not hide it. The rail found is the
    clip level as the codec wrote it."""
    for label, sig in recordings.items():
        peak = float(np.abs(sig[signal]).max())
        coded = dict(sig)
        coded[signal] = CODECS[codec](np.clip(sig[signal], -0.5 * peak, 0.5 * peak), signal)
        other = "a2" if signal == "a1" else "a1"
        coded[other] = CODECS[codec](sig[other], other)
        totals = counted(coded)
        assert totals[signal].at_rail > 0, (label, codec)
        assert totals[other].at_rail == 0, (label, codec, totals[other].message())
        found = [abs(v) for v in (totals[signal].upper_rail, totals[signal].lower_rail) if v is not None]
        assert found and all(abs(v - 0.5 * peak) <= 0.02 * peak for v in found), (label, codec, found)


def test_an_unquantised_clip_on_a_smooth_ramp_is_still_a_rail():
    """A smooth rise's samples are nearly evenly spaced, as a quantiser's levels are; they are met once each, so
    they are no step: a sine clipped at 90 % of its peak, unquantised, is at its rail."""
    t = np.arange(50_000) / 50_000.0
    rng = np.random.default_rng(3)
    x = 100 * np.sin(2 * np.pi * 4 * t) + 1e-3 * rng.standard_normal(t.size)
    r = assess_signal(np.clip(x, -90.0, 90.0), "a1")
    assert r.at_rail > 0 and r.upper_rail == 90.0 and r.lower_rail == -90.0


def test_a_dead_sensor_behind_a_codec_is_still_stuck(recordings):
    """A hold across a load event ends where the signal has gone meanwhile: many of the codec's steps."""
    for label, sig in recordings.items():
        x = block_floating_point(sig["a2"])
        peak = int(np.argmax(np.abs(x - np.median(x))))
        held = x.copy()
        held[peak - 500:peak + 1500] = x[peak - 501]
        r = assess_signal(held, "a2")
        assert r.stuck + r.at_rail >= 2000, (label, r.message())
