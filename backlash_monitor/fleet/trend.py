"""The width trend of each drive over its recordings, and the WARN it earns before the limit.

A drive's points are (time [s since the epoch], width [m]): one per analysed recording (the median
of its windows' continuous widths; its last fused estimate where the mode gives no continuous width,
docs/classifier.md). The trend is the least-squares slope of width over time
[m/day]. A drive is

- ERROR when its last width has reached ``error_width_m`` (as the live diagnostics),
- WARN when it has reached ``warn_width_m`` or when it grows faster than
  ``warn_growth_m_per_day``: the second warns a drive that is still narrow but wearing fast,
  before it reaches the limit, with the days left at that rate,
- OK otherwise.

config/trend.yaml gives the rate with its reason.

The running monitor applies the same rule live (:class:`LiveTrend`, node ``width_trend``): the
fused continuous widths as they come, one point per ``live_point_period_s`` (the median of that period), the
points of the last ``live_history_s``, and no rate before they span ``live_min_span_s``. Its
points can be kept in a file (:func:`save_live_points`, :func:`load_live_points`; the node's
``state_file``) so that a restarted monitor goes on with the drive's history instead of a day
without a rate.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass
import statistics
import json
from datetime import datetime, timezone
from pathlib import Path

import yaml

from backlash_monitor.files.config import config_file

SECONDS_PER_DAY = 86400.0

# The signal whose estimates speak for the drive (live and offline trend, fleet view, fleet table):
# both accelerations, the most accurate one (README, identification table).
PRIMARY_SIGNAL = "a1+a2"


@dataclass(frozen=True)
class TrendRule:
    warn_growth_m_per_day: float
    warn_width_m: float
    error_width_m: float
    live_point_period_s: float = 60.0
    live_history_s: float = 7 * 86400.0
    live_min_span_s: float = 86400.0


LIVE_KEYS = ("live_point_period_s", "live_history_s", "live_min_span_s")


def load_rule(path: str | None = None) -> TrendRule:
    """The rule of config/trend.yaml (or ``path``); KeyError/ValueError/TypeError for a missing or
    non-positive value."""
    path = path or _default_path()
    with open(path, encoding="utf-8") as f:
        cfg = yaml.safe_load(f)
    live = {k: float(cfg[k]) for k in LIVE_KEYS if k in cfg}
    rule = TrendRule(float(cfg["warn_growth_m_per_day"]), float(cfg["warn_width_m"]),
                     float(cfg["error_width_m"]), **live)
    for key in ("warn_growth_m_per_day", *LIVE_KEYS):
        value = getattr(rule, key)
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"{key} = {value!r}; allowed: a positive number")
    return rule


def _default_path() -> str:
    """The packaged config/trend.yaml (files.config: the source tree's, else the installed one)."""
    return str(config_file("trend.yaml"))


@dataclass(frozen=True)
class Trend:
    points: int
    last_time_s: float
    last_width_m: float
    rate_m_per_day: float        # NaN with fewer than two distinct times
    days_to_limit: float         # at that rate, from the last width to error_width_m (inf if <= 0)
    level: str
    reason: str


def slope_per_day(times_s, widths_m) -> float:
    """Least-squares slope [m/day]; NaN with fewer than two distinct times."""
    n = len(times_s)
    if n < 2:
        return math.nan
    t0 = min(times_s)
    xs = [(t - t0) / SECONDS_PER_DAY for t in times_s]
    mx, my = sum(xs) / n, sum(widths_m) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0.0:
        return math.nan
    return sum((x - mx) * (y - my) for x, y in zip(xs, widths_m)) / sxx


def drive_trend(points, rule: TrendRule, min_span_s: float = 0.0) -> Trend:
    """``points``: [(time_s, width_m)] of one drive, any order; NaN widths are left out.
    No rate (NaN) while the points span less than ``min_span_s``."""
    pts = sorted((t, w) for t, w in points if not math.isnan(w))
    if not pts:
        return Trend(0, math.nan, math.nan, math.nan, math.nan, "STALE", "no estimate")
    times, widths = [t for t, _ in pts], [w for _, w in pts]
    rate = slope_per_day(times, widths) if times[-1] - times[0] >= min_span_s else math.nan
    last = widths[-1]
    days = ((rule.error_width_m - last) / rate if rate == rate and rate > 0 else math.inf)
    if last >= rule.error_width_m:
        level, reason = "ERROR", f"width {last * 1e3:.2f} mm >= {rule.error_width_m * 1e3:g} mm"
    elif rate == rate and rate > rule.warn_growth_m_per_day:
        level, reason = "WARN", (f"grows {rate * 1e3:.3f} mm/day > "
                                 f"{rule.warn_growth_m_per_day * 1e3:g} mm/day: reaches "
                                 f"{rule.error_width_m * 1e3:g} mm in {days:.0f} days")
    elif last >= rule.warn_width_m:
        level, reason = "WARN", f"width {last * 1e3:.2f} mm >= {rule.warn_width_m * 1e3:g} mm"
    else:
        level, reason = "OK", "" if rate == rate else (
            "one recording: no trend yet" if min_span_s <= 0 else
            f"no trend yet: {(times[-1] - times[0]) / 3600:.1f} h of {min_span_s / 3600:g} h")
    return Trend(len(pts), times[-1], last, rate, days, level, reason)


class LiveTrend:
    """:func:`drive_trend` over a running drive's fused (continuous) widths.

    ``add(time_s, width_m)`` as estimates come (time: the window's stamp); one point per
    ``rule.live_point_period_s`` (the median time and width of that period's estimates, whatever
    the onset rate; the trend is taken when a period closes), points older than ``rule.live_history_s`` before
    the newest dropped, no rate while they span less than ``rule.live_min_span_s``. An estimate
    older than the period being collected (out of order) or non-finite is not used (counted).
    """

    def __init__(self, rule: TrendRule):
        self.rule = rule
        self.points: list[tuple[float, float]] = []     # closed periods: (time_s, width_m)
        self._period = None                              # index of the period being collected
        self._open: list[tuple[float, float]] = []
        self._cached = None
        self.ignored = 0

    def add(self, time_s: float, width_m: float) -> None:
        if not (math.isfinite(time_s) and math.isfinite(width_m)):
            self.ignored += 1
            return
        period = math.floor(time_s / self.rule.live_point_period_s)
        if self._period is not None and period < self._period:
            self.ignored += 1
            return
        if period != self._period:
            if self._open:
                self.points.append(self._median(self._open))
            self._period, self._open = period, []
            horizon = time_s - self.rule.live_history_s
            if self.points and self.points[0][0] < horizon:
                self.points = [p for p in self.points if p[0] >= horizon]
        self._open.append((time_s, width_m))

    @property
    def open_samples(self) -> list:
        """The (time_s, width_m) of the period being collected (not a point yet)."""
        return list(self._open)

    @staticmethod
    def _median(samples):
        return (statistics.median(t for t, _ in samples), statistics.median(w for _, w in samples))

    def trend(self) -> Trend:
        """The trend over the closed periods (recomputed when one closes); before the first
        closes, over the period being collected."""
        if not self.points:
            return drive_trend([self._median(self._open)] if self._open else [], self.rule,
                               self.rule.live_min_span_s)
        key = (len(self.points), self.points[-1])
        if self._cached is None or self._cached[0] != key:
            self._cached = (key, drive_trend(self.points, self.rule, self.rule.live_min_span_s))
        return self._cached[1]


LIVE_STATE_VERSION = 1


def save_live_points(path: str, drive: str, trend: "LiveTrend") -> None:
    """The live trend's closed points (and the period being collected) as JSON, written to a
    temporary file and renamed over ``path``: a crash while writing leaves the previous file."""
    state = {"version": LIVE_STATE_VERSION, "drive": drive, "points": trend.points,
             "open": trend.open_samples}
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        json.dump(state, f)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def load_live_points(path: str, drive: str, trend: "LiveTrend") -> str:
    """Feeds a saved state's points into ``trend`` (a fresh one); returns "" or why nothing was
    taken: no file yet is not a problem (""), a damaged file, another drive's or another version's
    is (the trend then starts anew, and the reason is shown)."""
    try:
        with open(path, encoding="utf-8") as f:
            state = json.load(f)
    except FileNotFoundError:
        return ""
    except (OSError, ValueError) as error:
        return f"state file {path} not read ({error}): the trend starts anew"
    if not isinstance(state, dict) or state.get("version") != LIVE_STATE_VERSION:
        return f"state file {path} has no version-{LIVE_STATE_VERSION} trend state: the trend starts anew"
    if state.get("drive") != drive:
        return (f"state file {path} holds drive {state.get('drive')!r}, not {drive!r}: the trend "
                "starts anew")
    try:
        samples = [(float(t), float(w)) for t, w in list(state["points"]) + list(state["open"])]
    except (KeyError, TypeError, ValueError):
        return f"state file {path}: points are not [time_s, width_m] pairs: the trend starts anew"
    for t, w in sorted(samples):
        trend.add(t, w)     # the rule of add(): periods, history, non-finite values left out
    return ""


def plot_trends(points_by_drive: dict, trends: dict, rule: TrendRule, out_dir) -> list:
    """A PNG per drive (width per recording over time, the fitted trend, the limits) and a
    fleet PNG with every drive; returns the paths written."""
    # deferred: matplotlib.pyplot costs ~900 ms at start-up (python -X importtime, 29 Nov)
    import matplotlib
    matplotlib.use("Agg")
    # deferred: as matplotlib above
    import matplotlib.pyplot as plt
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []

    def draw(ax, drive, pts, trend, label=None):
        pts = sorted((t, w) for t, w in pts if w == w)
        if not pts:
            return
        ts = [datetime.fromtimestamp(t, timezone.utc) for t, _ in pts]
        ax.plot(ts, [w * 1e3 for _, w in pts], "o-", label=label or drive, ms=4)
        if trend.rate_m_per_day == trend.rate_m_per_day and len(pts) >= 2:
            t_last = pts[-1][0]
            fit = [trend.last_width_m + trend.rate_m_per_day * (t - t_last) / SECONDS_PER_DAY
                   for t, _ in pts]
            ax.plot(ts, [w * 1e3 for w in fit], "--", color="grey", lw=1)

    def limits(ax):
        ax.axhline(rule.warn_width_m * 1e3, color="orange", lw=1, label="warn width")
        ax.axhline(rule.error_width_m * 1e3, color="red", lw=1, label="error width")
        ax.set_ylabel("backlash width [mm]")
        ax.set_xlabel("recording time (UTC)")
        ax.grid(alpha=0.3)

    for drive, pts in sorted(points_by_drive.items()):
        fig, ax = plt.subplots(figsize=(7, 3.5))
        draw(ax, drive, pts, trends[drive])
        limits(ax)
        t = trends[drive]
        rate = "-" if t.rate_m_per_day != t.rate_m_per_day else f"{t.rate_m_per_day * 1e3:+.3f} mm/day"
        ax.set_title(f"{drive}: {t.level} {rate} {t.reason}", fontsize=9)
        ax.legend(fontsize=7, loc="upper left")
        fig.autofmt_xdate()
        path = out_dir / f"trend_{drive.replace('/', '_')}.png"
        fig.savefig(path, dpi=100, bbox_inches="tight")
        plt.close(fig)
        written.append(path)
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for drive, pts in sorted(points_by_drive.items()):
        draw(ax, drive, pts, trends[drive])
    limits(ax)
    ax.set_title(f"fleet: {len(points_by_drive)} drives")
    ax.legend(fontsize=7, ncol=2, loc="upper left")
    fig.autofmt_xdate()
    path = out_dir / "trend_fleet.png"
    fig.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(fig)
    written.append(path)
    return written
