"""The terms with a memory in a second pass (proposal.MEMORY_SECOND_PASS): run only when the library without them
proposes nothing after the selection ran; they never replace a proposal the first pass made, and their pass's
result and cost are reported (docs/workbench.md "Terms with memory, in a second pass")."""
import numpy as np
import pytest

from backlash_monitor.workbench import candidate_terms, proposal
from backlash_monitor.workbench.proposal import Proposal


def _fake(first: Proposal, second: Proposal):
    calls = []

    def fake(run, up, verdict, memory=False, sensitivities=None):
        calls.append(memory)
        return second if memory else first
    return fake, calls


def test_the_memory_library_is_the_plain_one_and_its_lags():
    plain = {t.name for t in candidate_terms.library(memory=False)}
    with_memory = {t.name: t for t in candidate_terms.library(memory=True)}
    assert plain < set(with_memory)
    added = [with_memory[n] for n in set(with_memory) - plain]
    assert added and all("lag" in t.expression for t in added)
    # each library is its own plug-in file (its own kernel), named by its content
    assert candidate_terms.library_file(False) != candidate_terms.library_file(True)


def test_a_first_pass_proposal_is_kept_and_no_second_pass_runs(monkeypatch):
    first = Proposal(True, "proposed", selection_ran=True, cpu_seconds=10.0)
    fake, calls = _fake(first, Proposal(True, "other", selection_ran=True))
    monkeypatch.setattr(proposal, "_propose", fake)
    out = proposal.propose(None, None, "nothing_explains")
    assert out is first and calls == [False] and out.memory_pass == {}


def test_nothing_stable_without_memory_runs_the_second_pass_and_takes_its_proposal(monkeypatch):
    first = Proposal(False, "no candidate term lowers the held-out events' error stably", selection_ran=True,
                     cpu_seconds=10.0, simulated_sets=40)
    second = Proposal(True, "wheel torque += ...", selection_ran=True, cpu_seconds=25.0, simulated_sets=55)
    fake, calls = _fake(first, second)
    monkeypatch.setattr(proposal, "_propose", fake)
    out = proposal.propose(None, None, "partial")
    assert calls == [False, True]
    assert out is second and out.proposed
    assert out.cpu_seconds == pytest.approx(35.0) and out.simulated_sets == 95     # both passes' cost
    assert out.memory_pass["proposed"] and "after the library without them" in out.reason


def test_nothing_in_either_pass_keeps_the_first_and_says_both(monkeypatch):
    first = Proposal(False, "no candidate term lowers the held-out events' error stably", selection_ran=True,
                     cpu_seconds=10.0)
    second = Proposal(False, "nothing stable either", selection_ran=True, cpu_seconds=20.0)
    fake, calls = _fake(first, second)
    monkeypatch.setattr(proposal, "_propose", fake)
    out = proposal.propose(None, None, "nothing_explains")
    assert calls == [False, True] and out is first and not out.proposed
    assert "nothing stable either" in out.reason and out.cpu_seconds == pytest.approx(30.0)
    assert out.memory_pass == {"proposed": False, "reason": "nothing stable either", "cpu_seconds": 20.0}


def test_a_precondition_that_stops_the_first_pass_stops_the_second(monkeypatch):
    first = Proposal(False, "4 events: too few for a cross-validation over the events (at least 6)")
    fake, calls = _fake(first, Proposal(True, "x", selection_ran=True))
    monkeypatch.setattr(proposal, "_propose", fake)
    assert proposal.propose(None, None, "nothing_explains") is first and calls == [False]


def test_no_second_pass_when_the_memory_terms_are_in_the_library_already(monkeypatch):
    monkeypatch.setattr(candidate_terms, "MEMORY_IN_LIBRARY", True)
    first = Proposal(False, "nothing stable", selection_ran=True)
    fake, calls = _fake(first, Proposal(True, "x", selection_ran=True))
    monkeypatch.setattr(proposal, "_propose", fake)
    assert proposal.propose(None, None, "nothing_explains") is first and calls == [False]


def test_no_proposal_for_a_verdict_that_needs_none(monkeypatch):
    fake, calls = _fake(None, None)
    monkeypatch.setattr(proposal, "_propose", fake)
    assert proposal.propose(None, None, "consistent") is None and calls == [False]


class _Term:
    def __init__(self, name):
        self.name = name


def _simulator(offset=0.0):
    """A stand-in for _evaluate_each: a set's prediction is its coefficient's value (the reference's: ``offset``);
    every set it simulates is logged."""
    log = []

    def evaluate_each(p, sets):
        log.extend(sets)
        return [np.full(3, offset + sum(s.values())) for s in sets]
    return evaluate_each, log


def test_the_second_pass_simulates_only_the_reference_and_its_new_terms(monkeypatch):
    plain = [_Term("a"), _Term("b")]
    both = plain + [_Term("lag")]
    key = {t.name: t.name + ".c" for t in both}
    steps = {"a": 1.0, "b": 2.0, "lag": 3.0}
    evaluate_each, log = _simulator()
    monkeypatch.setattr(proposal, "_evaluate_each", evaluate_each)
    cache: dict = {}
    first = proposal._shared_predictions(None, plain, key, steps, cache)
    assert [float(x[0]) for x in first] == [0.0, 1.0, 2.0] and len(log) == 3
    log.clear()
    second = proposal._shared_predictions(None, both, key, steps, cache)
    assert [float(x[0]) for x in second] == [0.0, 1.0, 2.0, 3.0]
    assert log == [{}, {"lag.c": 3.0}]          # the plain terms' runs taken from the first pass


def test_a_second_pass_whose_reference_differs_simulates_every_term(monkeypatch):
    plain = [_Term("a")]
    both = plain + [_Term("lag")]
    key = {t.name: t.name + ".c" for t in both}
    steps = {"a": 1.0, "lag": 3.0}
    evaluate_each, _ = _simulator()
    monkeypatch.setattr(proposal, "_evaluate_each", evaluate_each)
    cache: dict = {}
    proposal._shared_predictions(None, plain, key, steps, cache)
    evaluate_each, log = _simulator(offset=1e-3)           # another model: its reference moved
    monkeypatch.setattr(proposal, "_evaluate_each", evaluate_each)
    second = proposal._shared_predictions(None, both, key, steps, cache)
    assert {k for s in log for k in s} == {"a.c", "lag.c"}
    assert [float(x[0]) for x in second] == pytest.approx([1e-3, 1.001, 3.001])
