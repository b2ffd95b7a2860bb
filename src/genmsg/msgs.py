"""genmsg.msgs: message specs as genmsg's generators read them (MsgSpec with parallel lists of
types and names, Constant, Field) and the type-name rules they follow."""

from __future__ import annotations

from typing import Any

from genmsg.base import EXT_MSG, MSG_DIR, SEP, InvalidMsgSpec, log
from genmsg.names import is_legal_resource_base_name, is_legal_resource_name, package_resource_name, resource_name
from kame.msg import spec as _kame

__all__ = ["BUILTIN_TYPES", "DURATION", "DURATION_MSG", "EXT_MSG", "HEADER", "HEADER_FULL_NAME", "MSG_DIR",
           "PRIMITIVE_TYPES", "SEP", "TIME", "TIME_MSG", "Constant", "Field", "InvalidMsgSpec", "MsgSpec",
           "bare_msg_type", "is_builtin", "is_header_type", "is_legal_resource_base_name", "is_legal_resource_name",
           "is_valid_constant_type", "is_valid_msg_field_name", "is_valid_msg_type", "log",
           "package_resource_name", "parse_type", "resolve_type", "resource_name"]

HEADER = "Header"
TIME = "time"
DURATION = "duration"
HEADER_FULL_NAME = _kame.HEADER_TYPE
TIME_MSG = "uint32 secs\nuint32 nsecs"
DURATION_MSG = "int32 secs\nint32 nsecs"
# genmsg's order (the deprecated aliases last)
PRIMITIVE_TYPES = ["int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64",
                   "string", "bool", "char", "byte"]
BUILTIN_TYPES = [*PRIMITIVE_TYPES, TIME, DURATION]


def bare_msg_type(msg_type: str | None) -> str | None:
    """'std_msgs/String[3]' -> 'std_msgs/String'."""
    if msg_type is None:
        return None
    return msg_type[:msg_type.find("[")] if "[" in msg_type else msg_type


def resolve_type(msg_type: str, package_context: str) -> str:
    """'String', 'std_msgs' -> 'std_msgs/String'; builtins stay; Header -> std_msgs/Header."""
    bare = bare_msg_type(msg_type)
    if bare in BUILTIN_TYPES:
        return msg_type
    if bare == HEADER:
        return HEADER_FULL_NAME
    if SEP in msg_type:
        return msg_type
    return f"{package_context}{SEP}{msg_type}"


def parse_type(msg_type: str) -> tuple[str, bool, int | None]:
    """(base type, is array, fixed length or None); ValueError for no type or a bad dimension."""
    if not msg_type:
        raise ValueError("Invalid empty type")
    if "[" not in msg_type:
        return msg_type, False, None
    splits = msg_type.split("[")
    if len(splits) > 2:
        raise ValueError(f"Currently only support 1-dimensional array types: {msg_type}")
    if msg_type.endswith("[]"):
        return msg_type[:-2], True, None
    try:
        return splits[0], True, int(splits[1][:-1])
    except ValueError:
        raise ValueError(f"Invalid array dimension: [{splits[1][:-1]}]") from None


def is_valid_msg_type(x: str | None) -> bool:
    """A legal resource name followed by any number of `[N]` or `[]` (checked no further here)."""
    if not x or len(x) != len(x.strip()):
        return False
    base = bare_msg_type(x)
    if not is_legal_resource_name(base):
        return False
    open_bracket = False
    for c in x[len(str(base)):]:
        if not open_bracket:
            if c != "[":
                return False
            open_bracket = True
        elif c == "]":
            open_bracket = False
        elif not c.isdigit():
            return False
    return not open_bracket


def is_valid_constant_type(x: str) -> bool:
    return x in PRIMITIVE_TYPES


def is_valid_msg_field_name(x: str) -> bool:
    return is_legal_resource_base_name(x)


def is_header_type(msg_type: str) -> bool:
    """Header by any of its names (roslib/Header is REP 100's old one)."""
    return msg_type in (HEADER, HEADER_FULL_NAME, "roslib/Header")


def is_builtin(msg_type_name: str | None) -> bool:
    return msg_type_name in BUILTIN_TYPES


class Constant:
    """A constant declaration: `type name=val`, with `val_text` as written."""

    __slots__ = ["name", "type", "val", "val_text"]

    def __init__(self, type_: str, name: str, val: Any, val_text: str) -> None:
        if type_ is None or name is None or val is None or val_text is None:
            raise ValueError("Constant must have non-None parameters")
        self.type = type_
        self.name = name.strip()
        self.val = val
        self.val_text = val_text

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Constant):
            return False
        return self.type == other.type and self.name == other.name and self.val == other.val

    __hash__ = None  # type: ignore[assignment]  # mutable, compared by value, as genmsg's

    def __repr__(self) -> str:
        return f"{self.type} {self.name}={self.val}"

    __str__ = __repr__


class Field:
    """One field of a MsgSpec: its name, its type and what the type says."""

    def __init__(self, name: str, type: str) -> None:
        self.name = name
        self.type = type
        self.base_type, self.is_array, self.array_len = parse_type(type)
        self.is_header = is_header_type(self.type)
        self.is_builtin = is_builtin(self.base_type)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Field) and self.name == other.name and self.type == other.type

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"[{self.name}, {self.type}, {self.base_type}, {self.is_array}, {self.array_len}]"


class MsgSpec:
    """A loaded message definition: field types and names in parallel lists, constants, the text
    as read (comments kept) and the type's names. InvalidMsgSpec for repeated field names or a
    type that is not one."""

    def __init__(self, types: list[str], names: list[str], constants: list[Constant], text: str, full_name: str,
                 package: str = "", short_name: str = "") -> None:
        alt_package, alt_short_name = package_resource_name(full_name)
        self.types = types
        if len(set(names)) != len(names):
            raise InvalidMsgSpec(f"Duplicate field names in message: {names}")
        self.names = names
        self.constants = constants
        if len(types) != len(names):
            raise InvalidMsgSpec(f"len({types}) != len({names})")
        self.header_present = bool(types) and types[0] == HEADER_FULL_NAME and names[0] == "header"
        self.text = text
        self.full_name = full_name
        self.short_name = short_name or alt_short_name
        self.package = package or alt_package
        try:
            self._parsed_fields = [Field(name, type_) for name, type_ in zip(names, types, strict=True)]
        except ValueError as e:
            raise InvalidMsgSpec(f"invalid field: {e}") from None

    def fields(self) -> list[tuple[str, str]]:
        """[(type, name), ...]."""
        return list(zip(self.types, self.names, strict=True))

    def parsed_fields(self) -> list[Field]:
        return self._parsed_fields

    def has_header(self) -> bool:
        """True when the first field is `Header header`."""
        return self.header_present

    def __eq__(self, other: object) -> bool:
        if not other or not isinstance(other, MsgSpec):
            return False
        return (self.types == other.types and self.names == other.names and self.constants == other.constants
                and self.text == other.text and self.full_name == other.full_name
                and self.short_name == other.short_name and self.package == other.package)

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        if self.constants:
            return f"MsgSpec[{self.constants!r}, {self.types!r}, {self.names!r}]"
        return f"MsgSpec[{self.types!r}, {self.names!r}]"

    def __str__(self) -> str:
        return self.text
