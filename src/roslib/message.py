"""roslib.message: the message base class, str() formatting, and classes by type name."""

from __future__ import annotations

from typing import Any

from kame.msg import lookup
from kame.msg.errors import DeserializationError, MessageError, SerializationError
from kame.msg.message import Message, strify_message

__all__ = ["DeserializationError", "Message", "SerializationError", "get_message_class", "get_service_class",
           "strify_message"]


def get_message_class(message_type: str, reload_on_error: bool = False) -> Any:
    """The class of 'pkg/Type', or None if it cannot be found."""
    try:
        return lookup.message_class(message_type)
    except MessageError:
        return None


def get_service_class(service_type: str, reload_on_error: bool = False) -> Any:
    """The class of the service 'pkg/Srv', or None if it cannot be found."""
    try:
        return lookup.service_class(service_type)
    except MessageError:
        return None
