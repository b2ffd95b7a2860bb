"""kame.msg.lookup: the one 'which class is this type name' of rospy, rosbag, roslib and the tools."""

from __future__ import annotations

import pytest

from kame.msg import lookup
from kame.msg.anymsg import AnyMsg
from kame.msg.errors import MessageError


def test_message_class_by_type_name() -> None:
    from std_msgs.msg import Header, String

    assert lookup.message_class("std_msgs/String") is String
    assert lookup.message_class("Header") is Header
    for missing in ("no_such_pkg/Nope", "std_msgs/Nope", "malformed", "std_msgs/", "/String", "std_msgs/a/b"):
        assert lookup.message_class(missing) is None, missing


def test_service_class_by_type_name_and_roscpp_request_name() -> None:
    from std_srvs.srv import Empty

    assert lookup.service_class("std_srvs/Empty") is Empty
    assert lookup.service_class("std_srvs/EmptyRequest") is Empty
    assert lookup.service_class("std_msgs/String") is None  # a message, not a service


def test_class_for_prefers_the_installed_class_with_the_same_md5sum() -> None:
    from std_msgs.msg import String

    assert lookup.class_for("std_msgs/String", String._md5sum, "") is String
    assert lookup.class_for("std_msgs/String", "*", "") is String
    other = lookup.class_for("std_msgs/String", "0" * 32, "int32 data\n")
    assert other is not None and other is not String and list(other._slot_types) == ["int32"]
    assert lookup.class_for("std_msgs/String", "0" * 32, "") is None
    assert lookup.class_for("nobody/Knows", "0" * 32, "string name\n") is not None
    with pytest.raises(MessageError):
        lookup.class_for("not a type", "0" * 32, "int32 x\n")


def test_anymsg_keeps_the_bytes() -> None:
    msg = AnyMsg._from_buffer(memoryview(b"\x01\x02"))
    assert msg._buff == b"\x01\x02"
    with pytest.raises(MessageError):
        AnyMsg(1)
