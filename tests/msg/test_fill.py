"""kame.msg.fill: YAML command-line values into messages, with genpy's rules and wording."""

from __future__ import annotations

import pytest
import yaml

from geometry_msgs.msg import PointStamped, PoseArray, Twist
from kame.msg.fill import FillError, fill_message_args, printable_message_args
from kame.msg.message import find_type_problem
from kame.rostime import Duration, Time
from sensor_msgs.msg import JointState
from std_msgs.msg import Empty, Header, Int32, String, UInt8MultiArray


def filled(cls: type, *args: str, keys: dict | None = None):  # type: ignore[no-untyped-def, type-arg]
    msg = cls()
    fill_message_args(msg, [yaml.safe_load(a) for a in args], keys or {})
    return msg


def test_positional_lists_fill_sub_messages_in_order() -> None:
    msg = filled(Twist, "[2, 0, 0]", "[0, 0, -2]")
    assert (msg.linear.x, msg.angular.z) == (2, -2)


def test_mapping_keeps_defaults_and_block_yaml_works() -> None:
    msg = filled(Twist, "linear: {x: 2.0}\nangular: {z: 1.8}")
    assert (msg.linear.x, msg.linear.y, msg.angular.z) == (2.0, 0.0, 1.8)
    assert filled(Twist, "{linear: {x: 1.0}, angular: {z: 0.5}}").angular.z == 0.5


def test_single_field_messages_take_a_bare_value() -> None:
    assert filled(String, "hello").data == "hello"
    assert filled(Int32, "5").data == 5
    assert filled(String, "data:").data == ""  # an empty YAML value is an empty string


def test_no_arguments_fit_only_a_message_without_fields() -> None:
    msg = Empty()
    fill_message_args(msg, None)
    assert msg == Empty()
    with pytest.raises(FillError, match=r"^Not enough arguments:"):
        fill_message_args(Twist(), [])


def test_wrong_field_name_is_named_with_its_path() -> None:
    with pytest.raises(FillError, match=r"^No field name \[linear\.q\]$"):
        filled(Twist, "{linear: {q: 1}}")
    assert printable_message_args(Twist()) == "linear.x linear.y linear.z angular.x angular.y angular.z"


def test_argument_counts_use_genpy_wording() -> None:
    with pytest.raises(FillError) as few:
        filled(Twist, "[1, 2]")
    assert str(few.value) == "Not enough arguments:\n * Given: [[1, 2]]\n * Expected: ['linear', 'angular']"
    with pytest.raises(FillError, match=r"^Too many arguments:\n \* Given: \[1, 2, 3, 4\]"):
        filled(Twist, "[1, 2, 3, 4]", "[0, 0, 0]")


def test_scalar_for_a_message_field_names_the_field() -> None:
    with pytest.raises(FillError, match=r"^Field \[linear\] is a message"):
        filled(Twist, "{linear: 3}")


def test_keys_now_and_auto() -> None:
    now = Time(10, 20)
    keys = {"now": now, "auto": Header(stamp=now)}
    msg = filled(PointStamped, "{header: auto, point: [1, 2, 3]}", keys=keys)
    assert msg.header.stamp == now
    msg = filled(PointStamped, "{header: {stamp: now, frame_id: odom}}", keys=keys)
    assert (msg.header.stamp, msg.header.frame_id) == (now, "odom")
    with pytest.raises(FillError, match=r"^No key named \[later\]$"):
        filled(PointStamped, "{header: {stamp: later}}", keys=keys)
    with pytest.raises(FillError, match=r"cannot be set to \[auto\]"):
        filled(PointStamped, "{header: {stamp: auto}}", keys=keys)


def test_time_values_from_mappings_lists_and_nanoseconds() -> None:
    assert filled(Header, "{stamp: {secs: 3, nsecs: 4}}").stamp == Time(3, 4)
    assert filled(Header, "{stamp: [3, 4]}").stamp == Time(3, 4)
    assert filled(Header, "{stamp: 3000000004}").stamp == Time(3, 4)


def test_arrays_of_primitives_and_messages() -> None:
    js = filled(JointState, "{name: [a, b], position: [1, 2.5]}")
    assert (js.name, js.position) == (["a", "b"], [1, 2.5])
    poses = filled(PoseArray, "{poses: [{position: {x: 1}}, [[2, 3, 0.5], [0, 0, 0, 1]]]}")
    assert [p.position.x for p in poses.poses] == [1, 2]
    assert poses.poses[1].orientation.w == 1
    with pytest.raises(FillError, match=r"^No field name \[poses\[0\]\.position\.q\]$"):
        filled(PoseArray, "{poses: [{position: {q: 1}}]}")
    with pytest.raises(FillError, match=r"^Field \[position\] must be a list or tuple instead of: float$"):
        filled(JointState, "{position: 1.5}")


def test_uint8_arrays_take_lists_or_strings() -> None:
    assert filled(UInt8MultiArray, "{data: [1, 2, 255]}").data == [1, 2, 255]
    assert filled(UInt8MultiArray, "{data: abc}").data == b"abc"


def test_wrong_primitive_types_are_left_to_the_type_check_which_names_the_field() -> None:
    msg = filled(Int32, "hello")
    assert find_type_problem(msg) == "field data must be an integer type (int32), got str 'hello'"
    assert Duration(1) == Duration(1)  # Duration fields share the time rules


@pytest.mark.parametrize("value", [-1, -0.5, float("nan"), float("inf")])
def test_a_time_that_cannot_be_is_a_fill_error(value: float) -> None:
    # Found by tests/fuzz: a negative stamp was a TypeError traceback out of rostopic pub.
    with pytest.raises(FillError, match=r"Field \[stamp\] cannot be"):
        fill_message_args(Header(), [0, value, "frame"])


def test_a_time_filled_with_non_numbers_is_a_type_problem_not_a_crash() -> None:
    # Found by tests/fuzz: find_type_problem compared None with 0 (TypeError out of rostopic pub).
    msg = Header()
    fill_message_args(msg, [0, [None, None], "frame"])
    assert find_type_problem(msg) == "field stamp time value must be integer seconds and nanoseconds: None, None"
