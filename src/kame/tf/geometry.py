"""tf2_geometry_msgs's do_transform_* on any objects with the geometry_msgs fields: each takes
a stamped value and a TransformStamped and returns a new stamped value in the transform's
parent frame (header copied from the transform). The input is never modified (ROS's
do_transform_vector3 zeroes the transform's translation in place; this one does not)."""

from __future__ import annotations

import copy
from typing import Any

from . import rotation
from .rotation import Quaternion, Vector


def _parts(transform: Any) -> tuple[Vector, Quaternion]:
    t, r = transform.transform.translation, transform.transform.rotation
    return (t.x, t.y, t.z), (r.x, r.y, r.z, r.w)


def _set_xyz(target: Any, values: Vector) -> None:
    target.x, target.y, target.z = values


def transform_point(transform: Any, point: Vector) -> Vector:
    translation, quaternion = _parts(transform)
    return rotation.add(rotation.rotate(quaternion, point), translation)


def transform_vector(transform: Any, vector: Vector) -> Vector:
    return rotation.rotate(_parts(transform)[1], vector)


def transform_pose(transform: Any, position: Vector, orientation: Quaternion) -> tuple[Vector, Quaternion]:
    translation, quaternion = _parts(transform)
    return (rotation.add(rotation.rotate(quaternion, position), translation),
            rotation.multiply(quaternion, orientation))


def do_transform_point(point: Any, transform: Any) -> Any:
    result = copy.deepcopy(point)
    p = point.point
    _set_xyz(result.point, transform_point(transform, (p.x, p.y, p.z)))
    result.header = copy.deepcopy(transform.header)
    return result


def do_transform_vector3(vector3: Any, transform: Any) -> Any:
    result = copy.deepcopy(vector3)
    v = vector3.vector
    _set_xyz(result.vector, transform_vector(transform, (v.x, v.y, v.z)))
    result.header = copy.deepcopy(transform.header)
    return result


def _move_pose(target: Any, source: Any, transform: Any) -> None:
    p, o = source.position, source.orientation
    position, orientation = transform_pose(transform, (p.x, p.y, p.z), (o.x, o.y, o.z, o.w))
    _set_xyz(target.position, position)
    target.orientation.x, target.orientation.y, target.orientation.z, target.orientation.w = orientation


def do_transform_pose(pose: Any, transform: Any) -> Any:
    result = copy.deepcopy(pose)
    _move_pose(result.pose, pose.pose, transform)
    result.header = copy.deepcopy(transform.header)
    return result


def rotate_covariance(covariance: Any, quaternion: Quaternion) -> list[float]:
    """A row-major 6x6 (x y z, roll pitch yaw) covariance in the rotated frame: R C R^T with
    R the rotation on both 3x3 blocks."""
    m = rotation.to_matrix(quaternion)
    full = [[0.0] * 6 for _ in range(6)]
    for block in (0, 3):
        for r in range(3):
            for c in range(3):
                full[block + r][block + c] = m[r][c]
    cov = [list(covariance[row * 6:(row + 1) * 6]) for row in range(6)]
    rc = [[sum(full[r][n] * cov[n][c] for n in range(6)) for c in range(6)] for r in range(6)]
    return [sum(rc[r][n] * full[c][n] for n in range(6)) for r in range(6) for c in range(6)]


def do_transform_pose_with_covariance_stamped(pose: Any, transform: Any) -> Any:
    result = copy.deepcopy(pose)
    _move_pose(result.pose.pose, pose.pose.pose, transform)
    result.pose.covariance = rotate_covariance(pose.pose.covariance, _parts(transform)[1])
    result.header = copy.deepcopy(transform.header)
    return result


def do_transform_wrench(wrench: Any, transform: Any) -> Any:
    """Force and torque rotated into the parent frame (the torque's reference point is not moved,
    as tf2_geometry_msgs does)."""
    result = copy.deepcopy(wrench)
    f, t = wrench.wrench.force, wrench.wrench.torque
    _set_xyz(result.wrench.force, transform_vector(transform, (f.x, f.y, f.z)))
    _set_xyz(result.wrench.torque, transform_vector(transform, (t.x, t.y, t.z)))
    result.header = copy.deepcopy(transform.header)
    return result
