"""rosapi's TypeDefs: a message type described field by field, as roslibjs's decodeTypeDefs reads it.

For a type and every message type inside it (each once, the asked one first): its field names,
field types (the base type, a nested message by its full name, Header as std_msgs/Header),
fieldarraylen (-1 not an array, 0 variable length, N fixed), an example value per field (the
default's text: "0", "0.0", "False", "", "{}" for a message, "[]" for an array) and its constants.
time and duration are TypeDefs of their own (secs and nsecs, int32), as rosapi gives them.
"""

from __future__ import annotations

from dataclasses import dataclass

from kame.msg.message import Message
from kame.msg.parser import parse_msg
from kame.msg.typenames import split_array

TIME_FIELDS = (("secs", "int32"), ("nsecs", "int32"))


@dataclass(frozen=True)
class TypeDef:
    type: str
    fieldnames: tuple[str, ...]
    fieldtypes: tuple[str, ...]
    fieldarraylen: tuple[int, ...]
    examples: tuple[str, ...]
    constnames: tuple[str, ...] = ()
    constvalues: tuple[str, ...] = ()


def _example(value: object, base: str, is_array: bool) -> str:
    if is_array:
        return "[]"
    if base in ("time", "duration"):
        return "{}"
    if isinstance(value, Message):
        return "{}"
    return str(value)


def _time_typedef(name: str) -> TypeDef:
    return TypeDef(name, tuple(n for n, _ in TIME_FIELDS), tuple(t for _, t in TIME_FIELDS), (-1, -1), ("0", "0"))


def typedefs(cls: type[Message]) -> list[TypeDef]:
    """`cls`'s TypeDef followed by those of the types inside it, each once."""
    out: list[TypeDef] = []
    seen: set[str] = set()
    _collect(cls, out, seen)
    return out


def _collect(cls: type[Message], out: list[TypeDef], seen: set[str]) -> None:
    if cls._type in seen:
        return
    seen.add(cls._type)
    instance = cls()
    names, types, lengths, examples = [], [], [], []
    nested: list[type[Message]] = []
    times: list[str] = []
    for name, type_name in zip(cls.__slots__, cls._slot_types, strict=True):
        base, is_array, length = split_array(type_name)
        names.append(name)
        types.append(base)
        lengths.append(-1 if not is_array else (length or 0))
        examples.append(_example(getattr(instance, name), base, is_array))
        slot_class = cls._slot_classes.get(name)
        if slot_class is not None:
            nested.append(slot_class)
            types[-1] = slot_class._type
        elif base in ("time", "duration"):
            times.append(base)
    spec = parse_msg(cls._full_text.split("\n" + "=" * 80 + "\n")[0], cls._type)
    out.append(TypeDef(cls._type, tuple(names), tuple(types), tuple(lengths), tuple(examples),
                       tuple(c.name for c in spec.constants), tuple(str(c.value) for c in spec.constants)))
    for time_type in times:
        if time_type not in seen:
            seen.add(time_type)
            out.append(_time_typedef(time_type))
    for slot_class in nested:
        _collect(slot_class, out, seen)
