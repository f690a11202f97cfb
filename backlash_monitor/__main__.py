"""``python -m backlash_monitor <command>``: the project's command line.

Every command calls the same numpy cores as the ROS 2 nodes. ``--help`` after any command explains
its options.
"""
import argparse
import os
import sys

from backlash_monitor.commands import UsageError, command_module_names, discover_commands
from backlash_monitor.errors import HelpFormatter, RunFailure, one_line


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="python -m backlash_monitor",
        description="Backlash-width monitor of an electric drive: simulate, record, analyse, "
                    "train, evaluate and run the ROS 2 pipeline.",
    )
    sub = parser.add_subparsers(dest="command", metavar="<command>")
    for module in discover_commands(only):
        command_parser = sub.add_parser(
            module.NAME, help=module.HELP, description=getattr(module, "DESCRIPTION", module.HELP),
            formatter_class=HelpFormatter)
        module.add_arguments(command_parser)
        command_parser.set_defaults(_run=module.run)
    return parser


# built by colcon into install/ (make setup) and put on the path by env.sh: a shell without them gets this line
BUILT_PACKAGES = ("backlash_monitor_msgs",)
NOT_SET_UP = ("the ROS 2 messages of this package ({name}) are not on the Python path: run `make setup`, then "
              "`source env.sh` in this shell (README, quick start)")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        return _main(argv)
    except ModuleNotFoundError as error:
        if error.name not in BUILT_PACKAGES:
            raise
        command = argv[0] if argv and not argv[0].startswith("-") else ""
        print(f"python -m backlash_monitor{' ' + command if command else ''}: error: "
              + NOT_SET_UP.format(name=error.name), file=sys.stderr)
        return 1


def _main(argv: list) -> int:
    # Import only the command asked for (each command's imports cost start-up time).
    parser = build_parser(argv[0] if argv else None)
    args = parser.parse_args(argv)
    if not getattr(args, "_run", None):
        parser.print_help()
        print(f"{parser.prog}: error: give a command; allowed: {', '.join(sorted(command_module_names()))}",
              file=sys.stderr)
        return 2
    try:
        return int(args._run(args) or 0)
    except UsageError as error:
        print(f"{parser.prog} {args.command}: error: {one_line(error)}", file=sys.stderr)
        return 2
    except RunFailure as error:
        print(f"{parser.prog} {args.command}: error: {one_line(error)}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print(f"{parser.prog} {args.command}: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # output piped into e.g. `head`, which stopped reading
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(main())
