"""How `rostopic echo` prints messages: genpy's YAML-like text, placeholders and CSV.

- `to_yaml` is genpy's strify_message with its options: a fixed numeric width (`-w`), a
  field filter, and time fields shown as offsets from a given time (`--offset`).
- `transform` replaces arrays and strings by `<array type: T, length: N>` /
  `<string length: N>` placeholders (`--noarr`, `--nostr`). Like rostopic it descends into
  nested message fields but not into arrays of messages.
- `csv_header` / `csv_row` are `-p`: a `%time` column, then one column per leaf field
  (`field.a.b`, array elements `field.name0`), bools as 1/0, strings raw. uint8[] fields
  have no columns, as in rostopic on Python 3.

Pure: the current time comes in as an argument.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import yaml

from kame.msg.message import Message
from kame.rostime import Time, TVal

__all__ = ["FieldFilter", "Transformed", "csv_header", "csv_row", "field_filter", "to_yaml", "transform"]

FieldFilter = Callable[[Any], Iterable[str]]
_BYTES = (bytes, bytearray, memoryview)


class Transformed:
    """A message with some fields replaced by placeholder strings (what --noarr/--nostr print)."""

    __slots__ = ("fields",)

    def __init__(self, fields: list[tuple[str, str, Any]]) -> None:
        self.fields = fields  # (name, slot type, value)


def _message_fields(val: Message | Transformed) -> list[tuple[str, str, Any]]:
    if isinstance(val, Transformed):
        return val.fields
    return [(name, slot_type, _convert_getattr(val, name, slot_type))
            for name, slot_type in zip(val.__slots__, val._slot_types, strict=False)]


def _convert_getattr(val: Any, name: str, slot_type: str) -> Any:
    value = getattr(val, name)
    if isinstance(value, _BYTES) and ("uint8[" in slot_type or "char[" in slot_type):
        return list(bytes(value))
    return value


def as_field_value(value: Any, type_information: str | None) -> Any:
    """A value picked out of a message by a field path, as echo prints it (uint8[] as ints)."""
    if type_information and isinstance(value, _BYTES) and type_information.startswith(("uint8[", "char[")):
        return list(bytes(value))
    return value


def _yaml_str(value: str) -> str:
    if not value:
        return "''"
    return yaml.dump(value, default_style='"').rstrip("\n")


def to_yaml(val: Any, indent: str = "", time_offset: Time | None = None, field_filter: FieldFilter | None = None,
            width: int | None = None) -> str:
    """genpy.message.strify_message: the text rostopic echo prints for `val`."""
    kind = type(val)
    if kind in (int, float) and width is not None:
        if kind is float:
            text: str = f"%.{width}f" % val
            return text[:max(text.find("."), width)]
        number: str = f"%{width}d" % val
        return number
    if kind in (int, float, bool):
        return str(val)
    if isinstance(val, str):
        return _yaml_str(val)
    if isinstance(val, TVal):
        if time_offset is not None and isinstance(val, Time):
            val = val - time_offset
        if width is not None:
            secs: str = f"%{width}d" % val.secs
            nsecs: str = f"%{width}d" % val.nsecs
            return f"\n{indent}secs: {secs}\n{indent}nsecs: {nsecs}"
        return f"\n{indent}secs: {val.secs}\n{indent}nsecs: {val.nsecs:9d}"
    if kind in (list, tuple):
        if not val:
            return "[]"
        first = val[0]
        if type(first) in (int, float) and width is not None:
            return "[" + ", ".join(to_yaml(v, indent, time_offset, field_filter, width) for v in val) + "]"
        if isinstance(first, str):
            text = yaml.dump(list(val)).rstrip("\n")
            if text.startswith("["):
                return text
            return "\n" + "\n".join(indent + line for line in text.splitlines())
        if type(first) in (int, float, bool):
            return str(list(val))
        inner = indent + "  "
        return "\n" + "\n".join(indent + "- " + to_yaml(v, inner, time_offset, field_filter, width) for v in val)
    if isinstance(val, (Message, Transformed)):
        wanted = set(field_filter(val)) if field_filter is not None else None
        inner = "  " + indent
        lines = [f"{indent}{name}: {to_yaml(value, inner, time_offset, field_filter, width)}"
                 for name, _type, value in _message_fields(val) if wanted is None or name in wanted]
        text = "\n".join(lines)
        return "\n" + text if indent else text
    if hasattr(val, "tolist"):  # numpy arrays
        return to_yaml(val.tolist(), indent, time_offset, field_filter, width)
    return str(val)


def _placeholder(value: Any, value_type: str, nostr: bool, noarr: bool) -> Any:
    if noarr and "[" in value_type:
        return f"<array type: {value_type.rstrip('[]')}, length: {len(value)}>"
    if nostr and value_type == "string":
        return f"<string length: {len(value)}>"
    if nostr and value_type == "string[]":
        return f"<array type: string, length: {len(value)}>"
    return value


def transform(val: Any, type_information: str | None, nostr: bool, noarr: bool) -> Any:
    """`val` with arrays (`noarr`) and strings (`nostr`) replaced by placeholders."""
    if not (nostr or noarr):
        return val
    if not isinstance(val, Message):
        if type_information is None:
            return val
        return _placeholder(val, type_information, nostr, noarr)
    fields: list[tuple[str, str, Any]] = []
    for name, slot_type in zip(val.__slots__, val._slot_types, strict=False):
        value = getattr(val, name)
        replaced = _placeholder(value, slot_type, nostr, noarr)
        if replaced is not value:
            fields.append((name, "string", replaced))
        elif isinstance(value, Message):
            fields.append((name, slot_type, transform(value, None, nostr, noarr)))
        else:
            fields.append((name, slot_type, _convert_getattr(val, name, slot_type)))
    return Transformed(fields)


def field_filter(nostr: bool, noarr: bool) -> FieldFilter | None:
    """The fields -p prints: with --noarr no arrays, with --nostr no strings."""
    if not (nostr or noarr):
        return None

    def wanted(val: Any) -> Iterable[str]:
        for name, slot_type in zip(val.__slots__, val._slot_types, strict=False):
            if noarr and "[" in slot_type:
                continue
            if nostr and "string" in slot_type:
                continue
            yield name

    return wanted


# ---------------------------------------------------------------- CSV (-p)


def _fields_of(val: Any, field_filter: FieldFilter | None) -> list[tuple[str, Any]]:
    wanted = set(field_filter(val)) if field_filter is not None else None
    return [(name, getattr(val, name)) for name in val.__slots__ if wanted is None or name in wanted]


def csv_names(val: Any, label: str, field_filter: FieldFilter | None) -> str | None:
    kind = type(val)
    if kind in (bool, int, float) or isinstance(val, TVal) or isinstance(val, str):
        return label
    if isinstance(val, Message):
        subs = [csv_names(v, f"{label}.{name}", field_filter) for name, v in _fields_of(val, field_filter)]
        found = [s for s in subs if s is not None]
        return ",".join(found) if found else None
    if kind in (list, tuple):
        if not val:
            return None
        first = val[0]
        if type(first) in (bool, int, float) or isinstance(first, (TVal, str)):
            return ",".join(f"{label}{i}" for i in range(len(val)))
        if isinstance(first, Message):
            subs = [csv_names(v, f"{label}{i}", field_filter) for i, v in enumerate(val)]
            found = [s for s in subs if s]
            return ",".join(found) if found else None
    return None


def _csv_values(val: Any, time_offset: Time | None, field_filter: FieldFilter | None) -> str | None:
    kind = type(val)
    if kind is bool:
        return "1" if val else "0"
    if kind in (int, float) or isinstance(val, TVal):
        if time_offset is not None and isinstance(val, Time):
            return str(val - time_offset)
        return str(val)
    if isinstance(val, Message):
        subs = [_csv_values(v, time_offset, field_filter) for _name, v in _fields_of(val, field_filter)]
        found = [s for s in subs if s is not None]
        return ",".join(found) if found else None
    if isinstance(val, str):
        return val
    if kind in (list, tuple):
        if not val:
            return None
        first = val[0]
        if type(first) is bool:
            return ",".join("1" if v else "0" for v in val)
        if type(first) in (int, float) or isinstance(first, TVal):
            return ",".join(str(v) for v in val)
        if isinstance(first, str):
            return ",".join(str(v) for v in val)
        if isinstance(first, Message):
            items = [_csv_values(v, time_offset, field_filter) for v in val]
            present = [item for item in items if item is not None]
            return ",".join(present) if present else None
    return None


def csv_header(val: Any, field_filter: FieldFilter | None = None) -> str:
    """`%time,field.x,field.y`: the first line rostopic echo -p prints."""
    names = csv_names(val, "field", field_filter)
    return "%time," + (names if names is not None else "")


def csv_row(val: Any, now: Time, time_offset: Time | None = None, field_filter: FieldFilter | None = None,
            receipt_time: Time | None = None) -> str:
    """One CSV line: the header stamp (else `receipt_time`, else `now`) in ns, then the values."""
    values = _csv_values(val, time_offset, field_filter) or ""
    offset = time_offset.to_nsec() if time_offset is not None else 0
    if receipt_time is not None:
        stamp = receipt_time.to_nsec()
    elif getattr(val, "_has_header", False):
        stamp = val.header.stamp.to_nsec()
    else:
        stamp = now.to_nsec()
    return f"{stamp - offset},{values}"
