"""genpy.message: the message base class, str() formatting, filling messages from YAML
arguments, and message classes by type name."""

from __future__ import annotations

import codecs
import logging
import struct
from collections.abc import Mapping
from importlib import reload as reload  # genpy's names from its Python 2 days, which code for both imports
from io import StringIO
from typing import Any

from genpy.base import is_simple
from kame import rostime as _rostime
from kame.msg.errors import DeserializationError, SerializationError
from kame.msg.errors import MessageError as MessageException
from kame.msg.fill import fill_message_args as _fill_message_args
from kame.msg.fill import printable_message_args
from kame.msg.message import Message, strify_message
from kame.rostime import Duration, Time, TVal
from roslib.message import get_message_class, get_service_class

long = int

__all__ = ["DeserializationError", "Duration", "Message", "MessageException", "RosMsgUnicodeErrors",
           "SerializationError", "TVal", "Time", "check_type", "fill_message_args", "get_message_class",
           "get_printable_message_args", "get_service_class", "isstring", "strify_message", "struct_I"]

struct_I = struct.Struct("<I")  # the length prefix genpy-style generated code reads


class RosMsgUnicodeErrors:
    """The 'rosmsg' codec error handler genpy-style generated code decodes strings with: bad
    UTF-8 is replaced, and said once per message type on the 'rosout' logger. The code sets
    `msg_type` (codecs.lookup_error("rosmsg").msg_type = self._type) before decoding."""

    def __init__(self) -> None:
        self.msg_type: str | None = None
        self._warned: set[str | None] = set()

    def __call__(self, err: UnicodeError) -> tuple[str | bytes, int]:
        if self.msg_type not in self._warned:
            self._warned.add(self.msg_type)
            extra = f"message {self.msg_type}" if self.msg_type else "unknown message"
            logging.getLogger("rosout").error("Characters replaced when decoding %s (will print only once): %s",
                                              extra, err)
        return codecs.replace_errors(err)


codecs.register_error("rosmsg", RosMsgUnicodeErrors())


def isstring(s: Any) -> bool:
    """True for a str (genpy's Python 2 and 3 helper)."""
    return isinstance(s, str)

_WIDTHS = {"byte": 8, "char": 8, "int8": 8, "uint8": 8, "int16": 16, "uint16": 16, "int32": 32, "uint32": 32,
           "int64": 64, "uint64": 64}
_FLOAT_TYPES: tuple[type, ...] = (float, int)
try:
    import numpy as _np

    _FLOAT_TYPES += (_np.float32, _np.float64, _np.int8, _np.int16, _np.int32, _np.int64, _np.uint8, _np.uint16,
                     _np.uint32, _np.uint64)
except ImportError:  # numpy is optional: without it only Python's numbers are floats
    pass


def check_type(field_name: str, field_type: str, field_val: Any) -> None:
    """Whether `field_val` fits the .msg type `field_type`, as genpy checks it to explain a failed
    serialization: SerializationError with genpy's texts when it does not (slow; for diagnosis)."""
    if is_simple(field_type):
        _check_simple(field_name, field_type, field_val)
    elif field_type == "string":
        if type(field_val) is str:
            try:
                field_val.encode("ascii")
            except UnicodeEncodeError:
                raise SerializationError(f"field {field_name} is a non-ascii string") from None
        elif type(field_val) is not bytes:
            raise SerializationError(f"field {field_name} must be of type bytes or an ascii string")
    elif field_type in ("time", "duration"):
        wanted = _rostime.Time if field_type == "time" else _rostime.Duration
        if not isinstance(field_val, wanted):
            raise SerializationError(f"field {field_name} must be of type {wanted.__name__}")
    elif field_type.endswith("]"):
        base_type = field_type[:field_type.index("[")]
        if type(field_val) in (bytes, str):
            if base_type not in ("char", "uint8"):
                raise SerializationError(
                    f"field {field_name} must be a list or tuple type. Only uint8[] can be a string")
            return
        if type(field_val) not in (list, tuple):
            raise SerializationError(f"field {field_name} must be a list or tuple type")
        for value in field_val:
            check_type(field_name + "[]", base_type, value)
    elif isinstance(field_val, Message):
        if field_val._type in ("std_msgs/Header", "roslib/Header"):
            if field_type not in ("Header", "std_msgs/Header", "roslib/Header"):
                raise SerializationError(f"field {field_name} must be a Header instead of a {field_val._type}")
        elif field_val._type != field_type:
            raise SerializationError(
                f"field {field_name} must be of type {field_type} instead of {field_val._type}")
        for name, slot_type in zip(field_val.__slots__, field_val._get_types(), strict=False):
            check_type(f"{field_name}.{name}", slot_type, getattr(field_val, name))
    else:
        raise SerializationError(f"field {field_name} must be of type [{field_type}]")


def _check_simple(field_name: str, field_type: str, field_val: Any) -> None:
    if field_type in ("byte", "int8", "int16", "int32", "int64"):
        if type(field_val) is not int:
            raise SerializationError(f"field {field_name} must be an integer type")
        limit = 1 << (_WIDTHS[field_type] - 1)
        if not -limit <= field_val < limit:
            raise SerializationError(f"field {field_name} exceeds specified width [{field_type}]")
    elif field_type in ("char", "uint8", "uint16", "uint32", "uint64"):
        if type(field_val) is not int or field_val < 0:
            raise SerializationError(f"field {field_name} must be unsigned integer type")
        if field_val >= 1 << _WIDTHS[field_type]:
            raise SerializationError(f"field {field_name} exceeds specified width [{field_type}]")
    elif field_type in ("float32", "float64"):
        if type(field_val) not in _FLOAT_TYPES:
            raise SerializationError(f"field {field_name} must be float type")
    elif field_val not in (True, False, 0, 1):  # bool
        raise SerializationError(f"field {field_name} is not a bool")


def fill_message_args(msg: Message, msg_args: list[Any], keys: Mapping[str, Any] | None = None) -> None:
    """Fill `msg` from YAML command-line values (positional, or one dict of fields), as
    `rostopic pub` does; `keys` maps `now`/`auto` to what they stand for. MessageException
    (with genpy's texts) when the arguments do not fit."""
    _fill_message_args(msg, msg_args, keys)


def get_printable_message_args(msg: Message, buff: StringIO | None = None, prefix: str = "") -> str:
    """`linear.x linear.y ...`: the fields a positional argument list fills, in order."""
    text = printable_message_args(msg, prefix)
    if buff is None:
        return text
    buff.write(text + " ")
    return buff.getvalue().rstrip()
