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
"""
from __future__ import annotations

import ctypes
import os
import signal
import sys
import threading
import time

PARENT_PID_ENV = "BACKLASH_MONITOR_PARENT_PID"
PR_SET_PDEATHSIG = 1            # <linux/prctl.h>
DEATH_SIGNAL = signal.SIGTERM   # a clean ROS shutdown; the watchdog escalates


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

    thread = threading.Thread(target=watch, name="parent-watchdog", daemon=True)
    thread.start()
    return thread
