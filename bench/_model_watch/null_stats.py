"""The model's own statistics under the watch's test: why a clean drive's windows exceed (docs/model_watch.md, "The
alarm rule"). Per grid point of the clean drives, from the reference's own K x E model events:

- ``loso_t2_over_q``: each seed's 16-event mean against the other seeds' mean and covariance (leave one seed out),
  T^2 / q, averaged over the K seeds, beside the expectation of Hotelling's predictive law for that covariance,
  dof / (dof - q - 1) (chi^2 says 1): the whitening is an estimate;
- ``lag1_autocorrelation``: of the events' whitened coordinates within a seed, pooled (independent events: ~-1/E);
  ``between_over_within``: the seeds' means' spread x E over the events' (1: no seed-level component);
- ``reference_event_max``: the largest single-event |u|^2 among the reference's events;

and from a stream of the model (own simulator, ``stream_s`` at that point, its own seed): every event's whitened
event-average deviation |u|^2 (q dimensions, chi^2_q for Gaussian events): the share beyond chi^2's 1e-4 radius
(Gaussian: 1e-4) and the largest. Events are the units throughout (not samples).
"""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np
from scipy import stats


def _event_vectors(ref, window):
    from backlash_monitor.workbench import consistency, spectral
    comp = SimpleNamespace(ensemble=SimpleNamespace(per_event=ref.seed_events,
                                                    dc_samples=lambda k: np.asarray(ref.seed_dc[k])[:, :2]),
                           weights=window.w,
                           model_event_spec=spectral.sensor_chain(ref.seed_events, ref.sample_period_s,
                                                                  window.noise_psd, window.quant_step)[0])
    return consistency.model_event_vectors(comp, window)


def reference_statistics(ref) -> dict:
    window = ref.for_window(np.zeros(2), ref.build_events, ("a1", "a2"))
    views = window.views
    z = _event_vectors(ref, window)
    k = len(ref.seed_events)
    seed_of = np.repeat(np.arange(k), [s.shape[0] for s in ref.seed_events])
    out = {}
    for name, sl in views.blocks:
        if name == "record_mean":
            continue
        raw_basis = dict(views.candidate_directions)[name]
        u = z @ views.basis[:, sl]
        q = u.shape[1]
        num = den = 0.0
        for s in range(k):
            us = u[seed_of == s] - u[seed_of == s].mean(axis=0)
            num += float(np.sum(us[1:] * us[:-1]))
            den += float(np.sum(us * us)) * (len(us) - 1) / len(us)
        means = np.stack([u[seed_of == s].mean(axis=0) for s in range(k)])
        t2 = []
        for s in range(k):
            train, test = z[seed_of != s] @ raw_basis, z[seed_of == s] @ raw_basis
            d = test.mean(axis=0) - train.mean(axis=0)
            cov = np.cov(train, rowvar=False).reshape(q, q)
            t2.append(float(d @ np.linalg.solve((1 / len(test) + 1 / len(train)) * cov, d)))
        dof = int(np.sum(seed_of != 0)) - 1
        out[name] = {"q": q, "loso_t2_over_q": round(float(np.mean(t2)) / q, 3),
                     "hotelling_expectation_over_q": round(dof / (dof - q - 1), 3),
                     "lag1_autocorrelation": round(num / den, 3),
                     "between_over_within": round(float(np.mean(np.var(means, axis=0, ddof=1))
                                                        * ref.build_events), 3),
                     "reference_event_max": round(float(np.max(np.sum(u * u, axis=1))), 1)}
    return out


def stream_tails(ref, grid, seed: int, stream_s: float) -> dict:
    from backlash_monitor.plant import PlantSimulator, Scenario
    from backlash_monitor.watch.events import LiveEvents
    from backlash_monitor.workbench.model import load_model
    width, eta_k, n1 = grid
    sim = PlantSimulator([Scenario(width_m=width, eta_k=eta_k, n1=n1, seed=seed)],
                         config=load_model(None).plant_config(None), outputs=("a1", "a2", "angle_difference"))
    live = LiveEvents(ref.sample_period_s, ref.pulse_period_samples)
    events = []
    for _ in range(int(round(stream_s / 0.02))):
        ch = sim.run(1000)
        events += live.feed(ch.first_sample_index, ch.a1[0], ch.a2[0], ch.angle_difference[0])
    window = ref.for_window(np.zeros(2), ref.build_events, ("a1", "a2"))
    sl = dict(window.views.blocks)["event_average"]
    basis = window.views.basis[window.event_slice, sl]
    dev = np.stack([(e.denoised * window.w[:, None]).ravel() for e in events]) - window.base[window.event_slice]
    d2 = np.sum((dev @ basis) ** 2, axis=1)
    q = basis.shape[1]
    radius2 = float(stats.chi2.isf(1e-4, q))
    return {"events": len(events), "q": q, "median_u2": round(float(np.median(d2)), 2),
            "share_beyond_chi2_1e-4": round(float(np.mean(d2 > radius2)), 4), "largest_u2": round(float(d2.max()), 1)}


def null_statistics(grid_points, reference_for, stream_s: float = 60.0, log=print) -> dict:
    rows = []
    for i, g in enumerate(grid_points):
        ref = reference_for(*g)
        row = {"grid": list(g), **reference_statistics(ref), "stream": stream_tails(ref, g, 6000 + i, stream_s)}
        log(f"null: {g}: {row}")
        rows.append(row)
    ev = [r["event_average"] for r in rows]
    return {"null_per_grid_point": rows,
            "null_loso_t2_over_q_mean": round(float(np.mean([e["loso_t2_over_q"] for e in ev])), 3),
            "null_hotelling_expectation_over_q_mean": round(float(np.mean([e["hotelling_expectation_over_q"]
                                                                           for e in ev])), 3),
            "null_event_share_beyond_chi2_1e-4_max": max(r["stream"]["share_beyond_chi2_1e-4"] for r in rows),
            "null_event_largest_u2": max(r["stream"]["largest_u2"] for r in rows)}
