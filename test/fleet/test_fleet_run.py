"""`fleet`: several simulated drives on this machine, each in its namespace, in both layouts."""
import json
import subprocess
import sys

import pytest


@pytest.mark.process
@pytest.mark.ros
@pytest.mark.parametrize("layout", ["process", "single"])
def test_two_drives_each_report_their_own_estimates_and_diagnostics(ros_env, tmp_path, layout):
    summary = tmp_path / "summary.json"
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "fleet", "--drives", "2",
                           "--width-m", "0.008", "--duration", "2.5", "--layout", layout,
                           "--view-period", "0", "--json", str(summary),
                           "--trend-state-dir", str(tmp_path / "trend")],
                          env=ros_env, capture_output=True, text=True, timeout=150)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    rows = {r["drive"]: r for r in json.loads(summary.read_text())["drives"]}
    assert set(rows) == {"line1/drive01", "line1/drive02"}
    for row in rows.values():
        # 2.5 s of stream: 125 chunks, 10 onsets (one every 0.25 s, README); the first before the
        # sensor offset is known (one whole load period): 9 classified.
        assert row["chunks"] == row["expected_chunks"] == 125, row
        assert row["discarded"] == 0
        assert row["onset_windows"] == 10 and row["onsets_before_offset"] == 1, row
        assert row["onsets_estimated"] == 9, row
        assert row["true_width_m"] == 0.008
        # the fused continuous width ~8.0 mm >= warn_width_m 7.5 mm, < error_width_m 9 mm (config/diagnostics.yaml;
        # the class width, the nearest pattern width, would be 7.5 mm)
        assert row["level"] == "WARN"
        assert row["status_times"], row    # its classifier's status reached /diagnostics
    assert "line1/drive02" in proc.stdout and "Traceback" not in proc.stderr
    # the summary table's width is the fused continuous width with its uncertainty (what the level follows); the
    # class width is the column beside it, named for what it is
    lines = proc.stdout.splitlines()
    at = next(i for i, line in enumerate(lines) if line.split()[:4] == ["drive", "true", "width", "nearest"])
    for line in lines[at + 2:at + 2 + len(rows)]:      # the header, its rule, a row per drive
        true, width = line.split()[1:3], line.split()[3:6]
        assert true == ["8.00", "mm"] and width[1] == "±", line
    # each drive's live trend was kept at shutdown, under its own name, with its own widths (the
    # fused continuous width near 8 mm). Trend periods are wall-clock minutes, so a 2.5 s run
    # closes at most one point (when it straddles a minute boundary); the period being collected
    # always holds the latest estimates.
    for drive in rows:
        state = json.loads((tmp_path / "trend" / f"{drive.replace('/', '_')}.json").read_text())
        assert state["drive"] == drive and len(state["points"]) <= 1, state
        assert len(state["open"]) >= (5 if not state["points"] else 1), state
        widths = [w for _, w in state["points"] + state["open"]]
        assert all(abs(w - 0.008) < 5e-4 for w in widths), state
