"""The fleet follows its registry: a drive's new model version is picked up live, by lifecycle transitions of that
drive's chain only (docs/registry.md, "Live pickup"; the decisions are fleet/registry_pickup.py's).

Once a second the supervisor (``fleet --config drives.yaml``) looks whether the file changed; when it did, it reads it
again and, for each drive whose current version changed, sends the drive's chain ``<ns>/chain`` over the standard
services what ``ros2 param set`` and ``ros2 lifecycle set`` would: the new ``library``, ``watch_reference`` and
``model_version`` parameters, then deactivate, cleanup, configure, activate. The plant and every other drive run on.
A version whose files are missing or whose library is unreadable is refused before the drive is touched; one whose
configure fails anyway (the chain's nodes check their parameters) takes the drive back to its old version. Either way
the drive's status ``LINE/DRIVE/registry: model version`` on /diagnostics says WARN with the reason, and the drive
keeps running on its version.
"""
from __future__ import annotations

import os
import time

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue
from lifecycle_msgs.msg import Transition
from lifecycle_msgs.srv import ChangeState
from rcl_interfaces.srv import SetParameters
from rclpy.parameter import Parameter

from backlash_monitor.errors import UsageError
from backlash_monitor.fleet.drives import load_drives
from backlash_monitor.fleet.registry_pickup import FileChange, Step, back_steps, plan, swap_steps, versions

TRANSITIONS = {"configure": Transition.TRANSITION_CONFIGURE, "cleanup": Transition.TRANSITION_CLEANUP,
               "activate": Transition.TRANSITION_ACTIVATE, "deactivate": Transition.TRANSITION_DEACTIVATE}
POLL_PERIOD_S = 1.0          # how often the registry file's stat is looked at
ANSWER_TIMEOUT_S = 30.0      # a chain that has not answered a request by then (a loaded machine: seconds) has failed
LEVELS = {"OK": DiagnosticStatus.OK, "WARN": DiagnosticStatus.WARN, "ERROR": DiagnosticStatus.ERROR}


def library_problem(path: str) -> str:
    """'' when the library file loads, else the loader's one-line reason (checked before the drive is touched)."""
    if not path:
        return ""
    # deferred: the library loader (numpy) only when a drive's library changes
    from backlash_monitor.classifier.patterns import PatternLibraryError, load_library
    try:
        load_library(path)
    except (PatternLibraryError, ValueError) as error:
        return str(error).splitlines()[0]
    return ""


class Swap:
    """One drive's chain taken from its old version to a new one, a request at a time."""

    def __init__(self, hardware_id: str, old, new, steps):
        self.hardware_id, self.old, self.new = hardware_id, old, new
        self.steps = list(steps)
        self.going_back = False
        self.future = None
        self.sent_at = 0.0
        self.step: Step | None = None
        self.refusal = ""          # why the chain refused the new version (it went back to the old one)
        self.problem = ""          # a request that failed or was not answered: the drive may be down


class RegistryFollower:
    def __init__(self, node, path: str, drives, log=print):
        self.node, self.path, self.log = node, path, log
        self.file = FileChange(path)
        self.seen = versions(drives)          # the registry's versions at its last reading
        self.running = dict(self.seen)        # the versions the drives' chains run
        self.watched = {d.hardware_id: d.watched for d in drives}
        self.namespaces = {d.hardware_id: d.namespace for d in drives}
        self.swaps: dict[str, Swap] = {}
        self.queued: dict = {}                # hardware id -> (new version): a change while its swap runs
        self.status: dict[str, tuple] = {}    # hardware id -> (level, message, {key: value})
        self.events: list[dict] = []          # what happened, for the summary (bench, tests)
        self.clients: dict = {}
        self.next_poll = 0.0
        self.next_status = 0.0
        self.publisher = node.create_publisher(DiagnosticArray, "/diagnostics", 10)

    # -- the registry -------------------------------------------------------------------------------------------

    def event(self, hardware_id: str, what: str, version, detail: str = "") -> None:
        self.events.append({"drive": hardware_id, "event": what, "version": version, "wall_s": time.time(),
                            "detail": detail})
        self.log(f"fleet: {hardware_id}: {what} version {version}" + (f": {detail}" if detail else ""))

    def read(self) -> None:
        try:
            after = versions(load_drives(self.path))
        except UsageError as error:
            self.log(f"fleet: registry {self.path} changed but cannot be read ({str(error).splitlines()[0]}); "
                     "every drive keeps its version")
            return
        pickup = plan(self.seen, after, self.watched, self.running)
        for note in pickup.notes:
            self.log(f"fleet: {note}")
        self.seen.update({h: v for h, v in after.items() if h in self.seen})
        for h, (new, reason) in pickup.refused.items():
            self.refuse(h, new, reason)
        for h, (old, new, steps) in pickup.swaps.items():
            problem = library_problem(new.library)
            if problem:
                self.refuse(h, new, problem)
            elif h in self.swaps:
                self.queued[h] = new
            else:
                self.start(h, old, new, steps)

    def refuse(self, hardware_id: str, new, reason: str) -> None:
        old = self.running[hardware_id]
        self.event(hardware_id, "refused", new.version, reason)
        self.status[hardware_id] = ("WARN", f"version {new.version} of the registry refused: {reason}; the drive "
                                            f"runs {old.describe()}", {"model_version": old.version,
                                                                       "refused_version": new.version})

    def start(self, hardware_id: str, old, new, steps) -> None:
        self.event(hardware_id, "swap started", new.version, f"from version {old.version}")
        self.swaps[hardware_id] = Swap(hardware_id, old, new, steps)

    # -- the requests -------------------------------------------------------------------------------------------

    def client(self, hardware_id: str, kind):
        key = (hardware_id, kind)
        if key not in self.clients:
            service = "change_state" if kind is ChangeState else "set_parameters"
            self.clients[key] = self.node.create_client(kind, f"{self.namespaces[hardware_id]}/chain/{service}")
        return self.clients[key]

    def send(self, swap: Swap, now: float) -> bool:
        step = swap.steps[0]
        kind = ChangeState if step.transition else SetParameters
        client = self.client(swap.hardware_id, kind)
        if not client.service_is_ready():
            return False
        if step.transition:
            request = ChangeState.Request(transition=Transition(id=TRANSITIONS[step.transition],
                                                                label=step.transition))
        else:
            request = SetParameters.Request(parameters=[Parameter(k, value=v).to_parameter_msg()
                                                        for k, v in step.parameters])
        swap.step, swap.future, swap.sent_at = swap.steps.pop(0), client.call_async(request), now
        return True

    @staticmethod
    def succeeded(step: Step, response) -> tuple[bool, str]:
        if step.transition:
            return bool(response.success), "" if response.success else f"{step.transition} failed"
        bad = [r.reason for r in response.results if not r.successful]
        return not bad, "; ".join(bad)

    def advance(self, swap: Swap, now: float) -> bool:
        """One step of the swap; True when it is over (done, or back on the old version, or failed)."""
        if swap.future is None:
            if not swap.steps:
                return True
            if not self.send(swap, now) and swap.sent_at and now - swap.sent_at > ANSWER_TIMEOUT_S:
                swap.problem = f"{swap.hardware_id}/chain's services not available"
                return True
            swap.sent_at = swap.sent_at or now
            return False
        if not swap.future.done():
            if now - swap.sent_at > ANSWER_TIMEOUT_S:
                swap.problem = f"no answer to {swap.step} within {ANSWER_TIMEOUT_S:g} s"
                return True
            return False
        ok, why = self.succeeded(swap.step, swap.future.result())
        step, swap.future, swap.sent_at = swap.step, None, 0.0
        if ok:
            return not swap.steps
        if not swap.going_back and step.transition in ("configure", "activate"):
            # the chain refused the new version's parameters: it is unconfigured (configure) or inactive
            # (activate); back to the old version
            swap.going_back, swap.refusal = True, (
                f"the drive's chain refused it at {step.transition} (its log names the parameter)")
            swap.steps = ([Step(transition="cleanup")] if step.transition == "activate" else []) \
                + back_steps(swap.old)
            return False
        swap.problem = why or f"{step} failed"
        return True

    def finish(self, swap: Swap) -> None:
        h = swap.hardware_id
        if not swap.problem and not swap.refusal:
            self.running[h] = swap.new
            self.event(h, "swapped", swap.new.version, swap.new.describe())
            self.status[h] = ("OK", f"runs {swap.new.describe()}, picked up live from the registry",
                              {"model_version": swap.new.version})
        elif not swap.problem:
            self.refuse(h, swap.new, swap.refusal)
        else:
            untouched = swap.step is None or (not swap.going_back and swap.step.transition == "deactivate")
            where = "on its old version" if untouched else "down"
            self.event(h, "swap failed", swap.new.version, f"{swap.problem}; the drive is {where}")
            self.status[h] = ("ERROR", f"taking version {swap.new.version} failed ({swap.problem}); the drive is "
                                       f"{where}: restart it", {"model_version": self.running[h].version})
        queued = self.queued.pop(h, None)
        if queued is not None and queued != self.running[h]:
            self.start(h, self.running[h], queued, swap_steps(queued))

    # -- the loop ----------------------------------------------------------------------------------------------

    def tick(self, now: float | None = None) -> None:
        """Called from the fleet's loop (between spins): requests, the file's check once a second, the statuses."""
        now = time.monotonic() if now is None else now
        for h in list(self.swaps):
            if self.advance(self.swaps[h], now):
                self.finish(self.swaps.pop(h))
        if now >= self.next_poll:
            self.next_poll = now + POLL_PERIOD_S
            if self.file.changed():
                self.read()
        if self.status and now >= self.next_status:
            self.next_status = now + 1.0
            self.publish()

    def publish(self) -> None:
        msg = DiagnosticArray()
        msg.header.stamp = self.node.get_clock().now().to_msg()
        msg.status = [DiagnosticStatus(level=LEVELS[level], name=f"{h}/registry: model version", message=message,
                                       hardware_id=h,
                                       values=[KeyValue(key=k, value=str(v)) for k, v in sorted(values.items())]
                                       + [KeyValue(key="registry", value=os.path.abspath(self.path))])
                      for h, (level, message, values) in sorted(self.status.items())]
        self.publisher.publish(msg)
