"""Waiting for something in another process that sends no event when it happens.

A master that is not up yet, a topic nobody publishes yet, a service not yet advertised: nobody
is told when they appear, so a program waiting for one asks again every REMOTE_POLL_PERIOD.
The wait between two questions is the caller's own stop (a stop event, the node's shutdown),
so stopping ends it at once; in a command's main thread Ctrl-C interrupts it as well.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TypeVar

T = TypeVar("T")

# rostopic, rosservice and roslaunch --wait ask ten times a second, as their ROS originals do
REMOTE_POLL_PERIOD = 0.1


def _never_stopped(period: float) -> bool:
    threading.Event().wait(period)  # a signal handler's exception (KeyboardInterrupt) ends it
    return False


def poll_remote(ask: Callable[[], T | None], wait_stopped: Callable[[float], bool] = _never_stopped,
                period: float = REMOTE_POLL_PERIOD) -> T | None:
    """ask() until it gives something other than None, which is returned; None once
    wait_stopped(period) (the wait between two questions) says the caller was stopped."""
    while True:
        found = ask()
        if found is not None:
            return found
        if wait_stopped(period):
            return None
