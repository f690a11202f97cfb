"""LateJoinCheck: a late reader's messages judged as a transient-local writer serves them.

A writer of depth D serves a reader that matches late its history first, oldest first: its whole history
from sequence number 1, or its last D messages; then the live ones. A first message that is live, or one
from the middle of the history (a span shorter than the depth), means the history was passed over.
"""
import pytest

from backlash_monitor.chain.late_join import (HOLD, LIVE_AGE_S, MAX_RESUBSCRIBES, PASS, RELEASE, RESUBSCRIBE,
                                              LateJoinCheck, age_s)

D = 100   # the writer's depth in these cases


def _serve(check, seqs, ages):
    """Offer the messages (their sequence numbers as items) -> the decisions and what was handed on."""
    decisions, handed = [], []
    for seq, age in zip(seqs, ages):
        d = check.offer(seq, seq, age)
        decisions.append(d)
        if d == PASS:
            handed.append(seq)
        elif d == RELEASE:
            handed += check.released
    return decisions, handed


def test_the_writers_whole_history_from_its_first_message_is_handed_on_at_once():
    check = LateJoinCheck(depth=D)
    decisions, handed = _serve(check, range(1, 41), [30.0 - k * 0.5 for k in range(40)])
    assert decisions == [PASS] * 40 and handed == list(range(1, 41))
    assert (check.resubscribes, check.gave_up) == (0, 0)


def test_a_history_cut_by_the_depth_is_held_then_handed_on_whole_in_order():
    # the writer had published 250: its last 100 come as history (old), the newest few of them and the
    # live ones young
    check = LateJoinCheck(depth=D)
    seqs = list(range(151, 261))
    ages = [60.0 - 0.6 * k for k in range(97)] + [0.5, 0.2, 0.01] + [0.003] * 10
    decisions, handed = _serve(check, seqs, ages)
    assert decisions[:97] == [HOLD] * 97 and decisions[97] == RELEASE
    assert decisions[98:] == [PASS] * 12
    assert handed == seqs
    assert check.last_span == 248 - 151 and check.last_release == "whole"
    assert check.resubscribes == 0


def test_a_full_depth_held_is_a_whole_history_even_without_a_young_message():
    check = LateJoinCheck(depth=D)
    decisions, handed = _serve(check, range(500, 600), [100.0] * D)
    assert decisions[-1] == RELEASE and handed == list(range(500, 600))


def test_a_live_first_message_is_a_history_passed_over():
    check = LateJoinCheck(depth=D)
    assert check.offer("w812", 812, 0.004) == RESUBSCRIBE
    assert check.last_span == 0 and check.resubscribes == 1 and check.in_a_row == 1


def test_a_history_from_its_middle_is_passed_over_and_its_messages_dropped():
    # the writer had published 60 (all in its history): the reader got them from 31 on
    check = LateJoinCheck(depth=D)
    decisions, handed = _serve(check, range(31, 61), [20.0 - 0.5 * k for k in range(29)] + [0.01])
    assert decisions == [HOLD] * 29 + [RESUBSCRIBE]
    assert handed == []
    assert check.last_span == 60 - 31


def test_asking_again_is_bounded_then_it_goes_on_with_what_it_holds():
    check = LateJoinCheck(depth=D)
    for k in range(MAX_RESUBSCRIBES):
        check.start()
        assert check.offer(900 + k, 900 + k, 0.01) == RESUBSCRIBE
    check.start()
    assert check.offer(990, 990, 0.01) == RELEASE and check.released == [990]
    assert (check.resubscribes, check.gave_up, check.in_a_row, check.last_release) == (MAX_RESUBSCRIBES, 1, 0,
                                                                                         "gave_up")
    assert check.offer(991, 991, 0.01) == PASS


def test_a_history_delivered_on_asking_again_ends_the_row():
    check = LateJoinCheck(depth=D)
    assert check.offer(812, 812, 0.01) == RESUBSCRIBE
    check.start()
    assert check.offer(1, 1, 40.0) == PASS
    assert (check.resubscribes, check.gave_up, check.in_a_row) == (1, 0, 0)


def test_a_writer_that_falls_silent_is_judged_on_what_came():
    whole = LateJoinCheck(depth=D)
    _serve(whole, range(301, 371), [90.0] * 70)
    assert whole.holding and whole.silent() == RELEASE and whole.released == list(range(301, 371))
    short = LateJoinCheck(depth=D)
    _serve(short, range(301, 311), [90.0] * 10)
    assert short.silent() == RESUBSCRIBE
    assert LateJoinCheck(depth=D).silent() == HOLD        # nothing held: nothing to judge


def test_a_middleware_that_says_nothing_changes_nothing():
    check = LateJoinCheck(depth=D)
    assert check.offer("a", None, None) == PASS
    assert check.offer("b", 7, 0.0) == PASS
    other = LateJoinCheck(depth=D)
    assert other.offer("x", 50, 30.0) == HOLD
    assert other.offer("y", 3, 0.01) == RELEASE and other.released == ["x", "y"]   # another writer's
    assert other.last_release == "unordered" and other.resubscribes == 0


def test_age_from_rmw_time_stamps():
    assert age_s(1_000_000_000, 3_500_000_000) == pytest.approx(2.5)
    assert age_s(0, 3_500_000_000) is None
    assert age_s(1_000_000_000, None) is None
    assert LIVE_AGE_S > 0


def test_bad_settings_name_the_allowed_values():
    with pytest.raises(ValueError, match="allowed: 1 or more"):
        LateJoinCheck(depth=0)
    with pytest.raises(ValueError, match="allowed: > 0 s"):
        LateJoinCheck(live_age_s=0.0)
    with pytest.raises(ValueError, match="allowed: 0 or more"):
        LateJoinCheck(max_resubscribes=-1)
