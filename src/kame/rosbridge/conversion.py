"""Messages as rosbridge writes them: JSON values, and CBOR values with typed arrays.

Rules (rosbridge_library's message_conversion and cbor_conversion, ROS 1 branch):
- A message is an object of its fields; a nested message is a nested object.
- time and duration are {"secs": int, "nsecs": int}; a time given as the string "now" is the
  caller's ROS time (`now`), as rosbridge reads it.
- uint8[] and char[] are one base64 string in JSON (a list of numbers is taken too), bytes in
  CBOR; in CBOR the other numeric arrays are RFC 8746 typed arrays (little-endian tags), bool[]
  and string[] are lists.
- floats that are not finite are null in JSON (JSON has no NaN); null reads back as NaN.
- From JSON: a field the type does not have, or a value of the wrong kind (a string for an
  int, an out-of-range integer, a list of the wrong length), is a ConversionError naming the
  field; missing fields keep their defaults.
"""

from __future__ import annotations

import base64
import binascii
import math
import struct
from collections.abc import Callable
from typing import Any

from kame.msg.message import Message
from kame.msg.typenames import split_array
from kame.rostime import Duration, Time

BINARY_TYPES = frozenset({"uint8", "char"})
INT_RANGES: dict[str, tuple[int, int]] = {
    "int8": (-(2**7), 2**7 - 1), "byte": (-(2**7), 2**7 - 1), "uint8": (0, 2**8 - 1), "char": (0, 2**8 - 1),
    "int16": (-(2**15), 2**15 - 1), "uint16": (0, 2**16 - 1), "int32": (-(2**31), 2**31 - 1),
    "uint32": (0, 2**32 - 1), "int64": (-(2**63), 2**63 - 1), "uint64": (0, 2**64 - 1),
}
FLOAT_TYPES = frozenset({"float32", "float64"})
TIME_TYPES = frozenset({"time", "duration"})
# RFC 8746 tags for little-endian typed arrays, with the struct code of one element
CBOR_TYPED_ARRAYS: dict[str, tuple[int, str]] = {
    "uint16": (69, "H"), "uint32": (70, "I"), "uint64": (71, "Q"), "int8": (72, "b"), "byte": (72, "b"),
    "int16": (77, "h"), "int32": (78, "i"), "int64": (79, "q"), "float32": (85, "f"), "float64": (86, "d"),
}


class ConversionError(ValueError):
    """A JSON value that does not fit the message type: says which field and why."""


def _field_types(cls: type[Message]) -> zip[tuple[str, str]]:
    return zip(cls.__slots__, cls._slot_types, strict=True)


# ------------------------------------------------------------------ message -> JSON


def _json_float(value: float) -> float | None:
    return value if math.isfinite(value) else None


def _time_value(value: Any) -> dict[str, int]:
    return {"secs": int(value.secs), "nsecs": int(value.nsecs)}


def to_json(msg: Message) -> dict[str, Any]:
    """`msg` as rosbridge's JSON object."""
    out: dict[str, Any] = {}
    for name, type_name in _field_types(type(msg)):
        out[name] = _json_field(getattr(msg, name), type_name)
    return out


def _json_field(value: Any, type_name: str) -> Any:
    base, is_array, _ = split_array(type_name)
    if is_array:
        if base in BINARY_TYPES:
            raw = bytes(value) if not isinstance(value, (list, tuple)) else bytes(bytearray(value))
            return base64.b64encode(raw).decode("ascii")
        if base in FLOAT_TYPES:
            return [_json_float(float(v)) for v in value]
        if base in INT_RANGES or base == "bool" or base == "string":
            return list(value) if not isinstance(value, list) else value
        return [_json_field(v, base) for v in value]
    if base in FLOAT_TYPES:
        return _json_float(float(value))
    if base in TIME_TYPES:
        return _time_value(value)
    if base in INT_RANGES or base in ("bool", "string"):
        return value
    return to_json(value)


# ------------------------------------------------------------------ message -> CBOR values


def to_cbor_value(msg: Message, tag: Callable[[int, bytes], Any]) -> dict[str, Any]:
    """`msg` as rosbridge's CBOR object; `tag(number, payload)` makes a CBOR tag (cbor2.CBORTag)."""
    out: dict[str, Any] = {}
    for name, type_name in _field_types(type(msg)):
        out[name] = _cbor_field(getattr(msg, name), type_name, tag)
    return out


def _cbor_field(value: Any, type_name: str, tag: Callable[[int, bytes], Any]) -> Any:
    base, is_array, _ = split_array(type_name)
    if is_array:
        if base in BINARY_TYPES:
            return bytes(value) if not isinstance(value, (list, tuple)) else bytes(bytearray(value))
        typed = CBOR_TYPED_ARRAYS.get(base)
        if typed is not None:
            number, code = typed
            return tag(number, struct.pack(f"<{len(value)}{code}", *value))
        if base in ("bool", "string"):
            return list(value)
        return [_cbor_field(v, base, tag) for v in value]
    if base in TIME_TYPES:
        return _time_value(value)
    if base in INT_RANGES or base in FLOAT_TYPES or base in ("bool", "string"):
        return value
    return to_cbor_value(value, tag)


# ------------------------------------------------------------------ JSON -> message


def from_json(cls: type[Message], value: Any, now: Callable[[], Time] | None = None, path: str = "") -> Message:
    """A `cls` message filled from rosbridge's JSON object `value` (ConversionError if it does not fit)."""
    if value is None:
        value = {}
    if not isinstance(value, dict):
        raise ConversionError(f"{path or cls._type}: expected an object for {cls._type}, got {_kind(value)}")
    msg = cls()
    types = dict(_field_types(cls))
    for name, field_value in value.items():
        type_name = types.get(name)
        if type_name is None:
            raise ConversionError(f"Message type {cls._type} does not have a field {name}")
        field_path = f"{path}.{name}" if path else name
        slot_class = cls._slot_classes.get(name)
        setattr(msg, name, _from_json_field(field_value, type_name, slot_class, now, field_path))
    return msg


def _kind(value: Any) -> str:
    return {dict: "an object", list: "a list", str: "a string", bool: "a boolean", type(None): "null"}.get(
        type(value), f"a {type(value).__name__}")


def _from_json_field(value: Any, type_name: str, slot_class: type[Message] | None,
                     now: Callable[[], Time] | None, path: str) -> Any:
    base, is_array, length = split_array(type_name)
    if is_array:
        if base in BINARY_TYPES and isinstance(value, str):
            try:
                raw = base64.b64decode(value, validate=True)
            except (binascii.Error, ValueError) as exc:
                raise ConversionError(f"{path}: {type_name} expects base64 text: {exc}") from None
            items: Any = raw
        elif base in BINARY_TYPES and isinstance(value, (bytes, bytearray)):
            items = bytes(value)
        elif isinstance(value, list):
            items = [_from_json_field(v, base, slot_class, now, f"{path}[{i}]") for i, v in enumerate(value)]
            if base in BINARY_TYPES:
                items = bytes(items)
        else:
            raise ConversionError(f"{path}: expected a list for {type_name}, got {_kind(value)}")
        if length is not None and len(items) != length:
            raise ConversionError(f"{path}: {type_name} needs {length} elements, got {len(items)}")
        return items
    if base in INT_RANGES:
        if isinstance(value, bool) or not isinstance(value, int):
            raise ConversionError(f"{path}: expected an integer for {base}, got {_kind(value)}")
        low, high = INT_RANGES[base]
        if not low <= value <= high:
            raise ConversionError(f"{path}: {value} is out of range for {base}")
        return value
    if base in FLOAT_TYPES:
        if value is None:
            return math.nan
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ConversionError(f"{path}: expected a number for {base}, got {_kind(value)}")
        return float(value)
    if base == "bool":
        if not isinstance(value, bool):
            raise ConversionError(f"{path}: expected a boolean, got {_kind(value)}")
        return value
    if base == "string":
        if not isinstance(value, str):
            raise ConversionError(f"{path}: expected a string, got {_kind(value)}")
        return value
    if base in TIME_TYPES:
        return _from_json_time(value, base, now, path)
    if slot_class is None:
        raise ConversionError(f"{path}: unknown field type {type_name}")
    return from_json(slot_class, value, now, path)


def _from_json_time(value: Any, base: str, now: Callable[[], Time] | None, path: str) -> Time | Duration:
    if base == "time" and value == "now" and now is not None:
        return now()
    if not isinstance(value, dict):
        raise ConversionError(f"{path}: expected {{secs, nsecs}} for {base}, got {_kind(value)}")
    parts = []
    for key in ("secs", "nsecs"):
        part = value.get(key, 0)
        if isinstance(part, bool) or not isinstance(part, int):
            raise ConversionError(f"{path}.{key}: expected an integer, got {_kind(part)}")
        parts.append(part)
    unknown = set(value) - {"secs", "nsecs"}
    if unknown:
        raise ConversionError(f"{path}: {base} has no field {sorted(unknown)[0]}")
    try:
        return Time(parts[0], parts[1]) if base == "time" else Duration(parts[0], parts[1])
    except (TypeError, ValueError) as exc:
        raise ConversionError(f"{path}: {exc}") from None
