"""Writing a recording: an MCAP bag (the official ``mcap`` + ``mcap_ros2`` writer, not backlash_monitor.bag), or
the NPZ/CSV tables docs/workbench.md "Measurement" documents.

Bag: schema ``backlash_monitor_msgs/msg/SignalChunk`` (encoding ros2msg; text = msg_defs/msg/SignalChunk.msg
followed, as rosbag2 writes it, by its dependencies std_msgs/Header and builtin_interfaces/Time, each after a
line of 80 '=' and ``MSG: pkg/Name``), CDR messages on ``<ns>/plant/{a1,a2,omega1,omega2,angle_difference}``,
one message per chunk per signal: header.stamp = the time of the chunk's first sample, header.frame_id = the
drive's name, signal_name, unit, sample_period_s, first_sample_index (samples since sample 0), samples.
Log time = the chunk's last sample + a receive latency (0.2-1.5 ms, from the recording's seed), as a recorder
logs a message when it arrives. No truth in the bag (the manifest holds it): a real drive has none.
Every file is written as NAME.partial and renamed when complete.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

import numpy as np

from . import constants as C
from .drive import Recording, make_recording
from .spec import RecordingSpec

SCHEMA_NAME = "backlash_monitor_msgs/msg/SignalChunk"
_REPO = Path(__file__).resolve().parents[1]
# the two standard definitions, as ROS 2 Jazzy's std_msgs and builtin_interfaces install them (used when no
# ROS share directory is found)
_HEADER_MSG = """# Standard metadata for higher-level stamped data types.
# This is generally used to communicate timestamped data
# in a particular coordinate frame.

# Two-integer timestamp that is expressed as seconds and nanoseconds.
builtin_interfaces/Time stamp

# Transform frame with which this data is associated.
string frame_id
"""
_TIME_MSG = """# This message communicates ROS Time defined here:
# https://design.ros2.org/articles/clock_and_time.html

# The seconds component, valid over all int32 values.
int32 sec

# The nanoseconds component, valid in the range [0, 1e9), to be added to the seconds component. 
# e.g.
# The time -1.7 seconds is represented as {sec: -2, nanosec: 3e8}
# The time 1.7 seconds is represented as {sec: 1, nanosec: 7e8}
uint32 nanosec
"""


def _share_msg(package: str, name: str, fallback: str) -> str:
    prefixes = [p for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p] + [sys.prefix]
    for pre in prefixes:
        f = Path(pre) / "share" / package / "msg" / f"{name}.msg"
        if f.is_file():
            return f.read_text(encoding="utf-8")
    return fallback


def schema_text() -> str:
    """The SignalChunk schema as rosbag2 stores it: the type's own .msg, then each dependency (depth-first)."""
    own = (_REPO / "msg_defs" / "msg" / "SignalChunk.msg").read_text(encoding="utf-8")
    sep = "\n" + "=" * 80 + "\n"
    return (own + sep + "MSG: std_msgs/Header\n" + _share_msg("std_msgs", "Header", _HEADER_MSG)
            + sep + "MSG: builtin_interfaces/Time\n" + _share_msg("builtin_interfaces", "Time", _TIME_MSG))


def topic_prefix(namespace: str) -> str:
    ns = namespace.strip("/")
    return f"/{ns}/plant" if ns else "/plant"


def _partial(path: Path) -> Path:
    return path.with_name(path.name + ".partial")


def _check_target(path: Path, overwrite: bool) -> None:
    if path.exists() and not overwrite:
        raise FileExistsError(f"{path} exists; allowed: a new file, or --overwrite")
    if not path.parent.is_dir():
        raise FileNotFoundError(f"{path.parent} is not a directory")


def write_bag(spec: RecordingSpec, path, recording: Recording | None = None, overwrite: bool = False) -> Path:
    """Make (or take) the spec's recording and write it as an MCAP bag."""
    from mcap.writer import CompressionType
    from mcap_ros2.writer import Writer

    path = Path(path)
    _check_target(path, overwrite)
    rec = recording if recording is not None else make_recording(spec)
    prefix = topic_prefix(spec.namespace)
    dt = rec.sample_period_s
    n = rec.n_samples
    rng = np.random.default_rng([spec.seed, 0x6D636170])      # receive latencies only
    tmp = _partial(path)
    with open(tmp, "wb") as f:
        w = Writer(f, chunk_size=512 * 1024, compression=CompressionType.ZSTD)
        schema = w.register_msgdef(SCHEMA_NAME, schema_text())
        seq = 0
        for k0 in range(0, n, spec.chunk_samples):
            m = min(spec.chunk_samples, n - k0)
            stamp = spec.start_time_ns + int(round(k0 * dt * 1e9))
            arrive = stamp + int(round((m - 1) * dt * 1e9)) + int(rng.uniform(2e5, 1.5e6))
            header = {"stamp": {"sec": stamp // 1_000_000_000, "nanosec": stamp % 1_000_000_000},
                      "frame_id": spec.drive_name}
            for i, (name, unit) in enumerate(C.SIGNAL_UNITS.items()):
                w.write_message(f"{prefix}/{name}", schema,
                                {"header": header, "signal_name": name, "unit": unit, "sample_period_s": float(dt),
                                 "first_sample_index": int(k0),
                                 "samples": rec.signals[name][k0:k0 + m].tolist()},
                                log_time=arrive + 1000 * i, publish_time=stamp, sequence=seq)
            seq += 1
        w.finish()
    tmp.replace(path)
    return path


def write_npz(spec: RecordingSpec, path, recording: Recording | None = None, overwrite: bool = False) -> Path:
    """1-D arrays a1, a2, omega1, omega2, angle_difference and the scalar sample_period_s (docs/workbench.md)."""
    path = Path(path)
    _check_target(path, overwrite)
    rec = recording if recording is not None else make_recording(spec)
    tmp = _partial(path)
    with open(tmp, "wb") as f:
        np.savez(f, sample_period_s=np.float64(rec.sample_period_s), **rec.signals)
    tmp.replace(path)
    return path


def write_csv(spec: RecordingSpec, path, recording: Recording | None = None, overwrite: bool = False) -> Path:
    """Header time_s, a1, a2, angle_difference, omega1, omega2; one row per sample (docs/workbench.md)."""
    path = Path(path)
    _check_target(path, overwrite)
    rec = recording if recording is not None else make_recording(spec)
    cols = ["time_s", "a1", "a2", "angle_difference", "omega1", "omega2"]
    data = np.column_stack([np.arange(rec.n_samples) * rec.sample_period_s] + [rec.signals[c] for c in cols[1:]])
    tmp = _partial(path)
    with open(tmp, "w") as f:
        f.write(",".join(cols) + "\n")
        np.savetxt(f, data, delimiter=",", fmt="%.17g")
    tmp.replace(path)
    return path
