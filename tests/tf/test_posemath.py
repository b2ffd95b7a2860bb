"""tf_conversions.posemath and kame's PyKDL subset against Debian's (real PyKDL, real posemath):
one driver script, run by both interpreters on the same random and corner-case inputs, must give
the same results to 1e-12 (the same text for reprs, the same exception for bad indices)."""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy
import pytest

import PyKDL
import tf_conversions
import tf_conversions.posemath as pm
from geometry_msgs.msg import Pose
from kame.tf import transformations as tr

from ..support import SYSTEM_PYTHON

DRIVER = Path(__file__).with_name("kdl_driver.py")
Case = tuple[str, dict[str, Any]]


def have_debian_posemath() -> bool:
    probe = "import tf_conversions.posemath, PyKDL, cv2"
    return subprocess.run([SYSTEM_PYTHON, "-c", probe], capture_output=True).returncode == 0


needs_debian = pytest.mark.skipif(not have_debian_posemath(), reason="Debian's python3-tf-conversions is not installed")


def run(python: str, cases: list[Case]) -> list[Any]:
    done = subprocess.run([python, str(DRIVER)], input=json.dumps(cases), capture_output=True, text=True,
                          check=True, timeout=60)
    results: list[Any] = json.loads(done.stdout)
    assert len(results) == len(cases)
    return results


def same(a: Any, b: Any, tol: float) -> bool:
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(same(x, y, tol) for x, y in zip(a, b, strict=True))
    if isinstance(a, float) and isinstance(b, float):
        return (math.isnan(a) and math.isnan(b)) or math.isclose(a, b, rel_tol=tol, abs_tol=tol)
    return type(a) is type(b) and a == b


def compare(cases: list[Case], tol: float = 1e-12) -> None:
    theirs = run(SYSTEM_PYTHON, cases)
    ours = run(sys.executable, cases)
    differ = [(case, o, t) for case, o, t in zip(cases, ours, theirs, strict=True) if not same(o, t, tol)]
    assert not differ, f"{len(differ)} of {len(cases)} differ, first: {differ[0]}"


def V(v: Any) -> list[Any]:
    return ["V", list(map(float, v))]


def R(m: Any) -> list[Any]:
    return ["R", [float(m[i][j]) for i in range(3) for j in range(3)]]


def F(m: Any) -> list[Any]:
    return ["F", [float(m[i][j]) for i in range(3) for j in range(3)] + [float(m[i][3]) for i in range(3)]]


# rotations where GetQuaternion leaves the trace branch (half turns about each axis and a diagonal),
# GetRPY meets gimbal lock, GetEulerZYZ's beta is 0 or pi, GetRotAngle sees 0 or pi
CORNERS = [tr.rotation_matrix(math.pi, axis) for axis in ([1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, 2, 3])]
CORNERS += [tr.euler_matrix(0.3, math.pi / 2, 0.2, "sxyz"), tr.euler_matrix(0.3, -math.pi / 2, 0.2, "sxyz"),
            tr.euler_matrix(0.4, 0.0, 0.9, "rzyz"), tr.euler_matrix(0.4, math.pi, 0.9, "rzyz"), numpy.identity(4),
            tr.rotation_matrix(1e-8, [0, 0, 1])]


def random_matrix(rng: numpy.random.Generator) -> Any:
    m = tr.quaternion_matrix(tr.random_quaternion(rng.random(3)))
    m[:3, 3] = rng.normal(size=3) * 5
    return m


def pose(t: Any, q: Any) -> list[Any]:
    return ["Pose", [*map(float, t), *map(float, q)]]


def posemath_cases(rng: numpy.random.Generator) -> list[Case]:
    cases: list[Case] = []
    for i in range(40):
        t, q = (rng.normal(size=3) * 5).tolist(), tr.random_quaternion(rng.random(3)).tolist()
        if i % 10 == 9:
            q = [2 * c for c in q]  # KDL does not normalize: both must scale the same way
        tf = [t, q]
        m = random_matrix(rng) if i < 30 else CORNERS[i - 30]
        p = pose(rng.normal(size=3), tr.random_quaternion(rng.random(3)))
        cases += [("pm.toTf(pm.fromTf(tf))", {"tf": tf}),
                  ("pm.toMsg(pm.fromTf(tf))", {"tf": tf}),
                  ("pm.toMatrix(pm.fromTf(tf))", {"tf": tf}),
                  ("pm.toMsg(pm.fromMsg(p))", {"p": p}),
                  ("pm.toMatrix(pm.fromMsg(p))", {"p": p}),
                  ("pm.toTf(pm.fromMatrix(m))", {"m": ["A", m.tolist()]}),
                  ("pm.toMsg(pm.fromMatrix(m))", {"m": ["A", m.tolist()]}),
                  ("pm.toMatrix(pm.fromMatrix(m))", {"m": ["A", m.tolist()]}),
                  ("pm.toMsg(pm.fromMsg(p) * pm.fromTf(tf))", {"p": p, "tf": tf}),
                  ("pm.toTf(pm.fromMatrix(m).Inverse() * pm.fromMsg(p))", {"p": p, "m": ["A", m.tolist()]}),
                  ("pm.toMatrix(pm.fromMsg(p).Inverse())", {"p": p}),
                  ("pm.fromMsg(p) == pm.fromTf(tf)", {"p": p, "tf": tf}),
                  ("tc.toTf(tc.fromMsg(p))", {"p": p}),
                  ("tc.transformations.euler_from_quaternion(q)", {"q": q}),
                  ("pm.toTf(pm.Frame(pm.Rotation.RPY(*t), pm.Vector(*t)))", {"t": t})]
    return cases


def kdl_cases(rng: numpy.random.Generator) -> list[Case]:
    cases: list[Case] = []
    for i in range(30):
        a, b = V(rng.normal(size=3) * 3), V(rng.normal(size=3))
        s, angle = float(rng.normal()), float(rng.uniform(-4, 4))
        r, r2 = R(random_matrix(rng)), R(random_matrix(rng) if i < 20 else CORNERS[i - 20])
        f, g = F(random_matrix(rng)), F(random_matrix(rng))
        three = [float(x) for x in rng.uniform(-3, 3, size=3)]
        q = tr.random_quaternion(rng.random(3)).tolist()
        unit = V(numpy.array(a[1]) / numpy.linalg.norm(a[1]))
        vectors = {"a": a, "b": b, "s": s}
        cases += [(e, vectors) for e in (
            "a + b", "a - b", "-a", "a * b", "a * s", "s * a", "a / s", "K.dot(a, b)", "a.Norm()",
            "(a.Normalize(), a)", "(a.ReverseSign(), a)", "a == b", "a == K.Vector(a)", "a != b", "a.x()",
            "(a.y(s), a)", "a[1]", "(a.__setitem__(2, s), a)", "(a.__iadd__(b), a)", "(a.__isub__(b), a)",
            "K.Equal(a, b, 10.0)", "K.Equal(a, a * (1 + 1e-9))", "repr(a)", "str(b)", "K.Vector.Zero()", "K.Vector()")]
        rotations = {"r": r, "r2": r2, "a": a, "u": unit, "t": angle, "abc": three, "q": q}
        cases += [(e, rotations) for e in (
            "K.Rotation.RotX(t)", "K.Rotation.RotY(t)", "K.Rotation.RotZ(t)", "K.Rotation.Rot(a, t)",
            "K.Rotation.Rot2(u, t)", "K.Rotation.RPY(*abc)", "K.Rotation.EulerZYX(*abc)", "K.Rotation.EulerZYZ(*abc)",
            "K.Rotation.Quaternion(*q)", "K.Rotation.Quaternion(*[2 * c for c in q])", "K.Rotation.Identity()",
            "r2.GetQuaternion()", "r2.GetRPY()", "r2.GetEulerZYX()", "r2.GetEulerZYZ()", "r2.GetRotAngle()",
            "r2.GetRot()", "r.GetRotAngle(1e-3)", "K.Rotation.RPY(*abc).GetRPY()", "r.Inverse()", "r.Inverse(a)",
            "r * r2", "r * a", "r.UnitX()", "r.UnitY()", "r.UnitZ()", "(r.UnitY(a), r)", "(r.DoRotX(t), r)",
            "(r.DoRotY(t), r)", "(r.DoRotZ(t), r)", "(r.SetInverse(), r)", "r[1, 2]", "(r.__setitem__((2, 0), t), r)",
            "r == r2", "r == K.Rotation(r)", "K.Rotation(a, u, a * u)", "repr(r)", "r[3, 0]", "r[0, -1]")]
        frames = {"f": f, "g": g, "r": r, "a": a, "b": b, "dh": [*three, angle]}
        cases += [(e, frames) for e in (
            "K.Frame(r, a)", "K.Frame(a)", "K.Frame(r)", "K.Frame(f)", "K.Frame()", "K.Frame.Identity()", "f * g",
            "f * a", "f.Inverse()", "f.Inverse(a)", "f.Inverse() * f", "f[0, 3]", "f[2, 1]", "f.M", "f.p",
            "(f.__setitem__((1, 3), 2.5), f)", "(f.p.__setitem__(0, 9.5), f)", "(f.M.DoRotZ(0.5), f)",
            "(setattr(f, 'p', b), b.__setitem__(0, 1.5), f)", "(setattr(f, 'M', r), r.DoRotX(1.0), f)",
            "K.Frame.DH(*dh)", "K.Frame.DH_Craig1989(*dh)", "f == g", "f == K.Frame(f)", "K.Equal(f, g, 100.0)",
            "repr(f)", "f[3, 3]", "f[0, 4]")]
    tiny_and_huge = {"z": V([0, 0, 0]), "tiny": V([1e-7, 5e-8, 0]), "huge": V([1e200, -3e200, 2e199]),
                     "half": V([0.5, 0, 0])}
    cases += [(e, tiny_and_huge) for e in (
        "z.Norm()", "(z.Normalize(), z)", "tiny.Norm()", "tiny.Norm(1e-9)", "(tiny.Normalize(), tiny)", "huge.Norm()",
        "(huge.Normalize(), huge)", "(half.Normalize(1.0), half)", "half / 0", "z / 0", "repr(huge)", "repr(tiny)",
        "repr(-z)", "list(half)", "half[-1]", "half[3]")]
    return cases


@needs_debian
def test_posemath_matches_debians() -> None:
    compare(posemath_cases(numpy.random.default_rng(17)))


@needs_debian
def test_from_camera_params_matches_debians() -> None:
    """Upstream rounds the rotation matrix to float32, kame keeps float64: equal to float32's precision."""
    rng = numpy.random.default_rng(5)
    cases: list[Case] = [("pm.fromCameraParams(cv, r, t)", {"r": ["A", (rng.normal(size=(3, 1))).tolist()],
                                                             "t": ["A", (rng.normal(size=(3, 1)) * 2).tolist()]})
                         for _ in range(20)]
    compare(cases, tol=1e-6)


@needs_debian
def test_pykdl_subset_matches_debians_pykdl() -> None:
    compare(kdl_cases(numpy.random.default_rng(23)))


def test_posemath_round_trips_and_shares_the_programs_pykdl() -> None:
    p = Pose()
    p.position.x, p.position.y, p.position.z = 1.0, -2.0, 0.5
    p.orientation.z, p.orientation.w = math.sin(0.3), math.cos(0.3)
    f = pm.fromMsg(p)
    assert isinstance(f, PyKDL.Frame) and pm.Frame is PyKDL.Frame and tf_conversions.fromMsg is pm.fromMsg
    back = pm.toMsg(f)
    assert [back.position.x, back.position.y, back.position.z] == [1.0, -2.0, 0.5]
    assert math.isclose(back.orientation.z, math.sin(0.3)) and math.isclose(back.orientation.w, math.cos(0.3))
    assert numpy.allclose(pm.toMatrix(pm.fromMatrix(pm.toMatrix(f))), pm.toMatrix(f), rtol=0, atol=1e-15)
    t, q = pm.toTf(f.Inverse() * f)
    assert numpy.allclose([*t, *q], [0, 0, 0, 0, 0, 0, 1], rtol=0, atol=1e-15)
