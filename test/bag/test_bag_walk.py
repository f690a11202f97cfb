"""walk_data over a data section of unchunked Message records (a file written without chunks):
its own loop for a run of messages (index._message_run) lays out what the record-by-record walk
(the one that counts messages) lays out, and gives up (None: the file is damaged, integrity.py
scans it) on the same damage: a message running past the data section, one too short for its
head, a zero opcode."""
from __future__ import annotations

import pytest

from backlash_monitor.bag import BagReader
from backlash_monitor.bag.index import BagIndex, walk_data
from backlash_monitor.bag.records import OP_MESSAGE, RECORD_HEADER

from bag_helpers import write_sample_bag
from mcap_conformance import rewrite_with_mcap


@pytest.fixture(scope="module")
def unchunked(tmp_path_factory):
    folder = tmp_path_factory.mktemp("walk")
    write_sample_bag(folder / "chunked.mcap", n_chunks=40)
    path = rewrite_with_mcap(folder / "chunked.mcap", folder / "unchunked.mcap", noChunking=True)
    with BagReader(path) as bag:
        bounds = bag._index.data_start, bag._index.data_end
    return path.read_bytes(), bounds


def walks(data: bytes, bounds) -> list:
    """The layouts (op, offset, body bytes) of the walk without and with counting, or None."""
    out = []
    for count in (False, True):
        index = BagIndex(data_start=bounds[0], data_end=bounds[1])
        walk = walk_data(memoryview(data), index, count=count)
        out.append(None if walk is None else [(op, pos, bytes(body)) for op, pos, body in index.layout])
    return out


def message_offsets(data: bytes, bounds) -> list[int]:
    index = BagIndex(data_start=bounds[0], data_end=bounds[1])
    walk_data(memoryview(data), index, count=False)
    return [pos for op, pos, _ in index.layout if op == OP_MESSAGE]


def test_a_run_of_messages_is_laid_out_as_record_by_record(unchunked):
    data, bounds = unchunked
    fast, counted = walks(data, bounds)
    assert fast == counted and len(fast) == 40 * 5 + 4 + 4 + 4   # every message, in file order
    assert all(op == OP_MESSAGE for op, _, _ in fast)


@pytest.mark.parametrize("where", [0, 1, 77, -1])
@pytest.mark.parametrize("damage", ["past the end", "too short", "zero opcode"])
def test_damage_in_a_run_is_found_as_record_by_record(unchunked, where, damage):
    data, bounds = unchunked
    pos = message_offsets(data, bounds)[where]
    broken = bytearray(data)
    op, length = RECORD_HEADER.unpack_from(data, pos)
    if damage == "past the end":
        RECORD_HEADER.pack_into(broken, pos, op, bounds[1])
    elif damage == "too short":   # 21 bytes, the rest of it a private record (skipped)
        RECORD_HEADER.pack_into(broken, pos, op, 21)
        RECORD_HEADER.pack_into(broken, pos + 30, 0x80, length - 21 - 9)
    else:
        broken[pos] = 0
    assert walks(bytes(broken), bounds) == [None, None]
