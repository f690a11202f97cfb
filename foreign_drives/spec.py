"""Typed recording specs and their truth; JSON round trip (the manifest).

A :class:`RecordingSpec` says everything one recording is made from: label, kind, the drive's NOMINAL width,
eta_k and n1 (what its user would give the workbench), the effects (form + parameters), the sensor nuisance
(not an effect), the seed, duration, chunk size, namespace and the pulse train's phase. Its :class:`Truth`
says what the recording really is: the true width (the measurand: a width drift moves it), and per effect the
catalogue family a user should be told about (None: outside the catalogue) with the catalogue-equivalent
parameters where they exist.
"""
from __future__ import annotations

import json
import math
import re
from dataclasses import asdict, dataclass, field

from . import constants as C
from . import forms as F
from .noise import SEGMENT_S

KINDS = ("clean", "one", "two", "outside")
_NAMESPACE_RE = re.compile(r"^(/?[A-Za-z][A-Za-z0-9_]*)*/?$")
_LABEL_RE = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.+-]*$")


@dataclass(frozen=True)
class EffectSpec:
    """One effect of a recording: a form of :data:`forms.FORMS` and its parameters."""
    form: str
    parameters: dict = field(default_factory=dict)

    def checked(self) -> "EffectSpec":
        return EffectSpec(self.form, F.check_parameters(F.get(self.form), dict(self.parameters)))


@dataclass(frozen=True)
class SensorNuisance:
    """What a real recording chain adds that is NOT an effect: white noise after the sensor [m/s^2 rms], the
    ADC's least significant bit [m/s^2] (0 = none), the shaft encoders' counts per revolution (0 = exact
    angles) and the encoders' zero offset in the angle difference [rad]."""
    a1_noise_rms_m_s2: float = 0.0
    a2_noise_rms_m_s2: float = 0.0
    a1_lsb_m_s2: float = 0.0
    a2_lsb_m_s2: float = 0.0
    encoder_counts_per_rev: int = 0
    angle_offset_rad: float = 0.0

    def check(self) -> None:
        for k, v in asdict(self).items():
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"sensor nuisance {k} = {v!r} is not a finite number")
            if k != "angle_offset_rad" and v < 0:
                raise ValueError(f"sensor nuisance {k} = {v!r}; allowed: >= 0")
        if float(self.encoder_counts_per_rev) != int(self.encoder_counts_per_rev):
            raise ValueError(f"sensor nuisance encoder_counts_per_rev = {self.encoder_counts_per_rev!r}; allowed: a "
                             "whole number (0 = exact angles)")

    @property
    def any(self) -> bool:
        return any(v != 0 for v in asdict(self).values())


@dataclass(frozen=True)
class EffectTruth:
    form: str
    family: str | None                 # the catalogue family a user should be told about; None: outside
    parameters: dict
    equivalent: dict | None            # catalogue-equivalent parameters of ``family`` where they exist
    also_accepted: dict                # {other family: equivalent or None}: explain it as well on this drive
    description: str
    note: str = ""
    # outside mechanisms (foreign_drives.outside): the balance the term acts in (outside.BALANCES), the drive
    # states it reads (outside.STATES), its law with the values, a plug-in's source with the exact law where a user
    # can write one, and the half it belongs to (dev | sealed | dev2 | sealed2 | ... | dev13 | sealed13)
    balance: str | None = None
    depends_on: tuple = ()
    law: str = ""
    plugin: str | None = None
    half: str = ""


@dataclass(frozen=True)
class Truth:
    true_width_m: float                # the measurand: nominal width + a width drift
    true_eta_k: float
    true_n1: float
    nominal: dict                      # {width_m, eta_k, n1}: what the drive's user believes
    families: tuple                    # catalogue families a user should be told about (in effect order)
    outside: tuple                     # forms outside the catalogue (nothing in it explains them fully)
    effects: tuple                     # EffectTruth per effect
    width_is_measurand: bool           # a width drift: report it as the measurement, never train it in

    def to_json(self) -> dict:
        d = asdict(self)
        d["families"], d["outside"] = list(self.families), list(self.outside)
        d["effects"] = [asdict(e) for e in self.effects]
        return d


@dataclass(frozen=True)
class RecordingSpec:
    label: str
    kind: str                          # clean | one | two | outside
    width_m: float                     # nominal (the drive's model); the truth may differ (drift_width)
    eta_k: float
    n1: float
    effects: tuple = ()                # EffectSpec
    sensor: SensorNuisance = SensorNuisance()
    seed: int = 0
    duration_s: float = 4.0            # s, <= 120 (the whole recording is held in memory: ~100 MB per minute)
    chunk_samples: int = 1000          # samples per SignalChunk message in a bag
    namespace: str = ""                # topics <namespace>/plant/<signal>
    drive_name: str = "drive"          # header.frame_id
    pulse_first_s: float = C.PULSE_FIRST_S   # first pulse after sample 0 (the recording's phase)
    start_time_ns: int = 1_700_000_000_000_000_000
    noise: bool = True                 # the two disturbance generators (SPEC section 3)
    run_in_s: float = 2.0

    def __post_init__(self):
        object.__setattr__(self, "effects", tuple(e if isinstance(e, EffectSpec) else EffectSpec(**e)
                                                  for e in self.effects))
        if isinstance(self.sensor, dict):
            object.__setattr__(self, "sensor", SensorNuisance(**self.sensor))

    # ------------------------------------------------------------------ checks
    def check(self) -> "RecordingSpec":
        """Raise ValueError (one line naming the problem and what is allowed) for a spec that cannot be made."""
        if not isinstance(self.label, str) or not _LABEL_RE.match(self.label):
            raise ValueError(f"recording label {self.label!r}; allowed: letters, digits and _ . + - (a file name)")
        if self.kind not in KINDS:
            raise ValueError(f"recording {self.label}: kind {self.kind!r}; allowed: {', '.join(KINDS)}")
        for name, (lo, hi) in (("width_m", (1e-4, 0.05)), ("eta_k", (1e-4, 1.0)), ("n1", (0.3, 1.5)),
                               ("duration_s", (0.4, 120.0)), ("run_in_s", (0.25, 60.0))):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not lo <= v <= hi:
                raise ValueError(f"recording {self.label}: {name} = {v!r}; allowed: {lo:g}..{hi:g}")
        for name, grid in (("duration_s", SEGMENT_S), ("pulse_first_s", SEGMENT_S), ("run_in_s", C.PULSE_PERIOD_S)):
            v = getattr(self, name)
            if abs(v / grid - round(v / grid)) > 1e-6:
                raise ValueError(f"recording {self.label}: {name} = {v!r} s is not a multiple of {grid:g} s")
        if not 0.0 <= self.pulse_first_s < C.PULSE_PERIOD_S:
            raise ValueError(f"recording {self.label}: pulse_first_s = {self.pulse_first_s!r}; allowed: 0 <= t < "
                             f"{C.PULSE_PERIOD_S} s")
        if isinstance(self.seed, bool) or not isinstance(self.seed, int) or self.seed < 0:
            raise ValueError(f"recording {self.label}: seed = {self.seed!r}; allowed: an integer >= 0")
        if isinstance(self.chunk_samples, bool) or not isinstance(self.chunk_samples, int) or self.chunk_samples < 1:
            raise ValueError(f"recording {self.label}: chunk_samples = {self.chunk_samples!r}; allowed: an "
                             "integer >= 1")
        if not isinstance(self.namespace, str) or not _NAMESPACE_RE.match(self.namespace):
            raise ValueError(f"recording {self.label}: namespace {self.namespace!r}; allowed: ROS name segments "
                             "(letters, digits, _; each starting with a letter) separated by /")
        self.sensor.check()
        checked = [e.checked() for e in self.effects]
        fams = [F.get(e.form).family for e in checked]
        n_in = sum(f is not None for f in fams)
        n_out = len(fams) - n_in
        want = {"clean": n_in == 0 and n_out == 0, "one": n_in == 1 and n_out == 0,
                "two": n_in == 2 and n_out == 0, "outside": n_out >= 1}[self.kind]
        if not want:
            raise ValueError(f"recording {self.label}: kind {self.kind!r} with {n_in} catalogue-family effect(s) and "
                             f"{n_out} outside one(s); allowed: clean = none, one = 1, two = 2 catalogue-family "
                             "effects, outside = at least one effect outside the catalogue")
        return self

    # ------------------------------------------------------------------ truth
    def truth(self) -> Truth:
        self.check()
        width, eta, n1 = self.width_m, self.eta_k, self.n1
        effects = []
        for e in (x.checked() for x in self.effects):
            form = F.get(e.form)
            p = e.parameters
            if form.name == "drift_width":
                width += p["change"]
            elif form.name == "drift_eta_k":
                eta *= 1.0 + p["relative_change"]
            elif form.name == "drift_n1":
                n1 += p["change"]
            outside = {}
            if getattr(form, "balance", None):
                outside = dict(balance=form.balance, depends_on=tuple(form.depends_on), law=form.law(p),
                               plugin=form.plugin(p), half=form.half)
            effects.append(EffectTruth(form=form.name, family=form.family, parameters=dict(p),
                                       equivalent=form.equivalent(p) if form.family else None,
                                       also_accepted=form.also(p) if form.family else {},
                                       description=form.description, note=form.note, **outside))
        return Truth(true_width_m=width, true_eta_k=eta, true_n1=n1,
                     nominal={"width_m": self.width_m, "eta_k": self.eta_k, "n1": self.n1},
                     families=tuple(e.family for e in effects if e.family),
                     outside=tuple(e.form for e in effects if e.family is None),
                     effects=tuple(effects),
                     width_is_measurand=any(e.form == "drift_width" for e in effects))

    # ------------------------------------------------------------------ JSON
    def to_json(self) -> dict:
        d = asdict(self)
        d["effects"] = [{"form": e.form, "parameters": dict(e.parameters)} for e in self.effects]
        return d

    @classmethod
    def from_json(cls, d: dict) -> "RecordingSpec":
        known = set(cls.__dataclass_fields__)
        unknown = [k for k in d if k not in known]
        if unknown:
            raise ValueError(f"recording spec: unknown field {unknown[0]!r}; allowed: {', '.join(sorted(known))}")
        return cls(**d).check()


def manifest(specs, files: dict | None = None) -> dict:
    """The manifest of a written suite: every spec, its truth, and its file (label -> path)."""
    files = files or {}
    return {"foreign_drives_manifest": 1,
            "recordings": [{"spec": s.to_json(), "truth": s.truth().to_json(), "file": files.get(s.label)}
                           for s in specs]}


def write_manifest(path, specs, files: dict | None = None) -> None:
    from pathlib import Path
    p = Path(path)
    tmp = p.with_name(p.name + ".partial")
    tmp.write_text(json.dumps(manifest(specs, files), indent=1) + "\n")
    tmp.replace(p)


def read_manifest(path) -> list:
    """[(RecordingSpec, truth dict, file)] of a manifest written by :func:`write_manifest`."""
    d = json.loads(open(path).read())
    if d.get("foreign_drives_manifest") != 1:
        raise ValueError(f"{path}: not a foreign_drives manifest (no foreign_drives_manifest: 1)")
    return [(RecordingSpec.from_json(r["spec"]), r["truth"], r.get("file")) for r in d["recordings"]]
