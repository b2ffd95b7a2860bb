"""KAME_RVIZ_STATS=FILE: rviz writes, for each stamped message it draws, one line when the
window's frame showing it has been swapped to the screen (for the Image and Camera displays:
when their panel has painted it):

    TOPIC STAMP TAKEN SHOWN

STAMP is the message's header.stamp (a MarkerArray's: its first marker's), TAKEN the wall time
the window's frame took it from the source (received and decoded), SHOWN the wall time Qt's
buffer swap of the first frame drawing it returned, all in seconds. With the publisher
stamping wall time as it publishes, SHOWN - STAMP is the message's latency to pixels
(bench/rviz_e2e_bench.py). Messages without a stamp, and those a newer one of their topic
replaced before a frame took them, have no line."""

from __future__ import annotations

import time
from collections.abc import Mapping
from typing import IO, Any

ENVIRONMENT = "KAME_RVIZ_STATS"


def stamp_of(message: Any) -> float | None:
    """The message's header.stamp in seconds (a MarkerArray's first marker's), None without one."""
    markers = getattr(message, "markers", None)
    if isinstance(markers, list) and markers:
        message = markers[0]
    header = getattr(message, "header", None)
    stamp = getattr(header, "stamp", None)
    if stamp is None or not (stamp.secs or stamp.nsecs):
        return None
    return float(stamp.secs + stamp.nsecs * 1e-9)


class ShownLog:
    def __init__(self, out: IO[str]) -> None:
        self._out = out
        self._taken: list[tuple[str, float, float]] = []  # taken, not yet on the screen

    def taken(self, messages: Mapping[str, list[Any]]) -> None:
        now = time.time()
        for topic, received in messages.items():
            for message in received:
                stamp = stamp_of(message)
                if stamp is not None:
                    self._taken.append((topic, stamp, now))

    def swapped(self) -> None:
        """A frame is on the screen: it drew every message taken before it (the frame that took
        them asked for the paint)."""
        now = time.time()
        for topic, stamp, taken in self._taken:
            self._out.write(f"{topic} {stamp:.6f} {taken:.6f} {now:.6f}\n")
        self._taken.clear()


def from_environment(environ: Mapping[str, str]) -> ShownLog | None:
    path = environ.get(ENVIRONMENT)
    if not path:
        return None
    # a line at a time: the log is whole up to the last swap when rviz is ended by a signal
    return ShownLog(open(path, "a", buffering=1, encoding="utf-8"))
