"""Chunk compression: none, bz2 (a standard bzip2 stream) and lz4 (a standard LZ4 frame).

Decompression is bounded by the size the chunk header promises, so a corrupt or hostile
chunk cannot make us allocate more than that; a size that does not match is an error.
"""

from __future__ import annotations

import types

from kame.bag.errors import BagCompressionError

__all__ = ["COMPRESSIONS", "compress", "decompress"]

NONE = "none"
BZ2 = "bz2"
LZ4 = "lz4"
COMPRESSIONS = (NONE, BZ2, LZ4)


def _lz4() -> types.ModuleType:
    try:
        import lz4.frame
    except ImportError as exc:  # pragma: no cover - lz4 is a dependency
        raise BagCompressionError("lz4 chunks need the 'lz4' package (pip install lz4)") from exc
    frame: types.ModuleType = lz4.frame
    return frame


def compress(kind: str, data: bytes | bytearray | memoryview) -> bytes:
    if kind == NONE:
        return bytes(data)
    if kind == BZ2:
        import bz2

        return bz2.compress(data, 9)
    if kind == LZ4:
        frame = _lz4()  # the frame roslz4 writes (and the only one it reads): 1 MB blocks, content checksum
        out: bytes = frame.compress(bytes(data), store_size=False, block_size=frame.BLOCKSIZE_MAX1MB,
                                    content_checksum=True)
        return out
    raise BagCompressionError(f"unsupported compression type: {kind}")


def decompress(kind: str, data: bytes | memoryview, size: int, where: str = "") -> bytes | memoryview:
    """The uncompressed bytes of a chunk, which must be exactly `size` long (an uncompressed
    chunk is returned as given, not copied)."""
    out: bytes | memoryview
    if kind == NONE:
        out = data
    elif kind == BZ2:
        import bz2  # on demand: `rosbag info` never needs it

        try:
            decomp = bz2.BZ2Decompressor()
            out = decomp.decompress(data, max_length=size + 1)
        except (OSError, ValueError, EOFError) as exc:
            raise BagCompressionError(f"corrupt bz2 chunk{where}: {exc}") from exc
    elif kind == LZ4:
        try:
            out = _lz4().LZ4FrameDecompressor().decompress(data, max_length=size + 1)
        except RuntimeError as exc:
            raise BagCompressionError(f"corrupt lz4 chunk{where}: {exc}") from exc
    else:
        raise BagCompressionError(f"unsupported compression type: {kind}{where}")
    if len(out) != size:
        raise BagCompressionError(f"{kind} chunk{where} holds {len(out)} bytes, its header says {size}")
    return out
