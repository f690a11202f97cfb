"""`python -m backlash_monitor bag-info`: ros2-bag-info-like output; clear errors and exit codes."""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from backlash_monitor.__main__ import main as cli
from backlash_monitor.bag import SIGNAL_CHUNK, BagWriter
from bag_helpers import T0, write_sample_bag

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def bag(tmp_path_factory):
    path = tmp_path_factory.mktemp("cli") / "run.mcap"
    write_sample_bag(path, n_chunks=30)
    return path


def test_info_shows_duration_topics_types_counts(bag, capsys):
    assert cli(["bag-info", str(bag)]) == 0
    out = capsys.readouterr().out
    assert "Duration:          0.580000004s" in out
    assert "Messages:          159" in out
    assert ("Topic: /plant/a1 | Type: backlash_monitor_msgs/msg/SignalChunk | Count: 30 | "
            "Serialization Format: cdr") in out
    assert "Topic: /diagnostics | Type: diagnostic_msgs/msg/DiagnosticArray | Count: 3" in out
    assert "Integrity:         complete" in out


def test_info_json_and_topic_details(bag, capsys):
    assert cli(["bag-info", str(bag), "--format", "json", "--topic", "/plant/a2", "--topic", "/estimate"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["messages"] == 159 and info["complete"] and info["ros_distro"] == "jazzy"
    d = info["details"]["/plant/a2"]
    assert d["samples"] == 30_000 and d["gap_count"] == 0 and d["sample_rate_hz"] == pytest.approx(5e4)
    assert info["details"]["/estimate"] == {"decoded_messages": 3}


@pytest.mark.process
def test_truncated_bag_is_a_clear_error_and_recover_reads_the_rest(tmp_path, bag, capsys):
    data = bag.read_bytes()
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(data[: len(data) * 2 // 3])
    proc = subprocess.run([sys.executable, "-m", "backlash_monitor", "bag-info", str(cut)],
                          capture_output=True, text=True, cwd=REPO, timeout=60)
    assert proc.returncode == 1
    assert "incomplete" in proc.stderr and "Traceback" not in proc.stderr + proc.stdout
    assert cli(["bag-info", str(cut), "--recover"]) == 0
    out = capsys.readouterr().out
    assert "INCOMPLETE" in out and "trailing byte(s) lost" in out


def test_unknown_schema_missing_topic_and_bad_files(tmp_path, bag, capsys):
    odd = tmp_path / "odd.mcap"
    with BagWriter(odd) as w:
        w.add_topic("/plant/a1", SIGNAL_CHUNK)
        w.write("/plant/a1", {"samples": np.zeros(3)}, log_time_ns=T0)
        w.add_topic("/weird", "foo_msgs/msg/Weird", definition="float64[ broken\n", type_hash="")
        w.write_raw("/weird", b"\x00\x01\x00\x00", log_time_ns=T0)
    assert cli(["bag-info", str(odd)]) == 1
    cap = capsys.readouterr()
    assert "SCHEMA ERROR" in cap.out and "topic /weird" in cap.err and "foo_msgs/msg/Weird" in cap.err

    assert cli(["bag-info", str(bag), "--topic", "/nope"]) == 2
    err = capsys.readouterr().err
    assert "'/nope' is not in the bag" in err and "/plant/a1" in err

    assert cli(["bag-info", str(tmp_path / "missing.mcap")]) == 2
    assert "does not exist" in capsys.readouterr().err
    text = tmp_path / "notes.mcap"
    text.write_text("not a bag\n" * 10)
    assert cli(["bag-info", str(text)]) == 2
    assert "not an MCAP file" in capsys.readouterr().err
