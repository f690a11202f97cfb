"""The model watch's core: a drive's last N onset events against its model version's reference, after every event.

``ModelWatch.feed`` takes the stream (a1, a2, angle difference and the motor speed omega1 by sample index;
watch/events.py makes the events),
``add_event`` one completed event. Once the window holds N events, every new event evaluates the reference
(workbench/reference.py: consistency.test, diagnose's test, at the width that fits best -- the measurand) on the
window, with the sensor noise floor read off the window's spectra; the alarm rule (watch/alarm.py) turns the
evaluations into OK / WARN. Each evaluation is a :class:`WatchUpdate`: what the node publishes on ``model_fit``
and ``/diagnostics``. Plain numpy, no rclpy (docs/model_watch.md).
"""
from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from backlash_monitor.workbench.events import DC_SIGNALS, SEGMENT_SIGNALS, POST_SAMPLES, PRE_SAMPLES
from backlash_monitor.workbench.reference import Evidence, ModelReference, evidence_from_measurement

from .alarm import AlarmRule, AlarmState, p_min, result_p_min
from .events import LiveEvent, LiveEvents
from backlash_monitor.workbench import spectral
from backlash_monitor.workbench.analysis import quantisation_step, quantisation_psd

DEFAULT_WINDOW_EVENTS = 16       # about a 4 s recording: the length the workbench is measured on
NOISE_REBUILD_FACTOR = 1.5       # the views are rebuilt when the noise floor moved by more than this factor
NOISE_NEGLIGIBLE = 0.05          # a noise floor below this share of the model's weakest spectral band is taken as 0:
                                 # it moves that band's ln power by < 0.05, well inside the events' spread (on the
                                 # own simulator a2's estimate wanders between 0 and 1e-2 of its weakest band,
                                 # and with 1e-3 every wander rebuilt the views: 1.4 s of CPU each)


@dataclass
class WatchUpdate:
    """One evaluation of the watch (after an onset event, once the window is full)."""
    entry_sample_index: int
    level: str                         # "OK" | "WARN" (the alarm rule's state after this evaluation)
    changed: bool                      # the level changed with this evaluation
    since_sample_index: int | None     # the evaluation the current level started at (WARN: its first exceeding)
    exceeding: bool
    exceeding_views: list
    evaluation: object                 # reference.Evaluation
    p_min: float
    events: int
    limits: dict = field(default_factory=dict)
    loo: list = field(default_factory=list)   # the robust rule's leave-one-out windows: [(smallest p, residual
                                              # ratio)] per left-out event (computed for an exceeding window)

    @property
    def where(self) -> tuple[str, str]:
        w = self.evaluation.where or {}
        return w.get("dominant_phase", ""), w.get("dominant_level", "")


class WindowEvidence(Evidence):
    """The window's Evidence whose raw segments are stacked only when read: an evaluation reads the events'
    denoised segments, spectral features and period means; the raw ones (E x 2 x L, ~0.6 MB a window) only
    ``where`` (once a window, or while WARN), the leave-one-out windows and the ADC step do."""

    _events: tuple = ()
    _raw = None

    @property
    def raw(self) -> np.ndarray:
        if self._raw is None:
            self._raw = np.stack([e.raw for e in self._events])
        return self._raw

    @raw.setter
    def raw(self, value) -> None:
        self._raw = value

    @classmethod
    def of(cls, events, noise_psd, quant_step, dc_names=SEGMENT_SIGNALS) -> "WindowEvidence":
        out = cls(None, np.stack([e.dc for e in events]), np.stack([e.spec for e in events]), noise_psd,
                  np.array([e.entry_sample_index for e in events]), tuple(dc_names),
                  denoised=(np.stack([e.denoised for e in events]) if all(e.denoised is not None for e in events)
                            else None),
                  quant_step=quant_step)
        out._events = tuple(events)
        return out


class ModelWatch:
    """``record_mean``: the record-mean view's signals, as diagnose takes a recording's (events.dc_signals): a1, a2
    and the motor speed omega1 (DC_SIGNALS, the default: each feed brings omega1), or a1 and a2 only (a drive that
    does not stream omega1; a load on the motor then shows only in what it does to the accelerations)."""

    def __init__(self, reference: ModelReference, window_events: int = DEFAULT_WINDOW_EVENTS,
                 rule: AlarmRule | None = None, record_mean=DC_SIGNALS):
        if isinstance(window_events, bool) or not isinstance(window_events, int) or window_events < 3:
            raise ValueError(f"window_events = {window_events!r}; allowed: an integer >= 3 (diagnose needs 3 "
                             "onset events)")
        self.record_mean = tuple(record_mean)
        missing = [n for n in self.record_mean if n not in reference.dc_names]
        if missing:
            raise ValueError(f"record-mean signals {', '.join(self.record_mean)}: the reference {getattr(reference, 'path', '')} has "
                             f"no {', '.join(missing)} (it has {', '.join(reference.dc_names)}); rebuild it with "
                             "`python -m backlash_monitor watch-reference` or watch a1 and a2 only")
        self.reference = reference
        self.window_events = window_events
        self.rule = (rule or AlarmRule()).check()
        self.state = AlarmState(self.rule)
        self.events: deque = deque(maxlen=window_events)
        self.live = LiveEvents(reference.sample_period_s, reference.pulse_period_samples, dc_names=self.record_mean)
        self.views_noise = np.zeros(len(SEGMENT_SIGNALS))
        self.views_quant: np.ndarray | None = None     # per signal the ADC step the views quantise the model at
        self.noise_checked = False
        self.quant_step: np.ndarray | None = None      # per signal the window's ADC step (found once), 0: none
        self.noise_scale = self._noise_scale()
        self.evaluations = 0
        self.dof = reference.view_dof()          # the views' whitening: degrees of freedom (the rule's p-values)
        self.last: WatchUpdate | None = None
        reference.for_window(self.views_noise, window_events, self.record_mean)   # the views at zero noise, before the stream

    def _noise_scale(self) -> np.ndarray:
        """Per signal: the model's weakest spectral band as a white PSD [(m/s^2)^2/Hz]."""
        unit = spectral.noise_power(np.ones(len(SEGMENT_SIGNALS)), PRE_SAMPLES + POST_SAMPLES,
                                    self.reference.sample_period_s)
        return self.reference.base_bands.mean(axis=0).min(axis=-1) / unit

    def feed(self, first_sample_index: int, a1, a2, angle_difference, omega1=None) -> list[WatchUpdate]:
        """The next samples of the drive's stream (omega1 [rad/s] when record_mean has it); the evaluations of the
        onset events they complete."""
        out = []
        for ev in self.live.feed(first_sample_index, a1, a2, angle_difference, omega1):
            u = self.add_event(ev)
            if u is not None:
                out.append(u)
        return out

    def noise_floor(self) -> np.ndarray:
        """The sensor noise floor of the window's events (their periods' mean Welch spectrum vs the model's): the
        white noise before the ADC's quantiser when the signal has one (analysis.sensor_noise_floor)."""
        psds = [e.psd for e in self.events if e.psd is not None]
        if not psds:
            return self.views_noise
        psd = np.mean(psds, axis=0)
        return self.reference.noise_floor(dict(zip(SEGMENT_SIGNALS, psd)), significant=True,
                                          quant_step=self.quantisation())

    def quantisation(self) -> np.ndarray:
        """Per signal the ADC's step (analysis.quantisation_step reads it off the samples), 0: not quantised. A
        property of the sensor chain: found once, on the first full window's raw segments (~36,000 samples per
        signal; np.unique of them cost ~4 ms, a third of the watch's work when repeated)."""
        if self.quant_step is None:
            self.quant_step = np.array([quantisation_step(np.concatenate([e.raw[i] for e in self.events]))
                                        for i in range(len(SEGMENT_SIGNALS))])
        return self.quant_step

    def _views_noise(self) -> np.ndarray:
        """The noise floor the views are built for: the window's, once it moved by NOISE_REBUILD_FACTOR (a
        rebuild costs ~0.1 s; the floor of a sensor does not change from event to event). The ADC's quantiser
        (quantisation) is fixed with the first window: a signal's counts when its step^2/12 is not negligible
        (NOISE_NEGLIGIBLE, as a white floor's)."""
        newest = self.events[-1]
        if self.noise_checked and newest.psd is None:
            return self.views_noise          # no new spectrum since the last look
        self.noise_checked = True            # (the first evaluation always looks: its window has 4 spectra)
        est = self.noise_floor()
        floor = NOISE_NEGLIGIBLE * self.noise_scale
        if self.views_quant is None:
            quant = self.quantisation()
            self.views_quant = np.where(quantisation_psd(quant, self.reference.sample_period_s) < floor, 0.0, quant)
        new = np.where(est < floor, 0.0, est)
        a, b = np.maximum(new, floor), np.maximum(self.views_noise, floor)
        if np.any(np.abs(np.log(a / b)) > math.log(NOISE_REBUILD_FACTOR)):
            self.views_noise = new
        return self.views_noise

    def evidence(self) -> Evidence:
        noise = self._views_noise()
        return WindowEvidence.of(list(self.events), noise,
                                 self.views_quant if np.any(self.views_quant > 0) else None, self.record_mean)

    def add_event(self, event: LiveEvent) -> WatchUpdate | None:
        self.events.append(event)
        if len(self.events) < self.window_events:
            return None
        evidence = self.evidence()
        ev = self.reference.evaluate(evidence, where=False, clip_p=self.rule.event_clip_p)
        self.evaluations += 1
        exceeding, names = self.rule.exceeds(ev, self.dof)
        loo = []
        if exceeding and self.rule.robust and self.state.level == "OK":
            # a WARN must not hinge on one event: the window without each of its events must exceed too (~10 ms,
            # only for a window that exceeds; not needed to hold a WARN)
            results = self.reference.leave_one_out(evidence, ev, clip_p=self.rule.event_clip_p)
            loo = [(result_p_min(r, self.rule, self.dof), r.residual_over_noise) for r in results]
            exceeding = all(self.rule.result_exceeds(r, self.dof)[0] for r in results)
        if exceeding or self.state.level != "OK" or self.evaluations % self.window_events == 1:
            ev.where = self.reference.where(evidence, ev)       # ~3 ms: when it matters, and once per window
        changed = self.state.update(exceeding, event.entry_sample_index)
        self.last = WatchUpdate(event.entry_sample_index, self.state.level, changed, self.state.since, exceeding,
                                names, ev, p_min(ev, self.rule, self.dof), len(self.events),
                                self.rule.limits(ev, self.dof), loo)
        return self.last


def evaluate_recording(meas, reference: ModelReference, rule: AlarmRule | None = None,
                       window_events: int = DEFAULT_WINDOW_EVENTS) -> dict:
    """The model fit of a recording as the watch sees it at its end: one evaluation of its last ``window_events``
    onset events (fewer in a short recording, at least 3), the events and the noise floor taken as diagnose takes
    them (reference.evidence_from_measurement); WARN when the alarm rule's test exceeds (one evaluation: no
    persistence). -> {level, residual_over_noise, consistent, exceeding, width_m, phase, wavelet_level, events}."""
    rule = (rule or AlarmRule()).check()
    evidence = evidence_from_measurement(meas, reference, last_n=window_events, significant_noise=True)
    if evidence.n_events < 3:
        raise ValueError(f"{meas.source}: {evidence.n_events} complete onset events; the model fit needs >= 3")
    dof = reference.view_dof()
    ev = reference.evaluate(evidence, clip_p=rule.event_clip_p)
    exceeding, names = rule.exceeds(ev, dof)
    if exceeding and rule.robust:
        exceeding = all(rule.result_exceeds(r, dof)[0]
                        for r in reference.leave_one_out(evidence, ev, clip_p=rule.event_clip_p))
    return {"level": "WARN" if exceeding else "OK", "residual_over_noise": ev.result.residual_over_noise,
            "consistent": ev.consistent, "exceeding": names, "width_m": ev.width_m,
            "phase": (ev.where or {}).get("dominant_phase", ""),
            "wavelet_level": (ev.where or {}).get("dominant_level", ""), "events": evidence.n_events,
            "model": reference.model_label, "p_min": p_min(ev, rule, dof)}
