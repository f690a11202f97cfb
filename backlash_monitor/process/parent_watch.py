"""Child processes die with their parent, also when the parent is killed with SIGKILL.

A parent's handlers run on SIGINT or SIGTERM, never on SIGKILL (or a crash): children it started
would then run on for good, streaming into a graph nobody watches. Two mechanisms, no rclpy:

- :func:`preexec_fn` (Linux): the child asks the kernel, between fork and exec, for SIGTERM when
  its parent dies (``prctl(PR_SET_PDEATHSIG)``). SIGTERM makes a node shut down cleanly (rclpy's
  handler). The kernel sends it when the *thread* that started the child ends: start children
  from the thread that lives as long as the run (the pipeline's main thread does).
- :func:`start_watchdog` (any system, and should SIGTERM not end the child): a process started
  with ``BACKLASH_MONITOR_PARENT_PID`` in its environment checks every half second whether its
  parent is still that process; when not, it sends itself SIGTERM and, if it still runs
  ``grace_s`` later, exits at once. The node processes call it at start (``run_nodes``).
- A hard stop outside the interpreter (Linux): the watchdog's thread needs the GIL, and a main
  thread that blocks in C while it holds the GIL (a deadlock in a signal handler, a stuck library
  call) starves it: the process would outlive its parent for good (seen once in CI, a killed
  pipeline's classifier). So :func:`start_watchdog` also starts a small watcher *process*
  (:data:`_HARD_STOP_WATCHER`, a child of the node that dies with it by its own
  ``PR_SET_PDEATHSIG``), which SIGKILLs the node ``grace_s + HARD_STOP_MARGIN_S`` after the
  parent is gone, if it still runs: only when SIGTERM and the thread's exit have both failed.
"""
from __future__ import annotations

import ctypes
import os
import signal
import subprocess
import sys
import threading
import time

PARENT_PID_ENV = "BACKLASH_MONITOR_PARENT_PID"
PR_SET_PDEATHSIG = 1            # <linux/prctl.h>
DEATH_SIGNAL = signal.SIGTERM   # a clean ROS shutdown; the watchdog escalates
# The watcher process's SIGKILL comes this long [s] after the thread's own hard exit would have:
# the thread's exit is the normal second stage, the watcher only the last.
HARD_STOP_MARGIN_S = 2.0
_WATCHERS: list[subprocess.Popen] = []    # held for the process's life (no "still running" warning)

# The watcher, run as ``python -I -S -c`` (no site, no project import: it starts in tens of ms):
# argv node_pid parent_pid delay_s period_s. It dies with the node (PR_SET_PDEATHSIG SIGKILL), and
# ends when the node has ended; it reads the node's parent from /proc/<node>/stat (field 4).
_HARD_STOP_WATCHER = r"""
import ctypes, os, signal, sys, time
node, parent, delay_s, period_s = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
try:
    ctypes.CDLL(None, use_errno=True).prctl(1, int(signal.SIGKILL), 0, 0, 0)
except (OSError, AttributeError):
    pass
def parent_of(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return None if fields[0] in ("Z", "X") else int(fields[1])
if os.getppid() != node:
    sys.exit(0)
while parent_of(node) == parent:
    time.sleep(period_s)
if parent_of(node) is None:
    sys.exit(0)
time.sleep(delay_s)
if parent_of(node) is not None:
    sys.stderr.write("[WARN] parent process %d is gone and process %d did not end: killing it\n" % (parent, node))
    os.kill(node, signal.SIGKILL)
"""


def _prctl():
    """libc's prctl, or None where there is none (not Linux)."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl
    except (OSError, AttributeError):
        return None
    prctl.argtypes = [ctypes.c_int, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong]
    prctl.restype = ctypes.c_int
    return prctl


def preexec_fn():
    """A ``subprocess.Popen(preexec_fn=...)`` that makes the child get SIGTERM when this process
    dies; None where prctl is not available. The libc function is looked up here, in the parent,
    so that the forked child only makes the system call."""
    prctl = _prctl()
    if prctl is None:
        return None
    parent = os.getpid()

    def die_with_parent():
        prctl(PR_SET_PDEATHSIG, int(DEATH_SIGNAL), 0, 0, 0)
        if os.getppid() != parent:          # the parent died before the prctl took effect
            os.kill(os.getpid(), DEATH_SIGNAL)

    return die_with_parent


def start_watchdog(grace_s: float = 5.0, period_s: float = 0.5) -> threading.Thread | None:
    """Watch the parent named by ``BACKLASH_MONITOR_PARENT_PID`` (see the module doc); None when
    the variable is unset or names another process than this one's parent (then this process was
    not started by that supervisor). The variable is removed, so grandchildren do not inherit it."""
    value = os.environ.pop(PARENT_PID_ENV, "")
    try:
        parent = int(value)
    except ValueError:
        return None
    if parent <= 1 or os.getppid() != parent:
        return None

    def watch():
        while os.getppid() == parent:
            time.sleep(period_s)
        print(f"[WARN] parent process {parent} is gone: shutting down", file=sys.stderr, flush=True)
        os.kill(os.getpid(), DEATH_SIGNAL)
        time.sleep(grace_s)
        os._exit(1)

    _start_hard_stop_watcher(parent, grace_s + HARD_STOP_MARGIN_S, period_s)
    thread = threading.Thread(target=watch, name="parent-watchdog", daemon=True)
    thread.start()
    return thread


def _start_hard_stop_watcher(parent: int, delay_s: float, period_s: float) -> None:
    """The watcher process of the module doc, where there is /proc (Linux); silently none where it
    cannot start (the thread still watches)."""
    if not os.path.isdir(f"/proc/{os.getpid()}"):
        return
    argv = [sys.executable, "-I", "-S", "-c", _HARD_STOP_WATCHER,
            str(os.getpid()), str(parent), repr(delay_s), repr(period_s)]
    try:
        _WATCHERS.append(subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                          close_fds=True))
    except OSError:
        return
