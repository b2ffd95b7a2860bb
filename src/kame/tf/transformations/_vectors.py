"""Vectors and the 4x4 matrices' small helpers, shared by the other transformation modules.

Algorithms and the order of every floating-point operation follow Christoph Gohlke's
transformations.py (BSD licence, version 20090418) that ROS ships as tf.transformations, so
results are bit-for-bit those of ROS.
"""

from __future__ import annotations

import math
from typing import Any

import numpy

# Tolerance for zero tests, as the ROS module's _EPS.
EPS = float(numpy.finfo(float).eps * 4.0)


def vector_norm(data: Any, axis: int | None = None, out: Any = None) -> Any:
    """Length, i.e. Euclidean norm, of an ndarray along an axis."""
    data = numpy.array(data, dtype=numpy.float64, copy=True)
    if out is None:
        if data.ndim == 1:
            return math.sqrt(numpy.dot(data, data))
        data *= data
        out = numpy.atleast_1d(numpy.sum(data, axis=axis))
        numpy.sqrt(out, out)
        return out
    data *= data
    numpy.sum(data, axis=axis, out=out)
    numpy.sqrt(out, out)
    return None


def unit_vector(data: Any, axis: int | None = None, out: Any = None) -> Any:
    """The ndarray normalized by length, i.e. Euclidean norm, along an axis."""
    if out is None:
        data = numpy.array(data, dtype=numpy.float64, copy=True)
        if data.ndim == 1:
            data /= math.sqrt(numpy.dot(data, data))
            return data
    else:
        if out is not data:
            out[:] = numpy.asarray(data)
        data = out
    length = numpy.atleast_1d(numpy.sum(data * data, axis))
    numpy.sqrt(length, length)
    if axis is not None:
        length = numpy.expand_dims(length, axis)
    data /= length
    if out is None:
        return data
    return None


def random_vector(size: Any) -> Any:
    """Array of random doubles in the half-open interval [0.0, 1.0)."""
    return numpy.random.random(size)


def inverse_matrix(matrix: Any) -> Any:
    return numpy.linalg.inv(matrix)


def concatenate_matrices(*matrices: Any) -> Any:
    """The product of the transformation matrices, left to right."""
    result = numpy.identity(4)
    for matrix in matrices:
        result = numpy.dot(result, matrix)
    return result


def is_same_transform(matrix0: Any, matrix1: Any) -> bool:
    """Whether two matrices perform the same transformation (up to the homogeneous scale)."""
    matrix0 = numpy.array(matrix0, dtype=numpy.float64, copy=True)
    matrix0 /= matrix0[3, 3]
    matrix1 = numpy.array(matrix1, dtype=numpy.float64, copy=True)
    matrix1 /= matrix1[3, 3]
    return bool(numpy.allclose(matrix0, matrix1))


def eigenvector(values: Any, vectors: Any, target: float, what: str, last: bool = True) -> Any:
    """The real eigenvector whose eigenvalue is `target` (the last such, or the first)."""
    found = numpy.where(abs(numpy.real(values) - target) < 1e-8)[0]
    if not len(found):
        raise ValueError(f"no {what}eigenvector corresponding to eigenvalue {target:g}")
    return numpy.real(vectors[:, found[-1] if last else found[0]]).squeeze()
