"""The QoS profiles of the graph's topics, in one place (docs/graph.md, "QoS", gives the reasons).

A leaf module: it imports rclpy's QoS types only, so a node takes its profiles from here without
importing another node's module (and that node's cores: the windowing node used to import the plant
simulator's module, and with it numba and scipy, only for two profiles).
"""
from __future__ import annotations

from rclpy.qos import (DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy,
                       qos_profile_sensor_data)

# plant/true_width_m: latched, so that a node started later still learns the simulated width.
LATCHED = QoSProfile(depth=1, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST)

RELIABLE_CHUNK_DEPTH = 1000  # chunks (20 s of stream at 1000 samples each): a late subscriber
                             # catches up instead of losing data when the stream runs faster than
                             # real time

CHUNK_QOS_CHOICES = ("sensor_data", "reliable")


def chunk_qos(name: str) -> QoSProfile:
    """QoS of the plant/* chunk topics: 'sensor_data' (best effort, depth 5; a live drive's stream
    must not block its source) or 'reliable' (depth 1000; a faster-than-real-time run loses
    nothing)."""
    if name == "reliable":
        return QoSProfile(depth=RELIABLE_CHUNK_DEPTH, reliability=ReliabilityPolicy.RELIABLE,
                          history=HistoryPolicy.KEEP_LAST)
    return qos_profile_sensor_data


# Windows come in bursts when the stream runs faster than real time (a replay, a simulation):
# 1000 windows (125 s of a drive's stream, 32 MB at most) may wait for a slow reader before the
# oldest is dropped. Transient local: a reader that matches late (a node started after the stream,
# a slow discovery while several processes start) still gets the last 1000 windows instead of
# losing the ones published before it matched.
WINDOW_QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE,
                        durability=DurabilityPolicy.TRANSIENT_LOCAL,
                        history=HistoryPolicy.KEEP_LAST)

# Transient local like the windows: a monitor that matches late still gets the last 1000
# estimates (250 s of onsets and returns of one drive).
ESTIMATE_QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE,
                          durability=DurabilityPolicy.TRANSIENT_LOCAL,
                          history=HistoryPolicy.KEEP_LAST)

# /diagnostics: reliable, depth 10, as diagnostic_aggregator and diagnostic_updater use it.
DIAGNOSTICS_DEPTH = 10
