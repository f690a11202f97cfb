"""`python -m backlash_monitor bag-info BAG`: what `ros2 bag info` shows, plus integrity/recovery.

Every chunk is checked: its record against the summary's chunk index, the data section's CRC and,
when that fails or is missing, each chunk's own CRC (every chunk is decompressed).

Every valid MCAP layout is read (with or without a summary, chunks, indexes, statistics; see
docs/bags.md). Exit codes: 0 = the bag is complete, intact and every topic's schema decodes (or
`--recover` read what was intact, and the report says what was damaged or lost); 1 = the bag is
damaged (truncated: recorder killed; a damaged chunk or summary; a schema that cannot be decoded);
2 = bad input (no such file, not an MCAP/ROS 2 bag, a layout this package cannot read such as an
unknown chunk compression, `--topic` not in the bag).
"""
from __future__ import annotations

import argparse
import datetime as _dt
import json
import sys

from backlash_monitor.commands.vocabulary import deprecated

NAME = "bag-info"
HELP = "show a recorded MCAP bag: duration, topics, types, counts, integrity (like ros2 bag info)"


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("bag", metavar="BAG", help="the .mcap file (or a rosbag2 directory holding one)")
    parser.add_argument("--recover", action="store_true",
                        help="read what is intact in a damaged bag (recorder killed: no summary; "
                             "damaged chunks are skipped) and report what was skipped or lost")
    parser.add_argument("--topic", action="append", default=[], metavar="TOPIC",
                        help="also decode this topic and show its details (SignalChunk: samples, "
                             "sample rate, gaps); repeatable")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="print text, or one JSON object")
    deprecated(parser, "--json", "--format json", "format", const="json")


def _fmt_time(ns: int | None) -> str:
    if ns is None:
        return "-"
    t = _dt.datetime.fromtimestamp(ns / 1e9, tz=_dt.timezone.utc)
    return f"{t.strftime('%b %d %Y %H:%M:%S')}.{ns % 1_000_000_000:09d} ({ns // 1_000_000_000}.{ns % 1_000_000_000:09d})"


def _fmt_size(n: int) -> str:
    for unit in ("B", "KiB", "MiB", "GiB"):
        if n < 1024 or unit == "GiB":
            return f"{n:.1f} {unit}" if unit != "B" else f"{n} B"
        n /= 1024
    return str(n)


def _err(msg: str) -> None:
    print(f"python -m backlash_monitor bag-info: error: {msg}", file=sys.stderr)


def run(args) -> int:
    # deferred: backlash_monitor.bag costs ~250 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from ..bag import (BagError, BagReader, DamagedBagError, MissingTopicError, NotABagError,
                       TruncatedBagError, UnknownSchemaError, UnsupportedBagError)

    try:
        reader = BagReader(args.bag, recover=args.recover)
    except FileNotFoundError as exc:
        _err(f"{exc}")
        return 2
    except NotABagError as exc:
        _err(f"{exc} (expected a rosbag2 MCAP file, profile 'ros2')")
        return 2
    except UnsupportedBagError as exc:   # a valid MCAP layout this package cannot read
        _err(f"{args.bag}: {exc}")
        return 2
    except (TruncatedBagError, DamagedBagError) as exc:
        _err(f"{exc}")
        return 1
    except (BagError, OSError) as exc:
        _err(f"cannot read {args.bag}: {exc}")
        return 1

    status = 0
    with reader:
        try:
            reader.verify()   # every chunk's CRC, unless the data section's CRC vouched for them
        except DamagedBagError as exc:
            _err(f"{exc}")
            return 1
        topics = reader.topics
        for t in args.topic:
            if t not in topics:
                _err(str(MissingTopicError(t, topics)))
                return 2
        schema_errors = {}
        for name in topics:
            try:
                reader.codec(name)
            except (UnknownSchemaError, BagError) as exc:
                schema_errors[name] = str(exc)
        meta = reader.rosbag2_metadata or {}
        info = {
            "file": str(reader.path),
            "bag_size_bytes": reader.file_size,
            "storage_id": "mcap",
            "ros_distro": meta.get("ros_distro", ""),
            "duration_ns": reader.duration_ns,
            "start_ns": reader.start_ns,
            "end_ns": reader.end_ns,
            "messages": reader.message_count,
            "topics": [{"topic": t.name, "type": t.type, "count": t.count,
                        "serialization_format": t.message_encoding,
                        **({"schema_error": schema_errors[t.name]} if t.name in schema_errors else {})}
                       for t in topics.values()],
            "complete": reader.recovery.complete,
            "intact": reader.recovery.intact,
            "integrity": reader.recovery.describe(),
            "lost_bytes": reader.recovery.lost_bytes,
            "recovery": reader.recovery.to_dict(),
        }
        info["input_saturation"] = _saturation(reader, topics)
        details = {}
        for t in args.topic:
            try:
                details[t] = _topic_details(reader, t)
            except BagError as exc:
                schema_errors.setdefault(t, str(exc))
        if details:
            info["details"] = details

    if args.format == "json":
        print(json.dumps(info, indent=2))
    else:
        _print_text(info)
    if schema_errors:
        for t, e in schema_errors.items():
            _err(f"topic {t}: {e}")
        status = 1
    if not args.recover and not reader.recovery.intact:   # pragma: no cover - raised at open
        status = 1
    return status


def _saturation(reader, topics) -> dict:
    """Each accelerometer topic's samples at a rail (a clipped sensor) or stuck at one value, counted in
    blocks of 1 s as the windowing node and analyze count them (windowing/saturation.py)."""
    # deferred: backlash_monitor.bag costs ~250 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from ..bag import BagError
    # deferred: backlash_monitor.windowing costs ~190 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from ..windowing import DEFAULTS
    # deferred: backlash_monitor.windowing.saturation costs ~230 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from ..windowing.saturation import SaturationCounter, SaturationSettings
    settings = SaturationSettings.from_config(DEFAULTS["saturation"])
    out = {}
    for name, t in topics.items():
        if not t.type.endswith("/SignalChunk") or name.rsplit("/", 1)[-1] not in ("a1", "a2"):
            continue
        try:
            signal = reader.read_signal(name)
        except BagError as exc:
            out[name] = {"error": str(exc)}
            continue
        counter = SaturationCounter((signal.signal_name,), settings)
        counter.feed({signal.signal_name: signal.samples})
        counter.flush()
        out[name] = counter.totals()[signal.signal_name].as_dict()
    return out


def _topic_details(reader, topic: str) -> dict:
    info = reader.topics[topic]
    if info.type.endswith("/SignalChunk"):
        s = reader.read_signal(topic)
        return {"samples": int(s.samples.size), "signal_name": s.signal_name, "unit": s.unit,
                "sample_period_s": s.sample_period_s,
                "sample_rate_hz": (1.0 / s.sample_period_s) if s.sample_period_s else None,
                "first_sample_index": int(s.sample_index[0]) if s.samples.size else None,
                "chunks": int(s.chunk_first_index.size), "gaps": s.gaps[:20],
                "gap_count": len(s.gaps)}
    n = 0
    for _ in reader.messages([topic]):
        n += 1
    return {"decoded_messages": n}


def _print_text(info: dict) -> None:
    w = 19
    print(f"{'Files:':<{w}}{info['file']}")
    print(f"{'Bag size:':<{w}}{_fmt_size(info['bag_size_bytes'])}")
    print(f"{'Storage id:':<{w}}{info['storage_id']}")
    print(f"{'ROS Distro:':<{w}}{info['ros_distro'] or '-'}")
    print(f"{'Duration:':<{w}}{info['duration_ns'] / 1e9:.9f}s")
    print(f"{'Start:':<{w}}{_fmt_time(info['start_ns'])}")
    print(f"{'End:':<{w}}{_fmt_time(info['end_ns'])}")
    print(f"{'Messages:':<{w}}{info['messages']}")
    first = True
    for t in info["topics"]:
        label = "Topic information:" if first else ""
        first = False
        extra = " | SCHEMA ERROR" if "schema_error" in t else ""
        print(f"{label:<{w}}Topic: {t['topic']} | Type: {t['type']} | Count: {t['count']} | "
              f"Serialization Format: {t['serialization_format']}{extra}")
    if first:
        print(f"{'Topic information:':<{w}}")
    print(f"{'Integrity:':<{w}}{info['integrity']}")
    rec = info["recovery"]
    origin = rec["origin_ns"]
    for d in rec["damaged_chunks"]:
        span = ("log time ?" if d["start_ns"] is None or origin is None else
                f"log time {(d['start_ns'] - origin) / 1e9:.3f}-{(d['end_ns'] - origin) / 1e9:.3f} s")
        msgs = "?" if d["messages"] is None else d["messages"]
        print(f"{'':<{w}}{'read ' if d['recovered'] else 'SKIPPED'} chunk at byte {d['offset']} "
              f"({d['length_bytes']} bytes, {span}, {msgs} messages): {d['reason']}")
    for topic, sat in info.get("input_saturation", {}).items():
        text = sat.get("error") or sat["message"] or "none (not at a rail, not stuck)"
        print(f"{'Saturation:':<{w}}{topic}: {text}")
    for topic, d in info.get("details", {}).items():
        print(f"{'Details ' + topic + ':'}")
        for k, v in d.items():
            print(f"  {k}: {v}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog=f"python -m backlash_monitor {NAME}", description=HELP)
    add_arguments(parser)
    return run(parser.parse_args(argv))


if __name__ == "__main__":
    sys.exit(main())
