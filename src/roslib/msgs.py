"""roslib.msgs: rosbuild's message specs (MsgSpec with types, names, constants and text), loaded
from .msg text, files or type names; the definitions are parsed and checked by kame's parser
(kame.msg.parser), the specs keep the types as rosbuild spells them (`Header` stays `Header`).
"""

from __future__ import annotations

import os
from io import StringIO
from typing import Any

from kame.msg.errors import MessageError
from kame.msg.parser import parse_msg, split_array_type
from roslib import names as _names
from roslib import packages as _packages

__all__ = ["BUILTIN_TYPES", "DURATION", "EXT", "HEADER", "PRIMITIVE_TYPES", "RESERVED_TYPES", "SEP", "TIME",
           "Constant", "Field", "MsgSpec", "MsgSpecException", "base_msg_type", "get_registered", "is_builtin",
           "is_header_type", "is_registered", "is_valid_constant_type", "is_valid_msg_field_name",
           "is_valid_msg_type", "list_msg_types", "load_by_type", "load_from_file", "load_from_string", "msg_file",
           "parse_type", "register", "resolve_type"]

EXT = ".msg"
SEP = "/"
HEADER = "Header"
TIME = "time"
DURATION = "duration"
PRIMITIVE_TYPES = ["int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64",
                   "string", "bool", "char", "byte"]
BUILTIN_TYPES = [*PRIMITIVE_TYPES, TIME, DURATION]
RESERVED_TYPES = [*BUILTIN_TYPES, HEADER]
_LOCAL = "roslib_msgs_local"  # the package kame's parser is given when the spec has none


class MsgSpecException(Exception):
    """A message definition that cannot be parsed, or a type that cannot be found."""


def base_msg_type(type_: str | None) -> str | None:
    """'std_msgs/String[3]' -> 'std_msgs/String'."""
    if type_ is None:
        return None
    return type_[:type_.find("[")] if "[" in type_ else type_


def resolve_type(type_: str, package_context: str) -> str:
    """'String', 'std_msgs' -> 'std_msgs/String'; builtins as they are; Header -> std_msgs/Header."""
    base = base_msg_type(type_)
    if base in BUILTIN_TYPES:
        return type_
    if base == HEADER:
        return "std_msgs/Header"
    return type_ if SEP in type_ else f"{package_context}{SEP}{type_}"


def parse_type(type_: str) -> tuple[str, bool, int | None]:
    """(base type, is array, fixed length or None); MsgSpecException for no type or a bad dimension."""
    if not type_:
        raise MsgSpecException("Invalid empty type")
    if type_.count("[") > 1:
        raise MsgSpecException(f"Currently only support 1-dimensional array types: {type_}")
    try:
        return split_array_type(type_)
    except (MessageError, ValueError):
        raise MsgSpecException(f"Invalid array dimension: [{type_[type_.find('[') + 1:-1]}]") from None


def is_valid_msg_type(x: str) -> bool:
    """A legal type name with any number of `[]`/`[N]` suffixes."""
    if not x or len(x) != len(x.strip()):
        return False
    base = str(base_msg_type(x))
    if not _names.is_legal_resource_name(base):
        return False
    rest = x[len(base):]
    while rest:
        close = rest.find("]")
        if not rest.startswith("[") or close < 0 or not (rest[1:close].isdigit() or close == 1):
            return False
        rest = rest[close + 1:]
    return True


def is_valid_constant_type(x: str) -> bool:
    return x in PRIMITIVE_TYPES


def is_valid_msg_field_name(x: str) -> bool:
    return _names.is_legal_resource_base_name(x)


def is_header_type(type_: str) -> bool:
    return type_ in (HEADER, "std_msgs/Header", "roslib/Header")


def is_builtin(msg_type_name: str) -> bool:
    return msg_type_name in BUILTIN_TYPES


class Constant:
    __slots__ = ["name", "type", "val", "val_text"]

    def __init__(self, type_: str, name: str, val: Any, val_text: str) -> None:
        if type_ is None or name is None or val is None or val_text is None:
            raise ValueError("Constant must have non-None parameters")
        self.type = type_
        self.name = name.strip()
        self.val = val
        self.val_text = val_text

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Constant) and (self.type, self.name, self.val) == (other.type, other.name, other.val)

    def __hash__(self) -> int:
        return hash((self.type, self.name))

    def __repr__(self) -> str:
        return f"{self.type} {self.name}={self.val}"

    __str__ = __repr__


class Field:
    def __init__(self, name: str, type: str) -> None:
        self.name = name
        self.type = type
        self.base_type, self.is_array, self.array_len = parse_type(type)
        self.is_header = is_header_type(self.base_type)
        self.is_builtin = is_builtin(self.base_type)

    def __repr__(self) -> str:
        return f"[{self.name}, {self.type}, {self.base_type}, {self.is_array}, {self.array_len}]"


class MsgSpec:
    def __init__(self, types: list[str], names: list[str], constants: list[Constant], text: str,
                 full_name: str = "", short_name: str = "", package: str = "") -> None:
        if len(set(names)) != len(names):
            raise MsgSpecException(f"Duplicate field names in message: {names}")
        self.types = types
        self.names = names
        self.constants = constants
        self.header_present = bool(types) and is_header_type(types[0]) and names[0] == "header"
        self.text = text
        self.full_name = full_name
        self.short_name = short_name
        self.package = package
        self._parsed_fields = [Field(name, type_) for name, type_ in zip(names, types, strict=True)]

    def fields(self) -> list[tuple[str, str]]:
        """(type, name) pairs."""
        return list(zip(self.types, self.names, strict=True))

    def parsed_fields(self) -> list[Field]:
        return self._parsed_fields

    def has_header(self) -> bool:
        return self.header_present

    def __eq__(self, other: object) -> bool:
        return isinstance(other, MsgSpec) and (self.types, self.names, self.constants, self.text) == (
            other.types, other.names, other.constants, other.text)

    def __hash__(self) -> int:
        return hash((tuple(self.types), tuple(self.names)))

    def __repr__(self) -> str:
        if self.constants:
            return f"MsgSpec[{self.constants!r}, {self.types!r}, {self.names!r}]"
        return f"MsgSpec[{self.types!r}, {self.names!r}]"

    def __str__(self) -> str:
        buff = StringIO()
        for c in self.constants:
            buff.write(f"{c.type} {c.name}={c.val_text}\n")
        for type_, name in self.fields():
            buff.write(f"{type_} {name}\n")
        return buff.getvalue().rstrip("\n")


def _declared_type(type_: str, package_context: str) -> str:
    """A field type as rosbuild keeps it: bare names in the package, reserved names as written."""
    if package_context and SEP not in type_ and base_msg_type(type_) not in RESERVED_TYPES:
        return f"{package_context}/{type_}"
    return type_


def load_from_string(text: str, package_context: str = "", full_name: str = "", short_name: str = "") -> MsgSpec:
    """The spec of .msg `text`; MsgSpecException (with kame's parser's reason) when it is no definition."""
    try:
        parsed = parse_msg(text, f"{package_context or _LOCAL}/{short_name or 'Message'}")
    except MessageError as exc:
        raise MsgSpecException(str(exc)) from None
    declared = [line.split("#")[0].split() for line in text.split("\n")]
    types = [_declared_type(words[0], package_context) for words in declared if len(words) == 2 and "=" not in
             " ".join(words)]
    constants = [Constant(c.type, c.name, c.value, c.value_text) for c in parsed.constants]
    return MsgSpec(types, list(parsed.names), constants, text, full_name, short_name, package_context)


def load_from_file(file_path: str, package_context: str = "") -> tuple[str, MsgSpec]:
    """('pkg/Name', spec) of a .msg file."""
    file_name = os.path.basename(file_path)
    short = file_name[:-len(EXT)]
    package_context = package_context.rstrip(SEP)
    type_ = f"{package_context}{SEP}{short}" if package_context else short
    if not _names.is_legal_resource_name(type_):
        raise MsgSpecException(f"{file_path}: [{type_}] is not a legal type name")
    with open(file_path) as f:
        text = f.read()
    try:
        return type_, load_from_string(text, package_context, type_, short)
    except MsgSpecException as exc:
        raise MsgSpecException(f"{file_name}: {exc}") from None


def msg_file(package: str, type_: str) -> str:
    """The path of `package`'s msg/<type_>.msg (which need not exist)."""
    return _packages.resource_file(package, "msg", type_ + EXT)


def list_msg_types(package: str, include_depends: bool) -> list[str]:
    """The message types (short names) `package` defines."""
    folder = os.path.dirname(msg_file(package, "x"))
    if not os.path.isdir(folder):
        return []
    return sorted(f[:-len(EXT)] for f in os.listdir(folder) if f.endswith(EXT) and not f.startswith("."))


def load_by_type(msgtype: str, package_context: str = "") -> tuple[str, MsgSpec]:
    """('pkg/Name', spec) of a type found by name (in `package_context` when it has no package)."""
    package, base = _names.package_resource_name(msgtype)
    package = package or package_context
    try:
        path = msg_file(package, base)
    except _packages.InvalidROSPkgException:
        raise MsgSpecException(
            f"Cannot locate message type [{msgtype}], package [{package}] does not exist") from None
    return load_from_file(path, package)


REGISTERED_TYPES: dict[str, MsgSpec] = {}


def is_registered(msg_type_name: str) -> bool:
    return msg_type_name in REGISTERED_TYPES


def get_registered(msg_type_name: str, default_package: str | None = None) -> MsgSpec:
    if msg_type_name in REGISTERED_TYPES:
        return REGISTERED_TYPES[msg_type_name]
    if default_package:
        full = f"{default_package}{SEP}{msg_type_name}"
        if full in REGISTERED_TYPES:
            return REGISTERED_TYPES[full]
    raise KeyError(msg_type_name)


def register(msg_type_name: str, msg_spec: MsgSpec) -> None:
    REGISTERED_TYPES[msg_type_name] = msg_spec
