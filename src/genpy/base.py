"""genpy.base: the fixed-size primitive types and their struct codes (kame's codegen's table)."""

from __future__ import annotations

from kame.msg.codegen import pack_codes

# in genpy's order; genpy packs bool as an unsigned byte ('B'), as kame's serializers do
_ORDER = ("int8", "uint8", "bool", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64",
          "char", "byte")
SIMPLE_TYPES_DICT: dict[str, str] = {name: pack_codes()[name] for name in _ORDER}
SIMPLE_TYPES: list[str] = list(SIMPLE_TYPES_DICT)

__all__ = ["SIMPLE_TYPES", "SIMPLE_TYPES_DICT", "is_simple"]


def is_simple(type_: str) -> bool:
    """True for a primitive of fixed serialized size (not string, time, duration, arrays or messages)."""
    return type_ in SIMPLE_TYPES_DICT
