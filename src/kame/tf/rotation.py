"""Quaternion (x, y, z, w) and vector arithmetic on plain floats, as tf2's LinearMath does it:
a lookup composes a handful of transforms, where numpy's per-call cost would dominate."""

from __future__ import annotations

import math

Vector = tuple[float, float, float]
Quaternion = tuple[float, float, float, float]

IDENTITY: Quaternion = (0.0, 0.0, 0.0, 1.0)
ZERO: Vector = (0.0, 0.0, 0.0)


def multiply(a: Quaternion, b: Quaternion) -> Quaternion:
    """a * b: rotate by b, then by a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by,
            aw * by + ay * bw + az * bx - ax * bz,
            aw * bz + az * bw + ax * by - ay * bx,
            aw * bw - ax * bx - ay * by - az * bz)


def inverse(q: Quaternion) -> Quaternion:
    """The conjugate: the inverse of a unit quaternion."""
    return (-q[0], -q[1], -q[2], q[3])


def rotate(q: Quaternion, v: Vector) -> Vector:
    """v rotated by the unit quaternion q (q v q*)."""
    qx, qy, qz, qw = q
    vx, vy, vz = v
    # t = 2 (q_xyz x v); v' = v + w t + q_xyz x t
    tx = 2.0 * (qy * vz - qz * vy)
    ty = 2.0 * (qz * vx - qx * vz)
    tz = 2.0 * (qx * vy - qy * vx)
    return (vx + qw * tx + qy * tz - qz * ty,
            vy + qw * ty + qz * tx - qx * tz,
            vz + qw * tz + qx * ty - qy * tx)


def add(a: Vector, b: Vector) -> Vector:
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def negate(v: Vector) -> Vector:
    return (-v[0], -v[1], -v[2])


def lerp(a: Vector, b: Vector, ratio: float) -> Vector:
    return (a[0] + (b[0] - a[0]) * ratio, a[1] + (b[1] - a[1]) * ratio, a[2] + (b[2] - a[2]) * ratio)


def slerp(a: Quaternion, b: Quaternion, t: float) -> Quaternion:
    """tf2::slerp: the short way round; nearly equal quaternions give a."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    magnitude = math.sqrt((ax * ax + ay * ay + az * az + aw * aw) * (bx * bx + by * by + bz * bz + bw * bw))
    product = (ax * bx + ay * by + az * bz + aw * bw) / magnitude
    if abs(product) >= 1.0:
        return a
    sign = -1.0 if product < 0 else 1.0
    theta = math.acos(sign * product)
    s1 = math.sin(sign * t * theta)
    d = 1.0 / math.sin(theta)
    s0 = math.sin((1.0 - t) * theta)
    return ((ax * s0 + bx * s1) * d, (ay * s0 + by * s1) * d, (az * s0 + bz * s1) * d, (aw * s0 + bw * s1) * d)


def transform_point(q: Quaternion, translation: Vector, v: Vector) -> Vector:
    """q v q* + translation: a point moved by a rigid transform (rotate and add, in one call)."""
    qx, qy, qz, qw = q
    vx, vy, vz = v
    tx = 2.0 * (qy * vz - qz * vy)
    ty = 2.0 * (qz * vx - qx * vz)
    tz = 2.0 * (qx * vy - qy * vx)
    return (vx + qw * tx + qy * tz - qz * ty + translation[0],
            vy + qw * ty + qz * tx - qx * tz + translation[1],
            vz + qw * tz + qx * ty - qy * tx + translation[2])


def chain(q: Quaternion, translation: Vector, inner_q: Quaternion, inner_t: Vector) -> tuple[Vector, Quaternion]:
    """(q, translation) applied after (inner_q, inner_t): transform_point and multiply fused into
    one call, the same arithmetic in the same order (a lookup does this once per link)."""
    qx, qy, qz, qw = q
    vx, vy, vz = inner_t
    tx = 2.0 * (qy * vz - qz * vy)
    ty = 2.0 * (qz * vx - qx * vz)
    tz = 2.0 * (qx * vy - qy * vx)
    bx, by, bz, bw = inner_q
    return ((vx + qw * tx + qy * tz - qz * ty + translation[0],
             vy + qw * ty + qz * tx - qx * tz + translation[1],
             vz + qw * tz + qx * ty - qy * tx + translation[2]),
            (qw * bx + qx * bw + qy * bz - qz * by,
             qw * by + qy * bw + qz * bx - qx * bz,
             qw * bz + qz * bw + qx * by - qy * bx,
             qw * bw - qx * bx - qy * by - qz * bz))


def norm_squared(q: Quaternion) -> float:
    return q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]


Matrix = tuple[tuple[float, float, float], tuple[float, float, float], tuple[float, float, float]]


def to_matrix(q: Quaternion) -> Matrix:
    """The 3x3 rotation matrix (tf2's Matrix3x3::setRotation)."""
    x, y, z, w = q
    s = 2.0 / norm_squared(q)
    xs, ys, zs = x * s, y * s, z * s
    wx, wy, wz = w * xs, w * ys, w * zs
    xx, xy, xz = x * xs, x * ys, x * zs
    yy, yz, zz = y * ys, y * zs, z * zs
    return ((1.0 - (yy + zz), xy - wz, xz + wy),
            (xy + wz, 1.0 - (xx + zz), yz - wx),
            (xz - wy, yz + wx, 1.0 - (xx + yy)))


def from_matrix(m: Matrix) -> Quaternion:
    """The quaternion of a rotation matrix (tf2's Matrix3x3::getRotation, signs included)."""
    trace = m[0][0] + m[1][1] + m[2][2]
    out = [0.0, 0.0, 0.0, 0.0]
    if trace > 0.0:
        s = math.sqrt(trace + 1.0)
        out[3] = s * 0.5
        s = 0.5 / s
        out[0] = (m[2][1] - m[1][2]) * s
        out[1] = (m[0][2] - m[2][0]) * s
        out[2] = (m[1][0] - m[0][1]) * s
    else:
        if m[0][0] < m[1][1]:
            i = 2 if m[1][1] < m[2][2] else 1
        else:
            i = 2 if m[0][0] < m[2][2] else 0
        j, k = (i + 1) % 3, (i + 2) % 3
        s = math.sqrt(m[i][i] - m[j][j] - m[k][k] + 1.0)
        out[i] = s * 0.5
        s = 0.5 / s
        out[3] = (m[k][j] - m[j][k]) * s
        out[j] = (m[j][i] + m[i][j]) * s
        out[k] = (m[k][i] + m[i][k]) * s
    return (out[0], out[1], out[2], out[3])


def matrix_product(a: Matrix, b: Matrix) -> Matrix:
    rows = tuple(tuple(sum(a[r][n] * b[n][c] for n in range(3)) for c in range(3)) for r in range(3))
    return rows  # type: ignore[return-value]
