"""a1 against the recorded motor speed (windowing/a1_chain.py): from the kinematics a1 = r·dΩ₁/dt (SPEC section 2).

The motions here are written as closed forms (a speed ripple, strokes, a backlash crossing's jolt) with their exact
derivatives, not simulated; a drive of the independent simulator (foreign_drives/) is checked in
test/offline/test_analyze_a1_chain.py."""
import math

import numpy as np
import pytest

from backlash_monitor.windowing.a1_chain import MAX_MISMATCH, MIN_SPAN_S, A1ChainCheck

R = 0.15          # drive-wheel radius [m]
DT = 2e-5         # 50 kHz


def motion(duration_s: float = 2.0):
    """(Ω₁ [rad/s], dΩ₁/dt [rad/s²]): a 150 rad/s drive with 4 strokes per second (a smooth pulse of the load),
    a 37 Hz ripple and a sharp jolt at each stroke (a contact closing within 2 ms)."""
    t = np.arange(int(round(duration_s / DT))) * DT
    w = 150.0 + 1.5 * np.sin(2 * np.pi * 4 * t) + 0.3 * np.sin(2 * np.pi * 37 * t + 0.4)
    dw = 1.5 * 2 * np.pi * 4 * np.cos(2 * np.pi * 4 * t) + 0.3 * 2 * np.pi * 37 * np.cos(2 * np.pi * 37 * t + 0.4)
    phase = (t * 4) % 1.0
    s = 2e-3 * 4        # the jolt's width in stroke phase (2 ms)
    jolt = np.exp(-0.5 * ((phase - 0.5) / s) ** 2)
    w = w + 0.4 * np.cumsum(jolt) * DT * 500
    dw = dw + 0.4 * jolt * 500
    return w, dw


def check_of(a1, omega1, chunk: int = 0, first: int = 0):
    c = A1ChainCheck(R)
    if chunk:
        for i in range(0, a1.size, chunk):
            c.feed(first + i, a1[i:i + chunk], omega1[i:i + chunk], DT)
    else:
        c.feed(first, a1, omega1, DT)
    return c.result()


def test_a1_that_is_the_motor_speeds_derivative_follows_it():
    w, dw = motion()
    r = check_of(R * dw, w)
    assert r.checked and not r.faulty
    assert r.mismatch < 0.01 and r.gain == pytest.approx(1.0, abs=0.01)


@pytest.mark.parametrize("gain", [0.8, 0.95, 1.05, 1.3])
def test_a_wrong_sensitivity_is_its_own_share_of_the_motion(gain):
    """No gain is fitted: a1 = g·r·dΩ₁/dt misses (g − 1) of the motor's velocity variation."""
    w, dw = motion()
    r = check_of(gain * R * dw, w)
    assert r.mismatch == pytest.approx(abs(gain - 1.0), abs=0.01)
    assert r.gain == pytest.approx(gain, abs=0.01)
    assert r.faulty == (abs(gain - 1.0) > MAX_MISMATCH)


def test_a_quadratic_characteristic_is_found():
    """y = x + x²/a_q (a1's amplifier distorting): its even part is motion the motor never made."""
    w, dw = motion()
    x = R * dw
    r = check_of(x + x ** 2 / 30.0, w)      # the jolt (30 m/s²) read 2x
    assert r.faulty, r


def test_an_offset_and_noise_on_a1_do_not_count():
    """A constant offset integrates to a straight line (removed per segment); white noise integrates to little."""
    w, dw = motion()
    rng = np.random.default_rng(3)
    r = check_of(R * dw + 3.0 + rng.normal(0.0, 1.0, dw.size), w)
    assert not r.faulty and r.mismatch < 0.02


@pytest.mark.parametrize("lag_s", [0.5e-3, 2e-3, 8e-3, 30e-3])
def test_a_filtered_speed_signal_is_a_lag_not_a_wrong_a1(lag_s):
    """A drive's speed estimate is filtered (here a first-order filter): the check tries such lags on either side."""
    w, dw = motion(duration_s=4.0)
    a = math.exp(-DT / lag_s)
    from scipy.signal import lfilter
    filtered = lfilter([1 - a], [1, -a], w, zi=[a * w[0]])[0]
    plain = check_of(R * dw, filtered)
    assert not plain.faulty and plain.mismatch < 0.02
    assert plain.lag.startswith("speed")


@pytest.mark.parametrize("bits,filter_s", [(14, 0.0), (12, 0.0), (12, 5e-3)])
def test_a_quantised_encoder_speed_is_not_a_wrong_a1(bits, filter_s):
    """Ω₁ from an encoder's counts differenced over 1 ms (and a first-order speed filter): far noisier than a1 in
    acceleration; the noise is not coherent with a1, so it does not bias the transfer estimate."""
    w, dw = motion(duration_s=4.0)
    angle = np.cumsum(w) * DT
    q = 2 * np.pi / 2 ** bits
    counts = np.floor(angle / q)
    k = 50
    speed = np.empty_like(w)
    speed[k:] = (counts[k:] - counts[:-k]) * q / (k * DT)
    speed[:k] = speed[k]
    if filter_s:
        from scipy.signal import lfilter
        a = math.exp(-DT / filter_s)
        speed = lfilter([1 - a], [1, -a], speed, zi=[a * speed[0]])[0]
    r = check_of(R * dw, speed)
    assert not r.faulty and r.mismatch < 0.03, r


def test_fed_in_chunks_it_finds_what_it_finds_at_once():
    w, dw = motion()
    x = 1.2 * R * dw
    whole, chunks = check_of(x, w), check_of(x, w, chunk=777)
    assert chunks.seconds == whole.seconds
    assert chunks.mismatch == pytest.approx(whole.mismatch, rel=1e-9)


def test_a_gap_starts_a_new_piece_and_no_segment_spans_it():
    """Two ranges with samples missing between them: a1's integral is not carried over the gap (it would jump)."""
    w, dw = motion(duration_s=4.0)
    c = A1ChainCheck(R)
    half = w.size // 2
    c.feed(0, R * dw[:half], w[:half], DT)
    c.feed(half + 5000, R * dw[half + 5000:], w[half + 5000:], DT)   # 0.1 s lost
    r = c.result()
    assert not r.faulty and r.mismatch < 0.01


def test_too_short_or_without_motion_it_is_not_checked():
    w, dw = motion(duration_s=MIN_SPAN_S - 0.1)
    short = check_of(R * dw * 2.0, w)
    assert not short.checked and not short.faulty and math.isnan(short.mismatch)
    steady = check_of(np.zeros(100_000), np.full(100_000, 150.0))
    assert not steady.checked and not steady.faulty


def test_a_radius_that_is_not_a_number_is_refused():
    with pytest.raises(ValueError, match="radius_m"):
        A1ChainCheck(0.0)
