"""The process shell shared by the nodes' executables: init, build, spin, clean shutdown.

Separate from :mod:`backlash_monitor.ros.parameters` (declaration and validation of parameters,
imported by every node module) so that neither that module nor the executor imports the other.
"""
from __future__ import annotations

import gc
import os
import signal
import sys
import threading
import argparse

import rclpy
import rclpy.executors
import rclpy.signals
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.utilities import remove_ros_args

from backlash_monitor.ros.fast_dds import configure_fast_dds
from backlash_monitor.ros.lean_executor import make_executor
from backlash_monitor.ros.parameters import ParameterValueError
from backlash_monitor.process.blas import limit_blas_threads
from backlash_monitor.process.parent_watch import start_watchdog
from backlash_monitor.errors import HelpFormatter, RunFailure, UsageError, one_line
from backlash_monitor.ros.params_file import check_params_files


def freeze_startup_objects() -> None:
    """Call once the nodes are built: everything built so far lives as long as they do, so keep it
    out of the garbage collector's scans and a collection inside a callback stays short. Measured
    with bench/latency.py, four runs each side by side: p99 8.4/8.9/8.7/16.8 ms frozen vs
    11.7/12.3/8.7/17.5 ms not."""
    gc.collect()
    gc.freeze()


def is_shutdown_error(error: BaseException) -> bool:
    """True for the rcl/rmw error (or invalid handle) a callback or the tidy-up gets when
    Ctrl-C/SIGTERM has already invalidated the context (the signal may arrive while it publishes:
    the plant publishes a burst of chunks per tick). That error is the shutdown, not a fault; the
    same error while the context is valid is."""
    return isinstance(error, (_rclpy.RCLError, _rclpy.RMWError, _rclpy.InvalidHandle)) \
        and not rclpy.ok()


def command_main(prog: str, description: str, add_arguments, run, argv=None) -> int:
    """``main()`` of an executable that takes options (``ros2 run backlash_monitor pipeline|fleet``):
    ROS arguments are passed through, a :class:`~backlash_monitor.errors.UsageError` is one line
    ``PROG: error: ...`` and exit code 2."""
    parser = argparse.ArgumentParser(prog=prog, description=description, formatter_class=HelpFormatter)
    add_arguments(parser)
    args = parser.parse_args(remove_ros_args(sys.argv if argv is None else argv)[1:])
    try:
        return run(args)
    except UsageError as error:
        print(f"{prog}: error: {one_line(error)}", file=sys.stderr)
        return 2
    except RunFailure as error:
        print(f"{prog}: error: {one_line(error)}", file=sys.stderr)
        return 1


SHUTDOWN_SIGNALS = (signal.SIGINT, signal.SIGTERM)


def _note_shutdown_signal(signum, frame) -> None:
    """SIGINT/SIGTERM while the process shuts down: one line on stderr, the clean shutdown goes on."""
    os.write(2, f"[WARN] {signal.Signals(signum).name} while shutting down: the clean shutdown "
                "(files closed, nodes destroyed) goes on\n".encode())


def begin_shutdown() -> None:
    """Call first when a process's ROS life ends (after Ctrl-C/SIGTERM or not; idempotent): stops
    rclpy's signal thread and keeps SIGINT/SIGTERM from interrupting the tidy-up.

    rclpy (Jazzy) handles SIGINT/SIGTERM in a thread of its own: the C signal handler wakes it, and
    it triggers the guard condition of every executor (a list it reads without a lock) and shuts
    the contexts down. ``Executor.shutdown()`` destroys that guard condition and frees the list.
    When the thread is preempted while it walks the list -- after it woke the executor, whose
    thread then closes files and destroys the executor -- it resumes on freed memory and the
    process dies with SIGSEGV after a clean close (how often: docs/graph.md "Shutdown").
    ``rclpy.signals.uninstall_signal_handlers()`` joins that thread: after it returns nothing
    but this thread touches the guard conditions. Python handlers are put in first, so that a
    second signal during the tidy-up neither kills the process (SIGTERM's default action once
    rclpy's handler is gone) nor raises KeyboardInterrupt in the middle of a file's close: it is
    noted (one line on stderr) and the shutdown goes on.
    """
    if threading.current_thread() is threading.main_thread():
        for signum in SHUTDOWN_SIGNALS:
            if signal.getsignal(signum) is not _note_shutdown_signal:
                signal.signal(signum, _note_shutdown_signal)
    rclpy.signals.uninstall_signal_handlers()


def _collect_unreachable_nodes() -> None:
    """Finalise now what no one can destroy any more: a node whose constructor raised after
    rclpy's Node.__init__ (a bad parameter, or Ctrl-C/SIGTERM while the nodes were being built)
    was never returned, so it is in no list; it holds an rcl node, and with it the process's DDS
    participant, until the garbage collector frees it (a Node is in reference cycles). Left
    to chance that could be after Python has finished, in Fast DDS's static destructors, which
    can then spin forever (release_nodes)."""
    gc.collect()


def release_nodes(executor, nodes) -> None:
    """The end of a process's ROS life: :func:`begin_shutdown`, the executor stopped, every node
    destroyed (a node's destroy_node closes its files), rclpy shut down (safe after a signal
    already did it), nodes no one holds any more collected, the default context destroyed.
    Every step runs even if one before failed; the first unexpected error is raised at the end.

    Nothing of ROS may outlive this: a DDS participant still alive when the process exits is
    deleted by Fast DDS's static destructors after Python has finished, and there (Fast DDS 2.14,
    DomainParticipantImpl::disable -> set_listener) it can busy-wait forever: a managed_chain
    ran on at 85 % of a core 23 minutes after SIGTERM (lifecycle.ManagedNodes.destroy_node).
    """
    begin_shutdown()
    # try_shutdown lets go of the default context; destroy it (rcl_context_fini) now rather than
    # whenever -- if ever: gc.freeze -- its last Python holder is collected.
    context = rclpy.get_default_context()
    steps = ([executor.shutdown] if executor is not None else []) \
        + [node.destroy_node for node in nodes] \
        + [rclpy.try_shutdown, _collect_unreachable_nodes, context.destroy]
    error_seen = None
    for step in steps:
        try:
            step()
        except KeyboardInterrupt:
            pass            # not with begin_shutdown's handler in place; should one come: go on
        except Exception as error:
            if not is_shutdown_error(error) and error_seen is None:
                error_seen = error
    if error_seen is not None:
        raise error_seen


def run_node(node_factory, args=None, spin=None) -> int:
    """``main()`` body shared by the nodes: init, build, spin until Ctrl-C/SIGTERM, clean shutdown.

    The node spins on a :func:`~backlash_monitor.ros.lean_executor.make_executor` executor
    (batching, when the node has an attribute ``executor_batch_s`` > 0: see LeanExecutor; and
    with ``blas_threads`` > 0 the process's BLAS uses that many threads: process/blas.py);
    ``spin(node, executor)`` replaces the plain ``executor.spin()``. A
    :class:`ParameterValueError` while building the node is logged as one clear line and gives
    exit code 2 (the node does not start).
    """
    return run_nodes([node_factory], args=args,
                     spin=None if spin is None else (lambda nodes, ex: spin(nodes[0], ex)))


def run_nodes(node_factories, args=None, spin=None) -> int:
    """:func:`run_node` for several nodes in one process on one executor (built in order; it
    batches only if every node asks for it: the smallest ``executor_batch_s``; likewise
    ``blas_threads``)."""
    start_watchdog()    # started by a supervisor (pipeline --processes): end with it
    configure_fast_dds()
    try:   # unknown keys and broken YAML in --params-file files: one line, not rclpy's traceback
        check_params_files(sys.argv if args is None else args)
    except ParameterValueError as error:
        print(f"[ERROR] {error}", file=sys.stderr, flush=True)
        return 2
    rclpy.init(args=args)
    nodes = []
    executor = None
    try:
        for factory in node_factories:
            nodes.append(factory())
        executor = make_executor(batch_s=min(getattr(n, "executor_batch_s", 0.0) for n in nodes))
        blas_threads = min(getattr(n, "blas_threads", 0) for n in nodes)
        if blas_threads > 0:
            limit_blas_threads(blas_threads)
        for node in nodes:
            executor.add_node(node)
        freeze_startup_objects()
        if spin is None:
            executor.spin()
        else:
            spin(nodes, executor)
        return 0
    except ParameterValueError as error:
        print(f"[ERROR] {error}", file=sys.stderr, flush=True)
        return 2
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        return 0
    except Exception as error:
        if is_shutdown_error(error):
            return 0
        raise
    finally:
        release_nodes(executor, nodes)
