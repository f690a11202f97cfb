"""ResendOnMatch: a window publisher that sends its recent windows again when a reader matches.

The window topics are reliable and transient local (docs/graph.md "QoS"): a reader that matches late
(a node restarted in a running graph) should get the writer's last 1000 windows from the DDS history.
Under load it sometimes gets none of them. Measured with `bench/_reliability/under_load.py` (the classifier killed 10
times at x2 beside a CPU hog, 2ae9ad2): in 1 run of 4 a restarted classifier's first estimate was fused over
1 event, 18 s of stream after the last one before the kill, and 138 onsets were never classified although the
denoise node had published their windows. Fast DDS has known reports of this race: a late
joiner that receives a live sample before the writer's heartbeat takes that sample's sequence number as its
start and never asks for the history (eProsima/Fast-DDS issues 2387 and 3822).

So the writer does not rely on it alone. It keeps the last ``depth`` messages it published and, when its
matched-reader count grows, publishes them again, oldest first, twice: ``RESEND_AFTER_S`` (1 and 5 s) after the
match, in slices of ``SLICE`` windows per ``TICK_S``. They are new samples with new sequence numbers, delivered like live ones. Not at once: a match is
two-sided, the writer counts the reader before the reader has matched the writer back, and what comes in between is
dropped on the reader's side (docs/graph.md, the plant's ``match_settle_s``). Measured with a single re-send at the
match (the same bench, 4 runs with a third busy loop): in 1 run a restarted classifier got the re-sent windows only
from 2.75 s of stream after the oldest on, and 10 onsets were lost; under load the reader can take seconds to match
back, hence the later re-send. Not all at once either: three re-sends of up to 1000 windows each in one callback
(0.5, 2 and 8 s) stalled the chain in 2 of 5 runs (a restarted classifier got no window at all for minutes; in one
run the windowing node stopped at 548 windows). Not through the live writer either: re-sent in slices through it, 1
run of 11 still had a restarted classifier get no window for minutes. A burst through the live writer turns its
1000-deep history over within seconds, while a new reader is still asking it for that history: our reading (not
traced in Fast DDS's source) is that the reader then waits for samples the writer no longer holds, and a reliable
reader delivers nothing after a hole (eProsima/Fast-DDS issue 2387 and the late-joiner GAP fixes of PR 1295). So the
re-send goes through a second writer on the same topic (``resend_publisher``, its own history of ``RESEND_DEPTH``):
whatever happens to a reader's exchange with it, the live writer's stream is not touched. Every reader sees them twice (from the history or live, and now again): the
denoise and classifier nodes skip a window they have seen (classifier/repeats.py). A reader that lost the history
may get the re-sent windows after a few newer ones; the classifier fuses them in the order they arrive, and
width_trend ignores an estimate older than its open period (fleet/trend.py).

Attaches to a host node as diagnostic_updater's Updater does: ``ResendOnMatch(node, msg_type, topic, qos)``,
then ``.publish(msg)`` in place of the publisher's. A published message is kept by reference: the host must not
change it afterwards.
"""
from __future__ import annotations

import time
from collections import deque

from rclpy.event_handler import PublisherEventCallbacks
from rclpy.qos import HistoryPolicy, QoSProfile

RESEND_AFTER_S = (1.0, 5.0)   # after a reader matched [s]: the reader matches back within a second when idle,
                              # within seconds under load; each re-send costs every reader a skip per window
SLICE = 50                    # windows published per timer tick while a re-send runs (1.6 MB at 2048 samples)
TICK_S = 0.1                  # the timer's period while a re-send is due or running [s]
RESEND_DEPTH = 4 * SLICE      # the re-send writer's own history: the slices a slow reader may still be taking


class ResendOnMatch:
    """A publisher that keeps its last ``depth`` messages and sends them again when a new reader matches."""

    def __init__(self, node, msg_type, topic: str, qos, depth: int | None = None,
                 resend_after_s: tuple[float, ...] = RESEND_AFTER_S):
        depth = qos.depth if depth is None else depth
        if depth < 0:
            raise ValueError(f"depth = {depth}; allowed: 0 (send nothing again) or more")
        self.node = node
        self.kept: deque = deque(maxlen=depth)
        self.resend_after_s = tuple(sorted(resend_after_s))
        self.due: list[float] = []  # time.monotonic() of the re-sends still to come
        self.sending: list = []     # the re-send under way: what is left of it, oldest first
        self.started_s = 0.0
        self.resent = 0            # messages sent again, in all
        self.matches = 0           # times a reader matched
        self.publisher = node.create_publisher(msg_type, topic, qos,
                                               event_callbacks=PublisherEventCallbacks(matched=self.on_matched))
        # the re-sent windows' own writer, of the same reliability and durability (a reader's QoS must match it)
        self.resend_publisher = node.create_publisher(
            msg_type, topic, QoSProfile(depth=RESEND_DEPTH, reliability=qos.reliability, durability=qos.durability,
                                        history=HistoryPolicy.KEEP_LAST))
        self.timer = node.create_timer(TICK_S, self.on_timer)
        self.timer.cancel()        # runs only while a re-send is due or under way

    def publish(self, msg) -> None:
        self.publisher.publish(msg)
        if self.kept.maxlen:
            self.kept.append(msg)

    def on_matched(self, info) -> None:
        """A reader matched (current_count_change > 0): the kept messages are due again at each delay."""
        if info.current_count_change <= 0:
            return
        self.matches += 1
        if not self.kept.maxlen:
            return
        now = time.monotonic()
        self.due = sorted(set(self.due) | {now + delay for delay in self.resend_after_s})
        self.timer.reset()

    def on_timer(self) -> None:
        """Publish the next slice of a re-send under way, or start one that is due. In slices, so that the node's
        own input is served in between (a re-send of 1000 windows at once kept the executor for seconds under
        load)."""
        now = time.monotonic()
        if not self.sending and self.due and self.due[0] <= now:
            while self.due and self.due[0] <= now:   # several due at once (a slow executor): one re-send
                self.due.pop(0)
            self.sending, self.started_s = list(self.kept), now
        if self.sending:
            part, self.sending = self.sending[:SLICE], self.sending[SLICE:]
            for msg in part:
                self.resend_publisher.publish(msg)
            self.resent += len(part)
            if not self.sending:
                self.node.get_logger().info(
                    f"a reader of {self.publisher.topic_name} matched: sent the last windows again "
                    f"({self.resent} in all, this one in {time.monotonic() - self.started_s:.1f} s)",
                    throttle_duration_sec=5.0)
        if not self.due and not self.sending:
            self.timer.cancel()
