"""The typed result of ``diagnose`` and the hand-off to ``add-effect``: what was diagnosed against what, what the
verdict is, and what the next model version should hold.

One recording is followed through ``workbench/`` like this (docs/workbench.md, "Diagnose: the steps"):
``diagnose.diagnose`` runs the named steps (screen -> refine -> decide -> second effect -> confidence ->
verdict) and returns one :class:`Diagnosis`; ``Diagnosis.to_json()`` is the file users' scripts read
(``discovery``, ``ranked``, ``where``, ``fit_percent``, ... and ``conditions``, ``additions``, ``verdict``);
``add-effect`` reads only ``conditions`` and ``additions`` back (:func:`read_handoff`); the HTML report takes the
Diagnosis object itself (its comparison and the model mean after the update), not a private key of the JSON.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

# verdicts, in the JSON's "verdict"
CONSISTENT = "consistent"            # the model explains the recording within its noise band and tolerance
DISCOVERY = "discovery"              # a catalogue effect (or two) is missing; the model with it is consistent
MEASURAND = "width"                  # the model explains the recording at another backlash width: a measurement
PARTIAL = "partial"                  # an effect explains part of the residual; the rest is left (and where)
NOTHING_EXPLAINS = "nothing_explains"  # inconsistent, and nothing in the catalogue explains it
VERDICTS = (CONSISTENT, DISCOVERY, MEASURAND, PARTIAL, NOTHING_EXPLAINS)

# roles of an addition
ROLE_DISCOVERY = "discovery"
ROLE_SECOND = "second_effect"
ROLE_PARTIAL = "partial"             # taken by add-effect only with --accept-partial
ROLES = (ROLE_DISCOVERY, ROLE_SECOND, ROLE_PARTIAL)

# the quantity the monitor measures: never trained into the model as an effect (docs/workbench.md)
MEASURAND_EFFECTS = {"backlash_width_drift": ("change", "width_m")}


@dataclass(frozen=True)
class Conditions:
    """What a diagnosis was made against, complete enough for ``add-effect`` to rebuild that model: the model
    file, its effective content (nominal width/eta_k/n1, plant overrides including ``--set``, effects added,
    effect files), the overrides given on the command line, and what was recovered from the recording."""
    measurement: str
    model_label: str
    model_file: str | None
    nominal: dict                     # {"width_m", "eta_k", "n1"}: the conditions the model was run at
    overrides: dict                   # --set / --width-m / --eta-k / --n1 given to diagnose (flat keys)
    effect_files: list                # the user's plug-in effect files (absolute paths)
    model: dict                       # the effective model (WorkbenchModel.to_dict()): rebuilds it exactly
    seeds: list
    timing: dict                      # recovered from the recording, e.g. {"pulse_load.first_s": 0.031}
    events: int

    def to_json(self) -> dict:
        return {"measurement": self.measurement, "model": self.model_label, "model_file": self.model_file,
                "nominal": dict(self.nominal), "overrides": dict(self.overrides),
                "effect_files": [str(f) for f in self.effect_files], "effective_model": self.model,
                "seeds": list(self.seeds), "timing": dict(self.timing), "events": int(self.events)}

    @classmethod
    def from_json(cls, d: dict) -> "Conditions":
        return cls(d["measurement"], d.get("model", ""), d.get("model_file"), dict(d["nominal"]),
                   dict(d.get("overrides") or {}), list(d.get("effect_files") or []),
                   dict(d.get("effective_model") or {}), list(d.get("seeds") or []),
                   dict(d.get("timing") or {}), int(d.get("events", 0)))


@dataclass(frozen=True)
class Addition:
    """One effect the next model version should hold, with its fitted values: what add-effect writes."""
    effect: str                       # catalogue effect name
    candidate: str                    # the fitted candidate (e.g. accelerometer_gain[a2])
    parameters: dict
    uncertainty: dict
    role: str                         # ROLES
    evidence: str = "event average"   # or "raw a1 spectrum" (a torque ripple)

    def to_json(self) -> dict:
        return {"effect": self.effect, "candidate": self.candidate, "parameters": dict(self.parameters),
                "uncertainty": dict(self.uncertainty), "role": self.role, "evidence": self.evidence}

    @classmethod
    def from_json(cls, d: dict) -> "Addition":
        if d.get("role") not in ROLES:
            raise ValueError(f"addition {d.get('effect')!r}: role {d.get('role')!r}; allowed: {', '.join(ROLES)}")
        return cls(str(d["effect"]), str(d.get("candidate", d["effect"])), dict(d["parameters"]),
                   dict(d.get("uncertainty") or {}), d["role"], d.get("evidence", "event average"))


@dataclass(frozen=True)
class WidthMeasurement:
    """The backlash width the diagnosis measured (nominal + a fitted width drift, or the nominal when none was
    needed), with its uncertainty: the monitor's measurand, never a model effect."""
    width_m: float
    uncertainty_m: float
    nominal_width_m: float
    drift_found: bool                 # True: the recording is at another width than the model's nominal
    form_sigma_m: float = float("nan")   # the model-form tolerance in the uncertainty (tolerance.measurand_form_sigma)
    averaged_over: tuple = ()         # where the model does not hold: the models the width was averaged over
                                      # (model_average.py), each {"model", "width_m", "uncertainty_m", "weight"}

    def to_json(self) -> dict:
        return {"width_m": self.width_m, "uncertainty_m": self.uncertainty_m,
                "nominal_width_m": self.nominal_width_m, "differs_from_nominal": self.drift_found,
                "form_tolerance_m": self.form_sigma_m, "averaged_over": [dict(m) for m in self.averaged_over]}


@dataclass
class Diagnosis:
    """Everything ``diagnose`` concluded about one recording against one model version."""
    conditions: Conditions
    verdict: str
    message: str
    discovery: dict | None            # the winner in the JSON's candidate form (FitResult.to_json or a ripple)
    second_effect: dict | None
    partial: list                     # candidate dicts that explain only part (verdict PARTIAL), else []
    additions: list                   # [Addition]
    width: WidthMeasurement
    ranked: list
    views: dict                       # consistency per view before / after (consistency.ConsistencyResult.to_json)
    report: dict = field(default_factory=dict)    # the remaining JSON fields (where, fit_percent, ...)
    # not in the JSON: the data the HTML report draws
    comparison: Any = None
    model_mean_after: np.ndarray | None = None

    @property
    def named(self) -> list:
        """Catalogue effects the diagnosis names: the discovery, its second effect and their twins."""
        out = []
        for d in (self.discovery, self.second_effect):
            if d:
                out += [d["effect"]] + [c.split("[")[0] for c in d.get("indistinguishable_from", [])]
        return list(dict.fromkeys(out))

    def to_json(self) -> dict:
        disc = self.discovery
        out = {"measurement": self.conditions.measurement, "model": self.conditions.model_label,
               "model_file": self.conditions.model_file, "verdict": self.verdict,
               "conditions": self.conditions.to_json(),
               "seeds": list(self.conditions.seeds), "events": self.conditions.events,
               "discovery": None if disc is None else disc["effect"],
               "discovery_candidate": None if disc is None else disc["candidate"],
               "discovery_parameters": disc,
               "indistinguishable": [] if disc is None else [
                   e.split("[")[0] for e in [disc["candidate"]] + list(disc.get("indistinguishable_from", []))],
               "second_effect": self.second_effect,
               "partial_explanation": self.partial or None,
               "additions": [a.to_json() for a in self.additions],
               "measured_width": self.width.to_json(),
               "message": self.message, "ranked": self.ranked, "consistency": self.views}
        out.update(self.report)
        return out


def read_handoff(diag: dict, source: str) -> tuple[Conditions | None, list, str | None]:
    """(conditions, additions, verdict) of a diagnosis JSON for add-effect. A JSON written before conditions
    and additions were recorded gives (None, additions re-derived from its discovery fields, None)."""
    if not isinstance(diag, dict) or "discovery" not in diag:
        raise ValueError(f"{source} is not a diagnose --json file (no 'discovery')")
    if "additions" in diag and "conditions" in diag:
        return (Conditions.from_json(diag["conditions"]), [Addition.from_json(a) for a in diag["additions"]],
                diag.get("verdict"))
    # an older diagnosis: its discovery and second effect (and a confident ripple) as the additions
    adds = []
    spectral = diag.get("spectral_discovery")
    spectral = spectral if isinstance(spectral, dict) and spectral.get("confident") else None
    for role, entry in ((ROLE_DISCOVERY, diag.get("discovery_parameters")), (ROLE_SECOND, diag.get("second_effect")),
                        (ROLE_SECOND, spectral)):
        if entry and all(a.effect != entry["effect"] for a in adds):
            adds.append(Addition(entry["effect"], entry.get("candidate", entry["effect"]), dict(entry["parameters"]),
                                 dict(entry.get("uncertainty") or {}), role))
    return None, adds, None
