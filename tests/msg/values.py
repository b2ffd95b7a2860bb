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
