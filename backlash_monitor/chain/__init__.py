"""The signal chain's stages as plain objects (no rclpy), shared by the nodes and ``analyze``.

The windowing, denoise and classifier nodes are thin shells over these; ``python -m
backlash_monitor analyze`` runs the same stages over a bag's messages in the order they were
received, so the offline estimates equal the live ones exactly. One module per stage:

- ``joiner``: :class:`ChunkJoiner` joins the per-signal chunks of one sample range (a drive's
  signals arrive on separate topics) into a :class:`JoinedRange` and gives up on ranges that stay
  incomplete (MAX_PENDING_RANGES, :func:`pending_ranges_for`, RESYNC_SAMPLES).
- ``stage``: :class:`WindowingStage` checks a joined range, places it in its stream
  (RESTART_CONFIRM_RANGES) and feeds it to the entry detector and the window capture.
- ``block_feeder``: :class:`BlockFeeder` (offline) feeds contiguous ranges to a WindowingStage in
  blocks, with the same windows as one by one.
- ``record``: :func:`estimate_record` (offline) the whole chain over one drive's record held in
  arrays: the windows and the estimates the live graph publishes for it.

The denoise stage's helpers (``denoise_checked``, ``denoise_pair``, ``denoise_pairs``, ...) are in
:mod:`backlash_monitor.denoise`, with the transform they apply.

The names are re-exported here so that ``from backlash_monitor.chain import ChunkJoiner`` keeps
working; the package's own code imports each from the module that holds it.
"""
from backlash_monitor.chain.block_feeder import BlockFeeder
from backlash_monitor.chain.joiner import (MAX_PENDING_RANGES, RESYNC_SAMPLES, ChunkJoiner,
                                           JoinedRange, pending_ranges_for)
from backlash_monitor.chain.record import estimate_record
from backlash_monitor.chain.stage import RESTART_CONFIRM_RANGES, WindowingStage

__all__ = [
    "BlockFeeder",
    "ChunkJoiner",
    "JoinedRange",
    "MAX_PENDING_RANGES",
    "RESTART_CONFIRM_RANGES",
    "RESYNC_SAMPLES",
    "WindowingStage",
    "estimate_record",
    "pending_ranges_for",
]
