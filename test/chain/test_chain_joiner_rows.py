"""chain.joiner.ChunkJoiner.add_rows (analyze on a file without chunks: its chunks joined at once) gives
the ranges that ChunkJoiner.add gives chunk by chunk, and leaves the joiner as those adds leave
it; chunks that do not come as whole ranges one after the other are refused (None), with the
joiner untouched, so that they are added one by one (which counts what is wrong)."""
import math

import numpy as np
import pytest

from backlash_monitor.chain.joiner import ChunkJoiner, JoinedRange

SIGNALS = ("a1", "a2", "angle_difference")
PERIOD = 2e-5


def chunks(n_ranges, size=5, orders=None, gaps=(), first=0):
    """[(signal, first index, period, samples, stamp, frame_id)] of n_ranges whole ranges; the
    signals of range r in orders[r % len(orders)]; a gap of gaps[r] samples before range r."""
    orders = orders or [SIGNALS]
    gaps = dict(gaps)
    out = []
    for r in range(n_ranges):
        first += gaps.get(r, 0)
        for k, name in enumerate(orders[r % len(orders)]):
            samples = np.arange(size, dtype=np.float64) + 100 * r + k
            samples.flags.writeable = False
            out.append((name, first, PERIOD, samples, (r, 1000 * SIGNALS.index(name)), f"f{r}{name}"))
        first += size
    return out


def one_by_one(items, joiner=None):
    joiner = joiner or ChunkJoiner(SIGNALS)
    got = [joiner.add(*item) for item in items]
    return [j for j in got if j is not None], joiner


def at_once(items, joiner=None):
    joiner = joiner or ChunkJoiner(SIGNALS)
    signal = np.array([SIGNALS.index(i[0]) if i[0] in SIGNALS else -1 for i in items], dtype=int)
    firsts = np.array([i[1] for i in items], dtype=np.uint64)
    periods = np.array([i[2] for i in items])
    return joiner.add_rows(signal, firsts, periods, [i[3] for i in items],
                           lambda k: (items[k][4], items[k][5])), joiner


def same(a: JoinedRange, b: JoinedRange) -> bool:
    return (type(a.first_sample_index) is type(b.first_sample_index) is int
            and a.first_sample_index == b.first_sample_index
            and type(a.sample_period_s) is type(b.sample_period_s)
            and (a.sample_period_s == b.sample_period_s
                 or math.isnan(a.sample_period_s) and math.isnan(b.sample_period_s))
            and list(a.arrays) == list(b.arrays)
            and all(a.arrays[k] is b.arrays[k] for k in a.arrays)
            and a.stamp == b.stamp and a.frame_id == b.frame_id
            and a.period_mismatch == b.period_mismatch)


def state(joiner):
    return (dict(joiner.pending), dict(joiner.meta), joiner._end, joiner.dropped_ranges,
            dict(joiner.faults.counts))


@pytest.mark.parametrize("orders", [None, [SIGNALS[::-1]], [("a2", "a1", "angle_difference"),
                                                             ("angle_difference", "a1", "a2"),
                                                             SIGNALS]],
                         ids=["recorder order", "reversed", "mixed"])
@pytest.mark.parametrize("gaps", [(), ((3, 7), (5, 1))], ids=["contiguous", "gaps"])
def test_whole_ranges_join_as_one_by_one(orders, gaps):
    items = chunks(8, orders=orders, gaps=gaps, first=1000)
    want, by_one = one_by_one(items)
    got, at = at_once(items)
    assert len(got) == len(want) == 8
    assert all(same(a, b) for a, b in zip(got, want))
    assert state(at) == state(by_one)
    # and the joiner goes on as after those adds
    more = chunks(2, first=1000 + 8 * 5 + sum(g for _, g in gaps))
    assert all(same(a, b) for a, b in zip(one_by_one(more, at)[0], one_by_one(more, by_one)[0]))
    assert state(at) == state(by_one)


def refused(items, joiner=None):
    joiner = joiner or ChunkJoiner(SIGNALS)
    before = state(joiner)
    got, _ = at_once(items, joiner)
    return got is None and state(joiner) == before


def test_what_does_not_come_as_whole_ranges_is_refused():
    good = chunks(4)
    assert not refused(good)
    assert refused([])
    assert refused(good[:-1])                                   # a range missing a signal
    assert not refused(good[:3] + good[4:5] + good[3:4] + good[5:])    # a range's own order: whole
    assert refused(good[:5] + good[6:7] + good[5:6] + good[7:])    # two ranges interleaved
    assert refused(good[:3] + [good[3]] + good[3:-1])           # a chunk twice
    assert refused([("a3",) + good[0][1:]] + good[1:])          # another signal
    assert refused(good[:3] + chunks(1) + good[3:9])            # index back: a restart
    assert refused(good[:3] + [tuple(good[3][:1]) + (good[3][1] + 1,) + good[3][2:]] + good[4:])
    for k, value in ((2, 1e-5), (2, math.nan)):                 # periods differ, or NaN
        bad = list(good)
        bad[4] = bad[4][:k] + (value,) + bad[4][k + 1:]
        assert refused(bad)
    bad = list(good)
    bad[4] = bad[4][:3] + (np.zeros(4),) + bad[4][4:]           # lengths differ
    assert refused(bad)
    bad = [item[:3] + (np.zeros(0),) + item[4:] for item in good]   # no samples
    assert refused(bad)
    huge = [item[:1] + (2 ** 53 + item[1],) + item[2:] for item in good]   # not a usable index
    assert refused(huge)
    waiting = ChunkJoiner(SIGNALS)
    waiting.add(*chunks(1, first=10_000)[0])                     # a range waits already
    assert refused(good, waiting)
    joined = ChunkJoiner(SIGNALS)
    one_by_one(chunks(1, first=0), joined)                       # the joiner's stream ends at 5
    assert refused(chunks(2, first=3), joined)                   # behind it: a restart or a repeat


@pytest.mark.parametrize("first", [5, 12], ids=["contiguous", "a gap"])
def test_after_earlier_adds_whole_ranges_go_on_as_one_by_one(first):
    """analyze adds a chunk's ranges one by one until the joiner has seen the drive's first a1 chunk
    or a range ends, then the whole ranges at once: add_rows goes on where those adds ended."""
    before = chunks(1, first=0)
    more = chunks(3, first=first)
    by_one, at = ChunkJoiner(SIGNALS), ChunkJoiner(SIGNALS)
    one_by_one(before, by_one)
    one_by_one(before, at)
    want, _ = one_by_one(more, by_one)
    got, _ = at_once(more, at)
    assert got is not None and len(got) == len(want) == 3
    assert all(same(a, b) for a, b in zip(got, want))
    assert state(at) == state(by_one)
