"""Build message objects from plain dict values (as vectors.json gives them)."""

from __future__ import annotations

from typing import Any

from kame.msg import Message
from kame.msg.spec import split_array
from kame.rostime import Duration, Time


def build(cls: type[Message], value: dict[str, Any]) -> Message:
    msg = cls()
    for name, slot_type in zip(cls.__slots__, cls._slot_types, strict=False):
        if name in value:
            setattr(msg, name, _convert(cls, name, slot_type, value[name]))
    return msg


def _convert(cls: type[Message], name: str, slot_type: str, value: Any) -> Any:
    base, is_array, _ = split_array(slot_type)
    if is_array:
        if base in ("uint8", "char"):
            return bytes(value)
        return [_convert(cls, name, base, v) for v in value]
    if base == "time":
        return Time(value["secs"], value["nsecs"])
    if base == "duration":
        return Duration(value["secs"], value["nsecs"])
    if base in ("float32", "float64"):
        return float(value)
    if isinstance(value, dict):
        return build(cls._slot_classes[name], value)
    return value


_SAMPLE_INTS = {"int8": -7, "byte": -7, "uint8": 200, "char": 200, "int16": -300, "uint16": 60000,
                "int32": -70000, "uint32": 4000000000, "int64": -(2**40), "uint64": 2**63 + 5}


def sample_value(type_name: str, cls: type[Message], name: str, depth: int = 0) -> Any:
    base, is_array, length = split_array(type_name)
    if is_array:
        count = length if length is not None else 2
        if base in ("uint8", "char"):
            return bytes(range(count))
        return [sample_value(base, cls, name, depth) for _ in range(count)]
    if base in _SAMPLE_INTS:
        return _SAMPLE_INTS[base]
    if base == "bool":
        return True
    if base in ("float32", "float64"):
        return 1.5
    if base == "string":
        return "héllo"
    if base == "time":
        return Time(1_700_000_000, 123)
    if base == "duration":
        return Duration(-2, 5)
    return filled(cls._slot_classes[name])


def filled(cls: type[Message]) -> Message:
    msg = cls()
    for name, slot_type in zip(cls.__slots__, cls._slot_types, strict=False):
        setattr(msg, name, sample_value(slot_type, cls, name))
    return msg


def to_plain(value: Any) -> Any:
    """A message as JSON-able data (bytes as {"__bytes__": hex}), for a peer process to rebuild."""
    if isinstance(value, Message):
        return {name: to_plain(getattr(value, name)) for name in value.__slots__}
    if isinstance(value, (Time, Duration)):
        return {"secs": value.secs, "nsecs": value.nsecs}
    if isinstance(value, (bytes, bytearray)):
        return {"__bytes__": bytes(value).hex()}
    if isinstance(value, (list, tuple)):
        return [to_plain(v) for v in value]
    return value
