"""The base of every message class and what generated code calls when things go wrong.

Generated classes (kame.msg.codegen) carry the fast paths; this module holds what they
share: the genpy-style constructor rules, equality, pickling, the YAML-like str(), and the
slow diagnostics that turn a failed serialize/deserialize into an error naming the field.
"""

from __future__ import annotations

import struct
from typing import Any, ClassVar

from kame.msg.errors import DeserializationError, SerializationError
from kame.msg.typenames import split_array
from kame.rostime import Duration, Time, TVal

_INT_RANGES: dict[str, tuple[int, int]] = {
    "byte": (-(2**7), 2**7), "int8": (-(2**7), 2**7), "char": (0, 2**8), "uint8": (0, 2**8),
    "int16": (-(2**15), 2**15), "uint16": (0, 2**16), "int32": (-(2**31), 2**31),
    "uint32": (0, 2**32), "int64": (-(2**63), 2**63), "uint64": (0, 2**64),
}
_SIZES: dict[str, int] = {
    "bool": 1, "byte": 1, "int8": 1, "char": 1, "uint8": 1, "int16": 2, "uint16": 2,
    "int32": 4, "uint32": 4, "float32": 4, "int64": 8, "uint64": 8, "float64": 8,
    "time": 8, "duration": 8,
}


class Message:
    """Base class of generated message classes (genpy.Message's behaviour)."""

    __slots__ = ("_connection_header",)
    _type: ClassVar[str] = ""
    _md5sum: ClassVar[str] = ""
    _full_text: ClassVar[str] = ""
    _has_header: ClassVar[bool] = False
    _slot_types: ClassVar[tuple[str, ...]] = ()
    _slot_classes: ClassVar[dict[str, type[Message]]] = {}

    def __init__(self, *args: Any, **kwds: Any) -> None:
        """genpy's base constructor: every field positionally, or some by keyword (the rest None),
        never both; a subclass fills its defaults after calling it."""
        init_fields(self, args, kwds)

    def _get_types(self) -> tuple[str, ...]:
        return self._slot_types

    def _check_types(self, exc: BaseException | None = None) -> None:
        problem = find_type_problem(self)
        if problem:
            raise SerializationError(problem)
        if exc is not None:
            raise SerializationError(str(exc))

    # Generated classes define these; the base class has no fields, so it writes and reads
    # nothing (genpy's base Message does the same).
    def serialize(self, buff: Any) -> None:
        return None

    def deserialize(self, data: Any) -> Message:
        return self

    def __getstate__(self) -> list[Any]:
        return [getattr(self, name) for name in self.__slots__]

    def __setstate__(self, state: list[Any]) -> None:
        for name, value in zip(self.__slots__, state, strict=False):
            setattr(self, name, value)

    def __repr__(self) -> str:
        return strify_message(self)

    def __str__(self) -> str:
        return strify_message(self)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, self.__class__):
            return False
        for name in self.__slots__:
            try:
                if not _values_equal(getattr(self, name), getattr(other, name)):
                    return False
            except AttributeError:
                return False
        return True

    def __ne__(self, other: object) -> bool:
        return not self == other

    __hash__ = None  # type: ignore[assignment]  # mutable, like genpy's


def _values_equal(a: Any, b: Any) -> bool:
    if isinstance(a, (list, tuple)) and isinstance(b, (list, tuple)):
        return len(a) == len(b) and all(_values_equal(x, y) for x, y in zip(a, b, strict=False))
    result = a == b
    if isinstance(result, bool):
        return result
    try:  # numpy arrays compare element-wise
        return bool(result.all()) and len(a) == len(b)
    except (AttributeError, TypeError):
        return bool(result)


def init_fields(msg: Message, args: tuple[Any, ...], kwds: dict[str, Any]) -> None:
    """genpy's constructor rules: all fields positionally, or some by keyword, never both."""
    slots = msg.__slots__
    if args and kwds:
        raise TypeError("Message constructor may only use args OR keywords, not both")
    if args:
        if len(args) != len(slots):
            raise TypeError(f"Invalid number of arguments, args should be {list(slots)} args are{args}")
        for name, value in zip(slots, args, strict=False):
            setattr(msg, name, value)
        return
    for key in kwds:
        if key not in slots:
            raise AttributeError(f"{key} is not an attribute of {type(msg).__name__}")
    for name in slots:
        setattr(msg, name, kwds.get(name))


# ---------------------------------------------------------------- str()


def _yaml_string(value: str) -> str:
    if not value:
        return "''"
    import yaml  # only str() needs it; keep it out of every node's start-up

    return yaml.dump(value, default_style='"').rstrip("\n")


def strify_message(val: Any, indent: str = "", time_offset: Time | None = None) -> str:
    """The YAML-like text rostopic echo prints and genpy's str() gives."""
    if isinstance(val, bool) or type(val) in (int, float):
        return str(val)
    if isinstance(val, (str, bytes)):
        if isinstance(val, bytes):
            return _yaml_string(val.decode("utf-8", "replace"))
        return _yaml_string(val)
    if isinstance(val, TVal):
        if time_offset is not None and isinstance(val, Time):
            val = val - time_offset
        return f"\n{indent}secs: {val.secs}\n{indent}nsecs: {val.nsecs:9d}"
    if isinstance(val, (list, tuple)):
        if not val:
            return "[]"
        first = val[0]
        if isinstance(first, str):
            import yaml

            text = yaml.dump(list(val)).rstrip("\n")
            if text.startswith("["):
                return text
            return "\n" + "\n".join(indent + line for line in text.splitlines())
        if isinstance(first, (int, float, bool)):
            return str(list(val))
        prefix = indent + "- "
        inner = indent + "  "
        return "\n" + "\n".join(prefix + strify_message(v, inner, time_offset) for v in val)
    if isinstance(val, Message):
        inner = "  " + indent
        lines = [
            f"{indent}{name}: {strify_message(_printable(val, name, slot_type), inner, time_offset)}"
            for name, slot_type in zip(val.__slots__, val._slot_types, strict=False)
        ]
        text = "\n".join(lines)
        return "\n" + text if indent else text
    if hasattr(val, "tolist"):  # numpy arrays from deserialize_numpy
        return strify_message(val.tolist(), indent, time_offset)
    return str(val)


def _printable(msg: Message, name: str, slot_type: str) -> Any:
    value = getattr(msg, name)
    if isinstance(value, (bytes, bytearray, memoryview)) and ("uint8[" in slot_type or "char[" in slot_type):
        return list(bytes(value))
    return value


# ---------------------------------------------------------------- diagnostics


def _type_problem(path: str, type_name: str, value: Any) -> str | None:
    base, is_array, length = split_array(type_name)
    if is_array:
        if base in ("uint8", "char") and isinstance(value, (bytes, bytearray, memoryview)):
            if length is not None and len(value) != length:
                return f"field {path} must hold exactly {length} bytes, got {len(value)}"
            return None
        if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or not hasattr(value, "__iter__"):
            return f"field {path} must be a list or tuple type, got {type(value).__name__}"
        if length is not None and len(value) != length:
            return f"field {path} must have exactly {length} elements, got {len(value)}"
        for index, item in enumerate(value):
            problem = _type_problem(f"{path}[{index}]", base, item)
            if problem:
                return problem
        return None
    if base in _INT_RANGES:
        if isinstance(value, bool) or not isinstance(value, int):
            if hasattr(value, "__index__") and not isinstance(value, float):
                value = value.__index__()
            else:
                return f"field {path} must be an integer type ({base}), got {type(value).__name__} {value!r}"
        low, high = _INT_RANGES[base]
        if not low <= value < high:
            return f"field {path} value {value} is out of range for {base} [{low}, {high - 1}]"
        return None
    if base in ("float32", "float64"):
        try:
            float(value)
        except (TypeError, ValueError):
            return f"field {path} must be float type ({base}), got {type(value).__name__} {value!r}"
        return None
    if base == "bool":
        if value not in (True, False, 0, 1):
            return f"field {path} is not a bool: {value!r}"
        return None
    if base == "string":
        if not isinstance(value, (str, bytes)):
            return f"field {path} must be a string, got {type(value).__name__} {value!r}"
        return None
    if base == "time":
        if not isinstance(value, Time):
            return f"field {path} must be of type Time, got {type(value).__name__}"
        if not _both_ints(value):
            return f"field {path} time value must be integer seconds and nanoseconds: {value.secs!r}, {value.nsecs!r}"
        if value.secs < 0 or value.secs >= 2**32 or not 0 <= value.nsecs < 2**32:
            return f"field {path} time value out of range: {value.secs}.{value.nsecs:09d}"
        return None
    if base == "duration":
        if not isinstance(value, Duration):
            return f"field {path} must be of type Duration, got {type(value).__name__}"
        if not _both_ints(value):
            return f"field {path} duration must be integer seconds and nanoseconds: {value.secs!r}, {value.nsecs!r}"
        if not -(2**31) <= value.secs < 2**31:
            return f"field {path} duration out of range: {value.secs}s"
        return None
    if not isinstance(value, Message):
        return f"field {path} must be a {base} message, got {type(value).__name__} {value!r}"
    if value._type != base:
        return f"field {path} must be of type {base}, got {value._type}"
    return find_type_problem(value, path + ".")


def _both_ints(value: Time | Duration) -> bool:
    return all(isinstance(v, int) and not isinstance(v, bool) for v in (value.secs, value.nsecs))


def find_type_problem(msg: Message, prefix: str = "") -> str | None:
    """A sentence naming the first field whose value cannot be serialized, or None."""
    for name, slot_type in zip(msg.__slots__, msg._slot_types, strict=False):
        try:
            value = getattr(msg, name)
        except AttributeError:
            return f"field {prefix}{name} is not set"
        problem = _type_problem(prefix + name, slot_type, value)
        if problem:
            return problem
    return None


def serialize_failed(msg: Message, exc: BaseException) -> SerializationError:
    """The error to raise when a generated serializer failed: it names the field at fault."""
    problem = find_type_problem(msg)
    detail = problem or f"{type(exc).__name__}: {exc}"
    return SerializationError(f"cannot serialize {msg._type}: {detail}")


class _Reader:
    """Walks bytes the way a message lays them out, to say where decoding ran out."""

    def __init__(self, data: Any) -> None:
        self.view = memoryview(data).cast("B")
        self.offset = 0

    def take(self, size: int, path: str) -> memoryview:
        end = self.offset + size
        if size < 0 or end > len(self.view):
            remaining = len(self.view) - self.offset
            raise DeserializationError(
                f"field {path}: needs {size} bytes at offset {self.offset}, only {remaining} left"
            )
        chunk = self.view[self.offset:end]
        self.offset = end
        return chunk

    def count(self, path: str) -> int:
        (n,) = struct.unpack("<I", self.take(4, path + " (length)"))
        return int(n)


def _walk(reader: _Reader, cls: type[Message], prefix: str) -> None:
    for name, slot_type in zip(cls.__slots__, cls._slot_types, strict=False):
        path = prefix + name
        base, is_array, length = split_array(slot_type)
        count = 1
        if is_array:
            count = reader.count(path) if length is None else length
            element = cls._slot_classes.get(name) if base not in _SIZES and base != "string" else None
            if element is not None and not element.__slots__:
                continue  # elements of no data (std_msgs/Empty): nothing to walk, whatever the count
        for index in range(count):
            item_path = f"{path}[{index}]" if is_array else path
            if base == "string":
                reader.take(reader.count(item_path), item_path)
            elif base in _SIZES:
                if is_array:  # a whole primitive array is one block
                    reader.take(_SIZES[base] * count, path)
                    break
                reader.take(_SIZES[base], item_path)
            else:
                _walk(reader, cls._slot_classes[name], item_path + ".")


def deserialize_failed(cls: type[Message], data: Any, exc: BaseException) -> DeserializationError:
    """The error to raise when a generated deserializer failed: it says which field and where."""
    try:
        _walk(_Reader(data), cls, "")
    except DeserializationError as found:
        return DeserializationError(f"cannot deserialize {cls._type}: {found}")
    except Exception:  # the walk is a diagnosis only: fall back on the original error below
        pass
    return DeserializationError(f"cannot deserialize {cls._type}: {type(exc).__name__}: {exc}")


def refill(msg: Any, cls: Any, data: Any) -> Any:
    """deserialize()'s way out when msg's nested objects cannot be reused (missing, None, of
    another kind): deserialize into new objects and put them in msg's fields."""
    fresh = cls._from_buffer(data)
    for name in cls.__slots__:
        setattr(msg, name, getattr(fresh, name))
    return msg


def buffer_too_short(cls: type[Message], needed: int, available: int) -> DeserializationError:
    return DeserializationError(
        f"cannot deserialize {cls._type}: buffer too short, need {needed} bytes, have {available}"
    )
