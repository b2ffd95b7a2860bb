"""Poses and twists relative to another entity, as gazebo_ros's services define them (Noetic's
ignition::math: `pose - frame` is the pose seen from the frame, `pose + frame` the frame's pose
carried into the world), without I/O.

The names "", "world", "map" and "/map" are the inertial frame, as gazebo_ros takes them.
"""

from __future__ import annotations

import numpy as np

from kame.gazebo.poses import Pose, Quaternion, Vector3

INERTIAL_NAMES = ("", "world", "map", "/map")


def is_inertial(name: str) -> bool:
    return name in INERTIAL_NAMES


def _multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
            aw * bw - ax * bx - ay * by - az * bz)


def _inverse(q: Quaternion) -> Quaternion:
    x, y, z, w = q
    return (-x, -y, -z, w)


def _vector(values: np.ndarray) -> Vector3:
    return (float(values[0]), float(values[1]), float(values[2]))


def rotate(frame: Pose, vector: Vector3) -> Vector3:
    return _vector(frame.rotation() @ np.asarray(vector, dtype=float))


def unrotate(frame: Pose, vector: Vector3) -> Vector3:
    return _vector(frame.rotation().T @ np.asarray(vector, dtype=float))


def normalized(q: Quaternion) -> Quaternion:
    """A unit quaternion; (0, 0, 0, 0), which a zero-filled request carries, becomes the identity
    (as ignition's Normalize makes it)."""
    norm = float(np.linalg.norm(q))
    if norm < 1e-12:
        return (0.0, 0.0, 0.0, 1.0)
    x, y, z, w = (v / norm for v in q)
    return (x, y, z, w)


def seen_from(pose: Pose, frame: Pose) -> Pose:
    """`pose` (in the world) expressed in `frame`'s coordinates."""
    offset = tuple(p - f for p, f in zip(pose.position, frame.position, strict=True))
    return Pose(unrotate(frame, (offset[0], offset[1], offset[2])),
                _multiply(_inverse(frame.orientation), pose.orientation))


def carried_into_world(pose: Pose, frame: Pose) -> Pose:
    """`pose`, given in `frame`'s coordinates, expressed in the world."""
    moved = rotate(frame, pose.position)
    return Pose((moved[0] + frame.position[0], moved[1] + frame.position[1], moved[2] + frame.position[2]),
                normalized(_multiply(frame.orientation, pose.orientation)))


def velocity_seen_from(velocity: Vector3, frame_velocity: Vector3, frame: Pose) -> Vector3:
    """A world-frame velocity relative to a moving frame, in that frame's coordinates."""
    return unrotate(frame, (velocity[0] - frame_velocity[0], velocity[1] - frame_velocity[1],
                            velocity[2] - frame_velocity[2]))
