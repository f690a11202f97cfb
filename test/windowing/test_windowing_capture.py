"""Window capture across chunk boundaries, and discards for dropped / out-of-order chunks and
sample-period changes."""
import numpy as np
import pytest

from backlash_monitor.windowing import (BacklashEntry, BacklashWindower, WindowCapture, extract_windows,
                                        extract_windows_batch)
from backlash_monitor.windowing.synthetic import synthetic_period, tile_events, tile_record

N = 2048


def _signals(n_periods=3, width=0.005):
    """(signals, contact_loss entries = the exact torque-zero crossings, zone entries)."""
    p = synthetic_period(width_m=width)
    d, w, dep, ent = tile_record(p, n_periods)
    k = np.arange(d.size, dtype=float)
    return {"a1": k, "a2": -k, "angle_difference": d}, tile_events(p, p.crossings, n_periods), ent


def _e(i, kind="onset"):
    return BacklashEntry(i, kind, "contact_loss", i)


def test_windows_are_the_samples_after_the_entry_across_chunks():
    sig, dep, _ = _signals()
    for chunk in (333, 5000, sig["a1"].size):
        wins = extract_windows(sig, trigger="contact_loss", chunk_samples=chunk)
        assert [(w.entry_sample_index, w.kind) for w in wins] == dep
        for w in wins:
            assert w.signals["a1"].shape == (N,)
            np.testing.assert_array_equal(w.signals["a1"], np.arange(w.entry_sample_index, w.entry_sample_index + N))
            np.testing.assert_array_equal(w.signals["a2"], -w.signals["a1"])
            assert w.trigger == "contact_loss" and w.sample_period_s == 2e-5


def test_configurable_signal_set_and_length():
    sig, dep, _ = _signals()
    wins = extract_windows(sig, trigger="paper", width_m=0.005, window_length=512,
                           window_signals=("a1", "angle_difference"))
    assert set(wins[0].signals) == {"a1", "angle_difference"} and wins[0].window_length == 512


def test_backdated_entry_in_previous_chunk():
    cap = WindowCapture(window_length=100, history_samples=500)
    x = np.arange(1000.0)
    w1, d1 = cap.feed(0, {"a1": x[:400], "a2": x[:400]})
    w2, d2 = cap.feed(400, {"a1": x[400:1000], "a2": x[400:1000]}, entries=[_e(150)])
    assert not d2 and len(w2) == 1 and w2[0].signals["a1"][0] == 150


def test_entry_older_than_history_is_discarded():
    cap = WindowCapture(window_length=100, history_samples=200)
    x = np.arange(1000.0)
    cap.feed(0, {"a1": x[:600], "a2": x[:600]})
    w, d = cap.feed(600, {"a1": x[600:], "a2": x[600:]}, entries=[_e(100)])
    assert not w and d[0].reason == "entry_before_history" and d[0].entry_sample_index == 100


def test_dropped_chunk_discards_open_window():
    cap = WindowCapture(window_length=300)
    x = np.arange(2000.0)
    w, d = cap.feed(0, {"a1": x[:200], "a2": x[:200]}, entries=[_e(100)])
    assert not w and not d
    w, d = cap.feed(400, {"a1": x[400:800], "a2": x[400:800]})      # 200..399 lost
    assert not w and [(q.entry_sample_index, q.reason) for q in d] == [(100, "dropped_chunk")]
    # the stream continues from the new chunk: a later window is fine
    w, d = cap.feed(800, {"a1": x[800:1500], "a2": x[800:1500]}, entries=[_e(900)])
    assert len(w) == 1 and w[0].signals["a1"][0] == 900 and not d


def test_out_of_order_chunk_discards_open_window_and_is_ignored():
    cap = WindowCapture(window_length=300)
    x = np.arange(2000.0)
    cap.feed(0, {"a1": x[:200], "a2": x[:200]}, entries=[_e(100)])
    w, d = cap.feed(0, {"a1": x[:200], "a2": x[:200]})               # duplicate / late chunk
    assert [q.reason for q in d] == ["out_of_order_chunk"]
    w, d = cap.feed(200, {"a1": x[200:900], "a2": x[200:900]}, entries=[_e(300)])
    assert len(w) == 1 and w[0].entry_sample_index == 300 and np.array_equal(w[0].signals["a1"], x[300:600])


def test_sample_period_change_discards():
    cap = WindowCapture(window_length=300)
    x = np.arange(2000.0)
    cap.feed(0, {"a1": x[:200], "a2": x[:200]}, entries=[_e(100)], sample_period_s=2e-5)
    w, d = cap.feed(200, {"a1": x[200:900], "a2": x[200:900]}, sample_period_s=4e-5)
    assert not w and [q.reason for q in d] == ["sample_period_change"]
    w, d = cap.feed(900, {"a1": x[900:1500], "a2": x[900:1500]}, entries=[_e(1000)], sample_period_s=4e-5)
    assert w[0].sample_period_s == 4e-5


def test_windower_with_dropped_chunk_discards_and_recovers():
    sig, dep, _ = _signals(n_periods=4)
    win = BacklashWindower(trigger="contact_loss")
    n = sig["a1"].size
    chunk = 2500
    windows, discarded = [], []
    for lo in range(0, n, chunk):
        if lo == 2500:          # drop 2500..4999: contains the first onset (2500) and its window
            continue
        w, d = win.feed(lo, {k: v[lo:lo + chunk] for k, v in sig.items()})
        windows += w
        discarded += d
    got = [w.entry_sample_index for w in windows]
    assert dep[0][0] not in got                      # never a window across the gap
    assert all(e in got for e, _ in dep[2:])         # the detector re-armed after the gap
    assert any("dropped" in ev for _, ev in win.detector.events)


def test_flush_reports_incomplete():
    sig, dep, _ = _signals(n_periods=1)
    wins, disc = extract_windows({k: v[:dep[1][0] + 1500] for k, v in sig.items()}, return_discarded=True)
    assert [w.entry_sample_index for w in wins] == [dep[0][0]]
    assert [(d.entry_sample_index, d.reason) for d in disc] == [(dep[1][0], "end_of_stream")]


def test_batch_equals_rows():
    s1, dep, _ = _signals()
    s2, _, _ = _signals(width=0.0025)
    batch = {k: np.stack([s1[k], s2[k]]) for k in s1}
    rows = extract_windows_batch(batch, width_m=[0.005, 0.0025], trigger="paper")
    assert [w.entry_sample_index for w in rows[0]] == [w.entry_sample_index for w in
                                                      extract_windows(s1, trigger="paper", width_m=0.005)]
    assert len(rows[1]) == 6


def test_missing_signal_is_an_error():
    with pytest.raises(ValueError, match="signals"):
        WindowCapture().feed(0, {"a1": np.zeros(10)})


def test_window_offset_starts_the_window_after_the_entry_across_chunks():
    sig, dep, _ = _signals()
    for chunk in (333, 5000, sig["a1"].size):
        wins = extract_windows(sig, trigger="contact_loss", chunk_samples=chunk, window_offset_samples=400)
        assert [(w.entry_sample_index, w.kind) for w in wins] == dep
        for w in wins:
            assert w.window_offset_samples == 400 and w.start_sample_index == w.entry_sample_index + 400
            np.testing.assert_array_equal(w.signals["a1"], np.arange(w.start_sample_index, w.start_sample_index + N))


def test_window_offset_validated_and_configured():
    from backlash_monitor.windowing import default_window_offset
    for bad in (-1, 1.5, True, 70000):
        with pytest.raises(ValueError, match="window_offset_samples"):
            WindowCapture(window_offset_samples=bad)
    assert default_window_offset("contact_loss") == 200 and default_window_offset("paper") == 0
