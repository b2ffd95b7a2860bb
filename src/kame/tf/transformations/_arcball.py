"""Shoemake's virtual trackball, as ROS's tf.transformations.Arcball."""

from __future__ import annotations

import math
from typing import Any

import numpy

from ._rotations import quaternion_from_matrix, quaternion_matrix, quaternion_multiply, quaternion_slerp
from ._vectors import EPS, unit_vector, vector_norm


class Arcball:
    def __init__(self, initial: Any = None) -> None:
        """`initial` is a quaternion or a rotation matrix."""
        self._axis: Any = None
        self._axes: Any = None
        self._radius = 1.0
        self._center = [0.0, 0.0]
        self._vdown = numpy.array([0, 0, 1], dtype=numpy.float64)
        self._constrain = False
        if initial is None:
            self._qdown = numpy.array([0, 0, 0, 1], dtype=numpy.float64)
        else:
            initial = numpy.array(initial, dtype=numpy.float64)
            if initial.shape == (4, 4):
                self._qdown = quaternion_from_matrix(initial)
            elif initial.shape == (4,):
                initial /= vector_norm(initial)
                self._qdown = initial
            else:
                raise ValueError("initial not a quaternion or matrix.")
        self._qnow = self._qpre = self._qdown

    def place(self, center: Any, radius: float) -> None:
        """Place the arcball, e.g. when the window size changes."""
        self._radius = float(radius)
        self._center[0] = center[0]
        self._center[1] = center[1]

    def setaxes(self, *axes: Any) -> None:
        """Axes to constrain rotations to."""
        self._axes = [unit_vector(axis) for axis in axes] if axes is not None else None

    def setconstrain(self, constrain: Any) -> None:
        self._constrain = constrain == True  # noqa: E712 -- ROS compares, so numpy bools count

    def getconstrain(self) -> bool:
        return self._constrain

    def down(self, point: Any) -> None:
        """Set the initial cursor window coordinates and pick the constrain axis."""
        self._vdown = arcball_map_to_sphere(point, self._center, self._radius)
        self._qdown = self._qpre = self._qnow
        if self._constrain and self._axes is not None:
            self._axis = arcball_nearest_axis(self._vdown, self._axes)
            self._vdown = arcball_constrain_to_axis(self._vdown, self._axis)
        else:
            self._axis = None

    def drag(self, point: Any) -> None:
        """Update the current cursor window coordinates."""
        vnow = arcball_map_to_sphere(point, self._center, self._radius)
        if self._axis is not None:
            vnow = arcball_constrain_to_axis(vnow, self._axis)
        self._qpre = self._qnow
        t = numpy.cross(self._vdown, vnow)
        if numpy.dot(t, t) < EPS:
            self._qnow = self._qdown
        else:
            q = [t[0], t[1], t[2], numpy.dot(self._vdown, vnow)]
            self._qnow = quaternion_multiply(q, self._qdown)

    def next(self, acceleration: float = 0.0) -> None:
        """Continue rotation in the direction of the last drag."""
        q = quaternion_slerp(self._qpre, self._qnow, 2.0 + acceleration, False)
        self._qpre, self._qnow = self._qnow, q

    def matrix(self) -> Any:
        return quaternion_matrix(self._qnow)


def arcball_map_to_sphere(point: Any, center: Any, radius: float) -> Any:
    v = numpy.array(((point[0] - center[0]) / radius, (center[1] - point[1]) / radius, 0.0), dtype=numpy.float64)
    n = v[0] * v[0] + v[1] * v[1]
    if n > 1.0:
        v /= math.sqrt(n)
    else:
        v[2] = math.sqrt(1.0 - n)
    return v


def arcball_constrain_to_axis(point: Any, axis: Any) -> Any:
    """The sphere point perpendicular to the axis."""
    v = numpy.array(point, dtype=numpy.float64, copy=True)
    a = numpy.array(axis, dtype=numpy.float64, copy=True)
    v -= a * numpy.dot(a, v)
    n = vector_norm(v)
    if n > EPS:
        if v[2] < 0.0:
            v *= -1.0
        v /= n
        return v
    if a[2] == 1.0:
        return numpy.array([1, 0, 0], dtype=numpy.float64)
    return unit_vector([-a[1], a[0], 0])


def arcball_nearest_axis(point: Any, axes: Any) -> Any:
    point = numpy.asarray(point, dtype=numpy.float64)
    nearest = None
    best = -1.0
    for axis in axes:
        t = numpy.dot(arcball_constrain_to_axis(point, axis), point)
        if t > best:
            nearest = axis
            best = t
    return nearest
