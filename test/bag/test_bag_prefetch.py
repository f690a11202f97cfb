"""BagReader.messages decompresses chunks ahead in a worker thread (prefetch.py, ``chunks_ahead``
per reader): the same messages, in the same order, as decompressing chunk by chunk; a corrupt
chunk raises (or is skipped with recover) where it did; stopping early and closing the reader
leaves nothing running on the file's map; a forked child has its own thread."""
import os
import threading

import pytest

from backlash_monitor.bag import BagReader
from backlash_monitor.bag import prefetch
from backlash_monitor.bag import reader as reader_module
from backlash_monitor.bag.errors import CorruptBagError
from backlash_monitor.bag.records import CHUNK_HEAD

from bag_helpers import write_sample_bag


@pytest.fixture(scope="module")
def small_chunk_bag(tmp_path_factory):
    path = tmp_path_factory.mktemp("prefetch") / "b.mcap"
    written = write_sample_bag(path, n_chunks=40, chunk_size=64 * 1024)  # many chunks
    return path, written


def keys(messages):
    return [(m.topic, m.log_time_ns, m.sequence, m.data) for m in messages]


@pytest.mark.parametrize("ahead", [0, 1, 2, 5])
def test_same_messages_as_chunk_by_chunk(small_chunk_bag, ahead):
    path, written = small_chunk_bag
    with BagReader(path, chunks_ahead=ahead) as bag:
        assert len(bag.chunks) > 5
        got = keys(bag.messages())
        by_topic = keys(bag.messages(["/plant/a2", "/estimate"]))
    # reference: the mcap library's reader, in file order (no thread, no shared parsing code)
    from mcap.reader import make_reader

    with open(path, "rb") as f:
        ref = [(ch.topic, m.log_time, m.sequence, bytes(m.data))
               for _s, ch, m in make_reader(f).iter_messages(log_time_order=False)]
    assert got == ref
    assert by_topic == [k for k in ref if k[0] in ("/plant/a2", "/estimate")]
    assert sum(len(v) for v in written.values()) == len(got)


def test_stop_early_then_close(small_chunk_bag):
    path, _ = small_chunk_bag
    bag = BagReader(path)
    it = bag.messages()
    for _ in range(3):
        next(it)
    it.close()                 # the worker's chunks are finished or cancelled here
    bag.close()
    assert bag._mm == b""      # the map was closed (no view left in use)
    names = [t.name for t in threading.enumerate()]
    assert sum(n.startswith("bag-decompress") for n in names) <= 1   # one, idle, for the next


def test_each_reader_its_own_setting(small_chunk_bag):
    """Two readers at once, one without a thread: neither setting leaks into the other."""
    path, _ = small_chunk_bag
    with BagReader(path, chunks_ahead=0) as plain, BagReader(path, chunks_ahead=3) as ahead:
        assert keys(plain.messages()) == keys(ahead.messages())
        assert plain._prefetcher.chunks_ahead == 0 and ahead._prefetcher.chunks_ahead == 3
        assert not plain._prefetcher.started and ahead._prefetcher.started
    with pytest.raises(ValueError, match="chunks_ahead"):
        BagReader(path, chunks_ahead=-1)


@pytest.mark.parametrize("cpus, load, ahead", [
    (1, 0.0, 0),                          # one CPU: nothing to run the thread on
    (2, 0.3, prefetch.DEFAULT_CHUNKS_AHEAD),   # a quiet machine: a core is free
    (2, 1.2, prefetch.DEFAULT_CHUNKS_AHEAD),   # this process and a little more
    (2, 1.6, 0),                          # within FREE_CORE_MARGIN of the CPUs: none free
    (2, 3.0, 0),                          # two other busy processes and this one
    (8, 3.0, prefetch.DEFAULT_CHUNKS_AHEAD),
    (8, 7.6, 0),
])
def test_the_default_takes_a_thread_only_when_a_core_is_free(monkeypatch, cpus, load, ahead):
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: set(range(cpus)))
    monkeypatch.setattr(os, "cpu_count", lambda: cpus)
    monkeypatch.setattr(os, "getloadavg", lambda: (load, load, load))
    assert prefetch.default_chunks_ahead() == ahead
    assert prefetch.ChunkPrefetcher().chunks_ahead == ahead
    assert prefetch.ChunkPrefetcher(2).chunks_ahead == 2      # a reader's own setting stays


def test_a_forked_child_reads_with_its_own_thread(small_chunk_bag):
    """The parent's worker thread is not copied by fork: the child must not wait for it."""
    path, _ = small_chunk_bag
    with BagReader(path, chunks_ahead=2) as bag:
        expected = len(keys(bag.messages()))    # the parent's thread exists now
    r, w = os.pipe()
    pid = os.fork()
    if pid == 0:   # the child: read with prefetch, report the count, never return into pytest
        try:
            with BagReader(path, chunks_ahead=2) as bag:
                os.write(w, str(len(keys(bag.messages()))).encode())
        finally:
            os._exit(0)
    os.close(w)
    _, status = os.waitpid(pid, 0)
    got = os.read(r, 64).decode()
    os.close(r)
    assert status == 0 and got == str(expected)


def test_corrupt_chunk_raises_at_its_place(small_chunk_bag, monkeypatch):
    path, _ = small_chunk_bag
    with BagReader(path) as bag:
        all_messages = keys(bag.messages())
        bad = bag.chunks[3]
        in_bad = [k for k in all_messages if bad.start <= k[1] <= bad.end]
        before = all_messages[:all_messages.index(in_bad[0])]
        real = reader_module.chunk_records

        def failing(body):
            if CHUNK_HEAD.unpack_from(body, 0)[0] == bad.start:
                raise CorruptBagError("chunk CRC mismatch")
            return real(body)

        monkeypatch.setattr(reader_module, "chunk_records", failing)
        seen = []
        with pytest.raises(CorruptBagError):
            for m in bag.messages():
                seen.append(m)
        assert keys(seen) == before
        bag.recover = True        # recovery mode skips the corrupt chunk and reads on
        assert keys(bag.messages()) == [k for k in all_messages if k not in in_bad]


def test_a_second_pass_starts_with_the_last_chunk_unchanged(small_chunk_bag, monkeypatch):
    """As analyze reads the latched true width (first chunk only), then the signals."""
    path, _ = small_chunk_bag
    calls = []
    real = reader_module.chunk_records

    def counting(body):
        calls.append(CHUNK_HEAD.unpack_from(body, 0)[0])
        return real(body)

    monkeypatch.setattr(reader_module, "chunk_records", counting)
    with BagReader(path) as bag:
        first_chunk = min(bag.chunks, key=lambda c: c.start)
        head = keys(bag.messages(end_ns=first_chunk.end))
        assert calls == [first_chunk.start]
        everything = keys(bag.messages())
        assert everything[:len(head)] == head and len(everything) == bag.message_count
        assert calls.count(first_chunk.start) == 1 and len(calls) == len(bag.chunks)
    assert bag._last_chunk is None                    # close() drops it
