"""kame.msg: the ROS 1 message layer (IDL parsing, md5sums, definitions, codegen, codecs).

Names are imported on first use, so that a node importing one message class does not pay
for the parser, the catalog and the code generator.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from kame.msg.catalog import MsgCatalog, Package, find_packages, package_path_roots
    from kame.msg.errors import (
        DeserializationError,
        MessageError,
        MsgDefinitionError,
        MsgNotFoundError,
        SerializationError,
    )
    from kame.msg.loader import generate_dynamic
    from kame.msg.message import Message, strify_message
    from kame.msg.parser import parse_action, parse_msg, parse_srv
    from kame.msg.spec import ActionSpec, Constant, Field, MsgSpec, SrvSpec

_EXPORTS = {
    "MsgCatalog": "catalog", "Package": "catalog", "find_packages": "catalog", "package_path_roots": "catalog",
    "DeserializationError": "errors", "MessageError": "errors", "MsgDefinitionError": "errors",
    "MsgNotFoundError": "errors", "SerializationError": "errors",
    "generate_dynamic": "loader",
    "Message": "message", "strify_message": "message",
    "parse_action": "parser", "parse_msg": "parser", "parse_srv": "parser",
    "ActionSpec": "spec", "Constant": "spec", "Field": "spec", "MsgSpec": "spec", "SrvSpec": "spec",
}
__all__ = [
    "ActionSpec", "Constant", "DeserializationError", "Field", "Message", "MessageError", "MsgCatalog",
    "MsgDefinitionError", "MsgNotFoundError", "MsgSpec", "Package", "SerializationError", "SrvSpec",
    "find_packages", "generate_dynamic", "package_path_roots", "parse_action", "parse_msg", "parse_srv",
    "strify_message",
]


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'kame.msg' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"kame.msg.{module}"), name)
    globals()[name] = value
    return value
