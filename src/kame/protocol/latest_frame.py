"""The reading side of a stream of frames where only the newest matters (a simulator's window
fed snapshots): bytes in as they arrive, the newest whole frame out.

Rules: pure. A codec says how one frame is read from the front of the buffer (`_parse`: the
frame and its size, or None while it is incomplete). A large raster that seldom changes is sent
only when it does (size 0 otherwise): `_raster` keeps the last one and checks its size.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import Generic, TypeVar

F = TypeVar("F")


class LatestFrameDecoder(ABC, Generic[F]):
    error: type[ValueError] = ValueError  # the codec's own error for bytes that are not its frames

    def __init__(self) -> None:
        self._buffer = bytearray()
        self._raster = b""
        self._latest: F | None = None

    def feed(self, data: bytes) -> None:
        self._buffer += data
        while (parsed := self._parse(self._buffer)) is not None:
            frame, size = parsed
            del self._buffer[:size]
            self._latest = frame

    def latest(self) -> F | None:
        """The newest whole frame (None before the first)."""
        return self._latest

    @abstractmethod
    def _parse(self, buffer: bytearray) -> tuple[F, int] | None:
        """The frame at the front of `buffer` and its size in bytes, or None while incomplete."""

    def _raster_at(self, buffer: bytearray, offset: int, size: int, expected: int, what: str) -> bytes:
        """The raster a frame carries at `offset` (`size` bytes, 0: the last one again)."""
        if size:
            if size != expected:
                raise self.error(f"{what}: a raster of {size} bytes where {expected} were due")
            self._raster = bytes(buffer[offset:offset + size])
        elif len(self._raster) != expected:
            raise self.error(f"{what}: a frame without a raster before any raster")
        return self._raster
