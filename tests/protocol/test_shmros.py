"""The shared-memory topic protocol's pure parts: negotiation, records, the ring."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kame.protocol import shmros
from kame.protocol.tcpros import FrameReader


def test_negotiation_needs_the_same_token_on_both_sides() -> None:
    mine = shmros.token(1000, "boot", 25, 1)
    assert shmros.offer(None) == {}
    assert shmros.accept(shmros.offer(mine), mine)
    assert not shmros.accept(shmros.offer(shmros.token(1001, "boot", 25, 1)), mine)  # another user
    assert not shmros.accept(shmros.offer(mine), None)  # we opted out
    assert not shmros.accept({}, mine)  # a real ROS subscriber never offers
    assert shmros.accepted({shmros.HEADER_FIELD: shmros.ACCEPTED})
    assert not shmros.accepted({"callerid": "/rospy_publisher"})


def test_records_are_tcpros_frames_that_decode_back() -> None:
    stream = (shmros.inline_prefix(3) + b"abc" + shmros.map_record("kame.1.2.ab", 1 << 20)
              + shmros.data_record(4096, 6220800))
    frames = FrameReader().feed(stream)
    assert [shmros.decode(f) if not isinstance(shmros.decode(f), memoryview) else bytes(shmros.decode(f))
            for f in frames] == [b"abc", shmros.Map("kame.1.2.ab", 1 << 20), shmros.Data(4096, 6220800)]


@pytest.mark.parametrize("record", [b"", b"\x07junk", b"\x01short", b"\x02" + bytes(8)])
def test_unknown_or_short_records_are_refused(record: bytes) -> None:
    with pytest.raises(shmros.ShmError):
        shmros.decode(memoryview(record))


def test_ring_places_in_order_wraps_and_frees_oldest_first() -> None:
    ring = shmros.Ring(1024)
    assert ring.place(300) == 0  # 320 with alignment
    assert ring.place(300) == 320
    assert ring.place(300) == 640
    assert ring.place(100) is None  # 960..1024 is too short, and 0 is still taken
    ring.release()
    assert ring.place(100) == 0  # back to the start, before the oldest (320)
    assert ring.place(200) is None  # 128+256 would run into the oldest, at 320
    assert ring.place(150) == 128  # 192 bytes: up to 320 exactly
    assert ring.place(1) == 960  # the 64 bytes left at the end
    assert ring.place(1) is None  # full
    ring.release()
    ring.release()
    assert ring.place(600) == 320  # the two at 0 and 128 are left: the rest follows them
    for _ in range(4):
        ring.release()
    assert ring.used == 0
    assert ring.place(1024) == 0  # empty: starts over at 0, the whole ring
    assert ring.place(2000) is None


def test_ring_reuses_the_start_as_soon_as_it_is_free() -> None:
    """What the subscriber has just read (still in the CPU's cache) takes the next message:
    a subscriber that keeps up sees the same two slots, not the whole ring in turn."""
    ring = shmros.Ring(5 * 1024)
    starts = []
    for _ in range(6):
        starts.append(ring.place(1000))
        if ring.used == 2:
            ring.release()
    assert starts == [0, 1024, 0, 1024, 0, 1024]


def test_ring_uses_a_gap_between_messages_when_start_and_end_are_taken() -> None:
    ring = shmros.Ring(4096)
    assert [ring.place(1024) for _ in range(4)] == [0, 1024, 2048, 3072]
    ring.release()
    ring.release()  # 0..2048 free
    assert ring.place(2048) == 0
    ring.release()  # 2048..3072 free; 0 and 3072 are taken
    assert ring.place(1024) == 2048
    assert ring.place(1) is None


@settings(max_examples=200)
@given(st.lists(st.one_of(st.integers(1, 3000), st.none()), max_size=60))
def test_ring_never_overlaps_and_refuses_only_when_no_gap_holds_it(steps: list[int | None]) -> None:
    """Random placements (a size) and releases (None) against a byte map of the segment."""
    capacity = 8192
    ring = shmros.Ring(capacity)
    placed: list[tuple[int, int]] = []  # (start, size), oldest first
    for step in steps:
        if step is None:
            if placed:
                ring.release()
                placed.pop(0)
            continue
        size = -(-step // shmros.ALIGN) * shmros.ALIGN
        used = bytearray(capacity)
        for start, taken in placed:
            used[start:start + taken] = b"\x01" * taken
        start = ring.place(step)
        if start is None:
            assert bytes(size) not in used
            continue
        assert start % shmros.ALIGN == 0
        assert used[start:start + size] == bytes(size)
        placed.append((start, size))
    assert ring.used == len(placed)
