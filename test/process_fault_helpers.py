"""Run `pipeline --processes`, read its live output, kill its processes (tests and the bench)."""
from __future__ import annotations

import os
import queue
import re
import signal
import subprocess
import sys
import threading
import time

ONSET = re.compile(r"^t=\s*([0-9.]+) s\s+onset")
# The plant's log line when its stream's clock starts (wall-clock stamp): its subscribers are there, or it
# stopped waiting for them. Not the "waiting for subscribers before streaming" line before it: under load
# the subscribers' discovery takes seconds, and a clock started there puts every stream time that long late.
STREAM_START = re.compile(r"^\[(?:INFO|WARN)\] \[([0-9.]+)\] \[plant_simulator\]: "
                          r"(?:subscribers there after [0-9.]+ s: streaming|streaming without them)")
PIDS = re.compile(r"^pipeline: node processes: (.*); restart policy")


def gone(pid: int) -> bool:
    """The process has ended (absent, or a zombie nobody reaped yet)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] in ("Z", "X")
    except FileNotFoundError:
        return True


def wait_until(predicate, timeout_s: float = 15.0) -> bool:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(0.1)
    return predicate()


class PipelineRun:
    """`python -m backlash_monitor pipeline --processes ...` in its own process group."""

    def __init__(self, args, env):
        self.process = subprocess.Popen(
            [sys.executable, "-m", "backlash_monitor", "pipeline", "--processes", *args],
            env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
            start_new_session=True)
        self.lines: list[str] = []
        self.stderr = ""
        self._queue: queue.Queue = queue.Queue()
        threading.Thread(target=self._read, daemon=True).start()
        self._err_thread = threading.Thread(target=self._read_err, daemon=True)
        self._err_thread.start()
        self.pids: dict[str, int] = {}

    def _read(self):
        for line in self.process.stdout:
            self._queue.put(line.rstrip("\n"))
        self._queue.put(None)

    def _read_err(self):
        self.stderr = self.process.stderr.read()

    def next_line(self, timeout_s: float) -> str | None:
        """The next stdout line (None at the end of the output or after timeout_s)."""
        try:
            line = self._queue.get(timeout=timeout_s)
        except queue.Empty:
            return None
        if line is not None:
            self.lines.append(line)
            match = PIDS.match(line)
            if match:
                self.pids = {name: int(pid) for name, pid in
                             (item.split(" pid ") for item in match.group(1).split(", "))}
        return line

    def wait_for(self, predicate, timeout_s: float) -> str | None:
        """Read until a line satisfies predicate; that line, or None."""
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline:
            line = self.next_line(max(0.01, deadline - time.monotonic()))
            if line is None:
                return None
            if predicate(line):
                return line
        return None

    def finish(self, timeout_s: float) -> int:
        """Read the rest of the output; the exit code."""
        while self.next_line(timeout_s) is not None:
            pass
        code = self.process.wait(timeout=timeout_s)
        self._err_thread.join(timeout=15)     # the node processes hold stderr until they end
        return code

    @property
    def output(self) -> str:
        return "\n".join(self.lines) + "\n--- stderr:\n" + self.stderr[-3000:]

    def stream_start_wall_s(self) -> float | None:
        """Wall-clock time [s] at which the plant started its first stream (its log line, stamped with the wall
        clock: STREAM_START); None before it said so."""
        starts = [float(m.group(1)) for line in self.stderr.splitlines() if (m := STREAM_START.match(line))]
        return starts[0] if starts else None

    def onsets(self) -> list[tuple[int, float]]:
        """(line number, event time [s]) of every onset line."""
        return [(i, float(m.group(1))) for i, line in enumerate(self.lines)
                if (m := ONSET.match(line))]

    def kill_group(self) -> None:
        """Teardown: end the pipeline's process group (its node processes with it)."""
        try:
            os.killpg(self.process.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            pass


HOG_CODE = "import time\nend = time.monotonic() + {s}\nwhile time.monotonic() < end: pass\n"


class CpuHog:
    """Keeps every core busy (one busy loop per core, normal priority): the machine under load
    that the process-fault tests and benches also run on (issue 34). Each loop ends by itself
    after ``max_s`` (bounded even if nobody stops it); ``stop()`` (or leaving the ``with``) kills
    them at once."""

    def __init__(self, max_s: float = 900.0, loops: int | None = None):
        self.max_s = max_s
        self.loops = loops or os.cpu_count() or 2
        self.processes: list[subprocess.Popen] = []

    def start(self) -> "CpuHog":
        for _ in range(self.loops):
            self.processes.append(subprocess.Popen(
                [sys.executable, "-c", HOG_CODE.format(s=float(self.max_s))],
                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        return self

    def stop(self) -> None:
        for process in self.processes:
            if process.poll() is None:
                process.kill()
            process.wait(timeout=10)
        self.processes.clear()

    def __enter__(self) -> "CpuHog":
        return self.start()

    def __exit__(self, *exc) -> None:
        self.stop()
