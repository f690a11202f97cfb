"""What the commands and the executables that parse command lines share: errors, the help format, old spellings.

A leaf module, so that an executable (``ros2 run backlash_monitor pipeline``) raises the same
:class:`UsageError` as ``python -m backlash_monitor`` without importing the command package. Also
:class:`DeprecatedSpelling`: an option's old spelling, still taken for one release with a
one-line warning on stderr that names the new one; :class:`HelpFormatter`, the help's layout; and
:func:`out_of_range`, the one form of a range error. The error policy is in docs/cli.md.
"""
from __future__ import annotations

import argparse
import sys


class UsageError(Exception):
    """Bad input from the user: the message names the problem and the allowed values (exit code 2)."""


class RunFailure(Exception):
    """A failure while running, not a bad option: a damaged or truncated bag, a recording that recorded
    nothing (exit code 1, one line; docs/cli.md)."""


def one_line(error: BaseException) -> str:
    """An error's message on one line (a message from a library may span several)."""
    return "; ".join(line.strip() for line in str(error).splitlines() if line.strip() and line.strip() != "^")


class DeprecatedSpelling(argparse.Action):
    """argparse action of an option's old spelling: stores (``append=True``: appends) into the new
    option's ``dest`` and prints one line on stderr naming the new spelling. Taken for one release.

        parser.add_argument("--effects", dest="effects_file", action=DeprecatedSpelling,
                            new="--effects-file", append=True, help=argparse.SUPPRESS)
    """

    def __init__(self, option_strings, dest, new: str, append: bool = False, **kwargs):
        self.new = new
        self.append = append
        if "const" in kwargs:          # an old flag (no value) that stands for a value of the new option
            kwargs.setdefault("nargs", 0)
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog}: warning: {option_string} is deprecated and will be removed in the next "
              f"release; use {self.new}", file=sys.stderr)
        if self.nargs == 0:
            values = self.const
        if self.append:
            items = list(getattr(namespace, self.dest, None) or [])
            items.append(values)
            values = items
        setattr(namespace, self.dest, values)


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Descriptions keep their line breaks; an option's help ends with its real default, once: added only when
    the help does not say its default already, and never as 'None', '' or an empty list (an option whose value
    is worked out at run time says so in its help: '(default: ...)')."""

    def _get_help_string(self, action):
        text = action.help or ""
        if "default" in text or action.default is argparse.SUPPRESS or not action.option_strings:
            return text
        if action.default is None or action.default is False or action.default in ("", [], ()) \
                or action.nargs == 0:
            return text
        value = action.default
        if isinstance(value, (list, tuple)):
            value = ",".join(f"{v:g}" if isinstance(v, float) else str(v) for v in value)
        elif isinstance(value, float):
            value = f"{value:g}"
        return f"{text} (default: {value})"


def out_of_range(option: str, value, low, high, unit: str = "") -> UsageError:
    """The one form of a range error: ``--width-m 0.2: out of range, allowed 0.0001..0.05 m``."""
    def fmt(v):
        return f"{v:g}" if isinstance(v, float) else str(v)
    return UsageError(f"{option} {fmt(value)}: out of range, allowed {fmt(low)}..{fmt(high)}"
                      + (f" {unit}" if unit else ""))
