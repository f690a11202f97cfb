"""The monitor on host A of the two-host run (ros/netns.py): counts a drive's onset estimates
coming back from host B and its windowing's onset windows (from /diagnostics; and those published
before the sensor offset was known, which are not classified); prints one JSON line.

    python -m backlash_monitor.nodes.two_host_monitor /line1/drive01 SECONDS
"""
from __future__ import annotations

import json
import sys
import time

import rclpy
from diagnostic_msgs.msg import DiagnosticArray
from backlash_monitor_msgs.msg import BacklashEstimate

from backlash_monitor.ros.qos import ESTIMATE_QOS

QUIET_S = 2.5            # [s] no change in the counts for this long ...
SETTLED_REPORTS = 3      # ... and over this many of the windowing's diagnostics (1 Hz) after the last change


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    namespace, wall_limit_s = argv[0], float(argv[1])
    rclpy.init()
    node = rclpy.create_node("two_host_monitor")
    onsets, windowing = set(), {}
    node.create_subscription(BacklashEstimate, f"{namespace}/estimate",
                             lambda m: onsets.add(m.entry_sample_index), ESTIMATE_QOS)

    reports = [0]            # the windowing's diagnostics received

    def on_diag(msg):
        for s in msg.status:
            if s.name.endswith("windowing: windowing"):
                windowing.update({kv.key: kv.value for kv in s.values})
                reports[0] += 1
    node.create_subscription(DiagnosticArray, "/diagnostics", on_diag, 10)
    started = time.monotonic()
    last_change, last, reports_at_change = started, (0, 0), 0
    while time.monotonic() - started < wall_limit_s:
        rclpy.spin_once(node, timeout_sec=0.1)
        # settled: no new estimate, onset window or chunk for QUIET_S, and over SETTLED_REPORTS of the windowing's
        # diagnostics (once a second): on a loaded machine its timer runs late, and a quiet time alone ended the count
        # one report before the last chunk's (measured: 199 of 200 chunks at load 5, 30 Nov)
        state = (len(onsets), int(windowing.get("onsets", 0))
                 - int(windowing.get("onsets_before_offset", 0)), windowing.get("chunks"))
        if state != last:
            last, last_change, reports_at_change = state, time.monotonic(), reports[0]
        if (state[1] and state[0] >= state[1] and time.monotonic() - last_change > QUIET_S
                and reports[0] - reports_at_change >= SETTLED_REPORTS):
            break
    print(json.dumps({"onsets_estimated": len(onsets),
                      "onset_windows": int(windowing.get("onsets", 0)),
                      "onsets_before_offset": int(windowing.get("onsets_before_offset", 0)),
                      "chunks": int(windowing.get("chunks", 0)),
                      "discarded": int(windowing.get("discarded", 0)),
                      # where a lost chunk went: the stream joined late, a range never completed
                      "joined_at_sample": int(windowing.get("joined_at_sample", 0)),
                      "incomplete_chunks": int(windowing.get("incomplete_chunks", 0)),
                      "input_faults": windowing.get("input_faults", "")}), flush=True)
    node.destroy_node()
    rclpy.try_shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
