"""RepeatedWindows: recognise a window that arrives a second time.

The window and estimate topics are transient local (docs/graph.md): a reader that matches late
gets the writer's last 1000 messages. When an upstream node restarts in a running graph (a
denoise node started again, say), it is such a late reader: it receives the windows it already
handled and publishes them again, and the classifier would count those events twice in its fused
estimate. A repeated window is the same message, so it has the same stamp, entry index and kind;
a new run of the same drive from sample 0 has a new stream start and hence new stamps, so it is
not mistaken for a repeat.
"""
from __future__ import annotations

from collections import OrderedDict


class RepeatedWindows:
    """Remembers the keys of the last ``capacity`` windows seen (the writers keep 1000)."""

    def __init__(self, capacity: int = 2000):
        if capacity < 1:
            raise ValueError(f"capacity = {capacity}; allowed: 1 or more")
        self.capacity = capacity
        self._seen: OrderedDict[tuple, None] = OrderedDict()
        self.repeats = 0

    def is_repeat(self, stamp_ns: int, entry_sample_index: int, entry_kind: str,
                  frame_id: str = "") -> bool:
        """True if this window was seen before (and counts it); else remember it."""
        key = (frame_id, stamp_ns, entry_sample_index, entry_kind)
        if key in self._seen:
            self.repeats += 1
            return True
        self._seen[key] = None
        if len(self._seen) > self.capacity:
            self._seen.popitem(last=False)
        return False
