"""A fleet of drives: many drives per machine, one diagnostics view (docs/fleet.md).

Pure cores, no rclpy: :mod:`.drives` (which drives, their namespaces and node parameters),
:mod:`.aggregator` (the diagnostic_aggregator analyzer YAML and our own aggregator view of it).
"""
