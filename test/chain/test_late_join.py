"""LateJoinCheck: a late reader's history judged as a transient-local writer serves it.

A writer of depth D serves a reader that matches late its history first, oldest first: its whole history
from sequence number 1, or its last D messages; then the live ones. A first message that is live, or one
from the middle of the history (a span shorter than the depth), means the history was passed over.
"""
import pytest

from backlash_monitor.chain.late_join import LIVE_AGE_S, LateJoinCheck, age_s

D = 100   # the writer's depth in these cases


def _serve(check, seqs, ages):
    return [check.offer(seq, age) for seq, age in zip(seqs, ages)]


def test_the_writers_whole_history_from_its_first_message_is_whole_at_once():
    check = LateJoinCheck(depth=D)
    verdicts = _serve(check, range(1, 41), [30.0 - k * 0.5 for k in range(40)])
    assert verdicts == [False] + [None] * 39
    assert check.passed_over == 0 and not check.judging


def test_a_history_cut_by_the_depth_is_whole():
    # the writer had published 250: its last 100 come as history (old), the newest few of them young
    check = LateJoinCheck(depth=D)
    ages = [60.0 - 0.6 * k for k in range(97)] + [0.5, 0.2, 0.01] + [0.003] * 10
    verdicts = _serve(check, range(151, 261), ages)
    assert verdicts[:97] == [None] * 97 and verdicts[97] is False and verdicts[98:] == [None] * 12
    assert check.last_span == 248 - 151 and check.passed_over == 0


def test_a_full_depth_of_old_messages_is_a_whole_history():
    check = LateJoinCheck(depth=D)
    assert _serve(check, range(500, 600), [100.0] * D)[-1] is False


def test_a_live_first_message_is_a_history_passed_over():
    check = LateJoinCheck(depth=D)
    assert check.offer(812, 0.004) is True
    assert (check.passed_over, check.missed_before, check.last_span) == (1, 812, 0)


def test_a_history_from_its_middle_is_passed_over():
    # what the under-load bench showed: the writer had published about 600 (all within its depth), the
    # restarted reader got them from 330 on, the first of them 62 s old
    check = LateJoinCheck(depth=1000)
    verdicts = _serve(check, range(330, 620), [62.4 - 0.2 * k for k in range(289)] + [0.02])
    assert verdicts == [None] * 289 + [True]
    assert (check.passed_over, check.missed_before, check.last_span) == (1, 330, 619 - 330)


def test_a_new_subscription_is_judged_again():
    check = LateJoinCheck(depth=D)
    assert check.offer(812, 0.01) is True
    check.start()
    assert check.offer(1, 40.0) is False
    check.start()
    assert check.offer(2000, 0.01) is True
    assert check.passed_over == 2


def test_a_writer_that_falls_silent_is_judged_on_what_came():
    whole = LateJoinCheck(depth=D)
    _serve(whole, range(301, 371), [90.0] * 70)
    assert whole.judging and whole.silent() is False
    short = LateJoinCheck(depth=D)
    _serve(short, range(301, 311), [90.0] * 10)
    assert short.silent() is True and short.missed_before == 301
    assert LateJoinCheck(depth=D).silent() is None        # nothing came: nothing to judge


def test_a_middleware_that_says_nothing_leaves_the_history_unjudged():
    check = LateJoinCheck(depth=D)
    assert check.offer(None, None) is None and not check.judging
    other = LateJoinCheck(depth=D)
    assert other.offer(50, 30.0) is None and other.judging
    assert other.offer(3, 0.01) is None and not other.judging     # another writer's: nothing to judge by
    assert other.passed_over == 0


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
