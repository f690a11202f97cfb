"""A diagnosis in the drive's own terms, for the console and the HTML report: the measured width with its
uncertainty, each fitted parameter as the drive quantity it changes ("n1: 0.89 → 0.9104 ± 0.0004"), each effect's
plain description, the near-ties with the measurement that would separate them, and one line each on what ΔIC and
T² mean. Reads a diagnosis JSON (diagnosis.Diagnosis.to_json) and the model it was made against; plain text."""
from __future__ import annotations

import math

from .decisions import identical_to
from .diagnosis_result import MEASURAND_EFFECTS

# the quantity a parameter drift (plant/effects.DRIFTS) moves: its name on the drive, its unit and the scale from
# the config's SI value to that unit
DRIFT_TARGETS = {
    "width_m": ("backlash width", "mm", 1e3),
    "eta_k": ("absorber consistency eta_k", "Pa·s^n", 1.0),
    "n1": ("n1", "", 1.0),
    "spring.stiffness_N_per_m": ("spring stiffness k", "N/m", 1.0),
    "mass_kg": ("mass m", "kg", 1.0),
    "wheel_inertia_kgm2": ("wheel inertia J2", "kg·m²", 1.0),
    "working_resistance.force_N": ("working resistance F0", "N", 1.0),
    "pulse_load.amplitude_pu": ("pulse load amplitude", "p.u.", 1.0),
    "rotor_resistance_pu": ("rotor resistance r_r", "p.u.", 1.0),
    "supply_voltage_scale": ("supply voltage", "× nominal", 1.0),
}
# units as a drive engineer writes them; "-" is a ratio (no unit), shown as such
UNIT_TEXT = {"-": "", "N*m": "N·m", "N*m*s/rad": "N·m·s/rad", "N*m*s^2/rad^2": "N·m·s²/rad²", "m/s^2": "m/s²",
             "rad/(N*m)": "rad/(N·m)", "N*s/m": "N·s/m"}
NEAR_TIE_IC = 10.0           # decisions.DELTA_IC_DECISIVE: a candidate closer than this to the winner is a near-tie

DELTA_IC_LINE = ("ΔIC: the change of the information criterion (BIC on the onset events, the independent units) when "
                 "the effect is added; negative = better, below -2 positive evidence, below -10 decisive; a "
                 "candidate 'n IC behind' the winner fits the events that much worse")
T2_LINE = ("T²: the residual's squared length in the model's whitened views, in units of its own noise ensemble; "
           "above its 1 % limit the model does not explain the recording (p < 0.01)")
UNITLESS_LINE = "n1, gains and relative changes are ratios: they have no unit"


def significant_digits(value: float, uncertainty: float) -> tuple[str, str]:
    """(value, uncertainty) as text, the uncertainty to 1 significant digit (2 when it starts with 1 or 2), the
    value to the same decimal place."""
    if not (math.isfinite(uncertainty) and uncertainty > 0):
        return f"{value:.4g}", "?"
    exp = math.floor(math.log10(uncertainty))
    lead = uncertainty / 10 ** exp
    digits = 2 if lead < 3 else 1
    decimals = max(0, -(exp - digits + 1))
    if decimals == 0:
        r = round(uncertainty, -(exp - digits + 1))
        return f"{round(value, -(exp - digits + 1)):.0f}", f"{r:.0f}"
    return f"{value:.{decimals}f}", f"{uncertainty:.{decimals}f}"


def _unit(u: str) -> str:
    return UNIT_TEXT.get(u, u)


def target_nominal(model, target: str) -> float | None:
    """The model's value of a drift's target (the config's SI unit), None when the model has no such value."""
    if target in ("width_m", "eta_k", "n1"):
        return float(model.nominal[target])
    try:
        cfg = model.plant_config()
        if target == "mass_kg":
            return float(cfg.load.mass_kg)
        if target == "wheel_inertia_kgm2":
            return float(cfg.load.wheel_inertia_kgm2)
        if target == "rotor_resistance_pu":
            return float(cfg.motor.r_r_pu)
        if target == "supply_voltage_scale":
            return 1.0
        section, key = target.split(".", 1)
        try:
            return float(cfg.effect_parameter(section, key))
        except (KeyError, ValueError, AttributeError):
            return float(getattr(getattr(cfg, section), key))
    except (AttributeError, ValueError, KeyError, TypeError):
        return None


def _effect_class(model, name: str):
    cat = getattr(model, "catalogue", None)
    try:
        return cat[name] if cat is not None and name in cat else None
    except TypeError:
        return None


def parameter_lines(entry: dict, model) -> list[str]:
    """Each fitted parameter of a candidate entry (FitResult.to_json) as "quantity: nominal → value ± uncertainty
    unit": a drift as the drive quantity it moves (its relative change applied to the model's value), any other
    parameter by its description, from the model's value."""
    name = entry["effect"]
    cls = _effect_class(model, name)
    params = dict(entry.get("parameters") or {})
    unc = dict(entry.get("uncertainty") or {})
    nominal = dict(entry.get("nominal") or {})
    units = dict(entry.get("units") or {})
    target = getattr(cls, "target", None) if cls is not None else None
    out = []
    if target is not None and target in DRIFT_TARGETS and len(params) >= 1:
        pname = next(iter(params))
        base = target_nominal(model, target)
        if base is not None:
            label, unit, scale = DRIFT_TARGETS[target]
            change, u = float(params[pname]), float(unc.get(pname, float("nan")))
            if getattr(cls, "relative", False):
                value, u_value = base * (1.0 + change), abs(base) * u
            else:
                value, u_value = base + change, u
            v, du = significant_digits(value * scale, u_value * scale)
            out.append(f"{label}: {base * scale:.4g} → {v} ± {du}{' ' + unit if unit else ''}")
            return out
    described = {p.name: p for p in getattr(cls, "parameters", ())} if cls is not None else {}
    for pname, value in params.items():
        if pname not in unc:
            continue          # a fixed form parameter (e.g. the low-pass' sections)
        p = described.get(pname)
        label = f"{p.description} ({pname})" if p is not None and p.description else pname
        unit = _unit(units.get(pname, getattr(p, "unit", "")) or "")
        v, du = significant_digits(float(value), float(unc[pname]))
        out.append(f"{label}: {float(nominal.get(pname, 0.0)):.4g} → {v} ± {du}{' ' + unit if unit else ''}")
    return out


def effect_text(entry: dict, model) -> str:
    """An effect in one line, as diagnose's verdict message gives it: its candidate name, its parameters in drive
    terms (:func:`parameter_lines`, the same lines the console and the report show) and its plain description:
    "absorber_flow_index_drift — n1: 0.89 → 0.9104 ± 0.0004 (drift of the absorber flow index n1 from nominal:
    value + change)"."""
    text = entry.get("candidate") or entry["effect"]
    values = parameter_lines(entry, model)
    if values:
        text += " — " + ", ".join(values)
    if entry.get("description"):
        text += f" ({entry['description']})"
    return text


def width_line(diag: dict) -> str:
    mw = diag["measured_width"]
    v, du = significant_digits(mw["width_m"] * 1e3, mw["uncertainty_m"] * 1e3)
    state = ("differs from the model's nominal" if mw.get("differs_from_nominal")
             else "the model's nominal: no other width needed")
    return f"backlash width {v} ± {du} mm (model nominal {mw['nominal_width_m'] * 1e3:.2f} mm; {state})"


def near_ties(diag: dict) -> list[dict]:
    """Fitted candidates that explain about as much as the discovery and trail it by less than NEAR_TIE_IC, with
    what separates them (the diagnosis' 'near_ties', else read off its ranking)."""
    if diag.get("near_ties") is not None:
        return list(diag["near_ties"])
    return []


def explained_percent(fraction: float) -> str:
    """The share of the residual's excess over the noise an effect removes (fitting.Problem.explained_share), as the
    messages show it: a fit that also takes part of the noise scores above 1 (measured: 1.20 on a clean drive, a width
    fitted into the noise); shown as 100 %, the JSON keeps the value."""
    return f"{min(float(fraction), 1.0):.0%}"


def effect_lines(entry: dict, model, role: str = "") -> list[str]:
    """An effect in the drive's terms: its name and role, what it is, its values, how much it explains."""
    head = entry["effect"] + (f" ({role})" if role else "")
    lines = [head + ": " + (entry.get("description") or "")]
    lines += ["  " + p for p in parameter_lines(entry, model)]
    if entry.get("delta_ic") is not None:
        lines.append(f"  explains {explained_percent(entry['explained_fraction'])} of the residual, ΔIC {entry['delta_ic']:.1f}")
    return lines


def summary_lines(diag: dict, model) -> list[str]:
    """The console's summary of a diagnosis: verdict, width, the effects in drive terms, near-ties, legend."""
    lines = [f"verdict: {diag['verdict'].replace('_', ' ')}", width_line(diag)]
    disc = diag.get("discovery_parameters")
    if disc and disc.get("effect") and disc["effect"] not in MEASURAND_EFFECTS and "delta_ic" in disc:
        lines += effect_lines(disc, model, "missing effect")
        twins = list(disc.get("indistinguishable_from", []))
        if twins:
            lines.append("  not distinguishable from this recording from (each explains it as well):")
            by_candidate = {r.get("candidate", r["effect"]): r for r in diag.get("ranked") or []}
            for t in twins:
                r = by_candidate.get(t)
                if r is None or r.get("uncertainty") is None:
                    lines.append(f"    {t.split('[')[0]}")
                    continue
                lines.append(f"    {r['effect']}: {r.get('description') or ''}")
                lines += ["      " + p for p in parameter_lines(r, model)]
            seps = [r["separating_measurement"] if not r["separating_measurement"].startswith("none")
                    else f"nothing separates {r['effect']} from "
                         + (" and ".join(identical_to(r["effect"])) or "the candidate it duplicates")
                         + ": the same term of the model"
                    for r in diag.get("ranked") or []
                    if r.get("candidate", r["effect"]) in twins and r.get("separating_measurement")]
            for sep in dict.fromkeys(seps):
                lines.append(f"  to tell them apart: {sep}")
    second = diag.get("second_effect")
    if second and second.get("effect") not in MEASURAND_EFFECTS and "delta_ic" in second:
        lines += effect_lines(second, model, "second effect")
    for p in diag.get("partial_explanation") or []:
        if p.get("effect") not in MEASURAND_EFFECTS:
            lines += effect_lines(p, model, "explains part")
    for t in near_ties(diag):
        lines.append(f"near-tie: {t['effect']} also explains {explained_percent(t['explained_fraction'])}, {t['ic_behind']:.1f} IC "
                     f"behind ({t.get('description', '')}); to tell them apart: {t['separating_measurement']}")
    lines += [DELTA_IC_LINE, T2_LINE, UNITLESS_LINE]
    return lines
