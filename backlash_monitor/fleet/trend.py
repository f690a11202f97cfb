"""The width trend of each drive over its recordings, and the WARN it earns before the limit.

A drive's points are (time [s since the epoch], fused width [m]): one per analysed recording (its
last fused estimate, docs/classifier.md). The trend is the least-squares slope of width over time
[m/day]. A drive is

- ERROR when its last fused width has reached ``error_width_m`` (as the live diagnostics),
- WARN when it has reached ``warn_width_m`` or when it grows faster than
  ``warn_growth_m_per_day``: the second warns a drive that is still narrow but wearing fast,
  before it reaches the limit, with the days left at that rate,
- OK otherwise.

config/trend.yaml gives the rate with its reason.
"""
from __future__ import annotations

import math
import os
from dataclasses import dataclass

SECONDS_PER_DAY = 86400.0


@dataclass(frozen=True)
class TrendRule:
    warn_growth_m_per_day: float
    warn_width_m: float
    error_width_m: float


def load_rule(path: str | None = None) -> TrendRule:
    import yaml
    path = path or _default_path()
    with open(path, encoding="utf-8") as f:
        cfg = yaml.safe_load(f)
    return TrendRule(float(cfg["warn_growth_m_per_day"]), float(cfg["warn_width_m"]),
                     float(cfg["error_width_m"]))


def _default_path() -> str:
    here = os.path.join(os.path.dirname(__file__), "..", "..", "config", "trend.yaml")
    if os.path.isfile(here):
        return os.path.normpath(here)
    from ament_index_python.packages import get_package_share_directory
    return os.path.join(get_package_share_directory("backlash_monitor"), "config", "trend.yaml")


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


def drive_trend(points, rule: TrendRule) -> Trend:
    """``points``: [(time_s, fused_width_m)] of one drive, any order; NaN widths are left out."""
    pts = sorted((t, w) for t, w in points if not math.isnan(w))
    if not pts:
        return Trend(0, math.nan, math.nan, math.nan, math.nan, "STALE", "no estimate")
    times, widths = [t for t, _ in pts], [w for _, w in pts]
    rate = slope_per_day(times, widths)
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
        level, reason = "OK", "" if rate == rate else "one recording: no trend yet"
    return Trend(len(pts), times[-1], last, rate, days, level, reason)


def plot_trends(points_by_drive: dict, trends: dict, rule: TrendRule, out_dir) -> list:
    """A PNG per drive (fused width per recording over time, the fitted trend, the limits) and a
    fleet PNG with every drive; returns the paths written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from datetime import datetime, timezone
    from pathlib import Path
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
        ax.set_ylabel("fused backlash width [mm]")
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
