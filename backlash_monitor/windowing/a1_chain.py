"""Does a1 read the motor side's motion? a1 against the recorded motor speed (no rclpy).

a1 is the acceleration of the drive wheel's circumference on the motor side: a1 = r·dΩ₁/dt (SPEC section 2), with
r the drive-wheel radius. A recording that holds both a1 and the motor speed Ω₁ (an encoder or resolver) can so
check a1's own sensor chain: integrated, a1 must give the velocity r·Ω₁ up to a constant. An accelerometer whose
chain distorts (a quadratic or compressing characteristic, a gain that an automatic gain control moves, a wrong
sensitivity) does not; the width the classifier reads from a1's windows is then off by about as much (the width is a
kinematic quantity: the gap the motor side crosses), and so is the width read from both accelerometers together.

How, and why so:
- **In velocity.** v = ∫a1 dt and w = r·Ω₁, both as block means of ``DECIMATE_S``. Differentiating a quantised
  encoder's speed gives noise far above a1's; integrating a1 does not.
- **As a transfer function, w over v.** The stream is cut into spans of up to ``SEGMENT_S`` (a parabola removed
  from each: a1's offset integrates to a straight line, an offset drifting at a steady rate to a parabola; Hann
  window). Their cross and auto spectra, averaged over ``SMOOTH_HZ`` of neighbouring frequencies, give
  G(f) = S_vw/S_vv: the H1 estimate, which noise in the speed signal does not bias (it is not coherent with a1). A
  sound chain has G = 1 at every frequency the motion has; a sensitivity g has G = 1/g; a distortion or a moving
  gain puts into a1 motion the speed never had.
- **Lags are allowed, gains are not.** A drive's speed signal is often filtered (a moving average over the
  encoder's counts, a first-order speed filter) and an accelerometer may carry a low-pass of its own: a lag, not a
  wrong reading of the motion. The mismatch is the smallest, over a moving average or a first-order lag L(f) of
  time constant T (``MAX_LAG_S`` at most) put on either side, of

      mismatch² = Σ_f S_L(f)·|1 − G_L(f)|²  /  Σ_f S_L(f)·|G_L(f)|²     (2 Hz ≤ f ≤ ``MAX_FREQUENCY_HZ``)

  with G_L the transfer from the lagged side to the other and S_L the lagged side's spectrum, both averaged AFTER
  the lag is put on (a lag turns the cross spectrum's phase across the averaging band; averaging the turning phase
  first read a 20 ms speed filter as 0.06-0.11). So 0.1 means that a tenth of the motor's motion, as the speed reads
  it, is not in a1; a 10 % sensitivity error gives 0.1. No gain is fitted, so a wrong sensitivity stays visible
  (``gain`` reports it). A lag's memory across a span's ends biases by about lag/span (1.5 % for 30 ms).

Measured on the independent simulator's recordings (138 of its spent and development recordings; docs/classifier.md
5.4): every clean drive 0.0007-0.0015 (14- and 16-bit encoders among them), every other mechanism 0.0021 at most
but an a1 auto-ranging amplifier and an a1 crossover dead zone (0.038, 0.051) and the two a1 chains that were far off,
a telemetry AGC and a quadratic characteristic (0.17, 0.64; their widths from a1 1.5 and 4.2 mm off, from a2 0.04 and
0.01 mm). What it cannot see: a distortion of a motion that is not periodic is partly incoherent with a1, as noise
is, and is then under-counted (the check errs towards "sound"); a fault above ``MAX_FREQUENCY_HZ`` (a resonance of
a1's bracket) is not in it.

The check needs the motor speed: the caller makes none without it. It runs as the samples come (``feed``:
contiguous ranges; a gap closes the span, none spans it) with a fixed memory (the open span's block means), and its
figure so far, over the spans compared, is ``result()`` (NaN before the first span of ``SEGMENT_S`` with motion).
10 s of stream cost about 14 ms of CPU.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from backlash_monitor.windowing.config import DEFAULTS

DECIMATE_S = 5e-4         # block means of this span [s] (25 samples at 50 kHz): a 2 kHz velocity
SEGMENT_S = 2.0           # the stream is compared in spans of up to this long [s]; a lag's memory crossing a span's
                          # ends biases the transfer estimate by about lag/span (1.5 % for a 30 ms speed filter)
SMOOTH_HZ = 8.0           # the spectra are averaged over this band [Hz] (as Welch averages over segments): what
                          # makes the transfer estimate robust to the speed signal's noise
MAX_FREQUENCY_HZ = 100.0  # compared up to here: the strokes and the ripple of the motion as a speed signal follows
                          # it; above, encoders' speed filters leave little to compare (200 Hz read the same figures
                          # on the spent rows and the closed forms, at 1.3x the cost)
MIN_FREQUENCY_HZ = 2.0    # from here: below, the span's parabola has taken the motion out (and an offset drift's)
MAX_LAG_S = 0.05          # the longest lag tried [s]: a drive's speed filter (count averages of 0.5-2 ms, first-order
                          # filters up to tens of ms) or an accelerometer's low-pass
LAG_STEPS = 50            # the lags tried: 0 and log-spaced from 0.1 ms to MAX_LAG_S, on either side, both kinds
                          # (a first-order speed filter between two of them reads at most 0.022; 40 read 0.046)
MIN_SPAN_S = 1.5          # a piece's last span shorter than this (cut by a gap) is not compared
MIN_MOTION_M_S = 1e-3     # a span whose velocity varies less than this (rms, detrended) [m/s]: not compared
# a1 does not read the motor's motion when more than this share of it is not in a1. The measured figures above: sound
# chains below 0.01, the two chains that were far off far above; a 10 % sensitivity error (on a 5-9 mm drive, half a
# millimetre and more of a kinematic width) is 0.1.
MAX_MISMATCH = 0.1


@dataclass(frozen=True)
class A1ChainResult:
    """What the check found so far."""
    mismatch: float          # share of the motor's motion not in a1 (NaN: not checked)
    gain: float              # a1's motion over the speed's at the best lag (NaN: not checked)
    lag: str                 # the lag that fitted best ("none", "speed: 1 ms average", "a1: 2 ms lag")
    seconds: float           # the stream compared [s]
    radius_m: float = math.nan   # the r of r·Ω₁ [m]

    @property
    def checked(self) -> bool:
        return math.isfinite(self.mismatch)

    @property
    def faulty(self) -> bool:
        """a1 does not read the motor's motion (``MAX_MISMATCH``)."""
        return self.checked and self.mismatch > MAX_MISMATCH

    def text(self) -> str:
        """The finding in words, for a width's line."""
        if not self.checked:
            return "a1 not checked against the motor speed"
        if self.faulty:
            return (f"a1 does not follow r·dΩ₁/dt (r = {self.radius_m:g} m): {self.mismatch:.0%} of the motor's "
                    f"motion is not in it (gain {self.gain:.2f}, over {self.seconds:.1f} s)")
        return f"a1 follows the motor speed ({self.mismatch:.1%} not in it, over {self.seconds:.1f} s)"

    def as_dict(self) -> dict:
        return {"mismatch": self.mismatch, "gain": self.gain, "lag": self.lag, "seconds": self.seconds,
                "radius_m": self.radius_m, "faulty": self.faulty, "max_mismatch": MAX_MISMATCH,
                "text": self.text()}


def _lags():
    return np.concatenate(([0.0], np.geomspace(1e-4, MAX_LAG_S, LAG_STEPS - 1)))


@functools.lru_cache(maxsize=1)
def _lag_names() -> list:
    return _responses(np.zeros(1))[0]


@functools.lru_cache(maxsize=8)
def _responses_on_grid(m: int, step_s: float, top: int) -> tuple[list, np.ndarray]:
    """``_responses`` on the first ``top`` frequencies of an ``m``-point real FFT at ``step_s`` (spans of one length
    share it: cached)."""
    return _responses(np.fft.rfftfreq(m, step_s)[:top])


def _responses(f: np.ndarray) -> tuple[list, np.ndarray]:
    """(names, responses[k, f]): no lag, then each lag as a moving average and as a first-order lag."""
    names, rows = ["none"], [np.ones_like(f, dtype=complex)]
    for lag in _lags()[1:]:
        x = np.pi * f * lag
        names.append(f"{lag * 1e3:.3g} ms average")
        rows.append(np.exp(-1j * x) * np.sinc(f * lag))
        names.append(f"{lag * 1e3:.3g} ms lag")
        rows.append(1.0 / (1.0 + 2j * x))
    return names, np.array(rows)


class A1ChainCheck:
    """a1 against r·Ω₁, fed as the samples come (see the module docstring)."""

    def __init__(self, radius_m: float | None = None):
        """``radius_m``: the drive-wheel radius r [m]; None: the configured one (config/windowing.yaml detector
        radius_m), as every caller in the project takes it."""
        if radius_m is None:
            radius_m = DEFAULTS["detector"]["radius_m"]
        if not (isinstance(radius_m, (int, float)) and math.isfinite(radius_m) and radius_m > 0):
            raise ValueError(f"radius_m = {radius_m!r}; allowed: a number > 0 [m]")
        self.radius_m = float(radius_m)
        self._period: float | None = None
        self._q = 1                               # samples per block mean
        self._next: int | None = None             # the sample index the piece goes on at
        self._v = 0.0                             # a1's running integral [m/s] at the piece's last sample
        self._rest = (np.zeros(0), np.zeros(0))   # samples not yet in a whole block (a1, Ω₁)
        self._weights = np.ones(1)
        self._span: list = [[], []]               # the open span's block means (lists of arrays: v, w)
        self._span_n = 0
        self._sums = None                         # per lag tried (on a1's side, then the speed's): Σ S·|1 − G|²,
                                                  # Σ S·|G|², Σ S·Re G over the closed spans (S: the lagged a1's spectrum)
        self.seconds = 0.0                        # stream compared in closed spans [s]
        self._cached: A1ChainResult | None = None  # result() of the spans so far (None: a span was added since)

    def feed(self, first_sample_index: int, a1_m_s2, omega1_rad_s, sample_period_s: float,
             finite: bool = False) -> None:
        """A contiguous range of samples (a1 [m/s²], Ω₁ [rad/s]). A range that does not continue the last one, comes
        at another sample period or holds a sample that is not finite starts a new piece. ``finite``: the caller
        checked the samples already (the windowing stage)."""
        a = np.asarray(a1_m_s2, dtype=float)
        w = np.asarray(omega1_rad_s, dtype=float)
        n = min(a.size, w.size)
        if n == 0 or not (finite or (math.isfinite(float(a[:n].sum())) and math.isfinite(float(w[:n].sum())))):
            self._new_piece()
            return
        if self._period != sample_period_s or first_sample_index != self._next:
            self._new_piece()
            self._period = float(sample_period_s)
            self._q = max(1, int(round(DECIMATE_S / self._period)))
            q = self._q
            self._weights = (q - np.arange(q)) / q * self._period    # a sample's share in its block's mean of ∫a1
        self._next = int(first_sample_index) + n
        a, w = a[:n], w[:n]
        q = self._q
        rest_a, rest_w = self._rest
        if rest_a.size:                      # complete the open block first (a copy of at most q samples)
            take = min(q - rest_a.size, n)
            rest_a = np.concatenate((rest_a, a[:take]))
            rest_w = np.concatenate((rest_w, w[:take]))
            a, w = a[take:], w[take:]
            if rest_a.size < q:
                self._rest = (rest_a, rest_w)
                return
            self._blocks(rest_a[None, :], rest_w[None, :])
        whole = (a.size // q) * q
        if whole:
            self._blocks(a[:whole].reshape(-1, q), w[:whole].reshape(-1, q))
        self._rest = (a[whole:].copy(), w[whole:].copy())

    def _blocks(self, A: np.ndarray, Wq: np.ndarray) -> None:
        """Whole blocks (rows of q samples): the block means of a1's running integral (rectangular steps: a constant
        half-sample shift, absorbed as a lag) and of r·Ω₁; whole spans compared as they fill."""
        sums = A.sum(axis=1) * self._period
        ends = self._v + np.cumsum(sums)
        self._v = float(ends[-1])
        self._span[0].append(ends - sums + A @ self._weights)
        self._span[1].append(self.radius_m * Wq.mean(axis=1))
        self._span_n += A.shape[0]
        m = self._span_blocks()
        if self._span_n >= m:
            bv, bw = np.concatenate(self._span[0]), np.concatenate(self._span[1])
            cut = (bv.size // m) * m
            for k in range(0, cut, m):                     # spans of exactly m blocks (one FFT grid: cached)
                self._add_span(bv[k:k + m], bw[k:k + m])
            self._span, self._span_n = [[bv[cut:]], [bw[cut:]]], bv.size - cut

    def _span_blocks(self) -> int:
        return max(8, int(round(SEGMENT_S / self._step_s())))

    def _step_s(self) -> float:
        return self._q * (self._period or DECIMATE_S)

    def _new_piece(self) -> None:
        self._close_span()
        self._next, self._v = None, 0.0
        self._rest = (np.zeros(0), np.zeros(0))

    def _close_span(self) -> None:
        if self._span_n:
            self._add_span(np.concatenate(self._span[0]), np.concatenate(self._span[1]))
        self._span, self._span_n = [[], []], 0

    def _add_span(self, v: np.ndarray, w: np.ndarray) -> None:
        sums = self._compare(v, w)
        if sums is not None:
            self._sums = sums[:3] if self._sums is None else tuple(a + b for a, b in zip(self._sums, sums[:3]))
            self.seconds += sums[3]
            self._cached = None

    def _compare(self, v: np.ndarray, w: np.ndarray):
        """One span's sums (see the module docstring), or None when it is too short or the motor barely moves."""
        step_s = self._step_s()
        m = v.size
        if m * step_s < MIN_SPAN_S:
            return None
        t = np.linspace(-1.0, 1.0, m)
        design = np.column_stack([t * t, t, np.ones(m)])
        coef_v, *_ = np.linalg.lstsq(design, v, rcond=None)
        coef_w, *_ = np.linalg.lstsq(design, w, rcond=None)
        v, w = v - design @ coef_v, w - design @ coef_w
        if not np.sqrt(np.mean(w ** 2)) > MIN_MOTION_M_S:
            return None
        window = np.hanning(m)
        FV, FW = np.fft.rfft(v * window), np.fft.rfft(w * window)
        f = np.fft.rfftfreq(m, step_s)
        k = max(1, int(round(SMOOTH_HZ * m * step_s)))        # bins averaged (a Daniell window)
        top = min(f.size, int(np.searchsorted(f, MAX_FREQUENCY_HZ, side="right")) + k)
        f, FV, FW = f[:top], FV[:top], FW[:top]
        _, L = _responses_on_grid(m, step_s, top)
        cross = np.conj(FV) * FW
        auto = np.abs(FV) ** 2
        # the band's frequencies, every other one: the averaged spectra change little from one to the next (each is
        # the mean over SMOOTH_HZ), so the sums lose nothing but half their cost
        band = np.flatnonzero((f >= MIN_FREQUENCY_HZ) & (f <= MAX_FREQUENCY_HZ))[::2]
        if not band.size:
            return None
        # each lag put on its side BEFORE the spectra are averaged over neighbouring frequencies: a lag turns the
        # cross spectrum's phase across the band (30 ms: 0.4 rad over 2 Hz), and averaging a turning phase would bias
        # the transfer estimate's size by as much as the mismatch it is to find
        on_a1 = (_smooth(np.conj(L) * cross[None, :], k), _smooth(np.abs(L) ** 2 * auto[None, :], k))
        on_speed = (_smooth(L * cross[None, :], k), np.broadcast_to(_smooth(auto[None, :], k), L.shape))
        sums = []
        for sxy, sxx in (on_a1, on_speed):
            sxy, sxx = sxy[:, band], sxx[:, band]
            g = sxy / np.where(sxx > 0, sxx, np.inf)
            sums.append((np.sum(sxx * np.abs(1.0 - g) ** 2, axis=1), np.sum(sxx * np.abs(g) ** 2, axis=1),
                         np.sum(sxx * np.real(g), axis=1)))
        num, den, re = (np.concatenate(x) for x in zip(*sums))
        return num, den, re, m * step_s

    def result(self) -> A1ChainResult:
        """The check over the spans compared so far (each closed at SEGMENT_S of stream, or at a gap): NaN before the
        first."""
        if self._cached is not None:
            return self._cached
        if self._sums is None or not (self._sums[1] > 0).all():
            self._cached = A1ChainResult(math.nan, math.nan, "", 0.0, self.radius_m)
            return self._cached
        num, den, re = self._sums
        ratio = num / den
        names = _lag_names()
        k = int(np.argmin(ratio))
        side = "speed" if k < len(names) else "a1"     # a lag on a1's velocity means the speed is the one filtered
        words = "none" if k % len(names) == 0 else f"{side}: {names[k % len(names)]}"
        # a1's motion over the speed's at that lag: v·L ≈ gain·w, so gain = Σ S·Re G / Σ S·|G|² (G = 1/gain)
        self._cached = A1ChainResult(float(math.sqrt(ratio[k])), float(re[k] / den[k]), words, float(self.seconds),
                                     self.radius_m)
        return self._cached


def _smooth(x: np.ndarray, k: int) -> np.ndarray:
    """Rows of ``x`` averaged over ``k`` neighbouring frequencies (centred; over fewer at the ends)."""
    n = x.shape[1]
    before = k // 2
    c = np.zeros((x.shape[0], n + k + 1), dtype=x.dtype)
    np.cumsum(x, axis=1, out=c[:, before + 1:before + 1 + n])
    c[:, before + 1 + n:] = c[:, before + n:before + n + 1]
    return (c[:, k:k + n] - c[:, :n]) / _counts(n, k)


@functools.lru_cache(maxsize=8)
def _counts(n: int, k: int) -> np.ndarray:
    """How many of the n frequencies each centred window of k holds."""
    idx = np.arange(n)
    return (np.clip(idx - k // 2 + k, 0, n) - np.clip(idx - k // 2, 0, n)).astype(float)
