"""Input faults of the signal chain: their names, a log of them, and the diagnostic level they give.

Every input of a core (a chunk, a joined sample range, a window, a B vector) is checked where it
enters the core; a bad one gets exactly one reaction (docs/windowing.md, "Input faults"):

- dropped and counted under one of :data:`REASONS` (nothing computed from it is published);
- the stream re-synchronised (an index restart) or resumed after the bad range (a gap, a bad
  range: the detector re-arms on the next settled contact, the windows spanning it are discarded);
- reported on ``/diagnostics``: WARN naming the reason while faults keep coming (and for
  ``fault_hold_s`` after the last one), STALE when no input arrived for ``stale_after_s``.

:class:`FaultLog` is what the cores fill (plain Python, no rclpy); :class:`InputHealth` turns a
log and the arrival times of the inputs into a diagnostic level and message for a node.
"""
from __future__ import annotations

import math
from collections import Counter

import numpy as np

# reason -> what it means (the reaction is in docs/windowing.md)
REASONS = {
    # chunks and joined sample ranges (ChunkJoiner, WindowingStage)
    "bad_index": "first_sample_index negative, not an integer or >= 2**53",
    "bad_sample_period": "sample period not a finite number > 0",
    "sample_period_mismatch": "the signals of one sample range have different sample periods",
    "bad_shape": "samples not a 1-D array, or empty",
    "length_mismatch": "the signals of one sample range (or a window's a1 and a2) differ in length",
    "non_finite_samples": "NaN or infinite samples",
    "out_of_range_samples": "an accelerometer sample outside the sensor's declared measurement range "
                            "(config/windowing.yaml sensors.accelerometer_range_m_s2)",
    "wrong_signal": "a recorded chunk whose signal name or unit is not its topic's (offline)",
    "incomplete_range": "not every signal's chunk of a sample range arrived",
    "gap": "samples missing between two ranges (lost chunks)",
    "out_of_order": "a range behind the stream (late or repeated)",
    "stream_restart": "the sample index went back (the drive restarted): re-synchronised",
    # windows (denoise, classifier)
    "wrong_window_length": "a window whose length is not the configured / the library's",
    "wrong_sample_period": "a window whose sample period is not the pattern library's",
    "unknown_entry_kind": "entry kind neither 'onset' nor 'return'",
    "not_denoised": "a raw window on windows/denoised",
    "no_signal": "a window whose a1 or a2 is all zeros (the paper modes' eq. 12 cannot normalise it)",
    "denoise_failed": "the window cannot be denoised with the configured level",
    "non_finite_estimate": "the classifier's B vector or width was not finite (not published)",
    "bad_b_vector": "a B vector of the wrong length, non-finite or negative (not fused)",
    "history_passed_over": "a late reader of a window topic (a restarted node) got the writer's history only from "
                           "its middle or not at all: the windows before it were not delivered "
                           "(chain/late_join.py)",
}

MAX_INDEX = 2 ** 53        # sample indices stay exact as float64 and in numpy int64 arithmetic


def is_index(value) -> bool:
    """A usable first_sample_index: an int (not bool), 0 <= index < 2**53."""
    if type(value) is int:     # the common case, once per chunk: no isinstance chain
        return 0 <= value < MAX_INDEX
    integer = isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))
    return integer and 0 <= int(value) < MAX_INDEX


def is_period(value) -> bool:
    """A usable sample period [s]: a finite float > 0 (and below one hour)."""
    try:
        v = float(value)
    except (TypeError, ValueError):
        return False
    return math.isfinite(v) and 0.0 < v < 3600.0


class FaultLog:
    """Counts input faults per reason and keeps the recent ones (for logging and diagnostics).

    ``add(reason, detail, count=1)``; ``counts`` (Counter by reason), ``total``, ``last``
    ((reason, detail) or None); ``take()`` returns the entries added since the last ``take``.
    """

    def __init__(self, keep: int = 256):
        self.counts: Counter = Counter()
        self.last: tuple[str, str] | None = None
        self._new: list[tuple[str, str]] = []
        self._keep = keep

    def add(self, reason: str, detail: str = "", count: int = 1) -> None:
        if reason not in REASONS:
            raise ValueError(f"fault reason {reason!r}; allowed: {', '.join(REASONS)}")
        self.counts[reason] += count
        self.last = (reason, detail)
        if len(self._new) < self._keep:
            self._new.append((reason, detail))

    @property
    def total(self) -> int:
        return sum(self.counts.values())

    def take(self) -> list[tuple[str, str]]:
        new, self._new = self._new, []
        return new

    def summary(self) -> str:
        return ", ".join(f"{reason} {n}" for reason, n in sorted(self.counts.items())) or "none"


class InputHealth:
    """The diagnostic state of a node's input: STALE / WARN / OK.

    ``arrived(now_s)`` on every input; ``faults(now_s, log)`` after handling it (``log`` the
    cores' FaultLog(s)). ``state(now_s)`` -> (level, message or ""):
    STALE when no input arrived for ``stale_after_s`` (or none yet), WARN while the fault count
    grew within the last ``fault_hold_s``, else OK.
    """

    def __init__(self, stale_after_s: float, fault_hold_s: float, what: str = "input"):
        if not (is_period(stale_after_s) and is_period(fault_hold_s)):
            raise ValueError(f"stale_after_s = {stale_after_s!r}, fault_hold_s = {fault_hold_s!r}: "
                             "allowed: finite numbers > 0")
        self.stale_after_s = float(stale_after_s)
        self.fault_hold_s = float(fault_hold_s)
        self.what = what
        self.last_input_s: float | None = None
        self.last_fault_s: float | None = None
        self.last_fault: tuple[str, str] | None = None
        self._seen = 0

    def arrived(self, now_s: float) -> None:
        self.last_input_s = now_s

    def update(self, now_s: float, *logs: FaultLog) -> bool:
        """Note new faults in ``logs``; True if there were any since the last call."""
        total = sum(log.total for log in logs)
        if total > self._seen:
            self._seen = total
            self.last_fault_s = now_s
            last = [log.last for log in logs if log.last is not None]
            self.last_fault = last[-1] if last else None
            return True
        return False

    def state(self, now_s: float) -> tuple[str, str]:
        if self.last_input_s is None:
            return "STALE", f"no {self.what} yet"
        silent = now_s - self.last_input_s
        if silent > self.stale_after_s:
            return "STALE", f"no {self.what} for {silent:.1f} s"
        if self.last_fault_s is not None and now_s - self.last_fault_s <= self.fault_hold_s:
            reason, detail = self.last_fault or ("?", "")
            return "WARN", f"bad {self.what}: {reason}" + (f" ({detail})" if detail else "")
        return "OK", ""
