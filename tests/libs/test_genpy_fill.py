"""genpy.message.fill_message_args and get_printable_message_args: the same messages and the same
error texts as Debian's genpy on the same arguments."""

from __future__ import annotations

from io import StringIO
from pathlib import Path

import pytest

import genpy.message

from . import debian
from .fill_driver import run

DRIVER = Path(__file__).with_name("fill_driver.py")
CASES = [
    ["geometry_msgs/Twist", [[1, 2, 3], [4, 5, 6]]],
    ["geometry_msgs/Twist", [{"linear": {"x": 1.5}, "angular": [0, 0, 2]}]],
    ["geometry_msgs/Twist", [1]],
    ["geometry_msgs/Twist", [[1, 2, 3], [4, 5, 6], 7]],
    ["geometry_msgs/Twist", [{"nope": 1}]],
    ["std_msgs/String", ["hello"]],
    ["std_msgs/String", []],
    ["std_msgs/Header", [1, "now", "frame"]],
    ["std_msgs/Header", [{"stamp": {"secs": 3, "nsecs": 4}}]],
    ["std_msgs/Int32MultiArray", [{"data": [1, 2, 3]}]],
    ["geometry_msgs/PoseStamped", [{"header": {"frame_id": "map"}, "pose": {"position": [1, 2, 3]}}]],
    ["std_msgs/Bool", [True]],
    ["std_msgs/Float64", ["x"]],
    ["std_msgs/Duration", [[1, 2]]],
]


@pytest.mark.skipif(not debian.has("genpy", "geometry_msgs.msg"), reason="Debian's genpy is not installed")
def test_fill_and_printable_args_as_debians_genpy() -> None:
    theirs = debian.run(DRIVER, CASES)
    assert sum(answer.startswith("error: ") for answer in theirs) >= 3
    assert run(CASES) == theirs


def test_printable_args_into_a_buffer() -> None:
    buff = StringIO()
    msg = genpy.message.get_message_class("geometry_msgs/Vector3")()
    assert genpy.message.get_printable_message_args(msg, buff=buff) == "x y z"
    assert genpy.message.get_printable_message_args(msg, buff=buff, prefix="v.") == "x y z v.x v.y v.z"
