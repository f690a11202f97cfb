"""Managed (lifecycle) versions of a drive's chain and plant, for a fleet supervisor.

    ros2 run backlash_monitor managed_chain --ros-args -r __ns:=/line1/drive07 -p drive_name:=line1/drive07
    ros2 lifecycle set /line1/drive07/chain configure     # checks the parameters, loads nothing yet
    ros2 lifecycle set /line1/drive07/chain activate      # the windowing, denoise, classifier nodes run
    ros2 lifecycle set /line1/drive07/chain deactivate    # they are gone: no subscription, no work
    ros2 lifecycle set /line1/drive07/chain cleanup

A new model version (docs/registry.md, live pickup; what ``fleet`` does when the registry changes):

    ros2 param set /line1/drive07/chain library /data/line1_drive07_v3.npz    # taken at the next configure
    ros2 param set /line1/drive07/chain model_version 3                       # the classifier reports it
    ros2 lifecycle set /line1/drive07/chain deactivate && ros2 lifecycle set /line1/drive07/chain cleanup
    ros2 lifecycle set /line1/drive07/chain configure && ros2 lifecycle set /line1/drive07/chain activate

A lifecycle node (rclpy.lifecycle, the standard ``<node>/change_state`` and ``get_state``
services) owns the drive's ordinary nodes: ``configure`` builds them once to check their
parameters (the same checks and one-line errors as the plain executables; a bad value makes the
transition fail and the node stays unconfigured) and releases them; ``activate`` builds them and
adds them to the process's executor; ``deactivate`` removes and destroys them, so an inactive
drive holds no subscription that would queue stale chunks; ``cleanup`` returns to unconfigured.
Other drives, in their own processes or namespaces, are not touched. ``-p`` and ``-r`` arguments
reach the owned nodes as they reach the nodes of ``chain``. ``--activate`` configures and
activates at start (what the fleet's drives do).

The plain executables (``chain``, ``plant_simulator``, ...) are unchanged.
"""
from __future__ import annotations

import sys

from rclpy.lifecycle import LifecycleNode, TransitionCallbackReturn
from rclpy.parameter import Parameter
import rclpy
from rclpy.utilities import remove_ros_args

from backlash_monitor.ros.parameters import ParameterValueError
from backlash_monitor.ros.runtime import is_shutdown_error, run_nodes


class ManagedNodes(LifecycleNode):
    """A lifecycle node whose active state is a set of ordinary nodes on the same executor."""

    def __init__(self, name: str, factories, executor=None, routes=None, **kwargs):
        """``factories``: builders of the owned nodes, each a callable or ``(node name, callable)``.
        ``routes``: {own parameter: (owned node name, its parameter, initial value)}: this node declares the
        parameter, and each build of the named node gets its current value (``parameter_overrides``), so a new
        value set while active takes effect at the next configure (deactivate, cleanup, configure, activate)."""
        super().__init__(name, **kwargs)
        self.factories = [f if isinstance(f, tuple) else ("", f) for f in factories]
        self.routes = dict(routes or {})
        for parameter, (_, _, initial) in self.routes.items():
            self.declare_parameter(parameter, initial)
        self.executor_ref = executor
        self.owned = []

    def routed_parameters(self, node_name: str) -> list:
        """The owned node ``node_name``'s parameters from this node's (its routes)."""
        return [Parameter(target, value=self.get_parameter(own).value)
                for own, (node, target, _) in self.routes.items() if node_name and node == node_name]

    def _build(self) -> list:
        nodes = []
        try:
            for node_name, factory in self.factories:
                routed = self.routed_parameters(node_name)
                nodes.append(factory(parameter_overrides=routed) if routed else factory())
        except BaseException:
            for node in nodes:
                node.destroy_node()
            raise
        return nodes

    def _release(self) -> None:
        """Remove the owned nodes from the executor and destroy them: every one, even if the
        executor or one node fails (the first error is raised at the end), since a node left
        undestroyed keeps the process's DDS participant alive until exit."""
        owned, self.owned = self.owned, []
        error_seen = None
        for node in owned:
            for step in ([lambda: self.executor_ref.remove_node(node)]
                         if self.executor_ref is not None else []) + [node.destroy_node]:
                try:
                    step()
                except Exception as error:
                    error_seen = error_seen or error
        if error_seen is not None:
            raise error_seen

    def on_configure(self, state) -> TransitionCallbackReturn:
        try:
            for node in self._build():     # the parameter checks, then nothing kept
                node.destroy_node()
        except ParameterValueError as error:
            self.get_logger().error(f"configure failed: {error}")
            return TransitionCallbackReturn.FAILURE
        return TransitionCallbackReturn.SUCCESS

    def on_activate(self, state) -> TransitionCallbackReturn:
        try:
            self.owned = self._build()
        except ParameterValueError as error:
            self.get_logger().error(f"activate failed: {error}")
            return TransitionCallbackReturn.FAILURE
        if self.executor_ref is not None:
            for node in self.owned:
                self.executor_ref.add_node(node)
        return super().on_activate(state)

    def on_deactivate(self, state) -> TransitionCallbackReturn:
        self._release()
        return super().on_deactivate(state)

    def on_cleanup(self, state) -> TransitionCallbackReturn:
        self._release()
        return TransitionCallbackReturn.SUCCESS

    def on_shutdown(self, state) -> TransitionCallbackReturn:
        self._release()
        return TransitionCallbackReturn.SUCCESS

    def destroy_node(self):
        """The owned nodes, this node, and its lifecycle state machine, in that order; each step
        runs even if one before failed.

        rclpy's (Jazzy) ``LifecycleNode.destroy_node`` is Node's: it leaves the node's
        ``LifecycleStateMachine`` alive, and that keeps a reference to the rcl node, so the rcl
        node -- and with it the process's DDS participant -- is finalised only when the Python
        object is collected. It sits in reference cycles (and in gc.freeze's permanent
        generation: runtime.freeze_startup_objects), so that happened never before exit: Fast DDS
        then deleted the participant in its static destructors, after Python had finished, where
        it can spin forever (a managed_chain that never exited after SIGTERM, 85 % of a core).
        Destroying the state machine here finalises the rcl node now."""
        try:
            self._release()
        finally:
            try:
                super().destroy_node()
            finally:
                state_machine = getattr(self, "_state_machine", None)
                if state_machine is not None:
                    state_machine.destroy_when_not_in_use()


def spin_until_shutdown(executor) -> None:
    """Spin until Ctrl-C/SIGTERM. The signal invalidates the context at once, possibly while a
    callback is publishing (the plant publishes a burst of chunks per tick): that publish then
    fails with RCLError, which here is the shutdown, not a fault."""
    while rclpy.ok():
        try:
            executor.spin_once(timeout_sec=0.1)
        except Exception as error:
            if not is_shutdown_error(error):
                raise
            return


def chain_factories():
    # deferred: the chain's node modules cost ~250 ms each at start-up (python -X importtime, 29 Nov); managed_plant does not run them
    from backlash_monitor.nodes.classifier import ClassifierNode
    # deferred: the chain's node modules cost ~250 ms each at start-up (python -X importtime, 29 Nov); managed_plant does not run them
    from backlash_monitor.nodes.denoise import DenoiseNode
    # deferred: the chain's node modules cost ~250 ms each at start-up (python -X importtime, 29 Nov); managed_plant does not run them
    from backlash_monitor.nodes.width_trend import WidthTrendNode
    # deferred: the chain's node modules cost ~250 ms each at start-up (python -X importtime, 29 Nov); managed_plant does not run them
    from backlash_monitor.nodes.windowing import WindowingNode
    return [("width_trend", WidthTrendNode), ("classifier", ClassifierNode), ("denoise", DenoiseNode),
            ("windowing", WindowingNode)]   # downstream first


# the chain's parameters that hold the drive's model version (docs/registry.md, live pickup):
# {chain parameter: (owned node, its parameter, initial value)}
CHAIN_ROUTES = {"library": ("classifier", "library", ""), "model_version": ("classifier", "model_version", 0),
                "watch_reference": ("model_watch", "reference", "")}


def plant_factories():
    # deferred: the plant node (numba) costs ~1300 ms at start-up (python -X importtime, 29 Nov); managed_chain does not run it
    from backlash_monitor.nodes.plant_simulator import PlantSimulatorNode
    return [PlantSimulatorNode]


def run_managed(name: str, factories, args=None, routes=None) -> int:
    """Spin one ManagedNodes until shut down; ``--activate`` (before --ros-args) configures and
    activates it at start."""
    argv = sys.argv if args is None else args
    activate = "--activate" in remove_ros_args(argv)[1:]
    holder = {}

    def build():
        holder["node"] = ManagedNodes(name, factories, routes=routes)
        return holder["node"]

    def spin(nodes, executor):
        node = nodes[0]
        node.executor_ref = executor
        if activate:
            node.trigger_configure()
            node.trigger_activate()
        spin_until_shutdown(executor)
    return run_nodes([build], args=[a for a in argv if a != "--activate"], spin=spin)


def main_chain(args=None) -> int:
    return run_managed("chain", chain_factories(), args, routes=CHAIN_ROUTES)


def main_plant(args=None) -> int:
    return run_managed("plant", plant_factories(), args)


if __name__ == "__main__":
    sys.exit(main_chain())
