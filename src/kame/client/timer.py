"""Rate, Timer and sleep (rospy's), on ROS time (wall clock or /clock)."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from kame import rostime as values
from kame.client import clock, core
from kame.client.errors import ROSInterruptException, ROSTimeMovedBackwardsException
from kame.net.signal_wake import SignalSafeEvent


def _seconds(duration: Any) -> float:
    return float(duration.to_sec()) if isinstance(duration, values.TVal) else float(duration)


def sleep(duration: Any) -> None:
    """Sleep for `duration` (seconds or a Duration) of ROS time.

    On the wall clock a shutdown during the sleep ends it early and quietly, as rospy's wall
    sleep never raises: `while not rospy.is_shutdown(): rate.sleep()` then ends cleanly on
    Ctrl-C. A sleep begun after the shutdown (a shutdown hook letting a last message go, a
    `while True:` loop) sleeps its whole time, as rospy's does. On simulated time shutdown
    raises ROSInterruptException, as rospy's sim-time branch does."""
    seconds = _seconds(duration)
    if not clock.is_sim_time():
        if core.is_shutdown():
            time.sleep(max(seconds, 0.0))
        else:
            core.wait_for_shutdown(max(seconds, 0.0))
        return
    start = clock.get_rostime()
    target = start + clock.Duration.from_sec(seconds)
    ticked = SignalSafeEvent()  # by each /clock message, and by shutdown; cleared before looking
    with core.woken_at_shutdown(ticked), clock.woken_at_change(ticked):
        while not core.is_shutdown():
            ticked.clear()
            now = clock.get_rostime()
            if now >= target:
                return
            if now < start:
                raise ROSTimeMovedBackwardsException(0)
            ticked.wait()
    raise ROSInterruptException("ROS shutdown request")


class Rate:
    """Keeps a loop at `hz` iterations a second: `rate.sleep()` waits out the rest of the period."""

    def __init__(self, hz: float, reset: bool = False) -> None:
        self.last_time: values.Time = clock.get_rostime()
        self.sleep_dur = clock.Duration.from_sec(1.0 / hz)
        self._reset = reset

    def _remaining(self, now: values.Time) -> values.Duration:
        if self.last_time > now:  # time moved backwards: start over from now
            self.last_time = now
        elapsed = now - self.last_time
        result: values.Duration = self.sleep_dur - elapsed
        return result

    def remaining(self) -> values.Duration:
        return self._remaining(clock.get_rostime())

    def sleep(self) -> None:
        now = clock.get_rostime()
        remaining = self._remaining(now)
        try:
            sleep(remaining)
        except ROSTimeMovedBackwardsException:
            if not self._reset:
                raise
            self.last_time = clock.get_rostime()
            return
        self.last_time = self.last_time + self.sleep_dur
        # Fell more than a period behind (a slow loop): start again from now, as rospy does.
        if clock.get_rostime() - self.last_time > self.sleep_dur * 2:
            self.last_time = clock.get_rostime()


class TimerEvent:
    def __init__(self, last_expected: Any, last_real: Any, current_expected: Any, current_real: Any,
                 last_duration: Any) -> None:
        self.last_expected = last_expected
        self.last_real = last_real
        self.current_expected = current_expected
        self.current_real = current_real
        self.last_duration = last_duration


class Timer(threading.Thread):
    """Calls `callback(TimerEvent)` every `period` (a Duration) on a thread of its own."""

    def __init__(self, period: Any, callback: Callable[[TimerEvent], Any], oneshot: bool = False,
                 reset: bool = False) -> None:
        super().__init__(daemon=True, name="rospy-timer")
        self._period = period
        self._callback = callback
        self._oneshot = oneshot
        self._reset = reset
        self._shutdown = False
        self.start()

    def shutdown(self) -> None:
        self._shutdown = True

    def run(self) -> None:
        period = _seconds(self._period)
        rate = Rate(1.0 / period, reset=self._reset)
        current_expected = clock.get_rostime() + clock.Duration.from_sec(period)
        last_expected, last_real, last_duration = None, None, None
        while not core.is_shutdown() and not self._shutdown:
            try:
                rate.sleep()
            except ROSInterruptException:
                break
            if self._shutdown or core.is_shutdown():  # a wall-clock sleep ends quietly at shutdown
                break
            current_real = clock.get_rostime()
            start = time.time()
            self._callback(TimerEvent(last_expected, last_real, current_expected, current_real, last_duration))
            if self._oneshot:
                break
            last_duration = time.time() - start
            last_expected, last_real = current_expected, current_real
            current_expected = current_expected + clock.Duration.from_sec(period)
