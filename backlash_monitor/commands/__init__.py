"""The commands of ``python -m backlash_monitor``: one module per command.

Each module defines ``NAME`` (the command word), ``HELP`` (one line), ``add_arguments(parser)`` and
``run(args) -> int`` (the exit code). Bad input raises :class:`UsageError` (or returns 2 after
printing its own message): the CLI prints the message and exits 2, never a traceback.
"""
import importlib
import pkgutil


class UsageError(Exception):
    """Bad input from the user: the message names the problem and the allowed values."""


def discover_commands():
    """Return the command modules of this package, sorted by command name."""
    modules = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("_"):
            continue
        module = importlib.import_module(f"{__name__}.{info.name}")
        if all(hasattr(module, attr) for attr in ("NAME", "HELP", "add_arguments", "run")):
            modules.append(module)
    return sorted(modules, key=lambda m: m.NAME)
