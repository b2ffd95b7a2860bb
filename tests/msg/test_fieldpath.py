"""kame.msg.fieldpath: `/a/b[1]`-style paths into messages, as rostopic echo and type use them."""

from __future__ import annotations

import pytest

from geometry_msgs.msg import Point, Pose, PoseArray
from kame.msg.fieldpath import FieldPathError, field_type, has_field, parse_field_path
from sensor_msgs.msg import JointState
from turtlesim.msg import Pose as TurtlePose


def poses() -> PoseArray:
    return PoseArray(poses=[Pose(position=Point(x=float(i))) for i in range(4)])


def test_empty_paths_name_no_field() -> None:
    assert parse_field_path("") is None
    assert parse_field_path("/") is None


def test_fields_indices_and_slices() -> None:
    js = JointState(name=["a", "b"], position=[1.0, 2.5])
    assert parse_field_path("/position[1]").evaluate(js) == 2.5  # type: ignore[union-attr]
    assert parse_field_path("/position[-1]").evaluate(js) == 2.5  # type: ignore[union-attr]
    assert parse_field_path("/name").evaluate(js) == ["a", "b"]  # type: ignore[union-attr]
    path = parse_field_path("/poses[1:3]/position/x")
    assert path is not None and path.evaluate(poses()) == [1.0, 2.0]
    assert parse_field_path("/poses[::2]/position/x").evaluate(poses()) == [0.0, 2.0]  # type: ignore[union-attr]


def test_errors_use_rostopic_wording() -> None:
    with pytest.raises(FieldPathError, match=r"^missing closing '\]' in slice spec 'x\[1'$"):
        parse_field_path("/x[1")
    with pytest.raises(FieldPathError, match=r"^field 'x' has invalid slice argument 'a': non-integer array index"):
        parse_field_path("/x[a]")
    with pytest.raises(FieldPathError, match=r"^field 'x' has invalid slice argument '': empty array index$"):
        parse_field_path("/x[]")
    with pytest.raises(FieldPathError, match=r"too many slice arguments"):
        parse_field_path("/x[1:2:3:4]")
    with pytest.raises(FieldPathError, match=r"^no field named q in /position/q$"):
        parse_field_path("/position/q").evaluate(Pose())  # type: ignore[union-attr]
    with pytest.raises(FieldPathError, match=r"index out of range: /position\[5\]"):
        parse_field_path("/position[5]").evaluate(JointState(position=[1.0]))  # type: ignore[union-attr]


def test_field_types() -> None:
    assert field_type(TurtlePose, "x") == "float32"
    assert field_type(JointState, "header/stamp") == "time"
    assert field_type(JointState, "position") == "float64[]"
    assert field_type(JointState, "position[0]") == "float64"
    assert field_type(PoseArray, "poses[1]/position") == "geometry_msgs/Point"
    assert field_type(PoseArray, "poses[1:2]") == "geometry_msgs/Pose[]"
    assert field_type(PoseArray, "") == "geometry_msgs/PoseArray"
    assert has_field(PoseArray, "header/frame_id")
    assert not has_field(PoseArray, "header/frame")
    assert not has_field(PoseArray, "poses/position")  # an array must be indexed to reach into it
    assert not has_field(TurtlePose, "x/y")
    with pytest.raises(FieldPathError, match=r"turtlesim/Pose has no field named \[z\]"):
        field_type(TurtlePose, "z")
