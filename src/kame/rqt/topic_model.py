"""rqt_topic's numbers (pure): a topic's rate and bandwidth over its last messages, as rqt_topic
measures them (rostopic hz's and bw's arithmetic over a window of arrivals), and how they are
written in its columns. Times are given, in seconds; nothing here reads a clock."""

from __future__ import annotations

from collections import deque

WINDOW = 100  # arrivals the rate and bandwidth are measured over


class TopicStats:
    def __init__(self, window: int = WINDOW) -> None:
        self._times: deque[float] = deque(maxlen=window)
        self._sizes: deque[int] = deque(maxlen=window)
        self.count = 0

    def add(self, time: float, size: int) -> None:
        self._times.append(time)
        self._sizes.append(size)
        self.count += 1

    def rate(self) -> float | None:
        """Messages a second between the first and last arrival of the window; None under two."""
        span = self._span()
        return (len(self._times) - 1) / span if span else None

    def bandwidth(self) -> float | None:
        """Bytes a second: what arrived after the window's first message, over the same span."""
        span = self._span()
        return sum(list(self._sizes)[1:]) / span if span else None

    def _span(self) -> float:
        return self._times[-1] - self._times[0] if len(self._times) > 1 else 0.0


def rate_text(rate: float | None) -> str:
    return "" if rate is None else f"{rate:.2f}"


def bandwidth_text(bandwidth: float | None) -> str:
    if bandwidth is None:
        return ""
    for unit, size in (("MB/s", 1e6), ("KB/s", 1e3)):
        if bandwidth >= size:
            return f"{bandwidth / size:.2f}{unit}"
    return f"{bandwidth:.2f}B/s"
