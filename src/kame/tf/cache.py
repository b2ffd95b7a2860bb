"""The transforms of one child frame over time, as tf2's TimeCache and StaticCache.

Rules (tf2's): a dynamic cache keeps `max_age` before its newest stamp; data older than that,
or with a stamp it already holds, is refused; lookups between two stamps interpolate (lerp and
slerp) when both have the same parent; time 0 means the newest; anything outside the held
stamps is an extrapolation error, with tf2's message. A static cache holds one transform, valid
at every time, and is never cleared. Times are integer nanoseconds.
"""

from __future__ import annotations

from bisect import bisect_left
from enum import Enum
from math import acos, sin, sqrt
from typing import NamedTuple

from .rotation import Quaternion, Vector


class Stored(NamedTuple):
    stamp: int
    parent: int  # the parent's frame number
    translation: Vector
    rotation: Quaternion


class Refusal(Enum):
    OLD = "TF_OLD_DATA ignoring data from the past (Possible reasons are listed at http://wiki.ros.org/tf/Errors%20explained)"
    REPEATED = "TF_REPEATED_DATA ignoring data with redundant timestamp"


def seconds(stamp: int) -> float:
    return stamp / 1e9


def _extrapolation_single(target: int, only: int) -> str:
    return (f"Lookup would require extrapolation at time {seconds(target):.9f}, "
            f"but only time {seconds(only):.9f} is in the buffer")


def _extrapolation_future(target: int, latest: int) -> str:
    return (f"Lookup would require extrapolation {seconds(target - latest):.9f}s into the future.  "
            f"Requested time {seconds(target):.9f} but the latest data is at time {seconds(latest):.9f}")


def _extrapolation_past(target: int, earliest: int) -> str:
    return (f"Lookup would require extrapolation {seconds(earliest - target):.9f}s into the past.  "
            f"Requested time {seconds(target):.9f} but the earliest data is at time {seconds(earliest):.9f}")


class TimeCache:
    is_static = False

    def __init__(self, max_age: int) -> None:
        self.max_age = max_age
        self._stamps: list[int] = []  # ascending, parallel to _data
        self._data: list[Stored] = []

    def insert(self, item: Stored) -> Refusal | None:
        stamps = self._stamps
        stamp = item.stamp
        if not stamps or stamp > stamps[-1]:  # the usual case: the newest yet
            stamps.append(stamp)
            self._data.append(item)
            if stamps[0] < stamp - self.max_age:
                self._prune()
            return None
        if stamps[-1] > stamp + self.max_age:
            return Refusal.OLD
        index = bisect_left(stamps, stamp)
        if stamps[index] == stamp:  # index < len: stamp is not past the newest
            return Refusal.REPEATED
        stamps.insert(index, stamp)
        self._data.insert(index, item)
        return None

    def _prune(self) -> None:
        cut = bisect_left(self._stamps, self._stamps[-1] - self.max_age)
        if cut:
            del self._stamps[:cut]
            del self._data[:cut]

    def get(self, time: int) -> Stored | str:
        """The transform at `time` (0: the newest), or why there is none. The hot path of every
        lookup, once per link: the interpolation is rotation.lerp and rotation.slerp written out
        in place (same arithmetic, same order), as their calls cost more than the sums."""
        data = self._data
        if not data:
            return ""  # tf2 says nothing for an empty cache; the caller reports connectivity
        if time == 0:
            return data[-1]
        stamps = self._stamps
        newer = bisect_left(stamps, time)
        if newer < len(stamps) and stamps[newer] == time:
            return data[newer]
        if len(data) == 1:
            return _extrapolation_single(time, stamps[0])
        if newer == len(stamps):
            return _extrapolation_future(time, stamps[-1])
        if newer == 0:
            return _extrapolation_past(time, stamps[0])
        older, later = data[newer - 1], data[newer]
        if older.parent != later.parent:
            return older
        ratio = (time - older.stamp) / (later.stamp - older.stamp)
        (ax, ay, az), (bx, by, bz) = older.translation, later.translation
        translation = (ax + (bx - ax) * ratio, ay + (by - ay) * ratio, az + (bz - az) * ratio)
        quaternion = older.rotation
        (ax, ay, az, aw), (bx, by, bz, bw) = quaternion, later.rotation
        product = (ax * bx + ay * by + az * bz + aw * bw) / sqrt(
            (ax * ax + ay * ay + az * az + aw * aw) * (bx * bx + by * by + bz * bz + bw * bw))
        if -1.0 < product < 1.0:
            sign = -1.0 if product < 0 else 1.0
            theta = acos(sign * product)
            s1 = sin(sign * ratio * theta)
            d = 1.0 / sin(theta)
            s0 = sin((1.0 - ratio) * theta)
            quaternion = ((ax * s0 + bx * s1) * d, (ay * s0 + by * s1) * d, (az * s0 + bz * s1) * d,
                          (aw * s0 + bw * s1) * d)
        return tuple.__new__(Stored, (time, older.parent, translation, quaternion))  # skips Stored's Python __new__

    def latest(self) -> tuple[int, int]:
        """(newest stamp, its parent), or (0, 0) when empty."""
        if not self._data:
            return 0, 0
        newest = self._data[-1]
        return newest.stamp, newest.parent

    def oldest_stamp(self) -> int:
        return self._stamps[0] if self._stamps else 0

    def __len__(self) -> int:
        return len(self._data)

    def clear(self) -> None:
        self._stamps.clear()
        self._data.clear()


class StaticCache:
    is_static = True

    def __init__(self) -> None:
        self._item: Stored | None = None

    def insert(self, item: Stored) -> Refusal | None:
        self._item = item
        return None

    def get(self, time: int) -> Stored | str:
        if self._item is None:
            return ""
        return self._item._replace(stamp=time)

    def latest(self) -> tuple[int, int]:
        """Static transforms hold at every time: they never limit the common time."""
        return (0, self._item.parent) if self._item is not None else (0, 0)

    def oldest_stamp(self) -> int:
        return 0

    def __len__(self) -> int:
        return 1 if self._item is not None else 0

    def clear(self) -> None:
        """Static transforms are kept forever (tf2's StaticCache ignores clearList)."""


Cache = TimeCache | StaticCache
