"""HistorySubscription: a transient-local subscription that makes sure a late reader got its writer's history.

The live shell of chain/late_join.py (the rule, and why). Attached to a host node like diagnostic_updater's
Updater: ``HistorySubscription(node, BacklashWindow, "windows/denoised", node.on_window)``. Each message goes
through the check with what rmw says of it (its publication sequence number, its source and received time
stamps): handed on to ``callback(msg)`` at once, or held till the history is judged and then handed on in
order, or -- the history passed over -- dropped with the messages held, and the subscription made anew (a new
match: the writer serves its history again). A timer judges a held history when the writer falls silent for
``SILENCE_S``. The host's ``/diagnostics`` reports ``check.resubscribes`` and ``check.gave_up``.
"""
from __future__ import annotations

import time

from backlash_monitor.chain.late_join import HOLD, PASS, RESUBSCRIBE, LateJoinCheck, age_s
from backlash_monitor.ros.qos import WINDOW_QOS

SILENCE_S = 5.0          # a held history is judged when the writer sent nothing for this long [s]
SILENCE_CHECK_S = 1.0    # how often the timer looks [s]


class HistorySubscription:
    def __init__(self, node, msg_type, topic: str, callback, qos=WINDOW_QOS, check: LateJoinCheck | None = None):
        self.node = node
        self.msg_type = msg_type
        self.topic = topic
        self.callback = callback
        self.qos = qos
        self.check = check or LateJoinCheck(depth=qos.depth)
        self._made = 0                 # subscriptions made; the current one's number
        self._first = None             # the current subscription's first message: (sequence number, age)
        self._last_message = time.monotonic()
        self.subscription = self._subscribe()
        node.create_timer(SILENCE_CHECK_S, self._look)

    def _subscribe(self):
        self._made += 1
        self._first = None
        self.check.start()
        made = self._made
        return self.node.create_subscription(self.msg_type, self.topic,
                                             lambda msg, info: self._on_message(made, msg, info), self.qos)

    def _on_message(self, made: int, msg, info) -> None:
        if made != self._made:     # a replaced subscription's message, taken before its destruction took effect
            return
        self._last_message = time.monotonic()
        info = info or {}
        seq = info.get("publication_sequence_number")
        age = age_s(info.get("source_timestamp"), info.get("received_timestamp"))
        if self._first is None:
            self._first = (seq, age)
            self.node.get_logger().info(f"{self.topic}: first message: sequence number {seq}, "
                                        f"{'-' if age is None else f'{age:.3f} s'} old")
        self._act(self.check.offer(msg, seq, age), msg)

    def _look(self) -> None:
        if self.check.holding and time.monotonic() - self._last_message > SILENCE_S:
            self._act(self.check.silent(), None)

    def _act(self, decision: str, msg) -> None:
        if decision == PASS:
            self.callback(msg)
            return
        if decision == HOLD:
            return
        if decision == RESUBSCRIBE:
            seq, age = self._first
            self.node.get_logger().warning(
                f"{self.topic}: the writer's history was passed over (the first message sequence number {seq}, "
                f"{'-' if age is None else f'{age:.3f} s'} old, spanning {self.check.last_span} of its last "
                f"{self.check.depth}): subscribing again ({self.check.in_a_row} of {self.check.max_resubscribes})")
            old = self.subscription
            self.subscription = self._subscribe()
            self.node.destroy_subscription(old)
            return
        released = self.check.released
        if self.check.last_release == "gave_up":
            self.node.get_logger().warning(
                f"{self.topic}: the writer's history was passed over {self.check.max_resubscribes + 1} times; "
                f"going on with the {len(released)} messages held (what the writer published before them is "
                "not handled)")
        for held in released:
            self.callback(held)
