"""kame's tf.transformations against Debian's (the module ROS ships), on random inputs.

The whole batch goes to one /usr/bin/python3 process as JSON, and Debian's numpy (1.24) is not
the one pip gives kame (anything from 1.22 to today's 2.x). What both sides compute with Python's
float arithmetic and the math module (EXACT) agrees to the last bit. What goes through numpy's own
kernels (dot, outer, norm, sin/cos over arrays: their summation order and SIMD paths change between
numpy releases) agrees within ULPS units in the last place of the result's scale, its largest
magnitude: measured, at most 11 ulps (quaternion_slerp) between Debian's 1.24.2 and numpy 1.23.2 or
2.4.6. The inverses built on numpy.linalg (eig, svd, inv) agree to 1e-9, compared through the
matrices they rebuild where eigenvectors are not unique.
"""

from __future__ import annotations

import json
import math
import subprocess
import warnings
from pathlib import Path
from typing import Any

import numpy
import pytest

from kame.tf import transformations as tr

from ..support import SYSTEM_PYTHON
from .debian_transformations import arcball_drag

PEER = Path(__file__).with_name("debian_transformations.py")
AXES = sorted(tr._AXES2TUPLE)
# plain float arithmetic on numpy scalars and math's functions on both sides, no numpy kernel
EXACT = {"euler_matrix", "quaternion_from_euler", "euler_from_matrix", "quaternion_multiply", "quaternion_conjugate",
         "translation_matrix", "translation_from_matrix"}
ULPS = 32


def have_debian_tf() -> bool:
    probe = subprocess.run([SYSTEM_PYTHON, "-c", "from tf import transformations"], capture_output=True)
    return probe.returncode == 0


def plain(value: Any) -> Any:
    if isinstance(value, numpy.ndarray):
        return value.tolist()
    if isinstance(value, (tuple, list)):
        return [plain(v) for v in value]
    if isinstance(value, (numpy.floating, numpy.integer, numpy.bool_)):
        return value.item()
    return value


def batch(rng: numpy.random.Generator) -> tuple[list[list[Any]], set[int]]:
    """[(function, args, kwargs)] and the indices compared to a tolerance."""
    calls: list[list[Any]] = []
    loose: set[int] = set()

    def add(name: str, *args: Any, tolerant: bool = False, **kwargs: Any) -> None:
        if tolerant:
            loose.add(len(calls))
        calls.append([name, [plain(a) for a in args], {k: plain(v) for k, v in kwargs.items()}])

    for _ in range(40):
        angles = rng.uniform(-math.pi, math.pi, 3).tolist()
        quat = rng.normal(size=4).tolist()
        vec = rng.normal(size=3).tolist()
        point = rng.normal(size=3).tolist()
        for axes in AXES:
            add("euler_matrix", *angles, axes=axes)
            add("quaternion_from_euler", *angles, axes=axes)
            add("euler_from_quaternion", quat, axes=axes)
            add("euler_from_matrix", tr.random_rotation_matrix(rng.random(3)), axes=axes)
        add("euler_matrix", *angles, axes=[1, 0, 1, 1])
        add("quaternion_from_euler", *angles, axes=[2, 1, 0, 0])
        add("quaternion_matrix", quat)
        add("quaternion_from_matrix", tr.random_rotation_matrix(rng.random(3)))
        add("quaternion_multiply", quat, rng.normal(size=4))
        add("quaternion_conjugate", quat)
        add("quaternion_inverse", quat)
        add("quaternion_about_axis", angles[0], vec)
        add("quaternion_slerp", quat, rng.normal(size=4), float(rng.random()))
        add("quaternion_slerp", quat, rng.normal(size=4), float(rng.random()), spin=1, shortestpath=False)
        add("random_quaternion", rng.random(3))
        add("random_rotation_matrix", rng.random(3))
        add("translation_matrix", vec)
        add("translation_from_matrix", rng.normal(size=(4, 4)))
        add("rotation_matrix", angles[1], vec)
        add("rotation_matrix", angles[1], vec, point)
        add("reflection_matrix", point, vec)
        add("scale_matrix", angles[2], point)
        add("scale_matrix", angles[2], point, vec)
        add("projection_matrix", point, vec)
        add("projection_matrix", point, vec, direction=rng.normal(size=3))
        add("projection_matrix", point, vec, perspective=rng.normal(size=3))
        add("projection_matrix", point, vec, perspective=rng.normal(size=3), pseudo=True)
        add("clip_matrix", -1.0, 1.0, -2.0, 2.0, 0.5, 9.0, perspective=bool(rng.random() > 0.5))
        add("shear_matrix", angles[0], [1, 0, 0], point, [0, 0, 1])
        add("compose_matrix", rng.random(3) + 0.5, rng.normal(size=3), angles, vec, [0, 0, 0, 1])
        add("orthogonalization_matrix", (10.0, 11.0, 12.0), (80.0, 85.0, 95.0))
        add("vector_norm", rng.normal(size=(3, 5)), axis=1)
        add("unit_vector", rng.normal(size=(4, 3)), axis=0)
        add("concatenate_matrices", rng.normal(size=(4, 4)), rng.normal(size=(4, 4)))
        add("is_same_transform", tr.rotation_matrix(angles[0], vec), tr.rotation_matrix(angles[0], vec))
        add("arcball_map_to_sphere", rng.normal(size=2), [0.1, 0.2], 2.0)
        add("arcball_constrain_to_axis", rng.normal(size=3), tr.unit_vector(vec))
        add("arcball_nearest_axis", rng.normal(size=3), [tr.unit_vector(rng.normal(size=3)) for _ in range(3)])
        add("Arcball", rng.normal(size=4), rng.normal(size=2) * 100, 100.0 + rng.random() * 50,
            [tr.unit_vector(rng.normal(size=3)) for _ in range(2)] if rng.random() > 0.5 else [],
            bool(rng.random() > 0.5), rng.normal(size=2) * 60, rng.normal(size=2) * 60, [0.0, 0.2])
        # numpy.linalg-based inverses
        rot = tr.rotation_matrix(angles[1], vec, point)
        add("rotation_from_matrix", rot, tolerant=True)
        add("reflection_from_matrix", tr.reflection_matrix(point, vec), tolerant=True)
        add("scale_from_matrix", tr.scale_matrix(angles[2] + 4.0, point, vec), tolerant=True)
        add("decompose_matrix", tr.compose_matrix(rng.random(3) + 0.5, rng.normal(size=3) * 0.1, angles, vec),
            tolerant=True)
        add("superimposition_matrix", rng.normal(size=(3, 6)), rng.normal(size=(3, 6)), tolerant=True)
        add("superimposition_matrix", rng.normal(size=(3, 6)), rng.normal(size=(3, 6)), scaling=True,
            usesvd=False, tolerant=True)
        add("inverse_matrix", rot, tolerant=True)
        normal = tr.unit_vector(rng.normal(size=3))
        add("projection_from_matrix", tr.projection_matrix(point, normal), tolerant=True)
        add("projection_from_matrix", tr.projection_matrix(point, normal, perspective=rng.normal(size=3) * 3),
            tolerant=True)
        add("projection_from_matrix", tr.projection_matrix(point, normal, perspective=rng.normal(size=3) * 3,
                                                           pseudo=True), pseudo=True, tolerant=True)
    # bad input: the same errors
    add("euler_matrix", 0.0, 0.0, 0.0, axes="nope")
    add("shear_matrix", 0.3, [1, 0, 0], [0, 0, 0], [1, 0, 0])
    add("clip_matrix", 1.0, -1.0, 0.0, 1.0, 0.1, 1.0)
    add("decompose_matrix", numpy.zeros((4, 4)))
    add("quaternion_matrix", [0.0, 0.0, 0.0, 0.0])
    return calls, loose


REBUILD = {"rotation_from_matrix": tr.rotation_matrix, "reflection_from_matrix": tr.reflection_matrix,
           "scale_from_matrix": tr.scale_matrix, "decompose_matrix": tr.compose_matrix,
           "projection_from_matrix": tr.projection_matrix}




def kame_call(name: str, args: list[Any], kwargs: dict[str, Any]) -> Any:
    try:
        if name == "Arcball":
            return plain(arcball_drag(*args))
        return plain(getattr(tr, name)(*args, **kwargs))
    except Exception as exc:
        return {"error": type(exc).__name__}


@pytest.mark.skipif(not have_debian_tf(), reason="Debian's python3-tf is not installed")
def test_identical_to_debians_module() -> None:
    calls, loose = batch(numpy.random.default_rng(17))
    done = subprocess.run([SYSTEM_PYTHON, str(PEER)], input=json.dumps(calls), capture_output=True, text=True,
                          check=True, timeout=60)
    theirs = json.loads(done.stdout)
    assert len(theirs) == len(calls)
    for index, ((name, args, kwargs), expected) in enumerate(zip(calls, theirs, strict=True)):
        ours = kame_call(name, args, kwargs)
        where = f"{name}(*{args}, **{kwargs})"
        if index in loose:
            # eigenvectors of repeated eigenvalues are not unique: compare what they rebuild
            rebuild = REBUILD.get(name)
            if rebuild is not None and not isinstance(expected, dict):
                ours, expected = plain(rebuild(*ours)), plain(rebuild(*expected))
            assert_close(ours, expected, where, 1e-9)
        elif name in EXACT:
            assert ours == expected, where
        else:
            assert_within_ulps(ours, expected, where)


def flat(value: Any) -> list[Any]:
    return [v for item in value for v in flat(item)] if isinstance(value, list) else [value]


def assert_within_ulps(ours: Any, theirs: Any, where: str) -> None:
    mine, their = flat(ours), flat(theirs)
    assert len(mine) == len(their), where
    scale = max((abs(v) for v in mine + their if isinstance(v, float) and math.isfinite(v)), default=0.0)
    for a, b in zip(mine, their, strict=True):
        if isinstance(a, float) and isinstance(b, float) and a != b:
            apart = abs(a - b) / math.ulp(scale)
            assert apart <= ULPS, f"{where}: {a} and {b} are {apart:.0f} ulps of {scale} apart"
        else:
            assert a == b, where


def assert_close(ours: Any, theirs: Any, where: str, tolerance: float) -> None:
    if isinstance(theirs, list):
        assert isinstance(ours, list) and len(ours) == len(theirs), where
        for a, b in zip(ours, theirs, strict=True):
            assert_close(a, b, where, tolerance)
    elif isinstance(theirs, float) or isinstance(ours, float):
        assert math.isclose(ours, theirs, rel_tol=tolerance, abs_tol=tolerance), where
    else:
        assert ours == theirs, where


def test_euler_round_trip_in_every_convention() -> None:
    rng = numpy.random.default_rng(3)
    for axes in AXES:
        angles = rng.uniform(-1.0, 1.0, 3)
        matrix = tr.euler_matrix(*angles, axes=axes)
        assert tr.is_same_transform(matrix, tr.euler_matrix(*tr.euler_from_matrix(matrix, axes), axes=axes))
        quat = tr.quaternion_from_euler(*angles, axes=axes)
        assert tr.is_same_transform(matrix, tr.quaternion_matrix(quat))


def test_quaternions_are_x_y_z_w() -> None:
    quat = tr.quaternion_about_axis(math.pi / 2, [0, 0, 1])
    assert numpy.allclose(quat, [0, 0, math.sqrt(0.5), math.sqrt(0.5)])
    assert numpy.allclose(tr.euler_from_quaternion(quat), [0, 0, math.pi / 2])
    assert numpy.allclose(tr.quaternion_multiply(quat, tr.quaternion_inverse(quat)), [0, 0, 0, 1])


def test_unknown_axes_is_a_key_error() -> None:
    with pytest.raises(KeyError):
        tr.quaternion_from_euler(0, 0, 0, "xyz")


DEBIAN_SOURCE = Path("/usr/lib/python3/dist-packages/tf/transformations.py")


@pytest.mark.skipif(not DEBIAN_SOURCE.exists(), reason="Debian's python3-tf is not installed")
def test_the_numpy_linalg_inverses_are_upstreams_to_the_bit_on_one_numpy() -> None:
    """A shear matrix is defective (eigenvalue 1 three times), so what shear_from_matrix recovers
    from LAPACK's eigenvectors changes in its third digit between numpy builds: it cannot be
    compared with Debian's process. Upstream's own source, run on this interpreter's numpy, must
    give kame's answers bit for bit, for it and the other eig/svd-based inverses."""
    upstream: dict[str, Any] = {}
    with warnings.catch_warnings():  # its docstrings' escapes are Python 2's
        warnings.simplefilter("ignore", DeprecationWarning)
        exec(compile(DEBIAN_SOURCE.read_text(), str(DEBIAN_SOURCE), "exec"), upstream)
    rng = numpy.random.default_rng(5)
    for _ in range(50):
        vec, point = rng.normal(size=3), rng.normal(size=3)
        normal = tr.unit_vector(numpy.cross(vec, rng.normal(size=3)))
        angle = float(rng.uniform(-1.2, 1.2))
        cases = [("shear_from_matrix", tr.shear_matrix(angle, tr.unit_vector(numpy.cross(normal, vec)), point, normal)),
                 ("projection_from_matrix", tr.projection_matrix(point, normal, perspective=rng.normal(size=3))),
                 ("rotation_from_matrix", tr.rotation_matrix(angle, vec, point)),
                 ("scale_from_matrix", tr.scale_matrix(angle + 2.0, point, vec)),
                 ("reflection_from_matrix", tr.reflection_matrix(point, vec))]
        for name, matrix in cases:
            assert plain(getattr(tr, name)(matrix)) == plain(upstream[name](matrix)), name
