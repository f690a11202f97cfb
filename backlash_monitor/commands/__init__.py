"""The commands of ``python -m backlash_monitor``: one module per command.

Each module defines ``NAME`` (the command word), ``HELP`` (one line), ``add_arguments(parser)`` and
``run(args) -> int`` (the exit code). Bad input raises :class:`UsageError` (or returns 2 after
printing its own message): the CLI prints the message and exits 2, never a traceback.
"""
import importlib
import pkgutil

from backlash_monitor.errors import UsageError  # noqa: F401  (the commands raise it from here)


def command_module_names() -> dict[str, str]:
    """{command word: module name}; a module ``bag_info`` is the command ``bag-info``."""
    return {info.name.replace("_", "-"): info.name for info in pkgutil.iter_modules(__path__)
            if not info.name.startswith("_")}


def discover_commands(only: str | None = None):
    """Return the command modules of this package, sorted by command name (``only``: just that
    command's module, so that running one command does not import every other's dependencies)."""
    modules = []
    names = command_module_names()
    wanted = [names[only]] if only in names else sorted(names.values())
    for name in wanted:
        module = importlib.import_module(f"{__name__}.{name}")
        if all(hasattr(module, attr) for attr in ("NAME", "HELP", "add_arguments", "run")):
            modules.append(module)
    return sorted(modules, key=lambda m: m.NAME)
