"""What the World answers with: states of models, links and joints, sensors as the ROS side reads
them, and visuals as a 3-D window draws them. Plain values."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from kame.gazebo import description as d
from kame.gazebo.poses import IDENTITY, Pose, Vector3
from kame.gazebo.xmltree import Element


@dataclass(frozen=True)
class State:
    """A model's or link's pose and twist, the twist in the world frame at the frame's origin."""

    pose: Pose = IDENTITY
    linear: Vector3 = (0.0, 0.0, 0.0)
    angular: Vector3 = (0.0, 0.0, 0.0)


@dataclass(frozen=True)
class JointState:
    position: tuple[float, ...]  # one value a degree of freedom; a ball joint's quaternion (w, x, y, z)
    velocity: tuple[float, ...]


@dataclass(frozen=True)
class SensorInfo:
    model: str
    link: str  # "model::link"
    name: str
    type: str
    pose: Pose  # in the link's frame
    update_rate: float
    always_on: bool
    visualize: bool
    config: Element  # the <sensor> element: <ray>, <camera>, <imu>, <noise>... as written


@dataclass(frozen=True)
class VisualShape:
    link: str  # "model::link"
    name: str
    kind: str  # box, cylinder, sphere, plane, mesh
    size: tuple[float, ...]  # as description.Geometry; a mesh's scale is applied to its triangles
    triangles: np.ndarray | None  # a mesh's corners (3 M x 3, float32) in the visual's frame
    pose: Pose  # in the link's frame (a plane lies in this pose's x-y plane)
    color: d.Color
