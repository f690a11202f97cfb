"""The signal chain's stages as plain objects (no rclpy), shared by the nodes and ``analyze``.

The windowing, denoise and classifier nodes are thin shells over these; ``python -m
backlash_monitor analyze`` runs the same stages over a bag's messages in the order they were
received, so the offline estimates equal the live ones exactly.

- :class:`ChunkJoiner` joins the per-signal chunks of one sample range (a drive's signals arrive on
  separate topics) and gives up on ranges that stay incomplete.
- :class:`WindowingStage` feeds joined ranges to the entry detector and the window capture.
- :class:`BlockFeeder` (offline) feeds contiguous ranges to a WindowingStage in blocks, with
  the same windows as one by one.
- :func:`denoise_pair` denoises a window's a1 and a2 together (one call, as the node does);
  :func:`denoise_pairs` (offline) many windows in one batch, with the same results.
- :func:`estimate_record` (offline) the whole chain over one drive's record held in arrays:
  the windows and the estimates the live graph publishes for it.
"""
from __future__ import annotations

import bisect
import math
from dataclasses import dataclass

import numpy as np

from backlash_monitor.denoise import DEFAULT_MODE, denoise_sym5, max_level
from backlash_monitor.windowing.faults import MAX_INDEX, FaultLog, is_index, is_period
from backlash_monitor.windowing.saturation import SaturationCounter, SaturationSettings
from backlash_monitor.signals import SIGNAL_UNITS
from backlash_monitor.windowing import DEFAULTS as WINDOWING_DEFAULTS
from backlash_monitor.windowing import BacklashEntryDetector, WindowCapture, default_window_offset

MAX_PENDING_RANGES = 16
# A node that joins chunks from queues deeper than that waits for a range as long as its missing
# chunk can still be waiting in one (pending_ranges_for): on a reliable topic a chunk comes late,
# never not at all, and under load the signals' topics run seconds apart (docs/graph.md, "While a
# consumer is away").


def pending_ranges_for(queue_depth: int) -> int:
    """Ranges a joiner keeps waiting for their missing chunks when each signal's chunks come
    through a queue of ``queue_depth``: that many (a chunk still in its queue can be that far
    behind the other signals'), at least MAX_PENDING_RANGES (best effort's 5-deep queue: a lost
    chunk never comes, a late one is a few ranges behind)."""
    return max(MAX_PENDING_RANGES, int(queue_depth))
# A range that starts this far (or more) behind the expected index is a restart of the stream (a
# drive restarted, its index counts from 0 again), not a late chunk: 1 s at 50 kHz, far more than
# any reordering of best-effort chunks (MAX_PENDING_RANGES ranges of 1000 samples at most).
RESYNC_SAMPLES = 50_000
# After a restart the stage follows the new stream and remembers where the one before it would go
# on. For the next resync_samples fed samples (late chunks of the old stream come far sooner, as
# above) it is unsure: a range that continues neither the new stream nor the old one (the old
# stream's late chunk after a lost one, the new stream after a lost chunk, ...) is dropped
# (out_of_order) until this many ranges in a chain continue it, and one continuing the old stream
# until this many in a row: then that stream goes on and the stage switches to it. A stray range
# cannot move the place the stage expects; a clean stream is fed again after at most this many of
# its ranges dropped.
RESTART_CONFIRM_RANGES = 2
DENOISE_DEFAULTS = dict(level=6, details_removed=(1, 2, 3, 4, 5, 6), mode=DEFAULT_MODE)


@dataclass
class JoinedRange:
    first_sample_index: int
    sample_period_s: float
    arrays: dict
    stamp: object = None     # the first signal's header stamp, when the caller has one
    frame_id: str = ""
    period_mismatch: bool = False   # the signals came with different sample periods


class ChunkJoiner:
    """Collects one chunk of each of ``signals`` per first_sample_index; returns complete ranges.

    A range still incomplete while more than ``max_pending`` ranges wait is dropped (counted in
    ``dropped_ranges`` and in ``faults`` as ``incomplete_range``); the window capture then sees the
    gap and discards the windows spanning it. A chunk whose index is not an integer in
    0..2**53 is dropped at once (``bad_index``): it cannot be placed in the stream. Everything
    else about the samples (period, lengths, values) is checked by :class:`WindowingStage`,
    which knows the range's place in the stream. A chunk at index 0 (or RESYNC_SAMPLES behind)
    after complete ranges is a restarted stream: the incomplete ranges still waiting are dropped
    first (counted), so that no old chunk is joined with a new one.
    """

    def __init__(self, signals, max_pending: int = MAX_PENDING_RANGES, faults: FaultLog | None = None):
        self.signals = tuple(signals)
        self.max_pending = max_pending
        self.pending: dict[int, dict] = {}
        self.meta: dict[int, tuple] = {}
        self.dropped_ranges = 0
        self.faults = faults if faults is not None else FaultLog()
        self._end: int | None = None    # end of the last complete range (restart detection)
        self._dropped_up_to: int | None = None  # the last range dropped incomplete (late chunks)
        self.pending_max = 0            # most ranges that waited at once (how far the topics ran apart)

    def add(self, name: str, first_sample_index: int, sample_period_s: float, samples,
            stamp=None, frame_id: str = "") -> JoinedRange | None:
        if name not in self.signals:
            return None
        if not is_index(first_sample_index):
            self.faults.add("bad_index", f"{name} chunk at index {first_sample_index!r}")
            return None
        first_sample_index = int(first_sample_index)
        if self._end is not None and first_sample_index < self._end and (
                first_sample_index == 0 or self._end - first_sample_index >= RESYNC_SAMPLES):
            # the stream restarted: an old incomplete range must not be completed by new chunks
            self._drop_pending("stream restart")
            self._end = None
            self._dropped_up_to = None
        if (self._dropped_up_to is not None and first_sample_index not in self.pending
                and first_sample_index <= self._dropped_up_to
                and (first_sample_index > 0 or self._end is None)
                and self._dropped_up_to - first_sample_index < RESYNC_SAMPLES):
            self.faults.add("out_of_order", f"{name} chunk at sample {first_sample_index}: its "
                            "range was dropped incomplete before it came")
            return None
        try:
            array = np.asarray(samples, dtype=np.float64)
        except (TypeError, ValueError):
            array = np.full(1, np.nan)   # not numbers: the stage drops the range as non-finite
        group = self.pending.setdefault(first_sample_index, {})
        group[name] = array
        if name == self.signals[0] or first_sample_index not in self.meta:
            self.meta[first_sample_index] = (sample_period_s, stamp, frame_id)
        if name != self.signals[0]:
            group.setdefault("__periods__", {})[name] = sample_period_s
        if len(group) - ("__periods__" in group) < len(self.signals):
            self.pending_max = max(self.pending_max, len(self.pending))
            if len(self.pending) > self.max_pending:
                oldest = min(self.pending)
                del self.pending[oldest]
                self.meta.pop(oldest, None)
                self.dropped_ranges += 1
                self._dropped_up_to = max(oldest, self._dropped_up_to or 0)
                self.faults.add("incomplete_range", f"range at sample {oldest}")
            return None
        del self.pending[first_sample_index]
        self._end = first_sample_index + int(array.size)
        periods = group.pop("__periods__", {})
        period, stamp, frame_id = self.meta.pop(first_sample_index)
        joined = JoinedRange(first_sample_index, period, group, stamp, frame_id)
        if any(p != period and not (_isnan(p) and _isnan(period)) for p in periods.values()):
            joined.sample_period_s = math.nan      # the stage drops it: sample_period_mismatch
            joined.period_mismatch = True
        return joined

    def add_rows(self, signal, first_sample_index, sample_period_s, samples,
                 meta) -> list[JoinedRange] | None:
        """What :meth:`add` returns, chunk by chunk, for chunks that come as whole ranges one after
        the other -- each signal's chunk of a range, in any order, then the next range's, at an
        index at or past the end of the one before (the way a recorder writes a drive's topics):
        the complete ranges, the joiner left as those adds leave it. None when they do not come
        that way (the first range behind the end of the last one completed before, too), or a
        chunk is irregular (an index that is not usable, a range whose chunks' periods or
        lengths differ, no samples), or ranges are waiting already: then nothing is done (add
        them one by one, which counts what is wrong). Called again for the next chunks, it goes
        on where the adds or the call before ended.

        ``signal``: each chunk's signal, as its index in ``signals`` (an int array);
        ``first_sample_index`` and ``sample_period_s``: numpy arrays of theirs (unsigned ints,
        floats); ``samples``: their float64 arrays; ``meta(i)``: (stamp, frame_id) of chunk i,
        asked for each range's first signal (``signals[0]``), whose stamp a range keeps as with
        ``add``."""
        width = len(self.signals)
        codes = np.asarray(signal)
        n = codes.size
        if (self.pending or n == 0 or n % width or len(samples) != n
                or codes.dtype.kind not in "ui"):
            return None
        codes = codes.reshape(-1, width)
        firsts = np.asarray(first_sample_index)
        periods = np.asarray(sample_period_s, dtype=np.float64).reshape(-1, width)
        sizes = np.array([a.size for a in samples]).reshape(-1, width)
        if firsts.dtype.kind not in "ui":
            return None
        firsts = firsts.reshape(-1, width)
        starts = firsts[:, 0]
        if not ((np.sort(codes, axis=1) == np.arange(width)).all()
                and (firsts == starts[:, None]).all() and (starts >= 0).all()
                and (starts < MAX_INDEX).all() and (periods == periods[:, :1]).all()
                and (sizes == sizes[:, :1]).all() and (sizes > 0).all()):
            return None
        starts = starts.astype(np.int64)
        if (starts[1:] < starts[:-1] + sizes[:-1, 0]).any() or (
                self._end is not None and starts[0] < self._end):
            return None       # a range behind the end of the one before: a restart or a repeat
        signals = self.signals
        firsts, period_list = starts.tolist(), periods[:, 0].tolist()
        if (codes == codes[0]).all():    # every range's signals come in one order (a recorder's)
            row = codes[0].tolist()
            order, head = [signals[k] for k in row], row.index(0)
            ranges = [JoinedRange(first, period, dict(zip(order, samples[at:at + width])),
                                  *meta(at + head))
                      for first, period, at in zip(firsts, period_list, range(0, n, width))]
        else:
            ranges = []
            for r, (first, row, period) in enumerate(zip(firsts, codes.tolist(), period_list)):
                at = r * width
                # the signals as they came (the dict's order, as add's)
                group = dict(zip([signals[k] for k in row], samples[at:at + width]))
                ranges.append(JoinedRange(first, period, group, *meta(at + row.index(0))))
        self._end = int(starts[-1]) + int(sizes[-1, 0])
        return ranges

    def flush(self) -> int:
        """End of the stream: the ranges still incomplete are dropped and counted
        (``incomplete_range``); returns how many."""
        return self._drop_pending("end of stream")

    def _drop_pending(self, why: str) -> int:
        n = len(self.pending)
        for first in sorted(self.pending):
            self.faults.add("incomplete_range", f"range at sample {first} ({why})")
        self.dropped_ranges += n
        self.pending.clear()
        self.meta.clear()
        return n


def _isnan(value) -> bool:
    try:
        return math.isnan(value)
    except TypeError:
        return False


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
    dropped (``out_of_order``) and one ahead is a gap, as above.

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
    """

    def __init__(self, trigger: str = "contact_loss", width_m: float | None = None,
                 angle_source: str = "measured", window_length: int = 2048,
                 signals=("a1", "a2"), window_offset_samples: int | None = None,
                 faults: FaultLog | None = None, resync_samples: int = RESYNC_SAMPLES,
                 accelerometer_range_m_s2: float | None = None):
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
                ranges = self._strays.pop(first, 0) + 1     # (first == _next is 'next')
                self._strays[first + n] = ranges
                if len(self._strays) > MAX_PENDING_RANGES:
                    del self._strays[next(iter(self._strays))]     # the oldest chain
                where = "continues neither the stream nor the one before the restart"
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
                self._place(first, n)
            return [], discarded
        if verdict == "behind":
            # late or repeated: dropped; the open windows keep their (complete) samples
            self.faults.add("out_of_order", f"range at sample {first}, expected {self._next}")
            return [], []
        self._note_gap(first)
        self._place(first, n)
        self.fed_samples += n
        # the range's samples are known finite here (check, or the block's samples_good): the
        # detector and the capture need not test them again
        entries = self.detector.feed(first, joined.arrays, joined.sample_period_s, finite=True)
        self.saturation.feed(joined.arrays)
        windows, more = self.capture.feed(first, joined.arrays, entries=entries,
                                          sample_period_s=joined.sample_period_s, finite=True)
        for window in windows:
            window.input_saturation = self.saturation.check_window(window.signals)
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

    def _place(self, first: int, n: int) -> None:
        """The stream goes on at first + n. A stray chain ending there or before is forgotten: the
        stream followed goes on, what continues such a chain is a late or repeated range (and
        BlockFeeder's blocks leave the same chains as the ranges one by one)."""
        self._next = first + n
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


class BlockFeeder:
    """Offline (``analyze``): feeds a :class:`WindowingStage` contiguous joined ranges merged into
    blocks of up to ``block_samples`` samples, giving the same windows, in the same order, as
    feeding the ranges one by one (the live node's way) -- with far fewer Python calls.

    Exact because the detector and the capture are chunk-invariant for measured angles (every
    decision is a search over the stream, the contact tracker's state carries over exactly;
    test_analyze_chunk_invariance.py checks it on plant data). Integrated angles (a running sum,
    whose rounding depends on the chunking) and irregular ranges (a gap, an out-of-order or
    repeated range, another sample period, unequal lengths) are fed one by one, after the block
    before them, and so are the ranges while the stage is unsure which stream to follow
    (:meth:`WindowingStage.takes_block`).

    ``add(joined)`` / ``flush()`` -> (list of (window, range), discarded): ``range`` is the
    joined range whose feed completes the window when fed one by one (its stamp/frame_id).
    """

    def __init__(self, stage: WindowingStage, block_samples: int = 65536):
        self.stage = stage
        self.block_samples = (int(block_samples) if stage.detector.angle_source == "measured"
                              else 0)
        self._pending: list[JoinedRange] = []
        self._n = 0

    def add(self, joined: JoinedRange):
        """(list of (window, range), discarded) completed by ``joined``. The sample values of a
        block are tested once, when the block is fed (:meth:`WindowingStage.samples_good`); a block
        that fails it is added again range by range with the full check, as if its bad range had
        been seen when it came: the same windows, discards and faults."""
        return self._add(joined, exact=False)

    def _add(self, joined: JoinedRange, exact: bool):
        windows, discarded = [], []
        reason, n = self.stage.check(joined, samples=exact)
        period = joined.sample_period_s
        regular = self.block_samples > 0 and reason is None
        if self._pending:
            last = self._pending[-1]
            if not (regular and joined.first_sample_index == last.first_sample_index + self._last_n
                    and period == last.sample_period_s
                    and joined.arrays.keys() == last.arrays.keys()):
                windows, discarded = self._flush(exact, whole=True)
        if regular and not self._pending and not self._accepts(joined):
            regular = False     # dropped, switching or unsure: one by one, followers must not merge
        if not regular:
            # its values are known good only after the full check (exact)
            w, d = self._feed([joined], checked=exact and reason is None)
            return windows + w, discarded + d
        self._pending.append(joined)
        self._last_n = n
        self._n += n
        if self._n >= self.block_samples:
            w, d = self._flush(exact, whole=False)
            windows += w
            discarded += d
        return windows, discarded

    def _accepts(self, joined: JoinedRange) -> bool:
        """The range may head a block (WindowingStage.takes_block); else it is fed alone."""
        return self.stage.takes_block(joined.first_sample_index)

    def flush(self):
        return self._flush(exact=False, whole=True)

    def _flush(self, exact: bool, whole: bool):
        """Feed the pending block. Not ``exact``: its values are tested first; when they fail,
        its ranges are added again with the full check (range by range, as they came), and the
        ranges left pending after that are fed too when ``whole``."""
        ranges, self._pending, self._n = self._pending, [], 0
        if not ranges:
            return [], []
        block = self._join(ranges)
        if exact or self.stage.samples_good(block.arrays):
            return self._feed(ranges, checked=True, block=block)
        windows, discarded = [], []
        for r in ranges:
            w, d = self._add(r, exact=True)
            windows += w
            discarded += d
        if whole:
            w, d = self._flush(exact=True, whole=True)
            windows += w
            discarded += d
        return windows, discarded

    @staticmethod
    def _join(ranges: list[JoinedRange]) -> JoinedRange:
        if len(ranges) == 1:
            return ranges[0]
        first = ranges[0]
        return JoinedRange(first.first_sample_index, first.sample_period_s,
                           {k: np.concatenate([r.arrays[k] for r in ranges]) for k in first.arrays},
                           first.stamp, first.frame_id)

    def _feed(self, ranges: list[JoinedRange], checked: bool, block: JoinedRange | None = None):
        if block is None:
            block = self._join(ranges)
        windows, discarded = self.stage.feed(block, checked=checked)
        if len(ranges) == 1:
            return [(w, block) for w in windows], discarded
        # one by one, a window comes out of the feed of the range holding both its confirmation
        # (when the detector reports the entry) and its last sample; stable: same order then
        starts = [r.first_sample_index for r in ranges]
        length = self.stage.capture.window_length
        done = [max(w.start_sample_index + length - 1, w.confirm_sample_index
                    if w.confirm_sample_index is not None else w.entry_sample_index)
                for w in windows]
        at = [max(0, bisect.bisect_right(starts, d) - 1) for d in done]
        order = sorted(range(len(windows)), key=lambda i: at[i])
        return [(windows[i], ranges[at[i]]) for i in order], discarded


def check_window_pair(a1, a2, level: int = DENOISE_DEFAULTS["level"],
                      window_length: int | None = None) -> str | None:
    """The reason a window's (a1, a2) cannot be denoised (or classified), or None: both 1-D of one
    length (``window_length`` when given), long enough for ``level``, finite (input_faults.REASONS)."""
    try:
        a1 = np.asarray(a1, dtype=np.float64)
        a2 = np.asarray(a2, dtype=np.float64)
    except (TypeError, ValueError):
        return "non_finite_samples"
    if a1.ndim != 1 or a2.ndim != 1:
        return "bad_shape"
    if a1.size != a2.size:
        return "length_mismatch"
    if window_length is not None and a1.size != window_length:
        return "wrong_window_length"
    if a1.size == 0 or max_level(a1.size) < level:
        return "wrong_window_length"
    if not (np.isfinite(a1).all() and np.isfinite(a2).all()):
        return "non_finite_samples"
    return None


def denoise_checked(a1, a2, **options):
    """``((a1, a2), None)`` denoised, or ``(None, reason)``: the window is checked first
    (:func:`check_window_pair`) and a result that is not finite (finite samples near the float
    limit can overflow the transform) is refused as ``denoise_failed``. The denoise node's core."""
    level = options.get("level", DENOISE_DEFAULTS["level"])
    reason = check_window_pair(a1, a2, level=level)
    if reason is not None:
        return None, reason
    try:
        with np.errstate(over="ignore", invalid="ignore"):
            clean = denoise_pair(a1, a2, **options)
    except ValueError:
        return None, "denoise_failed"
    if not (np.isfinite(clean[0]).all() and np.isfinite(clean[1]).all()):
        return None, "denoise_failed"
    return clean, None


def denoise_pair(a1, a2, **options):
    """sym5 denoising of a window's a1 and a2 in one call; returns (a1, a2)."""
    clean = denoise_sym5(np.stack([np.asarray(a1, dtype=np.float64),
                                   np.asarray(a2, dtype=np.float64)]),
                         **{**DENOISE_DEFAULTS, **options})
    return clean[0], clean[1]


def denoise_pairs(pairs, **options) -> list[tuple[np.ndarray, np.ndarray]]:
    """:func:`denoise_pair` of many windows' (a1, a2) in one batched transform (offline).

    pywt transforms every row of a 2-D batch with the same 1-D routine, so each result is bit for
    bit the window's own ``denoise_pair`` (test_chain_denoise_pairs.py); windows of unequal
    lengths are denoised pair by pair."""
    pairs = [(np.asarray(a1, dtype=np.float64), np.asarray(a2, dtype=np.float64))
             for a1, a2 in pairs]
    shapes = {a.shape for pair in pairs for a in pair}
    if len(pairs) < 2 or len(shapes) != 1 or len(next(iter(shapes))) != 1:
        return [denoise_pair(a1, a2, **options) for a1, a2 in pairs]
    rows = np.stack([a for pair in pairs for a in pair])          # a1, a2, a1, a2, ...
    clean = denoise_sym5(rows, **{**DENOISE_DEFAULTS, **options})
    return [(clean[2 * i], clean[2 * i + 1]) for i in range(len(pairs))]


def denoising_label(level: int, details_removed, mode: str) -> str:
    return (f"sym5 level {level}, details {','.join(map(str, details_removed))} removed, "
            f"mode {mode}")


def estimate_record(signals, sample_period_s: float, estimator, trigger: str = "contact_loss",
                    width_m: float | None = None, window_offset_samples: int | None = None,
                    first_sample_index: int = 0):
    """The chain over one drive's record held in arrays (no bag, no DDS): windowing (with its
    sensor offset estimate), denoising, ``estimator`` (a DriveEstimator; its fusion goes on from
    its state). ``signals``: 1-D arrays of one length, a1, a2 and angle_difference (measured
    angles) or omega1 and omega2 (integrated). Returns [(window, [WidthEstimate, ...])] for every
    window in stream order ([] for the ones not classified: returns, the first onset)."""
    angle = "measured" if "angle_difference" in signals else "integrated"
    stage = WindowingStage(trigger=trigger, width_m=width_m, angle_source=angle,
                           window_offset_samples=window_offset_samples)
    arrays = {name: np.ascontiguousarray(signals[name], dtype=np.float64)
              for name in stage.input_signals}
    windows, _ = stage.feed(JoinedRange(int(first_sample_index), float(sample_period_s), arrays))
    onsets = [w for w in windows if estimator.classifies(w.kind)]
    denoised = denoise_pairs([(w.signals["a1"], w.signals["a2"]) for w in onsets])
    results = estimator.estimate_many([(a1, a2, w.kind, w.sample_period_s, w.sensor_offsets)
                                       for w, (a1, a2) in zip(onsets, denoised)])
    by_window = {id(w): r for w, r in zip(onsets, results)}
    return [(w, by_window.get(id(w), [])) for w in windows]
