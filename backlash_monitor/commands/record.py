"""`python -m backlash_monitor record`: record the graph's topics into one MCAP bag.

The `record` node (`ros2 run backlash_monitor record`) with its parameters as options; Ctrl-C or
SIGTERM closes the file properly. docs/bags.md describes the file.
"""
from pathlib import Path
import sys

from backlash_monitor.commands._node_options import add_parameter_options, ros_arguments
from backlash_monitor.errors import UsageError
from backlash_monitor.files.outputs import missing_folder_message

NAME = "record"
HELP = "record the graph's topics into one rosbag2 MCAP file (Ctrl-C to stop)"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    # deferred: backlash_monitor.nodes.record costs ~290 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.nodes.record import PARAMETERS
    add_parameter_options(parser, PARAMETERS)


def run(args) -> int:
    # deferred: backlash_monitor.nodes.record costs ~290 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.nodes.record import PARAMETERS, main
    if args.output and not Path(args.output).absolute().parent.is_dir():
        raise UsageError(missing_folder_message("--output", args.output))
    code = main(args=["record", *ros_arguments(args, PARAMETERS)], empty_exit_code=1)
    if code == 1:
        print("python -m backlash_monitor record: warning: recorded nothing (no publisher on the recorded topics); "
              "the bag holds no messages", file=sys.stderr)
    return code
