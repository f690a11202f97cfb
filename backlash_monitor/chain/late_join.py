"""LateJoinCheck: did a reader that matched late get its writer's history, or only part of it?

The window topics are transient local (docs/graph.md, ros/qos.py WINDOW_QOS): a reader that matches
a running writer -- a classifier or denoise process restarted in a running graph -- is to receive the
writer's last ``depth`` (1000) windows first, oldest first, then the live ones. Under load it
sometimes does not (docs/graph.md "Not always 0"): its first window is one published after it
subscribed, and the windows before it are never delivered although the writer holds them. Reliable
delivery is in order, so once a later window has come the older ones will not.

What the middleware says of each message (rmw's message info: the writer's publication sequence
number, the source and received time stamps) tells the cases apart:

- the first message is sequence number 1: the writer's whole history from its start (or a writer
  that started after the reader);
- else the history should be the writer's last ``depth`` messages, the first one ``depth`` before the
  newest the writer had published. Which that was is known at the first message *younger* than
  ``live_age_s`` (received minus source time stamp: published after the match, or just before it), at
  the ``depth``-th message, or when the writer falls silent (``silent``). The history is whole when it
  spans at least half the depth (a history cut by the depth spans it all but the last ``live_age_s``
  of messages); a shorter one was passed over: ``passed_over`` counts it, ``missed_before`` is the first
  message's sequence number (the writer's messages before it, within its depth, were not delivered).

The check only tells: every message is handed on as it comes. Asking again (a new subscription, a new
match) was tried and is not done: under load the new subscription got nothing at all (docs/graph.md).
A middleware that gives no sequence number (0 or None), or a sequence that goes back (another writer on
the topic), leaves the history unjudged.
"""
from __future__ import annotations

from dataclasses import dataclass

LIVE_AGE_S = 2.0       # a message published after the match reaches its reader within this; the oldest
                       # of a history is as old as the history's span (minutes of stream for 1000 windows)
WHOLE_SHARE = 0.5      # a history spanning at least this share of the depth is whole


@dataclass
class LateJoinCheck:
    """Judges the history a subscription got (``offer`` each message; ``silent`` when the writer said nothing
    for a while). ``start()`` for a new subscription."""
    depth: int = 1000
    live_age_s: float = LIVE_AGE_S
    passed_over: int = 0              # histories passed over (over the reader's life)
    missed_before: int | None = None  # the last passed-over history's first message's sequence number
    last_span: int | None = None      # the last judged history's span (sequence numbers)
    _state: str = "first"             # "first", "judging", "judged"
    _first_seq: int = 0
    _last_seq: int = 0
    _count: int = 0

    def __post_init__(self):
        if self.depth < 1:
            raise ValueError(f"depth = {self.depth}; allowed: 1 or more")
        if not self.live_age_s > 0:
            raise ValueError(f"live_age_s = {self.live_age_s}; allowed: > 0 s")

    @property
    def judging(self) -> bool:
        return self._state == "judging"

    def start(self) -> None:
        """A new subscription: its history is judged again."""
        self._state = "first"

    def offer(self, sequence_number: int | None, age_s: float | None) -> bool | None:
        """Takes one message's rmw info. -> True when this message showed the history passed over, False when
        it showed it whole, None while undecided or after the judgement."""
        seq = int(sequence_number) if sequence_number else 0
        if self._state == "judged":
            return None
        if self._state == "first":
            if seq <= 1:
                self._state = "judged"
                return False if seq == 1 else None
            self._first_seq = self._last_seq = seq
            self._count = 1
            self._state = "judging"
            return self._judge(seq) if age_s is not None and age_s < self.live_age_s else None
        if seq <= self._last_seq:            # no sequence, or another writer: nothing to judge by
            self._state = "judged"
            return None
        self._last_seq = seq
        self._count += 1
        if (age_s is not None and age_s < self.live_age_s) or self._count >= self.depth:
            return self._judge(seq)
        return None

    def silent(self) -> bool | None:
        """The writer sent nothing for a while: the history is what came (None when not judging)."""
        return self._judge(self._last_seq + 1) if self._state == "judging" else None

    def _judge(self, newest_seq: int) -> bool:
        self._state = "judged"
        self.last_span = newest_seq - self._first_seq
        if self.last_span >= WHOLE_SHARE * self.depth or self._count >= self.depth:
            return False
        self.passed_over += 1
        self.missed_before = self._first_seq
        return True


def age_s(source_timestamp_ns: int | None, received_timestamp_ns: int | None) -> float | None:
    """The message's age on arrival [s] from rmw's time stamps; None when either is missing (0)."""
    if not source_timestamp_ns or not received_timestamp_ns:
        return None
    return (received_timestamp_ns - source_timestamp_ns) * 1e-9
