"""The check of the both-accelerometer width against the motor-side one (no rclpy).

The shape mode gives a width from each accelerometer and from both together (``a1``, ``a2``, ``a1+a2``). The
width is a kinematic quantity: the gap the motor shaft crosses before the jaws touch. ``a1`` (the motor side) reads
it from the crossing and the impact as the motor sees them; ``a2`` (the load side) from the load's response after
the impact, which the load side's own dynamics shape (spring, mass, wheel friction, whatever acts there). Where the
drive is the model the library was trained on, both together are the most precise (docs/classifier.md). Where the
load side carries a mechanism the library does not know, a2's features leave the training range and the
both-together regression extrapolates: on 88 recordings of the independent simulator's drives (clean, catalogue
effects in other laws, mechanisms outside the catalogue; sets 8-10 and the foreign bench, all spent or development
data) the fused ``a1+a2`` width was 0.96 mm off on the outside-mechanism drives against 0.22 mm for ``a1``'s,
while on the clean drives ``a1+a2`` was the closer (0.042 against 0.086 mm; docs/classifier.md 5.3).

So the width the drive's level follows is ``a1+a2``'s unless
- it departs from ``a1``'s by more than ``SIGNAL_CHECK_SIGMAS`` of their combined stated uncertainty (the robust
  standard errors of the two fused medians over the same events: the events are the independent units,
  classifier/fusion.py) and by more than ``MIN_DEPARTURE_M`` (0.2 mm: on clean drives the two regressions' own
  biases differ by up to about that, and 8 events' standard errors are themselves uncertain, so without it the test
  took ``a1`` on 6 % of the fusions of our own clean 10 s drives and 0.043 -> 0.119 mm on the tenth sealed half's
  clean drive), or
- its own stated uncertainty is more than ``SCATTER_RATIO`` times ``a1``'s: both together scatter far more from
  event to event than the motor side alone. On the library's own model they scatter less (training residual
  0.097 mm for ``a1+a2`` against 0.208 mm for ``a1``, docs/classifier.md 3.1), so a wide ``a1+a2`` beside a tight
  ``a1`` says the load side is not that model, even when the wide median happens to lie near ``a1``'s (measured:
  a viscoelastic coupling, ``a1+a2`` 6.7 ± 1.0 mm beside ``a1`` 5.75 ± 0.12 mm on a 5.4 mm drive: not 2 sigma apart,
  1.3 mm off).
Then ``a1``'s is taken, with its own uncertainty, and the estimate says so (``fused_from_signal``). The two are
correlated (both read a1's features), so the difference's true standard error is smaller than the root sum of
squares used here: the first test is conservative (it switches less often than a 2-sigma test would).

Both tests take the motor side as the sound one. Where a1's own sensor chain is what is wrong (it does not follow
the recorded motor speed: windowing/a1_chain.py), ``a1`` and ``a1+a2`` both read it, and the load side's ``a2`` is
taken instead (``a1_chain_checked``): measured on the independent simulator, a quadratic a1 characteristic read
4.46 mm off from ``a1+a2`` and 0.01 mm from ``a2``, a telemetry AGC on a1 0.99 mm and 0.04 mm (docs/classifier.md 5.4).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

BOTH_SIGNALS = "a1+a2"
MOTOR_SIDE_SIGNAL = "a1"
LOAD_SIDE_SIGNAL = "a2"
# 2 combined standard errors, chosen first (on 72 of those recordings): the clean drives' mean error 0.041 ->
# 0.049 mm (it switches on few windows), the outside-mechanism drives' 1.00 -> 0.23 mm; 1 sigma gave 0.068 / 0.24,
# 3 sigma 0.044 / 0.31 (docs/classifier.md 5.3).
SIGNAL_CHECK_SIGMAS = 2.0
# 2: on the development data above the second test took the outside-mechanism drives from 0.264 to 0.223 mm and left
# the clean ones at 0.049 mm (1: 0.216 / 0.052; 3: 0.226 / 0.049); our own grid 0.0520 -> 0.0524 mm.
SCATTER_RATIO = 2.0
# 0.2 mm, set after the tenth sealed half (its clean drive) on development data: the share of full fusions that take a1
# on clean drives 6-7 % -> 0-2 % (our own 21 clean 10 s drives 0.044 -> 0.038 mm, 14 foreign clean 0.050 -> 0.043),
# the outside-mechanism drives 0.237 -> 0.238 mm, other laws 0.181 -> 0.186 (/work/s47/rule_scan2.py)
MIN_DEPARTURE_M = 0.2e-3


@dataclass(frozen=True)
class CheckedWidth:
    """The width a drive's level follows and where it came from."""
    width_m: float
    uncertainty_m: float
    signal: str                  # BOTH_SIGNALS, MOTOR_SIDE_SIGNAL or (a1's chain not sound) LOAD_SIDE_SIGNAL
    departure_sigmas: float      # |both - motor side| / combined uncertainty (NaN: not checked)
    scatter_ratio: float = math.nan   # both's uncertainty / the motor side's (NaN: not checked)
    reason: str = ""             # why the motor side's was taken ("departed by 3.4 sigma (0.45 mm)"); "" when not


def checked_width(both_m: float, both_se_m: float, motor_m: float, motor_se_m: float,
                  sigmas: float = SIGNAL_CHECK_SIGMAS, scatter_ratio: float = SCATTER_RATIO,
                  min_departure_m: float = MIN_DEPARTURE_M) -> CheckedWidth:
    """Both accelerometers' fused width unless it departs from the motor side's by more than ``sigmas`` combined
    standard errors and ``min_departure_m``, or its standard error is more than ``scatter_ratio`` times the motor
    side's; then the motor side's. Both together censored at the top of the range (uncertainty +inf: the width is at
    least both_m) beside a finite motor side below it: the departure is at least both_m - motor_m, tested against the
    motor side's error alone and the same floor. Not checked (both's kept, departure NaN) when either width or
    uncertainty is otherwise not finite (fewer than 3 events; the motor side censored or unknown), or when the motor
    side's events gave one width exactly (a spread of 0 is a stuck or clipped input, not a precision: a drive's windows
    scatter by ~0.1 mm)."""
    values = (both_m, both_se_m, motor_m, motor_se_m)
    if _censored_above(both_m, both_se_m, motor_m, motor_se_m):
        # both together at the range's top (a censored width: at least both_m) beside a motor side read well inside
        # the range: the departure is at least both_m - motor_m, known to the motor side's error alone
        apart_m = both_m - motor_m
        departure = apart_m / motor_se_m
        if departure > sigmas and apart_m > min_departure_m:
            return CheckedWidth(motor_m, motor_se_m, MOTOR_SIDE_SIGNAL, departure, math.inf,
                                f"read at the top of the range (at least {both_m * 1e3:.2f} mm), {apart_m * 1e3:.2f} mm "
                                f"above a1's ({departure:.0f} sigma)")
        return CheckedWidth(both_m, both_se_m, BOTH_SIGNALS, departure, math.inf)
    if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in values) or motor_se_m <= 0:
        return CheckedWidth(both_m, both_se_m, BOTH_SIGNALS, math.nan)
    apart_m = abs(both_m - motor_m)
    departure = apart_m / math.hypot(both_se_m, motor_se_m)
    ratio = both_se_m / motor_se_m
    reasons = ([f"departed by {departure:.1f} sigma ({apart_m * 1e3:.2f} mm)"]
               if departure > sigmas and apart_m > min_departure_m else [])
    reasons += [f"scattered {ratio:.1f}x as much"] if ratio > scatter_ratio else []
    if reasons:
        return CheckedWidth(motor_m, motor_se_m, MOTOR_SIDE_SIGNAL, departure, ratio, " and ".join(reasons))
    return CheckedWidth(both_m, both_se_m, BOTH_SIGNALS, departure, ratio)


def _censored_above(both_m, both_se_m, motor_m, motor_se_m) -> bool:
    """Both together censored at the range's top (a finite width with an uncertainty of +inf:
    fusion.fused_width_uncertainty_m) above a motor side with a finite, non-zero error."""
    numbers = all(isinstance(v, (int, float)) for v in (both_m, both_se_m, motor_m, motor_se_m))
    return (numbers and math.isfinite(both_m) and both_se_m == math.inf and math.isfinite(motor_m)
            and math.isfinite(motor_se_m) and motor_se_m > 0 and motor_m < both_m)


def a1_chain_checked(check: CheckedWidth, a1_chain, load_m: float, load_se_m: float) -> CheckedWidth:
    """``check`` unless a1's chain does not follow the motor speed (``a1_chain``: windowing/a1_chain.A1ChainResult,
    None: not checked): then the load side's fused width (``load_m`` ± ``load_se_m``), with the finding as its reason.
    Kept as it is when the load side's width is not finite (no a2 estimate)."""
    if a1_chain is None or not getattr(a1_chain, "faulty", False):
        return check
    if not (isinstance(load_m, (int, float)) and math.isfinite(load_m)):
        return check
    return CheckedWidth(load_m, load_se_m, LOAD_SIDE_SIGNAL, check.departure_sigmas, check.scatter_ratio,
                        f"reads a1, and {a1_chain.text()}")


def source_text(fused_from_signal: str, signal: str, reason: str) -> str:
    """Why a width carries another signal's fusion, for a message ("a1's: a1+a2 departed by 3.4 sigma (0.45 mm)"), from
    the check's ``reason``; "" when it carries its own."""
    if fused_from_signal in ("", signal):
        return ""
    return f"{fused_from_signal}'s: {signal} {reason}".rstrip()


def rule_text(sigmas: float = SIGNAL_CHECK_SIGMAS, min_departure_m: float = MIN_DEPARTURE_M,
              scatter_ratio: float = SCATTER_RATIO) -> str:
    """The rule in words, for a user who sees the motor side's width taken."""
    # deferred: the commands import this module before numpy (fleet/folder_analysis.limit_threads)
    from backlash_monitor.windowing.a1_chain import MAX_MISMATCH as A1_CHAIN_MAX_MISMATCH
    return (f"a1+a2 is replaced by a1 when the two depart by more than {sigmas:g} combined standard errors and "
            f"{min_departure_m * 1e3:g} mm (a1's error alone when a1+a2 is at the top of the range), or a1+a2 scatters "
            f"more than {scatter_ratio:g}x as much as a1; by a2 when "
            f"a1 does not follow the motor speed r·dΩ₁/dt (more than {A1_CHAIN_MAX_MISMATCH:.0%} of its motion not in a1)")
