"""argparse types shared by the commands: comma-separated lists with clear errors."""
from __future__ import annotations

import argparse
import math


def float_list(text: str) -> list[float]:
    """'0.0025,0.005' -> [0.0025, 0.005]; one or more finite numbers."""
    try:
        values = [float(x) for x in text.replace(" ", "").split(",") if x != ""]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma-separated list of numbers") from None
    if not values or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"{text!r}: give one or more finite numbers, e.g. 0.0025,0.005")
    return values


def seed_list(text: str) -> list[int]:
    """'0,1,2' -> [0, 1, 2]; one or more integers >= 0."""
    try:
        values = [int(x) for x in text.replace(" ", "").split(",") if x != ""]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a comma-separated list of integers, "
                                         "e.g. 0,1,2") from None
    if not values or any(v < 0 for v in values):
        raise argparse.ArgumentTypeError(f"{text!r}: give one or more integers >= 0, e.g. 0,1,2")
    return values
