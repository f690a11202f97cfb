"""The offline core: one recorded bag through the signal chain, without DDS (docs/architecture.md).

:mod:`.analyze` holds it: :class:`~.analyze.AnalyzeOptions` (the typed options of an analysis),
:func:`~.analyze.load_library` and :func:`~.analyze.analyze_bag` (bag, output prefix, options ->
the estimates, written to PREFIX.csv/.json/.mcap). ``python -m backlash_monitor analyze`` (commands/)
parses and prints around it; the fleet (fleet/analyze.py) runs it on many bags. No rclpy.
"""
