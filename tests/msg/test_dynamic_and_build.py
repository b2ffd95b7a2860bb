"""Classes from a wire message_definition, and the generated packages being up to date."""

from __future__ import annotations

import io

import pytest

from kame.msg import MsgNotFoundError, generate_dynamic
from kame.msg import build as genmsg

from ..ros1_vectors import vectors

VECTORS = vectors()


@pytest.mark.parametrize("type_name", sorted(VECTORS["message_definition"]))
def test_dynamic_classes_from_real_definitions(type_name: str) -> None:
    definition = VECTORS["message_definition"][type_name]
    classes = generate_dynamic(type_name, definition)
    cls = classes[type_name]
    assert cls._md5sum == VECTORS["md5sum"][type_name]
    assert cls._full_text == definition
    assert cls._type == type_name


def test_dynamic_class_reads_what_the_installed_class_writes() -> None:
    from nav_msgs.msg import Odometry

    msg = Odometry(child_frame_id="base")
    msg.pose.pose.position.x = 4.5
    msg.twist.covariance = [float(i) for i in range(36)]
    buff = io.BytesIO()
    msg.serialize(buff)
    dynamic = generate_dynamic("nav_msgs/Odometry", VECTORS["message_definition"]["nav_msgs/Odometry"])
    back = dynamic["nav_msgs/Odometry"]().deserialize(buff.getvalue())
    assert back.pose.pose.position.x == 4.5
    assert back.twist.covariance[35] == 35.0
    assert back.child_frame_id == "base"
    assert type(back.header).__name__ == "Header"


def test_dynamic_classes_are_cached_per_definition() -> None:
    text = VECTORS["message_definition"]["std_msgs/String"]
    assert generate_dynamic("std_msgs/String", text) is generate_dynamic("std_msgs/String", text)


def test_a_definition_missing_a_dependency_says_so() -> None:
    with pytest.raises(MsgNotFoundError, match="does not define geometry_msgs/Vector3"):
        generate_dynamic("geometry_msgs/Twist", "Vector3 linear\nVector3 angular\n")


def test_generated_packages_are_up_to_date() -> None:
    # The message packages in src/ are generated files; this fails when a definition or
    # the generator changed and `kame-genmsg` was not rerun.
    assert genmsg.main(["--check"]) == 0


def test_arrays_of_empty_messages_work_and_a_huge_count_is_refused() -> None:
    # A peer's definition with std_msgs/Empty[] did not compile (an empty loop in the serializer),
    # and a 4-byte message claiming 4 billion such elements made the deserializer build them all.
    from kame.msg import DeserializationError

    separator = "=" * 80
    classes = generate_dynamic("x/Empties", f"std_msgs/Empty[] e\n{separator}\nMSG: std_msgs/Empty\n")
    cls, empty = classes["x/Empties"], classes["std_msgs/Empty"]
    buff = io.BytesIO()
    cls(e=[empty(), empty()]).serialize(buff)
    assert buff.getvalue() == b"\x02\x00\x00\x00" and len(cls().deserialize(buff.getvalue()).e) == 2
    with pytest.raises(DeserializationError, match="an array of 4294967295 elements that carry nothing"):
        cls().deserialize(b"\xff\xff\xff\xff")
