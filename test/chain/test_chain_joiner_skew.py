"""The joiner waits for a signal whose topic runs behind the others (issue 34).

Under load the signals' topics of a reliable stream arrive seconds apart: a chunk that Fast DDS
had to send again, or a topic the executor's round-robin serves after the others' backlog, comes
late but comes. With 16 pending ranges the joiner gave such ranges up as incomplete, and every
late chunk then opened a new range that waited and was dropped again: one 3 s stall of the
windowing process lost the rest of the stream (measured: 109 of 120 onsets, 4074 ranges). A
joiner sized for the queue (pending_ranges_for(1000)) completes every range, in order.
"""
import numpy as np

from backlash_monitor.chain.joiner import MAX_PENDING_RANGES, ChunkJoiner, pending_ranges_for

CHUNK = 1000
PERIOD_S = 2e-5


def chunk(index):
    return np.full(CHUNK, float(index))


def feed_skewed(joiner, behind):
    """a2's chunks run ``behind`` ranges ahead of a1's (both then go on one by one, as a
    round-robin executor takes them); -> the first indices of the ranges completed, in order."""
    done = []
    total = behind + 50
    for k in range(total):
        for name, r in (("a2", k), ("a1", k - behind)):
            if 0 <= r < total:
                out = joiner.add(name, r * CHUNK, PERIOD_S, chunk(r))
                if out is not None:
                    done.append(out.first_sample_index)
    for r in range(total - behind, total):      # a1's backlog drains once a2 has nothing new
        out = joiner.add("a1", r * CHUNK, PERIOD_S, chunk(r))
        if out is not None:
            done.append(out.first_sample_index)
    return done, total


def test_a_reliable_queue_deep_joiner_completes_every_range_of_a_topic_far_behind():
    joiner = ChunkJoiner(("a1", "a2"), max_pending=pending_ranges_for(1000))
    done, total = feed_skewed(joiner, behind=300)
    assert done == [r * CHUNK for r in range(total)]
    assert joiner.dropped_ranges == 0 and joiner.faults.total == 0
    assert joiner.pending_max == 300 + 1 and not joiner.pending   # a2 300 ranges ahead, and the one a1 completes next


def test_the_best_effort_joiner_drops_each_range_once_and_counts_each_late_chunk():
    """Best effort (depth 5): a range missing a chunk is given up after MAX_PENDING_RANGES; the
    late chunk of a range given up is dropped (out_of_order), not kept to be dropped again."""
    assert pending_ranges_for(5) == MAX_PENDING_RANGES
    joiner = ChunkJoiner(("a1", "a2"), max_pending=pending_ranges_for(5))
    behind = 40
    done, total = feed_skewed(joiner, behind=behind)
    assert joiner.dropped_ranges + len(done) == total        # every range: completed or dropped once
    assert joiner.faults.counts["incomplete_range"] == joiner.dropped_ranges
    assert joiner.faults.counts["out_of_order"] == joiner.dropped_ranges
    # what still waited when a1 caught up is completed, in order
    assert done == [r * CHUNK for r in range(total - MAX_PENDING_RANGES, total)]
