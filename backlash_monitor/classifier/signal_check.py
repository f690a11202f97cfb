"""The check of the both-accelerometer width against the motor-side one (no rclpy).

The shape mode gives a width from each accelerometer and from both together (``a1``, ``a2``, ``a1+a2``). The
width is a kinematic quantity: the gap the motor shaft crosses before the jaws touch. ``a1`` (the motor side) reads
it from the crossing and the impact as the motor sees them; ``a2`` (the load side) from the load's response after
the impact, which the load side's own dynamics shape (spring, mass, wheel friction, whatever acts there). Where the
drive is the model the library was trained on, both together are the most precise (docs/classifier.md). Where the
load side carries a mechanism the library does not know, a2's features leave the training range and the
both-together regression extrapolates: on 117 analyses of the independent simulator's drives (clean, catalogue
effects in other laws, mechanisms outside the catalogue; sets 1-9 and the foreign bench, all spent development
data) the fused ``a1+a2`` width was 0.88 mm off on the outside-mechanism drives against 0.24 mm for ``a1``'s,
while on the clean drives ``a1+a2`` was the closer (0.041 against 0.082 mm; docs/classifier.md "The signal
check").

So the width the drive's level follows is ``a1+a2``'s unless it departs from ``a1``'s by more than
``SIGNAL_CHECK_SIGMAS`` of their combined stated uncertainty (the robust standard errors of the two fused
medians over the same events: the events are the independent units, classifier/fusion.py). Then ``a1``'s is
taken, with its own uncertainty, and the estimate says so (``fused_from_signal``). The two are correlated (both
read a1's features), so the difference's true standard error is smaller than the root sum of squares used here:
the check is conservative (it switches less often than a 2-sigma test would).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

BOTH_SIGNALS = "a1+a2"
MOTOR_SIDE_SIGNAL = "a1"
# 2 combined standard errors: on the clean development drives the check moved the mean error from 0.041 to
# 0.049 mm (it switches on few windows), on the outside-mechanism drives from 0.88 to 0.27 mm; 1 sigma gave
# 0.068 / 0.24, 3 sigma 0.044 / 0.31 (docs/classifier.md "The signal check").
SIGNAL_CHECK_SIGMAS = 2.0


@dataclass(frozen=True)
class CheckedWidth:
    """The width a drive's level follows and where it came from."""
    width_m: float
    uncertainty_m: float
    signal: str                  # BOTH_SIGNALS or MOTOR_SIDE_SIGNAL
    departure_sigmas: float      # |both - motor side| / combined uncertainty (NaN: not checked)


def checked_width(both_m: float, both_se_m: float, motor_m: float, motor_se_m: float,
                  sigmas: float = SIGNAL_CHECK_SIGMAS) -> CheckedWidth:
    """Both accelerometers' fused width unless it departs from the motor side's by more than ``sigmas`` combined
    standard errors; then the motor side's. Not checked (both's kept, departure NaN) when either width or
    uncertainty is not finite: fewer than 3 events, or a width censored at the top of the range (+inf)."""
    values = (both_m, both_se_m, motor_m, motor_se_m)
    if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values):
        return CheckedWidth(both_m, both_se_m, BOTH_SIGNALS, math.nan)
    combined = math.hypot(both_se_m, motor_se_m)
    departure = abs(both_m - motor_m) / combined if combined > 0 else (0.0 if both_m == motor_m else math.inf)
    if departure > sigmas:
        return CheckedWidth(motor_m, motor_se_m, MOTOR_SIDE_SIGNAL, departure)
    return CheckedWidth(both_m, both_se_m, BOTH_SIGNALS, departure)
