"""One subscription's throttle_rate and queue_length: which messages go to the client, and when.

rosbridge's subscription modifiers, with the time passed in (no clock here):
- throttle_rate 0: every message goes at once (the client's send queue bounds the backlog).
- throttle_rate T > 0, queue_length 0: a message goes when at least T ms passed since the last
  one sent; those in between are dropped.
- throttle_rate T > 0, queue_length N > 0: a message that cannot go now waits in a queue of N
  (the oldest dropped past N), one sent every T ms (`due`, at `next_due`).
Several subscribe ops of one client on one topic are one subscription whose throttle_rate is
the smallest and queue_length the largest asked, as rosbridge merges them.
"""

from __future__ import annotations

import collections
from typing import Generic, TypeVar

Item = TypeVar("Item")


class Pacing(Generic[Item]):
    def __init__(self, throttle_rate_ms: float = 0.0, queue_length: int = 0) -> None:
        self.interval = throttle_rate_ms / 1000.0
        self.queue_length = queue_length
        self.dropped = 0
        self._last_sent: float | None = None
        self._queue: collections.deque[Item] = collections.deque()

    def change(self, throttle_rate_ms: float, queue_length: int) -> None:
        self.interval = throttle_rate_ms / 1000.0
        self.queue_length = queue_length
        while len(self._queue) > max(queue_length, 0):
            self._queue.popleft()
            self.dropped += 1

    def offer(self, item: Item, now: float) -> list[Item]:
        """What to send now that `item` came at `now` (seconds, any monotonic origin)."""
        if self.interval <= 0:
            return [item]
        if not self._queue and (self._last_sent is None or now - self._last_sent >= self.interval):
            self._last_sent = now
            return [item]
        if self.queue_length <= 0:
            self.dropped += 1
            return []
        self._queue.append(item)
        if len(self._queue) > self.queue_length:
            self._queue.popleft()
            self.dropped += 1
        return []

    def next_due(self) -> float | None:
        """When the next queued message may go; None with nothing queued."""
        if not self._queue:
            return None
        return self._last_sent + self.interval if self._last_sent is not None else 0.0

    def due(self, now: float) -> list[Item]:
        """The queued message whose time came, if any."""
        when = self.next_due()
        if when is None or now < when:
            return []
        self._last_sent = now
        return [self._queue.popleft()]
