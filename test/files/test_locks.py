"""files/locks.py: one process at a time holds the lock; the others wait for it; no lock where none can be taken."""
import multiprocessing as mp
import os
import time

from backlash_monitor.files.locks import exclusive


def _hold(path, log, hold_s):
    with exclusive(path):
        with open(log, "a") as f:
            f.write(f"in {os.getpid()}\n")
        time.sleep(hold_s)
        with open(log, "a") as f:
            f.write(f"out {os.getpid()}\n")


def test_holders_take_turns(tmp_path):
    log = tmp_path / "log"
    ctx = mp.get_context("fork")
    procs = [ctx.Process(target=_hold, args=(tmp_path / "a" / "x.lock", log, 0.3)) for _ in range(3)]
    for p in procs:
        p.start()
    for p in procs:
        p.join(30)
    lines = log.read_text().split()
    # each holder's "in" is followed by its own "out" before the next "in": never two inside at once
    events = list(zip(lines[0::2], lines[1::2]))
    assert len(events) == 6
    for (a, pa), (b, pb) in zip(events[0::2], events[1::2]):
        assert (a, b) == ("in", "out") and pa == pb, lines


def test_a_lock_that_cannot_be_taken_holds_nothing(tmp_path):
    # its directory cannot exist: a file is in the way (even root cannot make it)
    (tmp_path / "a_file").write_text("")
    ran = []
    with exclusive(tmp_path / "a_file" / "x.lock"):
        ran.append(1)
    assert ran == [1]
