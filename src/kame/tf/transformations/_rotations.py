"""Euler angles (all 24 `axes` conventions) and quaternions [x, y, z, w].

Bit-for-bit the arithmetic of ROS's tf.transformations (Gohlke's transformations.py).
"""

from __future__ import annotations

import math
from typing import Any

import numpy

from ._vectors import EPS, unit_vector, vector_norm

# Axis sequences for Euler angles: the axis after each one.
_NEXT_AXIS = [1, 2, 0, 1]

# 'sxyz' -> (inner axis, parity, repetition, frame)
AXES2TUPLE: dict[str, tuple[int, int, int, int]] = {
    "sxyz": (0, 0, 0, 0), "sxyx": (0, 0, 1, 0), "sxzy": (0, 1, 0, 0), "sxzx": (0, 1, 1, 0),
    "syzx": (1, 0, 0, 0), "syzy": (1, 0, 1, 0), "syxz": (1, 1, 0, 0), "syxy": (1, 1, 1, 0),
    "szxy": (2, 0, 0, 0), "szxz": (2, 0, 1, 0), "szyx": (2, 1, 0, 0), "szyz": (2, 1, 1, 0),
    "rzyx": (0, 0, 0, 1), "rxyx": (0, 0, 1, 1), "ryzx": (0, 1, 0, 1), "rxzx": (0, 1, 1, 1),
    "rxzy": (1, 0, 0, 1), "ryzy": (1, 0, 1, 1), "rzxy": (1, 1, 0, 1), "ryxy": (1, 1, 1, 1),
    "ryxz": (2, 0, 0, 1), "rzxz": (2, 0, 1, 1), "rxyz": (2, 1, 0, 1), "rzyz": (2, 1, 1, 1)}
TUPLE2AXES = {value: key for key, value in AXES2TUPLE.items()}


def _axes_tuple(axes: Any, lower: bool = True) -> tuple[int, int, int, int]:
    """The 4-tuple of an `axes` string or tuple; KeyError for neither (as ROS raises)."""
    try:
        return AXES2TUPLE[axes.lower() if lower else axes]
    except (AttributeError, KeyError):
        TUPLE2AXES[axes]  # the KeyError for an unknown tuple is the API
        first, parity, repetition, frame = axes
        return first, parity, repetition, frame


def euler_matrix(ai: float, aj: float, ak: float, axes: Any = "sxyz") -> Any:
    """The homogeneous rotation matrix of Euler angles and axis sequence."""
    first, parity, repetition, frame = _axes_tuple(axes, lower=False)
    i = first
    j = _NEXT_AXIS[i + parity]
    k = _NEXT_AXIS[i - parity + 1]
    if frame:
        ai, ak = ak, ai
    if parity:
        ai, aj, ak = -ai, -aj, -ak
    si, sj, sk = math.sin(ai), math.sin(aj), math.sin(ak)
    ci, cj, ck = math.cos(ai), math.cos(aj), math.cos(ak)
    cc, cs = ci * ck, ci * sk
    sc, ss = si * ck, si * sk
    m = numpy.identity(4)
    if repetition:
        m[i, i] = cj
        m[i, j] = sj * si
        m[i, k] = sj * ci
        m[j, i] = sj * sk
        m[j, j] = -cj * ss + cc
        m[j, k] = -cj * cs - sc
        m[k, i] = -sj * ck
        m[k, j] = cj * sc + cs
        m[k, k] = cj * cc - ss
    else:
        m[i, i] = cj * ck
        m[i, j] = sj * sc - cs
        m[i, k] = sj * cc + ss
        m[j, i] = cj * sk
        m[j, j] = sj * ss + cc
        m[j, k] = sj * cs - sc
        m[k, i] = -sj
        m[k, j] = cj * si
        m[k, k] = cj * ci
    return m


def euler_from_matrix(matrix: Any, axes: Any = "sxyz") -> tuple[float, float, float]:
    """Euler angles of a rotation matrix for the axis sequence (one of two solutions)."""
    first, parity, repetition, frame = _axes_tuple(axes)
    i = first
    j = _NEXT_AXIS[i + parity]
    k = _NEXT_AXIS[i - parity + 1]
    m = numpy.asarray(matrix, dtype=numpy.float64)[:3, :3]
    if repetition:
        sy = math.sqrt(m[i, j] * m[i, j] + m[i, k] * m[i, k])
        if sy > EPS:
            ax = math.atan2(m[i, j], m[i, k])
            ay = math.atan2(sy, m[i, i])
            az = math.atan2(m[j, i], -m[k, i])
        else:
            ax = math.atan2(-m[j, k], m[j, j])
            ay = math.atan2(sy, m[i, i])
            az = 0.0
    else:
        cy = math.sqrt(m[i, i] * m[i, i] + m[j, i] * m[j, i])
        if cy > EPS:
            ax = math.atan2(m[k, j], m[k, k])
            ay = math.atan2(-m[k, i], cy)
            az = math.atan2(m[j, i], m[i, i])
        else:
            ax = math.atan2(-m[j, k], m[j, j])
            ay = math.atan2(-m[k, i], cy)
            az = 0.0
    if parity:
        ax, ay, az = -ax, -ay, -az
    if frame:
        ax, az = az, ax
    return ax, ay, az


def euler_from_quaternion(quaternion: Any, axes: Any = "sxyz") -> tuple[float, float, float]:
    return euler_from_matrix(quaternion_matrix(quaternion), axes)


def quaternion_from_euler(ai: float, aj: float, ak: float, axes: Any = "sxyz") -> Any:
    """The quaternion [x, y, z, w] of Euler angles and axis sequence."""
    first, parity, repetition, frame = _axes_tuple(axes)
    i = first
    j = _NEXT_AXIS[i + parity]
    k = _NEXT_AXIS[i - parity + 1]
    if frame:
        ai, ak = ak, ai
    if parity:
        aj = -aj
    ai /= 2.0
    aj /= 2.0
    ak /= 2.0
    ci = math.cos(ai)
    si = math.sin(ai)
    cj = math.cos(aj)
    sj = math.sin(aj)
    ck = math.cos(ak)
    sk = math.sin(ak)
    cc = ci * ck
    cs = ci * sk
    sc = si * ck
    ss = si * sk
    q = numpy.empty((4,), dtype=numpy.float64)
    if repetition:
        q[i] = cj * (cs + sc)
        q[j] = sj * (cc + ss)
        q[k] = sj * (cs - sc)
        q[3] = cj * (cc - ss)
    else:
        q[i] = cj * sc - sj * cs
        q[j] = cj * ss + sj * cc
        q[k] = cj * cs - sj * sc
        q[3] = cj * cc + sj * ss
    if parity:
        q[j] *= -1
    return q


def quaternion_about_axis(angle: float, axis: Any) -> Any:
    q = numpy.zeros((4,), dtype=numpy.float64)
    q[:3] = axis[:3]
    qlen = vector_norm(q)
    if qlen > EPS:
        q *= math.sin(angle / 2.0) / qlen
    q[3] = math.cos(angle / 2.0)
    return q


def quaternion_matrix(quaternion: Any) -> Any:
    """The homogeneous rotation matrix of a quaternion (of any length; near-zero is identity)."""
    q = numpy.array(quaternion[:4], dtype=numpy.float64, copy=True)
    nq = numpy.dot(q, q)
    if nq < EPS:
        return numpy.identity(4)
    q *= math.sqrt(2.0 / nq)
    q = numpy.outer(q, q)
    return numpy.array(((1.0 - q[1, 1] - q[2, 2], q[0, 1] - q[2, 3], q[0, 2] + q[1, 3], 0.0),
                        (q[0, 1] + q[2, 3], 1.0 - q[0, 0] - q[2, 2], q[1, 2] - q[0, 3], 0.0),
                        (q[0, 2] - q[1, 3], q[1, 2] + q[0, 3], 1.0 - q[0, 0] - q[1, 1], 0.0),
                        (0.0, 0.0, 0.0, 1.0)), dtype=numpy.float64)


def quaternion_from_matrix(matrix: Any) -> Any:
    q = numpy.empty((4,), dtype=numpy.float64)
    m = numpy.asarray(matrix, dtype=numpy.float64)[:4, :4]
    t = numpy.trace(m)
    if t > m[3, 3]:
        q[3] = t
        q[2] = m[1, 0] - m[0, 1]
        q[1] = m[0, 2] - m[2, 0]
        q[0] = m[2, 1] - m[1, 2]
    else:
        i, j, k = 0, 1, 2
        if m[1, 1] > m[0, 0]:
            i, j, k = 1, 2, 0
        if m[2, 2] > m[i, i]:
            i, j, k = 2, 0, 1
        t = m[i, i] - (m[j, j] + m[k, k]) + m[3, 3]
        q[i] = t
        q[j] = m[i, j] + m[j, i]
        q[k] = m[k, i] + m[i, k]
        q[3] = m[k, j] - m[j, k]
    q *= 0.5 / math.sqrt(t * m[3, 3])
    return q


def quaternion_multiply(quaternion1: Any, quaternion0: Any) -> Any:
    """quaternion1 * quaternion0 (apply quaternion0 first)."""
    x0, y0, z0, w0 = quaternion0
    x1, y1, z1, w1 = quaternion1
    return numpy.array((x1 * w0 + y1 * z0 - z1 * y0 + w1 * x0,
                        -x1 * z0 + y1 * w0 + z1 * x0 + w1 * y0,
                        x1 * y0 - y1 * x0 + z1 * w0 + w1 * z0,
                        -x1 * x0 - y1 * y0 - z1 * z0 + w1 * w0), dtype=numpy.float64)


def quaternion_conjugate(quaternion: Any) -> Any:
    return numpy.array((-quaternion[0], -quaternion[1], -quaternion[2], quaternion[3]), dtype=numpy.float64)


def quaternion_inverse(quaternion: Any) -> Any:
    return quaternion_conjugate(quaternion) / numpy.dot(quaternion, quaternion)


def quaternion_slerp(quat0: Any, quat1: Any, fraction: float, spin: int = 0, shortestpath: bool = True) -> Any:
    """Spherical linear interpolation between two quaternions."""
    q0 = unit_vector(quat0[:4])
    q1 = unit_vector(quat1[:4])
    if fraction == 0.0:
        return q0
    if fraction == 1.0:
        return q1
    d = numpy.dot(q0, q1)
    if abs(abs(d) - 1.0) < EPS:
        return q0
    if shortestpath and d < 0.0:
        d = -d
        q1 *= -1.0
    angle = math.acos(d) + spin * math.pi
    if abs(angle) < EPS:
        return q0
    isin = 1.0 / math.sin(angle)
    q0 *= math.sin((1.0 - fraction) * angle) * isin
    q1 *= math.sin(fraction * angle) * isin
    q0 += q1
    return q0


def random_quaternion(rand: Any = None) -> Any:
    """A uniform random unit quaternion; `rand` is three values in [0, 1) if given."""
    if rand is None:
        rand = numpy.random.rand(3)
    elif len(rand) != 3:
        raise ValueError("rand must hold three values")
    r1 = numpy.sqrt(1.0 - rand[0])
    r2 = numpy.sqrt(rand[0])
    pi2 = math.pi * 2.0
    t1 = pi2 * rand[1]
    t2 = pi2 * rand[2]
    return numpy.array((numpy.sin(t1) * r1, numpy.cos(t1) * r1, numpy.sin(t2) * r2, numpy.cos(t2) * r2),
                       dtype=numpy.float64)


def random_rotation_matrix(rand: Any = None) -> Any:
    return quaternion_matrix(random_quaternion(rand))
