"""train / evaluate commands: bad input -> a clear message naming the problem, exit 2, no traceback."""
import subprocess
import sys

import pytest


def _run(*args):
    return subprocess.run([sys.executable, "-m", "backlash_monitor", *args], capture_output=True, text=True,
                          timeout=120)


@pytest.mark.process
@pytest.mark.parametrize("args, expected", [
    (("train", "--epochs", "0"), "--epochs 0: out of range, allowed 1..inf"),
    (("train", "--l1", "2"), "--l1 2: out of range, allowed 0..1"),
    (("train", "--output", "lib.txt"), "give a name ending in .npz"),
    (("train", "--trigger", "eq1"), "invalid choice: 'eq1'"),
    (("train", "--seeds", "a,b"), "not a comma-separated list of integers"),
    (("evaluate", "--fusion-events", "9"), "--fusion-events 9: out of range, allowed 1..8"),
    (("evaluate", "--library", "foo"), "give TRIGGER=FILE.npz"),
    (("evaluate", "--library", "eq1=x.npz"), "unknown trigger 'eq1'; allowed: paper, contact_loss"),
    (("evaluate", "--trigger", "paper", "--library", "paper=/nonexistent/x.npz"), "does not exist"),
    (("evaluate", "--trigger", "paper", "--seeds", "1000"), "trained the paper library"),
])
def test_bad_input_exit_2_with_message(args, expected):
    r = _run(*args)
    assert r.returncode == 2, r.stderr
    assert expected in r.stderr
    assert "Traceback" not in r.stderr


@pytest.mark.process
@pytest.mark.parametrize("command", ["train", "evaluate"])
def test_help_explains_every_option(command):
    r = _run(command, "--help")
    assert r.returncode == 0
    for option in (("--output", "--trigger", "--seeds", "--epochs", "--l1", "--l2", "--ridge", "--duration")
                   if command == "train" else ("--out-dir", "--trigger", "--seeds", "--library", "--fusion-events",
                                               "--unseen-seeds", "--no-plots")):
        assert option in r.stdout
