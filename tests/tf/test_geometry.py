"""tf2_geometry_msgs's do_transform_* against Debian's (PyKDL underneath) on random inputs, and
Buffer.transform() of each registered type."""

from __future__ import annotations

import json
import math
import subprocess
from pathlib import Path
from typing import Any

import numpy
import pytest

import tf2_geometry_msgs
import tf2_ros
from geometry_msgs.msg import (
    PointStamped,
    PoseStamped,
    PoseWithCovarianceStamped,
    TransformStamped,
    Vector3Stamped,
    WrenchStamped,
)
from kame.rostime import Time
from kame.tf import transformations as tr

from ..support import SYSTEM_PYTHON

PEER = Path(__file__).with_name("debian_geometry.py")


def have_debian_geometry() -> bool:
    return subprocess.run([SYSTEM_PYTHON, "-c", "import tf2_geometry_msgs"], capture_output=True).returncode == 0


def make_transform(t: list[float], q: list[float]) -> TransformStamped:
    msg = TransformStamped()
    msg.header.frame_id = "parent"
    msg.header.stamp = Time(7)
    (msg.transform.translation.x, msg.transform.translation.y, msg.transform.translation.z) = t
    (msg.transform.rotation.x, msg.transform.rotation.y, msg.transform.rotation.z, msg.transform.rotation.w) = q
    return msg


def xyz(v: Any) -> list[float]:
    return [v.x, v.y, v.z]


def ours(kind: str, tf: TransformStamped, value: Any) -> Any:
    if kind == "point":
        p = PointStamped()
        p.point.x, p.point.y, p.point.z = value
        return xyz(tf2_geometry_msgs.do_transform_point(p, tf).point)
    if kind == "vector":
        v = Vector3Stamped()
        v.vector.x, v.vector.y, v.vector.z = value
        return xyz(tf2_geometry_msgs.do_transform_vector3(v, tf).vector)
    if kind == "pose":
        p = PoseStamped()
        p.pose.position.x, p.pose.position.y, p.pose.position.z = value[0]
        o = p.pose.orientation
        o.x, o.y, o.z, o.w = value[1]
        r = tf2_geometry_msgs.do_transform_pose(p, tf).pose
        return [xyz(r.position), [r.orientation.x, r.orientation.y, r.orientation.z, r.orientation.w]]
    w = WrenchStamped()
    w.wrench.force.x, w.wrench.force.y, w.wrench.force.z = value[0]
    w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z = value[1]
    r = tf2_geometry_msgs.do_transform_wrench(w, tf).wrench
    return [xyz(r.force), xyz(r.torque)]


def close(a: Any, b: Any) -> bool:
    if isinstance(b, list):
        return len(a) == len(b) and all(close(x, y) for x, y in zip(a, b, strict=True))
    return math.isclose(a, b, rel_tol=1e-9, abs_tol=1e-9)


def same_pose(a: Any, b: Any) -> bool:
    """Positions equal; orientations equal up to sign (q and -q are one rotation; KDL picks one)."""
    return close(a[0], b[0]) and (close(a[1], b[1]) or close(a[1], [-v for v in b[1]]))


@pytest.mark.skipif(not have_debian_geometry(), reason="Debian's tf2_geometry_msgs is not installed")
def test_same_results_as_debians() -> None:
    rng = numpy.random.default_rng(11)
    batch: list[Any] = []
    for _ in range(50):
        frame = [rng.normal(size=3).tolist(), tr.random_quaternion(rng.random(3)).tolist()]
        batch += [["point", frame, rng.normal(size=3).tolist()],
                  ["vector", frame, rng.normal(size=3).tolist()],
                  ["pose", frame, [rng.normal(size=3).tolist(), tr.random_quaternion(rng.random(3)).tolist()]],
                  ["wrench", frame, [rng.normal(size=3).tolist(), rng.normal(size=3).tolist()]]]
    done = subprocess.run([SYSTEM_PYTHON, str(PEER)], input=json.dumps(batch), capture_output=True, text=True,
                          check=True, timeout=60)
    for (kind, frame, value), theirs in zip(batch, json.loads(done.stdout), strict=True):
        mine = ours(kind, make_transform(*frame), value)
        assert (same_pose(mine, theirs) if kind == "pose" else close(mine, theirs)), (kind, frame, value)


def test_buffer_transform_of_each_registered_type() -> None:
    buffer = tf2_ros.Buffer(debug=False)
    t = make_transform([1.0, 0.0, 0.0], [0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)])
    t.child_frame_id = "child"
    buffer.set_transform(t, "/test")
    point = PointStamped()
    point.header.frame_id = "child"
    point.point.x = 1.0
    moved = buffer.transform(point, "parent")
    assert moved.header.frame_id == "parent" and close(xyz(moved.point), [1.0, 1.0, 0.0])
    assert point.header.frame_id == "child"  # the input is left alone
    pose = PoseWithCovarianceStamped()
    pose.header.frame_id = "child"
    pose.pose.pose.orientation.w = 1.0
    pose.pose.covariance = [1.0 if i == 0 else 0.0 for i in range(36)]  # variance along the child's x only
    cov = buffer.transform(pose, "parent").pose.covariance
    assert close([cov[0], cov[7]], [0.0, 1.0])  # the child's x is the parent's y
    with pytest.raises(tf2_ros.TypeException):
        buffer.transform(object(), "parent")
