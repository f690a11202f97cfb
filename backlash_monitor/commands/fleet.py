"""`python -m backlash_monitor fleet`: many drives on one machine (same as `ros2 run backlash_monitor fleet`)."""
from backlash_monitor.nodes import fleet as _fleet

NAME = "fleet"
HELP = "run N simulated drives, each in its namespace, with one diagnostics view per drive"
DESCRIPTION = _fleet.__doc__
add_arguments = _fleet.add_arguments
run = _fleet.run
