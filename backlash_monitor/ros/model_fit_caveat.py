"""The live shell of the width's model-fit caveat (core: backlash_monitor/fleet/caveat.py).

The classifier and width_trend nodes subscribe to the model watch's ``model_fit`` of their own namespace
(relative topic: ``/line1/drive07/model_fit`` beside ``/line1/drive07/estimate``) and keep its last verdict.
No model watch in the namespace: no message, no caveat (the width reads as before).
"""
from __future__ import annotations

from backlash_monitor_msgs.msg import ModelFit

from backlash_monitor.fleet.caveat import FitVerdict

MODEL_FIT_TOPIC = "model_fit"
MODEL_FIT_DEPTH = 10     # RELIABLE, KEEP_LAST (the model watch publishes RELIABLE, depth 100)


def verdict_from_message(msg) -> FitVerdict:
    """A ModelFit message as the caveat's FitVerdict (level WARN: the model does not explain the drive)."""
    return FitVerdict.from_watch("WARN" if msg.level == msg.WARN else "OK", msg.model,
                                 msg.residual_over_noise_overall)


def follow_model_fit(node, on_verdict) -> None:
    """Subscribe ``node`` to its namespace's ``model_fit``; ``on_verdict(FitVerdict)`` for each message."""
    node.create_subscription(ModelFit, MODEL_FIT_TOPIC, lambda msg: on_verdict(verdict_from_message(msg)),
                             MODEL_FIT_DEPTH)
