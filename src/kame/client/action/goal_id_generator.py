"""GoalIDGenerator: `<name>-<counter>-<secs>.<nsecs>` ids, one counter per process (as ROS)."""

from __future__ import annotations

import itertools
import threading

from actionlib_msgs.msg import GoalID
from kame.action import generated_goal_id
from kame.client import clock, core

_counter = itertools.count(1)
_counter_lock = threading.Lock()


class GoalIDGenerator:
    def __init__(self, name: str | None = None) -> None:
        self.name = name if name is not None else core.get_name()

    def set_name(self, name: str) -> None:
        self.name = name

    def generate_ID(self) -> GoalID:
        now = clock.Time.now()
        with _counter_lock:
            count = next(_counter)
        return GoalID(stamp=now, id=generated_goal_id(self.name, count, now.secs, now.nsecs))
