"""The `Date` header kame's HTTP servers send (as Python's http.server, so rosmaster and rospy's
nodes, do): the wall clock's second, formatted once per second however many responses share it.
roswtf reads it to compare this machine's clock with the master's and the nodes' machines'."""

from __future__ import annotations

import functools
import time

from kame.protocol.http import date_header


@functools.lru_cache(maxsize=4)
def _date_line(second: int) -> bytes:
    return date_header(second)


def current_date_header() -> bytes:
    return _date_line(int(time.time()))
