"""Errors shared by the commands and the executables that parse command lines.

A leaf module, so that an executable (``ros2 run backlash_monitor pipeline``) raises the same
:class:`UsageError` as ``python -m backlash_monitor`` without importing the command package. Also
:class:`DeprecatedSpelling`: an option's old spelling, still taken for one release with a
one-line warning on stderr that names the new one.
"""
from __future__ import annotations

import argparse
import sys


class UsageError(Exception):
    """Bad input from the user: the message names the problem and the allowed values."""


class DeprecatedSpelling(argparse.Action):
    """argparse action of an option's old spelling: stores (``append=True``: appends) into the new
    option's ``dest`` and prints one line on stderr naming the new spelling. Taken for one release.

        parser.add_argument("--effects", dest="effects_file", action=DeprecatedSpelling,
                            new="--effects-file", append=True, help=argparse.SUPPRESS)
    """

    def __init__(self, option_strings, dest, new: str, append: bool = False, **kwargs):
        self.new = new
        self.append = append
        super().__init__(option_strings, dest, **kwargs)

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"{parser.prog}: warning: {option_string} is deprecated and will be removed in the next "
              f"release; use {self.new}", file=sys.stderr)
        if self.append:
            items = list(getattr(namespace, self.dest, None) or [])
            items.append(values)
            values = items
        setattr(namespace, self.dest, values)
