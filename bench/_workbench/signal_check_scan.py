"""The signal check's rule for a censored a1+a2 (classifier/signal_check.py, since stop 58) against the rule before,
on recordings of the independent simulator (foreign_drives/): per recording the mean |fused width - true width| over
the full fusions of what the monitor publishes (workbench/width.monitor_widths, a1+a2 with the packaged library),
under both rules on the same recording (the rule before: a censored a1+a2 never checked), and how many full fusions
sit at the range's top. One JSON object on stdout, progress on stderr.

    python bench/_workbench/signal_check_scan.py [SUITE ...]     # default: the alarm check's suites (the foreign
                                                                  # bench and every outside suite, never an unspent
                                                                  # sealed half: width_caveat.alarm_suites)
"""
from __future__ import annotations

import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "bench"))

import numpy as np  # noqa: E402

from _workbench.outside import _measurement  # noqa: E402  (registers the forms first)
from _workbench.width_caveat import alarm_suites  # noqa: E402
from foreign_drives.suites import SUITE_NAMES, suite  # noqa: E402

from backlash_monitor.classifier import signal_check  # noqa: E402
from backlash_monitor.estimation import DEFAULT_FUSION_EVENTS  # noqa: E402
from backlash_monitor.workbench.width import monitor_widths  # noqa: E402

TOP_M = 19.9e-3     # a full fusion at the range's top (shape.continuous_top_m: 20 mm for the paper's grid)


def row_of(name: str, spec) -> dict:
    meas, truth_of = _measurement(spec)
    truth = truth_of.true_width_m
    row = {"suite": name, "label": spec.label, "true_width_mm": truth * 1e3}
    rule = signal_check._censored_above
    try:
        for which, censored in (("before", lambda *a: False), ("since", rule)):
            signal_check._censored_above = censored
            trace = monitor_widths(meas)
            fused = trace.fused_continuous_m[trace.fused_events >= DEFAULT_FUSION_EVENTS]
            row[f"{which}_mm"] = float(np.mean(np.abs(fused - truth)) * 1e3) if fused.size else None
            row[f"{which}_at_top"] = int(np.sum(fused >= TOP_M))
    finally:
        signal_check._censored_above = rule
    return row


def main(suites) -> dict:
    rows = []
    for name in suites:
        for spec in suite(name):
            rows.append(row_of(name, spec))
            print(f"[scan] {name} {spec.label}: {rows[-1]['before_mm']} -> {rows[-1]['since_mm']} mm", file=sys.stderr)
    ok = [r for r in rows if r["before_mm"] is not None]
    changed = [r for r in ok if r["before_mm"] != r["since_mm"]]
    clean = [r for r in ok if "clean" in r["label"]]
    return {"command": "python bench/_workbench/signal_check_scan.py " + " ".join(suites),
            "recordings": len(rows), "with_full_fusions": len(ok),
            "mean_error_before_mm": statistics.mean(r["before_mm"] for r in ok),
            "mean_error_since_mm": statistics.mean(r["since_mm"] for r in ok),
            "recordings_with_a_fusion_at_top_before": sum(r["before_at_top"] > 0 for r in ok),
            "recordings_with_a_fusion_at_top_since": sum(r["since_at_top"] > 0 for r in ok),
            "changed": changed, "worse": [r["label"] for r in ok if r["since_mm"] > r["before_mm"] + 1e-9],
            "clean_recordings": len(clean),
            "clean_mean_error_before_mm": statistics.mean(r["before_mm"] for r in clean) if clean else None,
            "clean_mean_error_since_mm": statistics.mean(r["since_mm"] for r in clean) if clean else None}


if __name__ == "__main__":
    names = sys.argv[1:] or alarm_suites()
    unknown = [n for n in names if n not in SUITE_NAMES]
    if unknown:
        sys.exit(f"signal_check_scan: unknown suite(s) {', '.join(unknown)}; allowed: {', '.join(SUITE_NAMES)}")
    print(json.dumps(main(names)))
