"""Messages as the rqt plugins show and edit them (pure): a message as a tree of (field, type,
value) rows, a message type as its editable fields, and field expressions evaluated into a
message, as rqt_publisher and rqt_service_caller do.

Rules:
- A tree row's children are a nested message's fields or an array's elements; arrays show
  at most SHOWN_ELEMENTS elements (an image's data is a million bytes), and a uint8[] is shown
  as its length and first bytes, not element by element.
- The editable fields of a type are its leaves: primitives, time/duration and arrays (one
  expression for the whole array); nested messages are opened up (`pose/position/x`).
- An expression is Python evaluated with `i` (how many messages were published before this
  one), `math` and `random`, as rqt_publisher's. An empty expression keeps the default. The
  values fill the message by kame.msg.fill's rules (genpy's), so a time takes nanoseconds or
  {secs, nsecs}, a uint8[] a string or a list.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from kame.msg.fill import FillError, fill_message_args
from kame.msg.typenames import split_array
from kame.rostime import TVal

SHOWN_ELEMENTS = 64
BYTES_SHOWN = 16
PRIMITIVES = frozenset({"bool", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32",
                        "float64", "string", "char", "byte", "time", "duration"})


class ExpressionError(ValueError):
    """An expression that does not evaluate, or values that do not fit the message; names the field."""


@dataclass(frozen=True)
class TreeRow:
    name: str
    type: str
    value: str  # empty for a message or an array: its rows say
    children: tuple[TreeRow, ...] = ()


def value_tree(value: Any, name: str = "", type_name: str = "") -> TreeRow:
    """The rows a message (or any field value) shows as."""
    type_name = type_name or str(getattr(value, "_type", type(value).__name__))
    base, is_array, _ = split_array(type_name) if type_name.endswith("]") else (type_name, False, None)
    if is_array:
        if isinstance(value, (bytes, bytearray, memoryview)) or base in ("uint8", "char"):
            data = bytes(value)
            more = "..." if len(data) > BYTES_SHOWN else ""
            return TreeRow(name, type_name, f"{len(data)} bytes [{', '.join(map(str, data[:BYTES_SHOWN]))}{more}]")
        items = list(value)
        rows = tuple(value_tree(item, f"[{index}]", base) for index, item in enumerate(items[:SHOWN_ELEMENTS]))
        if len(items) > SHOWN_ELEMENTS:
            rows += (TreeRow("...", "", f"{len(items) - SHOWN_ELEMENTS} more"),)
        return TreeRow(name, type_name, f"{len(items)} items", rows)
    if isinstance(value, TVal):
        return TreeRow(name, type_name, f"{value.secs}.{value.nsecs:09d}")
    slots = getattr(value, "__slots__", None)
    slot_types = getattr(value, "_slot_types", None)
    if slots is not None and slot_types is not None and base not in PRIMITIVES:
        return TreeRow(name, type_name, "", tuple(value_tree(getattr(value, field), field, field_type)
                                                  for field, field_type in zip(slots, slot_types, strict=True)))
    return TreeRow(name, type_name, repr(value) if isinstance(value, str) else str(value))


def editable_fields(cls: type[Any], prefix: str = "") -> list[tuple[str, str]]:
    """(path, type) of each field an expression can set, in definition order."""
    fields: list[tuple[str, str]] = []
    example = cls()
    for field, field_type in zip(cls.__slots__, cls._slot_types, strict=True):
        path = f"{prefix}{field}"
        if field_type in PRIMITIVES or field_type.endswith("]"):
            fields.append((path, field_type))
        else:
            fields += editable_fields(type(getattr(example, field)), path + "/")
    return fields


def evaluate(expression: str, i: int) -> Any:
    try:
        # the user's own expression, in the user's own tool: evaluated as rqt_publisher evaluates it
        return eval(expression, {"__builtins__": __builtins__, "math": math, "random": random}, {"i": i})
    except Exception as exc:
        raise ExpressionError(f"{expression!r}: {type(exc).__name__}: {exc}") from exc


def build_message(cls: type[Any], expressions: Mapping[str, str], i: int = 0) -> Any:
    """A `cls` with each field path set to its expression's value (empty expressions skipped)."""
    values: dict[str, Any] = {}
    for path, expression in expressions.items():
        if not expression.strip():
            continue
        try:
            value = evaluate(expression, i)
        except ExpressionError as exc:
            raise ExpressionError(f"{path}: {exc}") from exc
        *parents, leaf = path.split("/")
        target = values
        for parent in parents:
            target = target.setdefault(parent, {})
        target[leaf] = value
    message = cls()
    try:
        fill_message_args(message, [values])
    except FillError as exc:
        raise ExpressionError(str(exc)) from exc
    return message
