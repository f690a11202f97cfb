"""The proposed term's form (proposal._form_stage, candidate_terms.hinge_terms; docs/workbench.md "The proposed term's
form"): a limiter caps the contact torque, a deadband or a limit clips a speed -- hinges max(0, ±(s - k)) of the
selected term's own state, at knots at quantiles of that state over the events, entered by the selection's own rule
(leave-one-event-out CV, stability under the events' resampling) on top of the groups already chosen."""
import os

import numpy as np

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from backlash_monitor.workbench import candidate_terms, proposal      # noqa: E402

P0 = candidate_terms.PENETRATION_SCALE_RAD


def _hinge(var: str, side: str, slot: int):
    return candidate_terms.by_name()[f"cand_{candidate_terms.SHORT[candidate_terms.HINGE_STATES[var].balance]}_"
                                     f"{var}_hinge_{side}{slot}"]


def _value(term, state: np.ndarray) -> np.ndarray:
    """The hinge's f on a known state (its expression with the knot written as a number, evaluated in numpy)."""
    return eval(term.expression, {"fabs": np.abs, candidate_terms.HINGE_STATES["penetration"].expression: state})


def test_a_hinge_is_zero_on_one_side_of_its_knot_and_the_state_past_it_on_the_other():
    """The penetration uniform over 0..10 mrad in the events: the knots are its 10, 50, 90 % quantiles (1, 5, 9 mrad);
    max(0, p - k)/p0 is 0 up to the knot and (p - k)/p0 past it, max(0, k - p)/p0 the mirror, and each side is non-zero
    on the share of the events' samples beyond its knot."""
    p = np.linspace(0.0, 0.01, 10001)
    knots = candidate_terms.hinge_knots({"penetration": p})["penetration"]
    assert np.allclose(knots, [0.001, 0.005, 0.009], atol=1e-9)
    for slot, q in enumerate(candidate_terms.HINGE_QUANTILES):
        k = knots[slot]
        up = _value(candidate_terms.with_knot(_hinge("penetration", "above", slot), k), p)
        down = _value(candidate_terms.with_knot(_hinge("penetration", "below", slot), k), p)
        assert np.all(up[p <= k] == 0.0) and np.allclose(up[p > k], (p[p > k] - k) / P0)
        assert np.all(down[p >= k] == 0.0) and np.allclose(down[p < k], (k - p[p < k]) / P0)
        assert abs(np.mean(up > 0) - (1 - q)) < 1e-3 and abs(np.mean(down > 0) - q) < 1e-3
        assert np.allclose(up - down, (p - k) / P0)          # the two sides together: the straight line through k


def test_a_hinge_is_written_with_its_knot_as_a_number_in_the_law_and_the_plugin():
    k = 0.0042
    term = candidate_terms.with_knot(_hinge("penetration", "above", 2), k)
    piece = candidate_terms.ProposedPiece((term,), (-12.0,), (1.0,))
    assert candidate_terms.proposal_law([piece]) == "clutch torque += -12 N·m · max(0, p − 0.0042)/0.003"
    src, values = candidate_terms.proposal_source([piece])
    assert "(penetration - (0.0042))" in src and values == {"proposed_term_clutch": {"c0_Nm": -12.0}}
    assert "(-200.0, 200.0)" in src                    # the coefficient bounded as the balance's


def _capped_design(seed: int, truth_scale: float):
    """16 events, each one contact: the penetration rises and falls over 40 samples to a peak that differs from event
    to event. A clutch term's whitened response is taken as its value along the event (a static balance). The library's
    groups: the preload (1), p/p0, (p/p0)^2; the hinges of p at its knots. The residual the model leaves: a limiter
    that caps the contact, -k_c * max(0, p - p_cap) (p_cap at the 85 % quantile, between two knots), times
    ``truth_scale``, plus the events' own noise."""
    rng = np.random.default_rng(seed)
    e, n = 16, 40
    peak = 0.006 * rng.uniform(0.6, 1.4, size=e)
    p = peak[:, None] * np.sin(np.pi * (np.arange(n) + 0.5) / n)[None] ** 2          # (E, D)
    knots = candidate_terms.hinge_knots({"penetration": p.ravel()})["penetration"]
    hinges = [t for t in candidate_terms.hinges_for(["penetration"])]
    cols = [np.ones_like(p), p / P0, (p / P0) ** 2]
    cols += [_value(candidate_terms.with_knot(t, knots[candidate_terms.hinge_slot(t)]), p) for t in hinges]
    G = np.stack(cols, axis=-1)                                                        # (E, D, M)
    cap = float(np.quantile(p, 0.85))
    truth = -3000.0 * np.maximum(0.0, p - cap) / 20.0 * truth_scale                    # N*m by T_b: whitened units
    Y = truth + 0.05 * rng.normal(size=p.shape)
    groups = [[i] for i in range(G.shape[-1])]
    alike = [[0], [1], [2]] + proposal.hinge_alike(hinges, 3)
    return G, Y, groups, alike, hinges


def test_on_a_capped_contact_a_hinge_of_the_penetration_enters_over_its_plain_square():
    """On top of p/p0 (the group the selection chose), with (p/p0)^2 and the hinges as candidates: the hinge above the
    cap's side enters (its knot the 90 % quantile, the nearest to the cap), stable in the resamples; the square,
    a smooth curvature over the whole contact, does not."""
    G, Y, groups, alike, hinges = _capped_design(7, 1.0)
    added, steps, freq = proposal.select_on_top(G, Y, groups, [1], [2] + list(range(3, len(groups))), alike)
    assert added and added[0] >= 3
    first = hinges[added[0] - 3]
    assert first.knot == "penetration" and first.name.endswith("above2")
    assert freq[added[0]] >= proposal.STABILITY and steps[0][2] > proposal.CV_Z
    assert 2 not in added


def test_on_noise_alone_no_hinge_enters():
    """The same design, the residual the events' noise alone: over 20 draws at most one hinge enters."""
    false = 0
    for k in range(20):
        G, Y, groups, alike, _ = _capped_design(100 + k, 0.0)
        added, _, _ = proposal.select_on_top(G, Y, groups, [1], list(range(3, len(groups))), alike)
        false += len(added)
    assert false <= 1


def test_switched_on_the_librarys_plugin_file_holds_every_hinge_neutral_with_a_bounded_knot(monkeypatch):
    """candidate_terms.HINGES_IN_PROPOSAL on: the library's plug-in file (the kernel the proposal screens) holds every
    hinge as an effect of its balance, its coefficient neutral at 0 and its knot a bounded parameter set per recording."""
    from backlash_monitor.plant.catalogue import builtin_catalogue
    monkeypatch.setattr(candidate_terms, "HINGES_IN_PROPOSAL", True)
    cat = builtin_catalogue().with_files([candidate_terms.library_file()])
    for t in candidate_terms.hinge_terms():
        params = cat[t.name].parameters
        assert params[0].default == 0.0 and params[1].name == candidate_terms.KNOT
        lo, hi = candidate_terms.HINGE_STATES[t.knot].bounds
        assert lo < 0.0 < hi
