"""Supervisor: the child processes of `pipeline --processes`, watched, named, restarted by policy.

No rclpy here: the supervisor starts commands, notices the ones that end, says which one ended and
how (exit code or signal), and restarts it when the policy says so. The pipeline calls
:meth:`Supervisor.poll` from its spin loop.

Children die with their parent, also when the parent is killed with SIGKILL (which no handler of
the parent can see): each child is started with ``prctl(PR_SET_PDEATHSIG, SIGTERM)`` (Linux; see
:mod:`backlash_monitor.process.parent_watch`) and with the parent's pid in its environment, from which a
watchdog thread in a node process notices the parent's death on systems without the prctl.

Policies (``--restart`` of the pipeline):

- ``no``: a child that ends before the run is over ends the run (the pipeline prints its
  summary and exits 1).
- ``on-failure``: a child that ends before the run is over is started again, at most
  ``max_restarts`` times per child; one more failure ends the run as with ``no``. A child that
  exits with code 2 (a node that refused its parameters) is not restarted: the same parameters
  would be refused again.

A child listed in ``finishing`` (the plant simulator, which stops after its duration) may end with
exit code 0: that is the end of its stream, not a fault.
"""
from __future__ import annotations

import os
import signal
import subprocess
import time
from dataclasses import dataclass, field

from backlash_monitor.process import parent_watch

RESTART_POLICIES = ("no", "on-failure")
NOT_RESTARTED = (2,)    # the nodes' exit code for a refused parameter (ros/parameters.py)


def describe_exit(returncode: int) -> str:
    """'exited with code 3' / 'was killed by signal SIGKILL (9)' from a Popen returncode."""
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = "an unknown signal"
        return f"was killed by signal {name} ({-returncode})"
    return f"exited with code {returncode}"


@dataclass
class Fault:
    """One child that ended before the run was over."""
    node: str
    pid: int
    returncode: int
    at_s: float                 # time.monotonic() when it was noticed
    restarted_pid: int | None = None

    def describe(self) -> str:
        text = f"node {self.node} (pid {self.pid}) {describe_exit(self.returncode)}"
        if self.restarted_pid is not None:
            text += f"; restarted as pid {self.restarted_pid}"
        return text


@dataclass
class _Child:
    name: str
    argv: list
    process: subprocess.Popen
    restarts: int = 0
    finished: bool = False      # ended normally (a finishing child with exit code 0)
    history: list = field(default_factory=list)


class Supervisor:
    """Starts ``commands`` ({name: argv}, in order), watches and restarts them (see module doc)."""

    def __init__(self, commands: dict, restart: str = "no", max_restarts: int = 3,
                 finishing=(), env=None, out=None):
        if restart not in RESTART_POLICIES:
            raise ValueError(f"restart policy {restart!r}; allowed: {', '.join(RESTART_POLICIES)}")
        if max_restarts < 0:
            raise ValueError(f"max_restarts = {max_restarts}; allowed: 0 or more")
        self.commands = dict(commands)
        self.restart = restart
        self.max_restarts = max_restarts
        self.finishing = set(finishing)
        self.env = dict(os.environ if env is None else env)
        self.env[parent_watch.PARENT_PID_ENV] = str(os.getpid())
        self.children: dict[str, _Child] = {}
        self.faults: list[Fault] = []
        self.failed: Fault | None = None     # the fault that ended the run (not restarted)

    def _spawn(self, argv) -> subprocess.Popen:
        return subprocess.Popen(argv, env=self.env, preexec_fn=parent_watch.preexec_fn())

    def start(self) -> None:
        for name, argv in self.commands.items():
            self.children[name] = _Child(name, list(argv), self._spawn(argv))

    def pids(self) -> dict[str, int]:
        return {name: child.process.pid for name, child in self.children.items()}

    def finished(self, name: str) -> bool:
        """The child ``name`` ended normally (a finishing child's exit code 0)."""
        child = self.children.get(name)
        return child is not None and child.finished

    def poll(self, restart: bool = True) -> list[Fault]:
        """Check every child; return the faults noticed now (restarted or not). After a fault
        that was not restarted, :attr:`failed` is set and the run should end. ``restart=False``:
        restart nothing (the run is ending)."""
        new = []
        for child in self.children.values():
            if child.finished:
                continue
            code = child.process.poll()
            if code is None:
                continue
            if code == 0 and child.name in self.finishing:
                child.finished = True
                continue
            fault = Fault(child.name, child.process.pid, code, time.monotonic())
            if restart and self.restart == "on-failure" and child.restarts < self.max_restarts \
                    and code not in NOT_RESTARTED:
                child.history.append(child.process)
                child.process = self._spawn(child.argv)
                child.restarts += 1
                fault.restarted_pid = child.process.pid
            elif self.failed is None:
                self.failed = fault
            self.faults.append(fault)
            new.append(fault)
        return new

    def stop(self, grace_s: float = 10.0) -> None:
        """SIGINT to every running child (a clean ROS shutdown), SIGKILL after ``grace_s``."""
        running = [c.process for c in self.children.values() if c.process.poll() is None]
        for process in running:
            try:
                process.send_signal(signal.SIGINT)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + grace_s
        for process in running:
            try:
                process.wait(timeout=max(0.0, deadline - time.monotonic()))
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
