"""train, evaluate and simulate refuse to write over an existing file unless --overwrite, and say so
before any work (one line, exit 2, the file untouched)."""
import subprocess
import sys

import pytest


def _run(*args):
    return subprocess.run([sys.executable, "-m", "backlash_monitor", *map(str, args)],
                          capture_output=True, text=True, timeout=120)


def _refused(proc, path, before):
    assert proc.returncode == 2, proc.stderr
    assert "exists already" in proc.stderr and "--overwrite" in proc.stderr
    assert len(proc.stderr.strip().splitlines()) == 1 and "Traceback" not in proc.stderr
    assert path.read_bytes() == before


@pytest.mark.process
def test_train_refuses_an_existing_library(tmp_path):
    lib = tmp_path / "lib.npz"
    lib.write_bytes(b"an older library")
    _refused(_run("train", "--output", lib, "--no-progress"), lib, b"an older library")


@pytest.mark.process
@pytest.mark.parametrize("name", ["evaluation.json", "confusion_paper.png"])
def test_evaluate_refuses_existing_outputs(tmp_path, name):
    kept = tmp_path / name
    kept.write_bytes(b"earlier figures")
    _refused(_run("evaluate", "--trigger", "paper", "--out-dir", tmp_path, "--no-progress"), kept,
             b"earlier figures")


@pytest.mark.process
def test_simulate_refuses_an_existing_npz_and_bag_and_replaces_them_when_told(tmp_path):
    npz, bags = tmp_path / "sim.npz", tmp_path / "bags"
    args = ["simulate", "--widths", "0.005", "--eta-k", "0.025", "--n1", "0.89", "--duration", "0.1",
            "-o", npz, "--mcap", bags, "--no-progress"]
    npz.write_bytes(b"earlier run")
    _refused(_run(*args), npz, b"earlier run")
    npz.unlink()
    bags.mkdir()
    bag = bags / "w5mm_eta0.025_n0.89_s0.mcap"
    bag.write_bytes(b"a recording")
    _refused(_run(*args), bag, b"a recording")
    assert not npz.exists()                      # refused before anything was written
    proc = _run(*args, "--overwrite")
    assert proc.returncode == 0, proc.stderr
    from backlash_monitor.bag import BagReader
    with BagReader(bag) as reader:               # replaced by a complete bag that names itself
        assert reader.topics["/plant/a1"].count == 5
        assert reader.rosbag2_metadata["relative_file_paths"] == [bag.name]
    assert sorted(p.name for p in tmp_path.rglob("*.partial")) == []
    import numpy as np
    assert np.load(npz)["a1"].shape == (1, 5000)
