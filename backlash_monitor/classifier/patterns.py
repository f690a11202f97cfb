"""The versioned pattern library: one ``.npz`` file (no pickles) holding every mode's patterns.

Layout (format version 1, documented in docs/classifier.md):

``meta``                              0-d unicode array: JSON with ``format_version``, ``settings``,
                                      ``widths_m``, ``n1_values``, ``signals``, ``modes``, ``training``
                                      (how the data were made) and ``created_utc``.
``paper/<signal>/m3``                 (n_n1, 6) M3 used for each n1 (eq. 14: the n1 = 0.89, eta_k = 0.025
                                      windows, so every row is the same in the paper's rule).
``paper/<signal>/w5``                 (n_n1, 6, 6) W5 per n1 (eq. 29, eta_k = 0.025, same n1).
``paper_corrected/<signal>/m3|w5``    the same for the corrected variant.
``shape/<name>``                      arrays of the improved mode's model (see shape.py).

``load_library(path, **expected)`` refuses a library whose format version or settings differ from the
ones requested (``PatternLibraryMismatch`` names every mismatching key with both values).
"""
from __future__ import annotations

import datetime as _dt
import hashlib
import io
import json
import math
import os
import re
import zipfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any
import dataclasses

import numpy as np

from .cpn import CPN_VARIANTS, CounterPropagationNetwork

FORMAT_VERSION = 1
SIGNALS = ("a1", "a2")
# Libraries made before the sample period was recorded in their settings were all trained on the
# plant's 50 kHz stream (config/plant.yaml); load_library takes that value for them.
LEGACY_SAMPLE_PERIOD_S = 2e-5
DATA_DIR = Path(__file__).resolve().parents[1] / "data"
DEFAULT_TRIGGER = "contact_loss"      # the windowing node's default trigger
DEFAULT_LIBRARY_PATH = DATA_DIR / "patterns.npz"          # made with trigger contact_loss
TRIGGER_LIBRARY_PATHS = {"contact_loss": DEFAULT_LIBRARY_PATH, "paper": DATA_DIR / "patterns_paper.npz"}


def default_library_path(trigger: str | None = None) -> Path:
    """The packaged library for a trigger (None: the default trigger's)."""
    trigger = trigger or DEFAULT_TRIGGER
    if trigger not in TRIGGER_LIBRARY_PATHS:
        raise ValueError(f"unknown trigger {trigger!r}; allowed: {', '.join(TRIGGER_LIBRARY_PATHS)}")
    return TRIGGER_LIBRARY_PATHS[trigger]

# Settings a library is made with; load_library compares the ones the caller passes.
SETTING_KEYS = ("trigger", "epochs", "l1", "l2", "denoising", "window_length", "window_offset_samples",
                "sample_period_s", "plant_config_hash", "sensor_offset")


class PatternLibraryError(ValueError):
    """The library file cannot be used (missing, unreadable, wrong format)."""


class PatternLibraryMismatch(PatternLibraryError):
    """The library was made with other settings than requested."""

    def __init__(self, path, mismatches: dict[str, tuple[Any, Any]]):
        self.mismatches = mismatches
        parts = [f"{k}: library has {lib!r}, requested {req!r}" for k, (lib, req) in mismatches.items()]
        super().__init__(f"pattern library {path} was made with other settings than requested ("
                         + "; ".join(parts) + "); rebuild it with `python -m backlash_monitor train` "
                         "using the requested settings, or request the library's settings")


def config_hash(obj) -> str:
    """Short stable hash of a (nested) config: dataclass, dict or anything JSON-able via repr. A plant config's
    effect parameters (held beside its dataclass fields) are part of it: two model versions that differ only
    in an effect's value (load_mass_drift +0.30 vs +0.32) must not share training windows (dataset.py's cache
    key). A config without any (the nominal plant) hashes as before, so existing libraries keep their hash."""
    extra = getattr(obj, "effect_parameters", None) if dataclasses.is_dataclass(obj) else None
    if dataclasses.is_dataclass(obj):
        obj = dataclasses.asdict(obj)
    if extra:
        obj = {**obj, "effect_parameters": extra}
    text = json.dumps(obj, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def _same(a, b) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
        return bool(np.isclose(float(a), float(b), rtol=1e-9, atol=0.0))
    return a == b


@dataclass
class PatternLibrary:
    settings: dict
    widths_m: np.ndarray
    n1_values: np.ndarray
    arrays: dict = field(default_factory=dict)   # "paper/a1/w5" -> ndarray, "shape/..." -> ndarray
    training: dict = field(default_factory=dict)
    shape_meta: dict = field(default_factory=dict)
    created_utc: str = ""
    path: str = ""
    signals: tuple = SIGNALS                     # the signals it has patterns for

    @property
    def sample_period_s(self) -> float:
        """The sample period the library was trained at [s]."""
        return float(self.settings.get("sample_period_s") or LEGACY_SAMPLE_PERIOD_S)

    # ---------------------------------------------------------------- queries
    @property
    def modes(self) -> list[str]:
        return sorted({k.split("/", 1)[0] for k in self.arrays})

    def n1_index(self, n1: float) -> int:
        d = np.abs(self.n1_values - float(n1))
        i = int(np.argmin(d))
        if d[i] > 1e-9:
            raise ValueError(f"creep index n1={n1} has no patterns in {self.path or 'the library'}; "
                             f"allowed: {', '.join(f'{v:g}' for v in self.n1_values)}")
        return i

    def cpn(self, variant: str, signal: str, n1: float) -> CounterPropagationNetwork:
        """The paper-mode network for one signal and n1, patterns loaded (no processing needed)."""
        if variant not in CPN_VARIANTS:
            raise ValueError(f"unknown variant {variant!r}; allowed: {', '.join(CPN_VARIANTS)}")
        if signal not in SIGNALS:
            raise ValueError(f"unknown signal {signal!r}; allowed: {', '.join(SIGNALS)}")
        key = f"{variant}/{signal}/"
        if key + "w5" not in self.arrays:
            raise PatternLibraryError(f"library {self.path} has no {variant} patterns for {signal}")
        i = self.n1_index(n1)
        s = self.settings
        return CounterPropagationNetwork(self.arrays[key + "m3"][i], variant=variant, epochs=s["epochs"],
                                         l1=s["l1"], l2=s["l2"], w5=self.arrays[key + "w5"][i])

    def shape_arrays(self) -> dict:
        return {k.split("/", 1)[1]: v for k, v in self.arrays.items() if k.startswith("shape/")}

    # ---------------------------------------------------------------- file
    def save(self, path) -> Path:
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        meta = {
            "format_version": FORMAT_VERSION,
            "settings": self.settings,
            "widths_m": [float(w) for w in self.widths_m],
            "n1_values": [float(v) for v in self.n1_values],
            "signals": list(self.signals),
            "modes": self.modes,
            "training": self.training,
            "shape_meta": self.shape_meta,
            "created_utc": self.created_utc or _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        }
        # written beside it, renamed onto it when complete: never a half-written library
        tmp = path.with_name(path.name + f".tmp{os.getpid()}.npz")
        try:
            np.savez_compressed(tmp, meta=np.array(json.dumps(meta, sort_keys=True)), **self.arrays)
        except BaseException:
            tmp.unlink(missing_ok=True)
            raise
        os.replace(tmp, path)
        return path


def load_library(path=None, **expected) -> PatternLibrary:
    """Load a pattern library; ``expected`` settings (e.g. trigger="contact_loss", epochs=30) must match.

    ``path`` None: the packaged library of the requested trigger (default_library_path). ``None`` values in
    ``expected`` are not checked. Raises PatternLibraryError / PatternLibraryMismatch.
    """
    if path is None:
        trig = expected.get("trigger")
        path = default_library_path(trig if trig in TRIGGER_LIBRARY_PATHS else None)
    path = Path(path)
    unknown = sorted(set(expected) - set(SETTING_KEYS))
    if unknown:
        raise ValueError(f"unknown library setting(s) {', '.join(unknown)}; allowed: {', '.join(SETTING_KEYS)}")
    if not path.is_file():
        raise PatternLibraryError(f"pattern library {path} does not exist; make one with "
                                  f"`python -m backlash_monitor train --trigger {expected.get('trigger') or DEFAULT_TRIGGER} --out {path}`")
    try:
        arrays = read_npz(path)
        meta = json.loads(str(arrays.pop("meta")))
    except Exception as exc:  # noqa: BLE001 - any unreadable file is the same problem for the user
        raise PatternLibraryError(f"pattern library {path} is unreadable: {exc}") from exc
    version = meta.get("format_version")
    if version != FORMAT_VERSION:
        raise PatternLibraryMismatch(path, {"format_version": (version, FORMAT_VERSION)})
    settings = meta.get("settings", {})
    if not settings.get("sample_period_s"):   # made before the setting was stored: 50 kHz
        settings = {**settings, "sample_period_s": LEGACY_SAMPLE_PERIOD_S}
    mism = {k: (settings.get(k), v) for k, v in expected.items() if v is not None and not _same(settings.get(k), v)}
    if mism:
        raise PatternLibraryMismatch(path, mism)
    return PatternLibrary(settings=settings, widths_m=np.asarray(meta["widths_m"]),
                          n1_values=np.asarray(meta["n1_values"]), arrays=arrays,
                          training=meta.get("training", {}), shape_meta=meta.get("shape_meta", {}),
                          created_utc=meta.get("created_utc", ""), path=str(path),
                          signals=tuple(meta.get("signals") or SIGNALS))


# the header numpy writes for a plain array (numpy.lib.format), as numpy's own header parser reads it
_NPY_HEADER = re.compile(r"\{'descr': '([<>|=][A-Za-z][0-9]*)', 'fortran_order': (True|False), "
                         r"'shape': \(([0-9, ]*)\), \}\s*")


def read_npz(path) -> dict[str, np.ndarray]:
    """Every array of an ``.npz`` file (no pickles): what ``np.load(path, allow_pickle=False)``
    gives for each name, as writable arrays of their own. A library's ~20 small arrays cost
    np.load ~1.2 ms, most of it parsing each array's header with ``ast.literal_eval``; a header
    of numpy's plain form (a dtype string, the order, the shape) is read here by a pattern, any
    other goes through numpy's reader (``numpy.lib.format.read_array``), as np.load reads it."""
    out = {}
    with zipfile.ZipFile(path) as z:
        for info in z.infolist():
            name = info.filename
            data = z.read(info)
            key = name[:-4] if name.endswith(".npy") else name
            found = None
            if data[:6] == b"\x93NUMPY" and data[6] in (1, 2, 3) and len(data) >= 10:
                if data[6] == 1:
                    start, size = 10, int.from_bytes(data[8:10], "little")
                else:
                    start, size = 12, int.from_bytes(data[8:12], "little")
                header = data[start:start + size].decode("latin1" if data[6] < 3 else "utf8")
                found = _NPY_HEADER.fullmatch(header)
            if found is None:
                out[key] = np.lib.format.read_array(io.BytesIO(data), allow_pickle=False)
                continue
            descr, fortran, dims = found.groups()
            dtype = np.dtype(descr)
            shape = tuple(int(d) for d in dims.split(",") if d.strip())
            count = math.prod(shape)
            offset = start + size
            if dtype.hasobject or offset + count * dtype.itemsize > len(data):
                out[key] = np.lib.format.read_array(io.BytesIO(data), allow_pickle=False)
                continue
            array = np.frombuffer(data, dtype=dtype, count=count, offset=offset)
            out[key] = array.reshape(shape, order="F" if fortran == "True" else "C").copy(
                order="F" if fortran == "True" else "C")
    return out


def flagged_warning(library) -> str | None:
    """One line for whoever loads a library that `train --model` flagged (its check against the diagnosis the
    model version came from failed: workbench/retrain.py); None when it is not flagged or was never checked."""
    check = (library.training or {}).get("check") or {}
    if not check.get("flagged"):
        return None
    return (f"pattern library {library.path} is FLAGGED by `train`'s check against the diagnosis it was retrained "
            "for: " + "; ".join(check.get("reasons", [])) + "; its widths may be biased")

