"""`python -m backlash_monitor replay BAG`: publish a recorded bag into the graph.

The `replay` node (`ros2 run backlash_monitor replay`) with its parameters as options: at the
recorded rate, at a factor (--rate-factor 2), or as fast as the subscribers take it without drops
(--rate-factor 0); original or fresh header stamps.
"""
from backlash_monitor.commands._node_options import add_parameter_options, ros_arguments
from backlash_monitor.commands import UsageError
from backlash_monitor.errors import RunFailure

NAME = "replay"
HELP = "publish an MCAP bag into the graph (recorded rate, a factor, or as fast as possible)"
DESCRIPTION = __doc__


def add_arguments(parser) -> None:
    # deferred: backlash_monitor.nodes.replay costs ~330 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.nodes.replay import PARAMETERS
    add_parameter_options(parser, PARAMETERS, positional="bag")


def run(args) -> int:
    # deferred: backlash_monitor.nodes.replay costs ~330 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.nodes.replay import PARAMETERS, main
    if not args.bag:
        raise UsageError("give the bag to play: python -m backlash_monitor replay FILE.mcap")
    _check_bag(args.bag, args.recover)
    return main(args=["replay", *ros_arguments(args, PARAMETERS)])


def _check_bag(path, recover: bool) -> None:
    """The bag opened as the node will open it, before the node starts: a bad path is bad input (exit 2), a
    damaged or truncated bag a failure (exit 1, as bag-info and analyze), each one line (docs/cli.md)."""
    # deferred: backlash_monitor.bag costs ~250 ms at start-up (python -X importtime, 29 Nov); --help imports every command
    from backlash_monitor.bag import BagError, BagReader, DamagedBagError, TruncatedBagError
    try:
        with BagReader(path, recover=recover):
            pass
    except FileNotFoundError as error:
        raise UsageError(f"{error}; allowed: the path of an existing .mcap file") from None
    except (TruncatedBagError, DamagedBagError) as error:
        raise RunFailure(str(error)) from None
    except (BagError, OSError) as error:
        raise UsageError(f"{path}: {error}") from None
