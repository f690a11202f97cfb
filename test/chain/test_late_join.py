"""LateJoinCheck: the first message after a subscription tells a delivered history from one passed over.

From how a transient-local writer serves a late reader (docs/graph.md): its history comes first, oldest
first, so the first message is sequence number 1 (the whole history) or one as old as the history's
depth; a live message (a later sequence number, just published) first means the history was passed over.
"""
import pytest

from backlash_monitor.chain.late_join import (ACCEPT, LIVE_AGE_S, MAX_RESUBSCRIBES, RESUBSCRIBE, LateJoinCheck,
                                              age_s)


def test_the_writers_first_message_is_its_whole_history_whatever_its_age():
    check = LateJoinCheck()
    assert check.is_history(1, 0.0) is True
    assert check.first(1, 0.001) == ACCEPT
    assert (check.resubscribes, check.gave_up) == (0, 0)


def test_a_later_message_as_old_as_a_cut_history_is_history():
    check = LateJoinCheck()
    assert check.first(4711, 120.0) == ACCEPT      # the oldest of the last 1000 windows: minutes of stream
    assert check.first(4711, LIVE_AGE_S) == ACCEPT
    assert check.resubscribes == 0


def test_a_live_first_message_asks_again_a_bounded_number_of_times_then_goes_on():
    check = LateJoinCheck()
    decisions = [check.first(812 + k, 0.004) for k in range(MAX_RESUBSCRIBES + 1)]
    assert decisions == [RESUBSCRIBE] * MAX_RESUBSCRIBES + [ACCEPT]
    assert (check.resubscribes, check.gave_up, check.in_a_row) == (MAX_RESUBSCRIBES, 1, 0)
    assert check.last_skipped_sequence == 812 + MAX_RESUBSCRIBES - 1


def test_a_history_delivered_on_asking_again_ends_the_row():
    check = LateJoinCheck()
    assert check.first(812, 0.01) == RESUBSCRIBE
    assert check.first(1, 0.5) == ACCEPT            # the new match got the history
    assert (check.resubscribes, check.gave_up, check.in_a_row) == (1, 0, 0)
    # a later restart of the writer's reader: the count of asks in a row starts again
    assert check.first(2000, 0.01) == RESUBSCRIBE
    assert check.in_a_row == 1


def test_a_middleware_that_says_nothing_changes_nothing():
    check = LateJoinCheck()
    for seq, age in ((None, 0.0), (0, 0.0), (37, None)):
        assert check.is_history(seq, age) is None
        assert check.first(seq, age) == ACCEPT
    assert (check.resubscribes, check.gave_up) == (0, 0)


def test_age_from_rmw_time_stamps():
    assert age_s(1_000_000_000, 3_500_000_000) == pytest.approx(2.5)
    assert age_s(0, 3_500_000_000) is None
    assert age_s(1_000_000_000, None) is None


def test_bad_settings_name_the_allowed_values():
    with pytest.raises(ValueError, match="allowed: > 0 s"):
        LateJoinCheck(live_age_s=0.0)
    with pytest.raises(ValueError, match="allowed: 0 or more"):
        LateJoinCheck(max_resubscribes=-1)
