"""LeanExecutor: a single-threaded executor with less Python work per wake-up than rclpy's.

rclpy's SingleThreadedExecutor rebuilds its wait set from scratch on every wake-up: it filters every
node's entity lists, enters each handle through an ExitStack, creates a new rcl wait set, checks
every QoS-event handler with a linear list search, wraps each callback in a Task, and triggers its
own guard condition twice per callback, which makes the next wait return at once without new work.
With the 50 kHz stream in 1000-sample chunks (150 messages/s per drive at real time, 1500 at 10x)
that overhead, not the signal chain, was most of the windowing node's CPU (measured: see
docs/graph.md).

This executor keeps the entity lists, their handle pointers and the wait set between wake-ups and
rebuilds them only when a node's entities change; it runs the ready callbacks directly. It serves
what the project's nodes use — subscriptions, timers, services (the parameter services),
QoS-event handlers and guard conditions — with plain (non-async) callbacks. A node with service
clients or a coroutine callback is handed to rclpy's own executor logic instead, so nothing is
silently dropped.

Batching (``batch_s`` > 0; opt-in per process: a node asks for it with an attribute
``executor_batch_s``, see runtime.run_nodes): a node that needs no low latency lets its messages
collect for up to ``batch_s`` after a wake-up that took some, then takes everything waiting, in
rounds of one message per subscription (the chunks of one range stay together). Every message
is still handed to its callback, one by one, in its subscription's order; what is saved is the
wake-ups: with four 50 Hz topics about 1/batch_s a second instead of ~75, each costing the wait
set, the rmw wait and a thread switch (measured for model_watch: docs/model_watch.md "Cost"). A
subscription's queue must not overflow meanwhile (KEEP_LAST drops the oldest): the pause adapts,
halved when a drain took more than half a queue's depth (e.g. best effort at depth 5 in a fast
replay), grown back towards ``batch_s`` while every queue stays under a quarter; a wake-up that
found no message (a timer, a service, a time-out) is followed by none.

Uses rclpy's internal handle API (the same calls rclpy's executors make, rclpy of ROS 2 Jazzy).
"""
from __future__ import annotations

import inspect
import threading
import time
import os

from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.exceptions import InvalidHandle
from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.qos import HistoryPolicy
from rclpy.subscription import Subscription
from rclpy.waitable import NumberOfEntities

from backlash_monitor.ros.parameters import ParameterValueError


MAX_WAIT_S = 0.5   # longest single wait: how late a shutdown whose wake-up was lost is noticed [s]
BATCH_START = 1.0 / 16   # batching: the first pause, as a share of batch_s (grows while queues stay short)
UNBOUNDED_DRAIN = 10000  # batching: most messages taken from a KEEP_ALL subscription per wake-up

class _Plan:
    """The entities of the executor's nodes, entered, with the rcl wait set sized for them."""

    def __init__(self, executor: "LeanExecutor", nodes):
        self.signature = LeanExecutor.signature(nodes)
        self.subscriptions = [s for n in nodes for s in n.subscriptions]
        self.timers = [t for n in nodes for t in n.timers]
        self.services = [s for n in nodes for s in n.services]
        self.waitables = [w for n in nodes for w in n.waitables]
        self.guards = [g for n in nodes for g in n.guards] + [executor._guard, executor._sigint_gc]
        self.entered = []
        try:
            for entity in self.subscriptions + self.timers + self.services:
                entity.handle.__enter__()
                self.entered.append(entity.handle)
            for guard in self.guards:
                guard.handle.__enter__()
                self.entered.append(guard.handle)
            for waitable in self.waitables:
                waitable.__enter__()
                self.entered.append(waitable)
            executor._context.handle.__enter__()
            self.entered.append(executor._context.handle)
        except BaseException:
            self.release()
            raise
        self.sub_by_pointer = {s.handle.pointer: s for s in self.subscriptions}
        self.timer_by_pointer = {t.handle.pointer: t for t in self.timers}
        self.service_by_pointer = {s.handle.pointer: s for s in self.services}
        self.guard_by_pointer = {g.handle.pointer: g for g in self.guards if g.callback is not None}
        count = NumberOfEntities(len(self.subscriptions), len(self.guards), len(self.timers), 0,
                                 len(self.services))
        for waitable in self.waitables:
            count += waitable.get_num_entities()
        self.wait_set = _rclpy.WaitSet(count.num_subscriptions, count.num_guard_conditions,
                                       count.num_timers, count.num_clients, count.num_services,
                                       count.num_events, executor._context.handle)

    def release(self) -> None:
        """Leave the handles (so that the nodes' entities can be destroyed)."""
        for handle in reversed(self.entered):
            handle.__exit__(None, None, None)
        self.entered = []


class LeanExecutor(SingleThreadedExecutor):
    """SingleThreadedExecutor with a kept wait set and direct callbacks (see the module doc)."""

    def __init__(self, *, context=None, batch_s: float = 0.0):
        super().__init__(context=context)
        if not (0.0 <= float(batch_s) <= MAX_WAIT_S):
            raise ValueError(f"batch_s = {batch_s!r}; allowed: 0 .. {MAX_WAIT_S} s")
        self.batch_s = float(batch_s)
        self._pause_s = self.batch_s * BATCH_START    # the adaptive pause (see the module doc)
        self._took_at: float | None = None           # when the last wake-up that took messages began
        self._plan: _Plan | None = None
        # Held while a spin_once uses the plan; remove_node/shutdown from another thread wake the
        # wait (rclpy triggers the executor's guard condition) and then take it to drop the plan.
        self._plan_lock = threading.RLock()

    @staticmethod
    def signature(nodes) -> tuple:
        """What the plan depends on: the nodes and how many entities of each kind they hold
        (rclpy's Node keeps them in these lists; its public properties are generators)."""
        return tuple((id(n), len(n._subscriptions), len(n._timers), len(n._services),
                      len(n._clients), sum(1 for _ in n.waitables), len(n._guards)) for n in nodes)

    def _lean_plan(self):
        """The kept plan, rebuilt when the nodes' entities changed; None when a node needs
        rclpy's general logic (service clients, pending tasks)."""
        nodes = self.get_nodes()
        if self._tasks:
            with self._tasks_lock:
                self._tasks = [t for t in self._tasks if not (t[0].done() or t[0].cancelled())]
        if self._tasks or any(n._clients for n in nodes):
            self._drop_plan()
            return None
        signature = self.signature(nodes)
        if self._plan is None or self._plan.signature != signature:
            self._drop_plan()
            self._plan = _Plan(self, nodes)
        return self._plan

    def _drop_plan(self) -> None:
        if self._plan is not None:
            self._plan.release()
            self._plan = None

    def remove_node(self, node) -> None:
        super().remove_node(node)
        with self._plan_lock:
            self._drop_plan()

    def shutdown(self, timeout_sec=None) -> bool:
        done = super().shutdown(timeout_sec)
        with self._plan_lock:
            self._drop_plan()
        return done

    def spin_once(self, timeout_sec: float | None = None) -> None:
        with self._plan_lock:
            self._spin_once_locked(timeout_sec)

    def _spin_once_locked(self, timeout_sec: float | None) -> None:
        if self._is_shutdown:
            return
        try:
            plan = self._lean_plan()
        except InvalidHandle:   # an entity was destroyed under us: start over next time
            self._drop_plan()
            plan = None
        if plan is None:
            return super().spin_once(timeout_sec)
        # "Forever" is capped: rclpy's signal handler triggers the executors' guard condition before
        # it shuts the context down, so a wait woken by SIGTERM can still find the context ok, loop,
        # and wait again with the trigger consumed: an uncapped wait then never returns (live_view
        # hung in 3 of 15 runs). spin() re-checks the context after every spin_once.
        if timeout_sec is None or timeout_sec < 0 or timeout_sec > MAX_WAIT_S:
            timeout_sec = MAX_WAIT_S
        if self._took_at is not None:      # batching, and the stream flows: let it collect
            pause = min(self._pause_s - (time.monotonic() - self._took_at), timeout_sec)
            if pause > 0:
                time.sleep(pause)
                timeout_sec -= pause
        timeout_ns = int(timeout_sec * 1e9)
        ws = plan.wait_set
        ws.clear_entities()
        for sub in plan.subscriptions:
            ws.add_subscription(sub.handle)
        for srv in plan.services:
            ws.add_service(srv.handle)
        for tmr in plan.timers:
            ws.add_timer(tmr.handle)
        for gc in plan.guards:
            ws.add_guard_condition(gc.handle)
        for waitable in plan.waitables:
            waitable.add_to_wait_set(ws)
        ws.wait(timeout_ns)
        if self._is_shutdown:
            return
        if not self._context.ok():
            raise ExternalShutdownException()
        ready_waitables = [w for w in plan.waitables if w.is_ready(ws)]
        subs_ready = ws.get_ready_entities("subscription")
        timers_ready = ws.get_ready_entities("timer")
        services_ready = ws.get_ready_entities("service")
        guards_ready = ws.get_ready_entities("guard_condition")
        woke = time.monotonic() if self.batch_s else 0.0
        took, fullest = 0, 0.0   # batching: messages taken, the fullest queue (share of its depth)
        with self._work_tracker:
            for waitable in ready_waitables:
                self._run(waitable.execute(waitable.take_data()))
            for pointer in timers_ready:
                tmr = plan.timer_by_pointer.get(pointer)
                if tmr is not None and tmr.handle.is_timer_ready():
                    tmr.handle.call_timer()
                    self._run(tmr.callback())
            if self.batch_s and subs_ready:
                took, fullest = self._drain(plan.subscriptions)
                subs_ready = ()
            for pointer in subs_ready:
                sub = plan.sub_by_pointer.get(pointer)
                if sub is None:
                    continue
                msg_info = self._take(sub)
                if msg_info is None:
                    continue
                if sub._callback_type is Subscription.CallbackType.MessageOnly:
                    self._run(sub.callback(msg_info[0]))
                else:
                    self._run(sub.callback(*msg_info))
            for pointer in services_ready:
                srv = plan.service_by_pointer.get(pointer)
                if srv is None:
                    continue
                request, header = srv.handle.service_take_request(srv.srv_type.Request)
                if header is not None:
                    srv.send_response(srv.callback(request, srv.srv_type.Response()), header)
            for pointer in guards_ready:
                gc = plan.guard_by_pointer.get(pointer)
                if gc is not None:
                    self._run(gc.callback())
        if self.batch_s:
            self._adapt(woke, took, fullest)

    def _take(self, sub):
        """``sub``'s next message (rclpy's take), or None. A take that fails while the context shuts down -- a signal
        between the wait and the take tears the entities down: measured once in ~200 process-fault runs, pybind's
        "Unable to convert call argument" from a killed chain's neighbour -- ends the spin as the external shutdown
        it is, not with a traceback."""
        try:
            return sub.handle.take_message(sub.msg_type, sub.raw)
        except (RuntimeError, InvalidHandle):
            if self._is_shutdown or not self._context.ok():
                raise ExternalShutdownException() from None
            raise

    def _drain(self, subs) -> tuple[int, float]:
        """Batching: every message waiting on ``subs`` (all of them: one that was not ready at
        the wake-up may be by now) to its callback, in rounds of at most one per subscription,
        until a round finds none: the chunks of a range arrive together as without batching (a
        joiner's pending ranges stay few, also while they keep coming during the drain). A
        subscription gives at most its depth per drain (KEEP_ALL: UNBOUNDED_DRAIN), so that a
        stream faster than its callbacks cannot keep timers and services waiting. -> (how many,
        the fullest queue: the share of its depth taken, 0 for KEEP_ALL)."""
        queues = []
        for sub in subs:
            keep_last = sub.qos_profile.history == HistoryPolicy.KEEP_LAST
            depth = sub.qos_profile.depth if keep_last else 0
            queues.append([sub, depth, depth or UNBOUNDED_DRAIN, 0,
                           sub._callback_type is Subscription.CallbackType.MessageOnly])
        took = 0
        while True:
            before = took
            for q in queues:
                sub, _depth, cap, taken, message_only = q
                if taken >= cap:
                    continue
                msg_info = self._take(sub)
                if msg_info is None:
                    continue
                q[3] = taken + 1
                took += 1
                if message_only:
                    self._run(sub.callback(msg_info[0]))
                else:
                    self._run(sub.callback(*msg_info))
            if took == before:
                break
        fullest = max((q[3] / q[1] for q in queues if q[1]), default=0.0)
        return took, fullest

    def _adapt(self, woke: float, took: int, fullest: float) -> None:
        """Batching: the next pause (module doc). A wake-up that took no message (a timer, a
        service, a time-out) found nothing waiting: no pause before the next one."""
        if not took:
            self._took_at = None
            return
        if fullest > 0.5:
            self._pause_s /= 2
        elif fullest <= 0.25:
            self._pause_s = min(self.batch_s, max(self._pause_s * 2, self.batch_s * BATCH_START))
        self._took_at = woke

    def _run(self, result) -> None:
        """A callback that returned a coroutine (rclpy's QoS-event handlers are `async`) goes to
        rclpy's task machinery, which the next spin_once runs."""
        if inspect.iscoroutine(result):
            self.create_task(result)


EXECUTOR_ENV = "BACKLASH_MONITOR_EXECUTOR"
EXECUTORS = ("lean", "rclpy")


def make_executor(context=None, batch_s: float = 0.0):
    """The executor the project's nodes spin on: LeanExecutor (``batch_s``: its batching, module
    doc), or rclpy's SingleThreadedExecutor when the environment variable
    BACKLASH_MONITOR_EXECUTOR=rclpy (a way back should an rclpy release change the internals
    LeanExecutor uses; it does not batch)."""
    choice = os.environ.get(EXECUTOR_ENV, "lean") or "lean"
    if choice not in EXECUTORS:
        raise ParameterValueError(f"{EXECUTOR_ENV}={choice!r}; allowed: " + ", ".join(EXECUTORS))
    return LeanExecutor(context=context, batch_s=batch_s) if choice == "lean" \
        else SingleThreadedExecutor(context=context)
