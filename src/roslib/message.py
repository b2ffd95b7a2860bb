"""roslib.message: the message base class, str() formatting, and classes by type name."""

from __future__ import annotations

from typing import Any

from kame.msg import lookup
from kame.msg.errors import DeserializationError, MessageError, SerializationError
from kame.msg.message import Message, strify_message
from kame.rostime import Duration, Time, TVal

__all__ = ["DeserializationError", "Duration", "Message", "SerializationError", "TVal", "Time", "get_message_class",
           "get_service_class", "strify_message"]

# genpy.message's, as roslib.message re-exports them; looked up on first use because
# genpy.message imports this module (its get_message_class is the one below)
_FROM_GENPY = ("check_type", "fill_message_args", "get_printable_message_args")


def __getattr__(name: str) -> Any:
    if name in _FROM_GENPY:
        import genpy.message

        return getattr(genpy.message, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _full_name(type_name: str) -> str:
    """'pkg/Type' as genpy reads it: ValueError for more than one '/' or no package (but Header's)."""
    parts = type_name.split("/")
    if len(parts) > 2:
        raise ValueError(f"invalid name [{type_name}]")
    if len(parts) == 1:
        if type_name != "Header":
            raise ValueError(f"message type is missing package name: {type_name}")
        return "std_msgs/Header"
    return type_name


def get_message_class(message_type: str, reload_on_error: bool = False) -> Any:
    """The class of 'pkg/Type' (`time` and `duration`: Time and Duration), or None when it cannot
    be found; ValueError for a name without a package (Header aside) or with more than one '/'."""
    if message_type == "time":
        return Time
    if message_type == "duration":
        return Duration
    try:
        return lookup.message_class(_full_name(message_type))
    except MessageError:
        return None


def get_service_class(service_type: str, reload_on_error: bool = False) -> Any:
    """The class of the service 'pkg/Srv', or None when it cannot be found; ValueError as
    get_message_class."""
    try:
        return lookup.service_class(_full_name(service_type))
    except MessageError:
        return None
