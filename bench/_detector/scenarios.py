"""Streams on which the entry detector's output is compared, old (reference_detector.py) against new.

A scenario is (name, detector kwargs, list of feeds); a feed is (first_sample_index, signals,
sample_period_s). ``run(cls, scenario)`` feeds one detector of class ``cls`` and returns what it said:
every entry of every feed (all fields), its event log, its re-reference count, and after every feed
the floats of its state (the contact tracker, offsets, drift rate, integration) as their bits, so
"identical" means the same decisions *and* the same numbers inside.

Records: the plant simulator (6 widths x 4 (eta_k, n1, seed), noise on, 10 s each, angle difference
and the two shaft speeds) and the synthetic records of backlash_monitor.windowing.synthetic (bounce,
encoder quantisation, a drifting integration over 30 s).
"""
from __future__ import annotations

import struct
import zlib

import numpy as np

FS = 50_000
DT = 2e-5
ETA_N1_SEED = ((0.0125, 0.89, 0), (0.05, 0.97, 7), (0.025, 0.93, 3000), (0.0375, 0.91, 11))


def plant_records(seconds: float = 10.0, widths=None, combos=ETA_N1_SEED):
    """[(label, width_m, {"angle_difference", "omega1", "omega2"})], one simulated run per scenario."""
    from backlash_monitor import plant

    widths = tuple(plant.K2_WIDTHS_M) if widths is None else tuple(widths)
    scen = [plant.Scenario(width_m=w, eta_k=e, n1=n1, seed=s) for w in widths for e, n1, s in combos]
    sim = plant.PlantSimulator(scen, config=plant.load_plant_config(), noise=True,
                               outputs=("omega1", "omega2", "angle_difference"))
    n = int(round(seconds * FS))
    parts = [sim.run(min(50_000, n - k)) for k in range(0, n, 50_000)]
    out = []
    for i, s in enumerate(scen):
        sig = {name: np.concatenate([getattr(c, name)[i] for c in parts])
               for name in ("angle_difference", "omega1", "omega2")}
        out.append((f"w{s.width_m * 1e3:g}mm_eta{s.eta_k:g}_n1{s.n1:g}_s{s.seed}", s.width_m, sig))
    return out


def chunked(sig: dict, sizes, first: int = 0, period=None):
    """Feeds of consecutive chunks; ``sizes`` an int (constant) or a sequence (cycled)."""
    n = len(next(iter(sig.values())))
    sizes = [sizes] if isinstance(sizes, (int, np.integer)) else list(sizes)
    feeds, lo, i = [], 0, 0
    while lo < n:
        c = int(sizes[i % len(sizes)])
        feeds.append((first + lo, {k: v[lo:lo + c] for k, v in sig.items()}, period))
        lo += c
        i += 1
    return feeds


def random_sizes(seed: int, low: int = 1, high: int = 6000, count: int = 4000):
    return np.random.default_rng(seed).integers(low, high, count)


def measured(sig):
    return {"angle_difference": sig["angle_difference"]}


def speeds(sig, bias=0.0):
    return {"omega1": sig["omega1"] + bias, "omega2": sig["omega2"]}


def faulty(sig: dict, chunk: int = 1000):
    """A stream with every irregularity the detector reacts to: a dropped stretch, a repeated and an
    older chunk, a NaN chunk, a bad and a changed sample period, and the source switching."""
    feeds = chunked(sig, chunk, period=DT)
    out = []
    for j, (first, s, p) in enumerate(feeds):
        if 30 <= j < 33:                               # dropped chunks (a gap)
            continue
        if j == 60:                                    # a NaN sample
            s = {k: v.copy() for k, v in s.items()}
            next(iter(s.values()))[17] = np.nan
        if j == 100:
            p = float("nan")                           # bad sample period
        if 140 <= j < 150:
            p = 2.5e-5                                 # another (valid) sample period, then back
        out.append((first, s, p))
        if j in (70, 71):                              # repeated chunk, then an older one
            out.append((first, s, p))
            out.append((first - 5000, s, p))
    return out


def source_switch(sig: dict, chunk: int = 1000):
    """Measured angles, then the speeds (the detector resets: another angle source), then angles again."""
    feeds = []
    for first, s, p in chunked(sig, chunk, period=DT):
        j = first // chunk
        feeds.append((first, speeds(s) if 150 <= j < 300 else measured(s), p))
    return feeds


def plant_scenarios(records, quick: bool = False):
    """Scenarios on the plant records (``quick``: fewer chunkings, for the timing bench's check)."""
    out = []
    for label, width, sig in records:
        m, w = measured(sig), speeds(sig)
        n = len(sig["angle_difference"])
        cl = {"trigger": "contact_loss"}
        pm = {"trigger": "paper", "width_m": width}
        out += [(f"{label}/cl/whole", cl, [(0, m, DT)]),
                (f"{label}/cl/1000", cl, chunked(m, 1000, period=DT)),
                (f"{label}/cl_int/whole", cl, [(0, w, DT)]),
                (f"{label}/cl_int/1000", cl, chunked(w, 1000, period=DT)),
                (f"{label}/paper/1000", pm, chunked(m, 1000, period=DT)),
                (f"{label}/paper_int/1000", pm, chunked(w, 1000, period=DT))]
        if quick:
            continue
        out += [(f"{label}/cl/777", cl, chunked(m, 777)),
                (f"{label}/cl/65536", cl, chunked(m, 65536, period=DT)),
                (f"{label}/cl/4096", cl, chunked(m, 4096)),
                (f"{label}/cl/random", cl, chunked(m, random_sizes(zlib.crc32(label.encode()) % 1000))),
                (f"{label}/cl/random_small", cl, chunked(m, random_sizes(7, 1, 300, 20000))),
                (f"{label}/cl_int/777", cl, chunked(w, 777)),
                (f"{label}/cl_int_bias/1000", cl, chunked(speeds(sig, 1e-3), 1000)),
                (f"{label}/cl_int_rect/1000", dict(cl, integration="rectangle"), chunked(w, 1000)),
                (f"{label}/paper/whole", pm, [(0, m, DT)]),
                (f"{label}/paper/777", pm, chunked(m, 777)),
                (f"{label}/paper/random", pm, chunked(m, random_sizes(3))),
                (f"{label}/paper_int/whole", pm, [(0, w, DT)]),
                (f"{label}/paper_int/777", pm, chunked(w, 777)),
                (f"{label}/paper_int_bias/4096", pm, chunked(speeds(sig, 1e-3), 4096)),
                (f"{label}/paper_int_side_none/1000", dict(pm, initial_contact_side=None), chunked(w, 1000)),
                (f"{label}/paper_int_reref10ms/1000", dict(pm, rereference_interval_s=0.01), chunked(w, 1000)),
                (f"{label}/cl/faulty", cl, faulty(m)),
                (f"{label}/cl_int/faulty", cl, faulty(w)),
                (f"{label}/paper/faulty", pm, faulty(m)),
                (f"{label}/paper_int/faulty", pm, faulty(w)),
                (f"{label}/cl/source_switch", dict(cl, angle_source="auto"), source_switch(sig)),
                (f"{label}/paper/source_switch", dict(pm, angle_source="auto"), source_switch(sig)),
                (f"{label}/cl/restart", cl, chunked(m, 1000) + chunked({"angle_difference": sig["angle_difference"][: n // 3]}, 1000))]
        # parameters away from the defaults (fewer records: they cost time)
        if label.endswith("_s0") or label.endswith("_s7"):
            for kw in ({"holdoff_samples": 300}, {"settle_samples": 50}, {"settle_samples": 400},
                       {"fit_samples": 64}, {"fit_samples": 512}, {"fit_samples": 4096},
                       {"confirm_rad": 0.012}, {"confirm_rad": 0.018}, {"settle_range_rad": 3e-3},
                       {"reference_tau_s": 0.005}, {"contact_deflection_rad": 0.0}):
                tag = "_".join(f"{k}{v}" for k, v in kw.items())
                out.append((f"{label}/cl_{tag}/1000", dict(cl, **kw), chunked(m, 1000)))
                out.append((f"{label}/cl_{tag}/whole", dict(cl, **kw), [(0, m, DT)]))
                out.append((f"{label}/paper_int_{tag}/1000", dict(pm, **kw), chunked(w, 1000)))
    return out


def chunk_one_scenarios(records, seconds: float = 1.0):
    """Chunks of ONE sample (the slowest stream there is): the first ``seconds`` of two records."""
    out = []
    for label, width, sig in records[:2]:
        n = int(seconds * FS)
        part = {k: v[:n] for k, v in sig.items()}
        out.append((f"{label}/cl/1", {"trigger": "contact_loss"}, chunked(measured(part), 1)))
        out.append((f"{label}/paper_int/1", {"trigger": "paper", "width_m": width}, chunked(speeds(part), 1)))
    return out


def synthetic_scenarios():
    from backlash_monitor.windowing.synthetic import synthetic_period, tile_record

    out = []
    for width in (0.0025, 0.005, 0.01):
        p = synthetic_period(width_m=width)
        d, w, _, _ = tile_record(p, 8)
        for chunk in (None, 777, 5000):
            feeds = [(0, {"angle_difference": d}, None)] if chunk is None else chunked({"angle_difference": d}, chunk)
            out.append((f"syn{width}/cl/{chunk}", {"trigger": "contact_loss"}, feeds))
            out.append((f"syn{width}/paper/{chunk}", {"trigger": "paper", "width_m": width}, feeds))
            wf = [(0, {"omega1": w + 150.0, "omega2": np.full_like(w, 150.0)}, None)] if chunk is None else \
                chunked({"omega1": w + 150.0, "omega2": np.full_like(w, 150.0)}, chunk)
            out.append((f"syn{width}/paper_int/{chunk}", {"trigger": "paper", "width_m": width}, wf))
            out.append((f"syn{width}/cl_int/{chunk}", {"trigger": "contact_loss"}, wf))
    # a bouncing contact, with a hold-off shorter than the bounce
    p = synthetic_period(width_m=0.005, bounce_rad=0.004, bounce_s=0.004)
    d, _, _, _ = tile_record(p, 8)
    for trig, kw in (("cl", {"trigger": "contact_loss"}), ("paper", {"trigger": "paper", "width_m": 0.005})):
        for hold in (2048, 300):
            out.append((f"bounce/{trig}/hold{hold}", dict(kw, holdoff_samples=hold), [(0, {"angle_difference": d}, None)]))
            out.append((f"bounce/{trig}/hold{hold}/333", dict(kw, holdoff_samples=hold), chunked({"angle_difference": d}, 333)))
    # quantised encoders with noise (alpha1, alpha2)
    rng = np.random.default_rng(1)
    for bits in (16, 14):
        q = 2 * np.pi / 2 ** bits
        p = synthetic_period(width_m=0.0025)
        d, _, _, _ = tile_record(p, 8)
        a2 = np.cumsum(np.full(d.size, 150.0 * 2e-5))
        a1 = a2 + d
        sig = {"alpha1": np.round((a1 + 0.5 * q * rng.standard_normal(d.size)) / q) * q,
               "alpha2": np.round((a2 + 0.5 * q * rng.standard_normal(d.size)) / q) * q}
        out.append((f"enc{bits}/cl/whole", {"trigger": "contact_loss"}, [(0, sig, None)]))
        out.append((f"enc{bits}/cl/1000", {"trigger": "contact_loss"}, chunked(sig, 1000)))
        out.append((f"enc{bits}/paper/1000", {"trigger": "paper", "width_m": 0.0025}, chunked(sig, 1000)))
    # 30 s with a drifting integration (speed bias): re-references and the drift-rate estimate
    p = synthetic_period(width_m=0.005)
    reps = 4
    w1 = np.tile(p.w_rel, reps)
    d1 = np.tile(p.delta, reps)
    n1 = d1.size
    t_local = np.arange(n1) / FS
    for trig, kw in (("paper", {"trigger": "paper", "width_m": 0.005}), ("cl", {"trigger": "contact_loss"})):
        feeds_i = [(c * n1, {"omega1": w1 + 1e-3, "omega2": np.zeros(n1)}, None) for c in range(30)]
        feeds_m = [(c * n1, {"angle_difference": d1 + 1e-3 * (c * n1 / FS + t_local)}, None) for c in range(30)]
        out.append((f"drift30s/{trig}_int", kw, feeds_i))
        out.append((f"drift30s/{trig}_meas", kw, feeds_m))
    return out


_STATE_FLOATS = ("_trk", "_offset", "_drift_rate", "_ema", "_entry_delta", "_int_delta", "_int_w", "_anchor")
_STATE_OTHER = ("_state", "_trav", "_holdoff_end", "_next_index", "_seg_start", "_side", "_offset_valid",
                "_offset_idx", "_last_ref_index", "_source", "n_rereferences")


def _bits(v):
    if isinstance(v, tuple):
        return tuple(_bits(x) for x in v)
    if isinstance(v, (float, np.floating)):
        return struct.pack("<d", float(v)).hex()
    return v


def state_digest(det) -> tuple:
    return tuple(_bits(getattr(det, a, None)) for a in _STATE_FLOATS) + \
        tuple(getattr(det, a, None) for a in _STATE_OTHER)


def run(cls, scenario, states: bool = True):
    """{"entries": [...], "events": [...], "states": [...]} of one scenario fed to a new ``cls`` detector."""
    _, kw, feeds = scenario
    det = cls(**kw)
    entries, digests = [], []
    for first, sig, period in feeds:
        got = det.feed(first, sig, period)
        entries += [(e.sample_index, e.kind, e.trigger, e.confirm_sample_index) for e in got]
        if states:
            digests.append(state_digest(det))
    return {"entries": entries, "events": list(det.events), "n_rereferences": det.n_rereferences,
            "states": digests}
