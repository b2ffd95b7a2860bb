"""Message specs to Python source: boring, fast, generated code.

Each message becomes a class whose serialize/deserialize are straight-line code:
nested messages are flattened, runs of fixed-size fields are packed and unpacked with one
precompiled struct, strings and arrays carry their length in the same struct call as the
fields before them, and uint8[] payloads are written and read with a single copy. A message
without loops is written with one write; structs are native where that is the wire format
(kame.msg.runtime.wire_struct). Failures go to a slow path in kame.msg.message that names
the offending field.

The same generator serves the message packages written to files (kame.msg.build), user
packages loaded by the import hook, and classes built from a message_definition at run time.
"""

from __future__ import annotations

import keyword
import struct
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace

from kame.msg.spec import MsgSpec, SrvSpec

Lookup = Callable[[str], MsgSpec]

_CODES: dict[str, tuple[str, str]] = {  # ROS type -> (pack code, unpack code)
    "bool": ("B", "?"), "int8": ("b", "b"), "byte": ("b", "b"), "uint8": ("B", "B"), "char": ("B", "B"),
    "int16": ("h", "h"), "uint16": ("H", "H"), "int32": ("i", "i"), "uint32": ("I", "I"),
    "int64": ("q", "q"), "uint64": ("Q", "Q"), "float32": ("f", "f"), "float64": ("d", "d"),
}


def pack_codes() -> dict[str, str]:
    """The struct code each fixed-size primitive is written with (bool as an unsigned byte)."""
    return {name: codes[0] for name, codes in _CODES.items()}


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
    #: "%d" formats of variable-length numeric arrays -> the name of their ArrayStructs cache
    arrays: dict[str, str] = field(default_factory=dict)

    def ref(self, fmt: str) -> str:
        name = self.names.get(fmt)
        if name is None:
            name = self.names[fmt] = f"_S{len(self.names)}"
        return name

    def array_ref(self, template: str) -> str:
        name = self.arrays.get(template)
        if name is None:
            name = self.arrays[template] = f"_A{len(self.arrays)}"
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
    """Straight-line packing code.

    With joined=True the bytes are not written as they are packed: `parts` collects the
    expressions, for one write of them all at the end (one write and one join cost less than
    a write per part); `streams` says the code could not do that (loops, uint8[] payloads,
    which are written without a copy) and must be generated again without joined.
    """

    def __init__(self, lookup: Lookup, code: _Code, structs: _Structs, joined: bool = False) -> None:
        self.lookup = lookup
        self.code = code
        self.structs = structs
        self.group = _Group()
        self.parts: list[str] | None = [] if joined else None
        self.streams = False

    def write(self, expr: str) -> None:
        if self.parts is None:
            self.code.emit(f"_w({expr})")
        else:
            self.parts.append(expr)

    def flush(self, tail: str | None = None) -> None:
        if self.group:
            fmt, items = self.group.take()
            packed = f"{self.structs.ref(fmt)}.pack({', '.join(items)})"
            if tail and self.parts is None:
                self.write(f"{packed} + {tail}")
                return
            self.write(packed)
        if tail:
            self.write(tail)

    def fields(self, spec: MsgSpec, obj: str) -> None:
        for f in spec.fields:
            self.one(f.type, f.base_type, f.is_array, f.array_len, f"{obj}.{f.name}")

    def _local(self, expr: str) -> str:
        """expr, or a local holding it when it is an attribute chain (read once, used often)."""
        if "." not in expr:
            return expr
        m = self.code.var("m")
        self.code.emit(f"{m} = {expr}")
        return m

    def one(self, type_name: str, base: str, is_array: bool, length: int | None, expr: str) -> None:
        code = self.code
        if not is_array:
            if base in _CODES:
                self.group.add(_CODES[base][0], expr)
            elif base in ("time", "duration"):
                t = self._local(expr)
                self.group.add("II" if base == "time" else "ii", f"{t}.secs", f"{t}.nsecs")
            elif base == "string":
                b = code.var("b")
                code.emit(f"{b} = {expr}")
                code.emit(f"if {b}.__class__ is not bytes: {b} = {b}.encode()")
                self.group.add("I", f"len({b})")
                self.flush(tail=b)
            else:
                nested = self.lookup(base)
                self.fields(nested, self._local(expr) if len(nested.fields) > 1 else expr)
            return
        x = code.var("x")
        code.emit(f"{x} = {expr}")
        if base in _BYTE_TYPES:
            code.emit(f"if {x}.__class__ is not bytes: {x} = _u8({x})")
            if length is None:
                self.group.add("I", f"len({x})")
                self.flush()
                self.streams = True
                code.emit(f"_w({x})")
            else:
                code.emit(f"if len({x}) != {length}: raise ValueError({x})")
                self.group.add(f"{length}s", x)
            return
        if base in _CODES and length is not None:
            self.group.add(f"{length}{_CODES[base][0]}", f"*{x}")
            return
        if base in _CODES:
            # lists and tuples: count and items in one call of a struct cached per count
            self.flush()
            self.streams = True
            pack_code = _CODES[base][0]
            counted = self.structs.array_ref(f"<I%d{pack_code}")
            code.emit(f"if {x}.__class__ is list or {x}.__class__ is tuple: "
                      f"_w({counted}[len({x})].pack(len({x}), *{x}))")
            code.emit(f"else: _w({self.structs.ref('<I')}.pack(len({x})) + "
                      f"_pack_array({x}, {pack_code!r}, {_DTYPES[base]!r}))")
            return
        if length is None:
            self.group.add("I", f"len({x})")
        self.flush()
        if length is not None:
            code.emit(f"if len({x}) != {length}: raise ValueError({x})")
        self.streams = True
        e = code.var("e")
        code.emit(f"for {e} in {x}:")
        code.depth += 1
        emitted = len(code.lines)
        self.one(base, base, False, None, e)
        self.flush()
        if len(code.lines) == emitted:  # elements without fields (std_msgs/Empty[]): nothing to write
            code.emit("pass")
        code.depth -= 1


class _Deserializer:
    """Straight-line unpacking code.

    Offsets known when the code is generated stay constants (`_end` exists only after the
    first variable-size field); variable-size slices are not bounds-checked one by one:
    slices clamp, every later unpack_from checks its own offset, and one check at the end
    catches a length that pointed past the data.

    With reuse=True, nested messages (and time/duration values) outside arrays are not
    allocated: the code unpacks into the objects the message already holds, gathered
    into locals by `gather` (name, expression, class) before the body runs.

    With bytes_in=True, strings are decoded with bytes.decode, quicker than str(b, ...);
    data without .decode (a memoryview) then raises AttributeError, and the method's caller
    takes the slow way (`decodes` says whether the code decodes any string).
    """

    def __init__(self, lookup: Lookup, code: _Code, structs: _Structs, use_numpy: bool, reuse: bool = False,
                 bytes_in: bool = False) -> None:
        self.lookup = lookup
        self.code = code
        self.structs = structs
        self.use_numpy = use_numpy
        self.reuse = reuse
        self.bytes_in = bytes_in
        self.decodes = False
        self.gather: list[tuple[str, str, str]] = []
        self.group = _Group()
        self.dynamic = False  # whether `_end` holds the base offset (else the base is 0)
        self.k = 0  # constant bytes past the base
        self.sliced = False  # whether a clamped slice may have moved `_end` past the data

    def pos(self) -> str:
        if not self.dynamic:
            return str(self.k)
        return f"_end + {self.k}" if self.k else "_end"

    def materialize(self) -> None:
        """Make `_end` hold the current offset (before loops and at the end)."""
        if not self.dynamic:
            self.code.emit(f"_end = {self.k}")
        elif self.k:
            self.code.emit(f"_end += {self.k}")
        self.dynamic, self.k = True, 0

    def flush(self) -> None:
        if not self.group:
            return
        fmt, targets = self.group.take()
        ref = self.structs.ref(fmt)
        lhs = f"{targets[0]}," if len(targets) == 1 else ", ".join(targets)
        self.code.emit(f"{lhs} = {ref}.unpack_from(_buf, {self.pos()})")
        self.k += struct.calcsize(fmt)

    def slice_to(self, nbytes: str) -> tuple[str, str]:
        """Emit the offset arithmetic of a variable-size read of nbytes; (start, stop) expressions."""
        self.sliced = True
        if not self.dynamic:
            start = str(self.k)
            self.code.emit(f"_end = {start} + {nbytes}")
        else:
            start = "_s"
            self.code.emit(f"_s = {self.pos()}")
            self.code.emit(f"_end = _s + {nbytes}")
        self.dynamic, self.k = True, 0
        return start, "_end"

    def fields(self, spec: MsgSpec, obj: str) -> None:
        for f in spec.fields:
            self.one(f.base_type, f.is_array, f.array_len, f"{obj}.{f.name}")

    def _object(self, cls: str, prefix: str, target: str) -> str:
        """A local holding the object at target: gathered (reuse) or a new one stored there."""
        v = self.code.var(prefix)
        if self.reuse:
            self.gather.append((v, target, cls))
        else:
            self.code.emit(f"{target} = {v} = _new({cls})")
        return v

    def one(self, base: str, is_array: bool, length: int | None, target: str) -> None:
        code = self.code
        if not is_array:
            if base in _CODES:
                self.group.add(_CODES[base][1], target)
            elif base in ("time", "duration"):
                t = self._object("_Time" if base == "time" else "_Duration", "t", target)
                self.group.add("II" if base == "time" else "ii", f"{t}.secs", f"{t}.nsecs")
            elif base == "string":
                self.group.add("I", "_n")
                self.flush()
                start, stop = self.slice_to("_n")
                if self.bytes_in:
                    self.decodes = True
                    code.emit(f"{target} = _buf[{start}:{stop}].decode('utf-8', 'replace')")
                else:
                    code.emit(f"{target} = str(_buf[{start}:{stop}], 'utf-8', 'replace')")
            else:
                v = self._object(type_ref(base), "v", target)
                self.fields(self.lookup(base), v)
            return
        if base in _BYTE_TYPES and length is not None:
            self.group.add(f"{length}s", target)
            return
        count = str(length)
        if length is None:
            self.group.add("I", "_n")
            count = "_n"
        self.flush()
        if base in _BYTE_TYPES:
            start, stop = self.slice_to(count)
            code.emit(f"{target} = bytes(_buf[{start}:{stop}])")
            return
        if base in _CODES:
            item_size = struct.calcsize("<" + _CODES[base][1])
            # bool arrays read as lists of bools, numpy or not, as genpy's (list(map(bool, ...)))
            as_list = base == "bool"
            if self.use_numpy and not as_list:
                code.emit(f"{target} = _np.frombuffer(_buf, {_DTYPES[base]!r}, {count}, {self.pos()})")
            else:
                if length is None:
                    ref = self.structs.array_ref(f"<%d{_CODES[base][1]}") + "[_n]"
                else:
                    ref = self.structs.ref(f"<{length}{_CODES[base][1]}")
                read = f"{ref}.unpack_from(_buf, {self.pos()})"
                code.emit(f"{target} = list({read})" if as_list else f"{target} = {read}")
            if length is None:
                nbytes = f"_n * {item_size}" if item_size > 1 else "_n"
                if self.dynamic:
                    code.emit(f"_end += {self.k} + {nbytes}" if self.k else f"_end += {nbytes}")
                else:
                    code.emit(f"_end = {self.k} + {nbytes}")
                self.dynamic, self.k = True, 0
            else:
                self.k += length * item_size
            return
        # arrays of messages, strings, times: a loop; elements are always new objects
        self.materialize()
        if length is None and base not in ("string", "time", "duration") and _carries_nothing(self.lookup(base),
                                                                                             self.lookup):
            # Each element is zero bytes, so no read can run past the data: the count alone
            # would have 4 bytes make us build four billion objects.
            code.emit(f"if _n > {MAX_EMPTY_ELEMENTS}: raise ValueError("
                      f"'an array of %d elements that carry nothing (at most {MAX_EMPTY_ELEMENTS})' % _n)")
        items = code.var("l")
        code.emit(f"{items} = []")
        code.emit(f"for _ in range({count}):")
        code.depth += 1
        reuse, self.reuse = self.reuse, False
        element = code.var("i")
        self.one(base, False, None, element)
        self.flush()
        self.materialize()
        self.reuse = reuse
        code.emit(f"{items}.append({element})")
        code.depth -= 1
        code.emit(f"{target} = {items}")

    def finish(self) -> None:
        self.flush()
        if self.sliced:
            self.code.emit("if _end > len(_buf): raise _Truncated")


#: Most elements of a message type with no data (std_msgs/Empty) one array may hold.
MAX_EMPTY_ELEMENTS = 1 << 16


def _carries_nothing(spec: MsgSpec, lookup: Lookup) -> bool:
    """Whether every message of `spec` serializes to zero bytes."""
    return all((f.is_array and f.array_len == 0)
               or (f.is_message and not f.is_array and _carries_nothing(lookup(f.base_type), lookup))
               for f in spec.fields)


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


def _flat_defaults(spec: MsgSpec, lookup: Lookup, code: _Code, obj: str) -> None:
    """Emit the default of every field of obj, nested messages and times built in place."""
    for f in spec.fields:
        target = f"{obj}.{f.name}"
        if f.is_array or not (f.is_message or f.base_type in ("time", "duration")):
            code.emit(f"{target} = {_default(f.base_type, f.is_array, f.array_len)}")
        elif f.is_message:
            v = code.var("v")
            code.emit(f"{target} = {v} = _new({type_ref(f.base_type)})")
            _flat_defaults(lookup(f.base_type), lookup, code, v)
        else:
            t = code.var("t")
            code.emit(f"{target} = {t} = _new({'_Time' if f.base_type == 'time' else '_Duration'})")
            code.emit(f"{t}.secs = {t}.nsecs = 0")


def python_name(name: str) -> str:
    """A field's or constant's attribute name: a Python keyword (or `self`) gets a trailing
    underscore, as genpy names it (a field `from` is `msg.from_`)."""
    return name + "_" if keyword.iskeyword(name) or name == "self" else name


def python_safe(spec: MsgSpec) -> MsgSpec:
    """The spec with its field and constant names as the Python class has them (python_name).
    Only the class's attribute names change: md5sums and definitions come from the original."""
    if all(python_name(f.name) == f.name for f in spec.fields) and \
            all(python_name(c.name) == c.name for c in spec.constants):
        return spec
    return replace(spec, fields=tuple(replace(f, name=python_name(f.name)) for f in spec.fields),
                   constants=tuple(replace(c, name=python_name(c.name)) for c in spec.constants))


def generate_class(
    spec: MsgSpec, lookup: Lookup, md5sum: str, full_text: str, structs: _Structs, class_name: str | None = None
) -> str:
    """Source of one message class; it refers to other message classes by type_ref() names."""
    spec = python_safe(spec)

    def safe_lookup(type_name: str) -> MsgSpec:
        return python_safe(base_lookup(type_name))

    base_lookup, lookup = lookup, safe_lookup
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
    # constructor: no arguments (the common case) builds the defaults flat, without nested calls
    out.append("    def __init__(self, *args, **kwds):")
    out.append("        if args or kwds:")
    out.append("            _init_fields(self, args, kwds)")
    for f in spec.fields:
        out.append(f"            if self.{f.name} is None:")
        out.append(f"                self.{f.name} = {_default(f.base_type, f.is_array, f.array_len)}")
    if spec.fields:
        code = _Code(depth=3)
        _flat_defaults(spec, lookup, code, "self")
        out.append("        else:")
        out.extend(code.lines)
    out.append("")
    # serialize: one write of all parts joined when there are more than two and no loops
    code = _Code()
    ser = _Serializer(lookup, code, structs, joined=True)
    ser.fields(spec, "self")
    ser.flush()
    if ser.parts is not None and len(ser.parts) > 2 and not ser.streams:
        code.emit(f"_w(b''.join(({', '.join(ser.parts)})))")
    else:
        code = _Code()
        ser = _Serializer(lookup, code, structs)
        ser.fields(spec, "self")
        ser.flush()
    out.append("    def serialize(self, buff):")
    out.append("        try:")
    writes = sum(line.count("_w(") for line in code.lines)
    if writes == 1 and not any(line.lstrip().startswith("for ") for line in code.lines):
        out.extend("    " + line.replace("_w(", "buff.write(") for line in code.lines)  # no need for a local
    else:
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
    out.extend(_deserializer("deserialize", spec, lookup, structs, use_numpy=False, reuse=True, class_name=name))
    out.extend(_deserializer("_from_buffer", spec, lookup, structs, use_numpy=False))
    if _has_numeric_arrays(spec, lookup):
        out.extend(_deserializer("deserialize_numpy", spec, lookup, structs, use_numpy=True))
    else:
        out.append("    def deserialize_numpy(self, data, numpy):")
        out.append("        return self.deserialize(data)")
        out.append("")
    return "\n".join(out) + "\n"


def _deserializer(
    method: str, spec: MsgSpec, lookup: Lookup, structs: _Structs, use_numpy: bool, reuse: bool = False,
    class_name: str = "",
) -> list[str]:
    """One deserializing method.

    deserialize (reuse=True) unpacks into the nested messages the instance already holds, as
    genpy does, so Cls().deserialize(data) allocates them once; when one is missing (an
    instance from object.__new__, None) or does not take a field, or the data is a buffer
    without .decode (its strings are decoded with bytes.decode), the AttributeError sends
    it to kame.msg.message.refill, which deserializes into new objects instead.
    _from_buffer is a classmethod that unpacks into a new instance and new nested objects:
    the receive path's one-call `Cls._from_buffer(frame)`.
    """
    code = _Code()
    des = _Deserializer(lookup, code, structs, use_numpy, reuse, bytes_in=reuse)
    des.fields(spec, "self")
    des.finish()
    slow_way = bool(des.gather) or des.decodes
    out: list[str] = []
    if method == "_from_buffer":
        out += ["    @classmethod", "    def _from_buffer(cls, data):", "        self = _new(cls)"]
    else:
        out.append(f"    def {method}(self, data, numpy):" if use_numpy else f"    def {method}(self, data):")
    out.append("        try:")
    out += [f"            {v} = {expr}" for v, expr, _ in des.gather]
    if use_numpy:
        out.append("            _np = numpy")
    out.append("            _buf = data")
    out.extend("    " + line for line in code.lines)
    if not code.lines and not des.gather:
        out.append("            pass")
    if slow_way:
        # a nested object missing (unset slot, None) or refusing a field, or data that is not
        # bytes: new objects, from scratch
        out += ["            return self", "        except AttributeError:", "            pass"]
    failed = "cls" if method == "_from_buffer" else "type(self)"
    out += ["        except Exception as exc:", f"            raise _deserialize_failed({failed}, data, exc) from exc"]
    out.append(f"        return _refill(self, {class_name}, data)" if slow_way else "        return self")
    out.append("")
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
from kame.msg.message import Message as _Message
from kame.msg.message import init_fields as _init_fields
from kame.msg.message import serialize_failed as _serialize_failed
from kame.msg.message import deserialize_failed as _deserialize_failed
from kame.msg.message import refill as _refill
from kame.msg.runtime import ArrayStructs as _ArrayStructs
from kame.msg.runtime import Truncated as _Truncated
from kame.msg.runtime import pack_array as _pack_array
from kame.msg.runtime import u8_payload as _u8
from kame.msg.runtime import wire_struct as _wire
from kame.rostime import Duration as _Duration
from kame.rostime import Time as _Time

_new = object.__new__
"""


def struct_definitions(structs: _Structs) -> str:
    return "".join([f"{name} = _wire({fmt!r})\n" for fmt, name in structs.names.items()]
                   + [f"{name} = _ArrayStructs({template!r})\n" for template, name in structs.arrays.items()])


def new_structs() -> _Structs:
    return _Structs()


def module_source(header: str, imports: Iterable[str], body: str, structs: _Structs) -> str:
    """Assemble a module: header comment, prelude, dependency imports, structs, classes."""
    return "".join(
        [header, PRELUDE, "".join(line + "\n" for line in imports), "\n", struct_definitions(structs), "\n\n", body]
    )
