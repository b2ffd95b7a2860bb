"""rqt_topic's feed: the published topics, and for each one the user ticks a subscription (as any
type: the class is kame's, or built from the publisher's definition) that counts arrivals and
keeps the newest message's bytes. The newest message is decoded only when the window asks,
once a refresh, however fast it comes."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from kame.msg.loader import generate_dynamic
from kame.msg.lookup import message_class as load_message_class
from kame.node.node import Node
from kame.rqt.topic_model import TopicStats

ANY_MD5 = "*"


@dataclass
class Watch:
    type_name: str
    stats: TopicStats
    cls: type[Any] | None = None
    newest: bytes | None = None
    header: dict[str, str] | None = None


class TopicMonitor:
    def __init__(self, node: Node, clock: Callable[[], float] = time.monotonic) -> None:
        self.node = node
        self.clock = clock
        self._watches: dict[str, Watch] = {}
        self._lock = threading.Lock()

    def topics(self) -> list[tuple[str, str]]:
        """(topic, type) of every published topic, sorted (OSError, MasterError without a master)."""
        return sorted((str(t), str(ty)) for t, ty in self.node.master.call("getTopicTypes"))

    def watch(self, topic: str, type_name: str) -> None:
        if topic in self._watches:
            return
        cls = load_message_class(type_name)
        with self._lock:
            self._watches[topic] = Watch(type_name, TopicStats(), cls)

        def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
            self._deliver(topic, frames, header)

        try:
            self.node.subscribe(topic, type_name, ANY_MD5, "", deliver)
        except Exception:
            self.unwatch(topic)
            raise

    def _deliver(self, topic: str, frames: list[memoryview], header: dict[str, str]) -> None:
        now = self.clock()
        with self._lock:
            watch = self._watches.get(topic)
            if watch is None or not frames:
                return
            for frame in frames:
                watch.stats.add(now, len(frame))
            watch.newest = bytes(frames[-1])
            watch.header = header

    def unwatch(self, topic: str) -> None:
        with self._lock:
            watch = self._watches.pop(topic, None)
        if watch is not None:
            self.node.unsubscribe(topic)

    def watched(self) -> list[str]:
        with self._lock:
            return sorted(self._watches)

    def stats(self, topic: str) -> tuple[float | None, float | None, int]:
        """(rate, bandwidth, count) of a watched topic."""
        with self._lock:
            watch = self._watches[topic]
            return watch.stats.rate(), watch.stats.bandwidth(), watch.stats.count

    def newest(self, topic: str) -> Any:
        """The newest message, decoded; None before the first. Raises what a bad message raises."""
        with self._lock:
            watch = self._watches.get(topic)
            if watch is None or watch.newest is None:
                return None
            data, header = watch.newest, watch.header or {}
            if watch.cls is None:  # a type kame does not have: its publisher's definition says
                type_name = header.get("type", watch.type_name)
                watch.cls = generate_dynamic(type_name, header.get("message_definition", ""))[type_name]
            cls = watch.cls
        return cls().deserialize(data)

    def close(self) -> None:
        for topic in self.watched():
            self.unwatch(topic)
