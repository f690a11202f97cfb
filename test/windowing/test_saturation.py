"""Sensor saturation (a signal at its rail) and a stuck sensor, from the data alone (windowing/saturation.py).

The false-flag cases were written before the thresholds (config/windowing.yaml ``saturation``) were tuned:
a clean noisy signal, a noise-free simulated one, and signals behind an undithered 16-bit ADC, whose
extreme value is a quantisation level that a slow peak sits on for tens of samples in a row.
"""
import dataclasses

import numpy as np
import pytest

from backlash_monitor.windowing.saturation import (SaturationCounter, SaturationSettings, assess,
                                                   assess_signal)

FS = 50_000.0
A2_LSB_M_S2 = 2 * 4 * 9.81 / 2 ** 16       # a 16-bit ADC over +-4 g (foreign_drives/suites.py ADC16)
A1_LSB_M_S2 = 2 * 50 * 9.81 / 2 ** 16      # over +-50 g


def quantise(x, lsb):
    return np.round(x / lsb) * lsb


def clip(x, fraction, rails="both"):
    """Both rails at +-fraction of the peak |x|; one rail at fraction of that side's peak."""
    peak = float(np.abs(x).max())
    hi = fraction * (peak if rails == "both" else float(x.max())) if rails in ("both", "upper") else np.inf
    lo = -fraction * (peak if rails == "both" else float(-x.min())) if rails in ("both", "lower") else -np.inf
    return np.clip(x, lo, hi)


@pytest.fixture(scope="module")
def plant_signals():
    plant = pytest.importorskip("backlash_monitor.plant")
    out = {}
    for noise in (True, False):
        sim = plant.PlantSimulator([plant.Scenario(width_m=0.0075, eta_k=0.025, n1=0.89, seed=11)],
                                   config=plant.load_plant_config(), noise=noise)
        chunks = [sim.run(10_000) for _ in range(8)]          # 1.6 s: 6 load pulses
        out[noise] = {s: np.concatenate([getattr(c, s)[0] for c in chunks]) for s in ("a1", "a2")}
    return out


@pytest.fixture(scope="module")
def foreign_signals():
    pytest.importorskip("foreign_drives")
    from foreign_drives.drive import make_recording
    from foreign_drives.suites import BENCH
    wanted = ("clean_w5.6_eta0.015_n0.96_adc", "clean_w9.0_eta0.019_n0.90_enc16", "clean_w4.4_eta0.031_n0.93_adc")
    specs = [s for s in BENCH if s.label in wanted]
    return {s.label: make_recording(dataclasses.replace(s, duration_s=2.0)).signals for s in specs}


# ---- clean signals are never flagged (written before tuning) -------------------------------------------

def _clean(result):
    return {name: (r.at_rail, r.stuck) for name, r in result.items() if r.at_rail or r.stuck}


def test_a_noisy_plant_signal_is_clean(plant_signals):
    assert _clean(assess(plant_signals[True])) == {}


def test_a_noise_free_simulated_signal_is_clean(plant_signals):
    assert _clean(assess(plant_signals[False])) == {}


def test_the_plant_behind_an_undithered_16_bit_adc_is_clean(plant_signals):
    for noise in (True, False):
        sig = plant_signals[noise]
        adc = {"a1": quantise(sig["a1"], A1_LSB_M_S2), "a2": quantise(sig["a2"], A2_LSB_M_S2)}
        assert _clean(assess(adc)) == {}, noise


def test_foreign_drives_behind_a_16_bit_adc_are_clean(foreign_signals):
    # clean_w9.0 (enc16): a2's largest value is one ADC level held for 90 samples in a row
    for label, sig in foreign_signals.items():
        assert _clean(assess({s: sig[s] for s in ("a1", "a2")})) == {}, label


def test_clean_blocks_and_windows_are_clean(plant_signals, foreign_signals):
    """Counted in blocks as a stream is (each 1 s block judged alone), and every 2048-sample window
    checked against the rails found: no flag."""
    sets = [plant_signals[True], plant_signals[False]] + [
        {s: v[s] for s in ("a1", "a2")} for v in foreign_signals.values()]
    sets += [{"a1": quantise(s["a1"], A1_LSB_M_S2), "a2": quantise(s["a2"], A2_LSB_M_S2)} for s in sets[:2]]
    for i, sig in enumerate(sets):
        counter = SaturationCounter(("a1", "a2"))
        for k in range(0, len(sig["a1"]), 2048):
            part = {name: x[k:k + 2048] for name, x in sig.items()}
            counter.feed(part)
            assert _clean(counter.check_window(part)) == {}, (i, k)
        counter.flush()
        assert _clean(counter.totals()) == {}, i


def test_a_window_at_a_found_rail_is_flagged(plant_signals):
    sig = dict(plant_signals[True])
    sig["a2"] = clip(sig["a2"], 0.75)
    counter = SaturationCounter(("a1", "a2"), SaturationSettings(block_samples=20_000))
    flagged = 0
    for k in range(0, len(sig["a1"]), 2048):
        part = {name: x[k:k + 2048] for name, x in sig.items()}
        counter.feed(part)
        result = counter.check_window(part)
        assert result["a1"].at_rail == 0
        flagged += result["a2"].at_rail > 0
    assert flagged > 0


def test_a_slow_quantised_sine_with_flat_peaks_is_clean():
    """A 4 Hz sine of 1 m/s^2 behind the +-4 g ADC: each peak sits on its top level ~150 samples."""
    t = np.arange(100_000) / FS
    x = quantise(1.0 * np.sin(2 * np.pi * 4.0 * t), A2_LSB_M_S2)
    r = assess_signal(x, "a2")
    assert (r.at_rail, r.stuck) == (0, 0)


# ---- clipped and stuck signals are found ------------------------------------------------------------

@pytest.mark.parametrize("fraction", [0.5, 0.75, 0.95])
@pytest.mark.parametrize("signal", ["a1", "a2"])
@pytest.mark.parametrize("rails", ["both", "upper"])
def test_a_clipped_plant_signal_is_at_its_rail(plant_signals, fraction, signal, rails):
    sig = dict(plant_signals[True])
    sig[signal] = clip(sig[signal], fraction, rails)
    result = assess(sig)
    other = "a2" if signal == "a1" else "a1"
    assert result[signal].at_rail > 0
    assert result[other].at_rail == 0
    clean = plant_signals[True][signal]
    if rails == "upper":
        assert result[signal].upper_rail == pytest.approx(fraction * clean.max())
    else:
        peak = float(np.abs(clean).max())
        found = [abs(v) for v in (result[signal].upper_rail, result[signal].lower_rail) if v is not None]
        assert found and all(v == pytest.approx(fraction * peak) for v in found)
    # the samples at the rail: every sample the clip changed lies on it, and runs of one may escape
    changed = int(np.count_nonzero(sig[signal] != plant_signals[True][signal]))
    assert 0.8 * changed <= result[signal].at_rail <= changed + 2 * result[signal].runs


def test_the_message_names_the_signal_the_rail_and_the_share(plant_signals):
    x = clip(plant_signals[True]["a2"], 0.75)
    r = assess_signal(x, "a2")
    rail = 0.75 * float(np.abs(plant_signals[True]["a2"]).max())
    share = 100.0 * r.at_rail / len(x)
    assert r.message() == (f"a2 at its rail (±{rail:.3g} m/s²) in {share:.1f} % of samples: "
                           "the accelerometer's range is too small")


def test_a_stuck_sensor_is_named_as_one_not_as_saturated(plant_signals):
    x = plant_signals[True]["a1"].copy()
    x[40_000:] = x[40_000]                  # the sensor dies at 0.8 s and holds its last value
    r = assess_signal(x, "a1")
    assert r.stuck == len(x) - 40_000 and r.at_rail == 0
    assert "stuck" in r.message() and "rail" not in r.message()
    dead = assess_signal(np.zeros(5000), "a2")  # a dead sensor: all one value
    assert dead.stuck == 5000 and dead.at_rail == 0


def test_the_counter_counts_a_recording_in_blocks_as_assess_does(plant_signals):
    sig = dict(plant_signals[True])
    sig["a2"] = clip(sig["a2"], 0.75)
    whole = assess(sig)
    counter = SaturationCounter(("a1", "a2"), SaturationSettings(block_samples=len(sig["a1"])))
    for k in range(0, len(sig["a1"]), 7777):     # chunks across block boundaries
        counter.feed({s: v[k:k + 7777] for s, v in sig.items()})
    counter.flush()
    assert counter.totals()["a2"].at_rail == whole["a2"].at_rail
    assert counter.totals()["a1"].at_rail == 0
    assert counter.totals()["a2"].samples == len(sig["a2"])


def test_settings_come_from_the_yaml():
    from backlash_monitor.windowing import load_windowing_config
    s = SaturationSettings.from_config(load_windowing_config()["saturation"])
    assert s == SaturationSettings()
    with pytest.raises(ValueError, match="rail_min_run_samples"):
        SaturationSettings(rail_min_run_samples=0)
    with pytest.raises(ValueError, match=r"stuck_quiet_steps = -1; allowed: an integer in \[0, 1000\]"):
        SaturationSettings(stuck_quiet_steps=-1)
    with pytest.raises(ValueError, match="stuck_quiet_max_run_samples"):
        SaturationSettings(stuck_quiet_max_run_samples=0.5)


def test_a_rail_hit_on_a_few_samples_is_said_as_their_count_never_as_zero_percent():
    """A handful of clipped samples in a long record is a fault found: its share printed at one decimal would read
    '0.0 %' (measured on an auto-ranging a1 of the eighth sealed set), so the count is said instead."""
    from backlash_monitor.windowing.saturation import SignalSaturation
    few = SignalSaturation("a1", samples=200_000, at_rail=12, runs=3, upper_rail=166.0, lower_rail=-166.0)
    assert "in 12 of 200000 samples: the accelerometer's range is too small" in few.message()
    many = SignalSaturation("a1", samples=200_000, at_rail=8_200, runs=40, upper_rail=166.0, lower_rail=-166.0)
    assert "in 4.1 % of samples" in many.message()
