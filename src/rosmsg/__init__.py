"""rosmsg as a library: message and service definitions as `rosmsg show` prints them
(`rosmsg.get_msg_text('geometry_msgs/Pose')`). The `rosmsg` command is kame.cli.rosmsg; both
describe types with kame.msg.describe, from the packages on ROS_PACKAGE_PATH and kame's own.
"""

from __future__ import annotations

from typing import Any

from kame.msg.catalog import MsgCatalog
from kame.msg.describe import describe_msg, describe_srv, load_msg, load_srv
from kame.msg.errors import MessageError

__all__ = ["ROSMsgException", "get_msg_text", "get_srv_text"]


class ROSMsgException(Exception):
    """A type that cannot be found or read."""


def get_msg_text(type_: str, raw: bool = False, rospack: Any = None) -> str:
    """The message type's fields, nested types expanded (`raw`: the .msg file's text)."""
    try:
        catalog = MsgCatalog.from_environment()
        msg = load_msg(catalog, type_)
        return msg.text if raw else describe_msg(catalog, msg)
    except MessageError as exc:
        raise ROSMsgException(f"Unable to load msg [{type_}]: {exc}") from None


def get_srv_text(type_: str, raw: bool = False, rospack: Any = None) -> str:
    """The service type's request and response, `---` between (`raw`: the .srv file's text)."""
    try:
        catalog = MsgCatalog.from_environment()
        srv = load_srv(catalog, type_)
        return srv.text if raw else describe_srv(catalog, srv)
    except MessageError as exc:
        raise ROSMsgException(f"Unknown srv type [{type_}]: {exc}") from None
