"""tf_conversions.posemath: PyKDL frames to and from tf tuples, geometry_msgs/Pose, 4x4 numpy
matrices and OpenCV's camera extrinsics, with upstream's names and results.

PyKDL's names come along (`pm.Frame`, `pm.Rotation`, `pm.Vector`), as upstream's
`from PyKDL import *` brings them, and so do `transformations` and geometry_msgs' Pose, Point
and Quaternion. The frames are whichever PyKDL the program imports, so they mix with the
program's own."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol, SupportsFloat

import numpy
import numpy.typing

from geometry_msgs.msg import Point, Pose, Quaternion
from kame.tf import transformations
from PyKDL import Equal, Frame, Rotation, Vector, dot

__all__ = ["Equal", "Frame", "Point", "Pose", "Quaternion", "Rotation", "Vector", "dot", "fromCameraParams",
           "fromMatrix", "fromMsg", "fromTf", "toMatrix", "toMsg", "toTf", "transformations"]


class _Rodrigues(Protocol):
    def Rodrigues(self, src: Any, /) -> Sequence[Any]: ...


def fromTf(tf: tuple[Sequence[SupportsFloat], Sequence[SupportsFloat]]) -> Frame:
    """A frame from tf's (translation, quaternion x y z w), as lookupTransform returns it."""
    position, quaternion = tf
    x, y, z = position
    qx, qy, qz, qw = quaternion
    return Frame(Rotation.Quaternion(float(qx), float(qy), float(qz), float(qw)), Vector(x, y, z))


def toTf(f: Frame) -> tuple[tuple[float, float, float], tuple[float, float, float, float]]:
    return (f.p[0], f.p[1], f.p[2]), f.M.GetQuaternion()


def fromMsg(p: Any) -> Frame:
    """A frame from a geometry_msgs/Pose (any object with its fields)."""
    o = p.orientation
    return Frame(Rotation.Quaternion(o.x, o.y, o.z, o.w), Vector(p.position.x, p.position.y, p.position.z))


def toMsg(f: Frame) -> Pose:
    p = Pose()
    p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w = f.M.GetQuaternion()
    p.position.x = f.p[0]
    p.position.y = f.p[1]
    p.position.z = f.p[2]
    return p


def fromMatrix(m: Any) -> Frame:
    """A frame from a 4x4 homogeneous matrix (anything indexed m[i, j]: numpy arrays and matrices)."""
    return Frame(Rotation(m[0, 0], m[0, 1], m[0, 2],
                          m[1, 0], m[1, 1], m[1, 2],
                          m[2, 0], m[2, 1], m[2, 2]),
                 Vector(m[0, 3], m[1, 3], m[2, 3]))


def toMatrix(f: Frame) -> numpy.typing.NDArray[numpy.float64]:
    return numpy.array([[f.M[0, 0], f.M[0, 1], f.M[0, 2], f.p[0]],
                        [f.M[1, 0], f.M[1, 1], f.M[1, 2], f.p[1]],
                        [f.M[2, 0], f.M[2, 1], f.M[2, 2], f.p[2]],
                        [0, 0, 0, 1]])


def fromCameraParams(cv: _Rodrigues, rvec: Any, tvec: Any) -> Frame:
    """A frame from solvePnP's (or calibrateCamera's) rotation vector and translation, 3x1 each.

    `cv` is the cv2 module. Upstream calls the old `cv` module's Rodrigues2, which Python 3 never
    had; cv2.Rodrigues is the same conversion. Upstream also rounds the matrix to float32: here it
    stays float64."""
    m = numpy.identity(4)
    m[:3, :3] = cv.Rodrigues(numpy.asarray(rvec, dtype=numpy.float64).reshape(3, 1))[0]
    m[:3, 3] = numpy.asarray(tvec, dtype=numpy.float64).reshape(3)
    return fromMatrix(m)
