"""Small measurements on simulated chunks, shared by the tests, the benchmark, the CLI and the docs."""
from __future__ import annotations

import numpy as np


def far_side_impact_samples(delta: np.ndarray, beta: float, entry_offset: int, kind: str, window: int = 2048):
    """Samples from an entry to the first sample in contact on the far side (Delta <= -beta after an
    onset entry, Delta >= beta after a return entry), within ``window`` samples; None if none.

    ``delta``: one scenario's angle difference; ``entry_offset``: the entry's index into ``delta``.
    """
    seg = delta[entry_offset:entry_offset + window]
    hit = np.flatnonzero(seg <= -beta) if kind == "onset" else np.flatnonzero(seg >= beta)
    return int(hit[0]) if hit.size else None


def impact_times_ms(chunk, betas, kind: str = "onset", window: int = 2048) -> list[list[float]]:
    """Per scenario: the far-side impact time [ms] after each entry of ``kind`` in the chunk."""
    out = []
    for i, entries in enumerate(chunk.entries):
        times = []
        for k, kd in entries:
            if kd != kind:
                continue
            off = k - chunk.first_sample_index
            j = far_side_impact_samples(chunk.angle_difference[i], betas[i], off, kd, window)
            if j is not None and off + window <= chunk.n_samples:
                times.append(j * chunk.sample_period_s * 1e3)
        out.append(times)
    return out


def windows(chunk, signal: str, kind: str | None = "onset", window: int = 2048) -> list[list[np.ndarray]]:
    """Per scenario: the complete ``window``-sample windows of ``signal`` that start at each entry."""
    data = getattr(chunk, signal)
    out = []
    for i, entries in enumerate(chunk.entries):
        ws = []
        for k, kd in entries:
            off = k - chunk.first_sample_index
            if (kind is None or kd == kind) and off + window <= chunk.n_samples:
                ws.append(data[i, off:off + window])
        out.append(ws)
    return out
