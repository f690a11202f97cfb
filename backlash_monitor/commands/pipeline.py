"""`python -m backlash_monitor pipeline`: the main job (same as `ros2 run backlash_monitor pipeline`)."""
from backlash_monitor.nodes import pipeline as _pipeline

NAME = "pipeline"
HELP = "run the whole graph (simulator -> windowing -> denoise -> classifier) and print estimates"
DESCRIPTION = _pipeline.__doc__
add_arguments = _pipeline.add_arguments
run = _pipeline.run
