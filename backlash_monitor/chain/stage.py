"""The windowing stage: a joined range checked, placed in its stream, fed to entry detection and
window capture (backlash_monitor.windowing) -- the windowing node's core, live and offline.
"""
from __future__ import annotations

import math

import numpy as np

from backlash_monitor.chain.joiner import MAX_PENDING_RANGES, RESYNC_SAMPLES, JoinedRange
from backlash_monitor.signals import SIGNAL_UNITS
from backlash_monitor.stream_time import sample_time_s, stamp_seconds, stream_origin_s
from backlash_monitor.windowing import DEFAULTS as WINDOWING_DEFAULTS
from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture, default_window_offset
from backlash_monitor.windowing.a1_chain import A1ChainCheck
from backlash_monitor.windowing.faults import FaultLog, is_index, is_period
from backlash_monitor.windowing.saturation import SaturationCounter, SaturationSettings

# After a restart the stage follows the new stream and remembers where the one before it would go
# on. For the next resync_samples fed samples (late chunks of the old stream come far sooner:
# joiner.RESYNC_SAMPLES) it is unsure: a range that continues neither the new stream nor the old
# one (the old stream's late chunk after a lost one, the new stream after a lost chunk, ...) is
# dropped (out_of_order) until this many ranges in a chain continue it, and one continuing the old
# stream until this many in a row: then that stream goes on and the stage switches to it. A stray range
# cannot move the place the stage expects; a clean stream is fed again after at most this many of
# its ranges dropped.
RESTART_CONFIRM_RANGES = 2

# While the stage is unsure (as above), a range that continues the stream followed by its index but
# whose header stamp lies more than this before the time its place in that stream has (the stream's
# time origin from the ranges placed, plus index x period) is a late range of an earlier stream whose
# index happens to fill the new stream's next place (a chunk of the new stream lost), and is judged
# as a range continuing neither. 0.5 s [s]: far above a publisher's stamp jitter (a chunk is stamped
# within milliseconds of its first sample) and below the time a restarted stream needs to begin again
# (a process restart takes seconds: docs/graph.md); a settled stream is never judged by its stamps.
STAMP_BACKSTEP_S = 0.5


class WindowingStage:
    """Entry detection + window capture of one drive (backlash_monitor.windowing).

    ``feed(joined)`` checks the range first (docs/windowing.md, "Input faults") and never raises
    for what is in it: a range with a bad sample period, signals of unequal lengths, missing
    signals or non-finite samples is dropped and counted in ``faults``; the windows spanning it
    are discarded and the detector starts again after it (it re-arms on the next settled
    contact). Samples missing before a range are counted (``gap``, ``lost_samples``); a range
    behind the stream is dropped (``out_of_order``; the open windows keep their samples) unless it
    is a restart of the stream (at index 0, or at least ``resync_samples`` behind): then detector
    and capture start afresh at it (``stream_restart``). A restart that does not start at 0 and
    is less than ``resync_samples`` behind is dropped as out of order until it passes the old
    index: at most ``resync_samples`` samples lost, and counted.

    After a restart two streams may be in play: the new one and late chunks of the one before it
    (reordered best-effort chunks). For the next ``resync_samples`` fed samples the stage is unsure
    which one goes on: it takes a range at once only if it continues the stream it follows
    exactly (no gap); a range continuing the stream before the restart is
    dropped (``out_of_order``) until ``RESTART_CONFIRM_RANGES`` come in a row (then the stage returns
    to it, ``stream_restart``), and a range continuing neither stream, ahead or behind, is dropped
    until ``RESTART_CONFIRM_RANGES`` ranges continue each other from it (then the stage follows
    them: a ``gap`` ahead, a ``stream_restart`` behind) -- a chain behind is forgotten when the
    stream followed goes on. Bad ranges take part with their own reason. The stage remembers the
    stream it left in turn. A stream with only its first range is unsure the same way (that range
    may be a restart whose old stream the stage never saw). Otherwise a range behind the stream is
    dropped (``out_of_order``) and one ahead is a gap, as above. While unsure, a range that continues
    the stream followed by its index but is stamped more than ``STAMP_BACKSTEP_S`` before its place
    (the old stream's late chunk whose index fills the new stream's lost one) continues neither
    stream; ranges without a stamp are placed by their index alone.

    So a stray chunk cannot move the place the stage expects for good: a clean stream after any
    cluster of swaps, gaps, duplicates, index jumps and restarts is fed again after at most
    ``RESTART_CONFIRM_RANGES`` of its ranges are dropped, all counted
    (test/windowing/test_windowing_stream_resume.py) -- when the stage saw the restart or the stream
    start; a stray ahead of a settled stream with no restart before it holds the stream up until it
    passes that place or comes ``resync_samples`` behind it, as before.

    An accelerometer signal (unit m/s^2: a1, a2) with a sample beyond ``accelerometer_range_m_s2``
    (config/windowing.yaml sensors: the sensor's declared measurement range) makes the range
    bad as a non-finite sample does (``out_of_range_samples``). ``fed_samples``: the samples that
    reached the detector.

    The captured signals (a1, a2) are counted for a rail (a clipped sensor) and for a stuck value
    (a dead one) in blocks of 1 s (``saturation``: windowing/saturation.py); every window returned
    carries its samples at a rail found so far, and its stuck ones (``input_saturation``). They are
    not dropped: a clipped window is still a window, flagged.

    ``check_a1_chain``: the motor speed ``omega1`` is an input too, and a1 is checked against r·Ω₁ as the
    samples come (windowing/a1_chain.py, r configured); every window returned carries the check so far
    (``a1_chain``).
    """

    def __init__(self, trigger: str = "contact_loss", width_m: float | None = None,
                 angle_source: str = "measured", window_length: int = 2048,
                 signals=("a1", "a2"), window_offset_samples: int | None = None,
                 faults: FaultLog | None = None, resync_samples: int = RESYNC_SAMPLES,
                 accelerometer_range_m_s2: float | None = None, check_a1_chain: bool = False):
        """``window_offset_samples``: window start after the entry; None = the trigger's configured
        value (config/windowing.yaml capture.window_offset_samples). ``accelerometer_range_m_s2``:
        None = the configured one (sensors.accelerometer_range_m_s2)."""
        if window_offset_samples is None:
            window_offset_samples = default_window_offset(trigger)
        self.detector = BacklashEntryDetector(trigger=trigger, width_m=width_m,
                                              angle_source=angle_source)
        self.capture = WindowCapture(window_length=window_length, signals=tuple(signals),
                                     window_offset_samples=window_offset_samples)
        self.window_offset_samples = self.capture.window_offset_samples
        angle = ("angle_difference",) if angle_source == "measured" else ("omega1", "omega2")
        self.input_signals = tuple(signals) + angle
        self.a1_chain = A1ChainCheck() if check_a1_chain else None
        if self.a1_chain is not None and "omega1" not in self.input_signals:
            self.input_signals += ("omega1",)
        self._input_set = frozenset(self.input_signals)
        self.faults = faults if faults is not None else FaultLog()
        self.resync_samples = int(resync_samples)
        self.lost_samples = 0          # samples never fed: gaps and dropped bad ranges
        self.fed_samples = 0           # samples fed to the detector
        # the captured signals' rails and stuck stretches, counted in blocks (windowing/saturation.py)
        self.saturation = SaturationCounter(tuple(signals), SaturationSettings.from_config(
            WINDOWING_DEFAULTS["saturation"]))
        self._next: int | None = None  # the index the next range should start at
        # while two streams may be in play (after a switch, for resync_samples fed samples):
        self._other_next: int | None = None   # where the stream of before the last switch goes on
        self._other_ranges = 0                # ranges in a row that continued it
        self._strays: dict[int, int] = {}     # ranges ahead continuing neither: end -> ranges in the chain
        self._switch_fed = 0                  # fed_samples at the last switch
        self._fresh = True                    # the stream followed has had no two ranges in a row yet
        self._time_origin_s: float | None = None   # stamp of the stream followed's sample 0 [s], from its ranges
        if accelerometer_range_m_s2 is None:
            accelerometer_range_m_s2 = WINDOWING_DEFAULTS["sensors"]["accelerometer_range_m_s2"]
        limit = float(accelerometer_range_m_s2)
        if not limit > 0:
            raise ValueError(f"accelerometer_range_m_s2 = {accelerometer_range_m_s2!r}; allowed: a number > 0")
        # (signal, limit or None): the accelerometers are checked against their range, the rest for finiteness
        self._sample_checks = tuple((s, limit if SIGNAL_UNITS.get(s) == "m/s^2" else None)
                                    for s in self.input_signals)

    def check(self, joined: JoinedRange, samples: bool = True) -> tuple[str | None, int]:
        """(reason the range is bad or None, its length or -1). ``samples=False``: the range's
        place and shape only, not its sample values (BlockFeeder tests those per block with
        :meth:`samples_good` and checks range by range only a block that fails it)."""
        if not is_index(joined.first_sample_index):
            return "bad_index", -1
        if getattr(joined, "period_mismatch", False):
            n = _common_length(joined.arrays, self.input_signals)
            return "sample_period_mismatch", n
        if not joined.arrays.keys() >= self._input_set:     # a signal missing
            return "incomplete_range", -1
        n = _common_length(joined.arrays, self.input_signals)
        if n == -2:
            return "bad_shape", -1
        if n < 0:
            return "length_mismatch", max(np.asarray(joined.arrays[s]).size for s in self.input_signals)
        if not is_period(joined.sample_period_s):
            return "bad_sample_period", n
        if not samples:
            return None, n
        out_of_range = False
        arrays = joined.arrays
        for s, limit in self._sample_checks:
            x = arrays[s]
            if limit is None:
                if not np.isfinite(x).all():
                    return "non_finite_samples", n
                continue
            low, high = x.min(), x.max()          # NaN propagates into both
            if not (-limit <= low and high <= limit):
                if not (math.isfinite(low) and math.isfinite(high)):
                    return "non_finite_samples", n
                out_of_range = True
        if out_of_range:
            return "out_of_range_samples", n
        return None, n

    def samples_good(self, arrays) -> bool:
        """True when every input signal in ``arrays`` is finite and every accelerometer sample lies
        within ``accelerometer_range_m_s2``: what :meth:`check` finds about the values of each
        range these arrays join. False means at least one range of them is bad (or the test could
        not tell): check them range by range."""
        for s, limit in self._sample_checks:
            x = arrays[s]
            if limit is None:
                if not math.isfinite(x.sum()):    # NaN or inf gives a non-finite sum (so does overflow)
                    return False
            elif not (-limit <= x.min() and x.max() <= limit):   # NaN fails both comparisons
                return False
        return True

    def feed(self, joined: JoinedRange, checked: bool = False):
        """(windows, discarded) completed by this range. ``checked``: :meth:`check` found the range
        good already (BlockFeeder)."""
        first = joined.first_sample_index
        if checked:
            reason, n = None, _common_length(joined.arrays, self.input_signals)
        else:
            reason, n = self.check(joined)
        if not is_index(first):
            self.faults.add(reason or "bad_index", f"range at sample {first!r}")
            return [], []
        first = int(first)
        self._expire()
        verdict = self._judge(first)
        stamp_s = stamp_seconds(joined.stamp)
        backstep_s = self._backstep_s(first, stamp_s, joined.sample_period_s) if verdict == "next" else 0.0
        if backstep_s > STAMP_BACKSTEP_S and n > 0:
            verdict = "stray"
        discarded: list = []
        if verdict == "restart":
            self.faults.add("stream_restart", f"index {first} after {self._next}")
            discarded = self._break("stream_restart", None)
            self._switch()
        elif verdict in ("other", "stray") and n > 0:
            # continues the stream of before the switch, or a range that continued neither stream
            if verdict == "other":
                self._other_next, self._other_ranges = first + n, self._other_ranges + 1
                ranges, where = self._other_ranges, "continues the stream before the restart"
            else:
                ranges = self._strays.pop(first, 0) + 1     # (first == _next: a stamp that stepped back)
                self._strays[first + n] = ranges
                if len(self._strays) > MAX_PENDING_RANGES:
                    del self._strays[next(iter(self._strays))]     # the oldest chain
                where = ("continues neither the stream nor the one before the restart"
                         if backstep_s <= STAMP_BACKSTEP_S else
                         f"continues the stream by its index but is stamped {backstep_s:.3f} s before "
                         f"its place: a late range of an earlier stream")
            if ranges < RESTART_CONFIRM_RANGES:
                self.faults.add(reason or "out_of_order",
                                f"range at sample {first} {where} (expected {self._next})")
                return [], []
            # that stream goes on: switch to it
            if verdict == "stray" and first > self._next:
                self._switch(keep_next=True)    # ahead of the stream: a gap, counted when placed
                self._fresh = False
            else:
                which = "before the restart" if verdict == "other" else "there"
                self.faults.add("stream_restart", f"index {first} after {self._next}: the stream "
                                                  f"{which} goes on")
                discarded = self._break("stream_restart", None)
                self._switch()
        elif verdict == "next":
            # ranges continuing the stream before the switch must come in a row; a stray's followers
            # need not (late chunks of the stream followed may come in between)
            self._other_ranges = 0
            if first == self._next:
                self._fresh = False     # the stream followed has two ranges in a row
        if reason is not None:
            self.faults.add(reason, f"range at sample {first}" + (f", {n} samples" if n >= 0 else ""))
            if n > 0 and verdict != "behind":
                # the range had its place in the stream: resume after it
                discarded += self._break(reason, first + n)
                self._note_gap(first)
                self.lost_samples += n
                self._place(first, n, stamp_s, joined.sample_period_s)
            return [], discarded
        if verdict == "behind":
            # late or repeated: dropped; the open windows keep their (complete) samples
            self.faults.add("out_of_order", f"range at sample {first}, expected {self._next}")
            return [], []
        self._note_gap(first)
        self._place(first, n, stamp_s, joined.sample_period_s)
        self.fed_samples += n
        # the range's samples are known finite here (check, or the block's samples_good): the
        # detector and the capture need not test them again
        entries = self.detector.feed(first, joined.arrays, joined.sample_period_s, finite=True)
        self.saturation.feed(joined.arrays)
        if self.a1_chain is not None and "a1" in joined.arrays:
            self.a1_chain.feed(first, joined.arrays["a1"], joined.arrays["omega1"], joined.sample_period_s,
                               finite=True)
        windows, more = self.capture.feed(first, joined.arrays, entries=entries,
                                          sample_period_s=joined.sample_period_s, finite=True)
        chain = self.a1_chain.result() if self.a1_chain is not None and windows else None
        for window in windows:
            window.input_saturation = self.saturation.check_window(window.signals)
            window.a1_chain = chain
        return windows, discarded + more

    def takes_block(self, first_sample_index: int) -> bool:
        """True when a good range at ``first_sample_index`` continues (or comes after a gap in) a
        settled stream: fed now, and ranges continuing it in one block leave the stage as one by one
        would. Not while the stream is in its first range or two streams may be in play (BlockFeeder
        feeds ranges one by one then), nor for a range the stage drops or that switches streams."""
        if not is_index(first_sample_index) or self._fresh or self._two_streams():
            return False
        return self._judge(int(first_sample_index), two_streams=False) == "next"

    def _two_streams(self) -> bool:
        """Ranges of the stream before the last switch may still come (resync_samples fed since)."""
        return (self._other_next is not None
                and self.fed_samples - self._switch_fed < self.resync_samples)

    def _expire(self) -> None:
        if self._other_next is not None and not self._two_streams():
            self._other_next, self._other_ranges = None, 0
        if self._strays and self._other_next is None and not self._fresh:
            self._strays.clear()

    def _judge(self, first: int, two_streams: bool | None = None) -> str:
        """Where a range at ``first`` belongs: 'next' (starts or continues the stream followed, or
        comes after a gap in it), 'restart' (a new stream, see :meth:`_is_restart`), 'other'
        (continues the stream before the last switch), 'stray' (continues neither while the stream
        followed is unsure: two streams may be in play, or it has only its first range) or 'behind'
        (late or repeated)."""
        if two_streams is None:
            two_streams = self._other_next is not None
        unsure = two_streams or self._fresh
        if self._next is None:
            return "other" if two_streams and first == self._other_next else "next"
        if first == self._next:
            return "next"
        if unsure and first in self._strays:
            return "stray"          # (before 'other': a stray's chain may reach the old stream's place)
        if two_streams and first == self._other_next:
            return "other"
        if first < self._next and self._is_restart(first, 0):
            return "restart"
        if unsure:
            return "stray"
        return "behind" if first < self._next else "next"

    def _backstep_s(self, first: int, stamp_s: float | None, sample_period_s) -> float:
        """How far [s] a range at ``first`` stamped ``stamp_s`` lies before the time of its place in
        the stream followed; 0 when the stage is settled (one stream, two ranges in a row), when
        the range or the stream has no stamp, or the period is bad."""
        if (stamp_s is None or self._time_origin_s is None or self._next is None
                or not (self._fresh or self._two_streams()) or not is_period(sample_period_s)):
            return 0.0
        return sample_time_s(self._time_origin_s, first, sample_period_s) - stamp_s

    def _place(self, first: int, n: int, stamp_s: float | None = None, sample_period_s=None) -> None:
        """The stream goes on at first + n; its time origin (the stamp of its sample 0) from the
        range's stamp when it has one. A stray chain ending there or before is forgotten: the
        stream followed goes on, what continues such a chain is a late or repeated range (and
        BlockFeeder's blocks leave the same chains as the ranges one by one)."""
        self._next = first + n
        if stamp_s is not None and is_period(sample_period_s):
            self._time_origin_s = stream_origin_s(stamp_s, first, sample_period_s)
        if self._strays:
            for end in [e for e in self._strays if e <= first + n]:
                del self._strays[end]

    def _switch(self, keep_next: bool = False) -> None:
        """The stage follows another stream: remember where the one it followed would go on."""
        self._other_next, self._other_ranges = self._next, 0
        self._switch_fed = self.fed_samples     # (the strays stay: a stray may be the stream switched to)
        if not keep_next:
            self._next = None
            self._fresh = True
            self._time_origin_s = None

    def _is_restart(self, first: int, n: int) -> bool:
        """A stream starts at index 0: a range at 0 behind the stream, or one at least
        resync_samples behind it, is a new stream (a late chunk is never that far behind)."""
        return first == 0 or self._next - first >= self.resync_samples

    def _note_gap(self, first: int) -> None:
        if self._next is not None and first > self._next:
            lost = first - self._next
            self.lost_samples += lost
            self.faults.add("gap", f"samples {self._next}..{first - 1} ({lost}) missing")

    def _break(self, reason: str, resume_at: int | None) -> list:
        """Discard the open windows with ``reason``; detector and capture start afresh (at
        ``resume_at``, or at the next range when None)."""
        discarded = self.capture._discard_all(reason)
        self.detector._reset(stream_start=reason == "stream_restart")
        self.detector._next_index = resume_at
        self.capture._next = resume_at
        if resume_at is not None:
            self.capture._restart(resume_at)
        return discarded


def _common_length(arrays, names) -> int:
    """Common length of the named 1-D arrays; -1 when they differ, -2 when one is not 1-D or empty."""
    n = -1
    for name in names:
        a = arrays.get(name)
        if a is None:
            continue
        if type(a) is not np.ndarray:    # (an array as is: no np.asarray call per range)
            a = np.asarray(a)
        if a.ndim != 1 or a.size == 0:
            return -2
        if n >= 0 and a.size != n:
            return -1
        n = a.size
    return n
