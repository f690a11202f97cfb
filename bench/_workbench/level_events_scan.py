"""How many drives of the independent simulator (foreign_drives/) get a wrong width level -- WARN with the true width
below warn_width_m, or ERROR with it below error_width_m (config/diagnostics.yaml) -- on some estimate, by the
number of onset events the estimate fuses (1-2: no standard error, the signal check cannot test it; 3-7; a full
fusion of 8), and with the classifier's level rule (estimation.estimate_level: no level from fewer than
LEVEL_MIN_EVENTS). Every estimate of a1+a2 as the monitor publishes it (workbench/width.monitor_widths, packaged
library). One JSON object on stdout, progress on stderr.

    python bench/_workbench/level_events_scan.py [SUITE ...]   # default: the alarm check's suites (the foreign
                                                                # bench and every outside suite, never an unspent
                                                                # sealed half: width_caveat.alarm_suites)
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import yaml  # noqa: E402

from _workbench.outside import _measurement  # noqa: E402  (registers the forms first)
from _workbench.width_caveat import alarm_suites  # noqa: E402
from foreign_drives.suites import SUITE_NAMES, suite  # noqa: E402

from backlash_monitor.estimation import estimate_level, level_width, width_level  # noqa: E402
from backlash_monitor.workbench.width import monitor_widths  # noqa: E402

PARAMS = yaml.safe_load((ROOT / "config" / "diagnostics.yaml").read_text())["/**"]["ros__parameters"]
WARN_M, ERROR_M = float(PARAMS["warn_width_m"]), float(PARAMS["error_width_m"])


def _wrong(level: str, truth_m: float) -> bool:
    return (level == "ERROR" and truth_m < ERROR_M) or (level == "WARN" and truth_m < WARN_M)


def row_of(name: str, spec) -> dict:
    meas, truth_of = _measurement(spec)
    truth = truth_of.true_width_m
    trace = monitor_widths(meas)
    widths = [level_width(c, f) for c, f in zip(trace.fused_continuous_m, trace.fused_m)]
    events = [int(n) for n in trace.fused_events]
    alone = [_wrong(width_level(w, WARN_M, ERROR_M), truth) for w in widths]
    ruled = [_wrong(estimate_level(w, n, WARN_M, ERROR_M), truth) for w, n in zip(widths, events)]
    return {"suite": name, "label": spec.label, "clean": spec.kind == "clean", "true_width_mm": truth * 1e3,
            "wrong_1_2_events": sum(a for a, n in zip(alone, events) if n < 3),
            "wrong_3_7_events": sum(a for a, n in zip(alone, events) if 3 <= n < 8),
            "wrong_full": sum(a for a, n in zip(alone, events) if n >= 8),
            "wrong_with_the_rule": sum(ruled), "estimates": len(events)}


def main(suites) -> dict:
    rows = []
    for name in suites:
        for spec in suite(name):
            rows.append(row_of(name, spec))
            print(f"[levels] {name} {spec.label}: {rows[-1]}", file=sys.stderr)

    def count(rs, key):
        return sum(r[key] > 0 for r in rs)
    out = {"command": "python bench/_workbench/level_events_scan.py " + " ".join(suites), "recordings": len(rows),
           "warn_width_m": WARN_M, "error_width_m": ERROR_M}
    for part, rs in (("all", rows), ("clean", [r for r in rows if r["clean"]]),
                     ("with_a_mechanism", [r for r in rows if not r["clean"]])):
        before = sum(any(r[k] for k in ("wrong_1_2_events", "wrong_3_7_events", "wrong_full")) for r in rs)
        only_early = sum(r["wrong_1_2_events"] > 0 and not (r["wrong_3_7_events"] or r["wrong_full"]) for r in rs)
        out[part] = {"recordings": len(rs), "wrong_level_on_some_estimate": before,
                     "wrong_only_on_1_or_2_events": only_early, "wrong_with_the_rule": count(rs, "wrong_with_the_rule")}
    out["per_recording_wrong"] = [r for r in rows if r["wrong_1_2_events"] or r["wrong_3_7_events"] or r["wrong_full"]]
    return out


if __name__ == "__main__":
    names = sys.argv[1:] or alarm_suites()
    unknown = [n for n in names if n not in SUITE_NAMES]
    if unknown:
        sys.exit(f"level_events_scan: unknown suite(s) {', '.join(unknown)}; allowed: {', '.join(SUITE_NAMES)}")
    print(json.dumps(main(names)))
