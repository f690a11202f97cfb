"""The workbench history per model version: what each version is, where it came from, and how well it fits.

``workbench_history.jsonl`` (model.py writes it) holds one line per event:

- ``version``: add-effect made a version (its parent, the effects added, nominal values changed, the diagnosis);
- ``check``: compare or diagnose held a version against a recording (fit % and residual over the noise floor
  per signal); add-effect also records the diagnosis's fit *after* the effect, which is the new version's fit
  on the diagnosed recording when the version holds every addition at its fitted values;
- ``monitor``: train --model measured the monitor's published width on the diagnosed recording with the
  retrained library (for the new version) and with the library in use before (for its parent).

:func:`version_rows` folds those into one row per version (its latest check, its latest monitor width);
:func:`plot_history` draws the error per version (the residual falling towards the noise floor).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
import html

NOT_CHECKED = "not checked"


@dataclass
class VersionRow:
    """One model version's line in the history."""
    name: str
    version: int
    model: str                         # its file (or "(unsaved)": the default model a diagnosis ran against)
    parent: str = "-"
    came_from: str = "first version"   # the diagnosis it was made from (file and date), or how it was made
    changes: str = "-"                 # effects added and nominal values changed
    date: str = ""                     # when the version was made (or first seen)
    fit_percent: dict = field(default_factory=dict)          # {"a1": %, "a2": %} of its latest check
    residual_over_noise_floor: dict = field(default_factory=dict)
    checked_by: str = NOT_CHECKED      # the command and recording of that check
    monitor_width_m: float | None = None
    monitor_library: str = ""

    @property
    def key(self) -> tuple:
        return (self.name, self.version)

    def cells(self) -> tuple:
        """The printed cells; none is blank: a figure that does not exist says why."""
        fp, rr = self.fit_percent, self.residual_over_noise_floor
        checked = bool(fp)
        fit = f"{fp.get('a1', math.nan):.1f}/{fp.get('a2', math.nan):.1f}" if checked else NOT_CHECKED
        res = f"{rr.get('a1', math.nan):.2f}/{rr.get('a2', math.nan):.2f}" if rr else NOT_CHECKED
        width = (f"{self.monitor_width_m * 1e3:.3f} ({Path(self.monitor_library).name})"
                 if self.monitor_width_m is not None and math.isfinite(self.monitor_width_m) else "not trained")
        return (f"{self.name} v{self.version}", self.model or "(unsaved)", self.parent or "-",
                self.came_from or "-", self.changes or "-", fit, res, self.checked_by or NOT_CHECKED, width,
                self.date or "-")


HEADER = ("version", "file", "parent", "from diagnosis", "changes", "fit % a1/a2", "resid/noise a1/a2",
          "checked by", "monitor width mm", "date")


def _date(text) -> str:
    return str(text or "")[:16].replace("T", " ")


def _changes(entry: dict) -> str:
    parts = [f"{a['effect']}({', '.join(f'{k}={x:.4g}' for k, x in a.get('parameters', {}).items())})"
             for a in entry.get("added") or []]
    for k, v in (entry.get("nominal_changed") or {}).items():
        if isinstance(v, dict):
            unc = v.get("uncertainty")
            parts.append(f"{k} {v.get('from', float('nan')):.4g} -> {v['value']:.4g}"
                         + (f" ± {unc:.2g}" if unc is not None else ""))
        else:
            parts.append(f"nominal {k} = {v:.4g}")
    return "; ".join(parts) or "-"


def _key(entry: dict) -> tuple:
    return (str(entry.get("name") or Path(str(entry.get("model", "default"))).stem), int(entry.get("version", 1)))


def version_rows(history: list[dict]) -> list[VersionRow]:
    """One row per model version (in the order first seen), from the history's entries."""
    rows: dict[tuple, VersionRow] = {}

    def row(entry) -> VersionRow:
        k = _key(entry)
        if k not in rows:
            rows[k] = VersionRow(k[0], k[1], str(entry.get("model") or "(unsaved)"),
                                 date=_date(entry.get("time_utc")))
        return rows[k]

    for e in history:
        kind = e.get("type")
        if kind == "version":
            r = row(e)
            r.model = str(e.get("model") or r.model)
            r.parent = str(e.get("parent") or "-")
            r.date = _date(e.get("time_utc")) or r.date
            prov = e.get("provenance") or {}
            diag = prov.get("diagnosis") or e.get("diagnosis")
            if diag:
                when = _date(prov.get("diagnosis_time_utc"))
                r.came_from = Path(str(diag)).name + (f" of {when}" if when else "")
            else:
                r.came_from = "by hand (add-effect EFFECT --value)" if e.get("added") else "-"
            r.changes = _changes(e)
        elif kind == "check":
            r = row(e)
            if r.model in ("", "(unsaved)") and e.get("model"):
                r.model = str(e["model"])
            r.fit_percent = dict(e.get("fit_percent") or {})
            r.residual_over_noise_floor = dict(e.get("residual_over_noise_floor") or {})
            r.checked_by = f"{e.get('command', '?')} {Path(str(e.get('measurement', ''))).name}".strip()
        elif kind == "monitor":
            r = row(e)
            w = e.get("width_m")
            r.monitor_width_m = None if w is None else float(w)
            r.monitor_library = str(e.get("library") or "")
    return list(rows.values())


def plot_history(rows: list[VersionRow], path, title: str = "") -> Path:
    """The error per version: residual over the noise floor (a1, a2; 1 = the floor) and fit % per version,
    and the monitor's width where it was measured. Versions never checked are marked on the axis."""
    # deferred: matplotlib.pyplot costs ~700 ms at start-up (python -X importtime, 29 Nov)
    import matplotlib
    matplotlib.use("Agg")
    # deferred: as matplotlib above
    import matplotlib.pyplot as plt
    labels = [f"{r.name} v{r.version}" for r in rows]
    x = list(range(len(rows)))
    fig, axes = plt.subplots(3, 1, figsize=(7, 7.5), sharex=True)
    for s, mark in (("a1", "o-"), ("a2", "s-")):
        axes[0].plot(x, [r.residual_over_noise_floor.get(s, math.nan) for r in rows], mark, label=s)
        axes[1].plot(x, [r.fit_percent.get(s, math.nan) for r in rows], mark, label=s)
    axes[0].axhline(1.0, color="0.5", ls="--", lw=1, label="noise floor")
    axes[0].set_ylabel("residual / noise floor")
    axes[0].set_yscale("log")
    axes[0].legend(fontsize=8)
    axes[1].set_ylabel("fit %")
    axes[1].legend(fontsize=8)
    axes[2].plot(x, [r.monitor_width_m * 1e3 if r.monitor_width_m is not None else math.nan for r in rows], "d-")
    axes[2].set_ylabel("monitor width [mm]")
    axes[2].set_xticks(x)
    axes[2].set_xticklabels([lab + ("" if r.fit_percent else "\n(not checked)") for lab, r in zip(labels, rows)],
                            fontsize=8)
    fig.suptitle(title or "the model's error per version")
    fig.tight_layout()
    fig.savefig(path, dpi=80)
    plt.close(fig)
    return Path(path)


def write_html(rows: list[VersionRow], directory, title: str = "workbench history") -> Path:
    """index.html (the table) and history.png (the plot) in ``directory``."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    plot_history(rows, d / "history.png", title)
    head = "".join(f"<th>{html.escape(h)}</th>" for h in HEADER)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r.cells()) + "</tr>" for r in rows)
    page = (f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            "<style>td,th{border:1px solid #ccc;padding:2px 6px;font:13px sans-serif}"
            "table{border-collapse:collapse}</style></head><body>"
            f"<h1>{html.escape(title)}</h1><p>Every model version with its fit and its residual over the "
            "model's noise floor on the recording it was last checked against (1 = the floor), the monitor's "
            "published width with the library trained on it, and the diagnosis it came from.</p>"
            f"<table><tr>{head}</tr>{body}</table><p><img src='history.png' alt='error per version'></p>"
            "</body></html>")
    (d / "index.html").write_text(page)
    return d / "index.html"
