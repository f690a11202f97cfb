"""LateJoinCheck: did a reader that matched late get its writer's history, or only what came after?

The window topics are transient local (docs/graph.md, ros/qos.py WINDOW_QOS): a reader that matches
a running writer -- a classifier or denoise process restarted in a running graph -- is to receive the
writer's last 1000 windows first, oldest first, then the live ones. Under load it sometimes gets none
of them (docs/graph.md "Not always 0"): its first window is a live one, and the windows published
while it was down are never delivered although the writer holds them. Reliable delivery is in order,
so once a live window has come the older ones will not.

The first message after a subscription is made tells which case it is, from what the middleware says
of it (rmw's message info):

- its publication sequence number is 1: the writer's whole history from its start (or a writer that
  started after the reader);
- it is older than ``LIVE_AGE_S`` (received minus source time stamp): it is history. A history that
  starts later than sequence number 1 is one the writer's depth cut (1000 windows: minutes of
  stream), so its oldest window is that old;
- else (a later sequence number, and as young as a live window) the history was passed over: the
  reader makes a new subscription (a new match, which the writer serves with its history again) and
  drops that first message, before it handled any. At most ``MAX_RESUBSCRIBES`` times in a row; then
  it goes on with what comes and says so (``gave_up``).

A middleware that gives no sequence number or time stamps (0 or None) is taken as it comes: the
check then changes nothing.
"""
from __future__ import annotations

from dataclasses import dataclass

LIVE_AGE_S = 2.0       # a live window reaches its reader within this (docs/graph.md "A history passed
                       # over"); the oldest of a history cut by its depth is minutes of stream old
MAX_RESUBSCRIBES = 3   # new subscriptions in a row before the reader goes on with what comes

ACCEPT = "accept"
RESUBSCRIBE = "resubscribe"


@dataclass
class LateJoinCheck:
    """The decision on the first message of each subscription (``first``), and its counts."""
    live_age_s: float = LIVE_AGE_S
    max_resubscribes: int = MAX_RESUBSCRIBES
    resubscribes: int = 0          # new subscriptions made so far (all of them, over the reader's life)
    in_a_row: int = 0              # of them since the last accepted first message
    gave_up: int = 0               # first messages taken although the history was passed over
    last_skipped_sequence: int | None = None   # the first message's sequence number when it asked again

    def __post_init__(self):
        if not self.live_age_s > 0:
            raise ValueError(f"live_age_s = {self.live_age_s}; allowed: > 0 s")
        if self.max_resubscribes < 0:
            raise ValueError(f"max_resubscribes = {self.max_resubscribes}; allowed: 0 or more")

    def is_history(self, sequence_number: int | None, age_s: float | None) -> bool | None:
        """True: the first message is the start of the writer's history; False: a live one after a
        passed-over history; None: the middleware does not say."""
        if not sequence_number or sequence_number < 1:
            return None
        if sequence_number == 1:
            return True
        if age_s is None:
            return None
        return age_s >= self.live_age_s

    def first(self, sequence_number: int | None, age_s: float | None) -> str:
        """ACCEPT (handle this message and what follows) or RESUBSCRIBE (drop it and subscribe anew)."""
        history = self.is_history(sequence_number, age_s)
        if history is False and self.in_a_row < self.max_resubscribes:
            self.resubscribes += 1
            self.in_a_row += 1
            self.last_skipped_sequence = sequence_number
            return RESUBSCRIBE
        if history is False:
            self.gave_up += 1
        self.in_a_row = 0
        return ACCEPT


def age_s(source_timestamp_ns: int | None, received_timestamp_ns: int | None) -> float | None:
    """The message's age on arrival [s] from rmw's time stamps; None when either is missing (0)."""
    if not source_timestamp_ns or not received_timestamp_ns:
        return None
    return (received_timestamp_ns - source_timestamp_ns) * 1e-9
