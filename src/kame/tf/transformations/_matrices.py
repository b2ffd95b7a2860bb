"""4x4 homogeneous matrices: translation, reflection, rotation, scale, projection, clipping,
shear, their decomposition and composition, orthogonalization and superimposition.

Bit-for-bit the arithmetic of ROS's tf.transformations (Gohlke's transformations.py).
"""

from __future__ import annotations

import math
from typing import Any

import numpy

from ._rotations import euler_matrix, quaternion_matrix
from ._vectors import EPS, eigenvector, unit_vector, vector_norm


def identity_matrix() -> Any:
    return numpy.identity(4, dtype=numpy.float64)


def translation_matrix(direction: Any) -> Any:
    matrix = numpy.identity(4)
    matrix[:3, 3] = direction[:3]
    return matrix


def translation_from_matrix(matrix: Any) -> Any:
    return numpy.asarray(matrix)[:3, 3].copy()


def reflection_matrix(point: Any, normal: Any) -> Any:
    """Mirror at the plane through `point` with `normal`."""
    normal = unit_vector(normal[:3])
    matrix = numpy.identity(4)
    matrix[:3, :3] -= 2.0 * numpy.outer(normal, normal)
    matrix[:3, 3] = 2.0 * numpy.dot(point[:3], normal) * normal
    return matrix


def reflection_from_matrix(matrix: Any) -> tuple[Any, Any]:
    """The mirror plane's point and normal."""
    m = numpy.asarray(matrix, dtype=numpy.float64)
    values, vectors = numpy.linalg.eig(m[:3, :3])
    normal = eigenvector(values, vectors, -1.0, "unit ", last=False)
    values, vectors = numpy.linalg.eig(m)
    point = eigenvector(values, vectors, 1.0, "unit ")
    point /= point[3]
    return point, normal


def rotation_matrix(angle: float, direction: Any, point: Any = None) -> Any:
    """Rotation by `angle` about the axis through `point` along `direction`."""
    sina = math.sin(angle)
    cosa = math.cos(angle)
    direction = unit_vector(direction[:3])
    rot = numpy.array(((cosa, 0.0, 0.0), (0.0, cosa, 0.0), (0.0, 0.0, cosa)), dtype=numpy.float64)
    rot += numpy.outer(direction, direction) * (1.0 - cosa)
    direction *= sina
    rot += numpy.array(((0.0, -direction[2], direction[1]),
                        (direction[2], 0.0, -direction[0]),
                        (-direction[1], direction[0], 0.0)), dtype=numpy.float64)
    matrix = numpy.identity(4)
    matrix[:3, :3] = rot
    if point is not None:
        point = numpy.asarray(point[:3], dtype=numpy.float64)
        matrix[:3, 3] = point - numpy.dot(rot, point)
    return matrix


def rotation_from_matrix(matrix: Any) -> tuple[float, Any, Any]:
    """The rotation's angle, axis direction and a point on the axis."""
    rot = numpy.asarray(matrix, dtype=numpy.float64)
    rot33 = rot[:3, :3]
    values, vectors = numpy.linalg.eig(rot33.T)
    direction = eigenvector(values, vectors, 1.0, "unit ")
    values, vectors = numpy.linalg.eig(rot)
    point = eigenvector(values, vectors, 1.0, "unit ")
    point /= point[3]
    cosa = (numpy.trace(rot33) - 1.0) / 2.0
    if abs(direction[2]) > 1e-8:
        sina = (rot[1, 0] + (cosa - 1.0) * direction[0] * direction[1]) / direction[2]
    elif abs(direction[1]) > 1e-8:
        sina = (rot[0, 2] + (cosa - 1.0) * direction[0] * direction[2]) / direction[1]
    else:
        sina = (rot[2, 1] + (cosa - 1.0) * direction[1] * direction[2]) / direction[0]
    return math.atan2(sina, cosa), direction, point


def scale_matrix(factor: float, origin: Any = None, direction: Any = None) -> Any:
    """Scale by `factor` around `origin`, uniformly or along `direction`."""
    if direction is None:
        matrix = numpy.array(((factor, 0.0, 0.0, 0.0), (0.0, factor, 0.0, 0.0),
                              (0.0, 0.0, factor, 0.0), (0.0, 0.0, 0.0, 1.0)), dtype=numpy.float64)
        if origin is not None:
            matrix[:3, 3] = origin[:3]
            matrix[:3, 3] *= 1.0 - factor
    else:
        direction = unit_vector(direction[:3])
        factor = 1.0 - factor
        matrix = numpy.identity(4)
        matrix[:3, :3] -= factor * numpy.outer(direction, direction)
        if origin is not None:
            matrix[:3, 3] = factor * numpy.dot(origin[:3], direction) * direction
    return matrix


def scale_from_matrix(matrix: Any) -> tuple[float, Any, Any]:
    """The scaling factor, origin and direction (None when uniform)."""
    m = numpy.asarray(matrix, dtype=numpy.float64)
    m33 = m[:3, :3]
    factor = numpy.trace(m33) - 2.0
    direction: Any
    try:
        values, vectors = numpy.linalg.eig(m33)
        index = numpy.where(abs(numpy.real(values) - factor) < 1e-8)[0][0]
        direction = numpy.real(vectors[:, index]).squeeze()
        direction /= vector_norm(direction)
    except IndexError:
        factor = (factor + 2.0) / 3.0
        direction = None
    values, vectors = numpy.linalg.eig(m)
    origin = eigenvector(values, vectors, 1.0, "")
    origin /= origin[3]
    return factor, origin, direction


def projection_matrix(point: Any, normal: Any, direction: Any = None, perspective: Any = None,
                      pseudo: bool = False) -> Any:
    """Projection onto the plane (point, normal): orthogonal, parallel along `direction`, or
    perspective from `perspective` (pseudo-perspective keeps relative depth)."""
    matrix = numpy.identity(4)
    point = numpy.asarray(point[:3], dtype=numpy.float64)
    normal = unit_vector(normal[:3])
    if perspective is not None:
        perspective = numpy.asarray(perspective[:3], dtype=numpy.float64)
        matrix[0, 0] = matrix[1, 1] = matrix[2, 2] = numpy.dot(perspective - point, normal)
        matrix[:3, :3] -= numpy.outer(perspective, normal)
        if pseudo:
            matrix[:3, :3] -= numpy.outer(normal, normal)
            matrix[:3, 3] = numpy.dot(point, normal) * (perspective + normal)
        else:
            matrix[:3, 3] = numpy.dot(point, normal) * perspective
        matrix[3, :3] = -normal
        matrix[3, 3] = numpy.dot(perspective, normal)
    elif direction is not None:
        direction = numpy.asarray(direction[:3], dtype=numpy.float64)
        scale = numpy.dot(direction, normal)
        matrix[:3, :3] -= numpy.outer(direction, normal) / scale
        matrix[:3, 3] = direction * (numpy.dot(point, normal) / scale)
    else:
        matrix[:3, :3] -= numpy.outer(normal, normal)
        matrix[:3, 3] = numpy.dot(point, normal) * normal
    return matrix


def projection_from_matrix(matrix: Any, pseudo: bool = False) -> tuple[Any, Any, Any, Any, bool]:
    """(point, normal, direction, perspective, pseudo) of a projection matrix."""
    m = numpy.asarray(matrix, dtype=numpy.float64)
    m33 = m[:3, :3]
    values, vectors = numpy.linalg.eig(m)
    ones = numpy.where(abs(numpy.real(values) - 1.0) < 1e-8)[0]
    if not pseudo and len(ones):
        point = numpy.real(vectors[:, ones[-1]]).squeeze()
        point /= point[3]
        values, vectors = numpy.linalg.eig(m33)
        direction = eigenvector(values, vectors, 0.0, "", last=False)
        direction /= vector_norm(direction)
        values, vectors = numpy.linalg.eig(m33.T)
        zeros = numpy.where(abs(numpy.real(values)) < 1e-8)[0]
        if len(zeros):
            normal = numpy.real(vectors[:, zeros[0]]).squeeze()
            normal /= vector_norm(normal)
            return point, normal, direction, None, False
        return point, direction, None, None, False
    nonzero = numpy.where(abs(numpy.real(values)) > 1e-8)[0]
    if not len(nonzero):
        raise ValueError("no eigenvector not corresponding to eigenvalue 0")
    point = numpy.real(vectors[:, nonzero[-1]]).squeeze()
    point /= point[3]
    normal = -m[3, :3]
    perspective = m[:3, 3] / numpy.dot(point[:3], normal)
    if pseudo:
        perspective -= normal
    return point, normal, None, perspective, pseudo


def clip_matrix(left: float, right: float, bottom: float, top: float, near: float, far: float,
                perspective: bool = False) -> Any:
    """The matrix mapping the frustum (or box) to the normalized device cube."""
    if left >= right or bottom >= top or near >= far:
        raise ValueError("invalid frustrum")
    if perspective:
        if near <= EPS:
            raise ValueError("invalid frustrum: near <= 0")
        t = 2.0 * near
        rows: Any = ((-t / (right - left), 0.0, (right + left) / (right - left), 0.0),
                     (0.0, -t / (top - bottom), (top + bottom) / (top - bottom), 0.0),
                     (0.0, 0.0, -(far + near) / (far - near), t * far / (far - near)),
                     (0.0, 0.0, -1.0, 0.0))
    else:
        rows = ((2.0 / (right - left), 0.0, 0.0, (right + left) / (left - right)),
                (0.0, 2.0 / (top - bottom), 0.0, (top + bottom) / (bottom - top)),
                (0.0, 0.0, 2.0 / (far - near), (far + near) / (near - far)),
                (0.0, 0.0, 0.0, 1.0))
    return numpy.array(rows, dtype=numpy.float64)


def shear_matrix(angle: float, direction: Any, point: Any, normal: Any) -> Any:
    """Shear by `angle` along `direction` on the plane (point, normal)."""
    normal = unit_vector(normal[:3])
    direction = unit_vector(direction[:3])
    if abs(numpy.dot(normal, direction)) > 1e-6:
        raise ValueError("direction and normal vectors are not orthogonal")
    tangent = math.tan(angle)
    matrix = numpy.identity(4)
    matrix[:3, :3] += tangent * numpy.outer(direction, normal)
    matrix[:3, 3] = -tangent * numpy.dot(point[:3], normal) * direction
    return matrix


def shear_from_matrix(matrix: Any) -> tuple[float, Any, Any, Any]:
    """(angle, direction, point, normal) of a shear matrix."""
    m = numpy.asarray(matrix, dtype=numpy.float64)
    m33 = m[:3, :3]
    values, vectors = numpy.linalg.eig(m33)
    ones = numpy.where(abs(numpy.real(values) - 1.0) < 1e-4)[0]
    if len(ones) < 2:
        raise ValueError(f"No two linear independent eigenvectors found {values}")
    rows = numpy.real(vectors[:, ones]).squeeze().T
    lenorm = -1.0
    normal: Any = None
    for i0, i1 in ((0, 1), (0, 2), (1, 2)):
        cross = numpy.cross(rows[i0], rows[i1])
        length = vector_norm(cross)
        if length > lenorm:
            lenorm = length
            normal = cross
    normal /= lenorm
    direction = numpy.dot(m33 - numpy.identity(3), normal)
    angle = vector_norm(direction)
    direction /= angle
    angle = math.atan(angle)
    values, vectors = numpy.linalg.eig(m)
    point = eigenvector(values, vectors, 1.0, "")
    point /= point[3]
    return angle, direction, point, normal


def decompose_matrix(matrix: Any) -> tuple[Any, Any, Any, Any, Any]:
    """(scale, shear, angles, translate, perspective) of a transformation matrix; raises
    ValueError if it is of the wrong type or degenerate."""
    m = numpy.array(matrix, dtype=numpy.float64, copy=True).T
    if abs(m[3, 3]) < EPS:
        raise ValueError("M[3, 3] is zero")
    m /= m[3, 3]
    p = m.copy()
    p[:, 3] = (0, 0, 0, 1)
    if not numpy.linalg.det(p):
        raise ValueError("Matrix is singular")
    scale = numpy.zeros((3,), dtype=numpy.float64)
    shear: Any = [0, 0, 0]
    angles: Any = [0, 0, 0]
    if any(abs(m[:3, 3]) > EPS):
        perspective = numpy.dot(m[:, 3], numpy.linalg.inv(p.T))
        m[:, 3] = (0, 0, 0, 1)
    else:
        perspective = numpy.array((0, 0, 0, 1), dtype=numpy.float64)
    translate = m[3, :3].copy()
    m[3, :3] = 0
    row = m[:3, :3].copy()
    scale[0] = vector_norm(row[0])
    row[0] /= scale[0]
    shear[0] = numpy.dot(row[0], row[1])
    row[1] -= row[0] * shear[0]
    scale[1] = vector_norm(row[1])
    row[1] /= scale[1]
    shear[0] /= scale[1]
    shear[1] = numpy.dot(row[0], row[2])
    row[2] -= row[0] * shear[1]
    shear[2] = numpy.dot(row[1], row[2])
    row[2] -= row[1] * shear[2]
    scale[2] = vector_norm(row[2])
    row[2] /= scale[2]
    shear[1:] /= scale[2]
    if numpy.dot(row[0], numpy.cross(row[1], row[2])) < 0:
        scale *= -1
        row *= -1
    angles[1] = math.asin(-row[0, 2])
    if math.cos(angles[1]):
        angles[0] = math.atan2(row[1, 2], row[2, 2])
        angles[2] = math.atan2(row[0, 1], row[0, 0])
    else:
        angles[0] = math.atan2(-row[2, 1], row[1, 1])
        angles[2] = 0.0
    return scale, shear, angles, translate, perspective


def compose_matrix(scale: Any = None, shear: Any = None, angles: Any = None, translate: Any = None,
                   perspective: Any = None) -> Any:
    """The matrix from a sequence of transformations (the inverse of decompose_matrix)."""
    matrix = numpy.identity(4)
    if perspective is not None:
        step = numpy.identity(4)
        step[3, :] = perspective[:4]
        matrix = numpy.dot(matrix, step)
    if translate is not None:
        step = numpy.identity(4)
        step[:3, 3] = translate[:3]
        matrix = numpy.dot(matrix, step)
    if angles is not None:
        matrix = numpy.dot(matrix, euler_matrix(angles[0], angles[1], angles[2], "sxyz"))
    if shear is not None:
        step = numpy.identity(4)
        step[1, 2] = shear[2]
        step[0, 2] = shear[1]
        step[0, 1] = shear[0]
        matrix = numpy.dot(matrix, step)
    if scale is not None:
        step = numpy.identity(4)
        step[0, 0] = scale[0]
        step[1, 1] = scale[1]
        step[2, 2] = scale[2]
        matrix = numpy.dot(matrix, step)
    matrix /= matrix[3, 3]
    return matrix


def orthogonalization_matrix(lengths: Any, angles: Any) -> Any:
    """The orthogonalization matrix of crystallographic cell coordinates (angles in degrees)."""
    a, b, c = lengths
    angles = numpy.radians(angles)
    sina, sinb, _ = numpy.sin(angles)
    cosa, cosb, cosg = numpy.cos(angles)
    co = (cosa * cosb - cosg) / (sina * sinb)
    return numpy.array(((a * sinb * math.sqrt(1.0 - co * co), 0.0, 0.0, 0.0),
                        (-a * sinb * co, b * sina, 0.0, 0.0),
                        (a * cosb, b * cosa, c, 0.0),
                        (0.0, 0.0, 0.0, 1.0)), dtype=numpy.float64)


def superimposition_matrix(v0: Any, v1: Any, scaling: bool = False, usesvd: bool = True) -> Any:
    """The matrix that transforms the point set v0 onto v1 (shape (3, n) or (4, n))."""
    v0 = numpy.asarray(v0, dtype=numpy.float64)[:3]
    v1 = numpy.asarray(v1, dtype=numpy.float64)[:3]
    if v0.shape != v1.shape or v0.shape[1] < 3:
        raise ValueError("Vector sets are of wrong shape or type.")
    t0 = numpy.mean(v0, axis=1)
    t1 = numpy.mean(v1, axis=1)
    v0 = v0 - t0.reshape(3, 1)
    v1 = v1 - t1.reshape(3, 1)
    if usesvd:
        u, s, vh = numpy.linalg.svd(numpy.dot(v1, v0.T))
        rot = numpy.dot(u, vh)
        if numpy.linalg.det(rot) < 0.0:
            rot -= numpy.outer(u[:, 2], vh[2, :] * 2.0)
            s[-1] *= -1.0
        matrix = numpy.identity(4)
        matrix[:3, :3] = rot
    else:
        xx, yy, zz = numpy.sum(v0 * v1, axis=1)
        xy, yz, zx = numpy.sum(v0 * numpy.roll(v1, -1, axis=0), axis=1)
        xz, yx, zy = numpy.sum(v0 * numpy.roll(v1, -2, axis=0), axis=1)
        n = ((xx + yy + zz, yz - zy, zx - xz, xy - yx),
             (yz - zy, xx - yy - zz, xy + yx, zx + xz),
             (zx - xz, xy + yx, -xx + yy - zz, yz + zy),
             (xy - yx, zx + xz, yz + zy, -xx - yy + zz))
        values, vectors = numpy.linalg.eig(n)
        q = vectors[:, numpy.argmax(values)]
        q /= vector_norm(q)
        q = numpy.roll(q, -1)
        matrix = quaternion_matrix(q)
    if scaling:
        v0 *= v0
        v1 *= v1
        matrix[:3, :3] *= math.sqrt(numpy.sum(v1) / numpy.sum(v0))
    matrix[:3, 3] = t1
    step = numpy.identity(4)
    step[:3, 3] = -t0
    return numpy.dot(matrix, step)
