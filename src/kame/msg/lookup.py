"""Which class is this type name: the one lookup rospy, rosbag, roslib and the ros* tools share.

- `message_class('std_msgs/String')` imports the package's `msg` module (kame's generated
  packages, or a workspace's through the import hook) and gives the class, or None when the
  name is no `pkg/Type`, the package is not there or has no such type. A package that is
  there but whose definitions are broken raises MessageError: that is the user's to fix.
  `Header` alone means `std_msgs/Header`, as in .msg files.
- `service_class('pkg/Srv')` likewise for services (`pkg/SrvRequest`, roscpp's old name for
  a service type, finds `pkg/Srv`).
- `class_for(type, md5sum, definition)` is what a reader of someone else's messages (a
  subscriber of any type, a bag) needs: the installed class when its md5sum matches, else a
  class built from the definition the writer sent; None when there is neither.
"""

from __future__ import annotations

import importlib
from types import ModuleType
from typing import Any

from kame.msg.errors import MessageError
from kame.msg.message import Message


def _module(package: str, kind: str) -> ModuleType | None:
    if not package.isidentifier():
        return None
    try:
        return importlib.import_module(f"{package}.{kind}")
    except ImportError:
        return None


def _split(type_name: str) -> tuple[str, str] | None:
    package, sep, short = type_name.partition("/")
    if not sep or not package or not short.isidentifier():
        return None
    return package, short


def message_class(type_name: str) -> type[Message] | None:
    if type_name == "Header":
        type_name = "std_msgs/Header"
    parts = _split(type_name)
    module = _module(parts[0], "msg") if parts else None
    if parts is None or module is None:
        return None
    cls = getattr(module, parts[1], None)
    if isinstance(cls, type) and issubclass(cls, Message) and cls._type == type_name:
        return cls
    return None


def service_class(type_name: str) -> Any:
    parts = _split(type_name)
    module = _module(parts[0], "srv") if parts else None
    if parts is None or module is None:
        return None
    short = parts[1]
    cls = getattr(module, short, None)
    if not hasattr(cls, "_request_class") and short.endswith("Request"):
        cls = getattr(module, short[: -len("Request")], None)
    return cls if isinstance(cls, type) and hasattr(cls, "_request_class") else None


def installed_class(type_name: str, md5sum: str) -> type[Message] | None:
    """The installed class of `type_name` if it has this md5sum ('*' matches any)."""
    try:
        cls = message_class(type_name)
    except MessageError:
        return None
    if cls is None or md5sum not in ("*", cls._md5sum):
        return None
    return cls


def class_for(type_name: str, md5sum: str, definition: str) -> type[Message] | None:
    """MessageError when the definition does not make a class of `type_name`."""
    cls = installed_class(type_name, md5sum)
    if cls is not None:
        return cls
    if not definition:
        return None
    from kame.msg.loader import generate_dynamic

    try:
        built: type[Message] = generate_dynamic(type_name, definition)[type_name]
    except ValueError as exc:  # a type name that is none
        raise MessageError(str(exc)) from exc
    return built
