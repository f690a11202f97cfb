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


def test_train_refuses_an_existing_library(tmp_path):
    lib = tmp_path / "lib.npz"
    lib.write_bytes(b"an older library")
    _refused(_run("train", "--out", lib, "--no-progress"), lib, b"an older library")


@pytest.mark.parametrize("name", ["evaluation.json", "confusion_paper.png"])
def test_evaluate_refuses_existing_outputs(tmp_path, name):
    kept = tmp_path / name
    kept.write_bytes(b"earlier figures")
    _refused(_run("evaluate", "--trigger", "paper", "--out-dir", tmp_path, "--no-progress"), kept,
             b"earlier figures")
