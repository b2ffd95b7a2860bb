"""kame.msg: the ROS 1 message layer (IDL parsing, md5sums, definitions, codegen, codecs)."""

from kame.msg.catalog import MsgCatalog, Package, find_packages, package_path_roots
from kame.msg.errors import (
    DeserializationError,
    MessageError,
    MsgDefinitionError,
    MsgNotFoundError,
    SerializationError,
)
from kame.msg.message import Message, strify_message
from kame.msg.parser import parse_action, parse_msg, parse_srv
from kame.msg.spec import ActionSpec, Constant, Field, MsgSpec, SrvSpec

__all__ = [
    "ActionSpec",
    "Constant",
    "DeserializationError",
    "Field",
    "Message",
    "MessageError",
    "MsgCatalog",
    "MsgDefinitionError",
    "MsgNotFoundError",
    "MsgSpec",
    "Package",
    "SerializationError",
    "SrvSpec",
    "find_packages",
    "package_path_roots",
    "parse_action",
    "parse_msg",
    "parse_srv",
    "strify_message",
]
