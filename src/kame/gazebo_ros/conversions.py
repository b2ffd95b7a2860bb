"""kame.gazebo's poses and vectors to geometry_msgs and back, and ROS time from simulated seconds."""

from __future__ import annotations

import math
from typing import Any

from kame.client import clock
from kame.gazebo.poses import Pose, Vector3


def stamp(seconds: float) -> Any:
    nanoseconds = round(seconds * 1e9)
    return clock.Time(nanoseconds // 1_000_000_000, nanoseconds % 1_000_000_000)


def seconds(time_value: Any) -> float:
    return float(time_value.secs) + float(time_value.nsecs) * 1e-9


def pose_msg(pose: Pose) -> Any:
    from geometry_msgs.msg import Point, Quaternion
    from geometry_msgs.msg import Pose as PoseMsg

    return PoseMsg(Point(*pose.position), Quaternion(*pose.orientation))


def vector_msg(vector: Vector3) -> Any:
    from geometry_msgs.msg import Vector3 as Vector3Msg

    return Vector3Msg(*vector)


def twist_msg(linear: Vector3, angular: Vector3) -> Any:
    from geometry_msgs.msg import Twist

    return Twist(vector_msg(linear), vector_msg(angular))


def vector_of(msg: Any) -> Vector3:
    return (float(msg.x), float(msg.y), float(msg.z))


def pose_of(msg: Any) -> Pose:
    o = msg.orientation
    return Pose(vector_of(msg.position), (float(o.x), float(o.y), float(o.z), float(o.w)))


def finite(*values: float) -> bool:
    return all(math.isfinite(v) for v in values)


def finite_pose(msg: Any) -> bool:
    o = msg.orientation
    return finite(*vector_of(msg.position), o.x, o.y, o.z, o.w)


def finite_twist(msg: Any) -> bool:
    return finite(*vector_of(msg.linear), *vector_of(msg.angular))
