"""genpy.generator: message and service modules written into a package's build, as catkin's
genpy step calls them (MsgGenerator().generate_messages(package, files, outdir, search_path)),
with kame's codegen (kame.msg.build): the modules are those kame-genmsg writes.

`search_path` maps package names to their msg/ (or srv/) folders, as genmsg gives it; types
it does not name come from the packages kame ships.

The helpers genpy's generator is made of answer as genpy's do: compute_pkg_type, compute_import,
compute_constructor, default_value (Python expressions, as text, in genpy's spelling) and
make_python_safe. Their `msg_context` is anything with genmsg's MsgContext's is_registered and
get_registered (roslib.msgs itself, whose register() fills it). msg_generator and srv_generator
yield the lines of kame's module for a spec; they read the types it uses from `search_path`,
not from `msg_context`.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any, Protocol

from genpy.base import SIMPLE_TYPES, is_simple
from genpy.generate_numpy import NUMPY_DTYPE, pack_numpy, unpack_numpy
from genpy.generate_struct import (
    clear_patterns,
    compute_struct_pattern,
    get_patterns,
    int32_pack,
    int32_unpack,
    pack,
    pack2,
    reduce_pattern,
    unpack,
    unpack2,
    unpack3,
)
from kame.msg.build import message_module, service_module
from kame.msg.catalog import SHARE_DIR, MsgCatalog, Package, find_packages
from kame.msg.codegen import python_name
from kame.msg.errors import MessageError
from kame.msg.parser import is_legal_base_name, parse_msg, parse_srv
from roslib.msgs import HEADER, SEP, Constant, MsgSpec, is_builtin, is_header_type, parse_type

__all__ = ["NUMPY_DTYPE", "SIMPLE_TYPES", "Generator", "MsgGenerationException", "MsgGenerator", "SrvGenerator",
           "clear_patterns", "compute_constructor", "compute_import", "compute_outfile_name", "compute_pkg_type",
           "compute_resource_name", "compute_struct_pattern", "default_value", "get_patterns", "get_special",
           "int32_pack", "int32_unpack", "is_simple", "is_special", "make_python_safe", "msg_generator", "pack",
           "pack2", "pack_numpy", "reduce_pattern", "srv_generator", "unpack", "unpack2", "unpack3",
           "unpack_numpy"]


class MsgGenerationException(Exception):
    """A package or definition that cannot be generated."""


def compute_resource_name(filename: str, ext: str) -> str:
    """'/path/to/Foo.msg', '.msg' -> 'Foo'."""
    return os.path.basename(filename)[:-len(ext)]


def compute_outfile_name(outdir: str, infile_name: str, ext: str) -> str:
    """The generated module's path: a leading `_` keeps it from shadowing the class name."""
    return os.path.join(outdir, "_" + compute_resource_name(infile_name, ext) + ".py")


def _remap_reserved(field_name: str) -> str:
    """A field named like a Python keyword gets genpy's trailing underscore (the last part of a
    dotted name only)."""
    prefix, dot, name = field_name.rpartition(".")
    return prefix + dot + python_name(name) if prefix else python_name(field_name)


class MsgContext(Protocol):
    def is_registered(self, full_msg_type: str) -> bool: ...

    def get_registered(self, full_msg_type: str) -> Any: ...


class Special:
    """A builtin type that is a class in Python: how to build one, fix it after
    deserializing, and import it."""

    def __init__(self, constructor: str, post_deserialize: str | None, import_str: str) -> None:
        self.constructor = constructor
        self.post_deserialize = post_deserialize
        self.import_str = import_str

    def get_post_deserialize(self, varname: str) -> str | None:
        return self.post_deserialize % varname if self.post_deserialize else None


_SPECIAL_TYPES = {
    HEADER: Special("std_msgs.msg._Header.Header()", None, "import std_msgs.msg"),
    "time": Special("genpy.Time()", "%s.canon()", "import genpy"),
    "duration": Special("genpy.Duration()", "%s.canon()", "import genpy"),
}
_INTEGERS = ("byte", "int8", "int16", "int32", "int64", "char", "uint8", "uint16", "uint32", "uint64")


def is_special(type_: str) -> bool:
    """True for the builtins that are classes (Header, time, duration)."""
    return type_ in _SPECIAL_TYPES


def get_special(type_: str) -> Special | None:
    return _SPECIAL_TYPES.get(type_)


def compute_pkg_type(package: str, type_: str) -> tuple[str, str]:
    """(package, type) of `type_`, in `package` when it names none; MsgGenerationException for
    a name with more than one `/`."""
    splits = type_.split(SEP)
    if len(splits) == 1:
        return package, splits[0]
    if len(splits) == 2:
        return splits[0], splits[1]
    raise MsgGenerationException(f"illegal message type: {type_}")


def _bare(type_: str) -> str:
    return type_.partition("[")[0]


def compute_constructor(msg_context: MsgContext, package: str, type_: str) -> str | None:
    """The expression building a `type_` (in `package`): None for an array or an unknown type."""
    special = get_special(type_)
    if special is not None:
        return special.constructor
    if _bare(type_) != type_:
        return None
    base_pkg, base_type = compute_pkg_type(package, type_)
    if not msg_context.is_registered(f"{base_pkg}/{base_type}"):
        return None
    return f"{base_pkg}.msg.{base_type}()"


def default_value(msg_context: MsgContext, field_type: str, default_package: str) -> str | None:
    """A field's default as genpy writes it in a generated module (`'0.'`, `"b''"`,
    `'[0] * 3'`, `'std_msgs.msg.Header()'`); None for a type `msg_context` does not know."""
    if field_type in _INTEGERS:
        return "0"
    if field_type in ("float32", "float64"):
        return "0."
    if field_type == "string":
        return "''"
    if field_type == "bool":
        return "False"
    if not field_type.endswith("]"):
        return compute_constructor(msg_context, default_package, field_type)
    base_type, _, array_len = parse_type(field_type)
    if base_type in ("char", "uint8"):  # bytes, as genpy holds them
        return "b''" if array_len is None else f"b'\\0'*{array_len}"
    if array_len is None:
        return "[]"
    element = default_value(msg_context, base_type, default_package)
    if element is None:  # genpy fails on this (a TypeError concatenating None)
        return None
    if base_type in _INTEGERS or base_type in ("float32", "float64", "string", "bool"):
        return f"[{element}] * {array_len}"
    return f"[{element} for _ in range({array_len})]"  # a distinct message in each slot


def make_python_safe(spec: Any) -> MsgSpec:
    """The spec with fields and constants named like Python keywords renamed (`from_`)."""
    package, _, short = str(spec.full_name).rpartition(SEP)
    constants = [Constant(c.type, _remap_reserved(c.name), c.val, c.val_text) for c in spec.constants]
    return MsgSpec(list(spec.types), [_remap_reserved(n) for n in spec.names], constants, spec.text,
                   spec.full_name, short, package)


def compute_import(msg_context: MsgContext, package: str, type_: str) -> list[str]:
    """The import statements a module of `package` needs to use `type_`, its own types' first
    (each once); none for a primitive or a type `msg_context` does not know."""
    orig_base_type = _bare(type_)
    pkg, base_type = compute_pkg_type(package, orig_base_type)
    full_msg_type = f"{pkg}/{base_type}"
    if is_builtin(orig_base_type) or is_header_type(orig_base_type):
        special = get_special(base_type)
        return [special.import_str] if special is not None else []
    if not msg_context.is_registered(full_msg_type):
        return []
    imports = [f"import {pkg}.msg"]
    for t in msg_context.get_registered(full_msg_type).types:
        if t == full_msg_type:
            raise MsgGenerationException(f"msg [{full_msg_type}] has circular self-dependencies")
        # genpy resolves the field types against the importing package, not pkg: kept
        imports.extend(x for x in compute_import(msg_context, package, t) if x not in imports)
    return imports


def msg_generator(msg_context: MsgContext, spec: Any, search_path: Mapping[str, Iterable[str]]) -> Iterator[str]:
    """The lines of the module of the message `spec` (types it uses from `search_path`)."""
    package = str(spec.full_name).partition(SEP)[0]
    catalog = _catalog(package, (), search_path)
    try:
        catalog.add_spec(parse_msg(spec.text, spec.full_name))
        text = message_module(catalog, spec.full_name, spec.full_name)
    except MessageError as exc:
        raise MsgGenerationException(str(exc)) from None
    yield from text.splitlines()


def srv_generator(msg_context: MsgContext, spec: Any, search_path: Mapping[str, Iterable[str]]) -> Iterator[str]:
    """The lines of the module of the service `spec`: request, response and service classes."""
    package = str(spec.full_name).partition(SEP)[0]
    catalog = _catalog(package, (), search_path)
    try:
        catalog.add_srv_spec(parse_srv(spec.text, spec.full_name))
        text = service_module(catalog, spec.full_name, spec.full_name)
    except MessageError as exc:
        raise MsgGenerationException(str(exc)) from None
    yield from text.splitlines()


def _catalog(package: str, package_files: Iterable[str], search_path: Mapping[str, Iterable[str]]) -> MsgCatalog:
    packages = dict(find_packages([SHARE_DIR]))
    for name, folders in search_path.items():
        for folder in folders:
            packages[name] = Package(name, Path(folder).resolve().parent)
            break
    for file in package_files:  # <package>/msg/Foo.msg: the package is two folders up
        packages.setdefault(package, Package(package, Path(file).resolve().parent.parent))
    return MsgCatalog(packages)


class Generator:
    """Writes one module per interface file of a package into `outdir`."""

    def __init__(self, what: str, ext: str, module_fn: Callable[[MsgCatalog, str, str], str]) -> None:
        self.what = what
        self.ext = ext
        self.module_fn = module_fn

    def generate(self, catalog: MsgCatalog, full_type: str, f: str, outdir: str) -> str:
        os.makedirs(outdir, exist_ok=True)
        outfile = compute_outfile_name(outdir, os.path.basename(f), self.ext)
        text = self.module_fn(catalog, full_type, os.path.basename(f))
        Path(outfile).write_text(text, encoding="utf-8")
        return outfile

    def generate_messages(self, package: str, package_files: Iterable[str], outdir: str,
                          search_path: Mapping[str, Iterable[str]]) -> int:
        """0, or 1 when a file could not be generated (each failure said on stderr, as genpy does)."""
        if not is_legal_base_name(package):
            raise MsgGenerationException(
                f"\nERROR: package name '{package}' is illegal and cannot be used in message generation.\n"
                "Please see http://ros.org/wiki/Names")
        files = [os.path.abspath(f) for f in package_files]
        catalog = _catalog(package, files, search_path)
        retcode = 0
        for f in files:
            try:
                self.generate(catalog, f"{package}/{compute_resource_name(f, self.ext)}", f, outdir)
            except (MessageError, OSError) as exc:
                print(f"\nERROR: Unable to generate {self.what} for package '{package}': while processing '{f}': "
                      f"{exc}\n", file=sys.stderr)
                retcode = 1
        return retcode


class MsgGenerator(Generator):
    """Message modules (`_Foo.py` for each `msg/Foo.msg`)."""

    def __init__(self) -> None:
        super().__init__("messages", ".msg", message_module)


class SrvGenerator(Generator):
    """Service modules (`_Foo.py` for each `srv/Foo.srv`: Foo, FooRequest, FooResponse)."""

    def __init__(self) -> None:
        super().__init__("services", ".srv", service_module)
