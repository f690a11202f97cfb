"""A small diagnostics helper that attaches to a host node (in the manner of diagnostic_updater).

The host calls :meth:`DriveDiagnostics.set` whenever its state changes; the helper publishes a
``diagnostic_msgs/DiagnosticArray`` on the absolute topic ``/diagnostics`` once per period, so many
drives (each in its own namespace) share one ``/diagnostics``. The status name is the node's fully
qualified name plus a task name (unique per drive); ``hardware_id`` is the drive's name.
"""
from __future__ import annotations

from diagnostic_msgs.msg import DiagnosticArray, DiagnosticStatus, KeyValue

LEVELS = {"OK": DiagnosticStatus.OK, "WARN": DiagnosticStatus.WARN,
          "ERROR": DiagnosticStatus.ERROR, "STALE": DiagnosticStatus.STALE}


class DriveDiagnostics:
    def __init__(self, node, task: str, hardware_id: str, period_s: float = 1.0, refresh=None):
        """``refresh()``, when given, is called before each periodic publication (so a level
        that depends on time, e.g. STALE when the input stopped, is current)."""
        self.node = node
        self.refresh = refresh
        self.hardware_id = hardware_id
        self.name = f"{node.get_fully_qualified_name().lstrip('/')}: {task}"
        self.publisher = node.create_publisher(DiagnosticArray, "/diagnostics", 10)
        self.level = "STALE"
        self.message = "no data yet"
        self.values: dict[str, str] = {}
        self.timer = node.create_timer(period_s, self.publish)

    def set(self, level: str, message: str, publish_now: bool = False, **values) -> None:
        """Update the status; ``publish_now`` also publishes it at once (e.g. on a fault)."""
        if level not in LEVELS:
            raise ValueError(f"diagnostic level {level!r}: allowed: {', '.join(LEVELS)}")
        self.level, self.message = level, message
        self.values.update({key: str(value) for key, value in values.items()})
        if publish_now:
            self.publish()

    def status(self) -> DiagnosticStatus:
        return DiagnosticStatus(
            level=LEVELS[self.level], name=self.name, message=self.message,
            hardware_id=self.hardware_id,
            values=[KeyValue(key=k, value=v) for k, v in sorted(self.values.items())])

    def publish(self) -> None:
        if self.refresh is not None:
            self.refresh()
        msg = DiagnosticArray()
        msg.header.stamp = self.node.get_clock().now().to_msg()
        msg.status = [self.status()]
        self.publisher.publish(msg)
