"""The evidence on a WARN: a ring of a drive's plant topics as they came off the wire, and the bag of the X s
before and the Y s after a trigger (rosbag2 has no such snapshot; its issue #900 asks for one).

The ring keeps every plant topic's serialized SignalChunk messages (no decoding, no copy) for the last
``capacity_samples`` of the stream. ``SnapshotRecorder.trigger(sample_index, when)`` names the file and waits until
the stream has passed sample_index + after; then the messages of [sample_index - before, sample_index + after)
are written as an ordinary project bag (backlash_monitor.bag.BagWriter: rosbag2-compatible MCAP, the topics'
names and types as recorded, so ``diagnose`` and ``analyze`` read it like any recording), in a thread: the stream
is not held up. Never overwrite, never lose: the bag is written to ``NAME.mcap.partial`` and linked to its name
only when complete (an existing name gets ``_2``, ``_3``, ...); a write that fails keeps its partial file and says
why. Plain Python, no rclpy.
"""
from __future__ import annotations

import datetime as _dt
import os
import threading
from collections import deque
from dataclasses import dataclass, field
from pathlib import Path

from backlash_monitor import bag

SIGNAL_CHUNK = "backlash_monitor_msgs/msg/SignalChunk"


@dataclass
class RawChunk:
    topic: str
    first_sample_index: int
    n_samples: int
    log_time_ns: int
    data: bytes


class PlantRing:
    """The last ``capacity_samples`` of every topic's serialized chunks, addressed by sample index."""

    def __init__(self, capacity_samples: int):
        self.capacity = int(capacity_samples)
        self.chunks: dict[str, deque] = {}
        self.qos: dict[str, list] = {}

    def add(self, topic: str, first_sample_index: int, n_samples: int, log_time_ns: int, data: bytes) -> None:
        q = self.chunks.setdefault(topic, deque())
        if q and first_sample_index < q[-1].first_sample_index:
            q.clear()                    # the stream restarted: what came before is another stream
        q.append(RawChunk(topic, int(first_sample_index), int(n_samples), int(log_time_ns), data))
        end = first_sample_index + n_samples
        while q and q[0].first_sample_index + q[0].n_samples <= end - self.capacity:
            q.popleft()

    def end(self, topics=None) -> int:
        """The sample index every topic (of ``topics``) has reached (0 before any)."""
        ends = [q[-1].first_sample_index + q[-1].n_samples if q else 0
                for t, q in self.chunks.items() if topics is None or t in topics]
        return min(ends) if ends else 0

    def between(self, lo: int, hi: int) -> list[RawChunk]:
        """Every held chunk overlapping [lo, hi), in log-time order."""
        out = [c for q in self.chunks.values() for c in q
               if c.first_sample_index < hi and c.first_sample_index + c.n_samples > lo]
        out.sort(key=lambda c: (c.log_time_ns, c.topic))
        return out


def unique_path(directory, stem: str, suffix: str = ".mcap") -> Path:
    """directory/stem.mcap, or stem_2.mcap, stem_3.mcap, ... : a name nothing has (nor its .partial)."""
    d = Path(directory)
    i = 1
    while True:
        p = d / (f"{stem}{suffix}" if i == 1 else f"{stem}_{i}{suffix}")
        if not p.exists() and not p.with_name(p.name + ".partial").exists():
            return p
        i += 1


def snapshot_stem(drive_name: str, when_utc: _dt.datetime) -> str:
    """drive7_20261124T120311: the drive's name (a namespace's / as _) and the UTC time of the WARN."""
    safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in drive_name.strip("/")) or "drive"
    return f"{safe}_{when_utc.strftime('%Y%m%dT%H%M%S')}"


def write_bag(path, chunks: list[RawChunk], types: dict, qos: dict | None = None) -> Path:
    """The chunks as a bag at ``path`` (via path.partial, linked when complete; never replaces a file)."""
    final = Path(path)
    partial = final.with_name(final.name + ".partial")
    with bag.BagWriter(partial, exclusive=True) as w:
        for topic in sorted({c.topic for c in chunks}):
            w.add_topic(topic, types.get(topic, SIGNAL_CHUNK), qos_profiles=(qos or {}).get(topic))
        for c in chunks:
            w.write_raw(c.topic, c.data, log_time_ns=c.log_time_ns)
    try:
        os.link(partial, final)          # fails if the name was taken meanwhile: nothing is replaced
    except FileExistsError:
        final = unique_path(final.parent, final.stem)
        os.link(partial, final)
    except OSError:                      # a file system without hard links
        if final.exists():
            final = unique_path(final.parent, final.stem)
        os.rename(partial, final)
        return final
    os.unlink(partial)
    return final


@dataclass
class Snapshot:
    path: Path
    lo: int
    hi: int
    state: str = "recording"             # recording | writing | written | failed: <why>
    messages: int = 0
    error: str = ""
    thread: threading.Thread | None = field(default=None, repr=False)


class SnapshotRecorder:
    """Snapshots of the ring around triggers: one at a time (a trigger while one is recording is not taken)."""

    def __init__(self, directory, drive_name: str, sample_period_s: float, before_s: float, after_s: float,
                 topics_types: dict, max_snapshots: int = 20):
        self.directory = Path(directory)
        self.drive_name = drive_name
        self.dt = float(sample_period_s)
        self.before = int(round(before_s / self.dt))
        self.after = int(round(after_s / self.dt))
        self.types = dict(topics_types)
        self.max_snapshots = int(max_snapshots)
        # the ring holds the window before the trigger until the window after it has come, with 1 s to spare
        self.ring = PlantRing(self.before + self.after + int(round(1.0 / self.dt)))
        self.snapshots: list[Snapshot] = []
        self.pending: Snapshot | None = None
        self.skipped = 0                 # triggers not taken (one recording, or max_snapshots reached)

    def add(self, topic: str, first_sample_index: int, n_samples: int, log_time_ns: int, data: bytes) -> None:
        self.ring.add(topic, first_sample_index, n_samples, log_time_ns, data)
        p = self.pending
        if p is not None and self.ring.end(self.types) >= p.hi:
            self._write(p)

    def trigger(self, sample_index: int, when_utc: _dt.datetime) -> Snapshot | None:
        """A snapshot of [sample_index - before, sample_index + after), named after ``when_utc``."""
        if self.pending is not None or len(self.snapshots) >= self.max_snapshots:
            self.skipped += 1
            return None
        path = unique_path(self.directory, snapshot_stem(self.drive_name, when_utc))
        snap = Snapshot(path, int(sample_index) - self.before, int(sample_index) + self.after)
        self.snapshots.append(snap)
        self.pending = snap
        if self.ring.end(self.types) >= snap.hi:
            self._write(snap)
        return snap

    def _write(self, snap: Snapshot) -> None:
        chunks = self.ring.between(snap.lo, snap.hi)
        snap.messages = len(chunks)
        snap.state = "writing"
        self.pending = None

        def run():
            try:
                snap.path = write_bag(snap.path, chunks, self.types, self.ring.qos)
                snap.state = "written"
            except (OSError, ValueError) as error:
                snap.error = getattr(error, "strerror", None) or str(error)
                snap.state = f"failed: {snap.error}"
        snap.thread = threading.Thread(target=run, name=f"snapshot {snap.path.name}", daemon=False)
        snap.thread.start()

    def flush(self, timeout_s: float = 30.0) -> None:
        """At the end: a snapshot still recording is written with what the ring has; wait for the writers."""
        if self.pending is not None:
            self._write(self.pending)
        for s in self.snapshots:
            if s.thread is not None:
                s.thread.join(timeout_s)

    @property
    def last(self) -> Snapshot | None:
        return self.snapshots[-1] if self.snapshots else None
