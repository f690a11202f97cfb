"""Exceptions of the bag package: each names the problem in words an operator understands."""
from __future__ import annotations


class BagError(Exception):
    """Base class of every error raised by backlash_monitor.bag."""


class NotABagError(BagError):
    """The file is not an MCAP file (wrong magic) or not a ROS 2 (`ros2` profile) MCAP file."""


class UnsupportedBagError(BagError):
    """A valid MCAP file that uses something this package cannot read (a chunk compression other
    than none, zstd or lz4): refused with one line naming it, never read short."""


class TruncatedBagError(BagError):
    """The file ends early: no footer/summary (the recorder was killed) or a record is cut off.

    Attributes: `path`, `file_size`, `intact_bytes` (bytes up to the last complete record),
    `complete_chunks` (complete chunks found by the scan). Open the file with
    `BagReader(path, recover=True)` to read the intact part.
    """

    def __init__(self, message: str, *, path: str = "", file_size: int = 0, intact_bytes: int = 0,
                 complete_chunks: int = 0):
        super().__init__(message)
        self.path = path
        self.file_size = file_size
        self.intact_bytes = intact_bytes
        self.complete_chunks = complete_chunks


class CorruptBagError(BagError):
    """A record is malformed (bad length, CRC mismatch, unknown compression) before the file's end."""


class DamagedBagError(CorruptBagError):
    """Chunks (or the summary) of a bag are damaged: a length field, a CRC, data that does not
    decompress. ``report`` (a RecoveryReport) lists every damaged chunk with its byte offset, log-time
    range and message count. Open the file with ``BagReader(path, recover=True)`` (``--recover``) to
    read every intact chunk and skip the damaged ones."""

    def __init__(self, message: str, report=None):
        super().__init__(message)
        self.report = report


class UnknownSchemaError(BagError):
    """A message type's definition cannot be found (writing) or parsed/decoded (reading)."""


class MissingTopicError(BagError, KeyError):
    """A topic was asked for that the bag (or writer) does not have. `available` lists the topics."""

    def __init__(self, topic: str, available):
        self.topic = topic
        self.available = sorted(available)
        shown = ", ".join(self.available) if self.available else "(none)"
        super().__init__(f"topic {topic!r} is not in the bag; topics in the bag: {shown}")

    def __str__(self) -> str:  # KeyError would otherwise repr() the message
        return self.args[0]


class CdrError(BagError):
    """A CDR payload does not match its message definition (too short, bad string, bad header)."""
