"""HistorySubscription: a transient-local subscription that makes sure a late reader got its writer's history.

The live shell of chain/late_join.py (the rule, and why). Attached to a host node like diagnostic_updater's
Updater: ``HistorySubscription(node, BacklashWindow, "windows/denoised", node.on_window)``. The first message
of each subscription is checked from rmw's message info (its publication sequence number, its source and
received time stamps); when the history was passed over, that message is dropped and the subscription made
anew (a new match: the writer serves its history again). Every other message goes to ``callback(msg)``
unchanged. The host's ``/diagnostics`` reports ``check.resubscribes`` and ``check.gave_up``.
"""
from __future__ import annotations

from backlash_monitor.chain.late_join import RESUBSCRIBE, LateJoinCheck, age_s
from backlash_monitor.ros.qos import WINDOW_QOS


class HistorySubscription:
    def __init__(self, node, msg_type, topic: str, callback, qos=WINDOW_QOS, check: LateJoinCheck | None = None):
        self.node = node
        self.msg_type = msg_type
        self.topic = topic
        self.callback = callback
        self.qos = qos
        self.check = check or LateJoinCheck()
        self._made = 0              # subscriptions made; the current one's number
        self._first_pending = True  # the current subscription's first message not come yet
        self.subscription = self._subscribe()

    def _subscribe(self):
        self._made += 1
        self._first_pending = True
        made = self._made
        return self.node.create_subscription(self.msg_type, self.topic,
                                             lambda msg, info: self._on_message(made, msg, info), self.qos)

    def _on_message(self, made: int, msg, info) -> None:
        if made != self._made:     # a replaced subscription's message, taken before its destruction took effect
            return
        if self._first_pending:
            self._first_pending = False
            info = info or {}
            seq = info.get("publication_sequence_number")
            age = age_s(info.get("source_timestamp"), info.get("received_timestamp"))
            gave_up = self.check.gave_up
            if self.check.first(seq, age) == RESUBSCRIBE:
                self.node.get_logger().warning(
                    f"{self.topic}: the first message came live (sequence number {seq}, {age:.3f} s old): the "
                    f"writer's history was passed over; subscribing again ({self.check.in_a_row} of "
                    f"{self.check.max_resubscribes})")
                old = self.subscription
                self.subscription = self._subscribe()
                self.node.destroy_subscription(old)
                return
            if self.check.gave_up > gave_up:
                self.node.get_logger().warning(
                    f"{self.topic}: the writer's history was passed over {self.check.max_resubscribes + 1} times; "
                    "going on with the live messages (what the writer published before them is not handled)")
            self.node.get_logger().info(f"{self.topic}: first message: sequence number {seq}, "
                                        f"{'-' if age is None else f'{age:.3f} s'} old")
        self.callback(msg)
