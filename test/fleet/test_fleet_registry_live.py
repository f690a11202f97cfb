"""A live fleet picks up one drive's new model version from its registry, by lifecycle transitions of that drive's
chain only; a version the chain cannot take leaves that drive on its old one (docs/registry.md, live pickup)."""
import json
import shutil
import subprocess
import sys
import threading
import time

import pytest

from backlash_monitor.classifier.patterns import TRIGGER_LIBRARY_PATHS
from backlash_monitor.files import registry

FLEET = """\
lines:
  line1:
    drive01: {width_m: 0.005, seed: 1}
    drive02: {width_m: 0.0075, seed: 2}
    drive03: {width_m: 0.005, seed: 3}
"""
DURATION_S = 8.0


@pytest.mark.process
@pytest.mark.ros
def test_one_drive_takes_its_new_version_live_and_the_others_run_on(ros_env, tmp_path):
    reg = tmp_path / "drives.yaml"
    reg.write_text(FLEET)
    # version 2 of drive02: a library file of its own (the packaged one's content: a valid library)
    shutil.copy(TRIGGER_LIBRARY_PATHS["contact_loss"], tmp_path / "drive02_v2.npz")
    # version 2 of drive03: a readable library made for the other trigger: its classifier refuses it at configure
    shutil.copy(TRIGGER_LIBRARY_PATHS["paper"], tmp_path / "drive03_v2.npz")
    summary = tmp_path / "summary.json"
    proc = subprocess.Popen([sys.executable, "-m", "backlash_monitor", "fleet", "--config", str(reg),
                             "--duration", str(DURATION_S), "--view-period", "0", "--json", str(summary)],
                            env=ros_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lines, streaming = [], threading.Event()

    def read_stderr():
        for line in proc.stderr:
            lines.append(line)
            if "drives streaming" in line:
                streaming.set()
    reader = threading.Thread(target=read_stderr, daemon=True)
    reader.start()
    try:
        assert streaming.wait(90), "".join(lines[-20:])
        time.sleep(1.5)
        registry.register(reg, "line1/drive02", library=tmp_path / "drive02_v2.npz")
        written_s = time.time()
        registry.register(reg, "line1/drive03", library=tmp_path / "drive03_v2.npz")
        out, _ = proc.communicate(timeout=120)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate()
    reader.join(5)
    err = "".join(lines)
    assert proc.returncode == 0, out + err
    assert "Traceback" not in err
    result = json.loads(summary.read_text())
    rows = {r["drive"]: r for r in result["drives"]}
    events = [(e["drive"], e["event"], e["version"]) for e in result["registry_events"]]

    # drive02 runs its new version, reported by its classifier within the bound
    assert rows["line1/drive02"]["model_version"] == 2 and rows["line1/drive02"]["library"].endswith("drive02_v2.npz")
    # (the pickup's time is the bench's measure, bench/fleet.py --parts registry_loop: tests assert no wall-clock time)
    assert rows["line1/drive02"]["versions_seen_wall_s"]["2"] > written_s, rows["line1/drive02"]
    assert ("line1/drive02", "swapped", 2) in events

    # drive03's version 2 was refused by its chain: back on version 1, estimating again, with the reason
    assert ("line1/drive03", "refused", 2) in events, events
    refused = next(e for e in result["registry_events"] if e["drive"] == "line1/drive03" and e["event"] == "refused")
    assert "refused it at configure" in refused["detail"]
    assert rows["line1/drive03"]["model_version"] == 1
    assert rows["line1/drive03"]["library"].endswith("patterns.npz")
    assert rows["line1/drive03"]["last_estimate_wall_s"] > refused["wall_s"], rows["line1/drive03"]

    # drive01 was never touched: no transition sent, every chunk taken, every onset estimated, same version
    assert not [e for e in events if e[0] == "line1/drive01"]
    d1 = rows["line1/drive01"]
    assert d1["chain_restarts"] == 0 and d1["model_version"] == 1
    assert d1["chunks"] == d1["expected_chunks"] == int(DURATION_S / 0.02) and d1["discarded"] == 0
    assert d1["onsets_estimated"] == d1["onset_windows"] - d1["onsets_before_offset"] > 0, d1
    assert d1["onsets_before_offset"] == 1     # the stream's first onset only: its windowing never started anew
