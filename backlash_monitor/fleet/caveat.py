"""The model-fit caveat of a width: a width never reads as confident when the drive's model does not
explain the recording it comes from (issue 31, part 3; docs/fleet.md "Model-fit caveat").

The width is identified against patterns simulated from the drive's model. When the model does not
explain the drive (an effect no one wrote down), the width can be far off with a small spread: a
healthy 5 mm drive read as 10.8 mm with every window agreeing. The spread cannot tell; the model fit
can. So every width, and every width alarm, carries the fit's verdict in the same line:

    width 10.80 ± 0.05 mm — model drive7 v1 does not explain this drive (residual 2.5× its floor):
    run diagnose before acting

One core, two shells:
- live: the classifier and width_trend nodes take the model watch's ``model_fit`` topic of their own
  namespace (``FitVerdict.from_watch``: its level, model and residual over the noise floor);
- offline: ``analyze FOLDER`` takes the model-fit column it computed for the same bag
  (``FitVerdict.from_recording``: watch/core.evaluate_recording's dict).

"Does not explain" is the model watch's own statement: its alarm rule exceeded (level WARN,
config/model_watch.yaml), the same statement its status and the fleet table's model-fit column make.
No fit known (no model watch, no reference) gives no caveat: the width is then as before.
Plain Python: no rclpy.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

CAVEAT_SEPARATOR = " — "


@dataclass(frozen=True)
class FitVerdict:
    """The model fit a width is read beside: the model version, whether it explains the drive, and the
    event-averaged residual over its noise floor (NaN: not known)."""
    model: str
    explains: bool
    residual_over_noise: float = math.nan

    @classmethod
    def from_watch(cls, level: str, model: str, residual_over_noise: float) -> "FitVerdict":
        """From the model watch's ModelFit message: ``level`` "OK" or "WARN" (its alarm rule)."""
        if level not in ("OK", "WARN"):
            raise ValueError(f"model fit level {level!r}; allowed: OK, WARN")
        return cls(model=str(model) or "?", explains=level == "OK",
                   residual_over_noise=float(residual_over_noise))

    @classmethod
    def from_recording(cls, fit) -> "FitVerdict | None":
        """From ``analyze FOLDER``'s model fit of a bag (watch/core.evaluate_recording's dict); None
        when the bag has none (a string: no reference, not evaluated)."""
        if not isinstance(fit, dict):
            return None
        return cls.from_watch(fit["level"], fit.get("model", "?"), fit.get("residual_over_noise", math.nan))


def caveat(fit: FitVerdict | None) -> str:
    """The words a width carries when its model does not explain the drive; "" otherwise."""
    if fit is None or fit.explains:
        return ""
    ratio = fit.residual_over_noise
    residual = f" (residual {ratio:.1f}× its floor)" if math.isfinite(ratio) else ""
    return f"model {fit.model} does not explain this drive{residual}: run diagnose before acting"


def with_caveat(text: str, fit: FitVerdict | None) -> str:
    """``text`` (a width, a width alarm's message) with the caveat appended in the same line, if any."""
    words = caveat(fit)
    if not words:
        return text
    return f"{text}{CAVEAT_SEPARATOR}{words}" if text else words


def width_text(width_m: float, uncertainty_m: float = math.nan) -> str:
    """'10.80 ± 0.05 mm', '10.80 mm' without an uncertainty, '-' without a width (NaN; 0 from a
    publisher that does not set the field reads as none), '≥ 20.00 mm (the top of the classifier's range)' for a
    censored width (uncertainty +inf: classifier/fusion.py fused_width_uncertainty_m)."""
    if not math.isfinite(width_m) or width_m <= 0:
        return "-"
    if uncertainty_m == math.inf:
        return f"≥ {width_m * 1e3:.2f} mm (the top of the classifier's range)"
    if math.isfinite(uncertainty_m) and uncertainty_m > 0:
        return f"{width_m * 1e3:.2f} ± {uncertainty_m * 1e3:.2f} mm"
    return f"{width_m * 1e3:.2f} mm"


def width_line(width_m: float, uncertainty_m: float, fit: FitVerdict | None) -> str:
    """'width 10.80 ± 0.05 mm' and, when the model does not explain the drive, its caveat."""
    return with_caveat(f"width {width_text(width_m, uncertainty_m)}", fit)


def says_model_fails(line: str) -> bool:
    """Whether a width's or a width alarm's line carries the caveat (the bench's and the tests' reading)."""
    return "does not explain this drive" in line
