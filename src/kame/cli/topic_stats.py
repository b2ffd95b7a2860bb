"""The statistics `rostopic hz`, `bw` and `delay` print, as rostopic computes them.

Pure: every arrival is given with its time (seconds as float), and reports are strings.
- hz: intervals between arrivals in a window of messages (default 50000); a report only
  when something new came (`None` otherwise, printed as `no new messages`); a clock that
  went back to zero starts over.
- bw: message sizes and arrival times over a window of messages (default 100); the rate
  is the window's bytes over the time from its first arrival to now.
- delay: arrival time minus header stamp; the first message only starts the count.
One deliberate difference: with several topics rostopic's table shows the first topic's
window on the second row (a bug); here each row shows its own topic's window.
"""

from __future__ import annotations

import math
from collections import deque
from dataclasses import dataclass

DEFAULT_HZ_WINDOW = 50000
DEFAULT_BW_WINDOW = 100
RESET_NOTICE = "time has reset, resetting counters"


@dataclass(frozen=True)
class Summary:
    mean: float
    min: float
    max: float
    std_dev: float
    window: int

    @property
    def rate(self) -> float:
        return 1.0 / self.mean if self.mean > 0.0 else 0.0


def _summary(values: deque[float]) -> Summary:
    n = len(values)
    mean = sum(values) / n
    std_dev = math.sqrt(sum((x - mean) ** 2 for x in values) / n)
    return Summary(mean, min(values), max(values), std_dev, n + 1)


class RateStats:
    """Arrival intervals of one topic (rostopic hz)."""

    def __init__(self, window: int = -1) -> None:
        self.window = DEFAULT_HZ_WINDOW if window < 0 else window
        self.t0 = -1.0
        self.tn = 0.0
        self.last_printed_tn = 0.0
        self.intervals: deque[float] = deque()

    def add(self, now: float) -> str | None:
        """Count an arrival at `now`; returns a notice to print when the clock was reset."""
        if now == 0.0:
            if self.intervals:
                self.intervals.clear()
                return RESET_NOTICE
            return None
        if self.t0 < 0 or self.t0 > now:
            self.t0 = self.tn = now
            self.intervals.clear()
        else:
            self.intervals.append(now - self.tn)
            self.tn = now
        while self.intervals and len(self.intervals) > self.window - 1:
            self.intervals.popleft()
        return None

    def summary(self) -> Summary | None:
        """The statistics since the last report, or None when nothing new arrived."""
        if not self.intervals or self.tn == self.last_printed_tn:
            return None
        self.last_printed_tn = self.tn
        return _summary(self.intervals)


def format_rate(summary: Summary | None) -> str:
    if summary is None:
        return "no new messages"
    return (f"average rate: {summary.rate:.3f}\n\tmin: {summary.min:.3f}s max: {summary.max:.3f}s "
            f"std dev: {summary.std_dev:.5f}s window: {summary.window}")


def format_rate_table(rows: list[tuple[str, Summary | None]]) -> str:
    """The table `rostopic hz /a /b` prints (ending with an empty line), or `no new messages`."""
    header = ["topic", "rate", "min_delta", "max_delta", "std_dev", "window"]
    cols: dict[str, list[str]] = {h: [] for h in header}
    for topic, summary in rows:
        if summary is None:
            continue
        cols["topic"].append(topic)
        cols["rate"].append(f"{summary.rate:.4}")
        cols["min_delta"].append(f"{summary.min:.4}")
        cols["max_delta"].append(f"{summary.max:.4}")
        cols["std_dev"].append(f"{summary.std_dev:.4}")
        cols["window"].append(str(summary.window))
    if not cols["topic"]:
        return "no new messages"
    widths = [max(len(h), *(len(v) for v in cols[h])) for h in header]
    head = "   ".join(h.center(w) for h, w in zip(header, widths, strict=True))
    body = "\n".join("   ".join(cols[h][i].ljust(w) for h, w in zip(header, widths, strict=True))
                     for i in range(len(cols["topic"])))
    line = "=" * (sum(widths) + 3 * (len(header) - 1))
    return f"{head}\n{line}\n{body}\n"


class BandwidthStats:
    """Sizes and arrival times of the last `window` messages (rostopic bw)."""

    def __init__(self, window: int | None = None) -> None:
        self.window = window or DEFAULT_BW_WINDOW
        self.times: deque[float] = deque()
        self.sizes: deque[int] = deque()

    def add(self, now: float, size: int) -> None:
        self.times.append(now)
        self.sizes.append(size)
        if len(self.times) > self.window:
            self.times.popleft()
            self.sizes.popleft()

    def report(self, now: float) -> str | None:
        """`average: 1.27KB/s` and its detail line; None before two messages arrived."""
        n = len(self.times)
        if n < 2:
            return None
        total = sum(self.sizes)
        elapsed = now - self.times[0]
        per_second = total / elapsed if elapsed > 0 else 0.0
        values = [per_second, total / n, float(min(self.sizes)), float(max(self.sizes))]
        if per_second < 1000:
            bw, mean, low, high = (f"{v:.2f}B" for v in values)
        elif per_second < 1000000:
            bw, mean, low, high = (f"{v / 1000:.2f}KB" for v in values)
        else:
            bw, mean, low, high = (f"{v / 1000000:.2f}MB" for v in values)
        return f"average: {bw}/s\n\tmean: {mean} min: {low} max: {high} window: {n}"


class DelayStats:
    """Arrival time minus header stamp (rostopic delay)."""

    def __init__(self, window: int = -1) -> None:
        self.window = DEFAULT_HZ_WINDOW if window < 0 else window
        self.t0 = -1.0
        self.tn = 0.0
        self.last_tn = 0.0
        self.delays: deque[float] = deque()

    def add(self, now: float, stamp: float) -> str | None:
        if now == 0.0:
            if self.delays:
                self.delays.clear()
                return RESET_NOTICE
            return None
        if self.t0 < 0 or self.t0 > now:
            self.t0 = self.tn = now
            self.delays.clear()
        else:
            self.delays.append(now - stamp)
            self.tn = now
        while self.delays and len(self.delays) > self.window - 1:
            self.delays.popleft()
        return None

    def summary(self) -> Summary | None:
        """The statistics since the last report, or None when nothing new arrived."""
        if self.tn == self.last_tn or not self.delays:
            return None
        self.last_tn = self.tn
        return _summary(self.delays)

    def report(self) -> str | None:
        """The report to print each second; None prints nothing (no delays measured yet)."""
        if not self.delays:
            return None
        s = self.summary()
        if s is None:
            return "no new messages"
        return (f"average delay: {s.mean:.3f}\n\tmin: {s.min:.3f}s max: {s.max:.3f}s "
                f"std dev: {s.std_dev:.5f}s window: {s.window}")
