"""genmsg.msg_loader: MsgSpecs and SrvSpecs loaded from text, files or type names along a
search path ({package: [msg folder, ...]}), and the MsgContext that holds them and their
dependencies. Each definition is parsed by kame's parser (kame.msg.parser), whose errors come
out as InvalidMsgSpec."""

from __future__ import annotations

import ast
import os
from collections.abc import Mapping, Sequence
from io import StringIO as StringIO  # genmsg.msg_loader's name, imported from it by old code
from typing import Any

from genmsg.base import COMMENTCHAR, CONSTCHAR, EXT_MSG, EXT_SRV, IODELIM, SEP, InvalidMsgSpec, log
from genmsg.msgs import (
    DURATION,
    DURATION_MSG,
    HEADER,
    HEADER_FULL_NAME,
    TIME,
    TIME_MSG,
    Constant,
    Field,
    MsgSpec,
    bare_msg_type,
    is_builtin,
    is_valid_constant_type,
    is_valid_msg_field_name,
    is_valid_msg_type,
    resolve_type,
)
from genmsg.names import normalize_package_context, package_resource_name
from genmsg.srvs import SrvSpec
from kame.msg import parser as _parser
from kame.msg.errors import MsgDefinitionError

__all__ = ["COMMENTCHAR", "CONSTCHAR", "DURATION", "DURATION_MSG", "EXT_MSG", "EXT_SRV", "HEADER", "HEADER_FULL_NAME",
           "IODELIM", "SEP", "TIME", "TIME_MSG", "Constant", "Field", "InvalidMsgSpec", "MsgContext", "MsgNotFound",
           "MsgSpec", "SrvSpec", "bare_msg_type", "convert_constant_value", "get_msg_file", "get_srv_file",
           "is_builtin", "is_valid_constant_type", "is_valid_msg_field_name", "is_valid_msg_type", "load_depends",
           "load_msg_by_type", "load_msg_depends", "load_msg_from_file", "load_msg_from_string",
           "load_srv_by_type", "load_srv_from_file", "load_srv_from_string", "log", "normalize_package_context",
           "package_resource_name", "resolve_type"]

SearchPath = Mapping[str, Sequence[str]]
# kame's parser resolves a bare type name in a package; a spec without one (`time`, a
# message_definition read as 'Foo') is parsed in this stand-in, which is taken off again
_NO_PACKAGE = "genmsg_no_package"


class MsgNotFound(Exception):
    """A type whose file is not on the search path."""

    def __init__(self, message: str, base_type: str | None = None, package: str | None = None,
                 search_path: Any = None) -> None:
        super().__init__(message)
        self.base_type = base_type
        self.package = package
        self.search_path = search_path


def _check_search_path(search_path: object) -> None:
    if not isinstance(search_path, dict):
        raise ValueError("search_path must be a dictionary of {namespace: dirpath}")


def get_msg_file(package: str, base_type: str, search_path: SearchPath, ext: str = EXT_MSG) -> str:
    """The first `<folder>/<base_type><ext>` of `package`'s folders; MsgNotFound if none."""
    log(f"msg_file({package}, {base_type}, {search_path})")
    _check_search_path(search_path)
    if package not in search_path:
        raise MsgNotFound(f"Cannot locate message [{base_type}]: unknown package [{package}] on search path "
                          f"[{search_path}]", base_type, package, search_path)
    for folder in search_path[package]:
        path = os.path.join(folder, base_type + ext)
        if os.path.isfile(path):
            return path
    raise MsgNotFound(f"Cannot locate message [{base_type}] in package [{package}] with paths "
                      f"[{search_path[package]}]", base_type, package, search_path)


def get_srv_file(package: str, base_type: str, search_path: SearchPath) -> str:
    return get_msg_file(package, base_type, search_path, ext=EXT_SRV)


def load_msg_by_type(msg_context: MsgContext, msg_type: str, search_path: SearchPath) -> MsgSpec:
    """The spec of `msg_type` ('Header' is std_msgs/Header) from its file, registered in `msg_context`."""
    log(f"load_msg_by_type({msg_type}, {search_path})")
    _check_search_path(search_path)
    if msg_type == HEADER:
        msg_type = HEADER_FULL_NAME
    package_name, base_type = package_resource_name(msg_type)
    file_path = get_msg_file(package_name, base_type, search_path)
    spec = load_msg_from_file(msg_context, file_path, msg_type)
    msg_context.set_file(msg_type, file_path)
    return spec


def load_srv_by_type(msg_context: MsgContext, srv_type: str, search_path: SearchPath) -> SrvSpec:
    """The spec of the service `srv_type` from its file (its request and response registered)."""
    log(f"load_srv_by_type({srv_type}, {search_path})")
    _check_search_path(search_path)
    package_name, base_type = package_resource_name(srv_type)
    return load_srv_from_file(msg_context, get_srv_file(package_name, base_type, search_path), srv_type)


def convert_constant_value(field_type: str, val: str) -> bool | int | float | str:
    """A constant's text as its value: ValueError (or SyntaxError for a bool) for text that is
    not one, InvalidMsgSpec for an integer out of its type's range or a type without constants."""
    if field_type in ("float32", "float64"):
        return float(val)
    if field_type == "string":
        return val.strip()
    if field_type == "bool":
        return bool(ast.literal_eval(val))
    if field_type not in _parser.INT_RANGES:
        raise InvalidMsgSpec(f"invalid constant type: [{field_type}]")
    value = int(val)
    lower, upper = _parser.INT_RANGES[field_type]
    if not lower <= value <= upper:
        raise InvalidMsgSpec(f"cannot coerce [{value}] to {field_type} (out of bounds)")
    return value


def _kame_full_name(full_name: str) -> tuple[str, str]:
    package, short = package_resource_name(full_name)
    return (package, full_name) if package else ("", f"{_NO_PACKAGE}/{short}")


def _genmsg_type(kame_type: str) -> str:
    prefix = _NO_PACKAGE + SEP
    return kame_type[len(prefix):] if kame_type.startswith(prefix) else kame_type


def load_msg_from_string(msg_context: MsgContext, text: str, full_name: str) -> MsgSpec:
    """The spec of .msg `text` for the type `full_name`, registered in `msg_context`."""
    log("load_msg_from_string", full_name)
    package_name, kame_name = _kame_full_name(full_name)
    try:
        parsed = _parser.parse_msg(text, kame_name)
    except MsgDefinitionError as exc:
        raise InvalidMsgSpec(str(exc)) from None
    constants = [Constant(c.type, c.name, c.value, c.value_text) for c in parsed.constants]
    spec = MsgSpec([_genmsg_type(f.type) for f in parsed.fields], [f.name for f in parsed.fields], constants, text,
                   full_name, package_name)
    msg_context.register(full_name, spec)
    return spec


def _read(file_path: str) -> str:
    with open(file_path) as f:
        return f.read()


def load_msg_from_file(msg_context: MsgContext, file_path: str, full_name: str) -> MsgSpec:
    """The spec of the .msg file, registered in `msg_context`; its errors name the file."""
    log("Load spec from", file_path)
    text = _read(file_path)
    try:
        return load_msg_from_string(msg_context, text, full_name)
    except InvalidMsgSpec as e:
        raise InvalidMsgSpec(f"{file_path}: {e}") from None


def load_msg_depends(msg_context: MsgContext, spec: MsgSpec, search_path: SearchPath) -> list[str]:
    """Load (and register) every message `spec` uses, recursively; the types it uses directly,
    in field order, repeats kept."""
    package_context = spec.package
    log("load_msg_depends <spec>", spec.full_name, package_context)
    depends = []
    for unresolved_type in spec.types:
        resolved_type = resolve_type(str(bare_msg_type(unresolved_type)), package_context)
        if is_builtin(resolved_type):
            continue
        if msg_context.is_registered(resolved_type):
            depspec = msg_context.get_registered(resolved_type)
        else:
            depspec = load_msg_by_type(msg_context, resolved_type, search_path)
            msg_context.register(resolved_type, depspec)
        depends.append(resolved_type)
        if msg_context.get_depends(resolved_type) is None:
            load_msg_depends(msg_context, depspec, search_path)
    msg_context.set_depends(spec.full_name, depends)
    return depends[:]


def load_depends(msg_context: MsgContext, spec: MsgSpec | SrvSpec, msg_search_path: SearchPath) -> list[str]:
    """load_msg_depends for a message, or for a service's request then response."""
    if isinstance(spec, MsgSpec):
        return load_msg_depends(msg_context, spec, msg_search_path)
    if isinstance(spec, SrvSpec):
        depends = load_msg_depends(msg_context, spec.request, msg_search_path)
        depends.extend(load_msg_depends(msg_context, spec.response, msg_search_path))
        return depends
    raise ValueError("spec does not appear to be a message or service")


class MsgContext:
    """The MsgSpecs loaded so far by type, the files they came from and each one's direct
    dependencies. Services are never registered, their request and response messages are."""

    def __init__(self) -> None:
        self._registered_packages: dict[str, dict[str, MsgSpec]] = {}
        self._files: dict[str, str] = {}
        self._dependencies: dict[str, list[str]] = {}

    def set_file(self, full_msg_type: str, file_path: str) -> None:
        self._files[full_msg_type] = file_path

    def get_file(self, full_msg_type: str) -> str | None:
        return self._files.get(full_msg_type)

    def set_depends(self, full_msg_type: str, dependencies: list[str]) -> None:
        log("set_depends", full_msg_type, dependencies)
        self._dependencies[full_msg_type] = dependencies

    def get_depends(self, full_msg_type: str) -> list[str] | None:
        """The types `full_msg_type` uses directly; None when they were not loaded."""
        return self._dependencies.get(full_msg_type)

    def get_all_depends(self, full_msg_type: str) -> list[str]:
        """Every type it uses, depth first, repeats kept; KeyError when they were not loaded."""
        depends = self.get_depends(full_msg_type)
        if depends is None:
            raise KeyError(full_msg_type)
        all_deps = []
        for d in depends:
            all_deps.append(d)
            all_deps.extend(self.get_all_depends(d))
        return all_deps

    @staticmethod
    def create_default() -> MsgContext:
        """A context holding time and duration (the builtins with fields, for serializers)."""
        msg_context = MsgContext()
        load_msg_from_string(msg_context, TIME_MSG, TIME)
        load_msg_from_string(msg_context, DURATION_MSG, DURATION)
        return msg_context

    def register(self, full_msg_type: str, msgspec: MsgSpec) -> None:
        package, base_type = package_resource_name(str(bare_msg_type(full_msg_type)))
        self._registered_packages.setdefault(package, {})[base_type] = msgspec

    def is_registered(self, full_msg_type: str) -> bool:
        package, base_type = package_resource_name(str(bare_msg_type(full_msg_type)))
        return base_type in self._registered_packages.get(package, {})

    def get_registered(self, full_msg_type: str) -> MsgSpec:
        """The spec of `full_msg_type` (array suffix ignored); KeyError if not registered."""
        full_msg_type = str(bare_msg_type(full_msg_type))
        if not self.is_registered(full_msg_type):
            raise KeyError(full_msg_type)
        package, base_type = package_resource_name(full_msg_type)
        return self._registered_packages[package][base_type]

    def __str__(self) -> str:
        return str(self._registered_packages)


def load_srv_from_string(msg_context: MsgContext, text: str, full_name: str) -> SrvSpec:
    """The spec of .srv `text`: its request and response (texts split at the `---` line, each
    keeping its comments) registered as `<full_name>Request` and `<full_name>Response`."""
    sections = _parser.split_sections(text)
    request = load_msg_from_string(msg_context, sections[0], f"{full_name}Request")
    response = load_msg_from_string(msg_context, "".join(sections[1:]), f"{full_name}Response")
    return SrvSpec(request, response, text, full_name)


def load_srv_from_file(msg_context: MsgContext, file_path: str, full_name: str) -> SrvSpec:
    log(f"Load spec from {file_path} {full_name}\n")
    spec = load_srv_from_string(msg_context, _read(file_path), full_name)
    msg_context.set_file(f"{full_name}Request", file_path)
    msg_context.set_file(f"{full_name}Response", file_path)
    return spec
