"""chain: the windowing, denoise, classifier and width_trend nodes in one process, on one executor.

    ros2 run backlash_monitor chain --ros-args -p drive_name:=drive7 -r __ns:=/line1/drive7

What a component container does for C++ nodes: the three nodes of a drive's signal chain share one
process, so the windows pass between them inside it instead of through two more processes, and a
drive costs one Python process instead of three. Measured with bench/latency.py (its
`chain_in_one_process` figures against the three-process graph, same run): see docs/graph.md.

The nodes keep their names, topics and parameters; a ``-p name:=value`` reaches every node that
declares ``name`` (drive_name and trigger are the windowing's and the classifier's both, as they
must agree), a parameters file can address each node by name.
"""
from __future__ import annotations

import sys

from backlash_monitor.ros.runtime import run_nodes
from backlash_monitor.nodes.classifier import ClassifierNode
from backlash_monitor.nodes.denoise import DenoiseNode
from backlash_monitor.nodes.width_trend import WidthTrendNode
from backlash_monitor.nodes.windowing import WindowingNode


def main(args=None) -> int:
    # Downstream first: each reader exists before its writer starts publishing.
    return run_nodes([WidthTrendNode, ClassifierNode, DenoiseNode, WindowingNode], args=args)


if __name__ == "__main__":
    sys.exit(main())
