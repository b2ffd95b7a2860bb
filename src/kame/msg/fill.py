"""Filling a message from YAML command-line values: genpy's fill_message_args rules.

What `rostopic pub` and `rosservice call` do with their arguments (each one a YAML value):
- a list of values fills the fields in definition order and must have one value per field;
  a nested message takes a list (positional) or a mapping (by name) of its own fields;
- a mapping is taken by field name, missing fields keep their defaults, and an empty
  value (`{data: }`) means an empty string;
- time and duration fields take `{secs: .., nsecs: ..}`, `[secs, nsecs]`, an integer count
  of nanoseconds, or a key such as `now`; a message field may take a key such as `auto`
  (the caller's `keys` say what they stand for);
- arrays take YAML lists; arrays of messages are built element by element;
  uint8[]/char[] also take a string.

Errors are FillError with genpy's wording (`No field name [linear.q]`, `Not enough
arguments: ...`) so that the command line can print them as the real tools do. Values of
the wrong primitive type are left for the serializer's type check, which names the field.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from kame.msg.errors import MessageError
from kame.msg.message import Message
from kame.msg.spec import BUILTIN_TYPES, split_array
from kame.rostime import Duration, Time, TVal

__all__ = ["FillError", "fill_message_args", "printable_message_args"]


class FillError(MessageError):
    """The arguments do not fit the message; the text names the field (genpy's wording)."""


def printable_message_args(msg: Message | TVal, prefix: str = "") -> str:
    """`linear.x linear.y ...`: the leaf fields a positional argument list fills."""
    parts: list[str] = []
    for name in _slots(msg):
        value = getattr(msg, name)
        if isinstance(value, Message):
            parts.append(printable_message_args(value, prefix + name + "."))
        else:
            parts.append(prefix + name)
    return " ".join(p for p in parts if p)


def fill_message_args(msg: Message, args: list[Any] | None, keys: Mapping[str, Any] | None = None) -> None:
    """Set `msg`'s fields from `args`, a list of YAML values (a single mapping counts as keywords).

    `keys` maps keywords to the values they stand for in time and message fields
    (rostopic passes `now` -> the current Time and `auto` -> a Header stamped now).
    """
    keys = keys or {}
    if args is None:
        args = []
    if len(args) == 1 and isinstance(args[0], dict):
        _fill(msg, args[0], keys, "")
    else:
        _fill(msg, list(args), keys, "")


def _slots(msg: Message | TVal) -> tuple[str, ...]:
    if isinstance(msg, TVal):
        return ("secs", "nsecs")
    return tuple(msg.__slots__)


def _slot_type(msg: Message | TVal, name: str) -> str:
    if isinstance(msg, TVal):
        return "int32" if isinstance(msg, Duration) else "uint32"
    return msg._slot_types[msg.__slots__.index(name)]


def _fill(msg: Message | TVal, args: Any, keys: Mapping[str, Any], prefix: str) -> None:
    slots = _slots(msg)
    if isinstance(args, dict):
        for name, value in args.items():
            if value is None:  # an empty YAML value means an empty string
                value = ""
            _fill_field(msg, str(name), value, keys, prefix)
    elif isinstance(args, (list, tuple)):
        if len(args) > len(slots):
            raise FillError(f"Too many arguments:\n * Given: {list(args)}\n * Expected: {list(slots)}")
        if len(args) < len(slots):
            raise FillError(f"Not enough arguments:\n * Given: {list(args)}\n * Expected: {list(slots)}")
        for name, value in zip(slots, args, strict=True):
            _fill_field(msg, name, value, keys, prefix)
    else:
        what = "time value" if isinstance(msg, TVal) else "message"
        field = prefix.rstrip(".") or "the message"
        raise FillError(f"Field [{field}] is a {what}: give a YAML list or mapping of its fields "
                        f"instead of: {args!r}")


def _fill_field(msg: Message | TVal, name: str, value: Any, keys: Mapping[str, Any], prefix: str) -> None:
    if name not in _slots(msg):
        raise FillError(f"No field name [{prefix}{name}]")
    path = prefix + name
    slot_type = _slot_type(msg, name)
    base, is_array, length = split_array(slot_type)
    current = getattr(msg, name)
    if is_array:
        setattr(msg, name, _array_value(msg, name, base, length, value, keys, path))
    elif isinstance(current, (Message, TVal)):
        setattr(msg, name, _compound_value(current, value, keys, path))
    else:
        setattr(msg, name, value)


def _compound_value(current: Message | TVal, value: Any, keys: Mapping[str, Any], path: str) -> Any:
    """The new value of a message or time field: a keyword's value, or `current` filled in."""
    if isinstance(value, str):
        if value not in keys:
            raise FillError(f"No key named [{value}]")
        replacement = keys[value]
        if not _same_kind(current, replacement):
            raise FillError(f"Field [{path}] cannot be set to [{value}]")
        return replacement
    if isinstance(current, TVal):
        if isinstance(value, bool):
            raise FillError(f"Field [{path}] is a time value and cannot be {value!r}")
        try:
            if isinstance(value, int):
                return type(current).from_nsec(value)
            if isinstance(value, float):
                return type(current).from_sec(value)
        except (TypeError, ValueError, OverflowError) as exc:  # negative times, nan, inf
            raise FillError(f"Field [{path}] cannot be {value!r}: {exc}") from None
    _fill(current, value, keys, path + ".")
    return current


def _same_kind(current: Message | TVal, replacement: Any) -> bool:
    if isinstance(current, Time):
        return isinstance(replacement, Time)
    if isinstance(current, Duration):
        return isinstance(replacement, Duration)
    return isinstance(current, Message) and isinstance(replacement, Message) and replacement._type == current._type


def _array_value(msg: Message | TVal, name: str, base: str, length: int | None, value: Any,
                 keys: Mapping[str, Any], path: str) -> Any:
    if base in ("uint8", "char") and isinstance(value, (str, bytes)):
        data = value.encode() if isinstance(value, str) else value
        if length is not None and len(data) != length:
            raise FillError(f"Field [{path}] has incorrect number of elements: {len(data)} != {length}")
        return data
    if not isinstance(value, (list, tuple)):
        raise FillError(f"Field [{path}] must be a list or tuple instead of: {type(value).__name__}")
    if length is not None and len(value) != length:
        raise FillError(f"Field [{path}] has incorrect number of elements: {len(value)} != {length}")
    if base in BUILTIN_TYPES and base not in ("time", "duration"):
        return list(value)
    elements: list[Any] = []
    for index, item in enumerate(value):
        element = _new_element(msg, name, base)
        elements.append(_compound_value(element, item, keys, f"{path}[{index}]"))
    return elements


def _new_element(msg: Message | TVal, name: str, base: str) -> Message | TVal:
    if base == "time":
        return Time()
    if base == "duration":
        return Duration()
    assert isinstance(msg, Message)
    cls = type(msg)._slot_classes.get(name)
    if cls is None:
        raise FillError(f"Cannot instantiate messages for field [{name}]: cannot load class {base}")
    element: Message = cls()
    return element
