"""Message specs to Python source: boring, fast, generated code.

Each message becomes a class whose serialize/deserialize are straight-line code:
nested messages are flattened, runs of fixed-size fields are packed and unpacked with one
precompiled struct, strings and arrays carry their length in the same struct call as the
fields before them, and uint8[] payloads are written and read with a single copy.
Failures go to a slow path in kame.msg.message that names the offending field.

The same generator serves the message packages written to files (kame.msg.build), user
packages loaded by the import hook, and classes built from a message_definition at run time.
"""

from __future__ import annotations

import keyword
import struct
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from kame.msg.spec import MsgSpec, SrvSpec

Lookup = Callable[[str], MsgSpec]

_CODES: dict[str, tuple[str, str]] = {  # ROS type -> (pack code, unpack code)
    "bool": ("B", "?"), "int8": ("b", "b"), "byte": ("b", "b"), "uint8": ("B", "B"), "char": ("B", "B"),
    "int16": ("h", "h"), "uint16": ("H", "H"), "int32": ("i", "i"), "uint32": ("I", "I"),
    "int64": ("q", "q"), "uint64": ("Q", "Q"), "float32": ("f", "f"), "float64": ("d", "d"),
}
_DTYPES: dict[str, str] = {
    "bool": "?", "int8": "<i1", "byte": "<i1", "int16": "<i2", "uint16": "<u2", "int32": "<i4",
    "uint32": "<u4", "int64": "<i8", "uint64": "<u8", "float32": "<f4", "float64": "<f8",
}
_DEFAULTS: dict[str, str] = {
    "bool": "False", "float32": "0.0", "float64": "0.0", "string": "''", "time": "_Time()",
    "duration": "_Duration()",
}
_BYTE_TYPES = ("uint8", "char")


def type_ref(full_name: str) -> str:
    """The module-level name generated code uses for the class of a message type."""
    return "_T_" + full_name.replace("/", "__")


@dataclass
class _Code:
    lines: list[str] = field(default_factory=list)
    depth: int = 2
    counter: int = 0

    def emit(self, line: str) -> None:
        self.lines.append("    " * self.depth + line)

    def var(self, stem: str) -> str:
        self.counter += 1
        return f"_{stem}{self.counter}"


@dataclass
class _Structs:
    """Precompiled structs a module needs, by format."""

    names: dict[str, str] = field(default_factory=dict)

    def ref(self, fmt: str) -> str:
        name = self.names.get(fmt)
        if name is None:
            name = self.names[fmt] = f"_S{len(self.names)}"
        return name


class _Group:
    """Fixed-size fields waiting to go through one struct call."""

    def __init__(self) -> None:
        self.codes: list[str] = []
        self.items: list[str] = []

    def add(self, code: str, *items: str) -> None:
        self.codes.append(code)
        self.items.extend(items)

    def take(self) -> tuple[str, list[str]]:
        fmt = "<" + "".join(self.codes)
        items = self.items
        self.codes, self.items = [], []
        return fmt, items

    def __bool__(self) -> bool:
        return bool(self.codes)


class _Serializer:
    def __init__(self, lookup: Lookup, code: _Code, structs: _Structs) -> None:
        self.lookup = lookup
        self.code = code
        self.structs = structs
        self.group = _Group()

    def flush(self, tail: str | None = None) -> None:
        if self.group:
            fmt, items = self.group.take()
            packed = f"{self.structs.ref(fmt)}.pack({', '.join(items)})"
            self.code.emit(f"_w({packed} + {tail})" if tail else f"_w({packed})")
        elif tail:
            self.code.emit(f"_w({tail})")

    def fields(self, spec: MsgSpec, obj: str) -> None:
        for f in spec.fields:
            self.one(f.type, f.base_type, f.is_array, f.array_len, f"{obj}.{f.name}")

    def one(self, type_name: str, base: str, is_array: bool, length: int | None, expr: str) -> None:
        code = self.code
        if not is_array:
            if base in _CODES:
                self.group.add(_CODES[base][0], expr)
            elif base == "time":
                self.group.add("II", f"{expr}.secs", f"{expr}.nsecs")
            elif base == "duration":
                self.group.add("ii", f"{expr}.secs", f"{expr}.nsecs")
            elif base == "string":
                b = code.var("b")
                code.emit(f"{b} = {expr}")
                code.emit(f"if {b}.__class__ is not bytes: {b} = {b}.encode()")
                self.group.add("I", f"len({b})")
                self.flush(tail=b)
            else:
                self.fields(self.lookup(base), expr)
            return
        x = code.var("x")
        code.emit(f"{x} = {expr}")
        if base in _BYTE_TYPES:
            code.emit(f"if {x}.__class__ is not bytes: {x} = _u8({x})")
            if length is None:
                self.group.add("I", f"len({x})")
                self.flush()
                code.emit(f"_w({x})")
            else:
                code.emit(f"if len({x}) != {length}: raise ValueError({x})")
                self.group.add(f"{length}s", x)
            return
        if length is None:
            self.group.add("I", f"len({x})")
        if base in _CODES and length is not None:
            self.group.add(f"{length}{_CODES[base][0]}", f"*{x}")
            return
        self.flush()
        if base in _CODES:
            code.emit(f"_w(_pack_array({x}, {_CODES[base][0]!r}, {_DTYPES[base]!r}))")
            return
        if length is not None:
            code.emit(f"if len({x}) != {length}: raise ValueError({x})")
        e = code.var("e")
        code.emit(f"for {e} in {x}:")
        code.depth += 1
        self.one(base, base, False, None, e)
        self.flush()
        code.depth -= 1


class _Deserializer:
    def __init__(self, lookup: Lookup, code: _Code, structs: _Structs, use_numpy: bool) -> None:
        self.lookup = lookup
        self.code = code
        self.structs = structs
        self.use_numpy = use_numpy
        self.group = _Group()
        self.size = 0

    def flush(self) -> None:
        if not self.group:
            return
        fmt, targets = self.group.take()
        size = struct.calcsize(fmt)
        ref = self.structs.ref(fmt)
        if len(targets) == 1:
            self.code.emit(f"{targets[0]}, = {ref}.unpack_from(_buf, _end)")
        else:
            self.code.emit(f"{', '.join(targets)} = {ref}.unpack_from(_buf, _end)")
        self.code.emit(f"_end += {size}")

    def fields(self, spec: MsgSpec, obj: str) -> None:
        for f in spec.fields:
            self.one(f.base_type, f.is_array, f.array_len, f"{obj}.{f.name}")

    def _take(self, nbytes: str) -> str:
        """Emit the bounds check for a variable-size read; returns the end variable."""
        self.code.emit(f"_stop = _end + {nbytes}")
        self.code.emit("if _stop > _len: raise _Truncated")
        return "_stop"

    def one(self, base: str, is_array: bool, length: int | None, target: str) -> None:
        code = self.code
        if not is_array:
            if base in _CODES:
                self.group.add(_CODES[base][1], target)
            elif base in ("time", "duration"):
                t = code.var("t")
                code.emit(f"{t} = _new({'_Time' if base == 'time' else '_Duration'})")
                code.emit(f"{target} = {t}")
                self.group.add("II" if base == "time" else "ii", f"{t}.secs", f"{t}.nsecs")
            elif base == "string":
                self.group.add("I", "_n")
                self.flush()
                stop = self._take("_n")
                code.emit(f"{target} = str(_buf[_end:{stop}], 'utf-8', 'replace')")
                code.emit(f"_end = {stop}")
            else:
                v = code.var("v")
                code.emit(f"{v} = _new({type_ref(base)})")
                code.emit(f"{target} = {v}")
                self.fields(self.lookup(base), v)
            return
        count = str(length)
        if length is None:
            self.group.add("I", "_n")
            count = "_n"
        self.flush()
        if base in _BYTE_TYPES:
            stop = self._take(count)
            code.emit(f"{target} = bytes(_buf[_end:{stop}])")
            code.emit(f"_end = {stop}")
            return
        if base in _CODES:
            item_size = struct.calcsize("<" + _CODES[base][1])
            stop = self._take(f"{count} * {item_size}" if item_size > 1 else count)
            if self.use_numpy:
                code.emit(f"{target} = _np.frombuffer(_buf, {_DTYPES[base]!r}, {count}, _end)")
            elif length is None:
                code.emit(f"{target} = _unpack_from('<%d{_CODES[base][1]}' % _n, _buf, _end)")
            else:
                ref = self.structs.ref(f"<{length}{_CODES[base][1]}")
                code.emit(f"{target} = {ref}.unpack_from(_buf, _end)")
            code.emit(f"_end = {stop}")
            return
        items = code.var("l")
        code.emit(f"{items} = []")
        code.emit(f"for _ in range({count}):")
        code.depth += 1
        element = code.var("i")
        self.one(base, False, None, element)
        self.flush()
        code.emit(f"{items}.append({element})")
        code.depth -= 1
        code.emit(f"{target} = {items}")


def _has_numeric_arrays(spec: MsgSpec, lookup: Lookup) -> bool:
    for f in spec.fields:
        if f.is_array and f.base_type in _CODES and f.base_type not in _BYTE_TYPES:
            return True
        if f.is_message and _has_numeric_arrays(lookup(f.base_type), lookup):
            return True
    return False


def _default(f_base: str, is_array: bool, length: int | None) -> str:
    if is_array:
        if f_base in _BYTE_TYPES:
            return "b''" if length is None else f"b'\\x00' * {length}"
        if length is None:
            return "[]"
        if f_base in _CODES or f_base == "string":
            return f"[{_DEFAULTS.get(f_base, '0')}] * {length}"
        return f"[{_default(f_base, False, None)} for _ in range({length})]"
    if f_base in _DEFAULTS:
        return _DEFAULTS[f_base]
    if f_base in _CODES:
        return "0"
    return f"{type_ref(f_base)}()"


def _check_field_names(spec: MsgSpec) -> None:
    for f in spec.fields:
        if keyword.iskeyword(f.name):
            raise ValueError(f"{spec.full_name}: field name '{f.name}' is a Python keyword")


def generate_class(
    spec: MsgSpec, lookup: Lookup, md5sum: str, full_text: str, structs: _Structs, class_name: str | None = None
) -> str:
    """Source of one message class; it refers to other message classes by type_ref() names."""
    _check_field_names(spec)
    name = class_name or spec.short_name
    out: list[str] = [f"class {name}(_Message):"]
    out.append(f"    __slots__ = {tuple(spec.names)!r}")
    out.append(f"    _slot_types = {tuple(spec.types)!r}")
    out.append(f"    _type = {spec.full_name!r}")
    out.append(f"    _md5sum = {md5sum!r}")
    out.append(f"    _has_header = {spec.has_header!r}")
    out.append(f"    _full_text = {full_text!r}")
    for c in spec.constants:
        out.append(f"    {c.name} = {c.value!r}")
    nested = {f.name: type_ref(f.base_type) for f in spec.fields if f.is_message}
    out.append("    _slot_classes = {" + ", ".join(f"{k!r}: {v}" for k, v in nested.items()) + "}")
    out.append("")
    # constructor
    out.append("    def __init__(self, *args, **kwds):")
    if spec.fields:
        out.append("        if args or kwds:")
        out.append("            _init_fields(self, args, kwds)")
        for f in spec.fields:
            out.append(f"            if self.{f.name} is None:")
            out.append(f"                self.{f.name} = {_default(f.base_type, f.is_array, f.array_len)}")
        out.append("        else:")
        for f in spec.fields:
            out.append(f"            self.{f.name} = {_default(f.base_type, f.is_array, f.array_len)}")
    else:
        out.append("        if args or kwds:")
        out.append("            _init_fields(self, args, kwds)")
    out.append("")
    # serialize
    code = _Code()
    ser = _Serializer(lookup, code, structs)
    ser.fields(spec, "self")
    ser.flush()
    out.append("    def serialize(self, buff):")
    out.append("        try:")
    out.append("            _w = buff.write")
    out.extend("    " + line for line in code.lines)
    if not code.lines:
        out.append("            pass")
    out.append("        except Exception as exc:")
    out.append("            raise _serialize_failed(self, exc) from exc")
    out.append("")
    out.append("    def serialize_numpy(self, buff, numpy):")
    out.append("        self.serialize(buff)")
    out.append("")
    out.extend(_deserializer("deserialize", spec, lookup, structs, use_numpy=False))
    if _has_numeric_arrays(spec, lookup):
        out.extend(_deserializer("deserialize_numpy", spec, lookup, structs, use_numpy=True))
    else:
        out.append("    def deserialize_numpy(self, data, numpy):")
        out.append("        return self.deserialize(data)")
        out.append("")
    return "\n".join(out) + "\n"


def _deserializer(method: str, spec: MsgSpec, lookup: Lookup, structs: _Structs, use_numpy: bool) -> list[str]:
    code = _Code()
    des = _Deserializer(lookup, code, structs, use_numpy)
    des.fields(spec, "self")
    des.flush()
    signature = "self, data, numpy" if use_numpy else "self, data"
    out = [f"    def {method}({signature}):", "        try:"]
    if use_numpy:
        out.append("            _np = numpy")
    out += ["            _buf = data", "            _len = len(data)", "            _end = 0"]
    out.extend("    " + line for line in code.lines)
    out += [
        "        except Exception as exc:",
        "            raise _deserialize_failed(type(self), data, exc) from exc",
        "        return self",
        "",
    ]
    return out


def generate_service(srv: SrvSpec, md5sum: str) -> str:
    request = srv.request.short_name
    response = srv.response.short_name
    return (
        f"class {srv.short_name}:\n"
        f"    _type = {srv.full_name!r}\n"
        f"    _md5sum = {md5sum!r}\n"
        f"    _request_class = {request}\n"
        f"    _response_class = {response}\n"
    )


PRELUDE = """\
import struct as _struct

from kame.msg.message import Message as _Message
from kame.msg.message import init_fields as _init_fields
from kame.msg.message import serialize_failed as _serialize_failed
from kame.msg.message import deserialize_failed as _deserialize_failed
from kame.msg.runtime import Truncated as _Truncated
from kame.msg.runtime import pack_array as _pack_array
from kame.msg.runtime import u8_payload as _u8
from kame.rostime import Duration as _Duration
from kame.rostime import Time as _Time

_new = object.__new__
_unpack_from = _struct.unpack_from
"""


def struct_definitions(structs: _Structs) -> str:
    return "".join(f"{name} = _struct.Struct({fmt!r})\n" for fmt, name in structs.names.items())


def new_structs() -> _Structs:
    return _Structs()


def module_source(header: str, imports: Iterable[str], body: str, structs: _Structs) -> str:
    """Assemble a module: header comment, prelude, dependency imports, structs, classes."""
    return "".join(
        [header, PRELUDE, "".join(line + "\n" for line in imports), "\n", struct_definitions(structs), "\n\n", body]
    )
