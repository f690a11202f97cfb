"""Simulated, denoised onset windows for training and evaluation (plant + windowing + denoise).

``collect_windows(seeds, trigger)`` simulates the grid (widths x eta_k x n1) for each noise seed as one
vectorised batch, captures the windows with the project's windowing core (``trigger`` "paper": eq. 1
with the scenario's true width; "contact_loss": the angle difference alone), keeps the onset windows
the monitor classifies (those with a sensor offset estimate: all but each drive's first), denoises
them with the project's sym5 stage, removes their sensor offset estimate exactly as the classifier
does (backlash_monitor.windowing.offset.remove_offset) and returns a ``WindowSet``. Each (seed,
trigger, grid, settings) piece is cached under ``.cache/windows/`` (gitignored) keyed by a hash of
everything that makes it, so evaluate/bench/train do not resimulate.
"""
from __future__ import annotations

import hashlib
import json
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Iterable, Sequence

import numpy as np

from ..denoise import DEFAULT_DETAILS_REMOVED, DEFAULT_LEVEL, DEFAULT_MODE, DEFAULT_WAVELET, denoise_sym5
from ..plant import (ETA_K_VALUES, K2_WIDTHS_M, N1_VALUES, grid_scenarios, load_plant_config,
                     simulate_batch)
from ..windowing import TRIGGERS, default_window_offset, extract_windows_batch
from ..windowing.offset import offset_removal_label, remove_offset
from .patterns import config_hash
from .training_defaults import DEFAULT_DURATION_S

DATASET_VERSION = 2           # 2: sensor offsets removed, each drive's first onset window left out
CACHE_DIR = Path(os.environ.get("BACKLASH_MONITOR_CACHE", Path(__file__).resolve().parents[2] / ".cache"))
DENOISING = f"{DEFAULT_WAVELET} level {DEFAULT_LEVEL}, details {','.join(map(str, DEFAULT_DETAILS_REMOVED))} removed, mode {DEFAULT_MODE}"

META_FIELDS = ("width_m", "eta_k", "n1", "seed", "scenario", "event", "entry_sample_index")


@dataclass
class WindowSet:
    """Onset windows of many scenarios. Arrays indexed by window; ``meta`` columns: META_FIELDS
    (``event``: 0, 1, ... over the drive's classified onset windows)."""
    a1: np.ndarray                 # (n, L) what the classifier reads: denoised, sensor offset removed
    a2: np.ndarray                 # (n, L) the same for a2
    meta: np.ndarray               # (n, len(META_FIELDS)) float
    trigger: str
    sample_period_s: float
    raw_a1: np.ndarray | None = None   # (n, L) float32, raw windows (for plots)
    raw_a2: np.ndarray | None = None
    info: dict = field(default_factory=dict)
    sensor_offsets: np.ndarray | None = None   # (n, 2) the (a1, a2) offsets removed [m/s^2]

    def __len__(self) -> int:
        return int(self.a1.shape[0])

    def col(self, name: str) -> np.ndarray:
        return self.meta[:, META_FIELDS.index(name)]

    @property
    def width_m(self) -> np.ndarray:
        return self.col("width_m")

    def signal(self, name: str) -> np.ndarray:
        if name == "a1":
            return self.a1
        if name == "a2":
            return self.a2
        raise ValueError(f"unknown signal {name!r}; allowed: a1, a2")

    def subset(self, mask) -> "WindowSet":
        mask = np.asarray(mask)
        return WindowSet(self.a1[mask], self.a2[mask], self.meta[mask], self.trigger, self.sample_period_s,
                         None if self.raw_a1 is None else self.raw_a1[mask],
                         None if self.raw_a2 is None else self.raw_a2[mask], dict(self.info),
                         None if self.sensor_offsets is None else self.sensor_offsets[mask])

    @staticmethod
    def concat(sets: Sequence["WindowSet"]) -> "WindowSet":
        sets = [s for s in sets if s is not None]
        if not sets:
            raise ValueError("no window sets to concatenate")
        raw = all(s.raw_a1 is not None for s in sets)
        offsets = all(s.sensor_offsets is not None for s in sets)
        return WindowSet(np.concatenate([s.a1 for s in sets]), np.concatenate([s.a2 for s in sets]),
                         np.concatenate([s.meta for s in sets]), sets[0].trigger, sets[0].sample_period_s,
                         np.concatenate([s.raw_a1 for s in sets]) if raw else None,
                         np.concatenate([s.raw_a2 for s in sets]) if raw else None, dict(sets[0].info),
                         np.concatenate([s.sensor_offsets for s in sets]) if offsets else None)


def source_hash() -> str:
    """Hash of the code that makes the windows (plant, windowing, denoise): a cache entry made by other code
    is not reused."""
    root = Path(__file__).resolve().parents[1]
    files = sorted([*(root / "plant").glob("*.py"), *(root / "windowing").glob("*.py"), root / "denoise.py"])
    h = hashlib.sha256()
    for f in files:
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


def _key(parts: dict) -> str:
    return hashlib.sha256(json.dumps(parts, sort_keys=True, default=repr).encode()).hexdigest()[:20]


def _windows_from_batch(res, scenarios, trigger: str, seed: int, window_length: int,
                        window_offset: int = 0) -> WindowSet:
    sig = {"a1": res.a1, "a2": res.a2, "angle_difference": res.angle_difference}
    widths = np.array([s.width_m for s in scenarios]) if trigger == "paper" else None
    per_row = extract_windows_batch(sig, width_m=widths, trigger=trigger, window_length=window_length,
                                    sample_period_s=res.sample_period_s, window_offset_samples=window_offset)
    raw1, raw2, meta, offsets = [], [], [], []
    for i, (s, wins) in enumerate(zip(scenarios, per_row)):
        ev = 0
        for w in wins:
            if w.kind != "onset" or w.offset_periods == 0:
                continue     # the monitor classifies onset windows with a sensor offset estimate
            raw1.append(w.signals["a1"])
            raw2.append(w.signals["a2"])
            meta.append((s.width_m, s.eta_k, s.n1, seed, i, ev, w.entry_sample_index))
            offsets.append((w.sensor_offsets["a1"], w.sensor_offsets["a2"]))
            ev += 1
    raw1 = np.array(raw1, dtype=float).reshape(-1, window_length)
    raw2 = np.array(raw2, dtype=float).reshape(-1, window_length)
    offsets = np.array(offsets, dtype=float).reshape(-1, 2)
    # the classifier's input, as DriveEstimator makes it: denoised, then the offset estimate removed
    a1 = np.array([remove_offset(x, o) for x, o in zip(denoise_sym5(raw1), offsets[:, 0])]).reshape(raw1.shape)
    a2 = np.array([remove_offset(x, o) for x, o in zip(denoise_sym5(raw2), offsets[:, 1])]).reshape(raw2.shape)
    return WindowSet(a1, a2, np.array(meta, dtype=float).reshape(-1, len(META_FIELDS)),
                     trigger, res.sample_period_s, raw1.astype(np.float32), raw2.astype(np.float32),
                     sensor_offsets=offsets)


def collect_windows(seeds: Iterable[int], trigger: str | Sequence[str] = "paper", *,
                    widths_m=K2_WIDTHS_M, eta_k_values=ETA_K_VALUES, n1_values=N1_VALUES,
                    duration_s: float = DEFAULT_DURATION_S, config=None, window_length: int = 2048,
                    cache: bool = True, progress=None, window_offset: int | dict | None = None):
    """Denoised onset windows of the grid for each seed. ``trigger`` one name -> WindowSet; a list of
    names -> dict trigger -> WindowSet (one simulation per seed serves every trigger).
    ``progress``: optional callable(n) called once per seed done (e.g. a tqdm's update).
    ``window_offset``: samples from the entry to the window start, one int or a dict trigger -> int;
    None = each trigger's configured value (windowing.default_window_offset)."""
    triggers = [trigger] if isinstance(trigger, str) else list(trigger)
    for t in triggers:
        if t not in TRIGGERS:
            raise ValueError(f"unknown trigger {t!r}; allowed: {', '.join(TRIGGERS)}")
    offsets = {t: int(default_window_offset(t) if window_offset is None else
                      window_offset[t] if isinstance(window_offset, dict) else window_offset) for t in triggers}
    config = config if config is not None else load_plant_config()
    chash = config_hash(config)
    code = source_hash()
    out = {t: [] for t in triggers}
    for seed in seeds:
        scen = grid_scenarios(seeds=(int(seed),), widths_m=tuple(widths_m), eta_k_values=tuple(eta_k_values),
                              n1_values=tuple(n1_values))
        files = {}
        for t in triggers:
            key = _key({"v": DATASET_VERSION, "seed": int(seed), "trigger": t, "widths": list(map(float, widths_m)),
                        "eta": list(map(float, eta_k_values)), "n1": list(map(float, n1_values)),
                        "duration": float(duration_s), "L": int(window_length), "offset": offsets[t], "plant": chash, "code": code,
                        "denoise": DENOISING})
            files[t] = CACHE_DIR / "windows" / f"{t}_seed{int(seed)}_{key}.npz"
        missing = [t for t in triggers if not (cache and files[t].is_file())]
        if missing:
            res = simulate_batch(scen, duration_s=duration_s, config=config, noise=True)
            for t in missing:
                ws = _windows_from_batch(res, scen, t, int(seed), window_length, offsets[t])
                if cache:
                    files[t].parent.mkdir(parents=True, exist_ok=True)
                    tmp = files[t].with_name(files[t].name + f".tmp{os.getpid()}.npz")
                    np.savez(tmp, a1=ws.a1, a2=ws.a2, meta=ws.meta, raw_a1=ws.raw_a1, raw_a2=ws.raw_a2,
                             sample_period_s=ws.sample_period_s, sensor_offsets=ws.sensor_offsets)
                    os.replace(tmp, files[t])
                out[t].append(ws)
            del res
        for t in triggers:
            if t in missing:
                continue
            with np.load(files[t]) as z:
                out[t].append(WindowSet(z["a1"], z["a2"], z["meta"], t, float(z["sample_period_s"]),
                                        z["raw_a1"], z["raw_a2"], sensor_offsets=z["sensor_offsets"]))
        if progress is not None:
            progress(1)
    sets = {}
    for t in triggers:
        ws = WindowSet.concat(out[t])
        ws.info = {"seeds": [int(s) for s in seeds], "trigger": t, "widths_m": list(map(float, widths_m)),
                   "eta_k_values": list(map(float, eta_k_values)), "n1_values": list(map(float, n1_values)),
                   "duration_s": float(duration_s), "plant_config_hash": chash, "code_hash": code, "denoising": DENOISING,
                   "window_length": int(window_length), "window_offset_samples": offsets[t],
                   "sensor_offset": offset_removal_label()}
        sets[t] = ws
    return sets[triggers[0]] if isinstance(trigger, str) else sets
