"""tf2_ros.Buffer's behaviour over the pure buffer core: one lock around the core, a condition
that wakes waiting lookups when a transform arrives (never a poll), timeouts, the handling of
a /tf message (authority, a clock that jumped back clears the cache) and tf2's warnings and
errors about the data, each kind (TF_REPEATED_DATA, TF_NAN_INPUT, ...) at most once per
REPORT_INTERVAL so that a publisher repeating a mistake at 1 kHz does not flood the log."""

from __future__ import annotations

import logging
import threading
import time as wallclock
from collections.abc import Callable
from typing import Any

from kame.rostime import Time
from kame.tf.buffer_core import BufferCore
from kame.tf.errors import TimeoutException
from kame.tf.messages import from_message, to_message, to_nsec

log = logging.getLogger("kame.tf")

REPORT_INTERVAL = 10.0  # seconds between two reports of one kind of bad data


class Buffer:
    def __init__(self, cache_time: Any = None, transform_type: type[Any] | None = None,
                 time_type: Any = Time, warn: Callable[[str], None] | None = None,
                 error: Callable[[str], None] | None = None) -> None:
        """`cache_time` is a Duration (default 10 s); `transform_type` the TransformStamped
        class lookups return; `warn` and `error` where tf2's warnings and errors go (the node's log)."""
        if transform_type is None:
            from geometry_msgs.msg import TransformStamped
            transform_type = TransformStamped
        self.warn: Callable[[str], None] = warn or log.warning
        self.error: Callable[[str], None] = error or log.error
        self._core = BufferCore(to_nsec(cache_time) if cache_time is not None else 10 * 10**9, self._warn)
        self._changed = threading.Condition()
        self._transform_type = transform_type
        self._time_type = time_type
        self._last_report: dict[str, float] = {}
        self._latest_input = 0
        self._input_order = threading.Lock()

    def _warn(self, text: str) -> None:
        if text.startswith("TF_DENORMALIZED_QUATERNION"):  # normalized and stored: a warning
            self._report(text, self.warn)
        else:
            self.warn(text)

    # ------------------------------------------------------------------ input

    def set_transform(self, transform: Any, authority: str) -> bool:
        return self._set(transform, authority, False)

    def set_transform_static(self, transform: Any, authority: str) -> bool:
        return self._set(transform, authority, True)

    def _set(self, transform: Any, authority: str, is_static: bool) -> bool:
        return not self._store([transform], authority, is_static)

    def _store(self, transforms: list[Any], authority: str, is_static: bool) -> list[str]:
        """Store transforms under one lock, wake the waiters once; the refusals, reported."""
        refusals = []
        stored = False
        set_transform = self._core.set_transform
        with self._changed:
            for transform in transforms:
                refusal = set_transform(from_message(transform), authority, is_static)
                if refusal is None:
                    stored = True
                else:
                    refusals.append(refusal)
            if stored:
                self._changed.notify_all()
        for refusal in refusals:  # tf2 warns about late and repeated data, and refuses the rest as errors
            self._report(refusal, self.warn if refusal.startswith(("TF_REPEATED_DATA", "TF_OLD_DATA")) else self.error)
        return refusals

    def _report(self, text: str, sink: Callable[[str], None]) -> None:
        """A bad-data message to `sink`, unless one of its kind went out less than
        REPORT_INTERVAL ago."""
        kind = text.split(" ", 1)[0].rstrip(":")
        now = wallclock.monotonic()
        if now - self._last_report.get(kind, -REPORT_INTERVAL) < REPORT_INTERVAL:
            return
        self._last_report[kind] = now
        sink(text)

    def receive(self, transforms: list[Any], authority: str, is_static: bool, now: int = 0) -> None:
        """One /tf or /tf_static message from `authority` (the publisher's callerid), received at
        ROS time `now` (ns; 0 if unknown): a clock that went back (a looping bag, a restarted
        simulation) clears the buffer first, as tf2_ros's listener does."""
        if now and now < self._latest_input:
            self.warn(f"Detected jump back in time of {(self._latest_input - now) / 1e9:g}s. Clearing TF buffer.")
            self.clear()
        if now:
            self._latest_input = now
        self._store(transforms, authority, is_static)

    def receive_at(self, transforms: list[Any], authority: str, is_static: bool, clock: Callable[[], int]) -> None:
        """receive() at the time `clock` gives (ns), read while no other message is handed over:
        /tf and /tf_static arrive on threads of their own, and a time read before another
        message's but handed over after it would look like the clock going back (a clear)."""
        with self._input_order:
            self.receive(transforms, authority, is_static, clock())

    def clear(self) -> None:
        with self._changed:
            self._core.clear()

    # ------------------------------------------------------------------ waiting

    def _wait(self, ready: Callable[[], tuple[bool, str]], timeout: Any,
              cancelled: threading.Event | None = None) -> tuple[bool, str]:
        """ready() under the lock, re-checked each time a transform arrives, until it is True,
        `timeout` (a Duration, or seconds) passes, or `cancelled` is set (see wake())."""
        seconds = to_nsec(timeout) / 1e9 if timeout is not None else 0.0
        deadline = wallclock.monotonic() + seconds
        with self._changed:
            while True:
                result = ready()
                remaining = deadline - wallclock.monotonic()
                if result[0] or remaining <= 0 or (cancelled is not None and cancelled.is_set()):
                    return result
                self._changed.wait(remaining)

    def wake(self) -> None:
        """Wake every waiting call to re-check (one whose `cancelled` event is set returns)."""
        with self._changed:
            self._changed.notify_all()

    def wait_for(self, target_frame: str, source_frame: str, time: Any, timeout: Any,
                 cancelled: threading.Event, target_time: Any = None, fixed_frame: str = "") -> bool:
        """Wait as can_transform(_full) does, but give up early once `cancelled` is set and wake()
        is called (a server shutting down)."""
        stamp = to_nsec(time)
        if fixed_frame:
            target_stamp = to_nsec(target_time)
            return self._wait(lambda: self._core.can_transform_full(target_frame, target_stamp, source_frame, stamp,
                                                                    fixed_frame), timeout, cancelled)[0]
        return self._wait(lambda: self._core.can_transform(target_frame, source_frame, stamp), timeout, cancelled)[0]

    # ------------------------------------------------------------------ lookups

    def can_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None,
                      return_debug_tuple: bool = False) -> Any:
        stamp = to_nsec(time)
        result = self._wait(lambda: self._core.can_transform(target_frame, source_frame, stamp), timeout)
        return result if return_debug_tuple else result[0]

    def can_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                           fixed_frame: str, timeout: Any = None, return_debug_tuple: bool = False) -> Any:
        target_stamp, source_stamp = to_nsec(target_time), to_nsec(source_time)
        result = self._wait(lambda: self._core.can_transform_full(target_frame, target_stamp, source_frame,
                                                                  source_stamp, fixed_frame), timeout)
        return result if return_debug_tuple else result[0]

    def lookup_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any = None) -> Any:
        """The pose of source_frame in target_frame at `time` (0: the latest common time),
        waiting up to `timeout` for it; raises tf2's exceptions."""
        if timeout is not None and to_nsec(timeout) > 0:
            self.can_transform(target_frame, source_frame, time, timeout)
        with self._changed:
            found = self._core.lookup_transform(target_frame, source_frame, to_nsec(time))
        return to_message(found, self._transform_type, self._time_type)

    def lookup_transform_full(self, target_frame: str, target_time: Any, source_frame: str, source_time: Any,
                              fixed_frame: str, timeout: Any = None) -> Any:
        if timeout is not None and to_nsec(timeout) > 0:
            self.can_transform_full(target_frame, target_time, source_frame, source_time, fixed_frame, timeout)
        with self._changed:
            found = self._core.lookup_transform_full(target_frame, to_nsec(target_time), source_frame,
                                                     to_nsec(source_time), fixed_frame)
        return to_message(found, self._transform_type, self._time_type)

    def wait_for_transform(self, target_frame: str, source_frame: str, time: Any, timeout: Any) -> None:
        """Block until the lookup can be done; TimeoutException with the last reason if not."""
        ok, why = self.can_transform(target_frame, source_frame, time, timeout, return_debug_tuple=True)
        if not ok:
            raise TimeoutException(why or f"timed out waiting for the transform from {source_frame} to {target_frame}")

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Any:
        with self._changed:
            stamp = self._core.latest_common_time(target_frame, source_frame)
        return self._time_type(stamp // 1_000_000_000, stamp % 1_000_000_000)

    # ------------------------------------------------------------------ descriptions

    def all_frames_as_yaml(self, current_time: float = 0.0) -> str:
        with self._changed:
            return self._core.all_frames_as_yaml(current_time)

    def all_frames_as_string(self) -> str:
        with self._changed:
            return self._core.all_frames_as_string()

    def all_frames_as_dot(self, current_time: float = 0.0) -> str:
        with self._changed:
            return self._core.all_frames_as_dot(current_time)

    def frame_exists(self, frame: str) -> bool:
        with self._changed:
            return self._core.frame_exists(frame)

    def frames(self) -> list[str]:
        with self._changed:
            return self._core.frames()

    def parent_of(self, frame: str, time: Any = 0) -> str | None:
        with self._changed:
            return self._core.parent_of(frame, to_nsec(time))

    def chain(self, target_frame: str, source_frame: str, time: Any = 0) -> list[str]:
        with self._changed:
            return self._core.chain(target_frame, source_frame, to_nsec(time))
