"""tf.transformations: homogeneous 4x4 matrices, Euler angles and quaternions [x, y, z, w],
numerically identical to the module ROS ships (Christoph Gohlke's transformations.py, BSD).

Matrices act on column vectors (numpy.dot(M, v)); angles are in radians; an `axes` argument
is one of the 24 strings 'sxyz' ... 'rzyz' ('s'tatic or 'r'otating frame, then the axis
sequence) or its 4-tuple (inner axis, parity, repetition, frame).
"""

from __future__ import annotations

from ._arcball import Arcball, arcball_constrain_to_axis, arcball_map_to_sphere, arcball_nearest_axis
from ._matrices import (
    clip_matrix,
    compose_matrix,
    decompose_matrix,
    identity_matrix,
    orthogonalization_matrix,
    projection_from_matrix,
    projection_matrix,
    reflection_from_matrix,
    reflection_matrix,
    rotation_from_matrix,
    rotation_matrix,
    scale_from_matrix,
    scale_matrix,
    shear_from_matrix,
    shear_matrix,
    superimposition_matrix,
    translation_from_matrix,
    translation_matrix,
)
from ._rotations import (
    AXES2TUPLE as _AXES2TUPLE,
)
from ._rotations import (
    TUPLE2AXES as _TUPLE2AXES,
)
from ._rotations import (
    euler_from_matrix,
    euler_from_quaternion,
    euler_matrix,
    quaternion_about_axis,
    quaternion_conjugate,
    quaternion_from_euler,
    quaternion_from_matrix,
    quaternion_inverse,
    quaternion_matrix,
    quaternion_multiply,
    quaternion_slerp,
    random_quaternion,
    random_rotation_matrix,
)
from ._vectors import (
    EPS as _EPS,
)
from ._vectors import (
    concatenate_matrices,
    inverse_matrix,
    is_same_transform,
    random_vector,
    unit_vector,
    vector_norm,
)

_NEXT_AXIS = [1, 2, 0, 1]

__all__ = [
    "_AXES2TUPLE", "_EPS", "_NEXT_AXIS", "_TUPLE2AXES",
    "Arcball", "arcball_constrain_to_axis", "arcball_map_to_sphere", "arcball_nearest_axis",
    "clip_matrix", "compose_matrix", "concatenate_matrices", "decompose_matrix", "euler_from_matrix",
    "euler_from_quaternion", "euler_matrix", "identity_matrix", "inverse_matrix", "is_same_transform",
    "orthogonalization_matrix", "projection_from_matrix", "projection_matrix", "quaternion_about_axis",
    "quaternion_conjugate", "quaternion_from_euler", "quaternion_from_matrix", "quaternion_inverse",
    "quaternion_matrix", "quaternion_multiply", "quaternion_slerp", "random_quaternion",
    "random_rotation_matrix", "random_vector", "reflection_from_matrix", "reflection_matrix",
    "rotation_from_matrix", "rotation_matrix", "scale_from_matrix", "scale_matrix", "shear_from_matrix",
    "shear_matrix", "superimposition_matrix", "translation_from_matrix", "translation_matrix",
    "unit_vector", "vector_norm",
]
