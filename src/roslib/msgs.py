"""roslib.msgs: rosbuild's message specs (MsgSpec with types, names, constants and text), loaded
from .msg text, files or type names; the definitions are parsed and checked by kame's parser
(kame.msg.parser), the specs keep the types as rosbuild spells them (`Header` stays `Header`).
"""

from __future__ import annotations

import os
import sys
from io import StringIO
from typing import Any

import rospkg
from kame import param_yaml
from kame.msg.errors import MessageError
from kame.msg.parser import parse_msg
from roslib import names as _names
from roslib import packages as _packages

__all__ = ["BUILTIN_TYPES", "COMMENTCHAR", "CONSTCHAR", "DURATION", "DURATION_MSG", "EXT", "EXTENDED_BUILTINS",
           "HEADER", "PRIMITIVE_TYPES", "RESERVED_TYPES", "SEP", "TIME", "TIME_MSG", "VERBOSE",
           "Constant", "Field", "MsgSpec", "MsgSpecException", "base_msg_type", "get_pkg_msg_specs", "get_registered",
           "is_builtin", "is_header_type", "is_registered", "is_valid_constant_type", "is_valid_msg_field_name",
           "is_valid_msg_type", "is_verbose", "list_msg_types", "load_by_type", "load_from_file", "load_from_string",
           "load_package", "load_package_dependencies", "msg_file", "parse_type", "register", "reinit",
           "resolve_type", "set_verbose"]

EXT = ".msg"
SEP = "/"
CONSTCHAR = "="
COMMENTCHAR = "#"
VERBOSE = False
HEADER = "Header"
TIME = "time"
DURATION = "duration"
PRIMITIVE_TYPES = ["int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64", "float32", "float64",
                   "string", "bool", "char", "byte"]
BUILTIN_TYPES = [*PRIMITIVE_TYPES, TIME, DURATION]
RESERVED_TYPES = [*BUILTIN_TYPES, HEADER]
TIME_MSG = "uint32 secs\nuint32 nsecs"
DURATION_MSG = "int32 secs\nint32 nsecs"
_INT_BITS = {"int8": 8, "uint8": 8, "int16": 16, "uint16": 16, "int32": 32, "uint32": 32, "int64": 64,
             "uint64": 64, "byte": 8, "char": 8}
_LOCAL = "roslib_msgs_local"  # the package kame's parser is given when the spec has none


class MsgSpecException(Exception):
    """A message definition that cannot be parsed, or a type that cannot be found."""


def is_verbose() -> bool:
    """Whether loading says what it loads on stdout (set_verbose)."""
    return VERBOSE


def set_verbose(v: bool) -> None:
    global VERBOSE
    VERBOSE = v


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
    """(base type, is array, fixed length or None); MsgSpecException for no type or a bad dimension
    (rosbuild's reading, character for character: 'a[' is a bad dimension, 'a]' a plain type)."""
    if not type_:
        raise MsgSpecException("Invalid empty type")
    if "[" not in type_:
        return type_, False, None
    splits = type_.split("[")
    if len(splits) > 2:
        raise MsgSpecException(f"Currently only support 1-dimensional array types: {type_}")
    if type_.endswith("[]"):
        return type_[:-2], True, None
    try:
        return splits[0], True, int(splits[1][:-1])
    except ValueError:
        raise MsgSpecException(f"Invalid array dimension: [{splits[1][:-1]}]") from None


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


EXTENDED_BUILTINS = {TIME: load_from_string(TIME_MSG), DURATION: load_from_string(DURATION_MSG)}
_loaded_packages: list[str] = []
_initialized = False


def _init() -> None:
    """Register Header (as Header, std_msgs/Header and roslib/Header) and time and duration, once."""
    global _initialized
    if _initialized:
        return
    std_msgs_dir = _packages.get_pkg_dir("std_msgs", required=False)
    if std_msgs_dir is None:
        raise MsgSpecException(f"Unable to locate roslib: {EXT} files cannot be loaded")
    header = os.path.join(std_msgs_dir, "msg", HEADER + EXT)
    if not os.path.isfile(header):
        sys.stderr.write(f"ERROR: cannot locate {HEADER}{EXT}. Expected to find it at '{header}'\n")
        return
    spec = load_from_file(header, "")[1]
    for name in (HEADER, "std_msgs/" + HEADER, "roslib/" + HEADER):
        register(name, spec)
    for name, builtin in EXTENDED_BUILTINS.items():
        register(name, builtin)
    _initialized = True


def reinit() -> None:
    """Forget every registered type and loaded package, then register the builtins again."""
    global _initialized
    _initialized = False
    del _loaded_packages[:]
    REGISTERED_TYPES.clear()
    _init()


def _convert_val(type_: str, val: str) -> Any:
    """A constant's value from its text: ValueError when it does not convert, MsgSpecException when
    an integer is out of its type's range or the type takes no constants."""
    if type_ in ("float32", "float64"):
        return float(val)
    if type_ == "string":
        return val.strip()
    bits = _INT_BITS.get(type_)
    if bits is not None:
        if type_[0] == "u" or type_ == "char":
            lower, upper = 0, 2**bits - 1
        else:
            upper = 2 ** (bits - 1) - 1
            lower = -upper - 1
        value = int(val)
        if value > upper or value < lower:
            raise MsgSpecException(f"cannot coerce [{value}] to {type_} (out of bounds)")
        return value
    if type_ == "bool":
        return bool(param_yaml.safe_load(val))  # rosbuild evaluates the text; YAML reads its literals
    raise MsgSpecException(f"invalid constant type: [{type_}]")


def get_pkg_msg_specs(package: str) -> tuple[list[tuple[str, MsgSpec]], list[str]]:
    """(('pkg/Type', spec) for each message of `package`, the types that failed to load)."""
    _init()
    specs = []
    failures = []
    for type_ in list_msg_types(package, False):
        try:
            specs.append(load_from_file(msg_file(package, type_), package))
        except Exception as exc:  # rosbuild reports each broken file and goes on
            failures.append(type_)
            print(f"ERROR: unable to load {type_}, {exc}")
    return specs, failures


def load_package_dependencies(package: str, load_recursive: bool = False) -> None:
    """Register the messages of the packages `package` depends on (directly; all with `load_recursive`).
    rosbuild read the direct ones from manifest.xml, which catkin packages lack (it raised
    InvalidROSPkgException for them); kame asks rospack."""
    _init()
    if VERBOSE:
        print("Load dependencies for package", package)
    depends = rospkg.RosPack().get_depends(package, implicit=load_recursive)
    for depend in depends:
        if depend in _loaded_packages or depend == package:
            continue
        _loaded_packages.append(depend)
        for key, spec in get_pkg_msg_specs(depend)[0]:
            register(key, spec)


def load_package(package: str) -> None:
    """Register the messages of `package`, under their short and full names."""
    _init()
    if VERBOSE:
        print("Load package", package)
    if package in _loaded_packages:
        if VERBOSE:
            print(f"Package {package} is already loaded")
        return
    _loaded_packages.append(package)
    for key, spec in get_pkg_msg_specs(package)[0]:
        register(key, spec)
        register(package + _names.PRN_SEPARATOR + key, spec)
