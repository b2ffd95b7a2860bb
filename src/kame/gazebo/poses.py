"""Rigid poses as the simulator's API gives them: a position and a unit quaternion (x, y, z, w),
as ROS's geometry_msgs/Pose orders it. MuJoCo orders quaternions (w, x, y, z): `mj_quat` and
`from_mj` are the only crossings. `pose_of` reads an SDF element's <pose> (x y z roll pitch yaw),
which SDF and the <gazebo> tags of URDF share.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from kame.gazebo.errors import GazeboError
from kame.gazebo.xmltree import Element, parse_vector

Vector3 = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]  # x, y, z, w


@dataclass(frozen=True)
class Pose:
    position: Vector3 = (0.0, 0.0, 0.0)
    orientation: Quaternion = (0.0, 0.0, 0.0, 1.0)

    @staticmethod
    def from_xyz_rpy(x: float, y: float, z: float, roll: float, pitch: float, yaw: float) -> Pose:
        """SDF's and URDF's fixed-axis roll, pitch, yaw (about x, then y, then z of the parent)."""
        cr, sr = math.cos(roll / 2), math.sin(roll / 2)
        cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
        cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
        return Pose((x, y, z), (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
                                cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy))

    @staticmethod
    def from_mj(position: np.ndarray, quaternion_wxyz: np.ndarray) -> Pose:
        w, x, y, z = (float(v) for v in quaternion_wxyz)
        return Pose((float(position[0]), float(position[1]), float(position[2])), (x, y, z, w))

    def mj_quat(self) -> np.ndarray:
        x, y, z, w = self.orientation
        return np.array((w, x, y, z))

    def rotation(self) -> np.ndarray:
        """The 3x3 rotation matrix."""
        x, y, z, w = self.orientation
        return np.array((
            (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
            (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
            (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
        ))

    def rpy(self) -> Vector3:
        x, y, z, w = self.orientation
        roll = math.atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (w * y - z * x))))
        yaw = math.atan2(2 * (w * z + x * y), 1 - 2 * (y * y + z * z))
        return roll, pitch, yaw

    def __mul__(self, other: Pose) -> Pose:
        """This pose composed with `other` (other expressed in this pose's frame)."""
        x1, y1, z1, w1 = self.orientation
        x2, y2, z2, w2 = other.orientation
        quaternion = (w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                      w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2)
        return Pose(self.apply(other.position), _normalized(quaternion))

    def inverse(self) -> Pose:
        x, y, z, w = self.orientation
        back = Pose((0.0, 0.0, 0.0), (-x, -y, -z, w))
        px, py, pz = back.apply(self.position)
        return Pose((-px, -py, -pz), back.orientation)

    def apply(self, point: tuple[float, ...] | np.ndarray) -> Vector3:
        p = self.rotation() @ np.asarray(point, dtype=float) + np.asarray(self.position)
        return float(p[0]), float(p[1]), float(p[2])


IDENTITY = Pose()


def _normalized(q: Quaternion) -> Quaternion:
    norm = math.sqrt(sum(v * v for v in q)) or 1.0
    return q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm


def normalized_pose(pose: Pose) -> Pose:
    """`pose` with its quaternion made unit length (a zero quaternion is the identity, as Gazebo takes it)."""
    if not any(pose.orientation):
        return Pose(pose.position)
    return Pose(pose.position, _normalized(pose.orientation))


def pose_of(element: Element) -> tuple[Pose, str]:
    """The element's <pose> and the frame it is relative to ("" when the default applies)."""
    found = element.child("pose")
    if found is None:
        return Pose(), ""
    relative_to = found.attrs.get("relative_to", found.attrs.get("frame", "")).strip()
    text = found.text.strip()
    if not text:
        return Pose(), relative_to
    values = parse_vector(text, 6, found)
    if not all(math.isfinite(v) for v in values):
        raise GazeboError(f"{found.where()}: a pose must be finite, not {text!r}")
    return Pose.from_xyz_rpy(*values), relative_to
