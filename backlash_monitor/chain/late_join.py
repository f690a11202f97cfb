"""LateJoinCheck: did a reader that matched late get its writer's history, or only part of it?

The window topics are transient local (docs/graph.md, ros/qos.py WINDOW_QOS): a reader that matches
a running writer -- a classifier or denoise process restarted in a running graph -- is to receive the
writer's last ``depth`` (1000) windows first, oldest first, then the live ones. Under load it
sometimes does not (docs/graph.md "A history passed over"): its first window is a live one, or one
from the middle of the history, and the windows before it are never delivered although the writer
holds them. Reliable delivery is in order, so once a later window has come the older ones will not.

What the middleware says of each message (rmw's message info: the writer's publication sequence
number, the source and received time stamps) tells the cases apart:

- the first message is sequence number 1: the writer's whole history from its start (or a writer
  that started after the reader): handed on at once;
- else the history should be the writer's last ``depth`` messages: the first one ``depth`` before
  the newest the writer had published. Which that was is known when the history has come: at the
  first message *younger* than ``live_age_s`` (received minus source time stamp: published after the
  match, or just before it), at the ``depth``-th message held, or when the writer falls silent. Till
  then the messages are held, in order. The history is whole when it spans at least half the depth
  (a history cut by the depth spans it all but the last ``live_age_s`` of messages); then the held
  messages are handed on, in order, and the rest as they come;
- a shorter span (a first message that is itself live spans 0) means the history was passed over:
  the held messages are dropped and the reader makes a new subscription (a new match, which the
  writer serves with its history again), before it handled any. At most ``max_resubscribes`` times
  in a row; then it hands on what it holds and goes on (``gave_up``).

A middleware that gives no sequence number (0 or None), or a sequence that goes back (another
writer on the topic), is taken as it comes: the check then changes nothing.
"""
from __future__ import annotations

from dataclasses import dataclass, field

LIVE_AGE_S = 2.0       # a message published after the match reaches its reader within this; the oldest
                       # of a history is as old as the history's span (minutes of stream for 1000 windows)
MAX_RESUBSCRIBES = 3   # new subscriptions in a row before the reader goes on with what comes
WHOLE_SHARE = 0.5      # a history spanning at least this share of the depth is whole

PASS = "pass"                # hand this message on
HOLD = "hold"                # kept: the history is not judged yet
RELEASE = "release"          # hand on the held messages (``released``, in order), this one last
RESUBSCRIBE = "resubscribe"  # the history was passed over: drop what is held, subscribe anew


@dataclass
class LateJoinCheck:
    """The decision on each message of a subscription (``offer``; ``silent`` when the writer said nothing
    for a while), and its counts. ``start()`` after every new subscription."""
    depth: int = 1000
    live_age_s: float = LIVE_AGE_S
    max_resubscribes: int = MAX_RESUBSCRIBES
    resubscribes: int = 0          # new subscriptions made so far (over the reader's life)
    in_a_row: int = 0              # of them since the last history taken
    gave_up: int = 0               # histories taken although they were passed over
    last_span: int | None = None   # the last judged history's span (sequence numbers)
    last_release: str = ""         # why the last held messages were handed on: "whole", "gave_up", "unordered"
    released: list = field(default_factory=list)   # RELEASE: the held messages to hand on, in order
    _state: str = "first"
    _held: list = field(default_factory=list)
    _first_seq: int = 0
    _last_seq: int = 0

    def __post_init__(self):
        if self.depth < 1:
            raise ValueError(f"depth = {self.depth}; allowed: 1 or more")
        if not self.live_age_s > 0:
            raise ValueError(f"live_age_s = {self.live_age_s}; allowed: > 0 s")
        if self.max_resubscribes < 0:
            raise ValueError(f"max_resubscribes = {self.max_resubscribes}; allowed: 0 or more")

    @property
    def holding(self) -> bool:
        return self._state == "holding"

    def start(self) -> None:
        """A new subscription: its first message is judged again."""
        self._state, self._held, self.released = "first", [], []

    def offer(self, item, sequence_number: int | None, age_s: float | None) -> str:
        """PASS, HOLD, RELEASE (then ``released`` holds the messages to hand on, in order, ``item`` the last
        of them; after ``silent`` all of them) or RESUBSCRIBE (``item`` and the held ones dropped)."""
        self.released = []
        if self._state == "passing":
            return PASS
        seq = int(sequence_number) if sequence_number else 0
        if self._state == "first":
            if seq <= 1:
                self._state, self.in_a_row = "passing", 0
                return PASS
            self._first_seq = self._last_seq = seq
            self._held = [item]
            self._state = "holding"
            if age_s is not None and age_s < self.live_age_s:
                return self._judge(seq)
            return HOLD
        # holding
        self._held.append(item)
        if seq <= self._last_seq:            # no sequence, or another writer: nothing to judge by
            return self._release("unordered")
        self._last_seq = seq
        if (age_s is not None and age_s < self.live_age_s) or len(self._held) >= self.depth:
            return self._judge(seq)
        return HOLD

    def silent(self) -> str:
        """The writer sent nothing for a while: the history is what came (HOLD when not holding)."""
        if self._state != "holding":
            return HOLD
        return self._judge(self._last_seq + 1)

    def _judge(self, newest_seq: int) -> str:
        self.last_span = newest_seq - self._first_seq
        if self.last_span >= WHOLE_SHARE * self.depth or len(self._held) >= self.depth:
            return self._release("whole")
        if self.in_a_row < self.max_resubscribes:
            self.resubscribes += 1
            self.in_a_row += 1
            self._state, self._held = "first", []
            return RESUBSCRIBE
        self.gave_up += 1
        return self._release("gave_up")

    def _release(self, why: str) -> str:
        """Hand on what is held, in order (the offered message is the last of it)."""
        self.released, self._held, self.last_release = self._held, [], why
        self._state, self.in_a_row = "passing", 0
        return RELEASE


def age_s(source_timestamp_ns: int | None, received_timestamp_ns: int | None) -> float | None:
    """The message's age on arrival [s] from rmw's time stamps; None when either is missing (0)."""
    if not source_timestamp_ns or not received_timestamp_ns:
        return None
    return (received_timestamp_ns - source_timestamp_ns) * 1e-9
