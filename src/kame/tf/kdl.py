"""The part of KDL's frames (orocos_kdl 1.5's Vector, Rotation and Frame, as PyKDL binds them)
that tf_conversions.posemath and course code use, on plain floats.

Each formula is KDL's own, in KDL's order of operations, so results equal PyKDL's (to 1e-12 in
tests/tf/test_posemath.py, most to the last bit): GetQuaternion's branches on the trace,
GetRPY's gimbal-lock case, Norm's scaling that keeps precision, Quaternion() without
normalizing. Equality is KDL's Equal with its epsilon (1e-6), as PyKDL's `==` is. `Frame.p` and
`Frame.M` are the frame's own parts (changing `f.p[0]` moves the frame) and assigning them
copies, as PyKDL's attributes do.
Not here: Twist, Wrench, the chains and solvers.
"""

from __future__ import annotations

import math
import operator
from typing import SupportsFloat, SupportsIndex, overload

EPSILON = 1e-6  # KDL's global epsilon: the default of Norm, Normalize, GetRotAngle and Equal


def _float(value: SupportsFloat) -> float:
    if isinstance(value, str | bytes):  # float() would parse them; PyKDL takes numbers only
        raise TypeError(f"a number is required, not {type(value).__name__}")
    return float(value)


def _divide(a: float, b: float) -> float:
    """IEEE division, as KDL's: dividing by zero gives inf or nan, not an exception."""
    if b != 0.0:
        return a / b
    if a == 0.0 or math.isnan(a):
        return math.nan
    return math.copysign(math.inf, a) * math.copysign(1.0, b)


def _near(a: float, b: float, eps: float) -> bool:
    return a + eps > b and a - eps < b  # KDL's Equal(double, double, eps)


def _index(i: SupportsIndex, size: int, kind: str) -> int:
    k = operator.index(i)
    if not 0 <= k < size:
        raise IndexError(f"{kind} index out of range")
    return k


def _pair(key: tuple[SupportsIndex, SupportsIndex], rows: int, cols: int, kind: str) -> tuple[int, int]:
    if not isinstance(key, tuple) or len(key) != 2:
        raise TypeError(f"{kind} indices are a pair (i, j)")
    i, j = operator.index(key[0]), operator.index(key[1])
    if not (0 <= i < rows and 0 <= j < cols):
        raise IndexError(f"{kind} index out of range")
    return i, j


def _sqr(value: float) -> float:
    return value * value  # KDL's sqr(), not pow(): the same rounding


def _g(value: float) -> str:
    return f"{value:12g}"  # KDL's operator<<: setw(12) and the stream's default precision of 6


class Vector:
    __slots__ = ("_d",)
    _d: list[float]

    @overload
    def __init__(self) -> None: ...
    @overload
    def __init__(self, x: SupportsFloat, y: SupportsFloat, z: SupportsFloat) -> None: ...
    @overload
    def __init__(self, x: Vector) -> None: ...

    def __init__(self, x: SupportsFloat | Vector | None = None, y: SupportsFloat | None = None,
                 z: SupportsFloat | None = None) -> None:
        if isinstance(x, Vector) and y is None and z is None:
            self._d = list(x._d)
        elif x is None and y is None and z is None:
            self._d = [0.0, 0.0, 0.0]
        elif x is not None and y is not None and z is not None and not isinstance(x, Vector):
            self._d = [_float(x), _float(y), _float(z)]
        else:
            raise TypeError("Vector() takes no arguments, a Vector, or x, y and z")

    @staticmethod
    def Zero() -> Vector:
        return Vector()

    def _coordinate(self, i: int, value: SupportsFloat | None) -> float | None:
        if value is None:
            return self._d[i]
        self._d[i] = _float(value)
        return None

    @overload
    def x(self) -> float: ...
    @overload
    def x(self, value: SupportsFloat) -> None: ...

    def x(self, value: SupportsFloat | None = None) -> float | None:
        """The x coordinate, or with a value, sets it (and returns None), as KDL's x()."""
        return self._coordinate(0, value)

    @overload
    def y(self) -> float: ...
    @overload
    def y(self, value: SupportsFloat) -> None: ...

    def y(self, value: SupportsFloat | None = None) -> float | None:
        return self._coordinate(1, value)

    @overload
    def z(self) -> float: ...
    @overload
    def z(self, value: SupportsFloat) -> None: ...

    def z(self, value: SupportsFloat | None = None) -> float | None:
        return self._coordinate(2, value)

    def __getitem__(self, i: SupportsIndex) -> float:
        return self._d[_index(i, 3, "Vector")]

    def __setitem__(self, i: SupportsIndex, value: SupportsFloat) -> None:
        self._d[_index(i, 3, "Vector")] = _float(value)

    def Norm(self, eps: float = EPSILON) -> float:
        """KDL's: divides by the largest coordinate first, so tiny or huge vectors keep their precision."""
        x, y, z = self._d
        a, b = abs(x), abs(y)
        if a >= b:
            b = abs(z)
            if a >= b:
                if a < eps:
                    return 0.0
                return a * math.sqrt(1 + _sqr(y / x) + _sqr(z / x))
            return b * math.sqrt(1 + _sqr(x / z) + _sqr(y / z))
        a = abs(z)
        if b > a:
            return b * math.sqrt(1 + _sqr(x / y) + _sqr(z / y))
        return a * math.sqrt(1 + _sqr(x / z) + _sqr(y / z))

    def Normalize(self, eps: float = EPSILON) -> float:
        """Makes this a unit vector and returns its norm; below eps, (1, 0, 0) and 0."""
        norm = self.Norm()
        if norm < eps:
            self._d = [1.0, 0.0, 0.0]
            return 0.0
        self._d = [c / norm for c in self._d]
        return norm

    def ReverseSign(self) -> None:
        self._d = [-c for c in self._d]

    def __add__(self, other: Vector) -> Vector:
        if not isinstance(other, Vector):
            return NotImplemented
        a, b = self._d, other._d
        return Vector(a[0] + b[0], a[1] + b[1], a[2] + b[2])

    def __sub__(self, other: Vector) -> Vector:
        if not isinstance(other, Vector):
            return NotImplemented
        a, b = self._d, other._d
        return Vector(a[0] - b[0], a[1] - b[1], a[2] - b[2])

    def __iadd__(self, other: Vector) -> Vector:
        if not isinstance(other, Vector):
            return NotImplemented
        self._d = [a + b for a, b in zip(self._d, other._d, strict=True)]
        return self

    def __isub__(self, other: Vector) -> Vector:
        if not isinstance(other, Vector):
            return NotImplemented
        self._d = [a - b for a, b in zip(self._d, other._d, strict=True)]
        return self

    def __neg__(self) -> Vector:
        return Vector(-self._d[0], -self._d[1], -self._d[2])

    def __mul__(self, other: SupportsFloat | Vector) -> Vector:
        """By a number, or by a Vector: the cross product, as KDL's operator*."""
        a = self._d
        if isinstance(other, Vector):
            b = other._d
            return Vector(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
        if isinstance(other, str | bytes) or not hasattr(other, "__float__"):
            return NotImplemented
        s = float(other)
        return Vector(a[0] * s, a[1] * s, a[2] * s)

    def __rmul__(self, other: SupportsFloat) -> Vector:
        if isinstance(other, str | bytes) or not hasattr(other, "__float__"):
            return NotImplemented
        s = float(other)
        return Vector(s * self._d[0], s * self._d[1], s * self._d[2])

    def __truediv__(self, other: SupportsFloat) -> Vector:
        if isinstance(other, str | bytes) or not hasattr(other, "__float__"):
            return NotImplemented
        s = float(other)
        return Vector(*(_divide(c, s) for c in self._d))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Vector):
            return NotImplemented
        return Equal(self, other)

    __hash__ = None  # type: ignore[assignment]  # mutable and compared with a tolerance, as PyKDL's

    def __copy__(self) -> Vector:
        return Vector(self)

    def __deepcopy__(self, memo: object) -> Vector:
        return Vector(self)

    def __repr__(self) -> str:
        return "[" + ",".join(_g(c) for c in self._d) + "]"


def dot(a: Vector, b: Vector) -> float:
    return b[0] * a[0] + b[1] * a[1] + b[2] * a[2]


class Rotation:
    """A 3x3 rotation matrix, stored row by row as KDL stores it."""

    __slots__ = ("_d",)
    _d: list[float]

    @overload
    def __init__(self) -> None: ...
    @overload
    def __init__(self, other: Rotation, /) -> None: ...
    @overload
    def __init__(self, x: Vector, y: Vector, z: Vector, /) -> None: ...
    @overload
    def __init__(self, Xx: SupportsFloat, Yx: SupportsFloat, Zx: SupportsFloat,
                 Xy: SupportsFloat, Yy: SupportsFloat, Zy: SupportsFloat,
                 Xz: SupportsFloat, Yz: SupportsFloat, Zz: SupportsFloat, /) -> None: ...

    def __init__(self, *args: SupportsFloat | Vector | Rotation) -> None:
        if not args:
            self._d = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        elif len(args) == 1 and isinstance(args[0], Rotation):
            self._d = list(args[0]._d)
        elif len(args) == 3 and all(isinstance(a, Vector) for a in args):
            x, y, z = (a._d for a in args if isinstance(a, Vector))
            self._d = [x[0], y[0], z[0], x[1], y[1], z[1], x[2], y[2], z[2]]  # the vectors are the columns
        elif len(args) == 9 and not any(isinstance(a, Vector | Rotation) for a in args):
            self._d = [_float(a) for a in args if not isinstance(a, Vector | Rotation)]
        else:
            raise TypeError("Rotation() takes no arguments, a Rotation, three column Vectors or nine numbers")

    @staticmethod
    def _of(d: list[float]) -> Rotation:
        r = Rotation()
        r._d = d
        return r

    @staticmethod
    def Identity() -> Rotation:
        return Rotation()

    @staticmethod
    def RotX(angle: float) -> Rotation:
        c, s = math.cos(angle), math.sin(angle)
        return Rotation._of([1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c])

    @staticmethod
    def RotY(angle: float) -> Rotation:
        c, s = math.cos(angle), math.sin(angle)
        return Rotation._of([c, 0.0, s, 0.0, 1.0, 0.0, -s, 0.0, c])

    @staticmethod
    def RotZ(angle: float) -> Rotation:
        c, s = math.cos(angle), math.sin(angle)
        return Rotation._of([c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0])

    @staticmethod
    def Rot(rotaxis: Vector, angle: float) -> Rotation:
        """About an axis of any length (normalized here)."""
        axis = Vector(rotaxis)
        axis.Normalize()
        return Rotation.Rot2(axis, angle)

    @staticmethod
    def Rot2(rotvec: Vector, angle: float) -> Rotation:
        """About a unit axis (not checked)."""
        ct, st = math.cos(angle), math.sin(angle)
        vt = 1 - ct
        v0, v1, v2 = rotvec._d
        vt0, vt1, vt2 = vt * v0, vt * v1, vt * v2
        st0, st1, st2 = v0 * st, v1 * st, v2 * st
        vt01, vt02, vt12 = vt0 * v1, vt0 * v2, vt1 * v2
        return Rotation._of([ct + vt0 * v0, -st2 + vt01, st1 + vt02,
                             st2 + vt01, ct + vt1 * v1, -st0 + vt12,
                             -st1 + vt02, st0 + vt12, ct + vt2 * v2])

    @staticmethod
    def RPY(roll: float, pitch: float, yaw: float) -> Rotation:
        """Roll about X, then pitch about Y, then yaw about Z, all about the fixed axes."""
        ca, sa = math.cos(yaw), math.sin(yaw)
        cb, sb = math.cos(pitch), math.sin(pitch)
        cc, sc = math.cos(roll), math.sin(roll)
        return Rotation._of([ca * cb, ca * sb * sc - sa * cc, ca * sb * cc + sa * sc,
                             sa * cb, sa * sb * sc + ca * cc, sa * sb * cc - ca * sc,
                             -sb, cb * sc, cb * cc])

    @staticmethod
    def EulerZYX(alpha: float, beta: float, gamma: float) -> Rotation:
        return Rotation.RPY(gamma, beta, alpha)

    @staticmethod
    def EulerZYZ(alpha: float, beta: float, gamma: float) -> Rotation:
        sa, ca = math.sin(alpha), math.cos(alpha)
        sb, cb = math.sin(beta), math.cos(beta)
        sg, cg = math.sin(gamma), math.cos(gamma)
        return Rotation._of([ca * cb * cg - sa * sg, -ca * cb * sg - sa * cg, ca * sb,
                             sa * cb * cg + ca * sg, -sa * cb * sg + ca * cg, sa * sb,
                             -sb * cg, sb * sg, cb])

    @staticmethod
    def Quaternion(x: float, y: float, z: float, w: float) -> Rotation:
        """Not normalized: a quaternion of norm n gives n^2 times a rotation, as KDL's does."""
        x, y, z, w = _float(x), _float(y), _float(z), _float(w)
        x2, y2, z2, w2 = x * x, y * y, z * z, w * w
        return Rotation._of([w2 + x2 - y2 - z2, 2 * x * y - 2 * w * z, 2 * x * z + 2 * w * y,
                             2 * x * y + 2 * w * z, w2 - x2 + y2 - z2, 2 * y * z - 2 * w * x,
                             2 * x * z - 2 * w * y, 2 * y * z + 2 * w * x, w2 - x2 - y2 + z2])

    def GetQuaternion(self) -> tuple[float, float, float, float]:
        """(x, y, z, w), from the largest of the trace and the diagonal for precision."""
        d = self._d
        trace = d[0] + d[4] + d[8]
        if trace > 1e-12:
            s = 0.5 / math.sqrt(trace + 1.0)
            return (d[7] - d[5]) * s, (d[2] - d[6]) * s, (d[3] - d[1]) * s, 0.25 / s
        if d[0] > d[4] and d[0] > d[8]:
            s = 2.0 * math.sqrt(1.0 + d[0] - d[4] - d[8])
            return 0.25 * s, (d[1] + d[3]) / s, (d[2] + d[6]) / s, (d[7] - d[5]) / s
        if d[4] > d[8]:
            s = 2.0 * math.sqrt(1.0 + d[4] - d[0] - d[8])
            return (d[1] + d[3]) / s, 0.25 * s, (d[5] + d[7]) / s, (d[2] - d[6]) / s
        s = 2.0 * math.sqrt(1.0 + d[8] - d[0] - d[4])
        return (d[2] + d[6]) / s, (d[5] + d[7]) / s, 0.25 * s, (d[3] - d[1]) / s

    def GetRPY(self) -> tuple[float, float, float]:
        """(roll, pitch, yaw); at pitch +-pi/2, roll is 0 and yaw takes the whole turn."""
        d = self._d
        pitch = math.atan2(-d[6], math.sqrt(_sqr(d[0]) + _sqr(d[3])))
        if abs(pitch) > math.pi / 2.0 - 1e-12:
            return 0.0, pitch, math.atan2(-d[1], d[4])
        return math.atan2(d[7], d[8]), pitch, math.atan2(d[3], d[0])

    def GetEulerZYX(self) -> tuple[float, float, float]:
        roll, pitch, yaw = self.GetRPY()
        return yaw, pitch, roll

    def GetEulerZYZ(self) -> tuple[float, float, float]:
        d = self._d
        if abs(d[8]) > 1 - 1e-12:
            if d[8] > 0:
                return math.atan2(d[3], d[0]), 0.0, 0.0
            return math.atan2(-d[3], -d[0]), math.pi, 0.0
        return (math.atan2(d[5], d[2]), math.atan2(math.sqrt(_sqr(d[6]) + _sqr(d[7])), d[8]),
                math.atan2(d[7], -d[6]))

    def GetRotAngle(self, eps: float = EPSILON) -> tuple[float, Vector]:
        """(angle in [0, pi], unit axis); the axis is Z at angle 0."""
        d = self._d
        if abs(d[1] - d[3]) < eps and abs(d[2] - d[6]) < eps and abs(d[5] - d[7]) < eps:
            eps2 = eps * 10  # tells 0 from pi
            if (abs(d[1] + d[3]) < eps2 and abs(d[2] + d[6]) < eps2 and abs(d[5] + d[7]) < eps2
                    and abs(d[0] + d[4] + d[8] - 3) < eps2):
                return 0.0, Vector(0.0, 0.0, 1.0)
            xx, yy, zz = (d[0] + 1) / 2, (d[4] + 1) / 2, (d[8] + 1) / 2
            xy, xz, yz = (d[1] + d[3]) / 4, (d[2] + d[6]) / 4, (d[5] + d[7]) / 4
            if xx > yy and xx > zz:
                x = math.sqrt(xx)
                return math.pi, Vector(x, xy / x, xz / x)
            if yy > zz:
                y = math.sqrt(yy)
                return math.pi, Vector(xy / y, y, yz / y)
            z = math.sqrt(zz)
            return math.pi, Vector(xz / z, yz / z, z)
        f = (d[0] + d[4] + d[8] - 1) / 2
        axis = Vector(d[7] - d[5], d[2] - d[6], d[3] - d[1])
        angle = math.atan2(axis.Norm() / 2, f)
        axis.Normalize()
        return angle, axis

    def GetRot(self) -> Vector:
        """The axis scaled by the angle."""
        angle, axis = self.GetRotAngle()
        return axis * angle

    def SetInverse(self) -> None:
        d = self._d
        d[1], d[3] = d[3], d[1]
        d[2], d[6] = d[6], d[2]
        d[5], d[7] = d[7], d[5]

    @overload
    def Inverse(self) -> Rotation: ...
    @overload
    def Inverse(self, v: Vector) -> Vector: ...

    def Inverse(self, v: Vector | None = None) -> Rotation | Vector:
        """The transpose, or with a Vector, the vector rotated back."""
        d = self._d
        if v is None:
            return Rotation._of([d[0], d[3], d[6], d[1], d[4], d[7], d[2], d[5], d[8]])
        a = v._d
        return Vector(d[0] * a[0] + d[3] * a[1] + d[6] * a[2],
                      d[1] * a[0] + d[4] * a[1] + d[7] * a[2],
                      d[2] * a[0] + d[5] * a[1] + d[8] * a[2])

    def _column(self, j: int, v: Vector | None) -> Vector | None:
        if v is None:
            return Vector(self._d[j], self._d[3 + j], self._d[6 + j])
        self._d[j], self._d[3 + j], self._d[6 + j] = v._d
        return None

    def UnitX(self, v: Vector | None = None) -> Vector | None:
        """The first column, or with a Vector, sets it (and returns None)."""
        return self._column(0, v)

    def UnitY(self, v: Vector | None = None) -> Vector | None:
        return self._column(1, v)

    def UnitZ(self, v: Vector | None = None) -> Vector | None:
        return self._column(2, v)

    def _turn(self, angle: float, a: int, b: int, sign: float) -> None:
        """self = self * Rot(axis, angle), touching the two columns a and b only."""
        c, s = math.cos(angle), sign * math.sin(angle)
        d = self._d
        for row in (0, 3, 6):
            da, db = d[row + a], d[row + b]
            d[row + a], d[row + b] = c * da + s * db, -s * da + c * db

    def DoRotX(self, angle: float) -> None:
        self._turn(angle, 1, 2, 1.0)

    def DoRotY(self, angle: float) -> None:
        self._turn(angle, 0, 2, -1.0)

    def DoRotZ(self, angle: float) -> None:
        self._turn(angle, 0, 1, 1.0)

    def __getitem__(self, key: tuple[SupportsIndex, SupportsIndex]) -> float:
        i, j = _pair(key, 3, 3, "Rotation")
        return self._d[3 * i + j]

    def __setitem__(self, key: tuple[SupportsIndex, SupportsIndex], value: SupportsFloat) -> None:
        i, j = _pair(key, 3, 3, "Rotation")
        self._d[3 * i + j] = _float(value)

    @overload
    def __mul__(self, other: Rotation) -> Rotation: ...
    @overload
    def __mul__(self, other: Vector) -> Vector: ...

    def __mul__(self, other: Rotation | Vector) -> Rotation | Vector:
        a = self._d
        if isinstance(other, Vector):
            v = other._d
            return Vector(a[0] * v[0] + a[1] * v[1] + a[2] * v[2],
                          a[3] * v[0] + a[4] * v[1] + a[5] * v[2],
                          a[6] * v[0] + a[7] * v[1] + a[8] * v[2])
        if not isinstance(other, Rotation):
            return NotImplemented
        b = other._d
        return Rotation._of([a[r] * b[c] + a[r + 1] * b[c + 3] + a[r + 2] * b[c + 6]
                             for r in (0, 3, 6) for c in (0, 1, 2)])

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Rotation):
            return NotImplemented
        return Equal(self, other)

    __hash__ = None  # type: ignore[assignment]

    def __copy__(self) -> Rotation:
        return Rotation(self)

    def __deepcopy__(self, memo: object) -> Rotation:
        return Rotation(self)

    def __repr__(self) -> str:
        d = self._d
        return "[" + ";\n ".join(",".join(_g(c) for c in d[r:r + 3]) for r in (0, 3, 6)) + "]"


class Frame:
    """A pose: the rotation M and the origin p of a frame in its parent."""

    __slots__ = ("_M", "_p")
    _M: Rotation
    _p: Vector

    @overload
    def __init__(self) -> None: ...
    @overload
    def __init__(self, R: Rotation, V: Vector) -> None: ...
    @overload
    def __init__(self, R: Rotation | Vector | Frame, /) -> None: ...

    def __init__(self, R: Rotation | Vector | Frame | None = None, V: Vector | None = None) -> None:
        if isinstance(R, Rotation) and isinstance(V, Vector):
            self._M, self._p = Rotation(R), Vector(V)
        elif V is not None:
            raise TypeError("Frame(R, V) takes a Rotation and a Vector")
        elif R is None:
            self._M, self._p = Rotation(), Vector()
        elif isinstance(R, Frame):
            self._M, self._p = Rotation(R._M), Vector(R._p)
        elif isinstance(R, Rotation):
            self._M, self._p = Rotation(R), Vector()
        elif isinstance(R, Vector):
            self._M, self._p = Rotation(), Vector(R)
        else:
            raise TypeError("Frame() takes a Rotation and a Vector, one of them, or a Frame")

    @property
    def M(self) -> Rotation:
        return self._M

    @M.setter
    def M(self, value: Rotation) -> None:
        self._M = Rotation(value)

    @property
    def p(self) -> Vector:
        return self._p

    @p.setter
    def p(self, value: Vector) -> None:
        self._p = Vector(value)

    @staticmethod
    def Identity() -> Frame:
        return Frame()

    @staticmethod
    def DH(a: float, alpha: float, d: float, theta: float) -> Frame:
        """Denavit-Hartenberg parameters."""
        ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
        return Frame(Rotation._of([ct, -st * ca, st * sa, st, ct * ca, -ct * sa, 0.0, sa, ca]),
                     Vector(a * ct, a * st, d))

    @staticmethod
    def DH_Craig1989(a: float, alpha: float, d: float, theta: float) -> Frame:
        """Modified Denavit-Hartenberg parameters (Craig's)."""
        ct, st, ca, sa = math.cos(theta), math.sin(theta), math.cos(alpha), math.sin(alpha)
        return Frame(Rotation._of([ct, -st, 0.0, st * ca, ct * ca, -sa, st * sa, ct * sa, ca]),
                     Vector(a, -sa * d, ca * d))

    @overload
    def Inverse(self) -> Frame: ...
    @overload
    def Inverse(self, v: Vector) -> Vector: ...

    def Inverse(self, v: Vector | None = None) -> Frame | Vector:
        if v is None:
            return Frame(self._M.Inverse(), -self._M.Inverse(self._p))
        return self._M.Inverse(v - self._p)

    def __getitem__(self, key: tuple[SupportsIndex, SupportsIndex]) -> float:
        i, j = _pair(key, 3, 4, "Frame")
        return self._p[i] if j == 3 else self._M[i, j]

    def __setitem__(self, key: tuple[SupportsIndex, SupportsIndex], value: SupportsFloat) -> None:
        i, j = _pair(key, 3, 4, "Frame")
        if j == 3:
            self._p[i] = value
        else:
            self._M[i, j] = value

    @overload
    def __mul__(self, other: Frame) -> Frame: ...
    @overload
    def __mul__(self, other: Vector) -> Vector: ...

    def __mul__(self, other: Frame | Vector) -> Frame | Vector:
        if isinstance(other, Vector):
            return self._M * other + self._p
        if not isinstance(other, Frame):
            return NotImplemented
        return Frame(self._M * other._M, self._M * other._p + self._p)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Frame):
            return NotImplemented
        return Equal(self, other)

    __hash__ = None  # type: ignore[assignment]

    def __copy__(self) -> Frame:
        return Frame(self)

    def __deepcopy__(self, memo: object) -> Frame:
        return Frame(self)

    def __repr__(self) -> str:
        return f"[{self._M!r}\n{self._p!r}]"


@overload
def Equal(a: Vector, b: Vector, eps: float = EPSILON) -> bool: ...
@overload
def Equal(a: Rotation, b: Rotation, eps: float = EPSILON) -> bool: ...
@overload
def Equal(a: Frame, b: Frame, eps: float = EPSILON) -> bool: ...


def Equal(a: Vector | Rotation | Frame, b: Vector | Rotation | Frame, eps: float = EPSILON) -> bool:
    """Every coordinate within eps."""
    if isinstance(a, Frame) and isinstance(b, Frame):
        return Equal(a._p, b._p, eps) and Equal(a._M, b._M, eps)
    if (isinstance(a, Vector) and isinstance(b, Vector)) or (isinstance(a, Rotation) and isinstance(b, Rotation)):
        return all(_near(x, y, eps) for x, y in zip(a._d, b._d, strict=True))
    raise TypeError("Equal() compares two Vectors, two Rotations or two Frames")
