"""genpy.message: the message base class, str() formatting, filling messages from YAML
arguments, and message classes by type name."""

from __future__ import annotations

from collections.abc import Mapping
from io import StringIO
from typing import Any

from kame.msg.errors import DeserializationError, SerializationError
from kame.msg.errors import MessageError as MessageException
from kame.msg.fill import fill_message_args as _fill_message_args
from kame.msg.fill import printable_message_args
from kame.msg.message import Message, strify_message
from roslib.message import get_message_class, get_service_class

__all__ = ["DeserializationError", "Message", "MessageException", "SerializationError", "fill_message_args",
           "get_message_class", "get_printable_message_args", "get_service_class", "strify_message"]


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
