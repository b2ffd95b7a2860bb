"""genpy.generator: message and service modules written into a package's build, as catkin's
genpy step calls them (MsgGenerator().generate_messages(package, files, outdir, search_path)),
with kame's codegen (kame.msg.build): the modules are those kame-genmsg writes.

`search_path` maps package names to their msg/ (or srv/) folders, as genmsg gives it; types
it does not name come from the packages kame ships.

The helpers genpy's generator is made of answer as genpy's do: compute_pkg_type, compute_import,
compute_constructor, default_value (Python expressions, as text, in genpy's spelling),
make_python_safe, flatten, and the serializer code writers (serialize_fn_generator and the
*_serializer_generator family: the lines genpy writes). Their `msg_context` is genmsg's MsgContext
(kame's genmsg) or anything with its is_registered and get_registered (roslib.msgs itself).
msg_generator and srv_generator yield the lines of kame's module for a spec; they read the types
it uses from `search_path`, not from `msg_context`.
"""

from __future__ import annotations

import os
import struct
import sys
from collections.abc import Callable, Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any, Protocol

import genmsg
from genmsg import SEP, Constant, InvalidMsgSpec, MsgContext, MsgGenerationException, MsgSpec
from genmsg.base import log
from genmsg.msgs import DURATION, HEADER, TIME, is_builtin, is_header_type, parse_type
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

__all__ = ["INDENT", "NUMPY_DTYPE", "SIMPLE_TYPES", "Generator", "InvalidMsgSpec", "MsgContext",
           "MsgGenerationException",
           "MsgGenerator", "SrvGenerator", "array_serializer_generator", "clear_patterns",
           "complex_serializer_generator", "compute_constructor", "compute_full_text_escaped", "compute_import",
           "compute_outfile_name", "compute_pkg_type", "compute_post_deserialize", "compute_resource_name",
           "compute_struct_pattern", "default_value", "deserialize_fn_generator", "flatten", "get_patterns",
           "get_registered_ex", "get_special", "int32_pack", "int32_unpack", "is_simple", "is_special",
           "len_serializer_generator", "log", "make_python_safe", "msg_generator", "next_var", "pack", "pack2",
           "pack_numpy", "pop_context", "push_context", "reduce_pattern", "reset_var", "serialize_fn_generator",
           "serializer_generator", "simple_serializer_generator", "srv_generator", "string_serializer_generator",
           "unpack", "unpack2", "unpack3", "unpack_numpy"]


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


class _Context(Protocol):
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
    TIME: Special("genpy.Time()", "%s.canon()", "import genpy"),
    DURATION: Special("genpy.Duration()", "%s.canon()", "import genpy"),
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


def compute_constructor(msg_context: _Context, package: str, type_: str) -> str | None:
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


def default_value(msg_context: _Context, field_type: str, default_package: str) -> str | None:
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
    constants = [Constant(c.type, _remap_reserved(c.name), c.val, c.val_text) for c in spec.constants]
    return MsgSpec(list(spec.types), [_remap_reserved(n) for n in spec.names], constants, spec.text, spec.full_name)


def compute_import(msg_context: _Context, package: str, type_: str) -> list[str]:
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


def msg_generator(msg_context: _Context, spec: Any, search_path: Mapping[str, Iterable[str]]) -> Iterator[str]:
    """The lines of the module of the message `spec` (types it uses from `search_path`)."""
    package = str(spec.full_name).partition(SEP)[0]
    catalog = _catalog(package, (), search_path)
    try:
        catalog.add_spec(parse_msg(spec.text, spec.full_name))
        text = message_module(catalog, spec.full_name, spec.full_name)
    except MessageError as exc:
        raise MsgGenerationException(str(exc)) from None
    yield from text.splitlines()


def srv_generator(msg_context: _Context, spec: Any, search_path: Mapping[str, Iterable[str]]) -> Iterator[str]:
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


def get_registered_ex(msg_context: _Context, type_: str) -> Any:
    """msg_context.get_registered, with any failure as MsgGenerationException."""
    try:
        return msg_context.get_registered(type_)
    except Exception:
        raise MsgGenerationException(
            f"Unknown type [{type_}]. Please check that the manifest.xml correctly declares dependencies.") from None


def flatten(msg_context: _Context, msg: Any) -> MsgSpec:
    """The spec with each embedded (non-array) message's fields in place of it ('pose.position.x'):
    not a real message, the field list genpy's serializers batch into struct calls."""
    new_types: list[str] = []
    new_names: list[str] = []
    for t, n in zip(msg.types, msg.names, strict=True):
        _, is_array, _ = parse_type(t)
        if not is_array and msg_context.is_registered(t):
            sub = flatten(msg_context, msg_context.get_registered(t))
            new_types.extend(sub.types)
            new_names.extend(f"{n}.{n2}" for n2 in sub.names)
        else:
            new_types.append(t)
            new_names.append(n)
    return MsgSpec(new_types, new_names, msg.constants, msg.text, msg.full_name)


def compute_post_deserialize(type_: str, varname: str) -> str | None:
    """The statement fixing up `varname` after it is read (`x.canon()` for time and duration)."""
    special = get_special(type_)
    return special.get_post_deserialize(varname) if special is not None else None


def compute_full_text_escaped(msg_context: Any, spec: Any) -> str:
    """genmsg's full text, safe inside a triple-quoted Python string."""
    return str(genmsg.compute_full_text(msg_context, spec)).replace('"""', r'\"\"\"')


# genpy's serializer code writers: the lines of Python a genpy-style module's serialize() and
# deserialize() are made of, as genpy 0.6.16 writes them (kame's own modules are written by
# kame.msg.codegen; these serve tools that emit genpy's code). They share genpy's module-level
# state, as its callers expect: the field-reference context ('self.', '_v1.'), pushed and popped
# while descending into embedded messages, and the temporary-variable counter.

INDENT = "  "
_BYTES_TYPES = ("uint8", "char")

_serial_context = ""
_context_stack: list[str] = []
_counter = 0


def next_var() -> str:
    """A fresh temporary name: _v1, _v2, ..."""
    global _counter
    _counter += 1
    return f"_v{_counter}"


def reset_var() -> None:
    global _counter
    _counter = 0


def push_context(context: str) -> None:
    """Make `context` the prefix of field references until pop_context."""
    global _serial_context
    _context_stack.append(_serial_context)
    _serial_context = context


def pop_context() -> None:
    global _serial_context
    _serial_context = _context_stack.pop()


def len_serializer_generator(var: str, is_string: bool, serialize: bool) -> Iterator[str]:
    """An array's or string's uint32 length: computed (and written, but for a string, whose
    length goes out with its bytes) or read."""
    if serialize:
        yield f"length = len({var})"
        if not is_string:
            yield int32_pack("length")
    else:
        yield "start = end"
        yield "end += 4"
        yield int32_unpack("length", "str[start:end]")


def string_serializer_generator(package: str, type_: str, name: str, serialize: bool) -> Iterator[str]:
    """A string, or a uint8/char array (bytes), with its length unless the array is fixed."""
    if _serial_context and serialize:
        yield f"_x = {_serial_context}{name}"  # read once, used twice
        var = "_x"
    else:
        var = _serial_context + name
    base_type, _, array_len = parse_type(type_)
    if base_type not in _BYTES_TYPES or array_len is None:
        yield from len_serializer_generator(var, True, serialize)
    if serialize:
        if base_type in _BYTES_TYPES:
            yield "# - if encoded as a list instead, serialize as bytes instead of string"
            yield f"if type({var}) in [list, tuple]:"
            if array_len is None:
                yield INDENT + pack2("'<I%sB'%length", f"length, *{var}")
                yield "else:"
                yield INDENT + pack2("'<I%ss'%length", f"length, {var}")
            else:
                yield INDENT + pack(f"{array_len}B", f"*{var}")
                yield "else:"
                yield INDENT + pack(f"{array_len}s", var)
        else:
            yield f"if python3 or type({var}) == unicode:"
            yield INDENT + f"{var} = {var}.encode('utf-8')"
            yield INDENT + f"length = len({var})"
            yield pack2("'<I%ss'%length", f"length, {var}")
        return
    yield "start = end"
    if array_len is not None:
        yield f"end += {array_len}"
        yield f"{var} = str[start:end]"
        return
    yield "end += length"
    if base_type in _BYTES_TYPES:
        yield f"{var} = str[start:end]"
    else:
        yield "if python3:"
        yield INDENT + f"{var} = str[start:end].decode('utf-8', 'rosmsg')"
        yield "else:"
        yield INDENT + f"{var} = str[start:end]"


def _simple_array(var: str, base_type: str, array_len: int | None, serialize: bool, is_numpy: bool) -> Iterator[str]:
    """An array of one struct code, in one struct call (numpy's buffer for is_numpy)."""
    code = compute_struct_pattern([base_type])
    if array_len is None:
        yield f"pattern = '<%s{code}'%length"
        if serialize:
            yield pack_numpy(var) if is_numpy else pack2("pattern", "*" + var)
        else:
            yield "start = end"
            yield "s = struct.Struct(pattern)"
            yield "end += s.size"
            yield (unpack_numpy(var, "length", NUMPY_DTYPE[base_type], "str[start:end]") if is_numpy
                   else unpack3(var, "s", "str[start:end]"))
    else:
        pattern = f"{array_len}{code}"
        if serialize:
            yield pack_numpy(var) if is_numpy else pack(pattern, "*" + var)
        else:
            yield "start = end"
            yield f"end += {struct.calcsize('<' + pattern)}"
            yield (unpack_numpy(var, str(array_len), NUMPY_DTYPE[base_type], "str[start:end]") if is_numpy
                   else unpack(var, pattern, "str[start:end]"))
    if not serialize and base_type == "bool":
        yield f"{var} = list(map(bool, {var}))"


def array_serializer_generator(msg_context: Any, package: str, type_: str, name: str, serialize: bool,
                               is_numpy: bool) -> Iterator[str]:
    """An array field: bytes as a string, simple types in one struct call, strings and messages
    one element at a time. MsgGenerationException for a type that is not an array."""
    base_type, is_array, array_len = parse_type(type_)
    if not is_array:
        raise MsgGenerationException(f"Invalid array spec: {type_}")
    if base_type in _BYTES_TYPES:
        yield from string_serializer_generator(package, type_, name, serialize)
        return
    var = _serial_context + name
    if array_len is None:
        yield from len_serializer_generator(var, False, serialize)
    if is_simple(base_type):
        yield from _simple_array(var, base_type, array_len, serialize, is_numpy)
        return
    loop_var = f"val{len(_context_stack)}"
    factory: Iterator[str]
    if base_type == "string":
        push_context("")
        factory = string_serializer_generator(package, base_type, loop_var, serialize)
    else:
        push_context(f"{loop_var}.")
        factory = serializer_generator(msg_context, make_python_safe(get_registered_ex(msg_context, base_type)),
                                       serialize, is_numpy)
    if serialize:
        if array_len is not None:
            yield f"if len({var}) != {array_len}:"
            yield INDENT + ("self._check_types(ValueError(\"Expecting %s items but found %s when writing '%s'\" % "
                            f"({array_len}, len({var}), '{var}')))")
        yield f"for {loop_var} in {var}:"
    else:
        yield f"{var} = []"
        yield "for i in range(0, length):" if array_len is None else f"for i in range(0, {array_len}):"
        if base_type != "string":
            yield INDENT + f"{loop_var} = {compute_constructor(msg_context, package, base_type)}"
    for line in factory:
        yield INDENT + line
    if not serialize:
        yield INDENT + f"{var}.append({loop_var})"
    pop_context()


def complex_serializer_generator(msg_context: Any, package: str, type_: str, name: str, serialize: bool,
                                 is_numpy: bool) -> Iterator[str]:
    """A field that is not simple: an array, a string, or an embedded message (descended into
    under a fresh temporary). MsgGenerationException for a type `msg_context` does not know."""
    _, is_array, _ = parse_type(type_)
    if is_array:
        yield from array_serializer_generator(msg_context, package, type_, name, serialize, is_numpy)
        return
    if type_ == "string":
        yield from string_serializer_generator(package, type_, name, serialize)
        return
    if not is_special(type_):
        pkg, base_type = compute_pkg_type(package, type_)
        type_ = f"{pkg}/{base_type}"
    if not msg_context.is_registered(type_):
        raise MsgGenerationException(f"Unknown type: {type_}. Package context is {package}")
    ctx_var = next_var()
    yield f"{ctx_var} = {_serial_context}{name}"
    push_context(ctx_var + ".")
    yield from serializer_generator(msg_context, make_python_safe(get_registered_ex(msg_context, type_)), serialize,
                                    is_numpy)
    pop_context()


def simple_serializer_generator(msg_context: Any, spec: Any, start: int, end: int, serialize: bool) -> Iterator[str]:
    """Fields start..end-1 of `spec`, all simple, in one struct call (bools read back as bool)."""
    names = spec.names[start:end]
    if end - start > 1 and _serial_context.endswith("."):
        yield "_x = " + _serial_context[:-1]
        vars_ = "_x." + ", _x.".join(names)
    elif serialize and end - start == 1 and _serial_context.endswith("."):
        yield f"_x = {_serial_context}{names[0]}"
        vars_ = "_x"
    else:
        vars_ = _serial_context + (", " + _serial_context).join(names)
    pattern = str(compute_struct_pattern(spec.types[start:end]))
    if serialize:
        yield pack(pattern, vars_)
        return
    yield "start = end"
    yield f"end += {struct.calcsize('<' + str(reduce_pattern(pattern)))}"
    yield unpack(f"({vars_},)", pattern, "str[start:end]")
    for field_name, field_type in zip(names, spec.types[start:end], strict=True):
        if field_type == "bool":
            var = _serial_context + field_name
            yield f"{var} = bool({var})"


_MAX_CHUNK = 255  # fields in one struct call at most


def serializer_generator(msg_context: Any, spec: Any, serialize: bool, is_numpy: bool) -> Iterator[str]:
    """The unindented body (de)serializing `spec`: runs of simple fields in struct calls (255 at
    most), each other field by complex_serializer_generator."""
    if spec is None:
        raise MsgGenerationException("spec is none")
    names, types = spec.names, spec.types
    if serialize and not names:
        yield "pass"
        return
    curr = 0
    for i, full_type in enumerate(types):
        if is_simple(full_type):
            continue
        for chunk_start in range(curr, i, _MAX_CHUNK):
            yield from simple_serializer_generator(msg_context, spec, chunk_start, min(chunk_start + _MAX_CHUNK, i),
                                                   serialize)
        curr = i + 1
        yield from complex_serializer_generator(msg_context, spec.package, full_type, names[i], serialize, is_numpy)
    for chunk_start in range(curr, len(types), _MAX_CHUNK):
        yield from simple_serializer_generator(msg_context, spec, chunk_start,
                                               min(chunk_start + _MAX_CHUNK, len(types)), serialize)


def serialize_fn_generator(msg_context: Any, spec: Any, is_numpy: bool = False) -> Iterator[str]:
    """The body of a genpy module's serialize(): the flattened spec's fields written in a try
    whose struct and type errors become _check_types' explanations."""
    yield "try:"
    push_context("self.")
    for line in serializer_generator(msg_context, make_python_safe(flatten(msg_context, spec)), True, is_numpy):
        yield "  " + line
    pop_context()
    yield ("except struct.error as se: self._check_types(struct.error(\"%s: '%s' when writing '%s'\" % "
           "(type(se), str(se), str(locals().get('_x', self)))))")
    yield ("except TypeError as te: self._check_types(ValueError(\"%s: '%s' when writing '%s'\" % "
           "(type(te), str(te), str(locals().get('_x', self)))))")


def deserialize_fn_generator(msg_context: Any, spec: Any, is_numpy: bool = False) -> Iterator[str]:
    """The body of a genpy module's deserialize(): embedded messages built, the flattened spec's
    fields read, times made canonical; a short buffer is genpy.DeserializationError."""
    yield "if python3:"
    yield INDENT + 'codecs.lookup_error("rosmsg").msg_type = self._type'
    yield "try:"
    for type_, name in spec.fields():
        if msg_context.is_registered(type_):
            yield f"  if self.{name} is None:"
            yield f"    self.{name} = {compute_constructor(msg_context, spec.package, type_)}"
    yield "  end = 0"
    push_context("self.")
    for line in serializer_generator(msg_context, make_python_safe(flatten(msg_context, spec)), False, is_numpy):
        yield "  " + line
    pop_context()
    for type_, name in spec.fields():
        code = compute_post_deserialize(type_, f"self.{name}")
        if code:
            yield f"  {code}"
    yield "  return self"
    yield "except struct.error as e:"
    yield "  raise genpy.DeserializationError(e)  # most likely buffer underfill"
