"""Parsed message and service definitions: plain frozen values.

A field's `type` is the resolved type as genmsg records it ('std_msgs/Header',
'geometry_msgs/Vector3[]', 'float64[36]'); builtin types keep their declared spelling,
aliases (`byte`, `char`) included, because md5 texts depend on it.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from kame.msg.typenames import split_array

PRIMITIVE_TYPES: frozenset[str] = frozenset(
    {
        "bool", "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64",
        "float32", "float64", "string", "byte", "char",
    }
)
BUILTIN_TYPES: frozenset[str] = PRIMITIVE_TYPES | {"time", "duration"}
HEADER_TYPE = "std_msgs/Header"

__all__ = ["BUILTIN_TYPES", "HEADER_TYPE", "PRIMITIVE_TYPES", "ActionSpec", "Constant", "Field", "MsgSpec", "SrvSpec",
           "is_builtin", "split_array"]


def is_builtin(base_type: str) -> bool:
    return base_type in BUILTIN_TYPES


@dataclass(frozen=True)
class Field:
    name: str
    type: str
    base_type: str
    is_array: bool
    array_len: int | None

    @property
    def is_builtin(self) -> bool:
        return self.base_type in BUILTIN_TYPES

    @property
    def is_message(self) -> bool:
        return self.base_type not in BUILTIN_TYPES


@dataclass(frozen=True)
class Constant:
    type: str
    name: str
    value: bool | int | float | str
    value_text: str


@dataclass(frozen=True)
class MsgSpec:
    """One message type. `text` is the definition text as genmsg keeps it (comments included)."""

    full_name: str
    fields: tuple[Field, ...]
    constants: tuple[Constant, ...]
    text: str
    source: str = ""

    @property
    def package(self) -> str:
        return self.full_name.partition("/")[0]

    @property
    def short_name(self) -> str:
        return self.full_name.partition("/")[2]

    @property
    def has_header(self) -> bool:
        return bool(self.fields) and self.fields[0].type == HEADER_TYPE and self.fields[0].name == "header"

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(f.name for f in self.fields)

    @property
    def types(self) -> tuple[str, ...]:
        return tuple(f.type for f in self.fields)

    def message_dependencies(self) -> tuple[str, ...]:
        """The message types this one names directly, in field order, without repeats."""
        seen: dict[str, None] = {}
        for f in self.fields:
            if f.is_message:
                seen.setdefault(f.base_type, None)
        return tuple(seen)


@dataclass(frozen=True)
class SrvSpec:
    full_name: str
    request: MsgSpec
    response: MsgSpec
    text: str
    source: str = ""

    @property
    def package(self) -> str:
        return self.full_name.partition("/")[0]

    @property
    def short_name(self) -> str:
        return self.full_name.partition("/")[2]


@dataclass(frozen=True)
class ActionSpec:
    """An .action file expanded into the seven messages genaction writes."""

    full_name: str
    messages: tuple[MsgSpec, ...] = field(default_factory=tuple)
