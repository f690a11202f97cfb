"""Foxglove's TypeScript stack (@mcap/core + @mcap/support + @foxglove/rosmsg +
@foxglove/rosmsg2-serialization, versions pinned in test/interop/package-lock.json) reads our bag:
every message decodes and equals what was written."""
from __future__ import annotations

import json
import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from bag_helpers import write_sample_bag

INTEROP = Path(__file__).resolve().parents[1] / "interop"
_INT = re.compile(r"^-?\d+$")


def _norm(v):
    if isinstance(v, dict):
        return {k: _norm(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_norm(x) for x in v]
    if hasattr(v, "tolist"):
        return _norm(v.tolist())
    if isinstance(v, float):
        if math.isnan(v):
            return "NaN"
        if math.isinf(v):
            return "Infinity" if v > 0 else "-Infinity"
        return v
    if isinstance(v, str) and _INT.match(v):
        return int(v)
    return v


@pytest.fixture(scope="module")
def node_modules():
    if shutil.which("node") is None or shutil.which("npm") is None:
        pytest.skip("node/npm are not installed: the Foxglove TypeScript interop check needs them")
    if not (INTEROP / "node_modules" / "@mcap" / "core").is_dir():
        proc = subprocess.run(["npm", "ci", "--no-audit", "--no-fund", "--ignore-scripts"],
                              cwd=INTEROP, capture_output=True, text=True, timeout=600)
        assert proc.returncode == 0, f"npm ci failed:\n{proc.stdout}\n{proc.stderr}"
    return INTEROP / "node_modules"


@pytest.mark.process
def test_foxglove_typescript_libraries_decode_every_message(node_modules, tmp_path):
    bag = tmp_path / "interop.mcap"
    written = write_sample_bag(bag, n_chunks=12)
    proc = subprocess.run(["node", str(INTEROP / "read_bag.mjs"), str(bag)], capture_output=True,
                          text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    out = json.loads(proc.stdout)
    assert out["header"]["profile"] == "ros2"
    assert out["chunkCompression"] == ["zstd"]
    assert [m["name"] for m in out["metadata"]] == ["backlash_monitor.writer", "rosbag2"]
    assert {s["encoding"] for s in out["schemas"]} == {"ros2msg"}
    for ch in out["channels"]:
        assert ch["messageEncoding"] == "cdr"
        assert set(ch["metadata"]) == {"offered_qos_profiles", "topic_type_hash"}
    assert int(out["statistics"]["messageCount"]) == sum(len(m) for m in written.values())
    got: dict[str, list] = {}
    for m in out["messages"]:
        got.setdefault(m["topic"], []).append(m)
    assert {t: len(m) for t, m in got.items()} == {t: len(m) for t, m in written.items()}
    for topic, msgs in written.items():
        got[topic].sort(key=lambda m: m["sequence"])
        for w, g in zip(msgs, got[topic]):
            assert _norm(g["message"]) == _norm(w.to_dict()), topic
