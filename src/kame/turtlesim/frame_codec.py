"""World snapshots as bytes, for turtlesim's window when it runs in a process of its own.

Rules: pure (bytes in, snapshots out). A frame is a fixed header, the turtles, and the raster
only when it differs from the last one the encoder sent (the world shares one copy of its
raster between snapshots until the trails change, so identity says it); the decoder keeps the
raster it has. The window process may be slow: its feeder drops frames, never the raster,
because the encoder decides at sending time.
"""

from __future__ import annotations

import struct

from kame.protocol.latest_frame import LatestFrameDecoder
from kame.turtlesim.world import Snapshot, Sprite

_MAGIC = b"KTF1"
_HEADER = struct.Struct("<4sQIIII")  # magic, version, width, height, turtles, raster bytes (0: unchanged)
_SPRITE = struct.Struct("<dddIH")  # x, y, theta, image, name length; then the name (UTF-8)


class FrameError(ValueError):
    """Bytes that are not a frame of this codec."""


class FrameEncoder:
    def __init__(self) -> None:
        self._sent: bytes | None = None

    def encode(self, snapshot: Snapshot) -> bytes:
        raster = b"" if snapshot.pixels is self._sent else snapshot.pixels
        self._sent = snapshot.pixels
        parts = [_HEADER.pack(_MAGIC, snapshot.version, snapshot.width, snapshot.height, len(snapshot.turtles),
                              len(raster))]
        for sprite in snapshot.turtles:
            name = sprite.name.encode()
            parts += [_SPRITE.pack(sprite.x, sprite.y, sprite.theta, sprite.image, len(name)), name]
        parts.append(raster)
        return b"".join(parts)


class FrameDecoder(LatestFrameDecoder[Snapshot]):
    """Feed it bytes as they arrive; `latest()` is the newest whole frame (None before the first)."""

    error = FrameError

    def _parse(self, buffer: bytearray) -> tuple[Snapshot, int] | None:
        if len(buffer) < _HEADER.size:
            return None
        magic, version, width, height, count, raster_size = _HEADER.unpack_from(buffer)
        if magic != _MAGIC:
            raise FrameError(f"not a turtlesim frame (starts {bytes(buffer[:4])!r})")
        offset = _HEADER.size
        sprites = []
        for _ in range(count):
            if len(buffer) < offset + _SPRITE.size:
                return None
            x, y, theta, image, name_size = _SPRITE.unpack_from(buffer, offset)
            offset += _SPRITE.size
            if len(buffer) < offset + name_size:
                return None
            sprites.append(Sprite(bytes(buffer[offset:offset + name_size]).decode(), x, y, theta, image))
            offset += name_size
        if len(buffer) < offset + raster_size:
            return None
        raster = self._raster_at(buffer, offset, raster_size, width * height * 3, f"a {width}x{height} world")
        return Snapshot(width, height, raster, tuple(sprites), version), offset + raster_size
