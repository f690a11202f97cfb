"""A node process watched at the race that made the project's node processes die with SIGSEGV
after a clean close (test_node_shutdown.py; docs/graph.md "Shutdown").

    python test/shutdown_probe.py [--starve] idle|MODULE [ARGS ...]

runs the idle node below on the project's process shell (``runtime.run_node``), or the node
module MODULE (e.g. ``backlash_monitor.nodes.record``) as ``python -m MODULE ARGS`` would.

rclpy (Jazzy) handles SIGINT/SIGTERM in a thread of its own that walks the list of the executors'
signal guard conditions without a lock; ``Executor.shutdown()`` unregisters its guard condition
(which frees that list) and destroys it. This process

- finds that thread (the one thread that rclpy.init's ``install_signal_handlers`` starts) and
  prints, each time a signal guard condition is unregistered, whether the thread still runs:
  ``unregister: signal thread alive=True|False``;
- prints ``READY`` on stdout when the nodes are built and the executor about to spin
  (``runtime.freeze_startup_objects``); the test then sends SIGINT or SIGTERM;
- with ``--starve``, at READY, holds that thread off the CPU as a loaded machine can: the thread
  and the main thread on one CPU, the thread at SCHED_IDLE, so that the main thread, once the
  thread has woken it, preempts it in the middle of its walk. With root or CAP_SYS_NICE the main
  thread also runs at SCHED_FIFO and so keeps the CPU until it blocks; the probe prints
  ``starve: SCHED_IDLE thread, SCHED_FIFO|SCHED_OTHER main thread``. Before the fix, SIGINT runs
  of the idle node died with SIGSEGV in 14 to 19 of 20 runs with SCHED_FIFO and in 2 to 11 of 20
  without, depending on the machine's load (docs/graph.md "Shutdown").

At exit (atexit: Python has finished the program, C++ static destructors have not run yet) it
prints ``dds participant at exit: alive|gone|unknown``: whether Fast DDS still holds a
DomainParticipant of this process in ROS_DOMAIN_ID (asked through Fast DDS's own
DomainParticipantFactory::lookup_participant; ``unknown`` where that library or symbol is not
found). One still alive there is deleted by Fast DDS's static destructors, where (Fast DDS 2.14)
it can spin forever: a managed_chain ran on 23 minutes after SIGTERM (nodes/lifecycle.py).

Linux only (/proc, sched_setscheduler).
"""
from __future__ import annotations

import atexit
import ctypes
import os
import runpy
import sys

import rclpy
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy

from backlash_monitor.ros import runtime

signal_thread_ids: list[str] = []
starve = False


def _tasks() -> set[str]:
    return set(os.listdir("/proc/self/task"))


_install_signal_handlers = rclpy.install_signal_handlers


def install_signal_handlers(*args, **kwargs):
    before = _tasks()
    result = _install_signal_handlers(*args, **kwargs)
    signal_thread_ids.extend(sorted(_tasks() - before))
    print(f"signal threads: {len(signal_thread_ids)}", file=sys.stderr, flush=True)
    return result


_unregister = _rclpy.unregister_sigint_guard_condition


def unregister_sigint_guard_condition(guard_condition):
    alive = any(os.path.exists(f"/proc/self/task/{tid}") for tid in signal_thread_ids)
    print(f"unregister: signal thread alive={alive}", file=sys.stderr, flush=True)
    return _unregister(guard_condition)


def starve_signal_thread() -> None:
    cpu = {min(os.sched_getaffinity(0))}
    for tid in signal_thread_ids:   # allowed without privileges: lowering a thread's priority
        os.sched_setaffinity(int(tid), cpu)
        os.sched_setscheduler(int(tid), os.SCHED_IDLE, os.sched_param(0))
    os.sched_setaffinity(0, cpu)
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))
        main_policy = "SCHED_FIFO"
    except PermissionError:          # no root / CAP_SYS_NICE: SCHED_IDLE alone still starves it
        main_policy = "SCHED_OTHER"
    print(f"starve: SCHED_IDLE thread, {main_policy} main thread", file=sys.stderr, flush=True)


_freeze_startup_objects = runtime.freeze_startup_objects


def freeze_startup_objects() -> None:
    _freeze_startup_objects()
    if starve:
        starve_signal_thread()
    print("READY", flush=True)


def dds_participant_at_exit() -> str:
    """``alive``, ``gone`` or ``unknown``: a Fast DDS participant of this process in its domain."""
    try:   # the copy rmw_fastrtps_cpp loaded, not a second one
        lib = ctypes.CDLL("libfastrtps.so.2.14", mode=os.RTLD_NOLOAD)
        factory = lib._ZN8eprosima7fastdds3dds24DomainParticipantFactory12get_instanceEv
        lookup = lib._ZNK8eprosima7fastdds3dds24DomainParticipantFactory18lookup_participantEj
    except (OSError, AttributeError):
        return "unknown"
    factory.restype = ctypes.c_void_p
    lookup.restype = ctypes.c_void_p
    lookup.argtypes = [ctypes.c_void_p, ctypes.c_uint32]
    domain = int(os.environ.get("ROS_DOMAIN_ID", "0") or 0)
    return "alive" if lookup(factory(), domain) else "gone"


def report_dds_participant() -> None:
    os.write(2, f"dds participant at exit: {dds_participant_at_exit()}\n".encode())


def idle_node():
    from rclpy.node import Node
    return Node("shutdown_probe")


def main(argv: list[str]) -> int:
    global starve
    starve = "--starve" in argv
    argv = [a for a in argv if a != "--starve"]
    rclpy.install_signal_handlers = install_signal_handlers   # what rclpy.init calls
    _rclpy.unregister_sigint_guard_condition = unregister_sigint_guard_condition
    runtime.freeze_startup_objects = freeze_startup_objects
    atexit.register(report_dds_participant)
    target, args = argv[0], argv[1:]
    if target == "idle":
        return runtime.run_node(idle_node, args=[sys.argv[0], *args])
    sys.argv = [target, *args]
    runpy.run_module(target, run_name="__main__", alter_sys=True)   # exits via sys.exit(main())
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
