"""rqt_console's feed: /rosout_agg on the tool's node, parsed straight from the wire into LogEntry
batches. The subscriber thread appends to a pending list and calls `on_ready` only when that
list was empty, so the window is woken once per batch, however fast messages come; what the
window has not taken yet is bounded by the store's capacity (the oldest dropped)."""

from __future__ import annotations

import threading
from collections.abc import Callable

from kame.cli.rosout import LogRecord, MalformedLog, parse_log
from kame.node.node import Node
from kame.rqt.console_model import DEFAULT_CAPACITY, LogEntry

TOPIC = "/rosout_agg"
LOG_TYPE = "rosgraph_msgs/Log"


def entry_of(record: LogRecord) -> LogEntry:
    def text(raw: bytes) -> str:
        return raw.decode("utf-8", "replace")

    return LogEntry(text(record.msg), record.level, text(record.name), record.secs, record.nsecs,
                    tuple(text(t) for t in record.topics), text(record.file), text(record.function), record.line)


class LogFeed:
    def __init__(self, node: Node, on_ready: Callable[[], None], topic: str = TOPIC,
                 capacity: int = DEFAULT_CAPACITY) -> None:
        from rosgraph_msgs.msg import Log

        self.node = node
        self.topic = topic
        self.capacity = capacity
        self.on_ready = on_ready
        self.malformed = 0
        self._pending: list[LogEntry] = []
        self._lock = threading.Lock()
        node.subscribe(topic, LOG_TYPE, Log._md5sum, Log._full_text, self._on_frames)

    def _on_frames(self, frames: list[memoryview], header: dict[str, str]) -> None:
        entries = []
        for frame in frames:
            try:
                entries.append(entry_of(parse_log(frame)))
            except MalformedLog:
                self.malformed += 1
        if not entries:
            return
        with self._lock:
            was_empty = not self._pending
            self._pending.extend(entries)
            if len(self._pending) > self.capacity:
                del self._pending[:len(self._pending) - self.capacity]
        if was_empty:
            self.on_ready()

    def take(self) -> list[LogEntry]:
        """Everything that arrived since the last take, oldest first."""
        with self._lock:
            batch, self._pending = self._pending, []
        return batch
