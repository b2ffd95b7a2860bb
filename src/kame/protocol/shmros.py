"""Shared-memory topics between kame nodes on one host: the negotiation, the records, the ring.

Rules:
- Negotiated in the TCPROS connection header. A kame subscriber that may use shared memory
  adds `kame_shm=<token>` (who it is and which /dev/shm it sees: user, boot, the tmpfs); a kame
  publisher whose own token is the same answers `kame_shm=1` and from then on speaks this
  module's stream on that connection. Real ROS peers ignore the unknown field, never answer
  it, and so keep plain TCPROS.
- The TCP connection stays: it carries every record in order, wakes the subscriber and brings
  back its acknowledgements, so queue_size, latching and disconnects work as over TCPROS.
  Each record is one TCPROS frame whose first byte says what it is: INLINE (the message
  itself follows: small messages are cheaper on the socket than through a descriptor), DATA
  (offset and length of a message in the current segment), MAP (the segment from now on:
  its file name and size; the one before it ends with it).
- The subscriber answers with a running count of the DATA and MAP records it is done with
  (a little-endian u64): the publisher then reuses their space. Nothing else goes that way.
- Payloads live in a ring: `Ring` places messages one after the other and frees them in the
  order they were sent (the order the subscriber acknowledges them).
"""

from __future__ import annotations

import bisect
import struct
from collections import deque
from typing import NamedTuple

HEADER_FIELD = "kame_shm"
ACCEPTED = "1"

INLINE = 0
DATA = 1
MAP = 2

_DATA = struct.Struct("<BQI")  # kind, offset, length
_MAP = struct.Struct("<BQ")  # kind, capacity; the segment's name follows
_PREFIX = struct.Struct("<I")
ACK = struct.Struct("<Q")
ALIGN = 64  # payloads start on cache lines: memcpy in and out runs at full speed


class ShmError(Exception):
    """A record that is not this protocol (a corrupt stream or a peer that is not kame)."""


class Data(NamedTuple):
    offset: int
    length: int


class Map(NamedTuple):
    name: str
    capacity: int


def token(uid: int, boot_id: str, shm_device: int, shm_inode: int) -> str:
    """Who may share memory with whom: the same user (segments are private to it), the same
    boot (the same kernel) and the same /dev/shm file system (not another container's)."""
    return f"{uid}:{boot_id}:{shm_device}:{shm_inode}"


def offer(local_token: str | None) -> dict[str, str]:
    """The subscriber's header field, or none when it will not use shared memory."""
    return {HEADER_FIELD: local_token} if local_token else {}


def accept(header: dict[str, str], local_token: str | None) -> bool:
    """The publisher's decision: the subscriber offered, and it sees what we see."""
    return bool(local_token) and header.get(HEADER_FIELD) == local_token


def accepted(reply: dict[str, str]) -> bool:
    """The subscriber's reading of the publisher's reply."""
    return reply.get(HEADER_FIELD) == ACCEPTED


def inline_prefix(length: int) -> bytes:
    """The frame prefix and kind byte of an INLINE record carrying `length` payload bytes."""
    return _PREFIX.pack(length + 1) + b"\x00"


def data_record(offset: int, length: int) -> bytes:
    return _PREFIX.pack(_DATA.size) + _DATA.pack(DATA, offset, length)


def map_record(name: str, capacity: int) -> bytes:
    encoded = name.encode()
    return _PREFIX.pack(_MAP.size + len(encoded)) + _MAP.pack(MAP, capacity) + encoded


def decode(frame: memoryview) -> memoryview | Data | Map:
    """One record (a TCPROS frame's payload): an inline message's bytes, or a DATA or MAP."""
    if not len(frame):
        raise ShmError("empty record")
    kind = frame[0]
    if kind == INLINE:
        return frame[1:]
    if kind == DATA and len(frame) == _DATA.size:
        _, offset, length = _DATA.unpack(frame)
        return Data(offset, length)
    if kind == MAP and len(frame) > _MAP.size:
        _, capacity = _MAP.unpack_from(frame)
        try:
            return Map(str(frame[_MAP.size:], "ascii"), capacity)
        except UnicodeDecodeError as exc:
            raise ShmError("a segment name that is not ASCII") from exc
    raise ShmError(f"unknown record (kind {kind}, {len(frame)} bytes)")


def payload_length(parts: list[memoryview]) -> int:
    """The payload bytes of a TCPROS frame given as buffers (its 4-byte prefix excluded)."""
    return sum(len(part) for part in parts) - 4


class Ring:
    """Where the next messages go in a segment of `capacity` bytes, freed oldest first.

    `place(n)` gives the offset of n contiguous bytes, or None while no gap is large enough;
    `release()` frees the oldest placed message. A message takes the lowest gap that holds
    it, at 0 first: those bytes were the last read by the subscriber, so they are likely
    still in the CPU's cache, where a ring that always moved on would come back to bytes last
    touched a whole ring ago (a 1080p image is copied 1.2-1.5x as fast through three or two
    reused slots as through a 32 MiB ring's five: bench/RESULTS.md). Then right after the newest
    message, as a ring would; only when neither has room are all the gaps searched.
    """

    def __init__(self, capacity: int) -> None:
        self.capacity = capacity
        self._order: deque[int] = deque()  # the start of each placed message, oldest first
        self._starts: list[int] = []  # the same, by address
        self._ends: dict[int, int] = {}  # start -> end of each placed message
        self._head = 0  # where the newest placed message ends
        self._taken = 0  # bytes placed and not released

    def place(self, length: int) -> int | None:
        size = -(-max(length, 1) // ALIGN) * ALIGN
        if size > self.capacity - self._taken:  # full: said without a search, however many it holds
            return None
        start = 0
        if not self._fits(start, size):
            start = self._head
            if not self._fits(start, size):
                start = next((end for end in map(self._ends.__getitem__, self._starts) if self._fits(end, size)), -1)
                if start < 0:
                    return None
        self._order.append(start)
        bisect.insort(self._starts, start)
        self._ends[start] = self._head = start + size
        self._taken += size
        return start

    def _fits(self, start: int, size: int) -> bool:
        if start + size > self.capacity:
            return False
        starts = self._starts
        after = bisect.bisect_left(starts, start)  # the first message at or after start
        if after < len(starts) and starts[after] < start + size:
            return False
        return after == 0 or self._ends[starts[after - 1]] <= start

    def release(self) -> None:
        start = self._order.popleft()
        del self._starts[bisect.bisect_left(self._starts, start)]
        self._taken -= self._ends.pop(start) - start

    @property
    def used(self) -> int:
        return len(self._order)
