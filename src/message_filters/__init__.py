"""message_filters: chains of filters over subscriptions, as ROS 1's Python package.

A filter takes messages from one or more inputs and passes them on to the callbacks
registered on it: Subscriber feeds a chain from a topic, Cache keeps a time history,
TimeSynchronizer calls back with one message from each input carrying the same header stamp,
and ApproximateTimeSynchronizer with messages whose stamps lie within `slop` seconds. The
synchronizers follow upstream's algorithm step by step (queues keyed by stamp, oldest dropped
past queue_size, the first in-slop combination wins), so the same input gives the same
callbacks as ROS's message_filters.
"""

from __future__ import annotations

import itertools
import threading
from collections.abc import Callable, Iterator, Sequence
from functools import reduce
from typing import Any

import rospy
from kame.client import log
from rospy.rostime import Duration, Time, is_wallclock

__all__ = ["ApproximateTimeSynchronizer", "Cache", "SimpleFilter", "Subscriber", "TimeSynchronizer"]

HEADERLESS_WARNING = ("Cannot use message filters with non-stamped messages. "
                      "Use the 'allow_headerless' constructor option to "
                      "auto-assign ROS time to headerless messages.")


class SimpleFilter:
    """A filter's output: the callbacks registered on it, called in registration order."""

    def __init__(self) -> None:
        self.callbacks: dict[int, tuple[Callable[..., Any], tuple[Any, ...]]] = {}

    def registerCallback(self, cb: Callable[..., Any], *args: Any) -> int:
        """Call `cb(*outputs, *args)` on every output; returns the connection's number."""
        conn = len(self.callbacks)
        self.callbacks[conn] = (cb, args)
        return conn

    def signalMessage(self, *msg: Any) -> None:
        for cb, args in list(self.callbacks.values()):
            cb(*(msg + args))


class Subscriber(SimpleFilter):
    """A rospy.Subscriber (same arguments but the callback) feeding this filter's callbacks."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        SimpleFilter.__init__(self)
        self.topic = args[0] if args else kwargs["name"]
        kwargs["callback"] = self.callback
        self.sub = rospy.Subscriber(*args, **kwargs)

    def callback(self, msg: Any) -> None:
        self.signalMessage(msg)

    def getTopic(self) -> str:
        return str(self.topic)

    def __getattr__(self, key: str) -> Any:
        # the rest of rospy.Subscriber's API (unregister, get_num_connections, ...)
        if key == "sub":  # not set yet: raise instead of recursing
            raise AttributeError(key)
        return getattr(self.sub, key)


def _stamp_of(msg: Any, allow_headerless: bool) -> Time | None:
    """The message's header stamp; ROS time now for a headerless one if allowed, else None."""
    header = getattr(msg, "header", None)
    if header is not None and hasattr(header, "stamp"):
        stamp: Time = header.stamp
        return stamp
    if not allow_headerless:
        log.emit(log.WARN, HEADERLESS_WARNING, ())
        return None
    return Time.now()


class Cache(SimpleFilter):
    """The newest `cache_size` messages of its input, queried by time; passes each message on."""

    def __init__(self, f: SimpleFilter, cache_size: int = 1, allow_headerless: bool = False) -> None:
        SimpleFilter.__init__(self)
        self.connectInput(f)
        self.cache_size = cache_size
        self.cache_msgs: list[Any] = []
        self.cache_times: list[Time] = []  # the stamp of cache_msgs[i], in arrival order
        self.allow_headerless = allow_headerless

    def connectInput(self, f: SimpleFilter) -> None:
        self.incoming_connection = f.registerCallback(self.add)

    def add(self, msg: Any) -> None:
        stamp = _stamp_of(msg, self.allow_headerless)
        if stamp is None:
            return
        self.cache_times.append(stamp)
        self.cache_msgs.append(msg)
        if len(self.cache_msgs) > self.cache_size:
            del self.cache_msgs[0]
            del self.cache_times[0]
        self.signalMessage(msg)

    def _stamped(self) -> Iterator[tuple[Any, Time]]:
        return zip(self.cache_msgs, self.cache_times, strict=True)

    def getInterval(self, from_stamp: Time, to_stamp: Time) -> list[Any]:
        """The cached messages stamped from `from_stamp` to `to_stamp`, both included."""
        assert from_stamp <= to_stamp
        return [msg for msg, time in self._stamped() if from_stamp <= time <= to_stamp]

    def getElemAfterTime(self, stamp: Time) -> Any:
        """The oldest message stamped at or after `stamp`, or None."""
        return next((msg for msg, time in self._stamped() if time >= stamp), None)

    def getElemBeforeTime(self, stamp: Time) -> Any:
        """The newest message stamped at or before `stamp`, or None."""
        older = [msg for msg, time in self._stamped() if time <= stamp]
        return older[-1] if older else None

    def getLatestTime(self) -> Time | None:
        return self.cache_times[-1] if self.cache_times else None

    def getLastestTime(self) -> Time | None:
        """getLatestTime under the misspelt name upstream keeps for old code."""
        return self.getLatestTime()

    def getOldestTime(self) -> Time | None:
        return self.cache_times[0] if self.cache_times else None

    def getLast(self) -> Any:
        latest = self.getLatestTime()
        return None if latest is None else self.getElemAfterTime(latest)


class TimeSynchronizer(SimpleFilter):
    """Calls back with one message from each input when all of them carry the same stamp.

    Each input keeps up to `queue_size` messages by stamp (the oldest dropped first). With
    `reset` under simulated time, an input's queue is cleared when ROS time jumps back.
    """

    def __init__(self, fs: Sequence[SimpleFilter], queue_size: int, reset: bool = False) -> None:
        SimpleFilter.__init__(self)
        self.connectInput(fs)
        self.queue_size = queue_size
        self.lock = threading.Lock()
        self.enable_reset = reset

    def connectInput(self, fs: Sequence[SimpleFilter]) -> None:
        self.queues: list[dict[Time, Any]] = [{} for _ in fs]
        self.latest_stamps: list[Time] = [Time(0) for _ in fs]
        self.input_connections = [f.registerCallback(self.add, queue, index)
                                  for index, (f, queue) in enumerate(zip(fs, self.queues, strict=True))]

    def _note_time_jump(self, my_queue: dict[Time, Any], my_queue_index: int | None) -> None:
        """Under sim time with reset: clear the queue of an input that saw ROS time jump back."""
        now = Time.now()
        if is_wallclock() or not self.enable_reset or my_queue_index is None:
            return
        if now < self.latest_stamps[my_queue_index]:
            log.emit(log.DEBUG, "Detected jump back in time. Clearing message filter queue", ())
            my_queue.clear()
        self.latest_stamps[my_queue_index] = now

    def _all_inputs_current(self) -> bool:
        """False under sim time with reset while another input has seen a later ROS time."""
        if is_wallclock() or not self.enable_reset:
            return True
        return bool(max(self.latest_stamps) == Time.now())

    def add(self, msg: Any, my_queue: dict[Time, Any], my_queue_index: int | None = None) -> None:
        with self.lock:
            self._note_time_jump(my_queue, my_queue_index)
            my_queue[msg.header.stamp] = msg
            while len(my_queue) > self.queue_size:
                del my_queue[min(my_queue)]
            if not self._all_inputs_current():
                return
            common: set[Time] = reduce(set.intersection, [set(queue) for queue in self.queues])
            for stamp in sorted(common):
                self.signalMessage(*[queue[stamp] for queue in self.queues])
                for queue in self.queues:
                    del queue[stamp]


class ApproximateTimeSynchronizer(TimeSynchronizer):
    """Calls back with one message from each input when their stamps lie within `slop` seconds.

    On each arrival, every other input's stamps within `slop` of the new one are ranked by
    their distance to it, and the first combination (nearest first) spanning less than `slop`
    is delivered and removed from the queues. All queues are cleared when ROS time jumps back.
    """

    def __init__(self, fs: Sequence[SimpleFilter], queue_size: int, slop: float,
                 allow_headerless: bool = False, reset: bool = False) -> None:
        TimeSynchronizer.__init__(self, fs, queue_size)
        self.slop = Duration.from_sec(slop)
        self.allow_headerless = allow_headerless
        self.last_added = Time()
        self.enable_reset = reset

    def add(self, msg: Any, my_queue: dict[Time, Any], my_queue_index: int | None = None) -> None:
        stamp = _stamp_of(msg, self.allow_headerless)
        if stamp is None:
            return
        with self.lock:
            self._note_time_jump(my_queue, my_queue_index)
            my_queue[stamp] = msg
            now = Time.now()
            if now < self.last_added:
                log.emit(log.INFO, "ApproximateTimeSynchronizer: Detected jump back in time. Clearing buffer.", ())
                for queue in self.queues:
                    queue.clear()
            self.last_added = now
            while len(my_queue) > self.queue_size:
                del my_queue[min(my_queue)]
            if not self._all_inputs_current():
                return
            self._deliver_near(stamp, my_queue_index)

    def _deliver_near(self, stamp: Time, my_queue_index: int | None) -> None:
        others = self.queues if my_queue_index is None else (
            self.queues[:my_queue_index] + self.queues[my_queue_index + 1:])
        candidates: list[list[Time]] = []
        for queue in others:
            near = sorted(((other, abs(other - stamp)) for other in queue if abs(other - stamp) <= self.slop),
                          key=lambda pair: pair[1])
            if not near:
                return
            candidates.append([other for other, _ in near])
        for combination in itertools.product(*candidates):
            stamps = list(combination)
            if my_queue_index is not None:
                stamps.insert(my_queue_index, stamp)
            chosen = list(zip(self.queues, stamps, strict=True))
            if max(stamps) - min(stamps) < self.slop and all(t in queue for queue, t in chosen):
                self.signalMessage(*[queue[t] for queue, t in chosen])
                for queue, t in chosen:
                    del queue[t]
                break
