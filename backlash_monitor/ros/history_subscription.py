"""HistorySubscription: a transient-local subscription that says when a late reader's history was passed over.

The live shell of chain/late_join.py (the rule, and why). Attached to a host node like diagnostic_updater's
Updater: ``HistorySubscription(node, BacklashWindow, "windows/denoised", node.on_window)``. Every message goes
to ``callback(msg)`` as it comes; what rmw says of it (its publication sequence number, its source and received
time stamps) goes to the check, and a timer judges the history when the writer falls silent for ``SILENCE_S``.
A history passed over is logged once as a warning, added to the host's input FaultLog ``faults`` as
``history_passed_over`` (the messages before ``check.missed_before`` named as not delivered), and ``on_passed_over()``
is called (the host refreshes its ``/diagnostics``).
"""
from __future__ import annotations

import time

from backlash_monitor.chain.late_join import LateJoinCheck, age_s
from backlash_monitor.ros.qos import WINDOW_QOS

SILENCE_S = 5.0          # a history still unjudged is judged when the writer sent nothing for this long [s]
SILENCE_CHECK_S = 1.0    # how often the timer looks [s]


class HistorySubscription:
    def __init__(self, node, msg_type, topic: str, callback, qos=WINDOW_QOS, faults=None, on_passed_over=None):
        self.node = node
        self.topic = topic
        self.callback = callback
        self.faults = faults
        self.on_passed_over = on_passed_over
        self.check = LateJoinCheck(depth=qos.depth)
        self._first = None               # the first message's (sequence number, age [s])
        self._last_message = time.monotonic()
        self.subscription = node.create_subscription(msg_type, topic, self._on_message, qos)
        node.create_timer(SILENCE_CHECK_S, self._look)

    def _on_message(self, msg, info) -> None:
        self._last_message = time.monotonic()
        if self.check.judging or self._first is None:
            info = info or {}
            seq = info.get("publication_sequence_number")
            age = age_s(info.get("source_timestamp"), info.get("received_timestamp"))
            if self._first is None:
                self._first = (seq, age)
                self.node.get_logger().info(f"{self.topic}: first message: sequence number {seq}, "
                                            f"{'-' if age is None else f'{age:.3f} s'} old")
            self._judged(self.check.offer(seq, age))
        self.callback(msg)

    def _look(self) -> None:
        if self.check.judging and time.monotonic() - self._last_message > SILENCE_S:
            self._judged(self.check.silent())

    def _judged(self, passed_over: bool | None) -> None:
        if passed_over:
            self.report_passed_over()

    def report_passed_over(self) -> None:
        """What the check judged passed over (its ``missed_before``, ``last_span``): logged, a fault, the host told."""
        seq, age = self._first or (self.check.missed_before, None)
        self.node.get_logger().warning(
            f"{self.topic}: the writer's history was passed over: the first message came with sequence number "
            f"{seq} ({'-' if age is None else f'{age:.1f} s'} old), its history spanning {self.check.last_span} of "
            f"the last {self.check.depth}; the writer's messages before it were not delivered (docs/graph.md "
            "\"Not always 0\")")
        if self.faults is not None:
            self.faults.add("history_passed_over", f"{self.topic} before sequence number {self.check.missed_before}")
        if self.on_passed_over is not None:
            self.on_passed_over()
