"""Wait until every subscriber has acknowledged what a node published (reliable publishers).

A reliable message that a subscriber has not yet acknowledged lives only in the publisher's history: when the
publisher's process exits, it is gone. A node that publishes a finite stream (the plant's chunks, a replayed bag)
therefore waits, after its last message, until every matched subscriber has acknowledged everything
(``Publisher.wait_for_all_acked``), up to a bound, and names the topics still behind when the bound passes.
Best-effort publishers acknowledge nothing: they return at once (docs/graph.md "The plant's last chunks").
"""
from __future__ import annotations

import time
from collections.abc import Mapping

from rclpy.duration import Duration

MIN_WAIT_S = 1e-3   # wait_for_all_acked with a zero duration waits for ever: the shortest wait asked for


def wait_acknowledged(publishers: Mapping, timeout_s: float) -> list[str]:
    """Wait until every subscriber of ``publishers`` (topic -> rclpy Publisher) has acknowledged every message, all
    topics within one deadline ``timeout_s`` [s] from now (each topic gets at least MIN_WAIT_S). -> the topics
    still not acknowledged when the deadline passed (empty: all delivered)."""
    deadline = time.monotonic() + max(float(timeout_s), 0.0)
    behind = []
    for topic, publisher in publishers.items():
        left = max(deadline - time.monotonic(), MIN_WAIT_S)
        if not publisher.wait_for_all_acked(Duration(seconds=left)):
            behind.append(topic)
    return behind
