"""ROS time: Time and Duration (rospy's) with now(), on the wall clock or simulated (/clock)."""

from __future__ import annotations

import contextlib
import threading
import time as _time
from collections.abc import Iterator
from typing import Any

from kame import rostime as _values


class Duration(_values.Duration):
    __slots__ = ()


class Time(_values.Time):
    __slots__ = ()

    @staticmethod
    def now() -> Time:
        """The current ROS time: wall clock, or /clock when /use_sim_time is true."""
        return get_rostime()

    @classmethod
    def from_seconds(cls, float_secs: float) -> Any:
        return cls.from_sec(float_secs)


_sim_time: _values.Time | None = None
_sim_lock = threading.Lock()
_initialized = False


_wakers: set[threading.Event] = set()  # events set at every change of simulated time (woken_at_change)
rostime_changed = threading.Condition()  # notified at every change of simulated time (rospy's get_rostime_cond)


def set_sim_time(value: _values.Time | None) -> None:
    """Switch to simulated time (a value) or back to the wall clock (None); wakes sleepers."""
    global _sim_time
    with _sim_lock:
        _sim_time = value
        for waker in _wakers:
            waker.set()
    with rostime_changed:
        rostime_changed.notify_all()


@contextlib.contextmanager
def woken_at_change(event: threading.Event) -> Iterator[None]:
    """Within the block, every change of simulated time (a /clock message, the switch to or from
    it) sets `event`: a wait for "this, or a ROS-time deadline" is one wait on `event`."""
    with _sim_lock:
        _wakers.add(event)
    try:
        yield
    finally:
        with _sim_lock:
            _wakers.discard(event)


def is_sim_time() -> bool:
    return _sim_time is not None


def set_rostime_initialized(value: bool) -> None:
    global _initialized
    _initialized = value


def is_rostime_initialized() -> bool:
    return _initialized


def get_rostime() -> Time:
    if not _initialized:
        from kame.client.errors import ROSInitException

        raise ROSInitException("time is not initialized. Have you called init_node()?")
    sim = _sim_time
    if sim is not None:
        return Time(sim.secs, sim.nsecs)
    now: Time = Time.from_nsec(_time.time_ns())
    return now


def get_time() -> float:
    return get_rostime().to_sec()


def wallsleep(duration: float) -> None:
    if duration > 0:
        _time.sleep(duration)
