"""Errors shared by the commands and the executables that parse command lines.

A leaf module, so that an executable (``ros2 run backlash_monitor pipeline``) raises the same
:class:`UsageError` as ``python -m backlash_monitor`` without importing the command package.
"""


class UsageError(Exception):
    """Bad input from the user: the message names the problem and the allowed values."""
