"""Figures (PNG) and the one-page HTML report of a comparison or a diagnosis."""
from __future__ import annotations

import html
import json
import os
import time
from pathlib import Path
import datetime

import numpy as np

from . import analysis, consistency, spectral, tolerance, drive_terms
from .events import PRE_SAMPLES, SEGMENT_SIGNALS, denoise
from backlash_monitor import __version__

UNITS = {"a1": "m/s²", "a2": "m/s²"}


def diagnosis_report(run, up, verdict, ripple_fit, spec, overall_before: float, identifiability: dict) -> dict:
    """The report part of a diagnosis' JSON (diagnosis.Diagnosis.report): the consistency views, spectral shape,
    noise floor, record mean, where the residual sits, fit %, whiteness, input correlation, spectral peaks.
    ``run``, ``up``, ``verdict``: diagnose's Run, Update and Verdict; ``spec``: analysis.spectra of the comparison;
    ``identifiability``: per candidate, how far its fit range moves the evidence."""
    comp, p = run.comp, run.problem
    discovery, partial = verdict.discovery, verdict.partial
    wb = analysis.where(comp)
    where_after = (analysis.where(comp, up.after_mean, up.after_raw)
                   if discovery is not None and up.after_raw is not None else None)
    fit_before = analysis.fit_percent(comp.target, comp.model_mean)
    fit_after = analysis.fit_percent(comp.target, verdict.after_mean)
    band = analysis.noise_band_fit_percent(comp)
    ratio_before = analysis.residual_ratio(comp)
    ratio_after = analysis.residual_ratio(comp, verdict.after_mean)
    gates = run.before.views
    report = {
        "partial_checks": up.checks if partial else None,
        "pairs_tried": up.pairs_tried,
        "pair_alternatives": up.pair_alternatives if verdict.second is not None and discovery is not None else [],
        "model_inconsistent": bool(run.inconsistent),
        "subspace": {"dimension": int(p.views.blocks[0][1].stop), "T2": gates["event_average"].t2,
                     "T2_limit_p01": gates["event_average"].limit,
                     "residual_over_noise": float(np.sqrt(gates["event_average"].t2_without_tolerance
                                                          * consistency.noise_scale(p.n_events, p.n_seeds)
                                                          / max(p.views.blocks[0][1].stop, 1))),
                     "blocks": {n: {"dimension": v.dimension, "T2": v.t2, "T2_limit_p01": v.limit,
                                    "T2_without_tolerance": v.t2_without_tolerance}
                                for n, v in gates.items() if n != consistency.OUTSIDE}},
        "spectral_shape": {"bands_hz": list(spectral.BAND_EDGES_HZ),
                           "measured_minus_model": dict(zip(
                               [f"{s}_{lo:.0f}-{hi:.0f}_vs_{hi:.0f}-{hh:.0f}_Hz" for s in SEGMENT_SIGNALS
                                for lo, hi, hh in zip(spectral.BAND_EDGES_HZ[:-2], spectral.BAND_EDGES_HZ[1:-1],
                                                      spectral.BAND_EDGES_HZ[2:])],
                               map(float, (p.target_vec - run.base_pred)[p.spectral_slice] / p.ws))),
                           "units": "ln(power ratio of adjacent bands), mean over the events"},
        "sensor_noise_floor": {"rms_m_s2": dict(zip(SEGMENT_SIGNALS, map(float, np.sqrt(
                                   comp.noise_psd * 0.5 / comp.meas.sample_period_s)))),
                               "psd_m2_s4_per_hz": dict(zip(SEGMENT_SIGNALS, map(float, comp.noise_psd))),
                               "quantisation_step_m_s2": dict(zip(SEGMENT_SIGNALS, map(float, (
                                   comp.quant_step if comp.quant_step is not None else np.zeros(2))))),
                               "note": "the white noise the recording's sensor chain adds (read off above "
                                       f"{analysis.NOISE_BAND_HZ[0] / 1e3:.0f} kHz), and its ADC's step when its "
                                       "samples lie on a grid (the model's events are quantised at it); a nuisance "
                                       "the spectral views allow for, not an effect"},
        "record_mean": {"measured": dict(zip(comp.dc_names, map(float, p.events.dc.mean(axis=0)))),
                        "model": dict(zip(comp.dc_names, map(float, comp.ensemble.dc_mean(0)))),
                        "units": "a1, a2: m/s^2; omega1: rad/s; the mean over the events of each one's pulse-period "
                                 "mean"},
        "where": wb,
        "where_after": where_after,
        "fit_percent": {"before": dict(zip(SEGMENT_SIGNALS, map(float, fit_before))),
                        "after": dict(zip(SEGMENT_SIGNALS, map(float, fit_after))),
                        "noise_band_median": dict(zip(SEGMENT_SIGNALS, map(float, np.median(band, axis=0))))},
        "residual_over_noise_floor": {"before": dict(zip(SEGMENT_SIGNALS, map(float, ratio_before))),
                                      "after": dict(zip(SEGMENT_SIGNALS, map(float, ratio_after))),
                                      "overall_before": overall_before,
                                      "overall_after": float(np.sqrt(np.mean(ratio_after ** 2)))},
        "identifiability": identifiability,
        "whiteness": analysis.whiteness(comp),
        "input_correlation": analysis.input_correlation(comp),
        "spectral_peaks": analysis.spectral_peaks(spec),
        "spectral_discovery": ripple_fit,
        "tolerance": {k: v for k, v in tolerance.NOMINAL_SIGMA.items()},
        "information_criterion": "BIC on the events: IC = E*sum_d ln(mean_e z_ed^2) + k*ln(E), E onset events, z_ed "
                                 "event e's residual in the whitened views' direction d",
        "simulated_parameter_sets": p.n_sets_simulated + 1,
        "seconds": time.perf_counter() - run.t0,
    }
    report["not_identifiable"] = [n for n, v in report["identifiability"].items() if not v["identifiable"]]
    return report


def _plt():
    # deferred: matplotlib.pyplot costs ~450 ms at start-up (python -X importtime, 29 Nov)
    import matplotlib
    matplotlib.use("Agg")
    # deferred: as matplotlib above
    import matplotlib.pyplot as plt
    return plt


def _save(plt, fig, path, title: str = "") -> Path:
    """Title, lay out, write the PNG and free the figure."""
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return Path(path)


def plot_event_average(comp, path, after_mean=None, title="") -> Path:
    """Measured event average vs the model's ensemble mean with its band (min..max of the seeds)."""
    plt = _plt()
    t_ms = (np.arange(comp.target.shape[-1]) - PRE_SAMPLES) * comp.meas.sample_period_s * 1e3
    seeds = comp.ensemble.seed_denoised()
    fig, axes = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for i, s in enumerate(SEGMENT_SIGNALS):
        ax = axes[i]
        ax.fill_between(t_ms, seeds[:, i].min(axis=0), seeds[:, i].max(axis=0), color="tab:blue", alpha=0.25,
                        label="model ensemble (seed averages, min..max)")
        ax.plot(t_ms, comp.model_mean[i], color="tab:blue", lw=1, label="model mean")
        if after_mean is not None:
            ax.plot(t_ms, after_mean[i], color="tab:green", lw=1, label="model with the effect")
        ax.plot(t_ms, comp.target[i], color="k", lw=1, label="measurement (event average)")
        ax.axvline(0, color="grey", lw=0.5)
        ax.set_ylabel(f"{s} [{UNITS[s]}]")
        if i == 0:
            ax.legend(fontsize=7, loc="upper right")
    axes[-1].set_xlabel("time from the onset entry [ms]")
    return _save(plt, fig, path, title or "event-averaged, denoised onset segment")


def plot_spectra(comp, spec, path) -> Path:
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, s in zip(axes, SEGMENT_SIGNALS):
        d = spec[s]
        f = d["f"][1:]
        ax.fill_between(f, d["ensemble"][:, 1:].min(axis=0), d["ensemble"][:, 1:].max(axis=0), color="tab:blue",
                        alpha=0.3, label="model ensemble")
        ax.loglog(f, d["measured"][1:], color="k", lw=0.7, label="measurement (raw)")
        ax.set_xlabel("frequency [Hz]")
        ax.set_ylabel(f"PSD of {s}")
        ax.legend(fontsize=7)
    return _save(plt, fig, path, "whole-record raw spectra (Welch)")


def plot_where(where_before, where_after, path) -> Path:
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    for ax, key, names in ((axes[0], "per_phase", analysis.PHASES), (axes[1], "per_level", analysis.LEVELS)):
        x = np.arange(len(names))
        ax.bar(x - 0.2, [where_before[key][n]["over_noise"] for n in names], 0.4, label="before")
        if where_after is not None:
            ax.bar(x + 0.2, [where_after[key][n]["over_noise"] for n in names], 0.4, label="after")
        ax.axhline(1.0, color="k", lw=0.8, ls="--", label="noise band")
        ax.set_xticks(x)
        ax.set_xticklabels([n.replace("_", "\n") for n in names], fontsize=8)
        ax.set_yscale("log")
        ax.set_ylabel("residual energy / noise energy")
        ax.legend(fontsize=7)
    axes[0].set_title("per phase of the window")
    axes[1].set_title("per sym5 wavelet level (raw)")
    return _save(plt, fig, path)


def plot_ranked(ranked, path) -> Path:
    """The candidates' ΔIC (fitted ones) and explained share (all), one row per candidate: the figure grows with
    the rows so that their labels never overlap."""
    plt = _plt()
    fitted = [r for r in ranked if r.get("delta_ic") is not None]
    screened = [r for r in ranked if r.get("delta_ic") is None]
    allr = fitted + screened
    height = max(3.0, 0.24 * len(allr) + 1.4)
    fig, axes = plt.subplots(1, 2, figsize=(11, height), gridspec_kw={"width_ratios": (1, 1)})
    names = [r.get("candidate", r["effect"]) for r in allr]
    y = np.arange(len(allr))
    axes[0].barh(y[:len(fitted)], [r["delta_ic"] for r in fitted], color="tab:purple")
    axes[0].axvline(-2, color="k", ls="--", lw=0.8)
    axes[0].set_xlabel("ΔIC (BIC on the events; < -2 positive evidence)")
    axes[1].barh(y, [r["explained_fraction"] for r in allr],
                 color=["tab:purple"] * len(fitted) + ["tab:gray"] * len(screened))
    axes[1].set_xlabel("share of the residual explained (purple: fitted, grey: screened)")
    axes[1].set_xlim(min(0, min((r["explained_fraction"] for r in allr), default=0)), 1)
    for ax in axes:
        ax.set_yticks(y)
        ax.set_ylim(len(allr) - 0.5, -0.5)
        ax.tick_params(axis="y", labelsize=8)
    axes[0].set_yticklabels(names)
    axes[1].set_yticklabels([])
    return _save(plt, fig, path)


def event_residuals(comp, model_mean=None) -> tuple[np.ndarray, list]:
    """Per onset event: the rms of its denoised segment minus the model's mean, in noise floors, per signal;
    (E, 2) for the recording and, per seed of the model's own ensemble, the same (E_k, 2) (the band a correct
    model's events fill)."""
    m = comp.model_mean if model_mean is None else model_mean
    w = comp.weights[None, :, None]

    def per_event(raw):
        return np.sqrt(np.mean(((denoise(raw) - m[None]) * w) ** 2, axis=-1))
    return per_event(comp.events.raw), [per_event(p) for p in comp.ensemble.per_event if len(p)]


def plot_event_residuals(comp, path, after_mean=None) -> Path:
    """Each onset event's residual against the model (rms over its segment, in noise floors), per signal, with the
    model's own events' range: an effect that is missing shows in every event, a single bad event stands alone."""
    plt = _plt()
    meas, band = event_residuals(comp)
    after = event_residuals(comp, after_mean)[0] if after_mean is not None else None
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharey=False)
    k = np.arange(1, len(meas) + 1)
    for i, s in enumerate(SEGMENT_SIGNALS):
        ax = axes[i]
        if band:
            vals = np.concatenate([b[:, i] for b in band])
            ax.axhspan(vals.min(), vals.max(), color="tab:blue", alpha=0.2, label="model's own events (min..max)")
        ax.plot(k, meas[:, i], "o-", color="k", ms=4, lw=0.8, label="before")
        if after is not None:
            ax.plot(k, after[:, i], "s-", color="tab:green", ms=4, lw=0.8, label="with the effect")
        ax.set_xlabel("onset event")
        ax.set_ylabel(f"{s}: rms residual / noise floor")
        ax.set_title(s)
        ax.legend(fontsize=7)
    return _save(plt, fig, path, "per-event residual (each event against the model's mean)")


def _table(rows, header) -> str:
    out = ["<table><tr>" + "".join(f"<th>{html.escape(h)}</th>" for h in header) + "</tr>"]
    for r in rows:
        out.append("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>")
    return "\n".join(out + ["</table>"])


def _header(result: dict, comp) -> list[str]:
    """The report's header: date, tool version, drive, model, nominal conditions and units."""
    cond = result.get("conditions") or {}
    nom = cond.get("nominal") or {}
    timing = cond.get("timing") or {}
    rows = [("date", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")),
            ("tool", f"backlash_monitor {__version__} (diagnose)"),
            ("drive (recording)", str(result["measurement"])),
            ("model", str(result["model"]) + (f" ({result['model_file']})" if result.get("model_file") else "")),
            ("nominal conditions", f"backlash width {nom.get('width_m', float('nan')) * 1e3:.2f} mm, absorber "
                                   f"consistency eta_k {nom.get('eta_k', float('nan')):.4g} Pa·s^n, flow index n1 "
                                   f"{nom.get('n1', float('nan')):.3g}"),
            ("recording", f"{result['events']} onset events, {comp.meas.n_samples * comp.meas.sample_period_s:.1f} s "
                          f"at {1 / comp.meas.sample_period_s / 1e3:.0f} kHz; pulse train from "
                          + ", ".join(f"{k} = {v:.4g} s" for k, v in timing.items())),
            ("units", "accelerations a1, a2 in m/s²; widths in mm; residuals in noise floors (1 = as close as the "
                      "model's own runs); n1, gains and relative changes have no unit")]
    return ["<table class='hdr'>" + "".join(f"<tr><th>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>"
                                            for k, v in rows) + "</table>"]


def write_report(diagnosis, directory, json_path=None) -> Path:
    """index.html + PNGs in ``directory`` (created). ``diagnosis``: a diagnosis.Diagnosis (its comparison and the
    model mean after the update draw the figures; its JSON the tables); ``json_path``: the diagnosis JSON the page
    links (written beside the page as diagnosis.json when not given)."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    result = diagnosis.to_json()
    comp = diagnosis.comparison
    after = diagnosis.model_mean_after
    model = comp.model
    if json_path is None:
        json_path = d / "diagnosis.json"
        json_path.write_text(json.dumps(result, indent=1, default=float))
    json_href = Path(os.path.relpath(Path(json_path).resolve(), d.resolve())).as_posix()
    spec = analysis.spectra(comp)
    imgs = [("Measurement vs model per signal (before/after)",
             plot_event_average(comp, d / "event_average.png", after)),
            ("Residual per onset event", plot_event_residuals(comp, d / "event_residuals.png", after)),
            ("Residual per phase and wavelet level", plot_where(result["where"], result.get("where_after"),
                                                                d / "where.png")),
            ("Ranked candidate effects", plot_ranked(result["ranked"], d / "ranked.png")),
            ("Whole-record spectra", plot_spectra(comp, spec, d / "spectra.png"))]
    fp = result["fit_percent"]
    rr = result["residual_over_noise_floor"]
    fit_rows = [(s, f"{fp['before'][s]:.1f}", f"{fp['after'][s]:.1f}", f"{fp['noise_band_median'][s]:.1f}",
                 f"{rr['before'][s]:.2f}", f"{rr['after'][s]:.2f}") for s in SEGMENT_SIGNALS]
    disc = result.get("discovery_parameters") or {}
    ties = {t["candidate"]: t for t in result.get("near_ties") or []}
    rank_rows = []
    for r in result["ranked"]:
        cand = r.get("candidate", r["effect"])
        if cand in (disc.get("indistinguishable_from") or []):
            tie = "indistinguishable from " + disc["effect"]
        elif cand in ties:
            tie = f"near-tie: {ties[cand]['ic_behind']:.1f} IC behind {disc['effect']}"
        elif cand == disc.get("candidate"):
            tie = "the discovery"
        else:
            tie = ""
        values = "; ".join(drive_terms.parameter_lines(r, model)) or ", ".join(
            f"{k} = {v:.4g}" for k, v in r["parameters"].items())
        rank_rows.append((cand, r.get("description") or "", values,
                          "screened only" if r["delta_ic"] is None else f"{r['delta_ic']:.1f}",
                          drive_terms.explained_percent(r['explained_fraction']), tie))
    summary = "".join(f"<li style='margin-left:{(len(line) - len(line.lstrip())) * 0.6:.1f}em'>"
                      f"{html.escape(line.strip())}</li>" for line in drive_terms.summary_lines(result, model)[1:]
                      if line not in (drive_terms.DELTA_IC_LINE, drive_terms.T2_LINE, drive_terms.UNITLESS_LINE))
    body = [f"<h1>Diagnosis of {html.escape(str(result['measurement']))}</h1>"]
    body += _header(result, comp)
    body += ["<h2>Summary</h2>",
             f"<p class='msg'><b>{html.escape(result['verdict'].replace('_', ' '))}</b>: "
             f"{html.escape(result['message'])}</p>", f"<ul>{summary}</ul>",
             f"<p>The whole diagnosis as data: <a href='{html.escape(json_href)}'>{html.escape(json_href)}</a> "
             f"(JSON). {result['events']} onset events; ensemble of {len(result['seeds'])} noise seeds; "
             f"{result['simulated_parameter_sets']} simulated parameter sets in {result['seconds']:.1f} s.</p>",
             "<p class='legend'>" + html.escape(drive_terms.DELTA_IC_LINE) + "<br>" + html.escape(drive_terms.T2_LINE)
             + "</p>"]
    for title, p in imgs:
        body.append(f"<h2>{html.escape(title)}</h2><img src='{p.name}' alt='{html.escape(title)}'>")
    body += ["<h2>Fit</h2>", _table(fit_rows, ("signal", "fit % before", "fit % after", "fit % noise band",
                                               "residual/noise before", "residual/noise after"))]
    if result["additions"]:
        body += ["<h2>For the next model version (add-effect)</h2>",
                 _table([(a["candidate"], a["role"], ", ".join(f"{k} = {v:.4g}" for k, v in a["parameters"].items()),
                          a["evidence"]) for a in result["additions"]], ("effect", "role", "values", "evidence"))]
    sd = result.get("spectral_discovery")
    if sd and sd.get("parameters"):
        p, u = sd["parameters"], sd["uncertainty"]
        body += ["<h2>From the raw spectrum</h2>",
                 f"<p>{html.escape(sd['effect'])}: amplitude_pu = {p['amplitude_pu']:.3g} ± {u['amplitude_pu']:.2g}, "
                 f"order {p['order']:.2f} ± {u['order']:.2f} (line at {sd['line_hz']:.1f} Hz, rotation "
                 f"{sd['rotation_hz']:.2f} Hz); explains {sd['explained_fraction']:.0%} of the line's excess power; "
                 f"{'confident' if sd['confident'] else 'not confident'}; phase not identifiable from a spectrum. "
                 "The event average cannot show it (not locked to the events): see the spectra above.</p>"]
    body += ["<h2>Candidates</h2>", _table(rank_rows, ("effect", "what it is", "fitted (model's value → fitted)",
                                                      "ΔIC", "explained", "tie"))]
    views = result["consistency"]["before"]["views"]
    after_views = result["consistency"]["after"]["views"]
    body += ["<h2>Consistency per view (T² with the model-form tolerance, against its 1 % limit)</h2>",
             _table([(n.replace("_", " "), v["dimension"], f"{v['T2']:.1f}", f"{after_views[n]['T2']:.1f}",
                      f"{v['T2_limit_p01']:.1f}", f"{v['T2_without_tolerance']:.1f}")
                     for n, v in views.items()],
                    ("view", "dimension", "T² before", "T² after", "limit", "T² before, no tolerance"))]
    if result.get("not_identifiable"):
        body.append("<h2>Not identifiable from this recording</h2><p>Over their whole fit range these effects move "
                    "the event average by less than the noise floor (linearised): "
                    + html.escape(", ".join(result["not_identifiable"])) + ".</p>")
    page = ("<!DOCTYPE html><html><head><meta charset='utf-8'><title>backlash_monitor diagnosis</title>"
            "<style>body{font-family:sans-serif;margin:2em;max-width:1100px}table{border-collapse:collapse}"
            "td,th{border:1px solid #999;padding:3px 8px;text-align:left;vertical-align:top}"
            "img{max-width:100%;border:1px solid #ccc}.hdr th{background:#f4f4f4}.legend{font-size:0.9em;color:#444}"
            ".msg{font-size:1.2em;background:#eef;padding:8px}</style></head><body>"
            + "\n".join(body) + "</body></html>")
    out = d / "index.html"
    out.write_text(page)
    return out
