"""backlash_monitor: online identification of a drive clutch's backlash width (ROS 2 Jazzy).

The physics, windowing, wavelet denoising, classifier, bag I/O and workbench are plain numpy modules
(no rclpy); the ROS 2 nodes in ``backlash_monitor.nodes`` are thin shells over them, and the CLI
(``python -m backlash_monitor <command>``) calls the same cores.
"""

__version__ = "0.1.0"
