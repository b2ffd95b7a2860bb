"""ROS time values: Time (a point since the epoch) and Duration (a signed span).

Both are (secs, nsecs) pairs kept canonical, nsecs in [0, 1e9), as genpy and roscpp keep them.
These are plain values: nothing here reads a clock (rospy.Time.now() lives in the facade).
Arithmetic is done on integer nanoseconds so that no precision is lost.
"""

from __future__ import annotations

import numbers
from typing import Any

_NSEC_PER_SEC = 1_000_000_000


def _canon(secs: int, nsecs: int) -> tuple[int, int]:
    extra, nsecs = divmod(nsecs, _NSEC_PER_SEC)
    return secs + extra, nsecs


def _split_seconds(value: Any, nsecs: Any) -> tuple[int, int]:
    if isinstance(value, numbers.Integral):
        return _canon(int(value), int(nsecs))
    if nsecs != 0:
        raise ValueError("if secs is a float, nsecs cannot be set")
    whole = int(value)
    return _canon(whole, int((value - whole) * _NSEC_PER_SEC))


class TVal:
    """What Time and Duration share: two integer slots and their conversions."""

    __slots__ = ("nsecs", "secs")
    _slot_types = ("int32", "int32")

    def __init__(self, secs: Any = 0, nsecs: Any = 0) -> None:
        self.secs, self.nsecs = _split_seconds(secs, nsecs)

    @classmethod
    def from_sec(cls, float_secs: float) -> Any:
        whole = int(float_secs)
        return cls(whole, int((float_secs - whole) * _NSEC_PER_SEC))

    @classmethod
    def from_nsec(cls, nsec: int) -> Any:
        secs, nsecs = divmod(int(nsec), _NSEC_PER_SEC)
        return cls(secs, nsecs)

    def is_zero(self) -> bool:
        return self.secs == 0 and self.nsecs == 0

    def set(self, secs: int, nsecs: int) -> None:
        self.secs = secs
        self.nsecs = nsecs

    def canon(self) -> None:
        self.secs, self.nsecs = _canon(self.secs, self.nsecs)

    def to_sec(self) -> float:
        return float(self.secs) + float(self.nsecs) / 1e9

    def to_nsec(self) -> int:
        return self.secs * _NSEC_PER_SEC + self.nsecs

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __str__(self) -> str:
        return str(self.to_nsec())

    def __bool__(self) -> bool:
        return self.secs != 0 or self.nsecs != 0

    def __getstate__(self) -> list[int]:
        return [self.secs, self.nsecs]

    def __setstate__(self, state: list[int]) -> None:
        self.secs, self.nsecs = state

    def _cmp_key(self, other: object) -> tuple[int, int]:
        if not isinstance(other, type(self)._comparable()):
            raise TypeError(f"cannot compare {type(self).__name__} to {type(other).__name__}")
        assert isinstance(other, TVal)
        return self.to_nsec(), other.to_nsec()

    @classmethod
    def _comparable(cls) -> type[TVal]:
        return TVal

    def __lt__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a < b

    def __le__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a <= b

    def __gt__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a > b

    def __ge__(self, other: object) -> bool:
        try:
            a, b = self._cmp_key(other)
        except TypeError:
            return NotImplemented
        return a >= b

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, type(self)._comparable()):
            return False
        assert isinstance(other, TVal)
        return self.secs == other.secs and self.nsecs == other.nsecs

    def __ne__(self, other: object) -> bool:
        return not self.__eq__(other)


class Time(TVal):
    """The ROS `time` primitive: seconds and nanoseconds since the epoch, never negative."""

    __slots__ = ()

    def __init__(self, secs: Any = 0, nsecs: Any = 0) -> None:
        super().__init__(secs, nsecs)
        if self.secs < 0:
            raise TypeError("time values must be positive")

    @classmethod
    def _comparable(cls) -> type[TVal]:
        return Time

    def to_time(self) -> float:
        return self.to_sec()

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __repr__(self) -> str:
        return f"genpy.Time[{self.to_nsec()}]"

    def __add__(self, other: object) -> Any:
        if not isinstance(other, Duration):
            return NotImplemented
        return self.__class__(self.secs + other.secs, self.nsecs + other.nsecs)

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if isinstance(other, Time):
            return Duration(self.secs - other.secs, self.nsecs - other.nsecs)
        if isinstance(other, Duration):
            return self.__class__(self.secs - other.secs, self.nsecs - other.nsecs)
        return NotImplemented


class Duration(TVal):
    """The ROS `duration` primitive: a signed span of seconds and nanoseconds."""

    __slots__ = ()

    @classmethod
    def _comparable(cls) -> type[TVal]:
        return Duration

    def __hash__(self) -> int:
        return hash((self.secs, self.nsecs))

    def __repr__(self) -> str:
        return f"genpy.Duration[{self.to_nsec()}]"

    def __neg__(self) -> Duration:
        return self.__class__(-self.secs, -self.nsecs)

    def __abs__(self) -> Duration:
        return self if self.secs >= 0 else -self

    def __add__(self, other: object) -> Any:
        if isinstance(other, Duration):
            return self.__class__(self.secs + other.secs, self.nsecs + other.nsecs)
        return NotImplemented

    __radd__ = __add__

    def __sub__(self, other: object) -> Any:
        if not isinstance(other, Duration):
            return NotImplemented
        return self.__class__(self.secs - other.secs, self.nsecs - other.nsecs)

    def __mul__(self, factor: object) -> Any:
        if isinstance(factor, numbers.Integral):
            return self.__class__(self.secs * int(factor), self.nsecs * int(factor))
        if isinstance(factor, numbers.Real):
            return self.__class__.from_sec(self.to_sec() * float(factor))
        return NotImplemented

    __rmul__ = __mul__

    def __floordiv__(self, divisor: object) -> Any:
        if isinstance(divisor, Duration):
            return int(self.to_sec() // divisor.to_sec())
        if isinstance(divisor, numbers.Real):
            return self.__class__.from_sec(self.to_sec() // float(divisor))
        return NotImplemented

    def __truediv__(self, divisor: object) -> Any:
        if isinstance(divisor, Duration):
            return self.to_sec() / divisor.to_sec()
        if isinstance(divisor, numbers.Real):
            return self.__class__.from_sec(self.to_sec() / float(divisor))
        return NotImplemented

    def __mod__(self, divisor: object) -> Any:
        if isinstance(divisor, Duration):
            return self.__class__.from_sec(self.to_sec() % divisor.to_sec())
        return NotImplemented

    def __divmod__(self, divisor: object) -> Any:
        if isinstance(divisor, Duration):
            quotient, remainder = divmod(self.to_sec(), divisor.to_sec())
            return int(quotient), self.__class__.from_sec(remainder)
        return NotImplemented
