"""Small helpers that generated message code calls on its less common paths."""

from __future__ import annotations

import struct
import sys
from typing import Any

#: Whether this host stores integers and float64 as the wire does (little-endian, IEEE 754).
#: Then struct's native formats write and read the same bytes as "<" formats, and float64
#: items go faster: native ones are one memcpy, "<" ones a PyFloat_Pack8/Unpack8 call each.
_PROBE = float.fromhex("-0x1.23456789abcdep+100")
NATIVE_IS_WIRE = sys.byteorder == "little" and struct.pack("@d", _PROBE) == bytes.fromhex("debc9a78563432c6")
#: Codes whose native form is not the standard one in more than alignment: float32 packs
#: without the overflow check, and bool reads the byte as a C _Bool.
_NOT_NATIVE = frozenset("f?")


def wire_struct(fmt: str) -> struct.Struct:
    """The precompiled struct of a little-endian wire format ("<..."): its native twin when
    that packs the same bytes (no alignment padding, no float32/bool) and is faster (float64
    items), else fmt itself. Both pack, unpack and fail alike, so generated code may use either.
    """
    body = fmt[1:]
    if NATIVE_IS_WIRE and "d" in body and not _NOT_NATIVE.intersection(body) \
            and struct.calcsize("@" + body) == struct.calcsize(fmt):
        return struct.Struct("@" + body)
    return struct.Struct(fmt)


class Truncated(Exception):
    """Raised inside generated deserializers when a length points past the end of the data."""


class ArrayStructs(dict[int, struct.Struct]):
    """Precompiled structs of a variable-length array format, by element count.

    template has one %d for the count ("<I%dd": count and float64 items). Counts up to
    MAX_CACHED are kept (real messages repeat their lengths); larger ones, and the counts of
    bad input, get a struct that is not kept, so the cache stays small.
    """

    MAX_CACHED = 4096

    def __init__(self, template: str) -> None:
        super().__init__()
        self.template = template

    def __missing__(self, count: int) -> struct.Struct:
        compiled = wire_struct(self.template % count)
        if count <= self.MAX_CACHED:
            self[count] = compiled
        return compiled


def u8_payload(value: Any) -> bytes | memoryview:
    """A uint8[]/char[] value as something with byte length and the buffer protocol.

    Lists and tuples of ints become bytes (range-checked); bytearray, memoryview, numpy
    arrays and array.array are used in place, without a copy.
    """
    if isinstance(value, (list, tuple)):
        return bytes(value)
    if isinstance(value, str):
        raise TypeError("a uint8[] field takes bytes or a list of ints, not str")
    return memoryview(value).cast("B")


def pack_array(value: Any, code: str, dtype: str) -> bytes:
    """The bytes of a numeric array: lists and tuples through struct, arrays through numpy."""
    if isinstance(value, (list, tuple)):
        return struct.pack(f"<{len(value)}{code}", *value)
    import numpy

    return numpy.asarray(value, dtype=dtype).tobytes()
