"""The subscriber's side of shared-memory topics (kame.net.shm.ShmReceiver): what it hands
on, and when it gives the publisher its ring space back."""

from __future__ import annotations

import socket
from collections.abc import Iterator

import pytest

from kame.net import shm
from kame.protocol import shmros

BIG = shm.ACK_EACH
SMALL = 1000


@pytest.fixture
def segment() -> Iterator[shm.Segment]:
    created = shm.create_segment(1 << 22)
    if created is None:
        pytest.skip("no room in /dev/shm")
    yield created
    created.close()
    shm.unlink(created.name)


@pytest.fixture
def pair() -> Iterator[tuple[socket.socket, socket.socket]]:
    publisher, subscriber = socket.socketpair()
    publisher.setblocking(False)
    yield publisher, subscriber
    publisher.close()
    subscriber.close()


def records(segment: shm.Segment, sizes: list[int]) -> list[memoryview]:
    """The MAP record of `segment`, then one DATA record per size (message i's bytes are all i)."""
    frames = [memoryview(shmros.map_record(segment.name, segment.capacity))[4:]]
    ring = shmros.Ring(segment.capacity)
    for number, size in enumerate(sizes):
        offset = ring.place(size)
        assert offset is not None
        segment.view[offset:offset + size] = bytes([number]) * size
        frames.append(memoryview(shmros.data_record(offset, size))[4:])
    return frames


def acks(sock: socket.socket) -> list[int]:
    data = b""
    while True:
        try:
            data += sock.recv(4096)
        except BlockingIOError:
            return [count for (count,) in shmros.ACK.iter_unpack(data)]


def test_a_large_message_is_acknowledged_as_soon_as_it_is_delivered(
        segment: shm.Segment, pair: tuple[socket.socket, socket.socket]) -> None:
    publisher, subscriber = pair
    receiver = shm.ShmReceiver(1 << 22)
    seen: list[tuple[list[int], list[int]]] = []  # (first bytes delivered, acks the publisher had by then)

    def deliver(views: list[memoryview]) -> None:
        seen.append(([view[0] for view in views], acks(publisher)))

    receiver.deliver(records(segment, [BIG, SMALL, SMALL, BIG, SMALL]), deliver, subscriber)
    assert seen == [
        ([0], []),
        ([1, 2, 3], [2]),  # the MAP and the first image: its space is free while the next are read
        ([4], [5]),
    ]
    assert acks(publisher) == [6]
    receiver.close()


def test_the_oldest_beyond_queue_size_are_dropped_and_acknowledged(
        segment: shm.Segment, pair: tuple[socket.socket, socket.socket]) -> None:
    publisher, subscriber = pair
    receiver = shm.ShmReceiver(1 << 22, queue_size=2)
    delivered: list[int] = []
    receiver.deliver(records(segment, [BIG, BIG, BIG, BIG]), lambda views: delivered.extend(v[0] for v in views),
                     subscriber)
    assert delivered == [2, 3]
    assert acks(publisher) == [4, 5]
    receiver.close()


def test_small_messages_are_acknowledged_once_per_batch(
        segment: shm.Segment, pair: tuple[socket.socket, socket.socket]) -> None:
    publisher, subscriber = pair
    receiver = shm.ShmReceiver(1 << 22)
    batches: list[list[int]] = []
    receiver.deliver(records(segment, [SMALL] * 5), lambda views: batches.append([v[0] for v in views]),
                     subscriber)
    assert batches == [[0, 1, 2, 3, 4]]
    assert acks(publisher) == [6]
    receiver.close()
