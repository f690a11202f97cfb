"""A *measurement*: one drive's recorded signals, from an MCAP bag or a CSV/NPZ table.

- MCAP: the project's SignalChunk topics ``<namespace>/plant/a1``, ``a2``, ``angle_difference`` (or
  ``omega1`` + ``omega2``), any namespace (found by the topic name's tail when not given).
  A ``true_width_m`` topic, if present, is ignored (a real drive has none).
- CSV: a header row, columns ``time_s, a1, a2, angle_difference`` (and/or ``omega1, omega2``),
  units s, m/s^2, m/s^2, rad, rad/s; equally spaced rows.
- NPZ: arrays with the same names (1-D, equal length); ``sample_period_s`` (scalar) or ``time_s``.
  A ``simulate`` NPZ (2-D arrays, one row per scenario) is accepted with ``row`` (default 0).
"""
from __future__ import annotations

import csv
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from backlash_monitor.windowing import DEFAULTS
from backlash_monitor.windowing.saturation import SaturationCounter, SaturationSettings
from backlash_monitor.bag import BagError, BagReader, DamagedBagError, TruncatedBagError
from backlash_monitor.errors import RunFailure

REQUIRED = ("a1", "a2")
ANGLE_SOURCES = (("angle_difference",), ("omega1", "omega2"))
KNOWN = ("a1", "a2", "angle_difference", "omega1", "omega2")
MIN_EVENTS = 3


class MeasurementError(ValueError):
    """A measurement that cannot be used (names the problem and what is allowed)."""


@dataclass
class Measurement:
    source: str
    sample_period_s: float
    signals: dict = field(default_factory=dict)     # name -> 1-D float64

    @property
    def n_samples(self) -> int:
        return len(self.signals["a1"])

    @property
    def duration_s(self) -> float:
        return self.n_samples * self.sample_period_s

    def saturation(self) -> dict:
        return saturation_of(self.signals)


def saturation_of(signals: dict) -> dict:
    """A recording's accelerometers at their rail (clipped) or stuck at one value, counted in blocks of
    1 s as the windowing node and ``analyze`` count them (windowing/saturation.py):
    {"saturated": bool, "signals": {a1, a2: counts, shares, rails}, "messages": [one per fault]}."""
    counter = SaturationCounter(REQUIRED, SaturationSettings.from_config(DEFAULTS["saturation"]))
    counter.feed({s: signals[s] for s in REQUIRED})
    counter.flush()
    totals = counter.totals()
    return {"saturated": any(r.faulty for r in totals.values()),
            "signals": {name: r.as_dict() for name, r in totals.items()}, "messages": counter.messages()}


def _check_signals(sig: dict, source: str) -> None:
    missing = [s for s in REQUIRED if s not in sig]
    if missing or not any(all(a in sig for a in grp) for grp in ANGLE_SOURCES):
        raise MeasurementError(
            f"measurement {source}: has signals {', '.join(sorted(sig)) or 'none'}; needs a1, a2 and "
            "angle_difference (or omega1 and omega2)")
    lengths = {len(v) for v in sig.values()}
    if len(lengths) != 1:
        raise MeasurementError(f"measurement {source}: signals have different lengths {sorted(lengths)}; "
                               "allowed: equal lengths")
    for name, v in sig.items():
        if not np.all(np.isfinite(v)):
            raise MeasurementError(f"measurement {source}: signal {name} has non-finite samples")


def _period_from_time(t: np.ndarray, source: str) -> float:
    if t.size < 2:
        raise MeasurementError(f"measurement {source}: fewer than 2 samples")
    d = np.diff(t)
    dt = float(np.median(d))
    if dt <= 0 or np.max(np.abs(d - dt)) > 1e-3 * dt:
        raise MeasurementError(f"measurement {source}: time_s is not equally spaced (steps "
                               f"{d.min():.6g}..{d.max():.6g} s); allowed: a constant sample period")
    return dt


def load_measurement(path, namespace: str | None = None, row: int = 0) -> Measurement:
    p = Path(path)
    if not p.is_file():
        raise MeasurementError(f"measurement {str(p)!r} does not exist; give an .mcap bag, a .csv or an .npz")
    suffix = p.suffix.lower()
    if suffix == ".mcap":
        m = _load_mcap(p, namespace)
    elif suffix == ".csv":
        m = _load_csv(p)
    elif suffix == ".npz":
        m = _load_npz(p, row)
    else:
        raise MeasurementError(f"measurement {p}: unknown file type {suffix!r}; allowed: .mcap, .csv, .npz")
    _check_signals(m.signals, str(p))
    return m


def _load_mcap(p: Path, namespace: str | None) -> Measurement:
    try:
        with BagReader(p) as reader:
            topics = list(reader.topics)
            chosen = {}
            for name in KNOWN:
                if namespace is not None:
                    ns = namespace.strip("/")
                    want = f"/{ns}/plant/{name}" if ns else f"/plant/{name}"
                    cands = [t for t in topics if t in (want, want.lstrip("/"))]
                else:
                    cands = [t for t in topics if t.rstrip("/").endswith(f"plant/{name}")]
                if len(cands) > 1:
                    raise MeasurementError(f"measurement {p}: several drives have {name} ({', '.join(cands)}); "
                                           "give --namespace")
                if cands:
                    chosen[name] = cands[0]
            if not chosen:
                raise MeasurementError(f"measurement {p}: no plant/a1 ... topics; it has {', '.join(topics)}")
            series = reader.read_signals(list(chosen.values()))
    except (TruncatedBagError, DamagedBagError) as exc:   # the data is damaged, not the command line
        raise RunFailure(f"measurement {p}: {exc}") from None
    except BagError as exc:
        raise MeasurementError(f"measurement {p}: {exc}") from None
    sig, periods, starts = {}, set(), set()
    for name, topic in chosen.items():
        s = series[topic]
        if s.gaps:
            raise MeasurementError(f"measurement {p}: topic {topic} has {len(s.gaps)} gap(s) in its sample "
                                   "index; allowed: a contiguous recording")
        sig[name] = np.asarray(s.samples, dtype=np.float64)
        periods.add(round(float(s.sample_period_s), 15))
        starts.add(int(s.sample_index[0]) if len(s.sample_index) else 0)
    if len(periods) != 1:
        raise MeasurementError(f"measurement {p}: topics have different sample periods {sorted(periods)}")
    n = min(len(v) for v in sig.values())
    if len(starts) != 1:
        first = max(starts)
        for name, topic in chosen.items():
            off = first - int(series[topic].sample_index[0])
            sig[name] = sig[name][off:]
        n = min(len(v) for v in sig.values())
    sig = {k: v[:n] for k, v in sig.items()}
    return Measurement(str(p), periods.pop(), sig)


def _load_csv(p: Path) -> Measurement:
    with open(p, newline="") as f:
        reader = csv.reader(f)
        try:
            header = [h.strip() for h in next(reader)]
        except StopIteration:
            raise MeasurementError(f"measurement {p}: empty file") from None
        if "time_s" not in header:
            raise MeasurementError(f"measurement {p}: no time_s column; columns are {', '.join(header)}; "
                                   "allowed layout: time_s, a1, a2, angle_difference (or omega1, omega2)")
        try:
            data = np.array([[float(x) for x in row] for row in reader if row], dtype=np.float64)
        except ValueError as exc:
            raise MeasurementError(f"measurement {p}: a value is not a number ({exc})") from None
    if data.ndim != 2 or data.shape[1] != len(header):
        raise MeasurementError(f"measurement {p}: rows do not all have {len(header)} columns")
    cols = {h: data[:, i] for i, h in enumerate(header)}
    dt = _period_from_time(cols["time_s"], str(p))
    return Measurement(str(p), dt, {k: v for k, v in cols.items() if k in KNOWN})


def _load_npz(p: Path, row: int) -> Measurement:
    with np.load(p) as z:
        names = set(z.files)
        sig = {}
        for k in KNOWN:
            if k in names:
                a = np.asarray(z[k], dtype=np.float64)
                if a.ndim == 2:
                    if not 0 <= row < a.shape[0]:
                        raise MeasurementError(f"measurement {p}: row {row} out of range; allowed 0..{a.shape[0] - 1}")
                    a = a[row]
                sig[k] = a
        if "sample_period_s" in names:
            dt = float(z["sample_period_s"])
        elif "time_s" in names:
            dt = _period_from_time(np.asarray(z["time_s"], dtype=float), str(p))
        else:
            raise MeasurementError(f"measurement {p}: needs sample_period_s or time_s")
    return Measurement(str(p), dt, sig)


def check_against_model(m: Measurement, model) -> None:
    """Refuse a measurement the model cannot be compared with: other sample rate, too short."""
    cfg = model.plant_config()
    fs_model = cfg.simulation.sample_rate_hz
    fs = 1.0 / m.sample_period_s
    if abs(fs - fs_model) > 1e-6 * fs_model:
        raise MeasurementError(f"measurement {m.source}: sample rate {fs:g} Hz differs from the model's "
                               f"{fs_model:g} Hz (simulation.sample_rate_hz); allowed: equal rates "
                               f"(resample the recording, or --set simulation.sample_rate_hz={fs:g})")
    need_s = MIN_EVENTS * cfg.pulse_load.period_s + cfg.pulse_load.first_s + 0.05
    if m.duration_s < need_s:
        raise MeasurementError(f"measurement {m.source}: {m.duration_s:.3f} s is too short for {MIN_EVENTS} onset "
                               f"events of the model's pulse train (period {cfg.pulse_load.period_s:g} s); "
                               f"allowed: >= {need_s:.2f} s")
