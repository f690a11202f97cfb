"""The alarm rule of the model watch: when a drive is said to no longer match its model (docs/model_watch.md).

The watch tests the model after every onset event, on the last N events (consistency.test, diagnose's test). At
diagnose's 1 % level per view, 14,400 tests an hour of a correct model would alarm about every few seconds, and the
windows of consecutive tests share N - 1 of their events, so they are not independent either. The rule:

- an evaluation *exceeds* when a view of the consistency test (event average, spectral shape, record mean) has a
  p-value below ``view_p``, or the event average's residual exceeds ``residual_ratio`` times the noise floor of an
  N-event mean (diagnose's second criterion, 2.0 at its level). With ``predictive`` the p-value is Hotelling's
  predictive law's (consistency.predictive_p: the views are whitened by a covariance estimated from the model's own
  events, reference.ModelReference.view_dof), else chi^2's;
- ``event_clip_p``: the event average is the bounded-influence mean of the window's events (reference.evaluate's
  clip_p, consistency.clipped_mean): the model's own single events are heavy-tailed (a far-side impact outside the
  segment: one clean 9 mm event's |u|^2 943, median 6.8), and one such event stays in the next N windows, so no
  persistence over consecutive windows removes it;
- ``robust``: ... and still does with any one of its events left out (the test on the N - 1 others);
- WARN after ``persistence`` consecutive exceeding evaluations; OK again after ``clear_after`` consecutive
  evaluations that do not exceed (a window that no longer holds the evidence).

The values and what they were measured on: config/model_watch.yaml, docs/model_watch.md ("The alarm rule";
bench/model_watch.py: false alarms over >= 1 h of clean drives, own and foreign, the onsets to detection of every
catalogue family, and the model's own statistics under the test).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
import os

import numpy as np
from scipy.special import chdtri     # chi^2's isf, as scipy.stats.chi2.isf computes it (scipy.stats costs ~1 s to import)
from scipy.special import chdtrc     # chi^2 survival function (stats.chi2.sf without its overhead)
from ament_index_python.packages import get_package_share_directory
import yaml

from backlash_monitor.files.config import config_file
from backlash_monitor.workbench.consistency import predictive_p, predictive_t2_isf

ALARM_VIEWS = ("event_average", "spectral_shape", "record_mean")     # consistency.ConsistencyResult.consistent's


@dataclass(frozen=True)
class AlarmRule:
    view_p: float = 1e-6
    residual_ratio: float = 3.0
    persistence: int = 3
    clear_after: int = 16
    robust: bool = True
    event_clip_p: float | None = 1e-3     # None: every event counts as it is (the plain mean)
    predictive: bool = True               # the views' p-values from Hotelling's predictive law (the whitening is
                                          # estimated from the model's own events); False: chi^2 (diagnose's)

    def check(self) -> "AlarmRule":
        if not (0.0 < self.view_p < 0.5):
            raise ValueError(f"alarm view_p = {self.view_p!r}; allowed: 0 < view_p < 0.5")
        if self.event_clip_p is not None and not (0.0 < self.event_clip_p < 0.5):
            raise ValueError(f"alarm event_clip_p = {self.event_clip_p!r}; allowed: 0 < event_clip_p < 0.5, or "
                             "none (no clipping)")
        if not (self.residual_ratio > 0):
            raise ValueError(f"alarm residual_ratio = {self.residual_ratio!r}; allowed: > 0")
        for name in ("persistence", "clear_after"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ValueError(f"alarm {name} = {v!r}; allowed: an integer >= 1")
        return self

    def exceeds(self, evaluation, dof: dict | None = None) -> tuple[bool, list]:
        """(the evaluation exceeds the rule, [the views / 'residual' that do]) -- the window as it is. ``dof``: per
        view, the degrees of freedom of its whitening (reference.ModelReference.view_dof)."""
        return self.result_exceeds(evaluation.result, dof)

    def result_exceeds(self, result, dof: dict | None = None) -> tuple[bool, list]:
        """The same for a consistency.ConsistencyResult."""
        names = []
        for name in ALARM_VIEWS:
            v = result.views.get(name)
            if v is not None and v.t2 > self.limit(name, v.dimension, dof):     # p < view_p
                names.append(name)
        if result.residual_over_noise > self.residual_ratio:
            names.append("residual")
        return bool(names), names

    def limit(self, name: str, dimension: int, dof: dict | None = None) -> float:
        """The T^2 at which a view exceeds: its p-value is view_p."""
        if self.predictive and dof and name in dof:
            return _predictive_isf(self.view_p, dimension, dof[name])
        return _isf(self.view_p, dimension)

    def p_value(self, name: str, t2: float, dimension: int, dof: dict | None = None) -> float:
        """A view's p-value under the rule's law (the one ``view_p`` is compared with)."""
        if self.predictive and dof and name in dof:
            return predictive_p(t2, dimension, dof[name])
        return float(chdtrc(dimension, t2))

    def limits(self, evaluation, dof: dict | None = None) -> dict:
        """Per alarm view: the T^2 at which it exceeds."""
        return {n: self.limit(n, v.dimension, dof) for n, v in evaluation.result.views.items() if n in ALARM_VIEWS}


class AlarmState:
    """OK / WARN with persistence and clearing; ``since``: what the state changed at (the caller's time)."""

    def __init__(self, rule: AlarmRule):
        self.rule = rule.check()
        self.level = "OK"
        self.run = 0              # consecutive exceeding (OK) or not exceeding (WARN) evaluations
        self.since = None
        self.first_exceeding = None

    def update(self, exceeding: bool, at) -> bool:
        """One evaluation; True when the level changed."""
        if self.level == "OK":
            if exceeding:
                if self.run == 0:
                    self.first_exceeding = at
                self.run += 1
                if self.run >= self.rule.persistence:
                    self.level, self.since, self.run = "WARN", self.first_exceeding, 0
                    return True
            else:
                self.run = 0
            return False
        if exceeding:
            self.run = 0
            return False
        self.run += 1
        if self.run >= self.rule.clear_after:
            self.level, self.since, self.run = "OK", at, 0
            return True
        return False


def config_path() -> str:
    """config/model_watch.yaml (the repository's, else the installed package's share)."""
    here = os.path.join(os.path.dirname(__file__), "..", "..", "config", "model_watch.yaml")
    if os.path.isfile(here):
        return os.path.normpath(here)
    return os.path.join(get_package_share_directory("backlash_monitor"), "config", "model_watch.yaml")


def _typed_keys(path: str, want: dict) -> dict:
    """The YAML file's keys ``want`` (name -> int, float or bool), each checked: ValueError naming a missing or bad
    key and what is allowed (``event_clip_p`` may be null)."""
    with open(path, encoding="utf-8") as f:
        cfg = yaml.safe_load(f) or {}
    out = {}
    for key, kind in want.items():
        if key not in cfg:
            raise ValueError(f"{path}: missing key {key!r}; allowed keys: {', '.join(want)}")
        v = cfg[key]
        if key == "event_clip_p" and v is None:
            out[key] = None
            continue
        if kind is bool:
            if not isinstance(v, bool):
                raise ValueError(f"{path}: {key} = {v!r}; allowed: true or false")
        elif isinstance(v, bool) or not isinstance(v, (int, float)) or (kind is int and not isinstance(v, int)):
            raise ValueError(f"{path}: {key} = {v!r} is not {'an integer' if kind is int else 'a number'}")
        out[key] = kind(v)
    return out


def load_config(path: str | None = None) -> dict:
    """The model watch's settings (config/model_watch.yaml): ValueError naming a missing or bad key."""
    path = path or config_path()
    out = _typed_keys(path, {"window_events": int, "view_p": float, "residual_ratio": float, "persistence": int,
                             "clear_after": int, "robust": bool, "event_clip_p": float, "predictive": bool,
                             "snapshot_before_s": float, "snapshot_after_s": float})
    load_rule_from(out)
    return out


FOLDER_CONFIG = "folder_model_fit.yaml"


def folder_config_path() -> str:
    """config/folder_model_fit.yaml (files.config.config_file: the source tree's, else the installed package's)."""
    return str(config_file(FOLDER_CONFIG))


def load_folder_config(path: str | None = None) -> dict:
    """The one-off model fit's settings (``analyze FOLDER``: one test per bag; config/folder_model_fit.yaml):
    ValueError naming a missing or bad key."""
    path = path or folder_config_path()
    out = _typed_keys(path, {"window_events": int, "view_p": float, "residual_ratio": float, "robust": bool,
                             "event_clip_p": float, "predictive": bool})
    if out["window_events"] < 3:
        raise ValueError(f"{path}: window_events = {out['window_events']!r}; allowed: an integer >= 3")
    load_folder_rule_from(out)
    return out


def load_folder_rule_from(c: dict) -> AlarmRule:
    """One evaluation decides (no persistence, nothing to clear)."""
    return AlarmRule(c["view_p"], c["residual_ratio"], 1, 1, c["robust"], c.get("event_clip_p"),
                     c.get("predictive", True)).check()


def load_folder_rule(path: str | None = None) -> AlarmRule:
    """The rule of a one-off model fit (``analyze FOLDER``'s column): config/folder_model_fit.yaml."""
    return load_folder_rule_from(load_folder_config(path))


def load_rule_from(c: dict) -> AlarmRule:
    return AlarmRule(c["view_p"], c["residual_ratio"], c["persistence"], c["clear_after"], c["robust"],
                     c.get("event_clip_p"), c.get("predictive", True)).check()


def load_rule(path: str | None = None) -> AlarmRule:
    return load_rule_from(load_config(path))


@lru_cache(maxsize=64)
def _isf(p: float, dimension: int) -> float:
    return float(chdtri(dimension, p))


@lru_cache(maxsize=64)
def _predictive_isf(p: float, dimension: int, dof: int) -> float:
    return predictive_t2_isf(p, dimension, dof)


def p_min(evaluation, rule: AlarmRule | None = None, dof: dict | None = None) -> float:
    """The smallest p-value of the alarm views (what ``view_p`` is compared with), under ``rule``'s law."""
    return result_p_min(evaluation.result, rule, dof)


def result_p_min(result, rule: AlarmRule | None = None, dof: dict | None = None) -> float:
    rule = rule or AlarmRule(predictive=False)
    ps = [rule.p_value(n, v.t2, v.dimension, dof) for n, v in result.views.items() if n in ALARM_VIEWS]
    return float(np.min(ps)) if ps else 1.0
