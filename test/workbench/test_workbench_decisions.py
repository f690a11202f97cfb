"""The decision rule's honesty about how many candidates it looked at (decisions.family_significance, qualifies):
the winner of a diagnosis is the best of the K candidates screened, so a weakly evidenced winner must stand out from
its uncertainty by more than the best of K null candidates does by chance (docs/workbench.md, "Decisions"). Stand-in
fits and seeded null draws: no simulation."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.special import erfc

from backlash_monitor.workbench import plant_adapter
from backlash_monitor.workbench.decisions import (DELTA_IC_DECISIVE, DELTA_IC_STRONG, SIGNIFICANCE,
                                                  family_significance, qualifies, refusals)
from backlash_monitor.workbench.fitting import FitResult
from backlash_monitor.workbench.model import load_model


@pytest.fixture(scope="module")
def catalogue():
    return plant_adapter.catalogue(load_model(None))


def _spring_fit(change: float, uncertainty: float, delta_ic: float, explained: float = 0.83) -> FitResult:
    """A stand-in fit of the spring stiffness drift (relative change of k, one parameter)."""
    return FitResult("spring_stiffness_drift", ["relative_change"], ["-"], np.array([change]),
                     np.array([uncertainty]), np.zeros(1), (np.array([-0.75]), np.array([3.0])), explained,
                     delta_ic, 0.0, np.zeros((2, 3)), explained, 1)


def _two_sided_tail(z: float) -> float:
    return float(erfc(z / np.sqrt(2.0)))


def test_one_candidate_keeps_the_single_test_and_more_candidates_need_more():
    assert family_significance(1) == pytest.approx(SIGNIFICANCE, abs=1e-12)
    z = [family_significance(k) for k in (1, 2, 5, 29, 100)]
    assert all(b > a for a, b in zip(z, z[1:]))


@pytest.mark.parametrize("k", [2, 7, 29, 60])
def test_the_best_of_k_independent_null_candidates_passes_as_rarely_as_one_passes_the_single_test(k):
    """Sidak: P(max of K independent |z| > z_K) = 1 - (1 - tail(z_K))^K equals the single test's tail(SIGNIFICANCE)."""
    family = 1.0 - (1.0 - _two_sided_tail(family_significance(k))) ** k
    assert family == pytest.approx(_two_sided_tail(SIGNIFICANCE), rel=1e-9)


def test_the_best_of_29_null_candidates_is_a_discovery_at_two_sigma_most_of_the_time_and_not_at_the_family_z():
    """Seeded null draws, 29 candidates (the catalogue's count) each with z ~ N(0, 1): the best one's |z| exceeds
    SIGNIFICANCE in about 1 - (1 - 0.0455)^29 = 74 % of the recordings (the look-elsewhere effect), the family-wise
    threshold in about 4.55 %, as one candidate at SIGNIFICANCE."""
    rng = np.random.default_rng(20261129)
    n, k = 20000, 29
    best = np.max(np.abs(rng.standard_normal((n, k))), axis=1)
    single = _two_sided_tail(SIGNIFICANCE)
    se = np.sqrt(single * (1 - single) / n)
    assert np.mean(best > SIGNIFICANCE) == pytest.approx(1 - (1 - single) ** k, abs=0.02)
    assert abs(np.mean(best > family_significance(k)) - single) < 4 * se


def test_a_weak_best_of_many_at_two_and_a_half_sigma_is_no_discovery_and_a_true_weak_effect_is(catalogue):
    """The fifth sealed half's clean drive: the best of the 29 candidates screened, a spring stiffness drift
    100 -> 81 +- 8 N/m (z 2.4) explaining 83 % at delta_ic -3.9, was a discovery under the single test; as the best
    of 29 it is not. A weak effect that stands out beyond the best of 29 null candidates (z 4) still qualifies, and
    so does any effect with decisive evidence (its test is the IC)."""
    spring = next(c for c in catalogue if c.name == "spring_stiffness_drift")
    k = len(catalogue)
    null_best = _spring_fit(-0.19, 0.08, -3.9)
    assert qualifies(null_best, spring, n_candidates=1)           # the single test: a false discovery
    assert not qualifies(null_best, spring, n_candidates=k)
    true_weak = _spring_fit(-0.32, 0.08, -6.0)
    assert DELTA_IC_STRONG < -true_weak.delta_ic < DELTA_IC_DECISIVE
    assert qualifies(true_weak, spring, n_candidates=k)
    decisive = _spring_fit(-0.19, 0.08, -40.0)
    assert qualifies(decisive, spring, n_candidates=k)


def test_a_synthetic_candidate_table_of_null_fits_gives_no_winner_and_a_true_effect_among_them_wins(catalogue):
    """A table of K null candidates (seeded z ~ N(0, 1), each a weak delta_ic): under the single test the best one
    qualifies when its |z| > 2, under the family-wise rule none does; a true weak effect at a z above the corrected
    threshold added to the same table qualifies."""
    spring = next(c for c in catalogue if c.name == "spring_stiffness_drift")
    k = len(catalogue)
    rng = np.random.default_rng(7)
    for _ in range(20):
        z = rng.standard_normal(k)
        z[np.argmax(np.abs(z))] = 2.5 * np.sign(z[np.argmax(np.abs(z))])   # the best of them at z 2.5
        table = [_spring_fit(0.05 * zi, 0.05, -3.0) for zi in z]
        assert any(qualifies(f, spring, n_candidates=1) for f in table)
        assert not any(qualifies(f, spring, n_candidates=k) for f in table)
    z_true = family_significance(k) + 0.5
    assert qualifies(_spring_fit(0.05 * z_true, 0.05, -8.0), spring, n_candidates=k)


def test_each_reason_against_a_candidate_is_named_in_words_and_none_when_it_qualifies(catalogue):
    """diagnose's `nothing_explains` message says why its best candidate was not taken (decisions.refusals): the
    reasons are the rule's own conditions, one each, and a candidate that qualifies has none."""
    spring = next(c for c in catalogue if c.name == "spring_stiffness_drift")
    k = len(catalogue)
    assert refusals(_spring_fit(-0.32, 0.08, -40.0), spring, n_candidates=k) == []
    look_elsewhere = refusals(_spring_fit(-0.19, 0.08, -3.9), spring, n_candidates=k)
    assert len(look_elsewhere) == 1
    assert f"best of {k} candidates" in look_elsewhere[0] and "z 2.38" in look_elsewhere[0]
    assert f"{family_significance(k):.2f}" in look_elsewhere[0]
    no_evidence = refusals(_spring_fit(-0.32, 0.08, -1.0, explained=0.2), spring, n_candidates=k)
    assert any("no evidence" in r for r in no_evidence) and any("less than 50%" in r for r in no_evidence)
    pinned = _spring_fit(-0.32, 0.08, -40.0)
    pinned.at_bound = True
    assert refusals(pinned, spring, n_candidates=k) == ["fitted at the bound of its range"]
