"""The fleet's diagnostic_aggregator configuration, and a small aggregator view that reads it.

:func:`analyzer_config` writes the analyzer YAML a real ROS 2 install loads
(``ros2 run diagnostic_aggregator aggregator_node --ros-args --params-file
config/fleet_aggregator.yaml``): one ``AnalyzerGroup`` per line, in it one ``GenericAnalyzer`` per
drive matching the drive's status names (``startswith: ['line1/drive07/']``) and expecting its two
statuses (``expected``), stale after ``timeout`` seconds without one.

:class:`AggregatorView` applies that same YAML the way diagnostic_aggregator (ros2-jazzy branch,
4.0.0: ``generic_analyzer.cpp``, ``generic_analyzer_base.hpp``, ``analyzer_group.cpp``) does:
a status matches an analyzer by ``regex`` (whole name), ``expected``, ``startswith`` or
``contains``; an item not heard for more than ``timeout`` is STALE; an analyzer's level is the
highest of its items', STALE only if all its items are stale, ERROR if only some are; a group's
likewise over its analyzers. It is what ``fleet`` prints once a second, where the aggregator
itself is not installed.
"""
from __future__ import annotations

import re
from dataclasses import dataclass, field

OK, WARN, ERROR, STALE = 0, 1, 2, 3
LEVEL_NAMES = ("OK", "WARN", "ERROR", "STALE")

GENERIC = "diagnostic_aggregator/GenericAnalyzer"
GROUP = "diagnostic_aggregator/AnalyzerGroup"

# The keys each analyzer reads (diagnostic_aggregator 4.0.0, ros2-jazzy; test_fleet_aggregator.py
# checks our YAML against them) and their parameter types.
GENERIC_KEYS = {"type": str, "path": str, "find_and_remove_prefix": list, "remove_prefix": list,
                "startswith": list, "contains": list, "expected": list, "regex": list,
                "timeout": float, "num_items": int, "discard_stale": bool}
GENERIC_MATCHERS = ("find_and_remove_prefix", "startswith", "contains", "expected", "regex")
GROUP_KEYS = {"type": str, "path": str, "analyzers": dict}
AGGREGATOR_KEYS = {"pub_rate": float, "path": str, "other_as_errors": bool, "history_depth": int,
                   "critical": bool}

STATUS_TASKS = ("classifier: backlash width", "windowing: windowing", "width_trend: width trend")   # per drive
WATCH_TASK = "model_watch: model fit"      # per drive with a model watch (docs/model_watch.md)
DEFAULT_TIMEOUT_S = 3.0   # three missed one-per-second statuses: a drive that went silent
BASE_PATH = "BacklashMonitor"


def drive_status_names(drive) -> list[str]:
    """The /diagnostics status names one drive's chain (and its model watch) publishes."""
    tasks = STATUS_TASKS + ((WATCH_TASK,) if getattr(drive, "watched", False) else ())
    return [f"{drive.hardware_id}/{task}" for task in tasks]


def analyzer_config(drives, timeout_s: float = DEFAULT_TIMEOUT_S, pub_rate_hz: float = 1.0,
                    base_path: str = BASE_PATH) -> dict:
    """The aggregator's parameters file for these drives: a group per line, an analyzer per drive."""
    params: dict = {"pub_rate": float(pub_rate_hz), "path": base_path}
    for drive in drives:
        group = params.setdefault(drive.line, {"type": GROUP, "path": drive.line, "analyzers": {}})
        group["analyzers"][drive.name] = {
            "type": GENERIC, "path": drive.name,
            "startswith": [drive.hardware_id + "/"],
            "expected": drive_status_names(drive),
            "timeout": float(timeout_s)}
    return {"analyzers": {"ros__parameters": params}}


def _parameters(config: dict) -> dict:
    """The ros__parameters of an aggregator parameters file (node 'analyzers' or '/**')."""
    for key in ("analyzers", "/**"):
        node = config.get(key)
        if isinstance(node, dict) and isinstance(node.get("ros__parameters"), dict):
            return node["ros__parameters"]
    raise ValueError("no 'analyzers: ros__parameters:' (or '/**:') section")


@dataclass
class Item:
    name: str
    level: int = STALE
    message: str = "no status yet"
    hardware_id: str = ""
    values: dict = field(default_factory=dict)
    last_s: float | None = None


@dataclass
class Generic:
    path: str
    timeout_s: float
    startswith: list
    contains: list
    expected: list
    regex: list
    items: dict = field(default_factory=dict)
    created_s: float = 0.0

    def match(self, name: str) -> bool:
        return (any(re.fullmatch(r, name) for r in self.regex) or name in self.expected
                or any(name.startswith(s) for s in self.startswith)
                or any(c in name for c in self.contains))

    def report(self, now_s: float) -> tuple[int, list[tuple[Item, bool]]]:
        rows = []
        level, all_stale = OK, True
        for name in sorted(set(self.items) | set(self.expected)):
            item = self.items.get(name) or Item(name)
            last = item.last_s if item.last_s is not None else self.created_s
            stale = self.timeout_s > 0 and now_s - last > self.timeout_s
            level = max(level, item.level)
            all_stale = all_stale and (item.level == STALE or stale)
            if stale:
                level = STALE
            rows.append((item, stale))
        if all_stale:
            level = STALE
        elif level == STALE:
            level = ERROR
        return level, rows


class AggregatorView:
    """diagnostic_aggregator's analyzers, from its parameters file, for a table per drive."""

    def __init__(self, config: dict, now_s: float = 0.0):
        params = _parameters(config)
        self.base_path = "/" + str(params.get("path", "")).strip("/") if params.get("path") else ""
        self.analyzers: list[Generic] = []
        self.groups: dict[str, list[Generic]] = {}
        self._load(params, self.base_path, now_s, top=True)

    def _load(self, params: dict, path: str, now_s: float, top: bool = False) -> None:
        for key, spec in params.items():
            if top and key in AGGREGATOR_KEYS:
                continue
            if not isinstance(spec, dict):
                continue
            kind = spec.get("type")
            if kind == GROUP:
                group_path = f"{path}/{spec['path']}"
                before = len(self.analyzers)
                self._load(spec.get("analyzers", {}), group_path, now_s)
                self.groups[group_path] = self.analyzers[before:]
            elif kind == GENERIC:
                self.analyzers.append(Generic(
                    path=f"{path}/{spec['path']}", timeout_s=float(spec.get("timeout", 5.0)),
                    startswith=list(spec.get("startswith", []))
                    + list(spec.get("find_and_remove_prefix", [])),
                    contains=list(spec.get("contains", [])),
                    expected=list(spec.get("expected", [])),
                    regex=list(spec.get("regex", [])), created_s=now_s))

    def update(self, name: str, level: int, message: str, hardware_id: str, values: dict,
               now_s: float) -> bool:
        """One received DiagnosticStatus; False if no analyzer matches it (diagnostic_aggregator
        would put it under 'Other')."""
        matched = False
        for analyzer in self.analyzers:
            if analyzer.match(name):
                analyzer.items[name] = Item(name, int(level), message, hardware_id, dict(values),
                                            now_s)
                matched = True
        return matched

    def report(self, now_s: float) -> list[dict]:
        """One row per analyzer: {path, level, items: [(name, level, message, age_s)]}."""
        out = []
        for analyzer in self.analyzers:
            level, rows = analyzer.report(now_s)
            out.append({"path": analyzer.path, "level": level, "items": [
                {"name": item.name, "level": STALE if stale else item.level,
                 "message": item.message, "values": item.values,
                 "age_s": None if item.last_s is None else now_s - item.last_s}
                for item, stale in rows]})
        return out

    def group_levels(self, now_s: float) -> dict[str, int]:
        """A group's level: the highest of its analyzers', STALE only if all are stale."""
        levels = {}
        by_path = {row["path"]: row["level"] for row in self.report(now_s)}
        for path, members in self.groups.items():
            lv = [by_path[a.path] for a in members]
            level = max(lv) if lv else ERROR
            if level == STALE and not all(x == STALE for x in lv):
                level = ERROR
            levels[path] = level
        return levels


def short_model_fit(message: str) -> str:
    """The model watch's status for a table cell: 'OK 0.9x', 'WARN 2.8x since 12:03:11 (gap traversal, d4)', the
    collecting/STALE text as it is."""
    if message.startswith("STALE (") and message.endswith(")"):
        return f"STALE ({short_model_fit(message[len('STALE ('):-1]).split(' (')[0]})"
    m = re.match(r"model (.+?) explains the drive \(residual ([\d.]+)x", message)
    if m:
        return f"OK {m.group(2)}x ({m.group(1)})"
    m = re.match(r"model (.+?) no longer explains the drive since ([\d:]+): residual ([\d.]+)x the noise floor"
                 r"(?:, in the (.+?), wavelet level (\w+))?", message)
    if m:
        where = f", {m.group(4)} {m.group(5)}" if m.group(4) else ""
        return f"WARN {m.group(3)}x since {m.group(2)} ({m.group(1)}{where})"
    return message


def format_table(view: AggregatorView, now_s: float) -> str:
    """The view as text: a line per group, then a row per drive with its statuses (the model fit where the drive
    has a model watch)."""
    rows = [("drive", "level", "backlash width", "model fit", "windowing", "age")]
    groups = view.group_levels(now_s)
    report = {row["path"]: row for row in view.report(now_s)}
    for members in (view.groups or {"": view.analyzers}).values():
        for analyzer in members:
            row = report[analyzer.path]
            msgs = {}
            ages = []
            for item in row["items"]:
                task = item["name"].rsplit("/", 1)[-1]
                text = item["message"] if item["level"] != STALE or item["age_s"] is None \
                    else f"STALE ({item['message']})"
                msgs[task.split(":")[0]] = text if item["age_s"] is not None else "STALE (never heard)"
                if item["age_s"] is not None:
                    ages.append(item["age_s"])
            rows.append((analyzer.path.removeprefix(view.base_path + "/"),
                         LEVEL_NAMES[row["level"]], msgs.get("classifier", "-"),
                         short_model_fit(msgs.get("model_watch", "-")), msgs.get("windowing", "-"),
                         f"{max(ages):.1f} s" if ages else "-"))
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip() for r in rows]
    lines.insert(1, "  ".join("-" * w for w in widths))
    head = "  ".join(f"{path.removeprefix(view.base_path + '/')} {LEVEL_NAMES[lv]}"
                     for path, lv in groups.items())
    return "\n".join(([head] if head else []) + lines)
