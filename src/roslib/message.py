"""roslib.message: message and service classes looked up by type name ('std_msgs/String')."""

from __future__ import annotations

import importlib
from typing import Any

from kame.msg.errors import DeserializationError, SerializationError

__all__ = ["DeserializationError", "SerializationError", "get_message_class", "get_service_class"]


def _lookup(type_name: str, kind: str) -> Any:
    package, sep, short = type_name.partition("/")
    if not sep or not package or not short:
        return None
    try:
        module = importlib.import_module(f"{package}.{kind}")
        return getattr(module, short)
    except (ImportError, AttributeError):
        return None


def get_message_class(message_type: str, reload_on_error: bool = False) -> Any:
    """The class of 'pkg/Type', or None if it cannot be found."""
    if message_type == "Header":
        message_type = "std_msgs/Header"
    return _lookup(message_type, "msg")


def get_service_class(service_type: str, reload_on_error: bool = False) -> Any:
    """The class of the service 'pkg/Srv', or None if it cannot be found."""
    return _lookup(service_type, "srv")
