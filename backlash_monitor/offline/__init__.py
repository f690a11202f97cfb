"""The offline core: one recorded bag through the signal chain, without DDS (docs/architecture.md).

:mod:`.bag_analysis` holds it: :class:`~.bag_analysis.AnalyzeOptions` (the typed options of an analysis),
:func:`~.bag_analysis.load_library` and :func:`~.bag_analysis.analyze_bag` (bag, output prefix, options ->
the estimates, written to PREFIX.csv/.json/.mcap). ``python -m backlash_monitor analyze`` (commands/)
parses and prints around it; the fleet (fleet/folder_analysis.py) runs it on many bags. No rclpy.
"""
