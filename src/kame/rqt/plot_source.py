"""rqt_plot's feed: one subscription per topic on the tool's node, each message's plotted fields
appended to their series.

A topic's class is kame's (or a ROS_PACKAGE_PATH package's, through the CLI's resolver); a type
kame does not have is subscribed as any type and built from the definition its publisher sends.
A message with a header is stamped with its header's stamp (as rqt_plot does), any other (and a
header stamped zero) with its arrival time; both in seconds since the plot started, on the wall
clock header stamps use. Each topic is read in batches (READ_INTERVAL): the messages of one
read came in over the time since the topic's previous read (at most READ_INTERVAL), so their
arrival times are spread evenly over it, ending at the read (all at the read's time, a 1 kHz
topic would plot in steps). A series keeps its points in time order: a message stamped before
the topic's previous one is left out, and the window says so. The series are shared between
the subscriber threads and the window under one lock; the window takes copies. Messages are
decoded straight from the received frames (no copy of their bytes), and `version` changes
whenever what there is to draw does, so the window redraws only then.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from kame.msg.fieldpath import FieldPathError, field_type
from kame.msg.loader import generate_dynamic
from kame.msg.lookup import message_class as load_message_class
from kame.node.node import Node
from kame.rqt.plot_model import (
    DEFAULT_HISTORY,
    Series,
    SeriesNameError,
    SeriesSpec,
    as_number,
    numeric_fields,
    split_series,
)

ANY_MD5 = "*"
STAGE_LIMIT = 65_536  # values staged per series before they are folded in without the window
# Each topic's messages are read in batches at most this often (Subscription.read_interval): a
# plot drawn at 30 frames a second cannot show them sooner, and a 1 kHz topic then wakes its
# thread 100 times a second instead of 1,000 (most of what receiving cost was those wake-ups)
READ_INTERVAL = 0.01


class PlotSource:
    def __init__(self, node: Node, history: float = DEFAULT_HISTORY,
                 clock: Callable[[], float] = time.time) -> None:
        self.node = node
        self.history = history
        self.clock = clock
        self.start = clock()
        self.specs: dict[str, SeriesSpec] = {}
        self.series: dict[str, Series] = {}
        self.errors: dict[str, str] = {}  # series name -> why its last message gave no value
        self._by_topic: dict[str, list[str]] = {}
        self._classes: dict[str, type[Any]] = {}
        self._lock = threading.Lock()
        # values the subscribers brought since the window last looked: plain lists, because a
        # numpy append per message costs more than the message; folded into the series on demand
        self._staged: dict[str, tuple[list[float], list[float]]] = {}
        self._latest: dict[str, float] = {}  # topic -> the time of its newest point
        self._read_at: dict[str, float] = {}  # topic -> when its previous batch was read
        self.version = 0  # bumped under the lock by every change to the series or their set

    def topic_types(self) -> list[tuple[str, str]]:
        return [(str(t), str(ty)) for t, ty in self.node.master.call("getTopicTypes")]

    def add(self, name: str) -> SeriesSpec:
        """Start plotting `name` (/topic/field); raises SeriesNameError for what cannot be plotted."""
        if name in self.specs:
            return self.specs[name]
        types = self.topic_types()

        def check(type_name: str, field: str) -> str:
            cls = load_message_class(type_name)
            if cls is None:
                return "float64"  # unknown here: its publisher's definition will tell when it comes
            return field_type(cls, field)

        spec = split_series(name, types, check)
        with self._lock:
            self.specs[name] = spec
            self.series[name] = Series(self.history)
            self.version += 1
            subscribed = spec.topic in self._by_topic
            self._by_topic.setdefault(spec.topic, []).append(name)
        if not subscribed:
            cls = load_message_class(spec.type)
            if cls is not None:
                self._classes[spec.topic] = cls
            md5, text = (cls._md5sum, cls._full_text) if cls is not None else (ANY_MD5, "")
            topic = spec.topic

            def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
                self._deliver(topic, frames, header)

            self.node.subscribe(topic, spec.type, md5, text, deliver, read_interval=READ_INTERVAL)
        return spec

    def remove(self, name: str) -> None:
        with self._lock:
            spec = self.specs.pop(name, None)
            self.series.pop(name, None)
            self._staged.pop(name, None)
            self.version += 1
            if spec is None:
                return
            names = self._by_topic[spec.topic]
            names.remove(name)
            unsubscribe = not names
            if unsubscribe:
                del self._by_topic[spec.topic]
                self._latest.pop(spec.topic, None)
                self._read_at.pop(spec.topic, None)
        if unsubscribe:
            self.node.unsubscribe(spec.topic)
            self._classes.pop(spec.topic, None)

    def _class_for(self, topic: str, header: dict[str, str]) -> type[Any]:
        cls = self._classes.get(topic)
        if cls is None:
            type_name = header.get("type", "")
            cls = generate_dynamic(type_name, header.get("message_definition", ""))[type_name]
            self._classes[topic] = cls
        return cls

    def _deliver(self, topic: str, frames: list[memoryview], header: dict[str, str]) -> None:
        # one subscription's batches come one at a time (Subscription.callback_lock): _read_at needs no lock
        now = self.clock() - self.start
        count = len(frames)
        since = now - self._read_at.get(topic, now - READ_INTERVAL)
        self._read_at[topic] = now
        step = min(max(since, 0.0), READ_INTERVAL) / max(count, 1)  # between arrivals, as spread
        try:
            cls = self._class_for(topic, header)
        except Exception as exc:  # a publisher whose definition we cannot read: say so in the window
            with self._lock:
                for name in self._by_topic.get(topic, []):
                    self.errors[name] = f"cannot read {topic}'s messages: {exc}"
            return
        messages: list[tuple[float, Any]] = []  # (time since start, message)
        stamped = bool(getattr(cls, "_has_header", False))
        from_buffer = cls._from_buffer  # the frames are only lent: the messages die with this call
        for index, frame in enumerate(frames):
            try:
                msg = from_buffer(frame)
            except Exception as exc:  # the publisher's fault; the plot goes on with the next message
                with self._lock:
                    for name in self._by_topic.get(topic, []):
                        self.errors[name] = f"a message on {topic} does not deserialize: {exc}"
                continue
            arrival = now - step * (count - 1 - index)
            messages.append((self._time_of(msg, arrival) if stamped else arrival, msg))
        with self._lock:
            messages, left_out = self._in_time_order(topic, messages)
            for name in self._by_topic.get(topic, []):
                spec = self.specs[name]
                values = []
                stamps = []
                for stamp, msg in messages:
                    try:
                        values.append(as_number(spec.path.evaluate(msg)))
                    except (FieldPathError, TypeError) as exc:
                        self.errors[name] = str(exc)
                        continue
                    stamps.append(stamp)
                if values:
                    times, staged = self._staged.setdefault(name, ([], []))
                    staged += values
                    times += stamps
                    if len(staged) > STAGE_LIMIT:
                        self._fold(name)
                    self.errors.pop(name, None)
                    self.version += 1
                if left_out:  # after the pop: a batch with good messages too still says it
                    self.errors[name] = f"a message on {topic} stamped before the previous one was left out"

    def _in_time_order(self, topic: str, messages: list[tuple[float, Any]]) -> tuple[list[tuple[float, Any]], bool]:
        """The messages not stamped before the topic's newest point (a series keeps its times in
        order), and whether any was left out. Under the lock."""
        latest = self._latest.get(topic, float("-inf"))
        kept = []
        left_out = False
        for stamp, msg in messages:
            if stamp < latest:
                left_out = True
                continue
            kept.append((stamp, msg))
            latest = stamp
        self._latest[topic] = latest
        return kept, left_out

    def _time_of(self, msg: Any, arrival: float) -> float:
        stamp = msg.header.stamp
        if stamp.secs == 0 and stamp.nsecs == 0:  # never stamped: when it came is all there is
            return arrival
        return float(stamp.secs + stamp.nsecs * 1e-9 - self.start)

    def _fold(self, name: str) -> None:
        times, values = self._staged.pop(name, ([], []))
        if values and name in self.series:
            self.series[name].extend(np.asarray(times), np.asarray(values))

    def _fold_all(self) -> None:
        for name in list(self._staged):
            self._fold(name)

    def data(self) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        with self._lock:
            self._fold_all()
            return {name: series.data() for name, series in self.series.items()}

    def problems(self) -> list[str]:
        """Why series got no value from their last messages, sorted."""
        with self._lock:
            return sorted(set(self.errors.values()))

    def newest(self) -> float | None:
        """The time of the newest point of any series."""
        with self._lock:
            self._fold_all()
            ends = [last[0] for last in (s.last() for s in self.series.values()) if last is not None]
        return max(ends) if ends else None

    def peaks(self, start: float, end: float, bins: int) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """What a plot `bins` pixels wide shows of each series between `start` and `end`
        (plot_model.visible_peaks), without copying whole histories."""
        with self._lock:
            self._fold_all()
            return {name: series.peaks(start, end, bins) for name, series in self.series.items()}

    def clear(self) -> None:
        with self._lock:
            self._staged.clear()
            for series in self.series.values():
                series.clear()
            self.version += 1

    def set_history(self, seconds: float) -> None:
        with self._lock:
            self._fold_all()
            self.history = seconds
            for series in self.series.values():
                series.set_history(seconds)
            self.version += 1

    def completions(self) -> list[str]:
        """Every plottable /topic/field of the published topics whose type kame can load."""
        out = []
        for topic, type_name in sorted(self.topic_types()):
            try:
                cls = load_message_class(type_name)
            except Exception:
                continue
            if cls is not None:
                out += [f"{topic.rstrip('/')}/{field}" for field in numeric_fields(cls)]
        return out

    def close(self) -> None:
        for name in list(self.specs):
            self.remove(name)


__all__ = ["PlotSource", "SeriesNameError"]
